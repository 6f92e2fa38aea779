//! Issue 27: the support-motion CSV (`run --motion`, a scenario's `[motion] file`, a log's
//! `motion.csv`) on any text: a table within the support-motion bounds or one short line of
//! error quoting at most the offending cell (no control character, nothing of a first line that
//! is not a motion header), never a panic; what it accepts round-trips through `to_csv` (the
//! log's attachment) and is evaluated anywhere without a panic.
//!
//! Goal: replay `tests/corpus/motion/` (and the cargo-fuzz corpus `fuzz/corpus/motion_table/`
//! when present) and seeded mutations of real motion files (the vessel example, hand-made
//! tables): cells replaced by hostile literals, lines deleted, duplicated and swapped, columns
//! dropped, and byte-level mutations. `BEAM_IMPACT_FUZZ_ITERATIONS` sets the number of mutations.

use crate::fuzz_support;

use beam_impact::model::motion_table::{MotionTable, MAX_QUOTED};
use beam_impact::model::support_motion::MOTION_LIMITS;
use fuzz_support::{corpus_dir, corpus_files, iterations, mutate, Rng};

const LITERALS: &[&str] = &[
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "0",
    "-0.0",
    "5e-324",
    "0.1",
    "0.1000001",
    "-0.1",
    "100",
    "100.5",
    "1e9",
    "2e9",
    "",
    " ",
    "\"1\"",
    "1_0",
    "\u{661}",
    "0x10",
    "\u{1b}[2J",
    "\0\0\0",
    "1,2",
    "#",
    "time",
];

/// The seeds: the vessel example's first 40 lines, and small tables of each support.
fn seeds() -> Vec<String> {
    let example: Vec<&str> = include_str!("../examples/vessel-motion.csv").lines().take(40).collect();
    vec![
        example.join("\n"),
        "time,upper.hinge_heave,upper.hinge_heave_velocity,upper.hinge_heave_acceleration\n0,0,0,2\n0.5,0.25,1,2\n1,1,2,2\n"
            .into(),
        "# rotation\ntime,lower.clamp_rotation,lower.clamp_rotation_velocity,lower.clamp_rotation_acceleration\n\
         0,0,0.01,0\n1,0.01,0.01,0\n2,0.02,0.01,0\n"
            .into(),
    ]
}

/// Parses `text` and checks what it gives; returns whether it was accepted.
fn check(name: &str, text: &str) -> bool {
    match MotionTable::parse(text) {
        Err(e) => {
            assert!(!e.chars().any(char::is_control), "{name}: a control character in {e:?}");
            assert!(e.chars().count() <= 4 * MAX_QUOTED + 600, "{name}: {} characters of error", e.len());
            false
        }
        Ok(table) => {
            for motion in &table.motions {
                for (v, limit) in motion.values().iter().zip(MOTION_LIMITS) {
                    assert!(v.abs() <= limit, "{name}: {v} accepted beyond {limit}");
                }
            }
            let again = MotionTable::parse(&table.to_csv()).unwrap_or_else(|e| panic!("{name}: to_csv: {e}"));
            assert_eq!(again, table, "{name}: round trip through to_csv");
            let (first, last) = (table.times[0], table.times[table.times.len() - 1]);
            for t in [first, 0.5 * (first + last), last, last + 1.0] {
                assert!(table.motion_at(t).values().iter().all(|v| v.is_finite()), "{name}: motion at {t}");
            }
            let _ = table.mismatches();
            let _ = table.check_covers(first, last);
            let _ = table.changes(first, 1_000_000_000);
            true
        }
    }
}

#[test]
fn the_committed_corpus_replays() {
    let mut files = corpus_files("motion");
    assert!(!files.is_empty());
    let campaign = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/motion_table");
    if let Ok(entries) = std::fs::read_dir(campaign) {
        files.extend(
            entries.flatten().filter_map(|e| Some((e.path().display().to_string(), std::fs::read(e.path()).ok()?))),
        );
    }
    for (name, bytes) in files {
        if let Ok(text) = std::str::from_utf8(&bytes) {
            check(&name, text);
        }
    }
}

#[test]
fn seeded_mutations_of_motion_files_never_panic_and_stay_within_bounds() {
    let seeds = seeds();
    let mut rng = Rng(0x00E7_AB1E);
    let (mut accepted, mut refused) = (0, 0);
    for i in 0..iterations(4000) {
        let seed = rng.pick(&seeds).clone();
        let text = if i % 4 == 3 {
            String::from_utf8_lossy(&mutate(seed.as_bytes(), &mut rng)).into_owned()
        } else {
            fuzz_support::mutate_csv(&seed, LITERALS, &mut rng)
        };
        if check(&format!("mutation {i}"), &text) {
            accepted += 1;
        } else {
            refused += 1;
        }
    }
    // Both sides reached: the mutator is neither only harmless nor only fatal.
    assert!(accepted > 0 && refused > 0, "accepted {accepted}, refused {refused}");
}

/// Writes `tests/corpus/motion/` (the seeds and hostile files) and the cargo-fuzz seeds:
/// `cargo test --release --test integration -- --ignored fuzz_motion_table::write_corpus`.
#[test]
#[ignore]
fn write_corpus() {
    let dir = corpus_dir("motion");
    let fuzz = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/motion_table");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::create_dir_all(&fuzz).unwrap();
    let heave = "time,upper.hinge_heave,upper.hinge_heave_velocity,upper.hinge_heave_acceleration\n";
    let mut files: Vec<(String, String)> =
        seeds().into_iter().enumerate().map(|(i, s)| (format!("seed-{i}.csv"), s)).collect();
    files.extend([
        ("shadow-first-line.csv".into(), "root:$6$salt$hash:19000:0:99999:7:::\n".into()),
        ("environ.csv".into(), "PATH=/bin\0HOME=/root\0SECRET=x\0".into()),
        ("nul-cell.csv".into(), format!("{heave}0,0,0,{}\n", "\0".repeat(5000))),
        ("escape-in-header.csv".into(), "time,\u{1b}]0;owned\u{7}\n".into()),
        (
            "rotation-1.5-rad.csv".into(),
            "time,lower.clamp_rotation,lower.clamp_rotation_velocity,lower.clamp_rotation_acceleration\n0,1.5,0,0\n"
                .into(),
        ),
        ("heave-acceleration-1e5.csv".into(), format!("{heave}0,0,0,1e5\n")),
        ("times-decreasing.csv".into(), format!("{heave}1,0,0,0\n0,0,0,0\n")),
        ("time-1e300.csv".into(), format!("{heave}1e300,0,0,0\n")),
        ("one-field-short.csv".into(), format!("{heave}0,0,0\n")),
        ("empty.csv".into(), String::new()),
    ]);
    for (name, text) in files {
        std::fs::write(dir.join(&name), &text).unwrap();
        std::fs::write(fuzz.join(&name), &text).unwrap();
    }
}
