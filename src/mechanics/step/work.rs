//! The preallocated Newton workspace of a step and the loads held over it.

use super::reduced::work::RedWork;
use super::tangent_state::Tangent;
use crate::mechanics::linalg::border::Border;
use crate::mechanics::linalg::tree::Block;
use crate::mechanics::model::runtime::Model;

/// Stages of predictor history kept (mean rates and sizes).
pub const HISTORY: usize = 6;

/// Difference tables of the predictor: table 0 follows every stage, tables 1–5 the stages of
/// the order-4 composition (3 or 5; allocated for order-4 models only).
pub const TABLES: usize = 6;

/// Length of the predictor history of `model` (`Work::hist`, `State::hist`): 6 numbers per
/// body, difference and table; order-4 models keep one table per stage besides table 0.
#[must_use]
pub fn history_len(model: &Model) -> usize {
    let s = model.settings();
    let tables = if s.order == 4 {
        1 + usize::from(s.stages.max(3))
    } else {
        1
    };
    6 * HISTORY * model.bodies.len() * tables
}

/// What the solver remembers of the last stages: counts of stages left in which it deviates
/// from its default (part of the state and of its snapshot, so that a restored state repeats
/// the original run exactly).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Memory {
    /// Stages in which the reduced iteration refreshes its Newton matrix at the second
    /// iteration too (set when chord iterations stopped contracting).
    pub eager: u32,
    /// Stages solved in the multiplier form straight away (set when the reduced iteration
    /// handed a stage back: the next ones would likely fail alike).
    pub multipliers: u32,
    /// Reduced stages left before the next one settles its start onto the joint rows
    /// (`reduced::settle`, every [`SETTLE_EVERY`] stages).
    pub settle: u32,
}

/// What a factorisation adds to [`Work::effort`], in iterations (an assembly and factorisation
/// costs about two residual evaluations and solves).
pub const FACTOR_EFFORT: u64 = 2;

/// A reduced stage settles its start onto the joint rows once in this many (the rows' round-off
/// grows as a random walk in between, by about √8 ε; settling every stage cost 5 % of a step).
pub const SETTLE_EVERY: u32 = 8;

impl Memory {
    /// Numbers in a snapshot.
    pub const LEN: usize = 3;

    /// As numbers of a snapshot.
    #[must_use]
    pub fn to_f64(self) -> [f64; Self::LEN] {
        [
            f64::from(self.eager),
            f64::from(self.multipliers),
            f64::from(self.settle),
        ]
    }

    /// From numbers of a snapshot (anything but a small non-negative count reads as 0).
    #[must_use]
    pub fn from_f64(x: [f64; Self::LEN]) -> Self {
        let count = |v: f64| {
            if (0.0..=1e6).contains(&v) {
                v as u32
            } else {
                0
            }
        };
        Self {
            eager: count(x[0]),
            multipliers: count(x[1]),
            settle: count(x[2]),
        }
    }
}

/// Preallocated Newton workspace (all sized at `State::new`).
#[derive(Clone, Debug)]
pub(crate) struct Work {
    /// Stage start: coordinates, velocities (12 per body).
    pub qn: Vec<f64>,
    /// Stage start velocities (high part).
    pub vn: Vec<f64>,
    /// Stage start velocities, low part: `vn + vlo` carries the velocity in double-double so
    /// that the recursion `v_{n+1} = v_n + 2a/h` accumulates no rounding (energy drift).
    pub vlo: Vec<f64>,
    /// `a = (q − qₙ) − h vₙ` of the last evaluation (12 per body).
    pub acc: Vec<f64>,
    /// `h vₙ` of the stage, rounded (12 per body; `stage_rates`).
    pub hv: Vec<f64>,
    /// The rest of `h (vₙ + v_lo)`: the rounding error of `hv` plus `h v_lo`.
    pub hv_lo: Vec<f64>,
    /// Multiplier memory `λ/2` per active row (warm start `μ = h² λ/2`).
    pub lam: Vec<f64>,
    /// Unwrapped turn angles at the stage start, rad.
    pub ang: Vec<f64>,
    /// Rotor rates at the stage start (`State::arm`), rad/s or m/s.
    pub arm: Vec<f64>,
    /// Rotor rates at the iterate's end of the stage (`finish`).
    pub arm1: Vec<f64>,
    /// Joint friction bristles at the stage start (`State::fric`), rad or m.
    pub fric: Vec<f64>,
    /// Joint friction bristles at the stage's end (`finish`).
    pub fric1: Vec<f64>,
    /// Accumulated work at the stage start, J.
    pub work: f64,
    /// Per joint, the energy its dampers (viscous and stop) took over the stages of the
    /// current step so far, J (a backward stage adds a negative amount).
    pub loss: Vec<f64>,
    /// Energy the contacts dissipated over the stages of the current step so far, J (a
    /// backward stage adds a negative amount).
    pub contact_loss: f64,
    /// Contact bristles at the stage's start (3 per ground point, then per feature), m.
    pub bristle: Vec<f64>,
    /// Contact bristles at the stage's end (`contact_finish`), m.
    pub bristle1: Vec<f64>,
    /// Predictor history: backward differences of the mean rates `(Δφ/h, θ/h)` of the last
    /// [`HISTORY`] stages, `[table][difference][body][6]` (see `predictor`).
    pub hist: Vec<f64>,
    /// Sizes of the stages of each table, newest first, s (0: no history).
    pub hprev: [[f64; HISTORY]; TABLES],
    /// The iteration's memory of the last stages (see [`Memory`]).
    pub memory: Memory,
    /// Newton work done on this workspace, in iterations: one per residual evaluation and
    /// solve, [`FACTOR_EFFORT`] more per factorisation (a measure, not state: never in a
    /// snapshot; callers bound the difference over a communication step).
    pub effort: u64,
    /// Newton iterate.
    pub q: Vec<f64>,
    /// Increment `q − qₙ`, kept separately so that velocities do not suffer the cancellation
    /// of large positions.
    pub dq: Vec<f64>,
    /// Midpoint `½(qₙ + q)`.
    pub qbar: Vec<f64>,
    /// Node residual `R̃` (12 per body).
    pub rn: Vec<f64>,
    /// Scaled multipliers.
    pub mu: Vec<f64>,
    /// Unwrapped turn angles at the iterate.
    pub ang1: Vec<f64>,
    /// `[s₀, c₀]` of each turn coordinate at the stage start (`turn`), valid where
    /// `sc0_at` equals `stage_id` (`joint_loads::turn_start`).
    pub sc0: Vec<[f64; 2]>,
    /// See `sc0`.
    pub sc0_at: Vec<u64>,
    /// Count of stage starts (`qₙ` set or settled), from 1.
    pub stage_id: u64,
    /// Discrete rotation increments `θ_b = ½ Σ d̄ⁱ × (dᵢ − dᵢₙ)` (3 per body).
    pub theta: Vec<f64>,
    /// Scaled joint torques on the projected moment rows (3 per body).
    pub mom: Vec<f64>,
    /// Per-body 4 × 4 node coupling `C` (mass + ½ Σ μ S on the diagonal).
    pub cbody: Vec<[f64; 16]>,
    /// Per-body extra 6 × 6 diagonal Jacobian terms.
    pub xbody: Vec<[f64; 36]>,
    /// Tree blocks (one per body).
    pub blocks: Vec<Block>,
    /// Border of the loop-closing joints and its factors (empty for a tree).
    pub border: Border,
    /// Dense matrix (test oracle `Model::dense` only), row-major `n × n`.
    pub dense: Vec<f64>,
    /// Dense pivots.
    pub dpiv: Vec<usize>,
    /// Dense right-hand side / solution.
    pub drhs: Vec<f64>,
    /// Workspace of the reduced (joint-increment) iteration; empty for loop models.
    pub red: RedWork,
    /// The step's tangent map carried along (`tangent`; for a discrete-time linear model
    /// only, `None` in a plain run).
    pub tangent: Option<Box<Tangent>>,
    /// Whether a Jacobian pass assembles the inertia `M` into the body blocks (true; the
    /// tangent map assembles the other terms alone, `tangent`).
    pub inertia_in_jacobian: bool,
    /// How a Jacobian pass takes the contact forces (Newton's blocks; the tangent map's
    /// exact ones, or none).
    pub contact_jacobian: ContactJacobian,
}

impl Work {
    /// Sets the midpoint `q̄ = qₙ + ½ Δq` of the iterate.
    pub fn set_midpoint(&mut self) {
        for (qbar, (qn, dq)) in self.qbar.iter_mut().zip(self.qn.iter().zip(&self.dq)) {
            *qbar = qn + 0.5 * dq;
        }
    }

    /// Sets body `b`'s `a = Δq − h vₙ − h v_lo` (12) from the iterate's increments and the
    /// stage's `hv`, `hv_lo` (`newton::stage_rates`).
    #[inline]
    pub fn set_acc(&mut self, b: usize) {
        let at = 12 * b..12 * b + 12;
        let parts = self.dq[at.clone()].iter().zip(&self.hv[at.clone()]);
        for ((a, (dq, hv)), lo) in self.acc[at.clone()]
            .iter_mut()
            .zip(parts)
            .zip(&self.hv_lo[at])
        {
            *a = (dq - hv) - lo;
        }
    }

    /// Workspace for `model`.
    pub fn new(model: &Model) -> Self {
        let nb = model.bodies.len();
        let nr = model.nrows;
        // a body without mass or inertia has a singular body block `K`
        let blocks = model.tree_blocks(|b| model.bodies[b].singular);
        let nd = if model.dense { 6 * nb + nr } else { 0 };
        Self {
            qn: model.q0.clone(),
            vn: model.v0.clone(),
            vlo: vec![0.0; 12 * nb],
            acc: vec![0.0; 12 * nb],
            hv: vec![0.0; 12 * nb],
            hv_lo: vec![0.0; 12 * nb],
            lam: vec![0.0; nr],
            ang: model.angles0.clone(),
            arm: vec![0.0; model.narm],
            arm1: vec![0.0; model.narm],
            fric: vec![0.0; model.nfric],
            fric1: vec![0.0; model.nfric],
            work: 0.0,
            loss: vec![0.0; model.joints.len()],
            contact_loss: 0.0,
            bristle: vec![0.0; 3 * model.contact.bristles()],
            bristle1: vec![0.0; 3 * model.contact.bristles()],
            hist: vec![0.0; history_len(model)],
            hprev: [[0.0; HISTORY]; TABLES],
            memory: Memory::default(),
            effort: 0,
            q: model.q0.clone(),
            dq: vec![0.0; 12 * nb],
            qbar: model.q0.clone(),
            rn: vec![0.0; 12 * nb],
            mu: vec![0.0; nr],
            ang1: model.angles0.clone(),
            sc0: vec![[0.0; 2]; model.angles0.len()],
            sc0_at: vec![0; model.angles0.len()],
            stage_id: 1,
            theta: vec![0.0; 3 * nb],
            mom: vec![0.0; 3 * nb],
            cbody: vec![[0.0; 16]; nb],
            xbody: vec![[0.0; 36]; nb],
            blocks,
            border: model.border(),
            dense: vec![0.0; nd * nd],
            dpiv: vec![0; nd],
            drhs: vec![0.0; nd],
            red: RedWork::new(model),
            tangent: None,
            inertia_in_jacobian: true,
            contact_jacobian: ContactJacobian::Newton,
        }
    }
}

/// How a Jacobian pass takes the contact forces (`Work::contact_jacobian`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactJacobian {
    /// Each body's own terms, the coupling through features left out (`contact`): Newton.
    Newton,
    /// The ground points' blocks exact (module formulas): the tangent's matrix at the root.
    Exact,
    /// No contact forces at all: the tangent's other terms, evaluated alone.
    Off,
}

/// Loads and parameters held over a step.
pub(crate) struct Held<'a> {
    /// Input values in `Model::inputs` order.
    pub inputs: &'a [f64],
    /// Per-joint damping.
    pub damping: &'a [f64],
    /// Per-joint stiffness.
    pub stiffness: &'a [f64],
    /// Gains `[kp, kv]` of each actuator of the model (two per actuator, `State::gains`).
    pub gains: &'a [f64],
}

/// Residual norms of an evaluation.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Norms {
    /// Scaled residual (max norm).
    pub res: f64,
}

/// What one call of `newton::evaluate` computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mode {
    /// Residual (all rows, norms, right-hand side `−r`) and the analytic Jacobian: clears
    /// and fills the tree blocks (`d`, `u`, `l`, `r`) and the border, or the dense system
    /// (`dense`, `drhs`).
    Full,
    /// Everything [`Mode::Full`] computes for the right-hand side, bit for bit, but no
    /// Jacobian: zeroes and fills only the right-hand sides (`Block::r` of every block and the
    /// border's `rc`, or `drhs`); the matrices `d`, `u`, `l`, the border's and `dense` are left
    /// untouched (they may hold the
    /// factors of an earlier `Full` iteration, for chord iterations).
    Residual,
}
