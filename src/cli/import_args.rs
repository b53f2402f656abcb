//! The options of URDF and MJCF import, one clap `Args` group flattened into every command that
//! reads a MODEL (`check`, `describe`, `simulate`, `build`, `animate`, `linearize`, `import`): a
//! new import option is added here and in `urdf::ImportOptions` or `mjcf::ImportOptions`,
//! nowhere else.

use clap::Args;
use triad::mjcf;
use triad::urdf::{Base, ImportOptions};

/// How a `.urdf` or MJCF `.xml` MODEL is imported (the same options and meaning as `triad
/// import`).
#[derive(Clone, Debug, Default, Args)]
#[command(next_help_heading = "URDF import (a .urdf only)")]
pub struct ImportArgs {
    /// Weld the base to the world even if the URDF declares it floating.
    #[arg(long, conflicts_with = "floating_base")]
    pub fixed_base: bool,
    /// Free the base (a floating base: legged robots, humanoids, free-flying arms, a loose
    /// object); by default a root link without a floating joint is welded to the world.
    #[arg(long)]
    pub floating_base: bool,
    /// Keep links on fixed joints as bodies on `fixed` joints instead of merging them into their
    /// parents (as sites).
    #[arg(long)]
    pub keep_fixed: bool,
    /// Leave out the URDF's <limit> (by default `lower`/`upper` become joint stops and
    /// `effort` clamps the actuator input).
    #[arg(long)]
    pub no_limits: bool,
    /// Leave out the URDF's <dynamics friction> (by default it becomes the joint's Coulomb
    /// `friction`: the joint sticks below it and slides at it).
    #[arg(long)]
    pub no_friction: bool,
    /// Leave <mimic> joints independent, each with its own input (by default a <mimic> is a
    /// [[coupling]]: the joint follows the one it names and has no input of its own).
    #[arg(long)]
    pub no_mimic: bool,
    /// Make each link's <collision> spheres, boxes and cylinders collision shapes that touch
    /// the ground (meshes are left out with a note), and add a ground plane at height 0.
    #[arg(long)]
    pub contacts: bool,
    /// With a floating base and --contacts: start the base at the height where the lowest
    /// collision shape rests on the ground (its initial position raised or lowered; the joints
    /// keep their initial values). By default the base starts where the URDF puts it (the
    /// origin), often with the feet inside the ground.
    #[arg(long)]
    pub on_ground: bool,
    /// MJCF: leave out the collision shapes (by default every sphere, capsule, box and cylinder
    /// geom that MuJoCo lets touch the world's plane is a collision shape, and that plane the
    /// ground).
    #[arg(long, help_heading = "MJCF import (a .xml only)")]
    pub no_contacts: bool,
    /// MJCF: start from the <key name="NAME"> of the <keyframe> (its qpos and qvel; by default
    /// the model's own pose, each hinge and slide at its ref).
    #[arg(long, value_name = "NAME", help_heading = "MJCF import (a .xml only)")]
    pub keyframe: Option<String>,
}

impl ImportArgs {
    /// The import options these arguments ask for.
    pub fn options(&self) -> ImportOptions {
        let base = match (self.fixed_base, self.floating_base) {
            (true, _) => Base::Fixed,
            (_, true) => Base::Floating,
            _ => Base::Auto,
        };
        ImportOptions {
            base,
            keep_fixed: self.keep_fixed,
            no_limits: self.no_limits,
            no_friction: self.no_friction,
            no_mimic: self.no_mimic,
            contacts: self.contacts,
            on_ground: self.on_ground,
        }
    }

    /// The MJCF import options these arguments ask for.
    pub fn mjcf_options(&self) -> mjcf::ImportOptions {
        mjcf::ImportOptions {
            no_contacts: self.no_contacts,
            keyframe: self.keyframe.clone(),
        }
    }

    /// The MJCF options given, as typed: for the message that a model other than an MJCF file
    /// takes none.
    pub fn given_mjcf(&self) -> Vec<&'static str> {
        [
            (self.no_contacts, "--no-contacts"),
            (self.keyframe.is_some(), "--keyframe"),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
        .collect()
    }

    /// The URDF options given, as typed (`--floating-base`, ...): for the message that a model
    /// other than a URDF takes none.
    pub fn given(&self) -> Vec<&'static str> {
        [
            (self.fixed_base, "--fixed-base"),
            (self.floating_base, "--floating-base"),
            (self.keep_fixed, "--keep-fixed"),
            (self.no_limits, "--no-limits"),
            (self.no_friction, "--no-friction"),
            (self.no_mimic, "--no-mimic"),
            (self.contacts, "--contacts"),
            (self.on_ground, "--on-ground"),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
        .collect()
    }
}
