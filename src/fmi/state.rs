//! FMU state snapshots and their portable byte format.
//!
//! A snapshot is the FMI state of an instance: the simulation's [`RunState`], the FMU parameters
//! it runs with, the run's absolute start time and whether it was initialized. It holds
//! everything needed to continue "without additional FMI C-API calls", so a fresh instance can
//! restore it (fmpy's `simulate_fmu(fmu_state=...)`, fmusim's `--initial-fmu-state-file`). Not in
//! it: the stop time and `log.path` (the importer's and the restoring instance's business).
//!
//! The bytes are versioned and independent of the process and of the memory layout:
//!
//! ```text
//! offset  size  content
//!      0     8  magic "BEAMFMU\0"
//!      8     4  format version, u32 little endian (FORMAT_VERSION)
//!     12     8  payload length n, u64 little endian
//!     20     4  CRC-32 (IEEE 802.3), u32 little endian, of bytes 0..20 followed by the payload
//!     24     n  payload: the Snapshot as MessagePack with field names (rmp-serde):
//!               start_time (s, absolute), initialized, parameters (name -> value), run (RunState)
//! ```
//!
//! MessagePack stores every f64 as its eight IEEE bytes, so a restored state continues bit for
//! bit (NaN, infinities and -0 included), and it names fields and types, so a string is never
//! taken for a number. The checksum catches damage (every single-bit flip, every burst up to 32
//! bits), not forgery: what the payload says is checked on restore ([`RunState::validate`], the
//! scenario limits). The field paths are pinned by a test at each [`FORMAT_VERSION`].

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::variables::is_fmu_parameter;
use crate::error::{Error, Result};
use crate::model::parameters::{self, PARAMETERS};
use crate::model::section::SectionSpec;
use crate::simulation::RunState;
use crate::Scenario;

/// The first bytes of every serialized state.
pub const MAGIC: &[u8; 8] = b"BEAMFMU\0";

/// Version of the byte format; bump it when the layout, [`Snapshot`], [`RunState`] or the set of
/// FMU parameters changes.
pub const FORMAT_VERSION: u32 = 9;

/// Bytes before the payload.
pub const HEADER: usize = 24;

/// Where the CRC-32 sits in the header.
const CRC_AT: usize = 20;

/// A saved FMU state (what `fmi2FMUstate` / `fmi3FMUState` point to).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    /// The run's absolute start time (the importer's startTime), s: the FMU's time is this plus
    /// the run's output time, so a state saved at 11.5 s of a run started at 10 s restores at 11.5 s.
    pub start_time: f64,
    /// Taken after ExitInitializationMode: restoring it into an instance that is not initialized
    /// puts that instance in Step Mode. A state taken before holds the parameters and step 0.
    pub initialized: bool,
    /// Every FMU parameter's value by name ([`parameters_of`]).
    pub parameters: BTreeMap<String, f64>,
    /// The simulation's state.
    pub run: RunState,
    /// The states of the discretisation check's runs (empty: not checked), in the order of
    /// [`crate::answer::check_scenarios`].
    pub checks: Vec<RunState>,
    /// The beams' sections (issue 30; empty: a uniform beam), which no FMU parameter holds: an
    /// FMU packed with a scenario of sections restores them with its parameters.
    pub sections: Sections,
}

/// Each beam's sections from its support, as in the scenario (`[[upper.sections]]`,
/// `[[lower.sections]]`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Sections {
    /// The bridge's, from the hinge.
    pub upper: Vec<SectionSpec>,
    /// The arrestor's, from the clamp.
    pub lower: Vec<SectionSpec>,
}

/// The sections of a scenario's beams.
pub fn sections_of(scenario: &Scenario) -> Sections {
    Sections { upper: scenario.upper.sections.clone(), lower: scenario.lower.sections.clone() }
}

/// The scenario a snapshot runs: `base` (the restoring instance's scenario: its `duration` and tip
/// forces) with the snapshot's sections and then every FMU parameter of it ([`scenario_with`],
/// which checks the result against the scenario limits).
pub fn scenario_of(base: &Scenario, snapshot: &Snapshot) -> Result<Scenario> {
    let mut base = base.clone();
    base.upper.sections.clone_from(&snapshot.sections.upper);
    base.lower.sections.clone_from(&snapshot.sections.lower);
    scenario_with(&base, &snapshot.parameters)
}

/// Every FMU parameter's value by name (the scenario fields the FMU exposes, so not the CLI's
/// `duration`, which follows the importer's stop time).
pub fn parameters_of(scenario: &Scenario) -> BTreeMap<String, f64> {
    PARAMETERS.iter().filter(|p| is_fmu_parameter(p)).map(|p| (p.name.to_string(), (p.get)(scenario))).collect()
}

fn invalid(detail: String) -> Error {
    Error::StateInvalid { field: "parameters".to_string(), detail }
}

/// `base` (the restoring instance's scenario: its `duration` and tip forces) with every FMU
/// parameter set from `parameters`, which must name each FMU parameter exactly once; the result
/// is checked against the scenario limits ([`Scenario::validate`]).
pub fn scenario_with(base: &Scenario, parameters: &BTreeMap<String, f64>) -> Result<Scenario> {
    let mut scenario = base.clone();
    let expected: Vec<_> = PARAMETERS.iter().filter(|p| is_fmu_parameter(p)).collect();
    if let Some(unknown) = parameters.keys().find(|name| !expected.iter().any(|p| p.name == name.as_str())) {
        return Err(invalid(format!("hold `{unknown}`, which is not a parameter of this FMU")));
    }
    for p in expected {
        let value = *parameters.get(p.name).ok_or_else(|| invalid(format!("lack `{}`", p.name)))?;
        parameters::set(&mut scenario, p, value)
            .map_err(|e| invalid(format!("are outside the scenario limits: {e}")))?;
    }
    scenario.validate().map_err(|e| invalid(format!("are outside the scenario limits: {e}")))?;
    Ok(scenario)
}

fn payload_error(detail: impl std::fmt::Display) -> Error {
    Error::StatePayload { detail: detail.to_string() }
}

fn crc(header: &[u8], payload: &[u8]) -> u32 {
    let mut hasher = crc32fast::Hasher::new();
    hasher.update(&header[..CRC_AT]);
    hasher.update(payload);
    hasher.finalize()
}

impl Snapshot {
    /// The portable bytes of the snapshot.
    pub fn to_bytes(&self) -> Result<Vec<u8>> {
        let payload = rmp_serde::to_vec_named(self).map_err(payload_error)?;
        let mut bytes = Vec::with_capacity(HEADER + payload.len());
        bytes.extend_from_slice(MAGIC);
        bytes.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
        let checksum = crc(&bytes, &payload);
        bytes.extend_from_slice(&checksum.to_le_bytes());
        bytes.extend_from_slice(&payload);
        Ok(bytes)
    }

    /// Reads bytes written by [`Snapshot::to_bytes`], checking magic, version, length and
    /// checksum before the payload is parsed (what the payload says is checked on restore).
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
        let declared = u64_at(12);
        let given = (bytes.len() - HEADER) as u64;
        if declared != given {
            return Err(Error::StateLength { declared, given });
        }
        let payload = &bytes[HEADER..];
        let (saved, computed) = (u32_at(CRC_AT), crc(bytes, payload));
        if saved != computed {
            return Err(Error::StateChecksum { saved, computed });
        }
        let mut rest = payload;
        let snapshot: Snapshot = rmp_serde::from_read(&mut rest).map_err(payload_error)?;
        if !rest.is_empty() {
            return Err(payload_error(format!("{} bytes after the state", rest.len())));
        }
        Ok(snapshot)
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

    fn snapshot_at(ns: u64) -> Snapshot {
        Snapshot {
            start_time: 10.0,
            initialized: true,
            parameters: parameters_of(&Scenario::default()),
            run: state_at(ns),
            checks: vec![state_at(ns)],
            sections: Sections::default(),
        }
    }

    #[test]
    fn round_trip_is_bit_exact() {
        let snapshot = snapshot_at(123_456_789);
        let bytes = snapshot.to_bytes().unwrap();
        assert_eq!(&bytes[..8], MAGIC);
        assert_eq!(Snapshot::from_bytes(&bytes).unwrap(), snapshot);
        assert_eq!(Snapshot::from_bytes(&bytes).unwrap().to_bytes().unwrap(), bytes);
    }

    #[test]
    fn nan_infinity_and_negative_zero_round_trip_bit_for_bit() {
        // The encoding keeps every bit; whether such values may be restored is RunState::validate's call.
        let mut snapshot = snapshot_at(50_000_000);
        let run = &mut snapshot.run;
        let odd_nan = f64::from_bits(0x7ff8_0000_dead_beef);
        run.gap = odd_nan;
        run.max_residual = f64::NEG_INFINITY;
        run.result.contact_force = -0.0;
        run.kinematics.velocity[0] = f64::NAN;
        snapshot.start_time = -0.0;
        let bytes = snapshot.to_bytes().unwrap();
        let back = Snapshot::from_bytes(&bytes).unwrap();
        assert_eq!(back.run.gap.to_bits(), odd_nan.to_bits());
        assert_eq!(back.run.max_residual, f64::NEG_INFINITY);
        assert_eq!(back.run.result.contact_force.to_bits(), (-0.0f64).to_bits());
        assert_eq!(back.start_time.to_bits(), (-0.0f64).to_bits());
        assert_eq!(back.run.kinematics.velocity[0].to_bits(), snapshot.run.kinematics.velocity[0].to_bits());
        assert_eq!(back.to_bytes().unwrap(), bytes);
    }

    #[test]
    fn damaged_bytes_are_refused_with_typed_errors() {
        let bytes = snapshot_at(0).to_bytes().unwrap();
        let given = (bytes.len() - HEADER - 1) as u64;
        match Snapshot::from_bytes(&bytes[..bytes.len() - 1]) {
            Err(Error::StateLength { declared, given: g }) => assert_eq!((declared, g), (given + 1, given)),
            other => panic!("{other:?}"),
        }
        let mut other = bytes.clone();
        other[8] = 99;
        match Snapshot::from_bytes(&other) {
            Err(e @ Error::StateVersion { found: 99, expected: FORMAT_VERSION }) => {
                let text = format!("format version 99, this binary reads version {FORMAT_VERSION}");
                assert!(e.to_string().contains(&text), "{e}")
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(Snapshot::from_bytes(b"garbage"), Err(Error::StateMagic { length: 7 })));
        // One flipped bit in the payload: the checksum says so.
        let mut flipped = bytes.clone();
        flipped[HEADER + 40] ^= 0x10;
        match Snapshot::from_bytes(&flipped) {
            Err(e @ Error::StateChecksum { .. }) => assert!(e.to_string().contains("checksum mismatch"), "{e}"),
            other => panic!("{other:?}"),
        }
        // A payload of the right length and checksum that is not a snapshot.
        let mut corrupt = bytes.clone();
        corrupt[HEADER..].fill(0xc1); // 0xc1 is never used in MessagePack
        let checksum = crc(&corrupt, &corrupt[HEADER..]);
        corrupt[CRC_AT..HEADER].copy_from_slice(&checksum.to_le_bytes());
        assert!(matches!(Snapshot::from_bytes(&corrupt), Err(Error::StatePayload { .. })));
    }

    /// Issue 9: no single-bit corruption of a real state is read back. Every bit of a serialized
    /// state after 50 ms (in contact) is flipped in turn; each flip is refused with a typed error
    /// (CRC-32 detects every single-bit error; the header fields are checked before it).
    #[test]
    fn every_single_bit_flip_is_refused() {
        let bytes = snapshot_at(50_000_000).to_bytes().unwrap();
        let mut copy = bytes.clone();
        for bit in 0..bytes.len() * 8 {
            copy[bit / 8] ^= 1 << (bit % 8);
            match Snapshot::from_bytes(&copy) {
                Err(Error::StateMagic { .. } | Error::StateVersion { .. } | Error::StateLength { .. })
                | Err(Error::StateChecksum { .. }) => {}
                other => panic!("bit {bit} (byte {}): {other:?}", bit / 8),
            }
            copy[bit / 8] ^= 1 << (bit % 8);
        }
        assert_eq!(copy, bytes);
    }

    #[test]
    fn parameters_round_trip_and_are_checked() {
        let other = Scenario { drop_height: 0.5, damping_ratio: 0.01, ..Scenario::default() };
        let parameters = parameters_of(&other);
        assert!(!parameters.contains_key("duration"), "the CLI's duration follows the stop time");
        let base = Scenario { duration: 7.0, ..Scenario::default() };
        let restored = scenario_with(&base, &parameters).unwrap();
        assert_eq!(parameters_of(&restored), parameters);
        assert_eq!(restored.duration, 7.0, "the restoring instance's duration stays");

        let mut missing = parameters.clone();
        missing.remove("upper.length");
        let e = scenario_with(&base, &missing).unwrap_err().to_string();
        assert!(e.contains("FMU state: parameters lack `upper.length`"), "{e}");
        let mut unknown = parameters.clone();
        unknown.insert("log.path".into(), 1.0);
        let e = scenario_with(&base, &unknown).unwrap_err().to_string();
        assert!(e.contains("hold `log.path`, which is not a parameter of this FMU"), "{e}");
        let mut outside = parameters.clone();
        outside.insert("lower.elements".into(), 1e6);
        let e = scenario_with(&base, &outside).unwrap_err().to_string();
        assert!(e.contains("outside the scenario limits") && e.contains("lower.elements"), "{e}");
        let mut nan = parameters;
        nan.insert("drop_height".into(), f64::NAN);
        let e = scenario_with(&base, &nan).unwrap_err().to_string();
        assert!(e.contains("drop_height"), "{e}");
    }

    /// Every leaf's path in the state with its type (`run.result.time: f64`); array elements are `[]`.
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

    /// The payload's layout at FORMAT_VERSION 9 (9: the struck beam's supports and contact position, issue 45; 8: every node's largest deflection and rotation, the model's range, issue 40; 7: the stress envelope's stations, the bridge's
    /// shear area and allowable shear stress, the beams' sections, issue 30; 6: the exact modal advance's step level; 5: issue 28's FMU parameters, the impact's
    /// angular velocity, `lower.kind`, `contact.stiffness` and `contact.clearance`; 4: the supports' motion, its start and input, the
    /// inertial potential and the supports' displacements in the results; 3: the method, modal cut-off, discretisation
    /// tolerance, allowables and yield stresses; the discretisation check's run states): every field path of `Snapshot` and its type, the
    /// FMU parameters by name. Version 2 (one bump for issues 7, 8 and 9): the energy verdict, the
    /// output time and input of grid-independent co-simulation, the first contact's peaks, the
    /// support reactions and tip velocities (RunState); the FMU parameters, the absolute start
    /// time and the initialized flag (the FMI state, restorable into a fresh instance); the
    /// header's CRC-32 and no scenario fingerprint. A field added to, renamed in, retyped in or
    /// removed from `Snapshot` or `RunState` (or a struct inside them), or an FMU parameter added
    /// or removed, changes what a serialized state means: bump FORMAT_VERSION and update this
    /// list together. (A DVector is nalgebra's `[data, nrows, ncols]`: `[][]` the data, `[]` the
    /// sizes; `null` an absent Option or the static column count.)
    #[test]
    fn snapshot_fields_are_pinned_at_format_version_9() {
        const VERSION_9: &[&str] = &[
            "checks[].contact_windows[].end: f64",
            "checks[].contact_windows[].start: f64",
            "checks[].dissipation_rate: f64",
            "checks[].envelope[]: f64",
            "checks[].envelope_times[]: f64",
            "checks[].first_contact.ended: bool",
            "checks[].first_contact.last_contact: f64",
            "checks[].first_contact.peaks.contact_force: f64",
            "checks[].first_contact.peaks.lower_clamp_bending_stress: f64",
            "checks[].first_contact.peaks.lower_clamp_shear_stress: f64",
            "checks[].first_contact.peaks.lower_tip_deflection: f64",
            "checks[].first_contact.peaks.upper_contact_bending_stress: f64",
            "checks[].first_contact.pending.contact_force: f64",
            "checks[].first_contact.pending.lower_clamp_bending_stress: f64",
            "checks[].first_contact.pending.lower_clamp_shear_stress: f64",
            "checks[].first_contact.pending.lower_tip_deflection: f64",
            "checks[].first_contact.pending.upper_contact_bending_stress: f64",
            "checks[].first_contact.window_start: f64",
            "checks[].forces.lower: f64",
            "checks[].forces.upper: f64",
            "checks[].gap: f64",
            "checks[].inertial_potential: f64",
            "checks[].initial_energy: f64",
            "checks[].input_forces.lower: f64",
            "checks[].input_forces.upper: f64",
            "checks[].input_motion.clamp_heave.acceleration: f64",
            "checks[].input_motion.clamp_heave.displacement: f64",
            "checks[].input_motion.clamp_heave.velocity: f64",
            "checks[].input_motion.clamp_rotation.acceleration: f64",
            "checks[].input_motion.clamp_rotation.displacement: f64",
            "checks[].input_motion.clamp_rotation.velocity: f64",
            "checks[].input_motion.hinge_heave.acceleration: f64",
            "checks[].input_motion.hinge_heave.displacement: f64",
            "checks[].input_motion.hinge_heave.velocity: f64",
            "checks[].kinematics.acceleration[]: null",
            "checks[].kinematics.acceleration[]: u64",
            "checks[].kinematics.acceleration[][]: f64",
            "checks[].kinematics.displacement[]: null",
            "checks[].kinematics.displacement[]: u64",
            "checks[].kinematics.displacement[][]: f64",
            "checks[].kinematics.velocity[]: null",
            "checks[].kinematics.velocity[]: u64",
            "checks[].kinematics.velocity[][]: f64",
            "checks[].last_forces.lower: f64",
            "checks[].last_forces.upper: f64",
            "checks[].max_external_work: f64",
            "checks[].max_residual: f64",
            "checks[].max_strain_energy: f64",
            "checks[].motion.clamp_heave.acceleration: f64",
            "checks[].motion.clamp_heave.displacement: f64",
            "checks[].motion.clamp_heave.velocity: f64",
            "checks[].motion.clamp_rotation.acceleration: f64",
            "checks[].motion.clamp_rotation.displacement: f64",
            "checks[].motion.clamp_rotation.velocity: f64",
            "checks[].motion.hinge_heave.acceleration: f64",
            "checks[].motion.hinge_heave.displacement: f64",
            "checks[].motion.hinge_heave.velocity: f64",
            "checks[].motion_ns: u64",
            "checks[].output_ns: u64",
            "checks[].peak_times.contact_force: f64",
            "checks[].peak_times.lower_clamp_bending_stress: f64",
            "checks[].peak_times.lower_clamp_shear_stress: f64",
            "checks[].peak_times.lower_tip_deflection: f64",
            "checks[].peak_times.upper_contact_bending_stress: f64",
            "checks[].range.lower_deflection.position: null",
            "checks[].range.lower_deflection.time: f64",
            "checks[].range.lower_deflection.value: f64",
            "checks[].range.lower_rotation.position: null",
            "checks[].range.lower_rotation.time: f64",
            "checks[].range.lower_rotation.value: f64",
            "checks[].range.upper_deflection.position: null",
            "checks[].range.upper_deflection.time: f64",
            "checks[].range.upper_deflection.value: f64",
            "checks[].range.upper_rotation.position: null",
            "checks[].range.upper_rotation.time: f64",
            "checks[].range.upper_rotation.value: f64",
            "checks[].result.contact: bool",
            "checks[].result.contact_force: f64",
            "checks[].result.contact_stress: f64",
            "checks[].result.energy.damping_dissipation: f64",
            "checks[].result.energy.external_work: f64",
            "checks[].result.energy.gravity_potential: f64",
            "checks[].result.energy.kinetic: f64",
            "checks[].result.energy.residual: f64",
            "checks[].result.energy.strain: f64",
            "checks[].result.lower_clamp_bending_stress: f64",
            "checks[].result.lower_clamp_reaction_force: f64",
            "checks[].result.lower_clamp_reaction_moment: f64",
            "checks[].result.lower_clamp_shear_stress: f64",
            "checks[].result.lower_far_reaction_force: f64",
            "checks[].result.lower_far_reaction_moment: f64",
            "checks[].result.lower_support_displacement: f64",
            "checks[].result.lower_tip_deflection: f64",
            "checks[].result.lower_tip_velocity: f64",
            "checks[].result.peaks.contact_force: f64",
            "checks[].result.peaks.lower_clamp_bending_stress: f64",
            "checks[].result.peaks.lower_clamp_shear_stress: f64",
            "checks[].result.peaks.lower_tip_deflection: f64",
            "checks[].result.peaks.upper_contact_bending_stress: f64",
            "checks[].result.step: u64",
            "checks[].result.step_size: f64",
            "checks[].result.time: f64",
            "checks[].result.time_ns: u64",
            "checks[].result.upper_contact_bending_stress: f64",
            "checks[].result.upper_contact_deflection: f64",
            "checks[].result.upper_hinge_reaction_force: f64",
            "checks[].result.upper_support_displacement: f64",
            "checks[].result.upper_tip_deflection: f64",
            "checks[].result.upper_tip_velocity: f64",
            "checks[].step_level: u64",
            "checks[].upper_strain_at_peak: f64",
            "initialized: bool",
            "parameters.contact.area: f64",
            "parameters.contact.clearance: f64",
            "parameters.contact.damping: f64",
            "parameters.contact.elastic_modulus: f64",
            "parameters.contact.exponent: f64",
            "parameters.contact.law: f64",
            "parameters.contact.length: f64",
            "parameters.contact.stiffness: f64",
            "parameters.contact_position: f64",
            "parameters.damping_ratio: f64",
            "parameters.discretisation_tolerance: f64",
            "parameters.drop_height: f64",
            "parameters.energy_tolerance: f64",
            "parameters.gravity: f64",
            "parameters.impact_angular_velocity: f64",
            "parameters.impact_speed: f64",
            "parameters.lower.allowable_bending_stress: f64",
            "parameters.lower.allowable_shear_stress: f64",
            "parameters.lower.contact_position: f64",
            "parameters.lower.elastic_modulus: f64",
            "parameters.lower.elements: f64",
            "parameters.lower.kind: f64",
            "parameters.lower.length: f64",
            "parameters.lower.mass: f64",
            "parameters.lower.poisson_ratio: f64",
            "parameters.lower.second_moment: f64",
            "parameters.lower.section_modulus: f64",
            "parameters.lower.shear_area: f64",
            "parameters.lower.supports: f64",
            "parameters.lower.tip_mass: f64",
            "parameters.lower.yield_stress: f64",
            "parameters.method: f64",
            "parameters.modal_cutoff: f64",
            "parameters.rayleigh_alpha: f64",
            "parameters.rayleigh_beta: f64",
            "parameters.step_contact: f64",
            "parameters.step_free: f64",
            "parameters.stress_recovery: f64",
            "parameters.upper.allowable_bending_stress: f64",
            "parameters.upper.allowable_shear_stress: f64",
            "parameters.upper.elastic_modulus: f64",
            "parameters.upper.elements_beyond_contact: f64",
            "parameters.upper.elements_to_contact: f64",
            "parameters.upper.kind: f64",
            "parameters.upper.length: f64",
            "parameters.upper.mass: f64",
            "parameters.upper.poisson_ratio: f64",
            "parameters.upper.radius: f64",
            "parameters.upper.second_moment: f64",
            "parameters.upper.section_modulus: f64",
            "parameters.upper.shear_area: f64",
            "parameters.upper.yield_stress: f64",
            "run.contact_windows[].end: f64",
            "run.contact_windows[].start: f64",
            "run.dissipation_rate: f64",
            "run.envelope[]: f64",
            "run.envelope_times[]: f64",
            "run.first_contact.ended: bool",
            "run.first_contact.last_contact: f64",
            "run.first_contact.peaks.contact_force: f64",
            "run.first_contact.peaks.lower_clamp_bending_stress: f64",
            "run.first_contact.peaks.lower_clamp_shear_stress: f64",
            "run.first_contact.peaks.lower_tip_deflection: f64",
            "run.first_contact.peaks.upper_contact_bending_stress: f64",
            "run.first_contact.pending.contact_force: f64",
            "run.first_contact.pending.lower_clamp_bending_stress: f64",
            "run.first_contact.pending.lower_clamp_shear_stress: f64",
            "run.first_contact.pending.lower_tip_deflection: f64",
            "run.first_contact.pending.upper_contact_bending_stress: f64",
            "run.first_contact.window_start: f64",
            "run.forces.lower: f64",
            "run.forces.upper: f64",
            "run.gap: f64",
            "run.inertial_potential: f64",
            "run.initial_energy: f64",
            "run.input_forces.lower: f64",
            "run.input_forces.upper: f64",
            "run.input_motion.clamp_heave.acceleration: f64",
            "run.input_motion.clamp_heave.displacement: f64",
            "run.input_motion.clamp_heave.velocity: f64",
            "run.input_motion.clamp_rotation.acceleration: f64",
            "run.input_motion.clamp_rotation.displacement: f64",
            "run.input_motion.clamp_rotation.velocity: f64",
            "run.input_motion.hinge_heave.acceleration: f64",
            "run.input_motion.hinge_heave.displacement: f64",
            "run.input_motion.hinge_heave.velocity: f64",
            "run.kinematics.acceleration[]: null",
            "run.kinematics.acceleration[]: u64",
            "run.kinematics.acceleration[][]: f64",
            "run.kinematics.displacement[]: null",
            "run.kinematics.displacement[]: u64",
            "run.kinematics.displacement[][]: f64",
            "run.kinematics.velocity[]: null",
            "run.kinematics.velocity[]: u64",
            "run.kinematics.velocity[][]: f64",
            "run.last_forces.lower: f64",
            "run.last_forces.upper: f64",
            "run.max_external_work: f64",
            "run.max_residual: f64",
            "run.max_strain_energy: f64",
            "run.motion.clamp_heave.acceleration: f64",
            "run.motion.clamp_heave.displacement: f64",
            "run.motion.clamp_heave.velocity: f64",
            "run.motion.clamp_rotation.acceleration: f64",
            "run.motion.clamp_rotation.displacement: f64",
            "run.motion.clamp_rotation.velocity: f64",
            "run.motion.hinge_heave.acceleration: f64",
            "run.motion.hinge_heave.displacement: f64",
            "run.motion.hinge_heave.velocity: f64",
            "run.motion_ns: u64",
            "run.output_ns: u64",
            "run.peak_times.contact_force: f64",
            "run.peak_times.lower_clamp_bending_stress: f64",
            "run.peak_times.lower_clamp_shear_stress: f64",
            "run.peak_times.lower_tip_deflection: f64",
            "run.peak_times.upper_contact_bending_stress: f64",
            "run.range.lower_deflection.position: null",
            "run.range.lower_deflection.time: f64",
            "run.range.lower_deflection.value: f64",
            "run.range.lower_rotation.position: null",
            "run.range.lower_rotation.time: f64",
            "run.range.lower_rotation.value: f64",
            "run.range.upper_deflection.position: null",
            "run.range.upper_deflection.time: f64",
            "run.range.upper_deflection.value: f64",
            "run.range.upper_rotation.position: null",
            "run.range.upper_rotation.time: f64",
            "run.range.upper_rotation.value: f64",
            "run.result.contact: bool",
            "run.result.contact_force: f64",
            "run.result.contact_stress: f64",
            "run.result.energy.damping_dissipation: f64",
            "run.result.energy.external_work: f64",
            "run.result.energy.gravity_potential: f64",
            "run.result.energy.kinetic: f64",
            "run.result.energy.residual: f64",
            "run.result.energy.strain: f64",
            "run.result.lower_clamp_bending_stress: f64",
            "run.result.lower_clamp_reaction_force: f64",
            "run.result.lower_clamp_reaction_moment: f64",
            "run.result.lower_clamp_shear_stress: f64",
            "run.result.lower_far_reaction_force: f64",
            "run.result.lower_far_reaction_moment: f64",
            "run.result.lower_support_displacement: f64",
            "run.result.lower_tip_deflection: f64",
            "run.result.lower_tip_velocity: f64",
            "run.result.peaks.contact_force: f64",
            "run.result.peaks.lower_clamp_bending_stress: f64",
            "run.result.peaks.lower_clamp_shear_stress: f64",
            "run.result.peaks.lower_tip_deflection: f64",
            "run.result.peaks.upper_contact_bending_stress: f64",
            "run.result.step: u64",
            "run.result.step_size: f64",
            "run.result.time: f64",
            "run.result.time_ns: u64",
            "run.result.upper_contact_bending_stress: f64",
            "run.result.upper_contact_deflection: f64",
            "run.result.upper_hinge_reaction_force: f64",
            "run.result.upper_support_displacement: f64",
            "run.result.upper_tip_deflection: f64",
            "run.result.upper_tip_velocity: f64",
            "run.step_level: u64",
            "run.upper_strain_at_peak: f64",
            "sections.lower[].allowable_bending_stress: f64",
            "sections.lower[].allowable_shear_stress: f64",
            "sections.lower[].length: f64",
            "sections.lower[].mass_per_length: f64",
            "sections.lower[].second_moment: f64",
            "sections.lower[].section_modulus: f64",
            "sections.lower[].section_modulus_bottom: f64",
            "sections.lower[].shear_area: f64",
            "sections.upper[].allowable_bending_stress: f64",
            "sections.upper[].allowable_shear_stress: f64",
            "sections.upper[].length: f64",
            "sections.upper[].mass_per_length: f64",
            "sections.upper[].second_moment: f64",
            "sections.upper[].section_modulus: f64",
            "sections.upper[].section_modulus_bottom: f64",
            "sections.upper[].shear_area: f64",
            "start_time: f64",
        ];
        let mut snapshot = snapshot_at(50_000_000);
        assert!(!snapshot.run.contact_windows.is_empty(), "the pinned paths need a contact window");
        // A section with every optional field, so that each field's path is pinned.
        let section = SectionSpec {
            length: 4.0,
            second_moment: 0.003,
            section_modulus: 0.018,
            section_modulus_bottom: Some(0.02),
            shear_area: 0.0145,
            mass_per_length: 980.0,
            allowable_bending_stress: Some(533e6),
            allowable_shear_stress: Some(355e6),
        };
        snapshot.sections = Sections { upper: vec![section.clone()], lower: vec![section] };
        let mut found = std::collections::BTreeSet::new();
        paths(&serde_json::to_value(&snapshot).unwrap(), "", &mut found);
        let found: Vec<&str> = found.iter().map(String::as_str).collect();
        assert_eq!(
            (FORMAT_VERSION, found.as_slice()),
            (9, VERSION_9),
            "Snapshot's fields changed: bump FORMAT_VERSION and update the pinned list"
        );
    }
}
