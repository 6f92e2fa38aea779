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

/// The allowed-states table: one entry per kind of call.
pub mod allowed {
    use super::{Mask, State};

    const I: Mask = State::Instantiated.bit();
    const N: Mask = State::Initialization.bit();
    const E: Mask = State::Event.bit();
    const S: Mask = State::Step.bit();
    const T: Mask = State::Terminated.bit();
    const F: Mask = State::Fatal.bit();

    /// `SetDebugLogging`: any state but Fatal.
    pub const SET_DEBUG_LOGGING: Mask = I.or(N).or(E).or(S).or(T);
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
    /// `Reset`.
    pub const RESET: Mask = I.or(N).or(E).or(S).or(T).or(F);
    /// Reading any variable.
    pub const GET: Mask = I.or(N).or(E).or(S).or(T);
    /// Writing parameters (causality parameter, variability fixed).
    pub const SET_PARAMETER: Mask = I.or(N);
    /// Writing inputs.
    pub const SET_INPUT: Mask = I.or(N).or(E).or(S);
    /// `GetFMUState`, `SerializedFMUStateSize`, `SerializeFMUState`.
    pub const GET_STATE: Mask = N.or(E).or(S).or(T);
    /// `SetFMUState` and deserialization into an instance.
    pub const SET_STATE: Mask = N.or(E).or(S).or(T);
    /// `FreeFMUState`, `DeserializeFMUState` (no effect on the instance).
    pub const STATE_MEMORY: Mask = I.or(N).or(E).or(S).or(T).or(F);
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
}
