//! Which FMI version an instance was made through, and the names its messages use: one
//! [`Instance`](super::Instance) serves `fmi2Instantiate` and `fmi3InstantiateCoSimulation`,
//! and a refused call names the function the importer called.

/// The FMI version of an instance's C interface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Api {
    /// FMI 2.0 Co-Simulation (`fmi2Instantiate`).
    Fmi2,
    /// FMI 3.0 Co-Simulation (`fmi3InstantiateCoSimulation`).
    Fmi3 {
        /// `earlyReturnAllowed` of `fmi3InstantiateCoSimulation`: `fmi3DoStep` returns early
        /// at stop and contact events.
        early_return_allowed: bool,
    },
}

impl Api {
    /// The instantiation function.
    #[must_use]
    pub fn instantiate(self) -> &'static str {
        match self {
            Self::Fmi2 => "fmi2Instantiate",
            Self::Fmi3 { .. } => "fmi3InstantiateCoSimulation",
        }
    }

    /// What the model-description identity is called (`guid` / `instantiationToken`).
    #[must_use]
    pub fn token(self) -> &'static str {
        match self {
            Self::Fmi2 => "GUID",
            Self::Fmi3 { .. } => "instantiationToken",
        }
    }

    /// The name of the function the importer called for the core operation that FMI 2 names
    /// `fmi2_name` (FMI 3 folds `fmi2SetupExperiment` into `fmi3EnterInitializationMode`).
    #[must_use]
    pub fn name(self, fmi2_name: &'static str) -> &'static str {
        if self == Self::Fmi2 {
            return fmi2_name;
        }
        match fmi2_name {
            "fmi2SetDebugLogging" => "fmi3SetDebugLogging",
            "fmi2SetupExperiment" | "fmi2EnterInitializationMode" => "fmi3EnterInitializationMode",
            "fmi2ExitInitializationMode" => "fmi3ExitInitializationMode",
            "fmi2Terminate" => "fmi3Terminate",
            "fmi2Reset" => "fmi3Reset",
            "fmi2DoStep" => "fmi3DoStep",
            "fmi2GetFMUstate" => "fmi3GetFMUState",
            "fmi2SetFMUstate" => "fmi3SetFMUState",
            "fmi2FreeFMUstate" => "fmi3FreeFMUState",
            "fmi2SerializedFMUstateSize" => "fmi3SerializedFMUStateSize",
            "fmi2SerializeFMUstate" => "fmi3SerializeFMUState",
            "fmi2DeSerializeFMUstate" => "fmi3DeserializeFMUState",
            "fmi2FreeInstance" => "fmi3FreeInstance",
            other => other,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Api;

    #[test]
    fn fmi3_instances_name_fmi3_functions() {
        let a = Api::Fmi3 {
            early_return_allowed: false,
        };
        assert_eq!(a.name("fmi2DoStep"), "fmi3DoStep");
        assert_eq!(a.name("fmi2SetupExperiment"), "fmi3EnterInitializationMode");
        assert_eq!(a.name("fmi3GetFloat64"), "fmi3GetFloat64");
        assert_eq!(Api::Fmi2.name("fmi2DoStep"), "fmi2DoStep");
    }
}
