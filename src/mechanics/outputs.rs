//! Output values at the current node time: per body, per joint and for the system.

use crate::math::{Mat3, Vec3};

/// Kinematic outputs of one body (interface.md §3).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BodyOutput {
    /// Origin of the body frame, world frame, m.
    pub r: Vec3,
    /// Rotation world ← body (columns are the directors), 1.
    pub rot: Mat3,
    /// Velocity of the body frame origin, world frame, m/s.
    pub v: Vec3,
    /// Angular velocity, world frame, rad/s.
    pub w: Vec3,
}

/// Joint coordinates and rates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct JointOutput {
    /// Coordinates (len `JointType::nq`): angles unwrapped (continuous), slides in m; spherical:
    /// the quaternion `[w, x, y, z]` of the child joint frame relative to the parent joint frame.
    pub q: Vec<f64>,
    /// Rates (len `JointType::dof`); spherical: relative angular velocity in the child frame.
    pub qd: Vec<f64>,
}

/// Every output of the system at the current time.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Outputs {
    /// Per body, in model order.
    pub bodies: Vec<BodyOutput>,
    /// Per joint, in model order.
    pub joints: Vec<JointOutput>,
    /// Kinetic + potential (gravity and joint springs) energy, J.
    pub energy: f64,
    /// Work of the inputs minus energy dissipated by damping since the start, J.
    pub work: f64,
    /// Total linear momentum, world frame, N·s.
    pub p: Vec3,
    /// Total angular momentum about the world origin, world frame, N·m·s.
    pub l: Vec3,
    /// Largest constraint violation after the last step (internal and joint rows), 1 or m.
    pub constraint_residual: f64,
}
