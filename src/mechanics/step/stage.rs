//! One energy–momentum step (order 2) or a symmetric composition of it (order 4).
//!
//! A stage of size `h` solves the scaled EM equations (see `newton`) from the predictor
//! `φ + h v̄`, `dᵢ ← cay(h ω̄) dᵢ` (mean rates extrapolated from the previous stages', see
//! `predictor`), `μ = h² λₙ/2`, then sets `v_{n+1} = (2/h)(q_{n+1} − qₙ) − vₙ`.
//! Order 4 is `Φ_{γ₁h} ∘ Φ_{γ₂h} ∘ Φ_{γ₁h}` with `γ₁ = 1/(2 − 2^{1/3})`, `γ₂ = 1 − 2γ₁`
//! (theory.md §4.8), or, with `stages = 5`, Suzuki's `Φ_{sh}² ∘ Φ_{(1−4s)h} ∘ Φ_{sh}²` with
//! `s = 1/(4 − 4^{1/3})`: its error is about 1/64 of the triple jump's at the same step
//! (measured on the heavy top, a free body and a 3-link chain; on `y' = iωy` the local errors
//! are `9.3e-4 (ωh)⁵` against `6.6e-2 (ωh)⁵`), so the same accuracy costs about 5/(3·64^{1/4})
//! ≈ 0.59 of the stages, and its backward stage is `−0.66 h` instead of `−1.70 h`. Every
//! stage is itself an EM step, so the conservation laws hold exactly whatever the stages.
//! (Sixth-order compositions, Kahan & Li's nine stages or the triple jump of triple jumps, give
//! only fourth order with this scheme: measured, every model shows `e(h)/e(h/2) = 16`.)
//!
//! **Dissipative at every λh.** A composition's backward stage (`γ₂ h < 0`) runs a damper
//! backwards: there it feeds energy in, and for a stiff damped mode (`λh` near the stage's
//! pole `2/|γ₂|`: 1.17 for the triple jump, 3.04 for Suzuki's) it amplifies the mode beyond
//! what the outer stages take. No order-4 composition with a negative stage can be dissipative
//! for every `λh`, so the step checks its dampers instead: when over the composed step the
//! dampers of some joint gave energy (beyond round-off of the kinetic energy), the step is
//! redone from its start as `n` order-2 stages of `h/n` (`n` the composition's stage count, so
//! the cost is the same), each an EM step of positive size, whose dampers can only take energy
//! ([`Plan::Midpoint`]). The step reports it (`StepStats::order2`, the joint in
//! `StepStats::stiff_damper`). Where the damping is resolved the dampers take energy in every
//! composed step and the order stays 4.
//! All work happens on workspace copies; the state is written only after every stage converged.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::error::StepError;
use super::finish::finish;
use super::identity::{balanced, narrowest, COLLAPSED, LARGE_TURN};
use super::momentum::balance;
use super::newton::{evaluate, resolve, solve, stage_rates, update, Held, Mode, Work};
use super::predictor::{invalidate, predict, record, Start};
use super::work::FACTOR_EFFORT;
use crate::mechanics::model::constraint::body_nodes;
use crate::mechanics::model::runtime::Model;

/// Statistics of one step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepStats {
    /// Newton iterations over all stages.
    pub iterations: usize,
    /// Iterations among them that assembled and factored the Jacobian (the others are chord
    /// iterations that reuse the factors: residual and back-substitution only).
    pub factorizations: usize,
    /// Final scaled residual.
    pub residual: f64,
    /// Stages the reduced iteration (joint increments) handed to the multiplier form because
    /// it did not converge or its root failed the energy identity; 0 for models that use the
    /// multiplier form throughout.
    pub fallbacks: usize,
    /// Steps of an order-4 run redone as order-2 stages because a damper would have fed energy
    /// in (module docs): 0 or 1 per step.
    pub order2: usize,
    /// The joint whose dampers gave energy in the composed step that was redone at order 2
    /// (`None` with `order2 = 1`: the contacts').
    pub stiff_damper: Option<usize>,
}

/// How a step is composed of stages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Plan {
    /// The model's order: one stage, or the order-4 composition.
    Configured,
    /// `n` order-2 stages of `h/n` (the stiff-damper fallback of an order-4 step).
    Midpoint(usize),
}

/// What [`compose`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Composed {
    /// The step is in the workspace.
    Done,
    /// The composed step's dampers of this joint (`None`: the contacts) gave energy: redo it
    /// with [`Plan::Midpoint`] (the workspace is mid-step).
    FedEnergy(Option<usize>),
}

/// Triple-jump coefficient `γ₁ = 1/(2 − 2^{1/3})`.
#[must_use]
pub fn gamma1() -> f64 {
    1.0 / (2.0 - 2f64.cbrt())
}

/// Suzuki's coefficient `s = 1/(4 − 4^{1/3})`.
#[must_use]
pub fn suzuki() -> f64 {
    1.0 / (4.0 - 4f64.cbrt())
}

/// The stage sizes of one step as fractions of `h` for `order` and `stages` (see the module
/// docs), written into `out`; returns how many.
#[must_use]
pub fn stage_fractions(order: u8, stages: u8, out: &mut [f64; 5]) -> usize {
    if order != 4 {
        out[0] = 1.0;
        return 1;
    }
    if stages == 5 {
        let s = suzuki();
        *out = [s, s, 1.0 - 4.0 * s, s, s];
        5
    } else {
        let g1 = gamma1();
        out[..3].copy_from_slice(&[g1, 1.0 - 2.0 * g1, g1]);
        3
    }
}

/// The stages of one step of size `h` on the workspace, from `ws.qn`, `ws.vn`, … (the state
/// at the step start, copied in by the caller) to the end of the step in the same buffers, as
/// `plan` says: one stage at order 2, the composition's stages at order 4 (each stage
/// extrapolates from its own predictor table), or [`Plan::Midpoint`]'s order-2 stages. An
/// order-4 step whose dampers gave energy ends as [`Composed::FedEnergy`] (module docs). On
/// error the workspace is left mid-step; the caller's state is untouched.
///
/// # Errors
/// [`StepError`] when a stage's Newton iteration fails after its halvings.
pub(crate) fn compose(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    h: f64,
    plan: Plan,
    stats: &mut StepStats,
) -> Result<Composed, StepError> {
    let settings = model.settings();
    let mut fractions = [0.0; 5];
    let count = match plan {
        Plan::Configured => stage_fractions(settings.order, settings.stages, &mut fractions),
        Plan::Midpoint(n) => {
            let n = n.clamp(1, fractions.len());
            fractions[..n].fill(1.0 / n as f64);
            n
        }
    };
    let stages = &fractions[..count];
    let order4 = plan == Plan::Configured && count > 1;
    ws.loss.fill(0.0);
    ws.contact_loss = 0.0;
    // only dampers and contacts can give energy back: models without any skip the check
    let guard = order4
        && (held.damping.iter().any(|&c| c != 0.0)
            || !model.contact.is_empty()
            || model
                .joints
                .iter()
                .any(|j| j.stops.is_some_and(|s| s.damping != 0.0) || j.friction.is_some()));
    let kinetic0 = if guard { kinetic(model, &ws.vn) } else { 0.0 };
    for (k, &g) in stages.iter().enumerate() {
        let table = if order4 { 1 + k } else { 0 };
        robust_stage(model, ws, held, g * h, Some(table), 0, stats)?;
    }
    if guard {
        let kinetic = kinetic0.max(kinetic(model, &ws.vn));
        if let Some(j) = fed_energy(ws, kinetic) {
            return Ok(Composed::FedEnergy(Some(j)));
        }
        if -ws.contact_loss > GAIN_SHARE * kinetic {
            return Ok(Composed::FedEnergy(None));
        }
    }
    Ok(Composed::Done)
}

/// Kinetic energy `½ Σ (m |v_φ|² + Σᵢⱼ Eᵢⱼ v_dᵢ·v_dⱼ)` of nodal velocities `v`, J.
fn kinetic(model: &Model, v: &[f64]) -> f64 {
    let mut t = 0.0;
    for (b, br) in model.bodies.iter().enumerate() {
        let vb = body_nodes(v, b);
        t += br.mass * vb[0].norm_squared();
        for i in 0..3 {
            for j in 0..3 {
                t += br.e[(i, j)] * vb[i + 1].dot(&vb[j + 1]);
            }
        }
    }
    0.5 * t
}

/// Share of the kinetic energy that the dampers of one joint may give over a composed step,
/// as round-off: a damper's loss is a sum of `c Δθ²/h` over the stages, exact to round-off of
/// the energy exchanged.
const GAIN_SHARE: f64 = 1e-12;

/// The first joint whose dampers gave energy over the composed step (beyond [`GAIN_SHARE`] of
/// `kinetic`, the larger kinetic energy of the step's start and end), if any. A damper gives
/// energy back inside the backward stage (`γ₂ h < 0`); over the whole step that wins for a
/// stiff enough damped mode (`λ h` near the stage's pole, module docs).
fn fed_energy(ws: &Work, kinetic: f64) -> Option<usize> {
    ws.loss
        .iter()
        .position(|&taken| -taken > GAIN_SHARE * kinetic)
}

/// Largest contraction per iteration `|δₖ|/|δₖ₋₁|` with which chord iterations go on reusing
/// the factors of the last Jacobian; a slower one assembles and factors a fresh Jacobian.
const CHORD_RATE: f64 = 1e-2;

/// Largest scaled body update of the first (Newton) iteration after which chord iterations
/// are tried (their contraction rate is about the size of that update).
const CHORD_START: f64 = 1e-3;

/// A chord iterate is accepted when its estimated distance to the solution is below
/// `CHORD_ACCEPT · tolerance` (1e-18 at the default tolerance). The residual is scaled by h²/2,
/// so a scaled error of 1e-16 is still a force error of 1e-16·2/h²: with 1e-6 · tolerance a free
/// body at h = 0.02 drifted by 2.6e-12 in energy through its flip (Newton's quadratic
/// convergence lands near 1e-18).
const CHORD_ACCEPT: f64 = 1e-8;

/// ... unless the round-off floor of the scaled updates, which grows with the number of bodies
/// `N` (measured ≈ 0.6 ε N: 8e-16 for the double pendulum, 1.2e-14 for chain100, 1.4e-13 for
/// chain1000), is larger: an estimated error below `FLOOR_SHARE · ε · N`, about 1/60 of that
/// floor, is as converged as the iterate can be (for one body the bound stays ≈ 1e-18).
const FLOOR_SHARE: f64 = 1e-2;

/// Stages solved in the multiplier form after the reduced iteration handed one back.
const MULTIPLIER_STAGES: u32 = 8;

/// Deepest halving of a stage whose Newton iteration failed.
const MAX_HALVINGS: usize = 3;

/// A stage of size `h`; if Newton fails (no convergence or a singular matrix) from a start at
/// the nodal rate, the stage is retried from the last stages' means (`predictor::Start`), and
/// if that fails too, redone as two EM stages of `h/2` (at most [`MAX_HALVINGS`] deep). Every
/// sub-stage is itself an EM step, so energy, momentum and the torque balance stay exact; only
/// the local accuracy of that step changes.
fn robust_stage(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    h: f64,
    table: Option<usize>,
    depth: usize,
    stats: &mut StepStats,
) -> Result<(), StepError> {
    let (mut outcome, nodal) = attempt(model, ws, held, h, table, Start::Rates, stats);
    let retry = |e: &StepError| {
        matches!(e, StepError::NoConvergence { .. } | StepError::Singular)
            && model.settings().max_iterations > 1
    };
    if nodal && outcome.as_ref().is_err_and(retry) {
        outcome = attempt(model, ws, held, h, table, Start::Means, stats).0;
    }
    match outcome {
        Ok(s) => {
            stats.iterations += s.iterations;
            stats.factorizations += s.factorizations;
            stats.residual = s.residual;
            Ok(())
        }
        Err(e) if depth < MAX_HALVINGS && retry(&e) => {
            if let Some(t) = table {
                invalidate(ws, t);
            }
            robust_stage(model, ws, held, 0.5 * h, None, depth + 1, stats)?;
            robust_stage(model, ws, held, 0.5 * h, None, depth + 1, stats)
        }
        Err(e) => Err(e),
    }
}

/// One attempt at a stage of size `h` from `start`: the reduced iteration first where it
/// applies; a stage it does not converge is redone in the multiplier form (same equations,
/// same solution). For a while after a stage was handed back, stages go to the multiplier form
/// straight away (large steps on long chains: the next ones would likely fail alike, at the
/// cost of a failed attempt each). Also returns whether the start was the nodal rate.
fn attempt(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    h: f64,
    table: Option<usize>,
    start: Start,
    stats: &mut StepStats,
) -> (Result<StepStats, StepError>, bool) {
    let reduced = model.uses_reduced_solver() && ws.memory.multipliers == 0;
    ws.memory.multipliers = ws.memory.multipliers.saturating_sub(1);
    let nodal = predict(model, ws, h, table, start);
    let mut outcome = stage(model, ws, held, h, table, reduced);
    // any failure of the reduced attempt (also a non-finite iterate, where its defects or arcs
    // ran away) is handed to the multiplier form, which reports its own
    if reduced && outcome.is_err() {
        stats.fallbacks += 1;
        ws.memory.multipliers = MULTIPLIER_STAGES;
        predict(model, ws, h, table, start);
        outcome = stage(model, ws, held, h, table, false);
    }
    (outcome, nodal)
}

/// One EM stage of size `h` (may be negative inside the composition) on the workspace, from
/// the predictor in `ws.q`, `ws.dq`, `ws.mu` (`predictor::predict`).
fn stage(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    h: f64,
    table: Option<usize>,
    reduced: bool,
) -> Result<StepStats, StepError> {
    let nb = model.bodies.len();
    ws.stage_id += 1;
    stage_rates(ws, h);
    let tol = model.settings().tolerance;
    let chord_accept = (CHORD_ACCEPT * tol).max(FLOOR_SHARE * f64::EPSILON * nb as f64);
    let (it, factorizations, last_res) = if reduced {
        let c = super::reduced::iterate::newton(model, ws, held, h, chord_accept)?;
        (c.iterations, c.factorizations, c.error)
    } else {
        multiplier_newton(model, ws, held, h, chord_accept)?
    };
    // bodies in contact: the momenta exact at any tolerance (`momentum`)
    balance(model, ws, held, h);
    // a stage that turned a body by about π, or whose root breaks the energy identity, is
    // refused (near π the rows are ill-conditioned, at π a root of them need not solve the
    // equations; see `identity`)
    let narrowest = narrowest(model, ws);
    if narrowest < COLLAPSED || (narrowest < LARGE_TURN && !balanced(model, ws, held, h)) {
        return Err(StepError::NoConvergence {
            iterations: it,
            residual: f64::NAN,
        });
    }
    // work and unwrapped angles at the converged iterate
    let work = finish(model, ws, held, h);
    if !work.is_finite() || ws.acc.iter().any(|x| !x.is_finite()) {
        return Err(StepError::NonFinite("state"));
    }
    // the tangent map through this stage (discrete-time linear models only)
    if let Some(mut t) = ws.tangent.take() {
        let carried = t.stage(model, ws, held, h);
        ws.tangent = Some(t);
        carried?;
    }
    // v_{n+1} = vₙ + 2a/h in double-double (two-sum), a from the final evaluation
    let two_over_h = 2.0 / h;
    for ((vn, vlo), acc) in ws.vn.iter_mut().zip(ws.vlo.iter_mut()).zip(&ws.acc) {
        let c = *vlo + acc * two_over_h;
        (*vn, *vlo) = two_sum(*vn, c);
    }
    ws.qn.copy_from_slice(&ws.q);
    ws.bristle.copy_from_slice(&ws.bristle1);
    let ih2 = 1.0 / (h * h);
    for k in 0..ws.mu.len() {
        ws.lam[k] = ws.mu[k] * ih2;
    }
    ws.ang.copy_from_slice(&ws.ang1);
    ws.arm.copy_from_slice(&ws.arm1);
    ws.fric.copy_from_slice(&ws.fric1);
    ws.work += work;
    record(ws, nb, h, table);
    Ok(StepStats {
        iterations: it,
        factorizations,
        residual: last_res,
        ..StepStats::default()
    })
}

/// The Newton iteration of a stage in the multiplier form (body increments and joint
/// multipliers) from the predictor: returns the iterations, the factorisations among them and
/// the estimated error of the accepted iterate.
fn multiplier_newton(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    h: f64,
    chord_accept: f64,
) -> Result<(usize, usize, f64), StepError> {
    let tol = model.settings().tolerance;
    let maxit = model.settings().max_iterations;
    let mut it = 0;
    let mut last_res: f64;
    let mut prev_full = f64::INFINITY;
    let (mut prev_upd, mut prev_dmu) = (f64::INFINITY, f64::INFINITY);
    // best contraction of the body and multiplier updates since the last factorisation
    let mut rates = [f64::INFINITY; 2];
    // Newton with chord iterations: an iteration with a fresh Jacobian (assembled and factored)
    // is followed by iterations that reuse its factors (residual + back-substitution) as long
    // as they contract by ≤ CHORD_RATE per iteration; slower contraction refactors.
    let mut fresh = true;
    let mut factorizations = 0;
    loop {
        it += 1;
        let mode = if fresh { Mode::Full } else { Mode::Residual };
        let n = evaluate(model, ws, held, h, mode);
        if !n.res.is_finite() {
            return Err(StepError::NonFinite("state"));
        }
        ws.effort += 1 + if fresh { FACTOR_EFFORT } else { 0 };
        let solved = if fresh {
            factorizations += 1;
            solve(model, ws)
        } else {
            resolve(model, ws)
        };
        if !solved {
            return Err(StepError::Singular);
        }
        let (upd, dmu) = update(model, ws);
        if !upd.is_finite() {
            return Err(StepError::NonFinite("state"));
        }
        last_res = n.res.max(upd);
        // a Newton update ≤ tol at a residual ≤ tol leaves an error of O(|δ|²); a chord update
        // only an error of O(rate·|δ|), so chord iterates are accepted by the test below only
        if fresh && upd <= tol && n.res <= tol {
            break;
        }
        // the full update (bodies and multipliers) contracted by θ ≤ 1e-2 against the previous
        // one, so the distance of the updated iterate to the solution is about θ·|δ|/(1 − θ)
        // (for Newton smaller still). Accept once that estimate is below tol/100: as converged
        // as a Newton iterate that passed the test above.
        let full = upd.max(dmu);
        let theta = full / prev_full;
        if fresh && it > 1 && theta <= 1e-2 && theta * full <= 1e-2 * tol {
            last_res = theta * full;
            break;
        }
        // A chord iterate carries about rate·|δ| of error into the accepted state, and the
        // conservation laws hold only as far as the equations are solved: the body unknowns
        // must be within round-off (CHORD_ACCEPT · tol) by that estimate, the multipliers (which
        // do no work while the constraints hold) within tol/100 like a Newton iterate.
        // The chord rate is estimated by the best contraction seen since the factorisation:
        // convergence is linear at that rate until round-off, where the observed ratios turn
        // to noise (≈ 1) while the iterate is as converged as it gets.
        if fresh {
            rates = [f64::INFINITY; 2];
        } else {
            rates[0] = rates[0].min(upd / prev_upd);
            rates[1] = rates[1].min(dmu / prev_dmu);
            let [rb, rm] = rates;
            let mu_ok = rm.min(1.0) * dmu <= 1e-2 * tol;
            if rb <= 1e-2 && rb * upd <= chord_accept && mu_ok {
                last_res = (rb * upd).max(rm * dmu);
                break;
            }
            // round-off floor: after contracting well the updates stop shrinking at a size
            // set by the number of bodies; a fresh Newton iteration would land on the same
            // floor, so the iterate is accepted as Newton's would be at that size
            if rb <= 1e-2 && upd >= 0.5 * prev_upd && upd <= 1e-2 * tol && mu_ok {
                last_res = upd.max(rm * dmu);
                break;
            }
        }
        prev_upd = upd;
        prev_dmu = dmu;
        prev_full = full;
        if it >= maxit {
            return Err(StepError::NoConvergence {
                iterations: it,
                residual: n.res.max(upd),
            });
        }
        // the last allowed iteration is a Newton one, so a tight iteration budget
        // (`max_iterations`) converges as it did without chord iterations
        // (after the first iteration the chord rate is about the size of its update: chord
        // iterations follow a small one only)
        let slow = if it == 1 {
            upd > CHORD_START
        } else {
            theta > CHORD_RATE
        };
        fresh = slow || it + 1 >= maxit;
    }
    Ok((it, factorizations, last_res))
}

/// Error-free sum: `a + b = s + e` exactly.
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}
