//! The one error type of the crate. Every variant carries the offending name and value, so a
//! message can be shown to a CLI user or an FMI logger as it is.

use thiserror::Error;

/// Result alias used across the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong, from a scenario field to a log file.
#[derive(Debug, Error)]
pub enum Error {
    /// A scenario parameter breaks its rule, e.g. `upper.length must be > 0 m, got -3`.
    #[error("{name} must be {rule}, got {value}")]
    InvalidParameter {
        /// Dotted parameter name as in the scenario file and the FMU (`upper.length`;
        /// `lower.sections[2].second_moment` for a section's field).
        name: std::borrow::Cow<'static, str>,
        /// The rule, with the unit (`> 0 m`).
        rule: String,
        /// The offending value, as given.
        value: String,
    },
    /// Several invalid parameters, each with its own message, reported at once.
    #[error("{}", .0.iter().map(ToString::to_string).collect::<Vec<_>>().join("; "))]
    Invalid(Vec<Error>),
    /// A time step above the stability limit of the linear acceleration method.
    #[error(
        "{name} = {step:e} s is above the stability limit of the linear acceleration method: \
         dt * omega_max = {product:.3} > sqrt(12) = 3.464 (omega_max = {omega_max:.1} rad/s {stage}); \
         use {name} <= {limit:e} s, or {name} = \"auto\" (0 in the FMU) for the largest energy-safe step, \
         {auto:e} s"
    )]
    UnstableStep {
        /// `step_free` or `step_contact`.
        name: &'static str,
        /// The requested step, s.
        step: f64,
        /// Highest natural frequency of the stage, rad/s.
        omega_max: f64,
        /// `step * omega_max`.
        product: f64,
        /// Largest stable step, s.
        limit: f64,
        /// Which stage ("out of contact", "in contact").
        stage: &'static str,
        /// The step `"auto"` would give, s.
        auto: f64,
    },
    /// A parameter name that the scenario does not have.
    #[error("unknown parameter `{0}`")]
    UnknownParameter(String),
    /// The scenario file could not be read or parsed.
    #[error("scenario {path}: {message}")]
    Scenario {
        /// File path.
        path: String,
        /// What went wrong, from the TOML parser.
        message: String,
    },
    /// A numerical breakdown (a factorization failed): the model is not well posed.
    #[error("numerical failure in {what}: {detail}")]
    Numerical {
        /// The routine that failed.
        what: &'static str,
        /// Why.
        detail: String,
    },
    /// Writing or reading a log, a figure or a result file.
    #[error("{action} {path}: {source}")]
    Io {
        /// What was being done ("cannot create").
        action: &'static str,
        /// The file.
        path: String,
        /// The operating system's reason.
        #[source]
        source: std::io::Error,
    },
    /// The MCAP writer or reader failed.
    #[error("MCAP {path}: {message}")]
    Mcap {
        /// The file.
        path: String,
        /// The mcap crate's message.
        message: String,
    },
    /// A saved run state that does not fit this model.
    #[error("FMU state: the state has {found} coordinates, this model has {expected}")]
    StateCoordinates {
        /// Coordinates in the saved state.
        found: usize,
        /// Coordinates of this model (its DOFs).
        expected: usize,
    },
    /// Bytes that do not start with the serialized FMU state's magic.
    #[error("FMU state: not a serialized beam-impact FMU state ({length} bytes, magic missing)")]
    StateMagic {
        /// How many bytes were given.
        length: usize,
    },
    /// A serialized FMU state of another format version.
    #[error("FMU state: format version {found}, this binary reads version {expected}")]
    StateVersion {
        /// The version in the bytes.
        found: u32,
        /// The version this binary writes and reads.
        expected: u32,
    },
    /// A serialized FMU state whose payload length is not the one its header declares.
    #[error("FMU state: the payload should be {declared} bytes, {given} were given")]
    StateLength {
        /// Payload length in the header.
        declared: u64,
        /// Bytes after the header.
        given: u64,
    },
    /// A serialized FMU state whose checksum does not match its bytes (damaged in storage or transit).
    #[error(
        "FMU state: checksum mismatch (CRC-32 {saved:08x} stored, {computed:08x} computed): the bytes are damaged"
    )]
    StateChecksum {
        /// The CRC-32 in the header.
        saved: u32,
        /// The CRC-32 of the header and payload as given.
        computed: u32,
    },
    /// A restored FMU state whose contents are impossible (a forged or corrupted state): the field
    /// and why.
    #[error("FMU state: {field} {detail}")]
    StateInvalid {
        /// The field's path in the state (`gap`, `result.step`, `contact_windows[3]`).
        field: String,
        /// What is wrong with it, with the value.
        detail: String,
    },
    /// A serialized FMU state whose payload cannot be read back into a run state.
    #[error("FMU state: corrupt payload: {detail}")]
    StatePayload {
        /// The parser's message.
        detail: String,
    },
    /// More rigid-body modes expected from the supports than the eigen problem has DOFs.
    #[error("{what}: {expected} rigid-body modes expected from the supports, but the problem has {dofs} DOFs")]
    RigidModeCount {
        /// The eigen problem ("natural modes", "coupled modes").
        what: &'static str,
        /// Rigid-body modes the supports give.
        expected: usize,
        /// Size of the eigen problem.
        dofs: usize,
    },
    /// Eigenvalues that contradict the rigid-body mode count of the supports: the lowest elastic
    /// eigenvalue omega^2 is not positive, or not above every eigenvalue taken as rigid.
    #[error(
        "{what}: {expected} rigid-body modes expected from the supports, but the lowest elastic eigenvalue \
         omega^2 = {lowest_elastic:e} 1/s^2 is not positive and above the largest taken as rigid, \
         |omega^2| = {largest_rigid:e} 1/s^2"
    )]
    RigidModeMismatch {
        /// The eigen problem ("natural modes", "coupled modes").
        what: &'static str,
        /// Rigid-body modes the supports give.
        expected: usize,
        /// Eigenvalue number `expected` (0-based) in ascending order, 1/s^2.
        lowest_elastic: f64,
        /// Largest magnitude among the eigenvalues set to 0, 1/s^2 (0 if none).
        largest_rigid: f64,
    },
    /// The run was stopped between two steps because its caller asked (Ctrl-C in the Python
    /// package: [`crate::record::cancel`]).
    #[error("run cancelled at t = {time} s (internal step {step}), as asked")]
    Cancelled {
        /// Simulated time of the last step taken, s.
        time: f64,
        /// That step's number.
        step: u64,
    },
    /// The run took as many internal steps as it may (`--max-steps`, the answer's limit, the FMU's
    /// `solver.max_steps`) before its end: checked at every step, so a run whose steps shrink far
    /// below the plan's stops. The message says which happened (see [`step_limit_cause`]).
    #[error(
        "max_steps = {limit} internal steps reached at t = {time} s of {duration} s (the plan's estimate for the \
         whole run {estimate} steps of {planned:e} s; the last step {last_step:e} s): {}; raise the limit (--max-steps, \
         max_steps=, solver.max_steps)",
        step_limit_cause(*limit, *estimate, *last_step, *planned)
    )]
    StepLimit {
        /// The limit.
        limit: u64,
        /// The plan's estimate of the whole run's steps (its duration over the smaller step).
        estimate: u64,
        /// Simulated time reached, s.
        time: f64,
        /// The run's duration, s.
        duration: f64,
        /// The last step's size, s.
        last_step: f64,
        /// The plan's smaller step, s.
        planned: f64,
    },
    /// Anything else, with its explanation.
    #[error("{0}")]
    Other(String),
}

/// Why a run met its step limit, from the numbers: the plan itself needs more steps than the
/// limit; the steps shrank far (10x) below the plan's (a very stiff contact chattering, a motion
/// that changes every instant); or the run took more than the plan's estimate (located contact
/// changes and output times add steps to it).
pub fn step_limit_cause(limit: u64, estimate: u64, last_step: f64, planned: f64) -> &'static str {
    if estimate > limit {
        "the plan's own estimate is above the limit"
    } else if last_step < 0.1 * planned {
        "the run's steps shrank far below the plan's (a very stiff contact chattering, a motion that changes every \
         instant)"
    } else {
        "the run took more steps than the plan's estimate (located contact changes and output times add steps)"
    }
}

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub fn invalid(
        name: impl Into<std::borrow::Cow<'static, str>>,
        rule: impl Into<String>,
        value: impl std::fmt::Display,
    ) -> Self {
        Error::InvalidParameter { name: name.into(), rule: rule.into(), value: value.to_string() }
    }
}

/// A number for a message, bounded in length (`{}` of 1e-300 is 302 characters): as Rust prints
/// it (the shortest text that reads back to the same number) for magnitudes from 1e-4 to below
/// 1e7, and 0, NaN and inf; in exponent form (`1e-300`) beyond. The FMU's log lines
/// (`fmi::logger::number`), the CLI's and the validation's messages share it.
pub fn number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e7).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// An error as one line of bounded length: a value quoted from a hostile input (a 4 MiB string in
/// a scenario) must not become a megabyte of standard error or of an FMU's log. Lines longer than
/// 600 characters keep their first 400 and last 150, with the count cut between.
pub fn bounded_line(message: &str) -> String {
    // Control characters (a terminal's escape sequences from a hostile file) are shown, not sent.
    let line: String = message
        .chars()
        .map(|c| {
            if c == '\n' || c == '\r' || c == '\t' {
                ' '
            } else if c.is_control() {
                '\u{FFFD}'
            } else {
                c
            }
        })
        .collect();
    let chars: Vec<char> = line.chars().collect();
    if chars.len() <= 600 {
        return line;
    }
    let head: String = chars[..400].iter().collect();
    let tail: String = chars[chars.len() - 150..].iter().collect();
    format!("{head} [... {} characters cut ...] {tail}", chars.len() - 550)
}
