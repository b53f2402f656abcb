//! The options of URDF import (`triad import`; the defaults are those of every other command).

/// How the base (the root link, or the link below a `world` root) is attached.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Base {
    /// As the URDF says: a bare root or a `fixed` joint to `world` welds, a `floating` joint frees.
    #[default]
    Auto,
    /// Welded to the world, whatever the URDF says.
    Fixed,
    /// Free (a floating base), whatever the URDF says.
    Floating,
}

/// The options of `triad import` (the defaults are those of every other command).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ImportOptions {
    /// How the base is attached.
    pub base: Base,
    /// Keep links on fixed joints as (possibly massless) bodies instead of merging them.
    pub keep_fixed: bool,
    /// Leave out `<limit lower upper effort>`: no joint stops, no effort clamp.
    pub no_limits: bool,
    /// Leave out `<dynamics friction>` (by default the joint's Coulomb `friction`).
    pub no_friction: bool,
    /// Leave `<mimic>` joints independent (by default each is a `[[coupling]]`).
    pub no_mimic: bool,
    /// Turn the links' `<collision>` spheres, boxes and cylinders into collision shapes
    /// (`[[collision]]`) and add a ground plane (`[ground]`, the defaults, height 0).
    pub contacts: bool,
    /// Place the floating base (with `contacts`) so that the lowest collision shape at the
    /// initial pose rests on the ground (gap 0): its initial `position` is raised or lowered
    /// against gravity. Without a floating base or without `contacts`, a problem.
    pub on_ground: bool,
}
