//! The default `log.path` (issue 8 item 4, issue 41 item 2): every instance with default
//! parameters records every step to a new file `BeamImpact-<instance>-<UTC time>-<n>.mcap` in the
//! user's log folder (`$XDG_STATE_HOME/beam-impact/logs`, else `~/.local/state/beam-impact/logs`),
//! never in the working directory and never one another's; two instances in one process and two
//! processes run side by side; serial runs never overwrite a log; a folder that cannot be written
//! is a warning and no log; an instance name that is a path (Ecos's) names the log by its last
//! component.
//!
//! The environment and the working directory are per process, so each case runs in a child
//! process: this test binary run again with `--exact fmi_default_log::child` and
//! `BEAM_IMPACT_LOG_CHILD=<case>`, in a temporary folder with `XDG_STATE_HOME` inside it (the
//! tests never write to the real home). The child drives the FMU through the C API (libloading)
//! and asserts; the parent checks the folders.

use crate::fmi_common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use beam_impact::fmi::instance::{file_name_part, log_name_part, timestamp, unique_log, DEFAULT_LOG_PATH};
use fmi_common::importer::{load, Fmu2, Fmu3, OK, WARNING};

const CASE: &str = "BEAM_IMPACT_LOG_CHILD";

/// The child runs in `dir` with `XDG_STATE_HOME` = `dir/state`: its default logs go to
/// [`log_dir`]`(dir)`.
fn spawn(case: &str, dir: &Path) -> std::process::Child {
    spawn_with(case, dir, &[("XDG_STATE_HOME", dir.join("state").as_os_str())])
}

fn spawn_with(case: &str, dir: &Path, env: &[(&str, &std::ffi::OsStr)]) -> std::process::Child {
    let mut command = Command::new(std::env::current_exe().unwrap());
    for (key, value) in env {
        command.env(key, value);
    }
    command
        .args(["--exact", "fmi_default_log::child", "--nocapture", "--test-threads=1"])
        .env(CASE, case)
        .current_dir(dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap()
}

fn check(output: Output, case: &str) {
    assert!(
        output.status.success(),
        "child {case} failed:\n{}\n{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}

fn run_child(case: &str, dir: &Path) {
    check(spawn(case, dir).wait_with_output().unwrap(), case);
    assert!(logs(dir).is_empty(), "{case}: a log in the working directory: {:?}", logs(dir));
}

/// Where the children of [`spawn`] in `dir` write their default logs.
fn log_dir(dir: &Path) -> PathBuf {
    dir.join("state").join("beam-impact").join("logs")
}

/// The `.mcap` files in `dir`, sorted (none if there is no such folder).
fn logs(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Vec::new() };
    let mut found: Vec<PathBuf> =
        entries.map(|e| e.unwrap().path()).filter(|p| p.extension().is_some_and(|e| e == "mcap")).collect();
    found.sort();
    found
}

/// Each log is complete, starts at step 0 (or `first_step`) and holds the steps of 0.05 s.
fn assert_complete(paths: &[PathBuf]) {
    for path in paths {
        let name = path.file_name().unwrap().to_str().unwrap();
        assert!(name.starts_with("BeamImpact-") && name.ends_with(".mcap"), "{name}");
        let log = beam_impact::replay::report::read_log(path).unwrap();
        assert!(log.complete, "{name}: {:?}", log.problem);
        assert!(log.steps.last().unwrap().time >= 0.049, "{name}: {:?}", log.steps.last());
    }
}

/// One FMI 2 instance named `name` with default parameters: initialize, 0.05 s, terminate.
/// Returns where the FMU said the log went.
fn default_run_fmi2(name: &str) -> PathBuf {
    let fmu = Fmu2::new_named(&load(), name);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    fmu.run(0.0, 0.05, 1e-2);
    assert_eq!(fmu.call0("fmi2Terminate"), OK, "{}", fmu.log.text());
    announced(&fmu.log.text())
}

/// The path in the logEvents line "MCAP log of the run: <path> (log.path is the default ...".
fn announced(log: &str) -> PathBuf {
    let line = log
        .lines()
        .find(|l| l.starts_with("[logEvents] MCAP log of the run: "))
        .unwrap_or_else(|| panic!("no line says where the log went: {log}"));
    let rest = line.trim_start_matches("[logEvents] MCAP log of the run: ");
    assert!(rest.contains("(log.path is the default \"BeamImpact.mcap\": a new file per instance and run)"), "{line}");
    PathBuf::from(rest.split(" (log.path").next().unwrap())
}

/// The child side: what each case runs in its own process and working directory.
#[test]
fn child() {
    let Ok(case) = std::env::var(CASE) else { return };
    let cwd = std::env::current_dir().unwrap();
    let expected_dir = std::env::var_os("XDG_STATE_HOME").map(|s| Path::new(&s).join("beam-impact").join("logs"));
    match case.as_str() {
        // Two instances in one process, both with default parameters and the same instance name
        // (libcosim aborted the process here), plus an FMI 3 one: three logs.
        "two-instances" => {
            let lib = load();
            let (a, b) = (Fmu2::new_named(&lib, "beam"), Fmu2::new_named(&lib, "beam"));
            let c = Fmu3::try_new(&lib, None, false).0.unwrap();
            assert_eq!(a.initialize(), OK, "{}", a.log.text());
            assert_eq!(b.initialize(), OK, "{}", b.log.text());
            assert_eq!(c.initialize(), OK, "{}", c.log.text());
            a.run(0.0, 0.05, 1e-2);
            b.run(0.0, 0.05, 1e-2);
            c.run(0.0, 0.05, 1e-2);
            for fmu in [&a, &b] {
                assert_eq!(fmu.call0("fmi2Terminate"), OK);
            }
            assert_eq!(c.call0("fmi3Terminate"), OK);
            let (pa, pb, pc) = (announced(&a.log.text()), announced(&b.log.text()), announced(&c.log.text()));
            assert!(pa != pb && pa != pc && pb != pc, "{pa:?} {pb:?} {pc:?}");
            for p in [&pa, &pb, &pc] {
                assert_eq!(Some(p.parent().unwrap()), expected_dir.as_deref(), "in the user's log folder, {cwd:?}");
                assert!(p.is_absolute() && p.is_file(), "{p:?}");
            }
            assert!(pc.file_name().unwrap().to_str().unwrap().starts_with("BeamImpact-beam3-"));
        }
        "one-instance" => {
            let path = default_run_fmi2("a run:with odd*chars");
            let name = path.file_name().unwrap().to_str().unwrap().to_string();
            assert!(name.starts_with("BeamImpact-a_run_with_odd_chars-"), "the instance name sanitised: {name}");
        }
        // Ecos names an instance after the FMU's file in its temporary folder: the log is named
        // after the last component, never after the folder.
        "path-named" => {
            let path = default_run_fmi2("/tmp/ecos/ssp_d27d578b-0203-4fe5/resources/BeamImpact.fmu");
            let name = path.file_name().unwrap().to_str().unwrap().to_string();
            assert!(name.starts_with("BeamImpact-BeamImpact-2"), "{name}");
        }
        // XDG_STATE_HOME relative (ignored, as the XDG specification says): HOME's .local/state.
        "home" => {
            let path = default_run_fmi2("beam");
            let home = std::env::var_os("HOME").unwrap();
            assert_eq!(path.parent().unwrap(), Path::new(&home).join(".local/state/beam-impact/logs"));
        }
        // The log folder cannot be created (the parent points XDG_STATE_HOME into /proc): a
        // warning from ExitInitializationMode, the reason logged, the run goes on without a log.
        "unwritable" => {
            let fmu = Fmu2::new(&load());
            assert_eq!(fmu.initialize(), WARNING, "{}", fmu.log.text());
            let log = fmu.log.text();
            assert!(
                log.contains("[logStatusWarning] log.path = \"BeamImpact.mcap\" (the default")
                    && log.contains("cannot create a log in /proc/")
                    && log.contains("the run goes on without an MCAP log"),
                "{log}"
            );
            fmu.run(0.0, 0.05, 1e-2);
            assert_eq!(fmu.call0("fmi2Terminate"), OK, "{}", fmu.log.text());
            let lib = load();
            let fmu3 = Fmu3::try_new(&lib, None, false).0.unwrap();
            assert_eq!(fmu3.initialize(), WARNING, "{}", fmu3.log.text());
        }
        // fmpy's restore flow with default parameters: the restored run logs to a new default
        // file, starting with the restored step.
        "restore" => {
            let lib = load();
            let first = Fmu2::new(&lib);
            assert_eq!(first.set_string("log.path", ""), OK);
            assert_eq!(first.initialize(), OK);
            first.run(0.0, 0.03, 1e-2);
            let state = first.get_state();
            let bytes = first.serialize(state);
            first.free_state(state);
            let second = Fmu2::new_named(&lib, "restored");
            let (status, state) = second.deserialize(&bytes);
            assert_eq!(status, OK);
            assert_eq!(second.set_state(state), OK, "{}", second.log.text());
            second.free_state(state);
            let path = announced(&second.log.text());
            second.run(0.03, 0.05, 1e-2);
            assert_eq!(second.call0("fmi2Terminate"), OK);
            let log = beam_impact::replay::report::read_log(&path).unwrap();
            assert!(log.complete, "{:?}", log.problem);
            let step = log.steps.first().unwrap();
            assert!(step.step > 0 && step.time <= 0.03 && step.time > 0.029, "{step:?}");
        }
        // A state of another scenario restored into a running instance with the default log:
        // the log of the first scenario is completed, the second goes on in a new default file.
        "switch" => {
            let lib = load();
            let other = Fmu2::new(&lib);
            assert_eq!(other.set_string("log.path", ""), OK);
            assert_eq!(other.set("drop_height", 0.8), OK);
            assert_eq!(other.initialize(), OK);
            other.run(0.0, 0.03, 1e-2);
            let state = other.get_state();
            let bytes = other.serialize(state);
            other.free_state(state);
            let fmu = Fmu2::new(&lib);
            assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
            fmu.run(0.0, 0.05, 1e-2);
            let first = announced(&fmu.log.text());
            fmu.log.clear();
            let (status, state) = fmu.deserialize(&bytes);
            assert_eq!(status, OK);
            assert_eq!(fmu.set_state(state), OK, "{}", fmu.log.text());
            fmu.free_state(state);
            let second = announced(&fmu.log.text());
            assert_ne!(first, second);
            fmu.run(0.03, 0.05, 1e-2);
            assert_eq!(fmu.call0("fmi2Terminate"), OK);
        }
        other => panic!("unknown case {other}"),
    }
}

#[test]
fn two_instances_in_one_process_write_their_own_logs_and_serial_runs_overwrite_none() {
    let dir = tempfile::tempdir().unwrap();
    run_child("two-instances", dir.path());
    let first = logs(&log_dir(dir.path()));
    assert_eq!(first.len(), 3, "{first:?}");
    assert_complete(&first);
    let contents: Vec<Vec<u8>> = first.iter().map(|p| std::fs::read(p).unwrap()).collect();
    // The same again in the same folder (within the same second, most likely): three new logs.
    run_child("two-instances", dir.path());
    let all = logs(&log_dir(dir.path()));
    assert_eq!(all.len(), 6, "{all:?}");
    assert_complete(&all);
    for (path, before) in first.iter().zip(&contents) {
        assert_eq!(&std::fs::read(path).unwrap(), before, "{} was overwritten", path.display());
    }
}

#[test]
fn two_processes_in_one_folder_write_their_own_logs() {
    let dir = tempfile::tempdir().unwrap();
    let children = [spawn("one-instance", dir.path()), spawn("one-instance", dir.path())];
    for child in children {
        check(child.wait_with_output().unwrap(), "one-instance");
    }
    assert!(logs(dir.path()).is_empty(), "a log in the working directory");
    let found = logs(&log_dir(dir.path()));
    assert_eq!(found.len(), 2, "{found:?}");
    assert_complete(&found);
}

#[test]
fn an_instance_named_after_a_temporary_path_names_its_log_after_the_fmu() {
    let dir = tempfile::tempdir().unwrap();
    run_child("path-named", dir.path());
    assert_eq!(logs(&log_dir(dir.path())).len(), 1);
}

#[test]
fn without_xdg_state_home_the_default_log_goes_under_home() {
    let dir = tempfile::tempdir().unwrap();
    let home = dir.path().join("home");
    let env = [("XDG_STATE_HOME", std::ffi::OsStr::new("relative/state")), ("HOME", home.as_os_str())];
    check(spawn_with("home", dir.path(), &env).wait_with_output().unwrap(), "home");
    assert_eq!(logs(&home.join(".local/state/beam-impact/logs")).len(), 1);
    assert!(logs(dir.path()).is_empty() && !dir.path().join("relative").exists());
}

#[test]
fn a_default_folder_that_cannot_be_written_is_a_warning_and_no_log() {
    // /proc takes no new folders, not even from root.
    let dir = tempfile::tempdir().unwrap();
    let env = [("XDG_STATE_HOME", std::ffi::OsStr::new("/proc/beam-impact-state"))];
    check(spawn_with("unwritable", dir.path(), &env).wait_with_output().unwrap(), "unwritable");
    assert!(logs(dir.path()).is_empty());
}

#[test]
fn a_state_restored_with_default_parameters_logs_to_a_new_default_file() {
    let dir = tempfile::tempdir().unwrap();
    run_child("restore", dir.path());
    assert_eq!(logs(&log_dir(dir.path())).len(), 1);
}

#[test]
fn another_scenario_restored_goes_on_in_a_new_default_log() {
    let dir = tempfile::tempdir().unwrap();
    run_child("switch", dir.path());
    let found = logs(&log_dir(dir.path()));
    assert_eq!(found.len(), 2, "{found:?}");
    assert_complete(&found);
}

#[test]
fn names_of_default_logs() {
    // The model descriptions' start value of log.path is the token that stands for the default.
    let table = beam_impact::fmi::variables::table();
    let log_path = table.iter().find(|v| v.name == "log.path").unwrap();
    assert_eq!(log_path.start.as_deref(), Some(DEFAULT_LOG_PATH));
    assert_eq!(file_name_part("beam"), "beam");
    assert_eq!(file_name_part("Model.instance-1_x"), "Model.instance-1_x");
    assert_eq!(file_name_part("a/b\\c d:é"), "a_b_c_d__");
    assert_eq!(file_name_part(""), "instance");
    assert_eq!(file_name_part(&"x".repeat(100)).len(), 64);
    assert_eq!(log_name_part("/tmp/ecos/ssp_1/resources/BeamImpact.fmu"), "BeamImpact");
    assert_eq!(log_name_part("C:\\Temp\\x\\gangway"), "gangway");
    assert_eq!(log_name_part("beam/"), "beam");
    assert_eq!(log_name_part("/"), "instance");
    assert_eq!(log_name_part("a run:with odd*chars"), "a_run_with_odd_chars");
    let at = |s: u64| timestamp(std::time::UNIX_EPOCH + std::time::Duration::from_secs(s));
    assert_eq!(at(0), "19700101T000000Z");
    assert_eq!(at(951_782_400), "20000229T000000Z");
    assert_eq!(at(1_709_251_199), "20240229T235959Z");
    assert_eq!(at(4_102_444_800), "21000101T000000Z");
    // Created with create_new: existing names are skipped, never reused.
    let dir = tempfile::tempdir().unwrap();
    let now = std::time::UNIX_EPOCH + std::time::Duration::from_secs(1_700_000_000);
    let first = unique_log(dir.path(), "i", now).unwrap();
    let second = unique_log(dir.path(), "i", now).unwrap();
    assert_eq!(first.file_name().unwrap(), "BeamImpact-i-20231114T221320Z-1.mcap");
    assert_eq!(second.file_name().unwrap(), "BeamImpact-i-20231114T221320Z-2.mcap");
    let err = unique_log(Path::new("/nonexistent-directory"), "i", now).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::NotFound);
}
