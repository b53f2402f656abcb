//! Constraint-consistent velocity outputs (theory.md §4.3, §4.7): the nodal velocities `vₙ`
//! satisfy the hidden constraints only to O(h²); the outputs report their M-orthogonal
//! projection `v' = argmin ½(v' − vₙ)ᵀM(v' − vₙ)` subject to `G(qₙ) v' = 0`, i.e. per body the
//! twist `t = (φ̇', ω')` with `v' = P t`, `P = [I; −d̂₁; −d̂₂; −d̂₃]`, from
//! `[PᵀMP, (GP)ᵀ; GP, 0] [t; λ] = [PᵀMvₙ; 0]`, `PᵀMP = diag(m I, J_s)`, `J_s = R J Rᵀ`,
//! `PᵀMvₙ = (m φ̇, Σᵢ dᵢ × pᵢ)`. Checked here from the reported quantities only
//! (`φ̇' = v + ω × R com`, `φ = r + R com`):
//! - joint velocity constraints hold to round-off: the joint points move together
//!   (`v_A + ω_A × (p − φ_A) = v_B + ω_B × (p − φ_B)`) and for a revolute `ω_B − ω_A ∥ axis`;
//! - momenta that are first integrals are unchanged: free body `J_s ω' + φ × m φ̇' = L` (the
//!   conserved discrete `L` of `system.L`) to ≤ 1e-13, the heavy top's vertical `L_z` likewise;
//! - `T' = Σ ½ m |φ̇'|² + ½ ω'·J_s ω'` differs from `½ vₙᵀ M vₙ` by O(h⁴) (ratio ≈ 16 when h
//!   halves on the double pendulum), while `system.energy` stays `½ vₙᵀMvₙ + V`.

mod common;
use common::*;
use triad::math::{Mat3, Vec3};
use triad::mechanics::body::{angular_velocity, BodyInertia};
use triad::mechanics::{step, JointType, Model, ModelDef, State};

/// Reported twist of body `b`: centre-of-mass velocity, angular velocity, COM position, `J_s`.
fn reported(def: &ModelDef, s: &State, b: usize) -> (Vec3, Vec3, Vec3, Mat3) {
    let o = &s.outputs().bodies[b];
    let bd = &def.bodies[b];
    let c = o.rot * bd.com;
    let js = o.rot * bd.inertia * o.rot.transpose();
    (o.v + o.w.cross(&c), o.w, o.r + c, js)
}

/// Nodal (unprojected) twist of body `b` from `State::velocities`.
fn nodal(s: &State, b: usize) -> (Vec3, Vec3, Vec3) {
    let q = &s.coordinates()[12 * b..12 * b + 12];
    let v = &s.velocities()[12 * b..12 * b + 12];
    (
        Vec3::new(v[0], v[1], v[2]),
        angular_velocity(q, v),
        Vec3::new(q[0], q[1], q[2]),
    )
}

/// Largest joint velocity-constraint violation (m/s, rad/s) of twists `tw(b) = (φ̇, ω, φ)`,
/// over the joints' point coincidence and, for revolutes, the axis condition.
fn joint_violation(def: &ModelDef, s: &State, tw: &dyn Fn(usize) -> (Vec3, Vec3, Vec3)) -> f64 {
    let mut worst = 0.0_f64;
    for j in &def.joints {
        let ob = &s.outputs().bodies[j.child];
        let (vb, wb, pb) = tw(j.child);
        let p = ob.r + ob.rot * j.child_frame.translation;
        let vel_b = vb + wb.cross(&(p - pb));
        let (vel_a, wa, axis) = match j.parent {
            Some(a) => {
                let oa = &s.outputs().bodies[a];
                let (va, wa, pa) = tw(a);
                (
                    va + wa.cross(&(p - pa)),
                    wa,
                    oa.rot * j.parent_frame.rotation * j.axis,
                )
            }
            None => (
                Vec3::zeros(),
                Vec3::zeros(),
                j.parent_frame.rotation * j.axis,
            ),
        };
        if matches!(j.kind, JointType::Revolute | JointType::Spherical) {
            worst = worst.max((vel_b - vel_a).norm());
        }
        if j.kind == JointType::Revolute {
            worst = worst.max((wb - wa).cross(&axis).norm());
        }
    }
    worst
}

/// Largest twist component (scale of the relative residual).
fn scale(def: &ModelDef, s: &State) -> f64 {
    (0..def.bodies.len())
        .map(|b| {
            let (v, w, _, _) = reported(def, s, b);
            v.norm().max(w.norm())
        })
        .fold(1e-300, f64::max)
}

/// `T' = Σ ½ m |φ̇'|² + ½ ω'·J_s ω'` and `T = ½ vₙᵀ M vₙ`.
fn kinetic(def: &ModelDef, s: &State) -> (f64, f64) {
    let mut tp = 0.0;
    let mut tn = 0.0;
    for (b, bd) in def.bodies.iter().enumerate() {
        let (v, w, _, js) = reported(def, s, b);
        tp += 0.5 * bd.mass * v.norm_squared() + 0.5 * w.dot(&(js * w));
        let bi = BodyInertia::new(bd).expect("valid body");
        tn += bi.kinetic_energy(&s.velocities()[12 * b..12 * b + 12]);
    }
    (tp, tn)
}

fn run(m: &Model, s: &mut State, h: f64, n: usize) {
    for _ in 0..n {
        step(m, s, h).expect("step");
    }
}

/// Joint velocity constraints hold to round-off for the reported velocities (tree, spherical
/// and loop models), whereas the nodal ones violate them at O(h²).
#[test]
fn reported_velocities_are_admissible() {
    for (name, def, h) in [
        ("double pendulum", double_pendulum(), 1e-3),
        ("heavy top", heavy_top(), 1e-3),
        ("chain8", chain(8), 1e-3),
        ("four-bar", four_bar(0.7, 3.0), 1e-3),
    ] {
        let (m, mut s) = build(&def, settings(h, 2));
        let mut worst = 0.0_f64;
        let mut nod = 0.0_f64;
        for _ in 0..5 {
            run(&m, &mut s, h, 100);
            let sc = scale(&def, &s);
            worst = worst.max(
                joint_violation(&def, &s, &|b| {
                    let (v, w, p, _) = reported(&def, &s, b);
                    (v, w, p)
                }) / sc,
            );
            nod = nod.max(joint_violation(&def, &s, &|b| nodal(&s, b)) / sc);
        }
        println!("{name}: relative G v' = {worst:.2e}, G vₙ = {nod:.2e}");
        assert!(worst <= tol(1e-12), "{name}: {worst:e}");
    }
}

/// Free body: the angular momentum of the reported twist equals the conserved discrete `L`.
#[test]
fn free_body_momentum_from_reported_twist() {
    let r0 = rot([0.3, -0.5, 0.2]);
    let j = inertia6([0.9, 1.3, 2.2, 0.1, -0.05, 0.2]);
    let def = free_body(
        2.0,
        j,
        r0,
        r0 * Vec3::new(0.8, -1.1, 3.0),
        Vec3::new(0.3, -0.2, 0.5),
        false,
        false,
    );
    let (m, mut s) = build(&def, settings(1e-3, 2));
    let l0 = s.outputs().l;
    let mut worst = 0.0_f64;
    let mut worst_nodal = 0.0_f64;
    for _ in 0..10 {
        run(&m, &mut s, 1e-3, 100);
        let (v, w, phi, js) = reported(&def, &s, 0);
        let l = js * w + phi.cross(&v) * 2.0;
        let p = v * 2.0;
        worst = worst.max((l - l0).norm() / l0.norm());
        worst = worst.max((p - s.outputs().p).norm() / l0.norm());
        let (vn, wn, _) = nodal(&s, 0);
        let ln = js * wn + phi.cross(&vn) * 2.0;
        worst_nodal = worst_nodal.max((ln - l0).norm() / l0.norm());
    }
    println!("free body: |L(reported ω) − L|/|L| = {worst:.2e} (from ½Σd×ḋ: {worst_nodal:.2e})");
    assert!(worst <= tol(1e-13), "{worst:e}");
}

/// Heavy top: the vertical angular momentum (a first integral) is the same from `v'`.
#[test]
fn heavy_top_vertical_momentum() {
    let def = heavy_top();
    let (m, mut s) = build(&def, settings(1e-3, 2));
    let mut worst = 0.0_f64;
    for _ in 0..10 {
        run(&m, &mut s, 1e-3, 100);
        let (v, w, phi, js) = reported(&def, &s, 0);
        let l = js * w + phi.cross(&v) * def.bodies[0].mass;
        let lz = s.outputs().l.z;
        worst = worst.max((l.z - lz).abs() / s.outputs().l.norm());
    }
    println!("heavy top: |L_z(v') − L_z(vₙ)|/|L| = {worst:.2e}");
    assert!(worst <= tol(1e-13), "{worst:e}");
}

/// The kinetic energy of the reported velocities differs from `½vₙᵀMvₙ` by O(h⁴); the energy
/// output stays the conserved discrete energy.
#[test]
fn kinetic_energy_difference_is_fourth_order() {
    let def = double_pendulum();
    let mut diffs = Vec::new();
    for h in [2e-3, 1e-3, 5e-4] {
        let (m, mut s) = build(&def, settings(h, 2));
        let e0 = s.outputs().energy;
        let n = (0.5 / h).round() as usize;
        run(&m, &mut s, h, n);
        let (tp, tn) = kinetic(&def, &s);
        let d = (tp - tn).abs() / tn;
        println!("h = {h:e}: |T' − T|/T = {d:.3e}");
        assert!(
            tp <= tn * (1.0 + 1e-15),
            "projection cannot add kinetic energy"
        );
        assert!((s.outputs().energy - e0).abs() <= tol(1e-12) * e0.abs().max(1.0));
        diffs.push(d);
    }
    for w in diffs.windows(2) {
        let order = (w[0] / w[1]).log2();
        println!("observed order {order:.2}");
        assert!(order > 3.5, "order {order}");
    }
}

/// Restore and tunable-parameter changes leave consistent outputs; the projection does not
/// change the snapshot.
#[test]
fn outputs_after_restore_match() {
    let def = chain(4);
    let (m, mut s) = build(&def, settings(1e-3, 2));
    run(&m, &mut s, 1e-3, 50);
    let snap = s.snapshot();
    let out = s.outputs().clone();
    run(&m, &mut s, 1e-3, 20);
    s.restore(&m, &snap).expect("restore");
    assert_eq!(s.outputs(), &out);
    assert_eq!(s.snapshot(), snap);
}

/// Cost report (not a pass/fail criterion): a restore is a copy plus the output refresh, i.e.
/// the projection solve plus the output formulas; printed next to the cost of a step.
#[test]
fn cost_report() {
    for n in [1, 8, 32] {
        let def = chain(n);
        let (m, mut s) = build(&def, settings(1e-3, 2));
        run(&m, &mut s, 1e-3, 10);
        let snap = s.snapshot();
        let reps = 2000;
        let t0 = std::time::Instant::now();
        for _ in 0..reps {
            s.restore(&m, &snap).expect("restore");
        }
        let refresh = t0.elapsed().as_secs_f64() / f64::from(reps) * 1e6;
        let t0 = std::time::Instant::now();
        run(&m, &mut s, 1e-3, reps as usize);
        let stp = t0.elapsed().as_secs_f64() / f64::from(reps) * 1e6;
        println!("chain{n}: refresh (projection + outputs) {refresh:.2} µs, step {stp:.2} µs");
    }
}
