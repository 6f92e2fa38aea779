//! A full disk under the FMU's MCAP log (issue 27; before, `doStep` returned Error and the
//! co-simulation stopped): the log is dropped with one warning through the FMI logger naming the
//! file and the reason, what was written stays `NAME.partial` (the recorder's rule for a log that
//! failed: `report` reads it as a log cut short; NAME is not written), and the co-simulation goes
//! on with OK and Warning statuses to the same outputs as a run without a log. A log that cannot
//! be completed at Terminate is a warning, not an error. FMI 2 and FMI 3.
//!
//! The full disk is a small tmpfs mounted in a private mount namespace around a child process
//! (`unshare --mount`: the mount ends with the child, whatever happens): this test binary run
//! again with `--exact fmi_full_disk::child` and `BEAM_IMPACT_FULL_DISK_CHILD=<case>`. Where that
//! cannot be done (not root, no `unshare`), the test prints why and passes.

use crate::fmi_common;

use std::ffi::c_int;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

use fmi_common::importer::{load, Fmu2, Fmu3, ERROR, OK, WARNING};

const CASE: &str = "BEAM_IMPACT_FULL_DISK_CHILD";
const DIR: &str = "BEAM_IMPACT_FULL_DISK_DIR";
/// The exit code of the wrapper when the tmpfs cannot be mounted (the test is skipped).
const NO_MOUNT: i32 = 77;

/// Runs `case` in a child process whose `DIR` is a tmpfs of `size` (mount's syntax, `64k`).
fn with_full_disk(case: &str, size: &str) {
    let dir = tempfile::tempdir().unwrap();
    let script = format!(
        "mount -t tmpfs -o size={size} beam-impact-full-disk \"$1\" || exit {NO_MOUNT}; exec \"$2\" --exact \
         fmi_full_disk::child --nocapture --test-threads=1"
    );
    let output = Command::new("unshare")
        .args(["--mount", "--propagation", "private", "sh", "-c", &script, "sh"])
        .arg(dir.path())
        .arg(std::env::current_exe().unwrap())
        .env(CASE, case)
        .env(DIR, dir.path())
        .output();
    let output = match output {
        Ok(output) => output,
        Err(e) => {
            eprintln!("fmi_full_disk::{case} skipped: cannot run unshare ({e})");
            return;
        }
    };
    let stderr = String::from_utf8_lossy(&output.stderr);
    if output.status.code() == Some(NO_MOUNT) || stderr.starts_with("unshare:") {
        eprintln!("fmi_full_disk::{case} skipped: no tmpfs can be mounted here (root in a private mount namespace is needed): {stderr}");
        return;
    }
    assert!(output.status.success(), "child {case} failed:\n{}\n{stderr}", String::from_utf8_lossy(&output.stdout));
    assert!(String::from_utf8_lossy(&output.stdout).contains("1 passed"), "the child ran no test");
}

/// Every real output, for comparisons bit for bit.
fn outputs() -> Vec<u32> {
    beam_impact::fmi::variables::table()
        .iter()
        .filter(|v| v.causality.name() == "output" && v.ty == beam_impact::fmi::variables::Type::Real)
        .map(|v| v.vr)
        .collect()
}

const STOP: f64 = 1.0;
const INTERVAL: f64 = 1e-2;

/// One FMI 2 run to [`STOP`] with `log_path`: the statuses of every doStep, then Terminate's;
/// the outputs; the instance.
fn fmi2_run(log_path: &Path) -> (Vec<c_int>, c_int, Vec<f64>, Fmu2) {
    let fmu = Fmu2::new(&load());
    assert_eq!(fmu.setup(0.0, Some(STOP)), OK);
    assert_eq!(fmu.set_string("log.path", log_path.to_str().unwrap()), OK);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.call0("fmi2ExitInitializationMode"), OK, "{}", fmu.log.text());
    let steps = (STOP / INTERVAL).round() as u64;
    let statuses: Vec<c_int> = (0..steps)
        .map(|n| {
            let (t, next) = (n as f64 * INTERVAL, if n + 1 == steps { STOP } else { (n + 1) as f64 * INTERVAL });
            fmu.do_step(t, next - t)
        })
        .collect();
    let values = fmu.get_reals(&outputs()).1;
    let terminated = fmu.call0("fmi2Terminate");
    (statuses, terminated, values, fmu)
}

/// [`fmi2_run`] through FMI 3.
fn fmi3_run(log_path: &Path) -> (Vec<c_int>, c_int, Vec<f64>, Fmu3) {
    let fmu = Fmu3::try_new(&load(), None, false).0.unwrap();
    assert_eq!(fmu.set_string("log.path", log_path.to_str().unwrap()), OK);
    assert_eq!(fmu.initialize_until(Some(STOP)), OK, "{}", fmu.log.text());
    let steps = (STOP / INTERVAL).round() as u64;
    let statuses: Vec<c_int> = (0..steps)
        .map(|n| {
            let (t, next) = (n as f64 * INTERVAL, if n + 1 == steps { STOP } else { (n + 1) as f64 * INTERVAL });
            fmu.do_step(t, next - t).0
        })
        .collect();
    let values = fmu.get_reals(&outputs()).1;
    let terminated = fmu.call0("fmi3Terminate");
    (statuses, terminated, values, fmu)
}

/// What a run whose log met the full disk must show against the same run without a log: no
/// error; every doStep as the run without a log returned, except the one that dropped the log
/// (a warning), with the steps after it going on; one warning naming the file and the disk's
/// error; the outputs bit for bit; NAME not written and what was written left as NAME.partial.
fn check_dropped(
    log: &Path,
    (statuses, terminated, values, text): (Vec<c_int>, c_int, Vec<f64>, String),
    (reference, reference_terminated, reference_values): (Vec<c_int>, c_int, Vec<f64>),
) {
    assert!(!statuses.contains(&ERROR), "a doStep returned Error: {statuses:?}\n{text}");
    assert_eq!(terminated, reference_terminated, "{text}");
    let changed: Vec<usize> = (0..statuses.len()).filter(|&k| statuses[k] != reference[k]).collect();
    assert_eq!(changed.len(), 1, "statuses {statuses:?} against {reference:?}\n{text}");
    assert_eq!(statuses[changed[0]], WARNING);
    assert!(changed[0] + 1 < statuses.len(), "the log was dropped at the last step: nothing shows the run going on");
    let warnings: Vec<&str> = text.lines().filter(|l| l.contains("cannot be written")).collect();
    assert_eq!(warnings.len(), 1, "{text}");
    let warning = warnings[0];
    assert!(warning.starts_with("[logStatusWarning]"), "{warning}");
    assert!(warning.contains(&log.display().to_string()), "{warning}");
    assert!(warning.contains("No space left on device") && warning.contains("dropped"), "{warning}");
    assert!(warning.contains("the run goes on without a log"), "{warning}");
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
    assert_eq!(bits(&values), bits(&reference_values), "the outputs differ from the run without a log");
    let partial = beam_impact::record::output::partial_path(log);
    assert!(!log.exists(), "{} was written", log.display());
    assert!(partial.is_file(), "{} is not left", partial.display());
    assert!(warning.contains(&partial.display().to_string()), "{warning}");
}

fn full_disk_dir() -> PathBuf {
    PathBuf::from(std::env::var_os(DIR).expect("the full disk's folder"))
}

/// The child side: runs in the private mount namespace with the tmpfs at `$BEAM_IMPACT_FULL_DISK_DIR`.
#[test]
fn child() {
    let Ok(case) = std::env::var(CASE) else { return };
    let dir = full_disk_dir();
    let none = Path::new("");
    match case.as_str() {
        "fmi2-steps" => {
            let log = dir.join("fmi2.mcap");
            let (statuses, terminated, values, fmu) = fmi2_run(&log);
            let (reference, reference_terminated, reference_values, reference_fmu) = fmi2_run(none);
            assert!(reference.iter().all(|&s| s == OK), "{}", reference_fmu.log.text());
            check_dropped(
                &log,
                (statuses, terminated, values, fmu.log.text()),
                (reference, reference_terminated, reference_values),
            );
        }
        "fmi3-steps" => {
            let log = dir.join("fmi3.mcap");
            let (statuses, terminated, values, fmu) = fmi3_run(&log);
            let (reference, reference_terminated, reference_values, reference_fmu) = fmi3_run(none);
            assert!(reference.iter().all(|&s| s == OK), "{}", reference_fmu.log.text());
            check_dropped(
                &log,
                (statuses, terminated, values, fmu.log.text()),
                (reference, reference_terminated, reference_values),
            );
        }
        // The disk fills between the last doStep and Terminate: the log cannot be completed.
        "terminate" => {
            let log = dir.join("terminate.mcap");
            let fmu = Fmu2::new(&load());
            assert_eq!(fmu.set_string("log.path", log.to_str().unwrap()), OK);
            assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
            assert_eq!(fmu.do_step(0.0, INTERVAL), OK, "{}", fmu.log.text());
            let mut filler = std::fs::File::create(dir.join("filler")).unwrap();
            let block = vec![0x5a_u8; 64 * 1024];
            let full = loop {
                if let Err(e) = filler.write_all(&block) {
                    break e;
                }
            };
            assert_eq!(full.raw_os_error(), Some(28), "the disk is full: {full}");
            let peak = fmu.get("peak.lower.tip_deflection");
            assert_eq!(fmu.call0("fmi2Terminate"), WARNING, "{}", fmu.log.text());
            let text = fmu.log.text();
            let warning = text.lines().find(|l| l.contains("cannot be completed")).unwrap_or_else(|| panic!("{text}"));
            assert!(warning.starts_with("[logStatusWarning]"), "{warning}");
            assert!(warning.contains("No space left on device"), "{warning}");
            assert!(!text.contains("[logStatusError]"), "{text}");
            assert!(!log.exists() && beam_impact::record::output::partial_path(&log).is_file());
            // The results stand: the outputs are read after Terminate as before it.
            assert_eq!(fmu.get("peak.lower.tip_deflection"), peak);
        }
        other => panic!("unknown case {other}"),
    }
}

/// FMI 2: a 64 KiB disk fills within the first second of the paper run's log.
#[test]
fn a_full_disk_drops_the_fmi2_log_and_the_run_goes_on() {
    with_full_disk("fmi2-steps", "64k");
}

/// FMI 3: the same through fmi3DoStep.
#[test]
fn a_full_disk_drops_the_fmi3_log_and_the_run_goes_on() {
    with_full_disk("fmi3-steps", "64k");
}

/// A log that cannot be completed at Terminate (the disk filled after the last step): Terminate
/// returns Warning with the reason, not Error.
#[test]
fn a_log_that_cannot_be_completed_at_terminate_is_a_warning() {
    with_full_disk("terminate", "8m");
}
