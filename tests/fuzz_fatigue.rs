//! Issue 44: the stress history of `beam-impact fatigue` on any text, and the counting and the
//! damage on any accepted history: one short line of error (no control character, at most the
//! offending cell quoted) or cycles and a damage that are finite and non-negative, never a panic.
//!
//! Goal: seeded mutations of real histories (cells replaced by hostile literals, lines deleted,
//! duplicated and swapped, byte-level mutations) and random bytes; a few of them through the
//! command (exit code 0 or 2, at most one line on standard error). `BEAM_IMPACT_FUZZ_ITERATIONS`
//! sets the number of mutations.

use crate::fuzz_support;

use beam_impact::fatigue::history::{StressHistory, MAX_STRESS_PA};
use beam_impact::fatigue::summary::HistoryFatigue;
use beam_impact::fatigue::{count, SnCurve, SnOptions};
use beam_impact::model::motion_table::MAX_QUOTED;
use fuzz_support::{iterations, mutate, Rng};

const LITERALS: &[&str] = &[
    "1e308",
    "-1e308",
    "1e12",
    "-1e12",
    "1.0000001e12",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "infinity",
    "0",
    "-0.0",
    "5e-324",
    "2.2e-308",
    "0.1",
    "-1e9",
    "",
    " ",
    "\"1\"",
    "1_0",
    "\u{661}",
    "0x10",
    "\u{1b}[2J",
    "\0\0",
    "1,2",
    "#",
    "time",
    "time,time",
    "\u{feff}",
];

/// The seeds: the ASTM example, a two-column history with plateaus, a long oscillation.
fn seeds() -> Vec<String> {
    let mut long = String::from("time,a,b\n");
    for i in 0..200 {
        let t = i as f64 * 1e-3;
        long += &format!("{t},{},{}\n", (i as f64 * 0.7).sin() * 1e8, ((i * 37) % 11) as f64 * 1e7);
    }
    vec![
        "time,sigma\n0,-2\n1,1\n2,-3\n3,5\n4,-1\n5,3\n6,-4\n7,4\n8,-2\n".into(),
        "# plateaus\ntime,\"upper\", lower\n0,0,1e6\n0.5,1e6,1e6\n1,1e6,1e6\n1.5,-2e6,0\n2,-2e6,3e6\n".into(),
        long,
    ]
}

/// Parses `text`, counts and sums what it accepts; returns whether it was accepted.
fn check(name: &str, text: &str, curve: &SnCurve) -> bool {
    match StressHistory::parse(text) {
        Err(e) => {
            assert!(!e.chars().any(char::is_control), "{name}: a control character in {e:?}");
            assert!(e.chars().count() <= 4 * MAX_QUOTED + 600, "{name}: {} characters of error", e.len());
            false
        }
        Ok(history) => {
            let options = SnOptions { scf: 20.0, thickness_m: Some(1.0), design_fatigue_factor: 10.0 };
            let doc = HistoryFatigue::new(&history, curve, &options);
            for column in &doc.columns {
                assert!(column.damage.is_finite() && column.damage >= 0.0, "{name}: damage {}", column.damage);
                for c in &column.cycles {
                    assert!(c.range.is_finite() && c.range <= 2.0 * MAX_STRESS_PA, "{name}: range {}", c.range);
                    assert!(c.mean.abs() <= MAX_STRESS_PA, "{name}: mean {}", c.mean);
                    assert!(c.count == 1.0 || c.count == 0.5);
                }
            }
            let _ = doc.table(40);
            serde_json::to_string(&doc).unwrap_or_else(|e| panic!("{name}: JSON {e}"));
            true
        }
    }
}

#[test]
fn seeded_mutations_and_random_bytes_never_panic() {
    let seeds = seeds();
    let curves = SnCurve::all();
    let mut rng = Rng(0x00FA_716E);
    let (mut accepted, mut refused) = (0, 0);
    for i in 0..iterations(4000) {
        let seed = rng.pick(&seeds).clone();
        let text = match i % 5 {
            3 => String::from_utf8_lossy(&mutate(seed.as_bytes(), &mut rng)).into_owned(),
            4 => {
                let bytes: Vec<u8> = (0..rng.below(300)).map(|_| rng.next_u64() as u8).collect();
                String::from_utf8_lossy(&bytes).into_owned()
            }
            _ => fuzz_support::mutate_csv(&seed, LITERALS, &mut rng),
        };
        if check(&format!("mutation {i}"), &text, rng.pick(&curves)) {
            accepted += 1;
        } else {
            refused += 1;
        }
    }
    // Both sides reached: the mutator is neither only harmless nor only fatal.
    assert!(accepted > 0 && refused > 0, "accepted {accepted}, refused {refused}");
}

/// The counting alone on hostile reversals (what a run's stations hand it, unchecked): extreme,
/// subnormal and equal neighbours give finite ranges where the inputs are finite, and no panic.
#[test]
fn counting_hostile_reversals_never_panics() {
    let mut rng = Rng(0x00C0_FFEE);
    let values = [0.0, -0.0, 5e-324, -5e-324, 1e12, -1e12, 1.0, -1.0, 1e-300, 7.0];
    for _ in 0..iterations(2000) {
        let reversals: Vec<f64> = (0..rng.below(60)).map(|_| *rng.pick(&values)).collect();
        let cycles = count(&reversals);
        let halves: f64 = cycles.iter().map(|c| 2.0 * c.count).sum();
        assert_eq!(halves, reversals.len().saturating_sub(1) as f64);
        assert!(cycles.iter().all(|c| c.range.is_finite() && c.range >= 0.0));
    }
}

/// Through the command: random bytes and mutated histories exit 0 or 2, with at most one line on
/// standard error.
#[test]
fn the_command_on_hostile_files_exits_0_or_2_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let seeds = seeds();
    let mut rng = Rng(0x0BAD_F11E);
    for i in 0..40 {
        let bytes = if i % 2 == 0 {
            (0..rng.below(2000)).map(|_| rng.next_u64() as u8).collect()
        } else {
            let seed = rng.pick(&seeds).clone();
            fuzz_support::mutate_csv(&seed, LITERALS, &mut rng).into_bytes()
        };
        let path = dir.path().join(format!("h{i}.csv"));
        std::fs::write(&path, &bytes).unwrap();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact"))
            .args(["fatigue", path.to_str().unwrap(), "--curve", "F-seawater-cp"])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(matches!(out.status.code(), Some(0 | 2)), "{i}: {:?} {stderr}", out.status);
        assert!(stderr.lines().count() <= 1, "{i}: {stderr}");
    }
}
