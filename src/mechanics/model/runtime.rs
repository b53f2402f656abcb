//! The immutable model: bodies, joint rows, loads, tree order, initial state.
//!
//! Built once by [`Model::new`]; everything `step` needs that does not change during a run lives
//! here (the mass data, the active constraint rows of every joint, the joint coordinates used by
//! loads, the tree order used by the block elimination, the initial `q0`, `v0`).

use super::constraint::{DotRow, LinVec, Nodes, NODES};
use super::def::{JointType, ModelDef, SolverSettings};
use super::joint::JointGeom;
use super::sparse_row::SparseRow;
use super::stops::Stops;
use crate::math::{Mat3, Vec3};
use crate::mechanics::linalg::border::Border;
use crate::mechanics::linalg::tree::Block;

/// One scalar input of the model, in the order of `State::inputs`.
///
/// Order: for each joint in model order its actuator inputs (revolute `[tau]`, prismatic
/// `[f]`, cylindrical `[f, tau]`, universal `[tau1, tau2]`, spherical `[tau1, tau2, tau3]` in
/// the parent joint frame), then for each body load its torque `[x, y, z]` then force `[x, y, z]`
/// (world frame), then the control of each joint actuator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputSlot {
    /// Actuator torque of a joint, N·m; `k` is 0 for single-torque joints, else the component.
    JointTorque {
        /// Joint index.
        joint: usize,
        /// Component.
        k: usize,
    },
    /// Actuator force of a prismatic or cylindrical joint, N.
    JointForce {
        /// Joint index.
        joint: usize,
    },
    /// World-frame body torque component `i`, N·m.
    BodyTorque {
        /// Body index.
        body: usize,
        /// Component 0..3.
        i: usize,
    },
    /// World-frame body force component `i` at the centre of mass, N.
    BodyForce {
        /// Body index.
        body: usize,
        /// Component 0..3.
        i: usize,
    },
    /// The control of a joint actuator (its units: `ModelDef::actuators`).
    ActuatorCtrl {
        /// Actuator index in `ModelDef::actuators`.
        actuator: usize,
    },
}

/// A principal moment at most this fraction of a body's largest counts as zero (the body's mass
/// matrix is then singular, `BodyRt::singular`; `determinacy` finds its null directions).
pub(crate) const ZERO_MOMENT: f64 = 1e-12;

/// Mass data of one body (body axes, about the centre of mass).
#[derive(Clone, Debug)]
pub(crate) struct BodyRt {
    /// Mass, kg.
    pub mass: f64,
    /// Euler tensor `E = ½ tr(J) I − J`, kg·m².
    pub e: Mat3,
    /// Centre of mass in the body frame, m.
    pub com: Vec3,
    /// Residual scale of the body's force rows `1/(m·lc)` (1/N·s²… per the h²/2 scaling).
    pub fs: f64,
    /// Residual scale of the body's moment rows `1/(|tr E| + ½|E|)` (1/(kg·m²)).
    pub ms: f64,
    /// The mass matrix in twist coordinates `diag(m I, J)` is singular (a massless body, a
    /// point mass, a rod): its Newton supernode is factored whole (`linalg::tree::Block`).
    pub singular: bool,
}

/// A rotational joint coordinate as the step sees it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TurnRt {
    /// Rotation axis `n(q)` (world frame, unit at the nodes): actuator torques act as `±τ n̄`.
    pub axis: LinVec,
    /// `s` of `t = atan2(s, c)`.
    pub sin: DotRow,
    /// `c` of `t = atan2(s, c)`.
    pub cos: DotRow,
    /// `sin` and `cos` compiled to their non-zero nodes (the joint's parent a body or not),
    /// for the loads' pass of every Newton evaluation.
    pub sparse: [super::sparse_row::SparseRow; 2],
}

/// A joint coordinate that loads act on.
// held inline in the joints' preallocated vectors: no box, no indirection in the step
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug)]
pub(crate) enum DofRt {
    /// Translational invariant `s = row(q)` (m); its midpoint gradient is an exact discrete
    /// gradient.
    Slide(DotRow),
    /// Rotation about the world axis `n(q)` by the angle `atan2(s, c)` (see `turn`).
    Turn(TurnRt),
}

impl DofRt {
    /// The gradient of the coordinate's value at the nodes `qa`, `qb` over the eight nodes
    /// (world frame): a slide's `∇s`, a turn's `∇t = (c ∇s − s ∇c)/(s² + c²)`; its rate along
    /// node velocities is the coordinate's rate.
    pub(crate) fn rate_gradient(&self, qa: &Nodes, qb: &Nodes) -> [Vec3; 2 * NODES] {
        let mut g = [Vec3::zeros(); 2 * NODES];
        match self {
            Self::Slide(row) => row.gradient(qa, qb, &mut g),
            Self::Turn(tr) => {
                let (s, c) = (tr.sin.eval(qa, qb), tr.cos.eval(qa, qb));
                let r2 = s * s + c * c;
                let mut gc = [Vec3::zeros(); 2 * NODES];
                tr.sin.gradient(qa, qb, &mut g);
                tr.cos.gradient(qa, qb, &mut gc);
                for (x, y) in g.iter_mut().zip(&gc) {
                    *x = (*x * c - y * s) / r2;
                }
            }
        }
        g
    }
}

/// A coupling `q_b = ratio · q_a + offset` of two one-coordinate joints as the step sees it
/// (`step::coupling`): one row of the multiplier system.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CouplingRt {
    /// The leading joint.
    pub a: usize,
    /// The following joint.
    pub b: usize,
    /// `∂q_b/∂q_a`.
    pub ratio: f64,
    /// `q_b` at `q_a = 0`, rad or m.
    pub offset: f64,
    /// Index of its multiplier in the global multiplier vector (after every joint row).
    pub row: usize,
}

impl CouplingRt {
    /// The two joints with their weights in the row `q_b − r q_a − o`: the following joint
    /// (1), then the leading one (`−r`).
    pub(crate) fn weighted(&self) -> [(usize, f64); 2] {
        [(self.b, 1.0), (self.a, -self.ratio)]
    }
}

/// A joint as the step sees it.
#[derive(Clone, Debug)]
pub(crate) struct JointRt {
    /// Parent body (`None`: world).
    pub parent: Option<usize>,
    /// Child body.
    pub child: usize,
    /// Rows kept in the Newton solve.
    pub rows: Vec<DotRow>,
    /// `rows` compiled to their non-zero nodes (same order), for the Newton evaluation.
    pub sparse: Vec<SparseRow>,
    /// Rows dropped as redundant (still reported in the residual).
    pub dropped: Vec<DotRow>,
    /// Offset of this joint's first active row in the global multiplier vector.
    pub row0: usize,
    /// Coordinates that carry actuators, springs and dampers, in coordinate order.
    pub dofs: Vec<DofRt>,
    /// Parent joint-frame axes (world-frame linear vectors) of a spherical joint.
    pub sph_axes: Option<[LinVec; 3]>,
    /// Index in the input vector of the first actuator input, if actuated.
    pub input: Option<usize>,
    /// Offset of this joint's turn dofs in the unwrapping memory.
    pub turn0: usize,
    /// The joint's geometry (coordinates and rates for outputs and unwrapping).
    pub geom: JointGeom,
    /// Position stops on the coordinate (revolute and prismatic joints with limits).
    pub stops: Option<Stops>,
    /// Largest actuator input magnitude (+∞: none).
    pub effort: f64,
    /// Rotor inertia on each coordinate of `dofs`, kg·m² or kg (0: none).
    pub armature: f64,
    /// Offset of this joint's rotor rates in the state's `arm` (one per dof when `armature`
    /// is set).
    pub arm0: usize,
    /// Coulomb friction on each coordinate of `dofs`, if any.
    pub friction: Option<super::joint_friction::JointFriction>,
    /// Offset of this joint's friction bristles in the state's `fric` (one per dof).
    pub fric0: usize,
    /// The actuators driving its coordinate (revolute and prismatic tree joints), and the clamp
    /// of their sum.
    pub acts: super::joint_actuator::JointActuators,
}

/// A built, immutable multibody model.
#[derive(Clone, Debug)]
pub struct Model {
    pub(crate) def: ModelDef,
    pub(crate) settings: SolverSettings,
    pub(crate) inputs: Vec<InputSlot>,
    pub(crate) notes: Vec<String>,
    pub(crate) bodies: Vec<BodyRt>,
    pub(crate) joints: Vec<JointRt>,
    /// Bodies, parents before children.
    pub(crate) order: Vec<usize>,
    /// Tree parent of each body.
    pub(crate) parent: Vec<Option<usize>>,
    /// Tree joint of each body.
    pub(crate) tree_joint: Vec<Option<usize>>,
    /// Number of active joint rows.
    pub(crate) nrows: usize,
    /// Joint couplings; their rows are the last `couplings.len()` of the `nrows`.
    pub(crate) couplings: Vec<CouplingRt>,
    /// Number of turn dofs (unwrapping memory length).
    pub(crate) nturn: usize,
    /// Number of joint coordinates with a rotor inertia (the state's rotor rates).
    pub(crate) narm: usize,
    /// Number of joint coordinates with friction (the state's friction bristles).
    pub(crate) nfric: usize,
    /// Use the dense LU over all unknowns (O(N³)) instead of the tree solve (bordered for loops):
    /// the test oracle only, false as built (see [`Model::set_dense_solver`]).
    pub(crate) dense: bool,
    /// Solve trees by the reduced (joint-increment) iteration, `reduced`; true as built for
    /// models it covers (see [`Model::set_reduced_solver`]).
    pub(crate) reduced: bool,
    /// Whether the reduced Newton matrix is the exact Jacobian: no slide pair (prismatic,
    /// cylindrical, planar), whose geometric stiffness is approximate.
    pub(crate) exact_reduced: bool,
    /// Characteristic length for scaled norms, m.
    pub(crate) lc: f64,
    /// Initial coordinates (12 per body), world frame.
    pub(crate) q0: Vec<f64>,
    /// Initial velocities (12 per body), world frame.
    pub(crate) v0: Vec<f64>,
    /// Initial unwrapped turn angles, rad.
    pub(crate) angles0: Vec<f64>,
    /// (body, input index) of each body torque load.
    pub(crate) body_torques: Vec<(usize, usize)>,
    /// (body, input index) of each body force load.
    pub(crate) body_forces: Vec<(usize, usize)>,
    /// Test-only switch: naive torque representation `F_{d_i} = ½ m × d̄_i`.
    pub(crate) naive_torque: bool,
    /// Contact: ground points and body–body features.
    pub(crate) contact: super::contact::ContactRt,
}

/// Euler tensor of an inertia tensor: `E = ½ tr(J) I − J`.
#[must_use]
pub(crate) fn euler_tensor(j: &Mat3) -> Mat3 {
    Mat3::identity() * (0.5 * j.trace()) - j
}

impl Model {
    /// The definition this model was built from.
    #[must_use]
    pub fn def(&self) -> &ModelDef {
        &self.def
    }

    /// Solver settings.
    #[must_use]
    pub fn settings(&self) -> &SolverSettings {
        &self.settings
    }

    /// A message naming the first joint whose actuator input in `inputs` (the layout of
    /// [`Model::inputs`]) exceeds its effort limit, if any: the step applies it clamped.
    #[must_use]
    pub fn clamped_input(&self, inputs: &[f64]) -> Option<String> {
        self.joints.iter().zip(&self.def.joints).find_map(|(jt, jd)| {
            let first = jt.input?;
            let e = jt.effort;
            let x = inputs
                .get(first..first + jd.kind.dof())?
                .iter()
                .find(|x| x.abs() > e)?;
            Some(format!("joint '{}': actuator input {x} exceeds its effort limit and is applied clamped to ±{e} (reported once per run)", jd.name))
        })
    }

    /// The scalar inputs, in the order of `State::inputs`.
    #[must_use]
    pub fn inputs(&self) -> &[InputSlot] {
        &self.inputs
    }

    /// What set-up did that a user should know (redundant loop rows dropped, initial rates
    /// projected onto the loop velocity constraints).
    #[must_use]
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// Appends a set-up note.
    pub(crate) fn push_note(&mut self, note: String) {
        self.notes.push(note);
    }

    /// Number of bodies.
    #[must_use]
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Number of joint constraint rows kept in the Newton solve (after dropping redundant rows).
    #[must_use]
    pub fn active_rows(&self) -> usize {
        self.nrows
    }

    /// Whether the dense LU test oracle is used instead of the tree elimination (O(N); with
    /// loop-closing joints bordered, O(N·t + t³) for `t` border unknowns). False as built, for
    /// trees and loops alike; only [`Model::set_dense_solver`] sets it.
    #[must_use]
    pub fn uses_dense_solver(&self) -> bool {
        self.dense
    }

    /// Test-only: switches the Newton and projection solves to one dense LU over all unknowns
    /// (O(N³)), the oracle of the tree and bordered solves. Call before `State::new` (the
    /// workspaces are sized for the solver). Never use outside tests.
    #[doc(hidden)]
    pub fn set_dense_solver(&mut self, dense: bool) {
        self.dense = dense;
    }

    /// Whether steps solve the reduced equations in the joint rates (discrete null-space
    /// method, theory.md §4.5) before the multiplier form: true as built for models without
    /// loop-closing joints (trees).
    #[must_use]
    pub fn uses_reduced_solver(&self) -> bool {
        self.reduced && !self.dense
    }

    /// Test-only: `false` solves every stage in the multiplier form (body increments and joint
    /// multipliers), the oracle of the reduced iteration; `true` solves every tree in the
    /// reduced form (the default). Never use outside tests.
    #[doc(hidden)]
    pub fn set_reduced_solver(&mut self, on: bool) {
        self.reduced = on && covers(self);
    }

    /// Test-only: switches body torques to the naive director-force representation
    /// `F_{d_i} = ½ m × d̄_i`, which violates the discrete angular-momentum balance (theory.md
    /// §2.3). Never use outside tests.
    #[doc(hidden)]
    pub fn set_naive_torque(&mut self, naive: bool) {
        self.naive_torque = naive;
    }
}

impl Model {
    /// One empty tree block per body (`6 +` the rows of its tree joint), factored whole where
    /// `whole(b)` says so (`linalg::tree::Block::whole`).
    pub(crate) fn tree_blocks(&self, whole: impl Fn(usize) -> bool) -> Vec<Block> {
        (0..self.bodies.len())
            .map(|b| {
                let mut k =
                    Block::new(6 + self.tree_joint[b].map_or(0, |j| self.joints[j].rows.len()));
                k.whole = whole(b);
                k
            })
            .collect()
    }

    /// The border of the model's loop-closing joints (those that are not the tree joint of
    /// their child) and couplings (row groups after the joints') for the bordered tree solve;
    /// empty for a tree without couplings.
    pub(crate) fn border(&self) -> Border {
        let tree_rows: Vec<usize> = self
            .tree_joint
            .iter()
            .map(|tj| tj.map_or(0, |j| self.joints[j].rows.len()))
            .collect();
        let mut loops: Vec<_> = self
            .joints
            .iter()
            .enumerate()
            .map(|(j, jt)| {
                (self.tree_joint[jt.child] != Some(j)).then(|| {
                    (
                        jt.rows.len(),
                        jt.parent.into_iter().chain([jt.child]).collect(),
                    )
                })
            })
            .collect();
        // a coupling's row touches the bodies of both its joints
        for c in &self.couplings {
            let bodies = [c.a, c.b]
                .iter()
                .flat_map(|&j| {
                    self.joints[j]
                        .parent
                        .into_iter()
                        .chain([self.joints[j].child])
                })
                .collect();
            loops.push(Some((1, bodies)));
        }
        Border::new(&tree_rows, &loops)
    }
}

/// Whether the reduced iteration (`step::reduced`) covers `model`: a tree (no loop-closing
/// joint; couplings between its joints are bordered, `step::reduced::couple`) solved without
/// the dense oracle.
pub(crate) fn covers(model: &Model) -> bool {
    model
        .joints
        .iter()
        .enumerate()
        .all(|(j, jt)| model.tree_joint[jt.child] == Some(j) && jt.dropped.is_empty())
}

/// Whether the reduced Newton matrix of `model` is the exact Jacobian: no slide pair
/// (prismatic, cylindrical, planar), whose geometric stiffness is approximate (`step::reduced::eval`).
pub(crate) fn exact_jacobian(model: &Model) -> bool {
    model.joints.iter().all(|j| {
        !matches!(
            j.geom.kind,
            JointType::Prismatic | JointType::Cylindrical | JointType::Planar
        )
    })
}
