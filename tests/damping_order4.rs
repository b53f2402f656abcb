//! Order 4 with stiff viscous damping: the triple jump's backward stage (γ₂ h < 0) turns a
//! damper into an energy source; for a damped rate λ with λh in about 1.13–1.20 that stage
//! amplifies the motion more than the outer stages damp it. Such a step is refused (the FMU
//! answers `fmi2Discard`) instead of reporting growing motion as damped; order 2 and smaller
//! steps integrate the same model.

use triad::mechanics::{step, Model, State, StepError};
use triad::spec::{Format, Spec};

/// A disc on a revolute joint, no gravity: J = 1e-4 kg·m², damping c, q̇₀ = 1 rad/s; the rate
/// decays as exp(−λt), λ = c/J.
fn disc(c: f64, order: u8, h: f64) -> (Model, State) {
    disc_with(c, order, 3, h)
}

/// [`disc`] with the composition's stage count (3: triple jump, 5: Suzuki's).
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

#[test]
fn an_amplifying_step_is_refused_and_changes_nothing() {
    // λh = 1.1748 is the pole of the backward stage; across the band the energy grows by 6 % to
    // 10⁸ per step
    for lh in [1.15, 1.1748, 1.19] {
        let (model, mut s) = disc(lh * 0.1, 4, 1e-3);
        let before = s.clone();
        let err = step(&model, &mut s, 1e-3).unwrap_err();
        assert_eq!(
            err,
            StepError::DampingAmplified("spin".into()),
            "λh = {lh}: {err}"
        );
        assert!(err
            .to_string()
            .contains("use order 2 or a smaller max_step"));
        assert_eq!(s.outputs(), before.outputs());
        assert_eq!(s.time(), before.time());
    }
}

#[test]
fn the_same_disc_decays_at_order_2_and_at_smaller_steps() {
    for (order, h) in [(2, 1e-3), (4, 5e-4), (4, 1e-4)] {
        let (model, mut s) = disc(0.11748, order, h);
        let mut last = s.outputs().energy;
        for _ in 0..(6e-3 / h).round() as usize {
            step(&model, &mut s, h).unwrap();
            let e = s.outputs().energy;
            assert!(e <= last, "order {order} h {h}: energy rose {last} -> {e}");
            last = e;
        }
        let o = s.outputs();
        let drift = (o.energy - o.work - 5e-5).abs();
        assert!(
            drift < 1e-18,
            "order {order} h {h}: energy - work drift {drift:e}"
        );
    }
}

/// Away from the band, order 4 damps as it should across λh from 0.01 to 1000.
#[test]
fn order_4_damps_outside_the_band() {
    for lh in [0.01, 0.5, 1.0, 1.3, 5.0, 100.0, 1000.0] {
        let h = 1e-3;
        let (model, mut s) = disc(lh / h * 1e-4, 4, h);
        let e0 = s.outputs().energy;
        for _ in 0..5 {
            step(&model, &mut s, h).unwrap();
        }
        assert!(s.outputs().energy < e0, "λh = {lh}");
    }
}

/// Suzuki's five stages (`stages = 5`) have a shorter backward stage (`(1 − 4s) h = −0.657 h`),
/// so their band lies at λh ≈ 3.023–3.055 (the pole `2/0.657 = 3.04`; the triple jump's
/// 1.134–1.201): the triple jump's worst case damps, the new band is refused alike.
#[test]
fn suzuki_moves_the_band() {
    let h = 1e-3;
    for lh in [1.1748, 1.19, 2.9, 3.2] {
        let (model, mut s) = disc_with(lh / h * 1e-4, 4, 5, h);
        let e0 = s.outputs().energy;
        step(&model, &mut s, h).unwrap();
        assert!(s.outputs().energy < e0, "λh = {lh}");
    }
    for lh in [3.03, 3.0397, 3.05] {
        let (model, mut s) = disc_with(lh / h * 1e-4, 4, 5, h);
        let err = step(&model, &mut s, h).unwrap_err();
        assert_eq!(err, StepError::DampingAmplified("spin".into()), "λh = {lh}");
    }
}
