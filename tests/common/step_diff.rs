//! Central differences of a communication step (`Simulation::advance`) for the tests of the
//! discrete-time linear model: a step from a minimal-coordinate state, the difference of two
//! ends in the coordinates of the first, and the relative error of a matrix.

use nalgebra::DMatrix;
use triad::math::{matrix_to_quat, Mat3, Vec3};
use triad::mechanics::{ModelDef, Operating, SolverSettings};
use triad::sim::Simulation;

/// The model and solver settings of a TOML spec text (panics with the spec's message).
pub fn lower(text: &str) -> (ModelDef, SolverSettings) {
    let spec = triad::spec::Spec::from_str(text, triad::spec::Format::Toml, "test.toml")
        .unwrap_or_else(|e| panic!("{e}"));
    spec.lower().unwrap()
}

/// Rotation vector of `r` (|θ| < π).
pub fn log(r: &Mat3) -> Vec3 {
    let q = matrix_to_quat(r);
    let v = Vec3::new(q[1], q[2], q[3]);
    let s = v.norm();
    if s < 1e-300 {
        return Vec3::zeros();
    }
    v * (2.0 * s.atan2(q[0]) / s)
}

/// The end of one communication step `h` from `x` with inputs `u`.
pub fn end_of(
    def: &ModelDef,
    settings: SolverSettings,
    op: &Operating,
    x: &[f64],
    u: &[f64],
    h: f64,
) -> Operating {
    let d = op.initial_def(def, x);
    let mut sim = Simulation::new(&d, settings, 0.0).unwrap();
    sim.state_mut().inputs_mut().copy_from_slice(u);
    sim.advance(h).unwrap();
    sim.operating().unwrap()
}

/// `(a − b)` in the coordinates of `a`'s operating point: plain differences, and rotation
/// vectors of the relative orientation (child frame for spherical joints, world for free bodies).
pub fn minus(def: &ModelDef, a: &Operating, b: &Operating) -> Vec<f64> {
    let n = a.q.len();
    let mut out: Vec<f64> = a.q.iter().zip(&b.q).map(|(x, y)| x - y).collect();
    out.extend(a.nu.iter().zip(&b.nu).map(|(x, y)| x - y));
    for j in 0..def.joints.len() {
        if let (true, Some(at)) = (a.dynamics.is_spherical(j), a.dynamics.joint_at(j)) {
            let th = log(&(b.dynamics.joint_rot0(j).transpose() * a.dynamics.joint_rot0(j)));
            out[at..at + 3].copy_from_slice(th.as_slice());
        }
    }
    for f in &def.free_bodies {
        let at = a.dynamics.free_at(f.body).unwrap();
        let th = log(&(a.dynamics.body_rot0(f.body) * b.dynamics.body_rot0(f.body).transpose()));
        out[at + 3..at + 6].copy_from_slice(th.as_slice());
    }
    // the bristle states (contact), plain differences
    out.extend(
        a.x()[2 * n..]
            .iter()
            .zip(&b.x()[2 * n..])
            .map(|(x, y)| x - y),
    );
    out
}

/// `|a − b|/|b|` (Frobenius), naming the worst entry where it exceeds 1e-6.
pub fn report(name: &str, a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    let err = (a - b).norm() / b.norm();
    if err > 1e-6 {
        let d = a - b;
        let (mut worst, mut at) = (0.0, (0, 0));
        for r in 0..d.nrows() {
            for c in 0..d.ncols() {
                if d[(r, c)].abs() > worst {
                    worst = d[(r, c)].abs();
                    at = (r, c);
                }
            }
        }
        eprintln!("{name}: worst entry {at:?}: exact {} fd {}", a[at], b[at]);
    }
    err
}
