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

/// `scenario` prints a file that `run` accepts, and `--json` writes the summary.
#[test]
fn scenario_output_runs_and_json_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = beam_impact().arg("scenario").output().unwrap();
    assert!(out.status.success());
    let file = dir.path().join("s.toml");
    let text = String::from_utf8(out.stdout).unwrap().replace("duration = 3.0", "duration = 0.1");
    std::fs::write(&file, text).unwrap();
    let json = dir.path().join("r.json");
    let out = beam_impact().args(["run", "--no-mcap", "--json"]).arg(&json).arg(&file).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(doc["summary"]["steps"].as_u64().unwrap() > 1000);
    assert!(doc["summary"]["peaks"]["lower_tip_deflection"].as_f64().unwrap() > 0.1);
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
