//! Heavy symmetric top on a fixed tip (theory.md §5.2 B5, data of §5.1: cone ρ = 2700, a = 0.1,
//! M = 0.706858 kg, J₁ = J₂ = J₃ = 5.301438e-4, l = 0.075, α₀ = π/3). (a) Steady precession
//! (ω₀ = ω_p e₃ + ω_s d₃, ω_s = Mgl/(J₃ω_p) + (J₁ + Ml² − J₃)/J₃ ω_p cos α₀): the polar-angle
//! deviation and precession-rate error are 7.55e-3, 1.90e-3, 4.76e-4 rad and 1.47e-2, 3.70e-3,
//! 9.26e-4 rad/s at h = 0.004, 0.002, 0.001 (order 2), while E and the vertical L are exact.
//! (b) Released top (ω₀ = 300 d₃): θ oscillates between 60° and θ_max = arccos u₁ = 70.3931°
//! (u₁ the smaller root of βu² − a²u + a²u₀ − β = 0) with period T = 4K(k)/√(β(u₂ − u₁)) =
//! 0.191934 s; EM errors 4.2e-5, 1.05e-5 rad (θ_max) and 4.1e-5, 1.0e-5 s (T) at h = 4e-4, 2e-4.

mod common;
use common::*;
use triad::math::{matrix_to_quat, Mat3, Vec3};
use triad::mechanics::{step, JointInitial, JointType, ModelDef};

const G: f64 = 9.81;

fn data() -> (f64, f64, f64, f64) {
    let (rho, a) = (2700.0, 0.1);
    let (r, l) = (a / 2.0, 3.0 * a / 4.0);
    let m = rho * std::f64::consts::PI * r * r * a / 3.0;
    let j1 = 3.0 / 80.0 * m * (4.0 * r * r + a * a);
    let j3 = 3.0 / 10.0 * m * r * r;
    (m, j1, j3, l)
}

fn top(w_world: Vec3) -> ModelDef {
    let (m, j1, j3, l) = data();
    let alpha0 = std::f64::consts::FRAC_PI_3;
    let r0 = rot([alpha0, 0.0, 0.0]);
    let mut j = joint(
        "tip",
        JointType::Spherical,
        None,
        0,
        Vec3::zeros(),
        Vec3::z(),
    );
    j.initial = JointInitial::Spherical {
        quat: matrix_to_quat(&r0),
        w: r0.transpose() * w_world,
    };
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -G),
        bodies: vec![body(
            "top",
            m,
            Vec3::new(0.0, 0.0, l),
            Mat3::from_diagonal(&Vec3::new(j1, j1, j3)),
        )],
        joints: vec![j],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

/// Polar angle of d₃ and its azimuth.
fn angles(rot: &Mat3) -> (f64, f64) {
    let d3 = rot.column(2);
    (d3.z.clamp(-1.0, 1.0).acos(), d3.y.atan2(d3.x))
}

#[test]
fn b5a_steady_precession() {
    let (m, j1, j3, l) = data();
    let (alpha0, wp) = (std::f64::consts::FRAC_PI_3, 10.0);
    let ws = m * G * l / (j3 * wp) + (j1 + m * l * l - j3) / j3 * wp * alpha0.cos();
    assert!((ws - 135.6).abs() < 1e-3, "spin {ws}");
    let r0 = rot([alpha0, 0.0, 0.0]);
    let w0 = Vec3::z() * wp + r0.column(2) * ws;
    let expected = [
        (0.004, 7.55e-3, 1.47e-2),
        (0.002, 1.90e-3, 3.70e-3),
        (0.001, 4.76e-4, 9.26e-4),
    ];
    for (h, dev_ref, rate_ref) in expected {
        let (md, mut s) = build(&top(w0), settings(h, 2));
        let (e0, lz0) = (s.outputs().energy, s.outputs().l.z);
        let (mut dev, mut de, mut dl) = (0.0_f64, 0.0_f64, 0.0_f64);
        let (_, az0) = angles(&s.outputs().bodies[0].rot);
        let mut az = az0;
        let n = (1.0 / h).round() as usize;
        for _ in 0..n {
            step(&md, &mut s, h).unwrap();
            let (th, raw) = angles(&s.outputs().bodies[0].rot);
            az += (raw - az) - std::f64::consts::TAU * ((raw - az) / std::f64::consts::TAU).round();
            dev = dev.max((th - alpha0).abs());
            de = de.max(rel(s.outputs().energy, e0, 1e-300));
            dl = dl.max(rel(s.outputs().l.z, lz0, 1e-300));
        }
        let rate_err = ((az - az0) / 1.0 - wp).abs();
        eprintln!("b5a h={h}: max|θ−α₀| {dev:e} (ref {dev_ref:e}), rate error {rate_err:e} (ref {rate_ref:e}), dE {de:e}, dLz {dl:e}");
        assert!(rel(dev, dev_ref, 1e-12) < 0.02 && rel(rate_err, rate_ref, 1e-12) < 0.02);
        assert!(de < tol(1e-12) && dl < tol(1e-12));
    }
}

/// Complete elliptic integral of the first kind K(m), parameter m = k², by the AGM.
fn ellipk(m: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - m).sqrt());
    for _ in 0..40 {
        let (an, bn) = (0.5 * (a + b), (a * b).sqrt());
        a = an;
        b = bn;
    }
    std::f64::consts::PI / (2.0 * a)
}

#[test]
fn b5b_released_top_nutation() {
    let (m, j1, j3, l) = data();
    let alpha0 = std::f64::consts::FRAC_PI_3;
    let w3 = 300.0;
    let a_big = j1 + m * l * l;
    let (aa, beta, u0) = (j3 * w3 / a_big, 2.0 * m * G * l / a_big, alpha0.cos());
    // roots of β u² − a² u + a² u₀ − β = 0
    let (qa, qb, qc) = (beta, -aa * aa, aa * aa * u0 - beta);
    let disc = (qb * qb - 4.0 * qa * qc).sqrt();
    let (u1, u2) = ((-qb - disc) / (2.0 * qa), (-qb + disc) / (2.0 * qa));
    let th_max = u1.acos();
    let period = 4.0 * ellipk((u0 - u1) / (u2 - u1)) / (beta * (u2 - u1)).sqrt();
    assert!(
        (th_max.to_degrees() - 70.3931).abs() < 1e-4,
        "{}",
        th_max.to_degrees()
    );
    assert!((period - 0.191934).abs() < 1e-6, "{period}");
    let r0 = rot([alpha0, 0.0, 0.0]);
    let mut errs = Vec::new();
    for (h, th_ref, per_ref) in [(4e-4, 4.2e-5, 4.1e-5), (2e-4, 1.05e-5, 1.0e-5)] {
        let (md, mut s) = build(&top(r0.column(2) * w3), settings(h, 2));
        let n = (0.6 / h).round() as usize;
        let mut th = vec![angles(&s.outputs().bodies[0].rot).0];
        for _ in 0..n {
            step(&md, &mut s, h).unwrap();
            th.push(angles(&s.outputs().bodies[0].rot).0);
        }
        // local maxima with parabolic refinement
        let (mut tm, mut thm) = (Vec::new(), Vec::new());
        for i in 1..n {
            if th[i] > th[i - 1] && th[i] >= th[i + 1] {
                let (y0, y1, y2) = (th[i - 1], th[i], th[i + 1]);
                let dx = 0.5 * (y0 - y2) / (y0 - 2.0 * y1 + y2);
                tm.push((i as f64 + dx) * h);
                thm.push(y1 - 0.25 * (y0 - y2) * dx);
            }
        }
        let per = (tm[tm.len() - 1] - tm[0]) / (tm.len() - 1) as f64;
        let e_th = (thm.iter().sum::<f64>() / thm.len() as f64 - th_max).abs();
        let e_per = (per - period).abs();
        eprintln!("b5b h={h}: θ_max error {e_th:e} (ref {th_ref:e}), period error {e_per:e} (ref {per_ref:e})");
        assert!(
            e_th < 1.5 * th_ref && e_per < 1.5 * per_ref,
            "{e_th:e} {e_per:e}"
        );
        errs.push((e_th, e_per));
    }
    let p = (errs[0].0 / errs[1].0).log2();
    assert!((p - 2.0).abs() < 0.2, "order {p}");
}
