//! Order 4 with stiff viscous damping stays dissipative at every λh. The composition's
//! backward stage (γ₂ h < 0) runs a damper backwards and feeds energy in; for a damped rate λ
//! with λh near that stage's pole (1.17 for the triple jump, 3.04 for Suzuki's five stages) it
//! amplifies the mode beyond what the outer stages take. Such a step is redone as order-2
//! stages (`StepStats::order2`, the joint in `stiff_damper`), whose dampers can only take
//! energy: over a sweep of λh from 1e-2 to 1e4 the kinetic energy never rises over a step (beyond 1e-12 of
//! itself, the round-off of the energy exchanged within the step) and `energy − work` stays at
//! round-off. Where the damping is resolved no step falls back and the
//! error falls as h⁴.

use triad::mechanics::{step, Model, State};
use triad::spec::{Format, Spec};

/// A disc on a revolute joint, no gravity: J = 1e-4 kg·m², damping c, q̇₀ = 1 rad/s; the rate
/// decays as exp(−λt), λ = c/J.
fn disc_with(c: f64, order: u8, stages: u8, h: f64) -> (Model, State) {
    let text = format!(
        "name = \"Spin\"\ngravity = [0.0, 0.0, 0.0]\n[solver]\nmax_step = {h}\norder = {order}\nstages = {stages}\n\
         [[body]]\nname = \"disc\"\nmass = 1.0\ninertia = [0.0001, 0.0001, 0.0001]\n\
         [[joint]]\nname = \"spin\"\ntype = \"revolute\"\nparent = \"world\"\nchild = \"disc\"\naxis = [0.0, 0.0, 1.0]\n\
         damping = {c}\ninitial = {{ q = 0.0, qd = 1.0 }}\n"
    );
    let spec = Spec::from_str(&text, Format::Toml, "spin.toml").unwrap();
    let (def, settings) = spec.lower().unwrap();
    let model = Model::new(&def, settings).unwrap();
    let state = State::new(&model);
    (model, state)
}

/// λh values: 60 per decade from 1e-2 to 1e4, and the two poles.
fn sweep() -> Vec<f64> {
    let mut v: Vec<f64> = (0..=360)
        .map(|k| 10f64.powf(-2.0 + k as f64 / 60.0))
        .collect();
    v.extend([1.1748, 3.0397]);
    v
}

#[test]
fn every_step_is_dissipative_at_every_lambda_h() {
    let h = 1e-3;
    for stages in [3u8, 5] {
        let mut fell_back = Vec::new();
        let mut worst = 0.0f64;
        for lh in sweep() {
            let (model, mut s) = disc_with(lh / h * 1e-4, 4, stages, h);
            let e0 = s.outputs().energy;
            let mut last = e0;
            for n in 0..20 {
                let stats = step(&model, &mut s, h)
                    .unwrap_or_else(|e| panic!("stages {stages}, λh = {lh}: step {n}: {e}"));
                if stats.order2 > 0 {
                    assert_eq!(stats.stiff_damper, Some(0));
                    fell_back.push(lh);
                }
                let e = s.outputs().energy;
                assert!(
                    e <= last * (1.0 + 1e-12),
                    "stages {stages}, λh = {lh}: step {n}: energy rose {last} -> {e}"
                );
                last = e;
            }
            let o = s.outputs();
            let drift = (o.energy - o.work - e0).abs();
            worst = worst.max(drift / e0);
        }
        // round-off of the energy exchanged (the backward stage's swing near its pole is
        // larger than the kinetic energy: measured ≤ 5.3e-14 of it)
        assert!(
            worst <= 2e-13,
            "stages {stages}: E − W drift {worst:e} of E₀"
        );
        // the fallback is taken around the backward stage's pole (and only where needed)
        let pole = if stages == 3 { 1.1748 } else { 3.0397 };
        assert!(
            fell_back.iter().any(|&lh| (lh - pole).abs() < 1e-3),
            "{stages}: {fell_back:?}"
        );
        assert!(
            fell_back.iter().all(|&lh| lh > 0.5 * pole),
            "stages {stages}: order 2 taken at resolved damping: {fell_back:?}"
        );
    }
}

/// A step in the band reports the fallback, and the state says so (the notices read it).
#[test]
fn a_fallback_is_reported() {
    let h = 1e-3;
    let (model, mut s) = disc_with(1.1748 / h * 1e-4, 4, 3, h);
    assert_eq!(s.order2_steps(), (0, None));
    let stats = step(&model, &mut s, h).unwrap();
    assert_eq!((stats.order2, stats.stiff_damper), (1, Some(0)));
    assert_eq!(s.order2_steps(), (1, Some(0)));
    // the order-2 step of the same size damps the mode exactly as a midpoint step does
    let (m2, mut s2) = disc_with(1.1748 / h * 1e-4, 2, 3, h / 3.0);
    for _ in 0..3 {
        step(&m2, &mut s2, h / 3.0).unwrap();
    }
    let rate = |s: &State| s.outputs().joints[0].qd[0];
    assert!(
        (rate(&s) - rate(&s2)).abs() <= 1e-14,
        "{} {}",
        rate(&s),
        rate(&s2)
    );
}

/// Resolved damping (λh = 0.05 … 0.0125): no fallback, and the error of the angle after 0.1 s
/// falls as h⁴ (ratio 16 per halving, within 10 %).
#[test]
fn resolved_damping_keeps_order_4() {
    let lambda = 50.0;
    let exact = |t: f64| (1.0 - (-lambda * t).exp()) / lambda;
    let mut errors = Vec::new();
    for h in [1e-3, 5e-4, 2.5e-4] {
        let (model, mut s) = disc_with(lambda * 1e-4, 4, 3, h);
        let n = (0.1 / h).round() as usize;
        for _ in 0..n {
            let stats = step(&model, &mut s, h).unwrap();
            assert_eq!(stats.order2, 0, "h = {h}");
        }
        errors.push((s.outputs().joints[0].q[0] - exact(0.1)).abs());
    }
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        assert!(
            (14.4..17.6).contains(&ratio),
            "error ratio {ratio} ({errors:?})"
        );
    }
}
