//! Any bytes as the records of one uncompressed chunk, behind a correct CRC, in an otherwise valid
//! log: reaches the record parser and the message decoders, which the CRC hides from `log_file`.
//! Seeds: the decompressed chunks of a real log (`seeds.sh`), which define the channels.
#![no_main]

use std::path::Path;
use std::sync::OnceLock;

use beam_impact::replay::report::{read_log_bytes, summary_from_log};
use beam_impact::replay::safe_read::{crc32, op, MAGIC};
use beam_impact::{Scenario, Simulation};
use libfuzzer_sys::fuzz_target;

fn simulation() -> &'static Simulation {
    static SIMULATION: OnceLock<Simulation> = OnceLock::new();
    SIMULATION.get_or_init(|| Simulation::new(&Scenario::default()).expect("the default scenario builds"))
}

fn record(out: &mut Vec<u8>, opcode: u8, body: &[u8]) {
    out.push(opcode);
    out.extend_from_slice(&(body.len() as u64).to_le_bytes());
    out.extend_from_slice(body);
}

/// A log holding `records` as one uncompressed chunk (the same wrapping as tests/fuzz_support).
pub fn wrap(records: &[u8]) -> Vec<u8> {
    let mut log = MAGIC.to_vec();
    record(&mut log, op::HEADER, &[0; 8]);
    let mut chunk = vec![0u8; 16];
    chunk.extend_from_slice(&(records.len() as u64).to_le_bytes());
    chunk.extend_from_slice(&crc32(records).to_le_bytes());
    chunk.extend_from_slice(&0u32.to_le_bytes());
    chunk.extend_from_slice(&(records.len() as u64).to_le_bytes());
    chunk.extend_from_slice(records);
    record(&mut log, op::CHUNK, &chunk);
    record(&mut log, op::DATA_END, &[0; 4]);
    record(&mut log, op::FOOTER, &[0; 20]);
    log.extend_from_slice(MAGIC);
    log
}

fuzz_target!(|data: &[u8]| {
    match read_log_bytes(&wrap(data), Path::new("fuzz.mcap")) {
        Err(e) => assert!(!e.to_string().contains('\n')),
        Ok(log) => {
            assert!(log.problem.as_deref().is_none_or(|p| !p.contains('\n')));
            assert!(log.steps.windows(2).all(|w| w[0].step < w[1].step));
            let _ = log.scenario();
            let _ = summary_from_log(&log, simulation());
        }
    }
});
