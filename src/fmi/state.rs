//! FMU state snapshots and their portable byte format.
//!
//! A snapshot is the simulation's [`RunState`] plus a fingerprint of the scenario it belongs to.
//! The bytes are versioned and independent of the process and of the memory layout:
//!
//! ```text
//! offset  size  content
//!      0     8  magic "BEAMFMU\0"
//!      8     4  format version, u32 little endian (FORMAT_VERSION)
//!     12     8  scenario fingerprint, u64 little endian (FNV-1a of the FMU parameters' names and bits)
//!     20     8  payload length n, u64 little endian
//!     28     n  payload: the RunState as JSON, every f64 written as {"f64 bits": "<16 hex digits>"}
//! ```
//!
//! Floats are carried as their bit patterns, in an object with a key no Rust field can have, so
//! that a restored state continues bit for bit whatever the JSON parser's rounding, NaN and -0
//! included, and no string is ever mistaken for a float. The JSON field paths of [`RunState`] are
//! pinned by a test at each [`FORMAT_VERSION`].

use serde::Deserialize;
use serde_json::{Map, Value};

use super::tree::{to_tree, Tree};
use super::variables::is_fmu_parameter;
use crate::error::{Error, Result};
use crate::model::parameters::PARAMETERS;
use crate::simulation::RunState;
use crate::Scenario;

/// The first bytes of every serialized state.
pub const MAGIC: &[u8; 8] = b"BEAMFMU\0";

/// Version of the byte format; bump it when the layout or [`RunState`] changes.
pub const FORMAT_VERSION: u32 = 1;

const HEADER: usize = 28;

/// The key of the object an f64 is written as (a space: no Rust field is called that).
const FLOAT_KEY: &str = "f64 bits";

/// A saved FMU state (what `fmi2FMUstate` / `fmi3FMUState` point to).
#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot {
    /// Fingerprint of the scenario the state belongs to.
    pub fingerprint: u64,
    /// The simulation's state.
    pub run: RunState,
}

/// FNV-1a over the FMU parameters' names and value bits (the scenario fields the FMU exposes, so
/// not the CLI's `duration`, which follows the importer's stop time): equal for equal parameters,
/// stable across processes and builds.
pub fn fingerprint(scenario: &Scenario) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let mut feed = |bytes: &[u8]| {
        for &b in bytes {
            hash ^= u64::from(b);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    for p in PARAMETERS.iter().filter(|p| is_fmu_parameter(p)) {
        feed(p.name.as_bytes());
        feed(&(p.get)(scenario).to_bits().to_le_bytes());
    }
    hash
}

fn payload_error(detail: impl std::fmt::Display) -> Error {
    Error::StatePayload { detail: detail.to_string() }
}

/// The value tree as JSON, each float as the object `{"f64 bits": "<16 hex digits>"}`.
fn to_json(tree: Tree) -> Value {
    match tree {
        Tree::F64(x) => {
            let mut map = Map::new();
            map.insert(FLOAT_KEY.into(), Value::String(format!("{:016x}", x.to_bits())));
            Value::Object(map)
        }
        Tree::Null => Value::Null,
        Tree::Bool(b) => Value::Bool(b),
        Tree::U64(n) => Value::from(n),
        Tree::I64(n) => Value::from(n),
        Tree::Str(s) => Value::String(s),
        Tree::Seq(items) => Value::Array(items.into_iter().map(to_json).collect()),
        Tree::Map(entries) => Value::Object(entries.into_iter().map(|(k, v)| (k, to_json(v))).collect()),
    }
}

/// The inverse of [`to_json`]: only `{"f64 bits": "<16 hex digits>"}` objects become floats, and a
/// JSON number must be an integer.
fn from_json(value: Value) -> Result<Tree> {
    Ok(match value {
        Value::Object(map) if map.len() == 1 && map.contains_key(FLOAT_KEY) => {
            let bits = match &map[FLOAT_KEY] {
                Value::String(s) if s.len() == 16 => u64::from_str_radix(s, 16).ok(),
                _ => None,
            }
            .ok_or_else(|| payload_error(format!("{} is not the 16 hex digits of an f64", map[FLOAT_KEY])))?;
            Tree::F64(f64::from_bits(bits))
        }
        Value::Object(map) => Tree::Map(map.into_iter().map(|(k, v)| Ok((k, from_json(v)?))).collect::<Result<_>>()?),
        Value::Number(n) => match (n.as_u64(), n.as_i64()) {
            (Some(u), _) => Tree::U64(u),
            (None, Some(i)) => Tree::I64(i),
            _ => return Err(payload_error(format!("{n} is not an integer (floats are written as their bits)"))),
        },
        Value::Null => Tree::Null,
        Value::Bool(b) => Tree::Bool(b),
        Value::String(s) => Tree::Str(s),
        Value::Array(items) => Tree::Seq(items.into_iter().map(from_json).collect::<Result<_>>()?),
    })
}

impl Snapshot {
    /// The portable bytes of the snapshot.
    pub fn to_bytes(&self) -> Result<Vec<u8>> {
        let tree = to_tree(&self.run).map_err(|e| Error::State(format!("cannot serialize: {e}")))?;
        let payload = serde_json::to_vec(&to_json(tree)).map_err(|e| Error::State(format!("cannot serialize: {e}")))?;
        let mut bytes = Vec::with_capacity(HEADER + payload.len());
        bytes.extend_from_slice(MAGIC);
        bytes.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        bytes.extend_from_slice(&self.fingerprint.to_le_bytes());
        bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
        bytes.extend_from_slice(&payload);
        Ok(bytes)
    }

    /// Reads bytes written by [`Snapshot::to_bytes`], checking magic, version and length.
    pub fn from_bytes(bytes: &[u8]) -> Result<Snapshot> {
        if bytes.len() < HEADER || &bytes[..8] != MAGIC {
            return Err(Error::StateMagic { length: bytes.len() });
        }
        let u32_at = |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
        let u64_at = |at: usize| u64::from(u32_at(at)) | (u64::from(u32_at(at + 4)) << 32);
        let version = u32_at(8);
        if version != FORMAT_VERSION {
            return Err(Error::StateVersion { found: version, expected: FORMAT_VERSION });
        }
        let fingerprint = u64_at(12);
        let declared = u64_at(20);
        let given = (bytes.len() - HEADER) as u64;
        if declared != given {
            return Err(Error::StateLength { declared, given });
        }
        let value: Value = serde_json::from_slice(&bytes[HEADER..]).map_err(payload_error)?;
        let run = RunState::deserialize(from_json(value)?).map_err(payload_error)?;
        Ok(Snapshot { fingerprint, run })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::NullRecorder;
    use crate::Simulation;

    fn state_at(ns: u64) -> RunState {
        let mut sim = Simulation::new(&Scenario::default()).unwrap();
        sim.advance_to(ns, &mut NullRecorder, false).unwrap();
        sim.state().clone()
    }

    #[test]
    fn round_trip_is_bit_exact() {
        let snapshot = Snapshot { fingerprint: fingerprint(&Scenario::default()), run: state_at(123_456_789) };
        let bytes = snapshot.to_bytes().unwrap();
        assert_eq!(&bytes[..8], MAGIC);
        assert_eq!(Snapshot::from_bytes(&bytes).unwrap(), snapshot);
    }

    #[test]
    fn nan_infinity_and_negative_zero_round_trip_bit_for_bit() {
        let mut run = state_at(50_000_000);
        let odd_nan = f64::from_bits(0x7ff8_0000_dead_beef);
        run.gap = odd_nan;
        run.max_residual = f64::NEG_INFINITY;
        run.result.contact_force = -0.0;
        run.kinematics.velocity[0] = f64::NAN;
        let bytes = Snapshot { fingerprint: 7, run: run.clone() }.to_bytes().unwrap();
        let back = Snapshot::from_bytes(&bytes).unwrap().run;
        assert_eq!(back.gap.to_bits(), odd_nan.to_bits());
        assert_eq!(back.max_residual, f64::NEG_INFINITY);
        assert_eq!(back.result.contact_force.to_bits(), (-0.0f64).to_bits());
        assert!(back.kinematics.velocity[0].is_nan());
        let bits = |r: &RunState| serde_json::to_string(&to_json(to_tree(r).unwrap())).unwrap();
        assert_eq!(bits(&back), bits(&run));
    }

    #[test]
    fn strings_and_integers_are_never_taken_for_floats() {
        // A string of 16 hex digits (the old encoding of a float) stays a string; only the typed
        // object is a float; a JSON float where bits are expected is refused.
        let json: Value = serde_json::json!({
            "name": "3ff0000000000000",
            "x": {"f64 bits": "3ff0000000000000"},
            "n": 42,
            "other": {"f64 bits": "3ff0000000000000", "more": 1}
        });
        let tree = from_json(json.clone()).unwrap();
        let Tree::Map(fields) = &tree else { panic!("{tree:?}") };
        let field = |name: &str| fields.iter().find(|(k, _)| k == name).map(|(_, v)| v.clone()).unwrap();
        assert_eq!(field("name"), Tree::Str("3ff0000000000000".into()));
        assert_eq!(field("x"), Tree::F64(1.0));
        assert_eq!(field("n"), Tree::U64(42));
        assert!(matches!(field("other"), Tree::Map(_)));
        assert_eq!(to_json(tree), json);
        assert!(matches!(from_json(serde_json::json!({"x": 1.5})), Err(Error::StatePayload { .. })));
        assert!(matches!(from_json(serde_json::json!({"f64 bits": "xyz"})), Err(Error::StatePayload { .. })));
    }

    #[test]
    fn damaged_bytes_are_refused_with_typed_errors() {
        let bytes = Snapshot { fingerprint: 1, run: state_at(0) }.to_bytes().unwrap();
        let given = (bytes.len() - HEADER - 1) as u64;
        match Snapshot::from_bytes(&bytes[..bytes.len() - 1]) {
            Err(Error::StateLength { declared, given: g }) => assert_eq!((declared, g), (given + 1, given)),
            other => panic!("{other:?}"),
        }
        let mut other = bytes.clone();
        other[8] = 9;
        match Snapshot::from_bytes(&other) {
            Err(e @ Error::StateVersion { found: 9, expected: 1 }) => {
                assert!(e.to_string().contains("format version 9, this binary reads version 1"))
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(Snapshot::from_bytes(b"garbage"), Err(Error::StateMagic { length: 7 })));
        let mut corrupt = bytes.clone();
        let last = corrupt.len() - 2;
        corrupt[last] = b'#';
        assert!(matches!(Snapshot::from_bytes(&corrupt), Err(Error::StatePayload { .. })));
    }

    #[test]
    fn fingerprint_tells_scenarios_apart_but_ignores_the_cli_duration() {
        let other = Scenario { drop_height: 0.5, ..Scenario::default() };
        assert_ne!(fingerprint(&other), fingerprint(&Scenario::default()));
        assert_eq!(fingerprint(&Scenario::default()), fingerprint(&Scenario::default()));
        // The FMU sets `duration` from the importer's stop time: not part of the state's identity.
        let longer = Scenario { duration: 5.0, ..Scenario::default() };
        assert_eq!(fingerprint(&longer), fingerprint(&Scenario::default()));
    }

    /// Every leaf's path in the payload with its type (`result.time: f64`); array elements are `[]`.
    fn paths(tree: &Tree, prefix: &str, out: &mut std::collections::BTreeSet<String>) {
        let leaf = match tree {
            Tree::Map(fields) => {
                for (k, v) in fields {
                    paths(v, &if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") }, out);
                }
                return;
            }
            Tree::Seq(items) if !items.is_empty() => {
                items.iter().for_each(|v| paths(v, &format!("{prefix}[]"), out));
                return;
            }
            Tree::Seq(_) => "empty",
            Tree::Null => "null",
            Tree::Bool(_) => "bool",
            Tree::U64(_) => "u64",
            Tree::I64(_) => "i64",
            Tree::F64(_) => "f64",
            Tree::Str(_) => "str",
        };
        out.insert(format!("{prefix}: {leaf}"));
    }

    /// The payload's layout at FORMAT_VERSION 1: every field path of `RunState` and its type. A
    /// field added to, renamed in, retyped in or removed from `RunState` (or a struct inside it)
    /// changes what a serialized state means: bump FORMAT_VERSION and update this list together.
    /// (A DVector is nalgebra's `[data, nrows, ncols]`: `[][]` the data, `[]` the sizes.)
    #[test]
    fn run_state_fields_are_pinned_at_format_version_1() {
        const VERSION_1: &[&str] = &[
            "contact_windows[].end: f64",
            "contact_windows[].start: f64",
            "dissipation_rate: f64",
            "forces.lower: f64",
            "forces.upper: f64",
            "gap: f64",
            "initial_energy: f64",
            "kinematics.acceleration[]: null",
            "kinematics.acceleration[]: u64",
            "kinematics.acceleration[][]: f64",
            "kinematics.displacement[]: null",
            "kinematics.displacement[]: u64",
            "kinematics.displacement[][]: f64",
            "kinematics.velocity[]: null",
            "kinematics.velocity[]: u64",
            "kinematics.velocity[][]: f64",
            "last_forces.lower: f64",
            "last_forces.upper: f64",
            "max_residual: f64",
            "peak_times.contact_force: f64",
            "peak_times.lower_clamp_bending_stress: f64",
            "peak_times.lower_clamp_shear_stress: f64",
            "peak_times.lower_tip_deflection: f64",
            "peak_times.upper_contact_bending_stress: f64",
            "result.contact: bool",
            "result.contact_force: f64",
            "result.contact_stress: f64",
            "result.energy.damping_dissipation: f64",
            "result.energy.external_work: f64",
            "result.energy.gravity_potential: f64",
            "result.energy.kinetic: f64",
            "result.energy.residual: f64",
            "result.energy.strain: f64",
            "result.lower_clamp_bending_stress: f64",
            "result.lower_clamp_shear_stress: f64",
            "result.lower_tip_deflection: f64",
            "result.peaks.contact_force: f64",
            "result.peaks.lower_clamp_bending_stress: f64",
            "result.peaks.lower_clamp_shear_stress: f64",
            "result.peaks.lower_tip_deflection: f64",
            "result.peaks.upper_contact_bending_stress: f64",
            "result.step: u64",
            "result.step_size: f64",
            "result.time: f64",
            "result.time_ns: u64",
            "result.upper_contact_bending_stress: f64",
            "result.upper_contact_deflection: f64",
            "result.upper_tip_deflection: f64",
            "upper_strain_at_peak: f64",
        ];
        let run = state_at(50_000_000);
        assert!(!run.contact_windows.is_empty(), "the pinned paths need a contact window");
        let mut found = std::collections::BTreeSet::new();
        paths(&to_tree(&run).unwrap(), "", &mut found);
        let found: Vec<&str> = found.iter().map(String::as_str).collect();
        assert_eq!(
            (FORMAT_VERSION, found.as_slice()),
            (1, VERSION_1),
            "RunState's fields changed: bump FORMAT_VERSION and update the pinned list"
        );
    }
}
