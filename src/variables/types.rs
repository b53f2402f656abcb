//! The kinds of a variable (causality, variability, initial, base type), where its value
//! lives (`Accessor`), one `Variable` and the `VariableTable` with its look-ups.

/// FMI causality.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Causality {
    /// Fixed or tunable parameter.
    Parameter,
    /// Input, held constant over a communication step.
    Input,
    /// Output.
    Output,
}

/// FMI variability.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Variability {
    /// Fixed after initialisation.
    Fixed,
    /// Changeable between steps.
    Tunable,
    /// Changes continuously (Real only).
    Continuous,
}

/// FMI `initial` attribute (`None`: attribute absent, as for inputs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Initial {
    /// `initial="exact"`.
    Exact,
    /// `initial="calculated"`.
    Calculated,
    /// No attribute.
    None,
}

/// FMI base type of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum VarType {
    /// `fmi2Real`.
    Real,
    /// `fmi2Integer`.
    Integer,
}

/// Where a variable's value lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Accessor {
    /// `State::inputs()[i]`.
    Input(usize),
    /// Body frame origin component `i`.
    BodyR {
        /// Body index.
        body: usize,
        /// Row or component, 0-based.
        i: usize,
    },
    /// Rotation matrix element `[i, j]` (0-based).
    BodyRot {
        /// Body index.
        body: usize,
        /// Row or component, 0-based.
        i: usize,
        /// Column, 0-based.
        j: usize,
    },
    /// Body frame origin velocity component `i`.
    BodyV {
        /// Body index.
        body: usize,
        /// Row or component, 0-based.
        i: usize,
    },
    /// Body angular velocity component `i`.
    BodyW {
        /// Body index.
        body: usize,
        /// Row or component, 0-based.
        i: usize,
    },
    /// Site frame origin component `i`.
    SiteR {
        /// Site index.
        site: usize,
        /// Component, 0-based.
        i: usize,
    },
    /// Site rotation matrix element `[i, j]` (0-based).
    SiteRot {
        /// Site index.
        site: usize,
        /// Row, 0-based.
        i: usize,
        /// Column, 0-based.
        j: usize,
    },
    /// Site frame origin velocity component `i`.
    SiteV {
        /// Site index.
        site: usize,
        /// Component, 0-based.
        i: usize,
    },
    /// Site angular velocity component `i`.
    SiteW {
        /// Site index.
        site: usize,
        /// Component, 0-based.
        i: usize,
    },
    /// Joint coordinate `k` (spherical: quaternion component).
    JointQ {
        /// Joint index.
        joint: usize,
        /// Coordinate, 0-based.
        k: usize,
    },
    /// Joint rate `k` (spherical: relative angular velocity in the child frame).
    JointQd {
        /// Joint index.
        joint: usize,
        /// Coordinate, 0-based.
        k: usize,
    },
    /// Joint acceleration `k` (the derivative of `JointQd`), computed from the state and the
    /// inputs when read (trees without contact).
    JointQdd {
        /// Joint index.
        joint: usize,
        /// Coordinate, 0-based.
        k: usize,
    },
    /// `system.energy`.
    Energy,
    /// `system.work`.
    Work,
    /// `system.p[i]`.
    P(usize),
    /// `system.L[i]`.
    L(usize),
    /// `system.constraint_residual`.
    ConstraintResidual,
    /// `contact.C.f[i]`: contact force on shape C's body through C, world frame.
    ContactForce {
        /// Shape index.
        shape: usize,
        /// Component, 0-based.
        i: usize,
    },
    /// `contact.C.gap`: shape C's signed distance to the ground.
    ContactGap(usize),
    /// `ground.height` (fixed).
    GroundHeight,
    /// `ground.friction` (fixed).
    GroundFriction,
    /// `ground.stiffness` (fixed).
    GroundStiffness,
    /// `ground.damping` (fixed).
    GroundDamping,
    /// `gravity[i]`.
    Gravity(usize),
    /// `body.B.mass`.
    Mass(usize),
    /// `body.B.inertia[i,j]`.
    Inertia {
        /// Body index.
        body: usize,
        /// Row or component, 0-based.
        i: usize,
        /// Column, 0-based.
        j: usize,
    },
    /// `joint.J.q0[k]` (or `q0`).
    Q0 {
        /// Joint index.
        joint: usize,
        /// Coordinate, 0-based.
        k: usize,
    },
    /// `joint.J.qd0[k]` (or `qd0`).
    Qd0 {
        /// Joint index.
        joint: usize,
        /// Coordinate, 0-based.
        k: usize,
    },
    /// `joint.J.damping` (tunable).
    Damping(usize),
    /// `joint.J.stiffness` (tunable).
    Stiffness(usize),
    /// `joint.J.lower` (fixed).
    Lower(usize),
    /// `joint.J.upper` (fixed).
    Upper(usize),
    /// `joint.J.effort` (fixed).
    Effort(usize),
    /// `joint.J.stop_stiffness` (fixed).
    StopStiffness(usize),
    /// `joint.J.stop_damping` (fixed).
    StopDamping(usize),
    /// `joint.J.armature` (fixed).
    Armature(usize),
    /// `joint.J.friction` (fixed).
    Friction(usize),
    /// `joint.J.actuatorfrcrange[k]` (fixed; `k` 0 for the lower end, 1 for the upper).
    ActuatorForce(usize, usize),
    /// `actuator.A.gear` (fixed; index in `ModelDef::actuators`).
    ActuatorGear(usize),
    /// `actuator.A.kp` of a position servo (tunable).
    ActuatorKp(usize),
    /// `actuator.A.kv` of a position or velocity servo (tunable).
    ActuatorKv(usize),
    /// `solver.max_step`.
    MaxStep,
    /// `solver.tolerance`.
    Tolerance,
    /// `solver.order` (Integer).
    Order,
    /// `solver.max_substeps` (Integer).
    MaxSubsteps,
    /// `solver.stages` (Integer).
    Stages,
    /// `solver.rtol`.
    Rtol,
    /// `solver.atol`.
    Atol,
    /// `solver.min_step`.
    MinStep,
}

/// One variable.
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    /// Value reference, unique over the table.
    pub vr: u32,
    /// Structured name (interface.md §3), e.g. `body.link1.R[1,2]`.
    pub name: String,
    /// Base type.
    pub ty: VarType,
    /// Causality.
    pub causality: Causality,
    /// Variability.
    pub variability: Variability,
    /// Initial attribute.
    pub initial: Initial,
    /// Start value (inputs: 0; parameters: their value; calculated outputs: none).
    pub start: Option<f64>,
    /// Unit name declared in `<UnitDefinitions>` (`None` for dimensionless integers).
    pub unit: Option<&'static str>,
    /// Display unit (`deg` for angles), declared under its unit.
    pub display_unit: Option<&'static str>,
    /// What it is, with frame.
    pub description: String,
    /// Where the value lives.
    pub accessor: Accessor,
}

/// The list of all variables, in ModelVariables order (index = position + 1).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VariableTable {
    /// Variables in ModelVariables order.
    pub vars: Vec<Variable>,
    /// A model with closed loops or couplings whose linear model the FMU provides: its states
    /// (decided when the table is built); `None` for a tree (or without a linear model).
    pub loops: Option<LoopStates>,
}

/// The states of a model with closed loops or couplings: the independent coordinates that
/// `triad linearize` picks by default (`mechanics::Independent::Auto`) at the model's initial
/// state; the other tree joints follow them around the loops and couplings.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LoopStates {
    /// The independent coordinates `(joint, k)` (joint index, coordinate of the joint), in
    /// the tree's coordinate order: their `joint.J.q`, `joint.J.qd` are the states.
    pub independent: Vec<(usize, usize)>,
    /// The loop-closing joints: their `joint.J.q`, `joint.J.qd` are no coordinates of the
    /// tree, and are not differentiated.
    pub closing: Vec<usize>,
}

impl Causality {
    /// The attribute value in modelDescription.xml (`parameter`, `input`, `output`).
    #[must_use]
    pub fn fmi_name(self) -> &'static str {
        match self {
            Self::Parameter => "parameter",
            Self::Input => "input",
            Self::Output => "output",
        }
    }
}

impl Variability {
    /// The attribute value in modelDescription.xml (`fixed`, `tunable`, `continuous`).
    #[must_use]
    pub fn fmi_name(self) -> &'static str {
        match self {
            Self::Fixed => "fixed",
            Self::Tunable => "tunable",
            Self::Continuous => "continuous",
        }
    }
}

impl VariableTable {
    /// The variable with value reference `vr`.
    #[must_use]
    pub fn by_vr(&self, vr: u32) -> Option<&Variable> {
        self.vars
            .get(usize::try_from(vr).ok()?)
            .filter(|v| v.vr == vr)
    }

    /// The variable called `name` (exact structured name).
    #[must_use]
    pub fn by_name(&self, name: &str) -> Option<&Variable> {
        self.vars.iter().find(|v| v.name == name)
    }

    /// Variables of one causality, in table order.
    pub fn with_causality(&self, causality: Causality) -> impl Iterator<Item = &Variable> {
        self.vars.iter().filter(move |v| v.causality == causality)
    }
}
