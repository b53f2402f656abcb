//! Why a model, or an operating point, has no linear model here: the obstacles
//! `tree_dynamics`, `sticking` and the loops' closure name.

/// Why a model has no minimal-coordinate dynamics here.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Unsupported {
    /// A joint closes a loop (refused where only trees are supported: the FMU's directional
    /// derivatives, the `joint.J.qdd` outputs).
    Loop(String),
    /// The closed loops cannot be put in independent coordinates at this state.
    Closure(String),
    /// The model has collision shapes.
    Contact,
    /// A joint has Coulomb friction.
    Friction(String),
    /// A joint follows another through a coupling.
    Coupling(String),
    /// Two bodies' shapes touch at the operating point (their names).
    Touching(String, String),
    /// A bristle slides at the operating point: its name and its load, percent of the limit.
    Sliding(String, u32),
    /// Closed loops or couplings with touching contacts or joint friction.
    LoopSticking,
    /// A spherical joint has friction (its vector bristle has no linear model yet).
    SphericalFriction(String),
}

impl std::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Loop(j) => write!(f, "joint '{j}' closes a kinematic loop; closed loops are linearised by `triad linearize` only (in independent coordinates), not here"),
            Self::Closure(why) => write!(f, "{why}"),
            Self::Contact => write!(f, "the model has collision shapes; contact is linearised by `triad linearize` only (its bristles are states there), not here"),
            Self::Friction(j) => write!(f, "joint '{j}' has Coulomb friction; joint friction is linearised by `triad linearize` only (its bristle is a state there), not here"),
            Self::Touching(a, b) => write!(f, "shapes '{a}' and '{b}' touch at the operating point; linear models cover contact with the ground only (move the point, or leave the pair out)"),
            Self::Sliding(what, r) => write!(f, "{what} slides at the operating point (its friction at {r}% of its limit; a linear model needs every bristle to stick, below {:.0}%: it has no continuous-time limit while it slides)", 100.0 * super::contact_law::YIELD),
            Self::LoopSticking => write!(f, "closed loops or couplings together with touching contacts or joint friction have no linear model here yet"),
            Self::SphericalFriction(j) => write!(f, "joint '{j}' is spherical with Coulomb friction; its vector bristle has no linear model yet"),
            Self::Coupling(j) => write!(f, "joint '{j}' follows another joint through a [[coupling]]; coupled joints are linearised by `triad linearize` only (in independent coordinates), not here"),
        }
    }
}
