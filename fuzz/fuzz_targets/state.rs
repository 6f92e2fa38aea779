//! Any bytes as a serialized FMU state: `Snapshot::from_bytes` (magic, version, length, checksum,
//! then the MessagePack payload).
#![no_main]

use beam_impact::fmi::state::Snapshot;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Err(e) = Snapshot::from_bytes(data) {
        assert!(!e.to_string().contains('\n'));
    }
});
