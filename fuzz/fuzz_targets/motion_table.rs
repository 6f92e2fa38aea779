//! Any text as a support-motion CSV (`run --motion`, `[motion] file`, a log's `motion.csv`):
//! `MotionTable::parse` gives a table or one short line of error quoting no control character;
//! an accepted table holds only values within the support-motion bounds, round-trips through
//! `to_csv` (the log's attachment) and is evaluated anywhere without a panic.
#![no_main]

use beam_impact::model::motion_table::{MotionTable, MAX_QUOTED};
use beam_impact::model::support_motion::MOTION_LIMITS;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    match MotionTable::parse(text) {
        Err(e) => {
            assert!(!e.chars().any(char::is_control), "{e:?}");
            assert!(e.chars().count() <= 4 * MAX_QUOTED + 600, "{} characters", e.len());
        }
        Ok(table) => {
            for motion in &table.motions {
                for (v, limit) in motion.values().iter().zip(MOTION_LIMITS) {
                    assert!(v.abs() <= limit, "{v} beyond {limit}");
                }
            }
            assert_eq!(MotionTable::parse(&table.to_csv()).as_ref(), Ok(&table));
            let (first, last) = (table.times[0], table.times[table.times.len() - 1]);
            for t in [first, 0.5 * (first + last), last, last + 1.0] {
                let _ = table.motion_at(t);
            }
            let _ = table.mismatches();
            let _ = table.check_covers(first, last);
            let _ = table.changes(first, 1_000_000_000);
        }
    }
});
