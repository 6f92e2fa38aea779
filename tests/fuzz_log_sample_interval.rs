//! Issue 41: the log's sample interval (`run --log-sample-interval`, Python's
//! `log_sample_interval`) on any number and any text: 0 (every internal step) or an interval
//! within its bounds, else one line naming the option and the value given, never a panic; and
//! the CLI refuses it before the run, without a log left behind.
//!
//! Goal: every f64 class (zero, signed zero, subnormals, the bounds and their neighbours, NaN,
//! infinities, huge and tiny values) and seeded random bit patterns (`BEAM_IMPACT_FUZZ_ITERATIONS`
//! sets how many), then hostile texts through the CLI.

use std::process::Command;

use crate::fuzz_support::{iterations, Rng};
use beam_impact::record::options::{sample_interval_ns, SAMPLE_INTERVAL_BOUNDS_NS};

/// The contract on one value: accepted within the bounds (or 0), else refused in one line.
fn check(seconds: f64) {
    let (low, high) = SAMPLE_INTERVAL_BOUNDS_NS;
    match sample_interval_ns("--log-sample-interval", seconds) {
        Ok(0) => assert_eq!(seconds, 0.0, "{seconds:e} read as every internal step"),
        Ok(ns) => {
            assert!((low..=high).contains(&ns), "{seconds:e} -> {ns} ns");
            assert!((ns as f64 * 1e-9 / seconds - 1.0).abs() < 1e-3, "{seconds:e} -> {ns} ns");
        }
        Err(message) => {
            assert!(!message.contains('\n') && message.len() < 200, "{message}");
            assert!(message.starts_with("--log-sample-interval must be 0"), "{message}");
            assert!(message.contains(" or between 1e-6 and 1 s, got "), "{message}");
            let given: f64 = message.rsplit("got ").next().unwrap().parse().unwrap();
            assert!(given == seconds || (given.is_nan() && seconds.is_nan()), "{message}");
        }
    }
}

#[test]
fn any_number_is_an_interval_within_bounds_or_one_line_of_refusal() {
    let (low, high) = SAMPLE_INTERVAL_BOUNDS_NS;
    let edges = [
        0.0,
        -0.0,
        5e-324,
        f64::MIN_POSITIVE,
        low as f64 * 1e-9,
        low as f64 * 1e-9 * (1.0 - 1e-12),
        0.99e-6,
        high as f64 * 1e-9,
        1.0000001,
        1e-4,
        -1e-4,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::MAX,
        -f64::MAX,
        1e300,
    ];
    edges.into_iter().for_each(check);
    assert_eq!(sample_interval_ns("x", 1e-4), Ok(100_000));
    assert_eq!(sample_interval_ns("x", 1.0), Ok(1_000_000_000));
    assert!(sample_interval_ns("x", 1e-7).is_err() && sample_interval_ns("x", 2.0).is_err());
    let mut rng = Rng(41);
    for _ in 0..iterations(20_000) {
        check(f64::from_bits(rng.next_u64()));
        // And values near the range, where the rounding to nanoseconds matters.
        check((rng.next_u64() % 3_000_000_000) as f64 * 1e-9 * 0.999_999);
    }
}

#[test]
fn the_cli_refuses_a_bad_interval_in_one_line_before_the_run() {
    let dir = tempfile::tempdir().unwrap();
    for text in ["-1e-4", "1e-9", "2", "nan", "inf", "fast", "", "0x10", "1e-4\u{1b}[2J"] {
        let log = dir.path().join("refused.mcap");
        let out = Command::new(env!("CARGO_BIN_EXE_beam-impact"))
            .args(["run", "--set", "duration=0.01", "--mcap"])
            .arg(&log)
            .arg(format!("--log-sample-interval={text}"))
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{text:?}: {stderr}");
        assert!(stderr.contains("log-sample-interval"), "{text:?}: {stderr}");
        assert!(!stderr.contains('\u{1b}'), "{text:?}: raw control characters echoed: {stderr:?}");
        assert!(!log.exists() && !dir.path().join("refused.mcap.partial").exists(), "{text:?}: a log was left");
    }
    // With --record-every, the dense output must be turned off.
    let out = Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .args([
            "run",
            "--set",
            "duration=0.01",
            "--mcap",
            "/dev/null",
            "--record-every",
            "5",
            "--log-sample-interval",
            "1e-4",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("--record-every 5 thins a log of every internal step"), "{stderr}");
}
