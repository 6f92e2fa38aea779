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
//!     28     n  payload: the RunState as MessagePack with field names (rmp-serde)
//! ```
//!
//! MessagePack stores every f64 as its eight IEEE bytes, so a restored state continues bit for
//! bit (NaN, infinities and -0 included), and it names fields and types, so a string is never
//! taken for a number. The field paths of [`RunState`] are pinned by a test at each
//! [`FORMAT_VERSION`].

use super::variables::is_fmu_parameter;
use crate::error::{Error, Result};
use crate::model::parameters::PARAMETERS;
use crate::simulation::RunState;
use crate::Scenario;

/// The first bytes of every serialized state.
pub const MAGIC: &[u8; 8] = b"BEAMFMU\0";

/// Version of the byte format; bump it when the layout or [`RunState`] changes.
pub const FORMAT_VERSION: u32 = 2;

const HEADER: usize = 28;

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

impl Snapshot {
    /// The portable bytes of the snapshot.
    pub fn to_bytes(&self) -> Result<Vec<u8>> {
        let payload = rmp_serde::to_vec_named(&self.run).map_err(payload_error)?;
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
        let run: RunState = rmp_serde::from_slice(&bytes[HEADER..]).map_err(payload_error)?;
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
        assert_eq!(back.kinematics.velocity[0].to_bits(), run.kinematics.velocity[0].to_bits());
        assert_eq!(rmp_serde::to_vec_named(&back).unwrap(), rmp_serde::to_vec_named(&run).unwrap());
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
            Err(e @ Error::StateVersion { found: 9, expected: 2 }) => {
                assert!(e.to_string().contains("format version 9, this binary reads version 2"))
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(Snapshot::from_bytes(b"garbage"), Err(Error::StateMagic { length: 7 })));
        // A payload of the right length that is not a RunState.
        let mut corrupt = bytes.clone();
        corrupt[HEADER..].fill(0xc1); // 0xc1 is never used in MessagePack
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

    /// Every leaf's path in the state with its type (`result.time: f64`); array elements are `[]`.
    fn paths(value: &serde_json::Value, prefix: &str, out: &mut std::collections::BTreeSet<String>) {
        use serde_json::Value;
        let leaf = match value {
            Value::Object(fields) => {
                for (k, v) in fields {
                    paths(v, &if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") }, out);
                }
                return;
            }
            Value::Array(items) if !items.is_empty() => {
                items.iter().for_each(|v| paths(v, &format!("{prefix}[]"), out));
                return;
            }
            Value::Array(_) => "empty",
            Value::Null => "null",
            Value::Bool(_) => "bool",
            Value::Number(n) if n.is_f64() => "f64",
            Value::Number(n) if n.is_u64() => "u64",
            Value::Number(_) => "i64",
            Value::String(_) => "str",
        };
        out.insert(format!("{prefix}: {leaf}"));
    }

    /// The payload's layout at FORMAT_VERSION 2 (2: the energy verdict, the output time and input of
    /// grid-independent co-simulation, the first contact's peaks): every field path of `RunState` and its type. A
    /// field added to, renamed in, retyped in or removed from `RunState` (or a struct inside it)
    /// changes what a serialized state means: bump FORMAT_VERSION and update this list together.
    /// (A DVector is nalgebra's `[data, nrows, ncols]`: `[][]` the data, `[]` the sizes.)
    #[test]
    fn run_state_fields_are_pinned_at_format_version_2() {
        const VERSION_2: &[&str] = &[
            "contact_windows[].end: f64",
            "contact_windows[].start: f64",
            "dissipation_rate: f64",
            "first_contact.ended: bool",
            "first_contact.last_contact: f64",
            "first_contact.peaks.contact_force: f64",
            "first_contact.peaks.lower_clamp_bending_stress: f64",
            "first_contact.peaks.lower_clamp_shear_stress: f64",
            "first_contact.peaks.lower_tip_deflection: f64",
            "first_contact.peaks.upper_contact_bending_stress: f64",
            "first_contact.pending.contact_force: f64",
            "first_contact.pending.lower_clamp_bending_stress: f64",
            "first_contact.pending.lower_clamp_shear_stress: f64",
            "first_contact.pending.lower_tip_deflection: f64",
            "first_contact.pending.upper_contact_bending_stress: f64",
            "first_contact.window_start: f64",
            "forces.lower: f64",
            "forces.upper: f64",
            "gap: f64",
            "initial_energy: f64",
            "input_forces.lower: f64",
            "input_forces.upper: f64",
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
            "max_external_work: f64",
            "max_residual: f64",
            "max_strain_energy: f64",
            "output_ns: u64",
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
            "result.lower_clamp_reaction_force: f64",
            "result.lower_clamp_reaction_moment: f64",
            "result.lower_clamp_shear_stress: f64",
            "result.lower_tip_deflection: f64",
            "result.lower_tip_velocity: f64",
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
            "result.upper_hinge_reaction_force: f64",
            "result.upper_tip_deflection: f64",
            "result.upper_tip_velocity: f64",
            "upper_strain_at_peak: f64",
        ];
        let run = state_at(50_000_000);
        assert!(!run.contact_windows.is_empty(), "the pinned paths need a contact window");
        let mut found = std::collections::BTreeSet::new();
        paths(&serde_json::to_value(&run).unwrap(), "", &mut found);
        let found: Vec<&str> = found.iter().map(String::as_str).collect();
        assert_eq!(
            (FORMAT_VERSION, found.as_slice()),
            (2, VERSION_2),
            "RunState's fields changed: bump FORMAT_VERSION and update the pinned list"
        );
    }
}
