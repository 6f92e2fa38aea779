//! Any bytes as the payload of a serialized FMU state behind a correct header (length and
//! CRC-32, as `src/fmi/state.rs` lays them out): reaches the MessagePack decoder, then what a
//! restore does with a state that decodes (its sections and parameters within the scenario limits,
//! `RunState::validate`, 1 ms of steps), for models of at most 32 elements a segment.
#![no_main]

use beam_impact::fmi::state::{scenario_of, Snapshot, FORMAT_VERSION, HEADER, MAGIC};
use beam_impact::record::NullRecorder;
use beam_impact::{Scenario, Simulation};
use libfuzzer_sys::fuzz_target;

/// The header of `src/fmi/state.rs`: magic, version u32, payload length u64, CRC-32 of bytes 0..20
/// and the payload.
fn seal(payload: &[u8]) -> Vec<u8> {
    let mut bytes = MAGIC.to_vec();
    bytes.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    let mut hasher = crc32fast::Hasher::new();
    hasher.update(&bytes);
    hasher.update(payload);
    bytes.extend_from_slice(&hasher.finalize().to_le_bytes());
    debug_assert_eq!(bytes.len(), HEADER);
    bytes.extend_from_slice(payload);
    bytes
}

fuzz_target!(|data: &[u8]| {
    let snapshot = match Snapshot::from_bytes(&seal(data)) {
        Ok(s) => s,
        Err(e) => {
            assert!(!e.to_string().contains('\n'));
            return;
        }
    };
    let Ok(scenario) = scenario_of(&Scenario::default(), &snapshot) else { return };
    let largest =
        scenario.upper.elements_to_contact.max(scenario.upper.elements_beyond_contact).max(scenario.lower.elements);
    if largest > 32 {
        return;
    }
    let Ok(mut sim) = Simulation::new(&scenario) else { return };
    if sim.restore(snapshot.run).is_ok() {
        let now = sim.state().result.time_ns;
        let _ = sim.advance_to(now.saturating_add(1_000_000), &mut NullRecorder, false);
    }
});
