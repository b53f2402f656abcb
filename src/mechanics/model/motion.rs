//! The motion of every body of a tree at a state of the minimal-coordinate dynamics
//! (`tree_dynamics::motion`), in any scalar: poses, twists and accelerations, world frame,
//!
//! ```text
//! o, R, v = ȯ, ω, a = ö, α = ω̇      per body (the frame origin's)
//! (ω_k, u_k, p_k)                      per rate: the twist it gives its subtree about p_k
//! ```

use super::scalar::Real;
use nalgebra::{Matrix3, Vector3};

/// Per body: pose, twist and acceleration (world frame; `v`, `a` of the frame origin).
#[derive(Clone, Debug)]
pub struct Motion<T: Real> {
    /// Frame origin.
    pub o: Vec<Vector3<T>>,
    /// Rotation world ← body.
    pub r: Vec<Matrix3<T>>,
    /// Velocity of the frame origin.
    pub v: Vec<Vector3<T>>,
    /// Angular velocity.
    pub w: Vec<Vector3<T>>,
    /// Acceleration of the frame origin (zero where the motion was formed without
    /// accelerations).
    pub a: Vec<Vector3<T>>,
    /// Angular acceleration (as `a`).
    pub al: Vec<Vector3<T>>,
    /// Per rate: the twist it gives its subtree, `(ω_k, u_k)` about the point `p_k`.
    pub(crate) cols: Vec<(Vector3<T>, Vector3<T>, Vector3<T>)>,
}
