//! The status codes of FMI 2.0 and 3.0 (the same numbers in both) and the FMI state machine:
//! an explicit state enum and, per function, the set of states in which it may be called.

/// `fmi2Status` / `fmi3Status`: a C `int` with the same values in both standards.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    /// All well.
    Ok = 0,
    /// Something to look at; the results can be used.
    Warning = 1,
    /// The call could not complete (FMI 2: a step was not taken); the host may go on.
    Discard = 2,
    /// The call failed; the instance may only be reset or freed (FMI says), but it stays safe.
    Error = 3,
    /// The instance is unusable (a caught panic).
    Fatal = 4,
}

impl Status {
    /// The category the standard's logging uses for this status.
    pub fn category(self) -> &'static str {
        match self {
            Status::Ok => "logEvents",
            Status::Warning => "logStatusWarning",
            Status::Discard => "logStatusDiscard",
            Status::Error => "logStatusError",
            Status::Fatal => "logStatusFatal",
        }
    }
}

/// Where an instance is in the FMI co-simulation state machine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum State {
    /// After instantiation: parameters and start values may be set.
    Instantiated,
    /// Between enter and exit of initialization mode.
    Initialization,
    /// FMI 3 event mode (only with `eventModeUsed`); nothing happens in it here.
    Event,
    /// Stepping (FMI 2 "slaveInitialized", FMI 3 "Step Mode").
    Step,
    /// After `Terminate`: outputs can still be read.
    Terminated,
    /// After `DoStep`, `Terminate` or `ExitInitializationMode` returned `Error`: only the getters,
    /// get/set/free FMU state, (de)serialization, `Reset` and `FreeInstance` are allowed; a
    /// successful `SetFMUState` returns to the state the failed call was made in.
    Error,
    /// After a caught panic: only `FreeInstance` (and `Reset`) are allowed.
    Fatal,
}

impl State {
    /// The state's bit in a [`Mask`].
    pub const fn bit(self) -> Mask {
        Mask(1 << self as u8)
    }

    /// The name used in messages.
    pub fn name(self) -> &'static str {
        match self {
            State::Instantiated => "Instantiated",
            State::Initialization => "Initialization Mode",
            State::Event => "Event Mode",
            State::Step => "Step Mode",
            State::Terminated => "Terminated",
            State::Error => "Error (after a failed call)",
            State::Fatal => "Fatal (after an internal error)",
        }
    }
}

/// A set of [`State`]s: where a function may be called.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mask(u8);

impl Mask {
    /// Whether `state` is in the set.
    pub const fn contains(self, state: State) -> bool {
        self.0 & state.bit().0 != 0
    }

    /// The union of two sets.
    pub const fn or(self, other: Mask) -> Mask {
        Mask(self.0 | other.0)
    }

    /// The empty set (for functions that are never allowed, i.e. not supported).
    pub const NONE: Mask = Mask(0);
}

/// The allowed-states table: one entry per function (or per family of functions with the same
/// rule), after the FMI 2.0 and 3.0 state machines and the Reference FMUs' `MASK_fmi*` tables.
pub mod allowed {
    use super::{Mask, State};

    const I: Mask = State::Instantiated.bit();
    const N: Mask = State::Initialization.bit();
    const E: Mask = State::Event.bit();
    const S: Mask = State::Step.bit();
    const T: Mask = State::Terminated.bit();
    const X: Mask = State::Error.bit();
    const F: Mask = State::Fatal.bit();
    /// Every state after instantiation but Fatal.
    const LIVE: Mask = I.or(N).or(E).or(S).or(T).or(X);

    /// `SetDebugLogging`: any state but Fatal.
    pub const SET_DEBUG_LOGGING: Mask = LIVE;
    /// `SetupExperiment` (FMI 2).
    pub const SETUP_EXPERIMENT: Mask = I;
    /// `EnterInitializationMode`.
    pub const ENTER_INITIALIZATION: Mask = I;
    /// `ExitInitializationMode`.
    pub const EXIT_INITIALIZATION: Mask = N;
    /// `EnterEventMode` (FMI 3, with event mode used).
    pub const ENTER_EVENT_MODE: Mask = S;
    /// `UpdateDiscreteStates` / `EvaluateDiscreteStates` (FMI 3).
    pub const UPDATE_DISCRETE_STATES: Mask = E;
    /// `EnterStepMode` (FMI 3).
    pub const ENTER_STEP_MODE: Mask = E;
    /// `DoStep`.
    pub const DO_STEP: Mask = S;
    /// `Terminate`.
    pub const TERMINATE: Mask = E.or(S);
    /// `Reset`: any state, Fatal included.
    pub const RESET: Mask = LIVE.or(F);
    /// `fmi2GetReal`, `fmi2GetInteger`, `fmi2GetBoolean`, `fmi2GetString`: from initialization mode
    /// on (FMI 2.0 does not allow them in Instantiated), in Error too.
    pub const FMI2_GET: Mask = N.or(E).or(S).or(T).or(X);
    /// Every `fmi3Get{VariableType}`: FMI 3.0 also allows them in Instantiated (parameters only
    /// there: outputs and calculated parameters exist after initialization).
    pub const FMI3_GET: Mask = I.or(FMI2_GET);
    /// `SetReal` / `SetFloat64`: parameters before `ExitInitializationMode`, the two inputs also
    /// in event and step mode (the per-variable rule is [`SET_PARAMETER`] / [`SET_INPUT`]).
    pub const SET_REAL: Mask = I.or(N).or(E).or(S);
    /// `SetInteger` / `SetInt32`: every Integer variable is a parameter.
    pub const SET_INTEGER: Mask = I.or(N);
    /// `SetBoolean`: there is no settable Boolean; the call is allowed where inputs are set, and
    /// each value reference is refused by name.
    pub const SET_BOOLEAN: Mask = I.or(N).or(E).or(S);
    /// `SetString`: `log.path` is a parameter.
    pub const SET_STRING: Mask = I.or(N);
    /// FMI 3 setters of types this FMU has no variables of (Float32, Int8, ..., Binary, Clock).
    pub const SET_ABSENT: Mask = I.or(N).or(E).or(S);
    /// Where one parameter (causality parameter, variability fixed) may be written.
    pub const SET_PARAMETER: Mask = I.or(N);
    /// Where one input may be written.
    pub const SET_INPUT: Mask = I.or(N).or(E).or(S);
    /// `GetFMUState`: every state after instantiation (FMI 2 `MASK_fmi2GetFMUstate` =
    /// `MASK_fmi2FreeInstance`, FMI 3 any state), not after a panic.
    pub const GET_STATE: Mask = LIVE;
    /// `SetFMUState`: as [`GET_STATE`]; in Error it is the way back.
    pub const SET_STATE: Mask = LIVE;
    /// `FreeFMUState`, `SerializedFMUStateSize`, `SerializeFMUState`, `DeserializeFMUState`: they
    /// touch the snapshot only, never the instance, so Fatal too.
    pub const STATE_MEMORY: Mask = LIVE.or(F);
    /// The status queries of FMI 2.
    pub const STATUS: Mask = S.or(T);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn do_step_is_allowed_only_in_step_mode() {
        for state in [State::Instantiated, State::Initialization, State::Event, State::Terminated, State::Fatal] {
            assert!(!allowed::DO_STEP.contains(state), "{state:?}");
        }
        assert!(allowed::DO_STEP.contains(State::Step));
        assert!(!Mask::NONE.contains(State::Step));
    }

    #[test]
    fn fmi2_getters_start_at_initialization_mode_fmi3_getters_at_instantiated() {
        assert!(!allowed::FMI2_GET.contains(State::Instantiated));
        assert!(allowed::FMI3_GET.contains(State::Instantiated));
        for state in [State::Initialization, State::Event, State::Step, State::Terminated, State::Error] {
            assert!(allowed::FMI2_GET.contains(state) && allowed::FMI3_GET.contains(state), "{state:?}");
        }
    }

    #[test]
    fn error_state_allows_only_getters_fmu_state_reset_and_debug_logging() {
        let allowed_in_error = [
            allowed::FMI2_GET,
            allowed::FMI3_GET,
            allowed::GET_STATE,
            allowed::SET_STATE,
            allowed::STATE_MEMORY,
            allowed::RESET,
            allowed::SET_DEBUG_LOGGING,
        ];
        for mask in allowed_in_error {
            assert!(mask.contains(State::Error));
        }
        let refused_in_error = [
            allowed::SETUP_EXPERIMENT,
            allowed::ENTER_INITIALIZATION,
            allowed::EXIT_INITIALIZATION,
            allowed::ENTER_EVENT_MODE,
            allowed::UPDATE_DISCRETE_STATES,
            allowed::ENTER_STEP_MODE,
            allowed::DO_STEP,
            allowed::TERMINATE,
            allowed::SET_REAL,
            allowed::SET_INTEGER,
            allowed::SET_BOOLEAN,
            allowed::SET_STRING,
            allowed::SET_ABSENT,
            allowed::STATUS,
        ];
        for mask in refused_in_error {
            assert!(!mask.contains(State::Error), "{mask:?}");
        }
    }

    #[test]
    fn fmu_state_functions_are_allowed_in_every_state_after_instantiation() {
        for state in
            [State::Instantiated, State::Initialization, State::Event, State::Step, State::Terminated, State::Error]
        {
            for mask in [allowed::GET_STATE, allowed::SET_STATE, allowed::STATE_MEMORY] {
                assert!(mask.contains(state), "{state:?}");
            }
        }
    }

    #[test]
    fn parameters_only_before_exit_initialization_inputs_in_step_mode() {
        assert!(allowed::SET_PARAMETER.contains(State::Initialization));
        assert!(!allowed::SET_PARAMETER.contains(State::Step));
        assert!(allowed::SET_INPUT.contains(State::Step));
        assert!(!allowed::SET_INPUT.contains(State::Terminated));
    }
}
