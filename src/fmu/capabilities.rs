//! The `<CoSimulation>` capability flags: one const read by the XML writer and by the FFI, so the
//! description and the behaviour cannot drift apart (style.md §3 rule 3).

/// Capability flags of FMI 2.0.4 §4.3.1 (`<CoSimulation>` attributes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capabilities {
    /// `needsExecutionTool`.
    pub needs_execution_tool: bool,
    /// `canHandleVariableCommunicationStepSize`: every `fmi2DoStep` may use a different H.
    pub can_handle_variable_communication_step_size: bool,
    /// `canInterpolateInputs`: `fmi2SetRealInputDerivatives` has an effect.
    pub can_interpolate_inputs: bool,
    /// `maxOutputDerivativeOrder`: `fmi2GetRealOutputDerivatives` up to this order.
    pub max_output_derivative_order: u32,
    /// `canRunAsynchronuously` (sic, the standard's spelling).
    pub can_run_asynchronuously: bool,
    /// `canBeInstantiatedOnlyOncePerProcess`.
    pub can_be_instantiated_only_once_per_process: bool,
    /// `canNotUseMemoryManagementFunctions`: the Rust allocator is used, never the callbacks.
    pub can_not_use_memory_management_functions: bool,
    /// `canGetAndSetFMUstate`.
    pub can_get_and_set_fmu_state: bool,
    /// `canSerializeFMUstate`.
    pub can_serialize_fmu_state: bool,
    /// `providesDirectionalDerivative`.
    pub provides_directional_derivative: bool,
}

/// What this FMU can do. `fmi2SetRealInputDerivatives` and `fmi2GetRealOutputDerivatives` are
/// exported (all 34 functions must be) but return `fmi2Error` because the matching flags are
/// false; `providesDirectionalDerivative` is per model ([`Capabilities::with_directional`]).
pub const CAPABILITIES: Capabilities = Capabilities {
    needs_execution_tool: false,
    can_handle_variable_communication_step_size: true,
    can_interpolate_inputs: false,
    max_output_derivative_order: 0,
    can_run_asynchronuously: false,
    can_be_instantiated_only_once_per_process: false,
    can_not_use_memory_management_functions: true,
    can_get_and_set_fmu_state: true,
    can_serialize_fmu_state: true,
    provides_directional_derivative: false,
};

impl Capabilities {
    /// These flags with `providesDirectionalDerivative` as given (true for models that declare
    /// states: `variables::linear::states`).
    #[must_use]
    pub const fn with_directional(mut self, provides: bool) -> Self {
        self.provides_directional_derivative = provides;
        self
    }

    /// The `<CoSimulation>` attributes (name, value) in a fixed order (after
    /// `modelIdentifier`), as written to modelDescription.xml.
    #[must_use]
    pub fn attributes(&self) -> Vec<(&'static str, String)> {
        let b = |v: bool| v.to_string();
        vec![
            ("needsExecutionTool", b(self.needs_execution_tool)),
            (
                "canHandleVariableCommunicationStepSize",
                b(self.can_handle_variable_communication_step_size),
            ),
            ("canInterpolateInputs", b(self.can_interpolate_inputs)),
            (
                "maxOutputDerivativeOrder",
                self.max_output_derivative_order.to_string(),
            ),
            ("canRunAsynchronuously", b(self.can_run_asynchronuously)),
            (
                "canBeInstantiatedOnlyOncePerProcess",
                b(self.can_be_instantiated_only_once_per_process),
            ),
            (
                "canNotUseMemoryManagementFunctions",
                b(self.can_not_use_memory_management_functions),
            ),
            ("canGetAndSetFMUstate", b(self.can_get_and_set_fmu_state)),
            ("canSerializeFMUstate", b(self.can_serialize_fmu_state)),
            (
                "providesDirectionalDerivative",
                b(self.provides_directional_derivative),
            ),
        ]
    }
}
