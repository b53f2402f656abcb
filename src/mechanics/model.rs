//! The immutable model: bodies, joint rows, loads, tree order, initial state.
//!
//! PLACEHOLDER written at project set-up: the public items (names and signatures) are the
//! contract used by `sim`, `variables` and `fmu`; the mechanics work replaces the bodies.

use super::def::{ModelDef, SolverSettings};
use super::error::ModelError;

/// One scalar input of the model, in the order of `State::inputs`.
///
/// Order: for each joint in model order its actuator inputs (revolute `[tau]`, prismatic
/// `[f]`, cylindrical `[f, tau]`, universal `[tau1, tau2]`, spherical `[tau1, tau2, tau3]` in
/// the parent joint frame), then for each body load its torque `[x, y, z]` then force `[x, y, z]`
/// (world frame).
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
}

/// A built, immutable multibody model.
#[derive(Clone, Debug)]
pub struct Model {
    def: ModelDef,
    settings: SolverSettings,
    inputs: Vec<InputSlot>,
    notes: Vec<String>,
}

impl Model {
    /// Builds the model: validates, orders the spanning tree, assembles constraint rows, drops
    /// redundant loop rows (reported in [`Model::notes`]) and computes the initial state.
    ///
    /// # Errors
    /// [`ModelError`] for an inconsistent definition or a loop not closed at the start.
    pub fn new(def: &ModelDef, settings: SolverSettings) -> Result<Self, ModelError> {
        let mut inputs = Vec::new();
        for (j, joint) in def.joints.iter().enumerate() {
            if !joint.actuated {
                continue;
            }
            use super::def::JointType as T;
            match joint.kind {
                T::Revolute => inputs.push(InputSlot::JointTorque { joint: j, k: 0 }),
                T::Prismatic => inputs.push(InputSlot::JointForce { joint: j }),
                T::Cylindrical => {
                    inputs.push(InputSlot::JointForce { joint: j });
                    inputs.push(InputSlot::JointTorque { joint: j, k: 0 });
                }
                T::Universal => {
                    (0..2).for_each(|k| inputs.push(InputSlot::JointTorque { joint: j, k }))
                }
                T::Spherical => {
                    (0..3).for_each(|k| inputs.push(InputSlot::JointTorque { joint: j, k }))
                }
                T::Planar | T::Fixed => {}
            }
        }
        for load in &def.loads {
            if load.torque {
                (0..3).for_each(|i| inputs.push(InputSlot::BodyTorque { body: load.body, i }));
            }
            if load.force {
                (0..3).for_each(|i| inputs.push(InputSlot::BodyForce { body: load.body, i }));
            }
        }
        Ok(Self {
            def: def.clone(),
            settings,
            inputs,
            notes: Vec::new(),
        })
    }

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
}
