//! The names a log is made of: its topics, records and attachments, its format number and the
//! log lines a reader recognises. Written by the recorder ([`super::mcap`]) and its writer thread
//! ([`super::writer`]), read back by [`crate::replay`]; here so that neither of the two writing
//! files needs the other for them.

/// Topic of the step messages.
pub const STEP_TOPIC: &str = "/beam/step";
/// Topic of the modal coordinates (log format 2).
pub const MODES_TOPIC: &str = "/beam/modes";
/// Topic of the contact events.
pub const CONTACT_TOPIC: &str = "/beam/contact";
/// Topic of the one-off model message.
pub const MODEL_TOPIC: &str = "/beam/model";
/// Topic of the per-step stresses at the stress stations (issue 30).
pub const STATIONS_TOPIC: &str = "/beam/stations";
/// Topic of the 3D scene.
pub const SCENE_TOPIC: &str = "/beam/scene";
/// Topic of the log lines.
pub const LOG_TOPIC: &str = "/beam/log";
/// The attachment holding the CLI's answer with its checks (`quality`, `design`,
/// `discretisation` as `run --json` writes them), added after the run's last step.
pub const ANSWER_ATTACHMENT: &str = "answer.json";
/// The attachment holding the run's stress envelope (issue 30: [`crate::results::StressEnvelope`]
/// as JSON, each beam's bending and shear stations with their largest |stress|, when, and the
/// allowable), added when the log is finished: by the CLI and the FMU alike.
pub const ENVELOPE_ATTACHMENT: &str = "envelope.json";
/// The attachment holding the printed run's bending stations' stress histories as turning points
/// (issue 44: [`crate::run_fatigue::StationHistories`] as JSON), added after the run's last step
/// by `run` (the CLI's and Python's), from which `report --fatigue` applies any S-N curve.
pub const FATIGUE_ATTACHMENT: &str = "fatigue.json";
/// Name of the scenario's Metadata record.
pub const SCENARIO_METADATA: &str = "scenario";
/// Name of the scenario's TOML attachment.
pub const SCENARIO_ATTACHMENT: &str = "scenario.toml";
/// The attachment holding the support-motion table a run used (issue 27): its rows as read,
/// written back as CSV (`time` and the columns the file gave, every value round-trip exact), so
/// that a log replays without the motion file. The file's name is the scenario's `motion.file`.
pub const MOTION_ATTACHMENT: &str = "motion.csv";
/// Media type of [`MOTION_ATTACHMENT`].
pub const MOTION_MEDIA_TYPE: &str = "text/csv";
/// Key of the log format in the scenario's Metadata record (absent in format 1 logs).
pub const LOG_FORMAT_KEY: &str = "log_format";
/// The format this recorder writes: 2 = modal coordinates on `/beam/modes`.
pub const LOG_FORMAT: u32 = 2;

/// How the log line of a rollback starts (the reader recognises it).
pub const ROLLBACK_LINE: &str = "rolled back to";

/// What the warning line of a log stopped at its size cap says (the reader recognises it).
pub const SIZE_CAP_LINE: &str = "reached its size cap";
