//! The `beam-impact` command as a user meets it: output, exit codes, one-line errors.

use std::process::Command;

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

/// No subcommand runs the paper scenario and prints the comparison with the paper.
#[test]
fn default_run_prints_the_paper_comparison() {
    let dir = tempfile::tempdir().unwrap();
    let out = beam_impact().arg("--no-mcap").current_dir(dir.path()).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    for needle in ["Table 1", "Table 2", "Table 3", "0.691", "longest separation", "steps: 9", "wall time"] {
        assert!(text.contains(needle), "missing {needle:?} in\n{text}");
    }
}

/// Issue 19 (quiet by default): the bare paper run printed two advisories about the paper's own
/// steps, which its user cannot act on; it prints only its verdict now, a line for each peak the
/// paper mesh gets wrong with what to do (issue 28 item 7).
#[test]
fn the_paper_run_prints_no_advisory_about_its_own_steps() {
    let dir = tempfile::tempdir().unwrap();
    let out = beam_impact().arg("--no-mcap").current_dir(dir.path()).output().unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(!stderr.contains("note:") && !stderr.contains("energy-safe"), "{stderr}");
    // The verdict alone: one line per peak the paper mesh gets wrong (tau_a, sigma_b, F_c).
    assert_eq!(stderr.lines().count(), 3, "the verdict alone: {stderr}");
    for line in stderr.lines() {
        assert!(
            line.starts_with(
                "beam-impact: warning: results not trusted: the paper mesh's peaks differ from the converged answer"
            ) && line.ends_with("run with `--set method=converged`"),
            "{stderr}"
        );
    }
}

/// A bad scenario: exit code 2, one line on stderr naming the field, no panic trace.
#[test]
fn bad_scenario_exits_2_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.toml");
    std::fs::write(&file, "[upper]\nlength = -3.0\n").unwrap();
    let out = beam_impact().args(["run", "--no-mcap"]).arg(&file).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("upper.length must be > 0 m, got -3"), "{stderr}");
    let out = beam_impact().args(["run", "--no-mcap", "/nonexistent/x.toml"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/x.toml"));
}

/// `scenario` prints a file, with units, that `run` accepts, and `--json` writes the summary.
#[test]
fn scenario_output_runs_and_json_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = beam_impact().arg("scenario").output().unwrap();
    assert!(out.status.success());
    let file = dir.path().join("s.toml");
    let text = String::from_utf8(out.stdout).unwrap();
    // Issue 19: each field's unit and meaning as a comment on its line (read back unchanged).
    for needle in
        ["drop_height = 0.567  # [m] Drop height", "elastic_modulus = 210000000000.0  # [Pa]", "tip_force = 0.0  # [N]"]
    {
        assert!(text.contains(needle), "{needle} in\n{text}");
    }
    let text = text.replace("duration = 3.0", "duration = 0.1");
    std::fs::write(&file, text).unwrap();
    let json = dir.path().join("r.json");
    let out = beam_impact().args(["run", "--no-mcap", "--json"]).arg(&json).arg(&file).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    // 0.1 s of the default scenario: 972 internal steps (the exact advance's, long in contact too).
    assert!(doc["summary"]["steps"].as_u64().unwrap() > 500);
    assert!(doc["summary"]["peaks"]["lower_tip_deflection"].as_f64().unwrap() > 0.1);
    // One name per quantity: the FMU's name beside the former key, the same value.
    assert_eq!(doc["summary"]["peaks"]["lower.tip_deflection"], doc["summary"]["peaks"]["lower_tip_deflection"]);
    assert_eq!(doc["summary"]["converged_peaks"]["contact.force"], doc["summary"]["converged_peaks"]["contact_force"]);
}

/// `report` on a file that is not an MCAP log: one line naming the file, exit code 2.
#[test]
fn report_on_a_foreign_file_is_a_one_line_error() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("notes.mcap");
    std::fs::write(&file, "hello\n").unwrap();
    let out = beam_impact().arg("report").arg(&file).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("notes.mcap") && stderr.contains("not an MCAP file"), "{stderr}");
}

/// An untrusted run (the paper's method and step pair on an undamped 0.2 m drop: its energy
/// residual blows up) warns on stderr, reports the verdict in `--json` (`quality`, also under
/// `summary.quality`), exits 0, and exits 3 with `--strict`. The bare paper run is not trusted
/// either (its mesh's sigma_b and tau_a are 7 % and 14 % off the converged answer) and exits 3
/// with `--strict`; a converged run of the paper scenario with `--strict` exits 0. The existing
/// JSON keys stay.
#[test]
fn untrusted_run_warns_reports_quality_and_exits_3_with_strict() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("undamped.toml");
    std::fs::write(
        &file,
        "method = \"paper\"\nlower.elements = 7\nupper.elements_to_contact = 7\nupper.elements_beyond_contact = 7\n\
         drop_height = 0.2\ndamping_ratio = 0.0\nstep_free = 5e-5\nstep_contact = 2.5e-5\n",
    )
    .unwrap();
    let json = dir.path().join("out.json");
    let out = beam_impact().args(["run", "--no-mcap", "--json"]).arg(&json).arg(&file).output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.contains("warning: results not trusted: energy residual"), "{stderr}");
    assert!(stderr.contains("step_free = 5e-5 s is stable but not energy-safe"), "{stderr}");
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let quality = &doc["quality"];
    assert_eq!(quality["trusted"], false, "{quality}");
    assert!(quality["energy_residual_fraction"].as_f64().unwrap() > 0.05, "{quality}");
    assert_eq!(quality["energy_tolerance"], 0.01);
    assert!(!quality["reasons"].as_array().unwrap().is_empty());
    assert_eq!(&doc["summary"]["quality"], quality);
    for key in ["peaks", "peak_times", "contact_windows", "max_energy_residual", "energy_method", "modes"] {
        assert!(doc["summary"].get(key).is_some(), "existing key {key} kept");
    }
    let out = beam_impact().args(["run", "--no-mcap", "--strict"]).arg(&file).output().unwrap();
    assert_eq!(out.status.code(), Some(3));
    let out = beam_impact().args(["run", "--no-mcap", "--strict"]).output().unwrap();
    assert_eq!(out.status.code(), Some(3), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stderr).contains("differ from the converged answer"));
    let out = beam_impact().args(["run", "--no-mcap", "--strict", "--set", "duration=1"]).output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
}

/// Scenario files take `"auto"` time steps (the default) and a named stress recovery; the JSON
/// reports the steps used and the first sustained contact's peaks beside the whole run's.
#[test]
fn auto_steps_and_stress_recovery_from_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("user.toml");
    std::fs::write(&file, "step_free = \"auto\"\nstress_recovery = \"left\"\nduration = 1.0\n").unwrap();
    let json = dir.path().join("out.json");
    let out = beam_impact().args(["run", "--no-mcap", "--json"]).arg(&json).arg(&file).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(doc["scenario"]["step_free"], "auto");
    assert_eq!(doc["scenario"]["stress_recovery"], "left");
    // The converged rung's energy-safe step: 1 / omega_max of its kept modes.
    assert_eq!(doc["summary"]["time_steps"]["free"], 2.3601e-5);
    let first = doc["summary"]["first_contact_peaks"]["upper_contact_bending_stress"].as_f64().unwrap();
    let whole = doc["summary"]["peaks"]["upper_contact_bending_stress"].as_f64().unwrap();
    assert!(first > 1e8 && first <= whole, "{first} vs {whole}");
    assert!((doc["summary"]["first_contact_end"].as_f64().unwrap() - 0.75).abs() < 0.01);
    std::fs::write(&file, "stress_recovery = \"middle\"\n").unwrap();
    let out = beam_impact().args(["run", "--no-mcap"]).arg(&file).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("middle"));
}

/// Paths from strangers (issue 9): `--json` and `--mcap` on one file is refused; an output that
/// is a symbolic link is refused without touching the link's target; a FIFO as scenario or log
/// is refused at once instead of blocking; `-` reads the scenario from standard input and writes
/// the JSON to standard output; `/dev/null` works as either output.
#[test]
fn output_and_input_paths_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = beam_impact().args(["run", "--mcap", "x.out", "--json", "x.out"]).current_dir(d).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--json and --mcap name the same file"));
    std::fs::write(d.join("target.txt"), "keep").unwrap();
    std::os::unix::fs::symlink(d.join("target.txt"), d.join("link.mcap")).unwrap();
    let out = beam_impact().args(["run", "--mcap", "link.mcap"]).current_dir(d).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("symbolic link"));
    assert_eq!(std::fs::read_to_string(d.join("target.txt")).unwrap(), "keep");
    assert!(std::process::Command::new("mkfifo").arg(d.join("fifo")).status().unwrap().success());
    for args in [vec!["run", "fifo", "--no-mcap"], vec!["run", "--mcap", "fifo"]] {
        let out = beam_impact().args(&args).current_dir(d).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("FIFO"), "{args:?}");
    }
    let mut child = beam_impact()
        .args(["run", "-", "--no-mcap", "--json", "-"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child.stdin.take().unwrap().write_all(b"drop_height = 0.3\nduration = 0.1\n").unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(doc["scenario"]["drop_height"], 0.3);
    let out = beam_impact().args(["run", "--mcap", "/dev/null", "--json", "/dev/null"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// `report log.mcap | head` (issue 11): the reader going away ends the report quietly, exit 0,
/// nothing on stderr, as `run` already does.
#[test]
fn report_into_a_closed_pipe_is_quiet() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("short.toml");
    std::fs::write(&scenario, "duration = 0.05\n").unwrap();
    let log = dir.path().join("short.mcap");
    let out = beam_impact().args(["run", "--mcap"]).arg(&log).arg(&scenario).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mut child = beam_impact()
        .arg("report")
        .arg(&log)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take()); // the reader closes before the report is written
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.stderr.is_empty(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// Issue 9: the log has a size cap (`--max-log-bytes`, 2 GiB by default): at the cap it ends as a
/// valid file with a warning, and the run goes on to its end unrecorded.
#[test]
fn the_log_stops_at_its_size_cap_and_the_run_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("capped.mcap");
    let json = dir.path().join("capped.json");
    let out = beam_impact()
        .args(["run", "--max-log-bytes", "1000000", "--mcap"])
        .arg(&log)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stderr).contains("reached its size cap of 1000000 bytes"));
    let size = std::fs::metadata(&log).unwrap().len();
    // The cap is checked at every flush (1000 steps, about 0.35 MB): one flush and the summary
    // beyond it at most.
    assert!((1_000_000..2_000_000).contains(&size), "{size} bytes");
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(doc["summary"]["time"], 3.0, "the run went on to its end");
    let out = beam_impact().arg("report").arg(&log).arg("--out").arg(dir.path().join("fig")).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // The report says the log stopped early, not "complete" (it compared a few ms with the paper
    // without a word).
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("status: STOPPED EARLY: the MCAP log") && text.contains("size cap"), "{text}");
    assert!(!text.contains("status: complete"), "{text}");
    let out = beam_impact().arg("report").arg(&log).args(["--csv", "-"]).output().unwrap();
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("size cap"), "{}", String::from_utf8_lossy(&out.stderr));
}

/// Issue 11: `run FILE.toml` logs to `FILE.mcap` beside it, so a user scenario never overwrites
/// the paper run's `paper.mcap` and two files never share a log.
#[test]
fn a_scenario_file_logs_beside_itself() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["a", "b"] {
        std::fs::write(dir.path().join(format!("{name}.toml")), "duration = 0.01\n").unwrap();
        let out = beam_impact().args(["run", &format!("{name}.toml")]).current_dir(dir.path()).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        assert!(dir.path().join(format!("{name}.mcap")).is_file());
    }
    assert!(!dir.path().join("paper.mcap").exists());
}

/// Issue 19: `damping` and `verify` take `--set` as `run` does (the same names, one line for a
/// bad one), and the change reaches the runs.
#[test]
fn damping_and_verify_take_set() {
    let text = |args: &[&str]| {
        let out = beam_impact().args(args).output().unwrap();
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        // The peaks, not the wall time.
        String::from_utf8(out.stdout)
            .unwrap()
            .lines()
            .filter(|l| !l.contains("wall time"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    for command in ["damping", "verify"] {
        let low = text(&[command, "--set", "duration=0.02", "--set", "drop_height=0.3"]);
        let high = text(&[command, "--set", "duration=0.02", "--set", "drop_height=1.5"]);
        assert_ne!(low, high, "{command}: --set drop_height changes the peaks");
        let out = beam_impact().args([command, "--set", "drop_hieght=1"]).output().unwrap();
        assert_eq!(out.status.code(), Some(2));
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert!(stderr.lines().count() == 1 && stderr.contains("drop_hieght"), "{stderr}");
    }
}

/// Issue 19 (report prints the trust verdict stored with the run) and issue 15 (the rungs used go
/// to the log): `run` stores its answer with the checks in the log (`answer.json`), the same
/// quality, design and rungs as `--json`, and `report` prints its verdict.
#[test]
fn the_log_stores_the_runs_answer_and_report_prints_its_verdict() {
    let dir = tempfile::tempdir().unwrap();
    for (settings, trusted) in [(vec!["--set", "duration=0.02"], true), (vec![], false)] {
        let log = dir.path().join("run.mcap");
        let json = dir.path().join("run.json");
        let out = beam_impact()
            .args(["run", "--mcap"])
            .arg(&log)
            .arg("--json")
            .arg(&json)
            .args(&settings)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        let data = beam_impact::replay::report::read_log(&log).unwrap();
        let stored: serde_json::Value = serde_json::from_str(data.answer_json.as_deref().unwrap()).unwrap();
        assert_eq!(stored["quality"], doc["quality"]);
        assert_eq!(stored["design"], doc["design"]);
        assert_eq!(stored["discretisation"]["runs"], doc["discretisation"]["runs"]);
        assert_eq!(doc["quality"]["trusted"], trusted, "{settings:?}");
        let out = beam_impact().arg("report").arg(&log).arg("--out").arg(dir.path().join("figs")).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let text = String::from_utf8(out.stdout).unwrap();
        let expected =
            if trusted { "verdict stored with the run: trusted" } else { "verdict stored with the run: NOT TRUSTED" };
        assert!(text.contains(expected), "{text}");
    }
}

/// `run --motion` with a bad file: one line naming what is wrong and where (the row and line, or the
/// end the file does not reach), exit status 2, no panic.
#[test]
fn bad_motion_files_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let header = "time,lower.clamp_heave,lower.clamp_heave_velocity,lower.clamp_heave_acceleration\n";
    let cases = [
        ("unknown.csv", "time,lower.clamp_hieve\n0,0\n".to_string(), "unknown column `lower.clamp_hieve`"),
        ("order.csv", format!("{header}0,0,0,0\n1,0,0,0\n0.5,0,0,0\n"), "row 3 (line 4): time 0.5 s is not after"),
        ("nan.csv", format!("{header}0,0,0,0\n1,NaN,0,0\n"), "row 2 (line 3): `lower.clamp_heave` = NaN is not finite"),
        ("short.csv", format!("{header}0,0,0,0\n0.5,0,0,0\n"), "which ends at 0.5 s, before the run's end at 3 s"),
    ];
    for (name, text, expected) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let out = beam_impact().args(["run", "--no-mcap", "--motion"]).arg(&path).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
        assert!(stderr.contains(expected), "{name}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{name}: {stderr}");
    }
}
