//! FMU state snapshots and their portable byte format.
//!
//! A snapshot is the simulation's [`RunState`] plus a fingerprint of the scenario it belongs to.
//! The bytes are versioned and independent of the process and of the memory layout:
//!
//! ```text
//! offset  size  content
//!      0     8  magic "BEAMFMU\0"
//!      8     4  format version, u32 little endian (FORMAT_VERSION)
//!     12     8  scenario fingerprint, u64 little endian (FNV-1a of every parameter's name and bits)
//!     20     8  payload length n, u64 little endian
//!     28     n  payload: the RunState as JSON, every f64 written as the 16 hex digits of its bits
//! ```
//!
//! Floats are carried as their bit patterns so that a restored state continues bit for bit,
//! whatever the JSON parser's rounding.

use serde_json::Value;

use crate::error::{Error, Result};
use crate::model::parameters::PARAMETERS;
use crate::simulation::RunState;
use crate::Scenario;

/// The first bytes of every serialized state.
pub const MAGIC: &[u8; 8] = b"BEAMFMU\0";

/// Version of the byte format; bump it when the layout or [`RunState`] changes.
pub const FORMAT_VERSION: u32 = 1;

const HEADER: usize = 28;

/// A saved FMU state (what `fmi2FMUstate` / `fmi3FMUState` point to).
#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot {
    /// Fingerprint of the scenario the state belongs to.
    pub fingerprint: u64,
    /// The simulation's state.
    pub run: RunState,
}

/// FNV-1a over every parameter's name and value bits: equal for equal scenarios, stable across
/// processes and builds.
pub fn fingerprint(scenario: &Scenario) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let mut feed = |bytes: &[u8]| {
        for &b in bytes {
            hash ^= u64::from(b);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    for p in PARAMETERS {
        feed(p.name.as_bytes());
        feed(&(p.get)(scenario).to_bits().to_le_bytes());
    }
    hash
}

fn floats_to_bits(value: Value) -> Value {
    match value {
        Value::Number(n) if n.is_f64() => Value::String(format!("{:016x}", n.as_f64().unwrap_or(f64::NAN).to_bits())),
        Value::Array(items) => Value::Array(items.into_iter().map(floats_to_bits).collect()),
        Value::Object(map) => Value::Object(map.into_iter().map(|(k, v)| (k, floats_to_bits(v))).collect()),
        other => other,
    }
}

fn bits_to_floats(value: Value) -> Result<Value> {
    Ok(match value {
        Value::String(s) => {
            let bits = u64::from_str_radix(&s, 16)
                .map_err(|_| Error::State(format!("`{s}` is not the hex bit pattern of a number")))?;
            let x = f64::from_bits(bits);
            Value::Number(
                serde_json::Number::from_f64(x)
                    .ok_or_else(|| Error::State(format!("non-finite number {x} in state")))?,
            )
        }
        Value::Array(items) => Value::Array(items.into_iter().map(bits_to_floats).collect::<Result<_>>()?),
        Value::Object(map) => {
            Value::Object(map.into_iter().map(|(k, v)| Ok((k, bits_to_floats(v)?))).collect::<Result<_>>()?)
        }
        other => other,
    })
}

impl Snapshot {
    /// The portable bytes of the snapshot.
    pub fn to_bytes(&self) -> Result<Vec<u8>> {
        let value = serde_json::to_value(&self.run).map_err(|e| Error::State(format!("cannot serialize: {e}")))?;
        let payload =
            serde_json::to_vec(&floats_to_bits(value)).map_err(|e| Error::State(format!("cannot serialize: {e}")))?;
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
            return Err(Error::State(format!(
                "not a serialized beam-impact FMU state ({} bytes, magic missing)",
                bytes.len()
            )));
        }
        let word = |range: std::ops::Range<usize>| -> [u8; 8] {
            let mut w = [0u8; 8];
            w[..range.len()].copy_from_slice(&bytes[range]);
            w
        };
        let version = u32::from_le_bytes(word(8..12)[..4].try_into().unwrap_or([0; 4]));
        if version != FORMAT_VERSION {
            return Err(Error::State(format!("format version {version}, this binary reads version {FORMAT_VERSION}")));
        }
        let fingerprint = u64::from_le_bytes(word(12..20));
        let length = u64::from_le_bytes(word(20..28));
        if length != (bytes.len() - HEADER) as u64 {
            return Err(Error::State(format!(
                "the payload should be {length} bytes, {} were given",
                bytes.len() - HEADER
            )));
        }
        let value: Value =
            serde_json::from_slice(&bytes[HEADER..]).map_err(|e| Error::State(format!("corrupt payload: {e}")))?;
        let run = serde_json::from_value(bits_to_floats(value)?)
            .map_err(|e| Error::State(format!("corrupt payload: {e}")))?;
        Ok(Snapshot { fingerprint, run })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::NullRecorder;
    use crate::Simulation;

    #[test]
    fn round_trip_is_bit_exact() {
        let scenario = Scenario::default();
        let mut sim = Simulation::new(&scenario).unwrap();
        sim.advance_to(123_456_789, &mut NullRecorder, false).unwrap();
        let snapshot = Snapshot { fingerprint: fingerprint(&scenario), run: sim.state().clone() };
        let bytes = snapshot.to_bytes().unwrap();
        assert_eq!(&bytes[..8], MAGIC);
        assert_eq!(Snapshot::from_bytes(&bytes).unwrap(), snapshot);
    }

    #[test]
    fn damaged_bytes_are_refused_with_a_reason() {
        let scenario = Scenario::default();
        let sim = Simulation::new(&scenario).unwrap();
        let bytes = Snapshot { fingerprint: 1, run: sim.state().clone() }.to_bytes().unwrap();
        let err = Snapshot::from_bytes(&bytes[..bytes.len() - 1]).unwrap_err().to_string();
        assert!(err.contains("payload should be"), "{err}");
        let mut other = bytes.clone();
        other[8] = 9;
        let err = Snapshot::from_bytes(&other).unwrap_err().to_string();
        assert!(err.contains("format version 9"), "{err}");
        assert!(Snapshot::from_bytes(b"garbage").is_err());
    }

    #[test]
    fn fingerprint_tells_scenarios_apart() {
        let other = Scenario { drop_height: 0.5, ..Scenario::default() };
        assert_ne!(fingerprint(&other), fingerprint(&Scenario::default()));
        assert_eq!(fingerprint(&Scenario::default()), fingerprint(&Scenario::default()));
    }
}
