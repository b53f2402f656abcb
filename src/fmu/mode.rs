//! The FMI 2.0 Co-Simulation state machine as data (FMI 2.0.4 §4.2.4; fmi.md §1.3): the
//! [`Mode`] of an instance, the functions whose legality depends on it ([`Op`]) and one
//! [`allowed`] table, checked at the top of every call.

/// The states of an FMI 2.0 Co-Simulation slave. `stepInProgress` never occurs: `fmi2DoStep`
/// is synchronous.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// After `fmi2Instantiate` or `fmi2Reset`.
    Instantiated,
    /// Between `fmi2EnterInitializationMode` and `fmi2ExitInitializationMode`.
    InitializationMode,
    /// `slaveInitialized`, ready for `fmi2DoStep`.
    StepComplete,
    /// After a failed step that was not rolled back (not produced by triad; restored states only).
    StepFailed,
    /// After `fmi2CancelStep` (never: steps are synchronous).
    StepCanceled,
    /// After `fmi2Terminate`.
    Terminated,
    /// After a failure: only reset, restoring an FMU state, getters and free are allowed.
    Error,
    /// After a panic: poisoned, only `fmi2FreeInstance` is allowed.
    Fatal,
}

impl Mode {
    /// Name used in messages.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Instantiated => "Instantiated mode",
            Self::InitializationMode => "Initialization Mode",
            Self::StepComplete => "stepComplete mode",
            Self::StepFailed => "stepFailed mode",
            Self::StepCanceled => "stepCanceled mode",
            Self::Terminated => "Terminated mode",
            Self::Error => "Error mode (reset the instance or set an FMU state)",
            Self::Fatal => "Fatal mode",
        }
    }

    /// Whether `fmi2GetFMUstate` records this mode (it refuses Error and Fatal, and the step
    /// modes never occur): the only modes a saved state may hold.
    #[must_use]
    pub fn recordable(self) -> bool {
        matches!(
            self,
            Self::Instantiated | Self::InitializationMode | Self::StepComplete | Self::Terminated
        )
    }

    pub(super) fn code(self) -> u8 {
        self as u8
    }

    pub(super) fn from_code(c: u8) -> Option<Mode> {
        use Mode as M;
        [
            M::Instantiated,
            M::InitializationMode,
            M::StepComplete,
            M::StepFailed,
            M::StepCanceled,
            M::Terminated,
            M::Error,
            M::Fatal,
        ]
        .get(usize::from(c))
        .copied()
    }
}

/// The functions whose legality depends on the mode (FMI 2.0.4 §4.2.4 table).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    /// `fmi2SetDebugLogging`.
    SetDebugLogging,
    /// `fmi2FreeInstance`.
    FreeInstance,
    /// `fmi2SetupExperiment`.
    SetupExperiment,
    /// `fmi2EnterInitializationMode`.
    EnterInitializationMode,
    /// `fmi2ExitInitializationMode`.
    ExitInitializationMode,
    /// `fmi2Terminate`.
    Terminate,
    /// `fmi2Reset`.
    Reset,
    /// `fmi2Get{Real,Integer,Boolean,String}`.
    Get,
    /// `fmi2Set{Real,Integer,Boolean,String}`.
    Set,
    /// `fmi2GetFMUstate`, `fmi2SetFMUstate`, `fmi2FreeFMUstate`, (de)serialisation.
    FmuState,
    /// `fmi2GetDirectionalDerivative`.
    GetDirectionalDerivative,
    /// `fmi2SetRealInputDerivatives`.
    SetRealInputDerivatives,
    /// `fmi2GetRealOutputDerivatives`.
    GetRealOutputDerivatives,
    /// `fmi2DoStep`.
    DoStep,
    /// `fmi2CancelStep`.
    CancelStep,
    /// `fmi2GetStatus` and `fmi2Get*Status`.
    GetStatus,
}

/// The state machine as one table: may `op` be called in `mode`? (FMI 2.0.4 §4.2.4; fmi.md §1.3).
#[must_use]
pub fn allowed(op: Op, mode: Mode) -> bool {
    use Mode as M;
    use Op as O;
    if mode == M::Fatal {
        return op == O::FreeInstance;
    }
    match op {
        O::SetDebugLogging | O::FreeInstance => true,
        O::SetupExperiment | O::EnterInitializationMode => mode == M::Instantiated,
        O::ExitInitializationMode => mode == M::InitializationMode,
        O::Terminate => matches!(mode, M::StepComplete | M::StepFailed),
        O::Reset | O::FmuState => true,
        O::Get | O::GetDirectionalDerivative => mode != M::Instantiated,
        O::Set | O::SetRealInputDerivatives => {
            matches!(
                mode,
                M::Instantiated | M::InitializationMode | M::StepComplete
            )
        }
        O::GetRealOutputDerivatives => !matches!(mode, M::Instantiated | M::InitializationMode),
        O::DoStep => mode == M::StepComplete,
        O::CancelStep => false,
        O::GetStatus => matches!(mode, M::StepComplete | M::StepFailed | M::Terminated),
    }
}
