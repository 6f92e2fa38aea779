//! Issue 44 item 3: fatigue of a stress history. Rainflow counting against ASTM E1049-85's own
//! example, the DNV-RP-C203 curves against their tables, Miner's damage against closed forms, and
//! `beam-impact fatigue` as a user meets it (output, JSON, one-line errors, exit code 2).

use std::path::Path;
use std::process::Command;

use beam_impact::fatigue::{count_history, damage, SnCurve, SnOptions};

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

/// ASTM E1049-85 (2017) Fig. 6, the rainflow example.
const ASTM_FIG6: [f64; 9] = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0];

/// The standard's table for Fig. 6 (Fig. 6(f)): range and count, in ascending range.
const ASTM_FIG6_COUNTS: [(f64, f64); 5] = [(3.0, 0.5), (4.0, 1.5), (6.0, 0.5), (8.0, 1.0), (9.0, 0.5)];

fn write_history(dir: &Path, name: &str, columns: &[(&str, &[f64])]) -> std::path::PathBuf {
    let mut text = String::from("time");
    for (name, _) in columns {
        text += &format!(",{name}");
    }
    text.push('\n');
    for row in 0..columns[0].1.len() {
        text += &format!("{}", row as f64 * 0.01);
        for (_, values) in columns {
            text += &format!(",{:?}", values[row]);
        }
        text.push('\n');
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Runs `beam-impact fatigue ARGS --json -` and returns the document.
fn fatigue_json(history: &Path, args: &[&str]) -> serde_json::Value {
    let out = beam_impact().arg("fatigue").arg(history).args(args).args(["--json", "-"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Sums the counts per range of a column's `cycles` (exact: the ranges are small integers).
fn counts_by_range(column: &serde_json::Value) -> Vec<(f64, f64)> {
    let mut totals: Vec<(f64, f64)> = Vec::new();
    for c in column["cycles"].as_array().unwrap() {
        let (range, count) = (c["range"].as_f64().unwrap(), c["count"].as_f64().unwrap());
        match totals.iter_mut().find(|(r, _)| *r == range) {
            Some((_, total)) => *total += count,
            None => totals.push((range, count)),
        }
    }
    totals.sort_by(|a, b| a.0.total_cmp(&b.0));
    totals
}

#[test]
fn astm_e1049_fig6_counts_exactly_as_the_standard_s_table() {
    let cycles = count_history(&ASTM_FIG6).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = write_history(dir.path(), "astm.csv", &[("sigma", &ASTM_FIG6)]);
    let doc = fatigue_json(&path, &["--curve", "D"]);
    let column = &doc["columns"][0];
    assert_eq!(counts_by_range(column), ASTM_FIG6_COUNTS);
    assert_eq!(column["reversals"], 9);
    // The command lists what the library counts, in its order, with the means.
    let listed: Vec<(f64, f64, f64)> = column["cycles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| (c["range"].as_f64().unwrap(), c["mean"].as_f64().unwrap(), c["count"].as_f64().unwrap()))
        .collect();
    assert_eq!(listed, cycles.iter().map(|c| (c.range, c.mean, c.count)).collect::<Vec<_>>());
    assert_eq!(listed[2], (4.0, 1.0, 1.0), "the one full cycle, -1 to 3");
}

/// DNVGL-RP-C203 (2016) Table 2-1 prints the D curve's "fatigue limit" 52.63 MPa at 1e7 cycles.
/// Tolerance from the table's rounding: log a to 3 decimals (+-0.0005 in log10 N) and 52.63 to
/// 2 decimals (+-0.005 MPa: m2 x 0.005 / (52.63 ln 10) = 2.1e-4 in log10 N): |log10 N - 7| <= 7.1e-4.
#[test]
fn d_curve_n_at_52_63_mpa_is_1e7_cycles() {
    let d = SnCurve::by_name("D").unwrap();
    let log_n = d.cycles_to_failure(52.63e6).log10();
    let tolerance = 0.0005 + 5.0 * 0.005 / (52.63 * std::f64::consts::LN_10);
    assert!((log_n - 7.0).abs() <= tolerance, "log10 N = {log_n}");
    // The same in seawater with CP: the second branch is the air curve's (Table 2-2).
    let sea = SnCurve::by_name("D-seawater-cp").unwrap();
    assert!((sea.cycles_to_failure(52.63e6).log10() - 7.0).abs() <= tolerance);
}

/// Each two-branch curve's branches meet at n_switch to the tables' rounding (log a1, log a2 each
/// +-0.0005; S_switch from log a1 carries its error times m2/m1 into branch 2).
#[test]
fn every_curve_s_two_branches_meet_at_n_switch() {
    let mut checked = 0;
    for c in SnCurve::all() {
        let (Some(m2), Some(log_a2), Some(n)) = (c.m2, c.log_a2, c.n_switch) else { continue };
        let s = c.switch_range_mpa().unwrap();
        let below = c.cycles_to_failure(s * 1e6 * (1.0 - 1e-12)).log10();
        let above = c.cycles_to_failure(s * 1e6 * (1.0 + 1e-12)).log10();
        let bound = 0.0005 * (1.0 + m2 / c.m1);
        assert!((below - n.log10()).abs() <= bound, "{}: below {below}", c.name);
        assert!((above - n.log10()).abs() <= 1e-9, "{}: above {above}", c.name);
        assert!((log_a2 - m2 * s.log10() - n.log10()).abs() <= bound, "{}", c.name);
        checked += 1;
    }
    assert_eq!(checked, 14 + 14 + 6, "air, seawater CP, the 2024 C family");
}

/// A constant-amplitude history of n reversal pairs of range S: n cycles (2n halves, ASTM step 5
/// moves the start each time), so D = n S^m / a on the first branch; with SCF and a thickness
/// t > t_ref, D scales by (SCF (t/t_ref)^k)^m; with DFF by DFF. Relative 1e-12: a few roundings.
#[test]
fn constant_amplitude_damage_matches_the_closed_form_with_scf_thickness_and_dff() {
    let n = 50;
    let history: Vec<f64> = (0..=2 * n).map(|i| if i % 2 == 0 { -60e6 } else { 60e6 }).collect();
    let cycles = count_history(&history).unwrap();
    assert_eq!(cycles.iter().map(|c| c.count).sum::<f64>(), n as f64);
    let d = SnCurve::by_name("D").unwrap();
    let closed = |factor: f64| n as f64 * (120.0 * factor).powi(3) / 10f64.powf(12.164);
    let plain = damage(&cycles, &d, &SnOptions::default());
    assert!((plain / closed(1.0) - 1.0).abs() < 1e-12, "{plain}");
    let options = SnOptions { scf: 1.5, thickness_m: Some(0.04), design_fatigue_factor: 3.0 };
    let factor = 1.5 * (0.04f64 / 0.025).powf(0.2);
    let designed = damage(&cycles, &d, &options);
    assert!((designed / (3.0 * closed(factor)) - 1.0).abs() < 1e-12, "{designed}");
    // Through the command: the same numbers.
    let dir = tempfile::tempdir().unwrap();
    let path = write_history(dir.path(), "ca.csv", &[("s", &history)]);
    let doc = fatigue_json(&path, &["--curve", "D", "--scf", "1.5", "--thickness", "0.04", "--dff", "3"]);
    assert_eq!(doc["columns"][0]["damage"].as_f64().unwrap(), designed);
    assert_eq!(doc["curve"]["name"], "D");
    assert_eq!(doc["options"]["scf"], 1.5);
}

/// The printed table names the curve and lists the ASTM example's cycles.
#[test]
fn the_table_prints_the_curve_and_each_column_s_cycles() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_history(dir.path(), "astm.csv", &[("sigma", &ASTM_FIG6), ("flat", &[0.0; 9])]);
    let out = beam_impact().args(["fatigue", path.to_str().unwrap(), "--curve", "D-free-corrosion"]).output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for needle in [
        "S-N curve D-free-corrosion (DNVGL-RP-C203 (April 2016) Table 2-4): m1 3, log a1 11.687, k 0.2",
        "column sigma: 9 reversals, 1 full and 6 half cycles",
        "column flat: 1 reversals, 0 full and 0 half cycles, damage 0.000000e0",
    ] {
        assert!(text.contains(needle), "missing {needle:?} in\n{text}");
    }
}

/// Runs the command expecting exit code 2 and one line on standard error; returns that line.
fn refused(args: &[&str]) -> String {
    let out = beam_impact().args(args).output().unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
    assert!(out.stdout.is_empty());
    stderr.trim_end().to_string()
}

#[test]
fn bad_input_is_one_line_and_exit_code_2() {
    let dir = tempfile::tempdir().unwrap();
    let file = |name: &str, text: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        path.display().to_string()
    };
    let no_time = file("no-time.csv", "t,s\n0,1\n");
    assert!(refused(&["fatigue", &no_time, "--curve", "D"])
        .ends_with("it has no `time` column (expected `time` and one or more stress columns, Pa)"));
    let word = file("word.csv", "time,s\n0,1\n1,abc\n");
    assert!(refused(&["fatigue", &word, "--curve", "D"]).ends_with("row 2 (line 3), column `s`: `abc` is not a number"));
    let nan = file("nan.csv", "time,s\n0,NaN\n");
    assert!(
        refused(&["fatigue", &nan, "--curve", "D"]).ends_with("row 1 (line 2), column `s`: NaN is not a finite number")
    );
    let empty = file("empty.csv", "");
    assert!(refused(&["fatigue", &empty, "--curve", "D"])
        .ends_with("no header line (a `time` column and stress columns in Pa)"));
    let back = file("back.csv", "time,s\n1,0\n0.5,1\n");
    assert!(refused(&["fatigue", &back, "--curve", "D"]).contains("time 0.5 s is not after the row before's 1 s"));
    let good = file("good.csv", "time,s\n0,0\n1,1\n");
    let unknown = refused(&["fatigue", &good, "--curve", "X9"]);
    assert!(unknown.starts_with("beam-impact: --curve: unknown S-N curve `X9`: known curves are B1, B2, C, C1, C2, D,"));
    assert!(unknown.contains("NAME-seawater-cp") && unknown.contains("C-2024"), "{unknown}");
    assert_eq!(
        refused(&["fatigue", &good, "--curve", "D", "--scf", "0.5"]),
        "beam-impact: fatigue.scf must be >= 1 and <= 20, got 0.5"
    );
    assert_eq!(
        refused(&["fatigue", &good, "--curve", "D", "--thickness", "0"]),
        "beam-impact: fatigue.thickness must be > 0 m and <= 1 m, got 0"
    );
    assert_eq!(
        refused(&["fatigue", &good, "--curve", "D", "--dff", "inf"]),
        "beam-impact: fatigue.design_fatigue_factor must be >= 1 and <= 10, got inf"
    );
    // A huge file is refused from its size before a byte is read (a sparse file: no disk used).
    let huge = dir.path().join("huge.csv");
    std::fs::File::create(&huge).unwrap().set_len(beam_impact::fatigue::history::MAX_HISTORY_BYTES + 1).unwrap();
    assert!(refused(&["fatigue", huge.to_str().unwrap(), "--curve", "D"])
        .contains("larger than 268435456 bytes (the limit)"));
    assert!(refused(&["fatigue", "/dev/zero", "--curve", "D"]).contains("not a regular file"));
    assert!(refused(&["fatigue", &good, "--curve", "D", "--json", &good]).contains("name the same file"));
}
