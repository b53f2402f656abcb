//! Symmetric impacts stay symmetric, and momenta between colliding bodies are exact at the
//! default Newton tolerance (`model::contact`: body–body features measure segments and points
//! from the shapes' centres, so a mirror symmetry of the pair maps every invariant to itself or
//! to its negative, and the gap is even in the ones it negates):
//!
//! ```text
//! capsule dropped square across a capsule, no gravity, no friction, h = 1e-4 … 1e-2:
//!     sideways impulse ≤ 1e-12 × normal impulse,  |ω| ≤ 1e-12 rad/s
//! sphere dropped on the middle of a capsule: the same
//! capsule across a capsule, gravity and friction: comes to rest (|v|, |ω| ≤ 1e-6 after 5 s)
//! two boxes, corner to face, default steps, tolerance 1e-10 and 1e-6: Δp, ΔL ≤ 1e-13 of p, L
//! ```

mod common;

use common::spec_model as model;
use triad::mechanics::step;

/// Body `top` (shape `shape_top`, its axis along world x) above body `bottom` (shape
/// `shape_bottom`, its axis along world y, held by a weld when `welded`), falling at 1 m/s
/// along −z, both centred on the z axis.
fn crossed(shape_top: &str, shape_bottom: &str, gravity: f64, mu: f64, welded: bool) -> String {
    let bottom = if welded {
        "[[joint]]\nname = \"weld\"\ntype = \"fixed\"\nparent = \"world\"\nchild = \"bottom\"\n\
         origin = { rpy = [-1.5707963267948966, 0.0, 0.0] }\n"
            .to_string()
    } else {
        "position = [0.0, 0.0, 0.0]\norientation = [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]\n"
            .to_string()
    };
    format!(
        "name = \"Crossed\"\ngravity = [0.0, 0.0, {gravity}]\n\
         [[body]]\nname = \"top\"\nmass = 1.0\ninertia = [0.01, 0.01, 0.002]\n\
         position = [0.0, 0.0, 0.2]\n\
         orientation = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]\n\
         velocity = [0.0, 0.0, -1.0]\n\
         [[body]]\nname = \"bottom\"\nmass = 2.0\ninertia = [0.02, 0.02, 0.004]\n{bottom}\
         [[collision]]\nname = \"a\"\nbody = \"top\"\n{shape_top}\nfriction = {mu}\n\
         stiffness = 1e5\ndamping = 0.0\n\
         [[collision]]\nname = \"b\"\nbody = \"bottom\"\n{shape_bottom}\nfriction = {mu}\n\
         stiffness = 1e5\ndamping = 0.0\n\
         [[contact_pair]]\na = \"a\"\nb = \"b\"\n"
    )
}

const CAPSULE_TOP: &str = "capsule = { radius = 0.05, length = 0.4 }";
const CAPSULE_BOTTOM: &str = "capsule = { radius = 0.06, length = 0.3 }";
const SPHERE_TOP: &str = "sphere = { radius = 0.05 }";

/// Drops the top body through its impact with fixed steps `h` for 0.4 s; returns the sideways
/// impulse over the normal one and the largest angular rate of the top body.
fn drop(text: &str, h: f64) -> (f64, f64) {
    let (m, mut s) = model(text);
    let v0 = s.outputs().bodies[0].v;
    let mut spin = 0.0_f64;
    let n = (0.4 / h).round() as usize;
    for _ in 0..n {
        step(&m, &mut s, h).unwrap();
        spin = spin.max(s.outputs().bodies[0].w.norm());
    }
    let dv = s.outputs().bodies[0].v - v0;
    assert!(dv.z > 1.0, "the top body did not bounce: Δv {dv:?}");
    (dv.x.hypot(dv.y) / dv.z.abs(), spin)
}

#[test]
fn a_capsule_dropped_square_across_a_capsule_bounces_straight() {
    for h in [1e-4, 1e-3, 1e-2] {
        for (what, top) in [("capsule", CAPSULE_TOP), ("sphere", SPHERE_TOP)] {
            let (side, spin) = drop(&crossed(top, CAPSULE_BOTTOM, 0.0, 0.0, false), h);
            eprintln!(
                "{what} across a capsule, h = {h:e}: sideways/normal impulse {side:.1e}, |ω| {spin:.1e} rad/s"
            );
            assert!(
                side <= 1e-12,
                "{what}, h = {h}: sideways impulse {side:e} of the normal"
            );
            assert!(spin <= 1e-12, "{what}, h = {h}: spin {spin:e} rad/s");
        }
    }
}

#[test]
fn a_capsule_resting_across_a_capsule_comes_to_rest() {
    // with gravity and friction on a welded capsule, the top one settles (no rocking)
    let text = crossed(CAPSULE_TOP, CAPSULE_BOTTOM, -9.81, 0.8, true)
        .replace("damping = 0.0", "damping = 2.0")
        .replace("velocity = [0.0, 0.0, -1.0]", "velocity = [0.0, 0.0, 0.0]")
        .replace(
            "position = [0.0, 0.0, 0.2]",
            "position = [0.0, 0.0, 0.1105]",
        );
    let (m, mut s) = model(&text);
    for _ in 0..5000 {
        step(&m, &mut s, 1e-3).unwrap();
    }
    let b = &s.outputs().bodies[0];
    eprintln!(
        "capsule resting across a capsule after 5 s: |v| {:.1e} m/s, |ω| {:.1e} rad/s, sideways {:.1e} m",
        b.v.norm(),
        b.w.norm(),
        b.r.x.hypot(b.r.y)
    );
    assert!(
        b.v.norm() <= 1e-6 && b.w.norm() <= 1e-6,
        "still moving: v {:?}, ω {:?}",
        b.v,
        b.w
    );
    assert!(b.r.x.hypot(b.r.y) <= 1e-9, "moved sideways: {:?}", b.r);
}

/// Two free boxes, corner of one to the face of the other, no gravity, the model's default
/// solver settings (tolerance 1e-10, max_step 1e-3), and a loose tolerance.
#[test]
fn boxes_colliding_corner_to_face_keep_momenta_at_any_tolerance() {
    for solver in ["", "[solver]\ntolerance = 1e-6\n"] {
        let text = format!(
            "name = \"Boxes\"\ngravity = [0.0, 0.0, 0.0]\n{solver}\
             [[body]]\nname = \"a\"\nmass = 1.0\ninertia = [0.01, 0.012, 0.008]\n\
             position = [-0.4, 0.03, 0.02]\norientation = [0.88, 0.28, 0.36, 0.14]\n\
             velocity = [2.0, 0.0, 0.0]\nangular_velocity = [0.5, -1.0, 2.0]\n\
             [[body]]\nname = \"b\"\nmass = 2.0\ninertia = [0.02, 0.015, 0.03]\n\
             position = [0.2, 0.0, 0.0]\n\
             velocity = [-0.5, 0.1, 0.0]\nangular_velocity = [0.0, 0.3, -0.5]\n\
             [[collision]]\nname = \"sa\"\nbody = \"a\"\nbox = {{ size = [0.2, 0.15, 0.1] }}\n\
             friction = 0.5\nstiffness = 1e5\ndamping = 0.5\n\
             [[collision]]\nname = \"sb\"\nbody = \"b\"\nbox = {{ size = [0.3, 0.3, 0.3] }}\n\
             friction = 0.5\nstiffness = 1e5\ndamping = 0.5\n\
             [[contact_pair]]\na = \"sa\"\nb = \"sb\"\n"
        );
        let (m, mut s) = model(&text);
        let o = s.outputs().clone();
        let (p0, l0) = (o.p, o.l);
        let (mut dp, mut dl, mut touched) = (0.0_f64, 0.0_f64, false);
        for _ in 0..600 {
            step(&m, &mut s, 1e-3).unwrap();
            let o = s.outputs();
            dp = dp.max((o.p - p0).norm() / p0.norm());
            dl = dl.max((o.l - l0).norm() / l0.norm());
            touched |= o.contacts[0].force.norm() > 0.0;
        }
        let tol = m.settings().tolerance;
        eprintln!("boxes corner to face, tolerance {tol:e}: |Δp|/|p| {dp:.1e}, |ΔL|/|L| {dl:.1e}");
        assert!(touched, "no contact");
        assert!(
            dp <= 1e-13 && dl <= 1e-13,
            "tolerance {tol}: Δp {dp:e}, ΔL {dl:e}"
        );
    }
}
