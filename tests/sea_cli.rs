//! Issue 42: a `[sea]` through the doors: `beam-impact sea` writes the record as a motion file
//! that `run --motion` reads back to the same run, to the bit; the RAO file is never written
//! over; the log records the sea (its fields, the RAO file's SHA-256, the seed) and carries the
//! record, so that `report` replays the run without the RAO file.

use std::process::Command;

use crate::sea_scenario::{folder, sea_toml};

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn the_sea_commands_file_run_with_motion_gives_the_sea_runs_peaks_to_the_bit() {
    let dir = folder(&sea_toml(""));
    let d = dir.path();
    let out = beam_impact()
        .args(["sea", "s.toml", "--duration", "120", "--out", "record.csv"])
        .current_dir(d)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("24001 rows, the record's time 0 to 120 s every 0.005 s"), "{text}");
    let csv = std::fs::read_to_string(d.join("record.csv")).unwrap();
    assert!(csv.starts_with("time,wave_elevation,upper.hinge_heave,"), "{}", &csv[..200]);
    // The [sea] run (the record from 100 s) and the plain scenario run on the file from 100 s.
    let sea = beam_impact().args(["run", "s.toml", "--no-mcap", "--json", "sea.json"]).current_dir(d).output().unwrap();
    assert!(sea.status.success(), "{}", String::from_utf8_lossy(&sea.stderr));
    std::fs::write(d.join("plain.toml"), "duration = 1.0\n").unwrap();
    let file = beam_impact()
        .args(["run", "plain.toml", "--motion", "record.csv", "--set", "motion.time_shift=100", "--no-mcap"])
        .args(["--json", "file.json"])
        .current_dir(d)
        .output()
        .unwrap();
    assert!(file.status.success(), "{}", String::from_utf8_lossy(&file.stderr));
    let (a, b) = (json(&d.join("sea.json")), json(&d.join("file.json")));
    // The same rows (the record's grid, values in shortest round-trip form) drive the same steps:
    // every peak, its time and the step count equal to the bit (round-off would be the issue's
    // allowance; none is needed).
    for key in ["peaks", "peak_times", "steps", "converged_peaks"] {
        assert_eq!(a["summary"][key], b["summary"][key], "{key}");
    }
    assert_ne!(a["summary"]["peaks"], serde_json::Value::Null);
    // The run says where its supports' motion comes from.
    let sea_text = String::from_utf8(sea.stdout).unwrap();
    assert!(sea_text.contains("supports on a vessel in a sea state: Hs 1 m, Tp 8 s, jonswap"), "{sea_text}");
}

#[test]
fn the_sea_command_never_writes_over_its_inputs_and_refuses_a_scenario_without_sea() {
    let dir = folder(&sea_toml(""));
    let d = dir.path();
    let before = std::fs::read(d.join("raos.csv")).unwrap();
    for target in ["raos.csv", "s.toml"] {
        let out =
            beam_impact().args(["sea", "s.toml", "--duration", "10", "--out", target]).current_dir(d).output().unwrap();
        assert!(!out.status.success());
        let e = String::from_utf8_lossy(&out.stderr);
        assert!(e.contains("name the same file"), "{e}");
    }
    assert_eq!(std::fs::read(d.join("raos.csv")).unwrap(), before);
    std::fs::write(d.join("plain.toml"), "duration = 1.0\n").unwrap();
    let out = beam_impact()
        .args(["sea", "plain.toml", "--duration", "10", "--out", "x.csv"])
        .current_dir(d)
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&out.stderr).contains("no [sea] section"));
    let out =
        beam_impact().args(["sea", "s.toml", "--duration", "1e5", "--out", "x.csv"]).current_dir(d).output().unwrap();
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("raise --sample-interval") && e.lines().count() == 1, "{e}");
    // `run` refuses a log onto the RAO file too.
    let out = beam_impact().args(["run", "s.toml", "--mcap", "raos.csv"]).current_dir(d).output().unwrap();
    assert!(String::from_utf8_lossy(&out.stderr).contains("name the same file"));
    assert_eq!(std::fs::read(d.join("raos.csv")).unwrap(), before);
}

#[test]
fn a_sea_runs_log_records_the_sea_and_report_replays_it_without_the_rao_file() {
    let dir = folder(&sea_toml(""));
    let d = dir.path();
    let run = beam_impact()
        .args(["run", "s.toml", "--mcap", "s.mcap", "--json", "run.json"])
        .current_dir(d)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let data = beam_impact::replay::report::read_log(&d.join("s.mcap")).unwrap();
    let sha = data.metadata.get("sea.raos_sha256").cloned().unwrap_or_default();
    assert_eq!(sha.len(), 64, "{:?}", data.metadata);
    assert_eq!(data.metadata.get("sea.seed").map(String::as_str), Some("7"));
    assert_eq!(data.metadata.get("sea.significant_wave_height").map(String::as_str), Some("1.0"));
    assert!(data.scenario_toml.as_deref().unwrap().contains("[sea]"));
    // The record travels as the log's motion table: 201 rows from 100 s.
    let table = beam_impact::model::motion_table::MotionTable::parse(data.motion_csv.as_deref().unwrap()).unwrap();
    assert_eq!((table.times.len(), table.times[0]), (201, 100.0));
    // `report` replays it with the RAO file gone, and gives the run's peaks.
    std::fs::remove_file(d.join("raos.csv")).unwrap();
    let report = beam_impact().args(["report", "s.mcap", "--out", "figures"]).current_dir(d).output().unwrap();
    assert!(report.status.success(), "{}", String::from_utf8_lossy(&report.stderr));
    let text = String::from_utf8(report.stdout).unwrap();
    let peaks = &json(&d.join("run.json"))["summary"]["peaks"];
    let deflection = peaks["lower.tip_deflection"].as_f64().unwrap();
    assert!(text.contains(&format!("{deflection:.3}")), "{deflection}: {text}");
    // The replayed scenario's motion is the log's record.
    let scenario = data.scenario().unwrap();
    let (replayed, shift) = scenario.motion_source().unwrap().unwrap();
    assert_eq!((*replayed).clone(), table);
    assert_eq!(shift, 100.0);
}
