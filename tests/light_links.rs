//! Light and massless links: the reported joint rates stay accurate to round-off relative to the
//! motion whatever the mass ratios (issue: rates below a light body used to lose accuracy in
//! proportion to 1/mass).
//!
//! Model: three revolute joints about y, x, y in series from the world; links of 1 kg with the
//! centre of mass 0.2 m below each joint and the next joint 0.4 m below; the middle link of
//! mass `m` and inertia `1e-4·m·I` for m = 1 … 1e-6 kg and m = 0 (massless). Gravity on.
//! Reference: an independent reduced-coordinate code in this file (recursive Newton–Euler for
//! the mass matrix and the bias forces, classical RK4 at h = 1e-5), against triad at order 4,
//! h = 1e-4.

mod common;
use common::*;
use triad::math::{exp_so3, Mat3, Vec3};
use triad::mechanics::{step, JointType, Model, ModelDef, State};

const G: f64 = 9.81;
const AXES: [Vec3; 3] = [
    Vec3::new(0.0, 1.0, 0.0),
    Vec3::new(1.0, 0.0, 0.0),
    Vec3::new(0.0, 1.0, 0.0),
];
const Q0: [f64; 3] = [0.7, -0.4, 1.1];
const QD0: [f64; 3] = [1.3, -2.1, 0.9];

/// Anchor of joint `i` in its parent's frame (world for joint 0), m.
fn anchor(i: usize) -> Vec3 {
    if i == 0 {
        Vec3::zeros()
    } else {
        Vec3::new(0.0, 0.0, -0.4)
    }
}

/// Centre of mass of every link in its frame (at the joint), m.
fn com() -> Vec3 {
    Vec3::new(0.0, 0.0, -0.2)
}

/// Mass and inertia (about the centre of mass) of link `i` for middle-link mass `m`.
fn mass_props(i: usize, m: f64) -> (f64, Mat3) {
    if i == 1 {
        (m, Mat3::identity() * (1e-4 * m))
    } else {
        (1.0, box_inertia(1.0, 0.05, 0.05, 0.4))
    }
}

fn chain(m: f64) -> ModelDef {
    let mut joints = Vec::new();
    let mut bodies = Vec::new();
    for i in 0..3 {
        let (mi, ji) = mass_props(i, m);
        bodies.push(body(&format!("l{i}"), mi, com(), ji));
        let parent = if i == 0 { None } else { Some(i - 1) };
        let mut j = joint(
            &format!("j{i}"),
            JointType::Revolute,
            parent,
            i,
            anchor(i),
            AXES[i],
        );
        set_q(&mut j, &[Q0[i]], &[QD0[i]]);
        joints.push(j);
    }
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -G),
        bodies,
        joints,
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

/// Joint torques of the reference chain by recursive Newton–Euler (world frame), for
/// coordinates `q`, rates `qd`, accelerations `qdd` and gravity `g` (m/s²).
fn rnea(m: f64, q: &[f64; 3], qd: &[f64; 3], qdd: &[f64; 3], g: Vec3) -> [f64; 3] {
    let mut rot = Mat3::identity();
    let (mut o, mut w, mut al, mut ao) =
        (Vec3::zeros(), Vec3::zeros(), Vec3::zeros(), Vec3::zeros());
    let mut kin = Vec::new();
    for i in 0..3 {
        // the joint point rides on the parent
        let r = rot * anchor(i);
        ao += al.cross(&r) + w.cross(&w.cross(&r));
        o += r;
        let s = rot * AXES[i];
        al += s * qdd[i] + w.cross(&(s * qd[i]));
        w += s * qd[i];
        rot *= exp_so3(&(AXES[i] * q[i]));
        let rho = rot * com();
        let ac = ao + al.cross(&rho) + w.cross(&w.cross(&rho));
        kin.push((o, s, rho, rot, w, al, ac));
    }
    let (mut f, mut n, mut tau) = (Vec3::zeros(), Vec3::zeros(), [0.0; 3]);
    let mut o_next = Vec3::zeros();
    for i in (0..3).rev() {
        let (oi, s, rho, rot, w, al, ac) = kin[i];
        let (mi, ji) = mass_props(i, m);
        let jw = rot * ji * rot.transpose();
        let fi = (ac - g) * mi;
        // moment about the joint point: own inertia, own force, the child's load moved here
        n = jw * al + w.cross(&(jw * w)) + rho.cross(&fi) + n + (o_next - oi).cross(&f);
        f += fi;
        tau[i] = s.dot(&n);
        o_next = oi;
    }
    tau
}

/// Accelerations `M(q)⁻¹ (−bias)` of the free chain.
fn accel(m: f64, q: &[f64; 3], qd: &[f64; 3]) -> [f64; 3] {
    let g = Vec3::new(0.0, 0.0, -G);
    let bias = rnea(m, q, qd, &[0.0; 3], g);
    let mut mm = Mat3::zeros();
    for k in 0..3 {
        let mut e = [0.0; 3];
        e[k] = 1.0;
        let col = rnea(m, q, &[0.0; 3], &e, Vec3::zeros());
        for i in 0..3 {
            mm[(i, k)] = col[i];
        }
    }
    let x = mm
        .lu()
        .solve(&Vec3::new(-bias[0], -bias[1], -bias[2]))
        .expect("regular");
    [x.x, x.y, x.z]
}

/// Reference state `(q, qd)` at time `t` (RK4, step 1e-5).
fn reference(m: f64, t: f64) -> ([f64; 3], [f64; 3]) {
    let n = (t / 1e-5).round() as usize;
    let h = t / n as f64;
    let mut y = [Q0[0], Q0[1], Q0[2], QD0[0], QD0[1], QD0[2]];
    let f = |y: &[f64; 6]| {
        let a = accel(m, &[y[0], y[1], y[2]], &[y[3], y[4], y[5]]);
        [y[3], y[4], y[5], a[0], a[1], a[2]]
    };
    let add =
        |y: &[f64; 6], k: &[f64; 6], c: f64| std::array::from_fn::<f64, 6, _>(|i| y[i] + c * k[i]);
    for _ in 0..n {
        let k1 = f(&y);
        let k2 = f(&add(&y, &k1, 0.5 * h));
        let k3 = f(&add(&y, &k2, 0.5 * h));
        let k4 = f(&add(&y, &k3, h));
        for i in 0..6 {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    ([y[0], y[1], y[2]], [y[3], y[4], y[5]])
}

/// Largest error of triad's joint angles and rates against the reference after `t` seconds,
/// relative to the largest reference rate: `(angle error, rate error)`.
fn errors(m: f64, t: f64, reduced: bool) -> (f64, f64) {
    let h = 1e-4;
    let mut model = Model::new(&chain(m), settings(h, 4)).expect("model");
    model.set_reduced_solver(reduced);
    let mut s = State::new(&model);
    let n = (t / h).round() as usize;
    for _ in 0..n {
        step(&model, &mut s, h).expect("step");
    }
    let (q, qd) = reference(m, t);
    let scale = qd.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
    let (mut eq, mut ev) = (0.0_f64, 0.0_f64);
    for i in 0..3 {
        let out = &s.outputs().joints[i];
        eq = eq.max((out.q[0] - q[i]).abs());
        ev = ev.max((out.qd[0] - qd[i]).abs() / scale);
    }
    (eq, ev)
}

#[test]
fn rates_below_a_light_link_are_accurate_for_any_mass_ratio() {
    for reduced in [true, false] {
        for m in [1.0, 1e-2, 1e-4, 1e-6, 0.0] {
            let (eq, ev) = errors(m, 0.2, reduced);
            let form = if reduced {
                "joint increments"
            } else {
                "multipliers"
            };
            eprintln!("{form}, m = {m:e} kg: angle error {eq:.2e} rad, rate error {ev:.2e}");
            assert!(eq <= tol(1e-12), "{form}, m = {m}: angle error {eq:e}");
            assert!(ev <= tol(1e-12), "{form}, m = {m}: rate error {ev:e}");
        }
    }
}
