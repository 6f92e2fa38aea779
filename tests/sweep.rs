//! `beam-impact sweep` and `run --set` as a user meets them (issue 10).
//!
//! Goal: every row of a sweep is the single run of its scenario (the library's
//! `Simulation::new(..).run(..)` summary, and `beam-impact run --set .. --json`); the grid is the
//! product of the `--vary` options with the last fastest; a scenario that fails is a row with its
//! error while the sweep goes on; bad options are one-line errors naming the key; a run with
//! `--set` never logs over `paper.mcap`.
//!
//! Tolerance: 1e-9 relative, the issue's contract for "the same code path" (in practice the
//! values are bit-identical: the CSV and JSON write the shortest decimal that gives the same
//! f64, and the runs take the same steps; the largest difference is printed).

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Output};

use beam_impact::model::parameters;
use beam_impact::record::NullRecorder;
use beam_impact::solver::ModalCache;
use beam_impact::Scenario;

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

fn ok(out: Output) -> Output {
    assert!(out.status.success(), "exit {:?}: {}", out.status.code(), String::from_utf8_lossy(&out.stderr));
    out
}

/// Splits one CSV line (RFC 4180 quoting, no line breaks inside fields: the sweep has none).
fn csv_fields(line: &str) -> Vec<String> {
    let mut fields = vec![String::new()];
    let (mut quoted, mut chars) = (false, line.chars().peekable());
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                fields.last_mut().unwrap().push('"');
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(String::new()),
            (c, _) => fields.last_mut().unwrap().push(c),
        }
    }
    fields
}

/// The CSV as rows of column -> text.
fn read_csv(path: &Path) -> (Vec<String>, Vec<BTreeMap<String, String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = csv_fields(lines.next().unwrap());
    let rows = lines
        .map(|line| {
            let fields = csv_fields(line);
            assert_eq!(fields.len(), header.len(), "{line}");
            header.iter().cloned().zip(fields).collect()
        })
        .collect();
    (header, rows)
}

/// The expected result columns of a run, from its summary's own JSON (independent of the sweep
/// module's tables): peaks, `<peak>_time`, `energy_method.<field>`, `max_energy_residual`, `trusted`.
fn expected_columns(summary: &serde_json::Value) -> BTreeMap<String, serde_json::Value> {
    let mut map = BTreeMap::new();
    // The former keys (the JSON also holds each peak under its dotted FMU name, a duplicate).
    for (name, value) in summary["peaks"].as_object().unwrap().iter().filter(|(name, _)| !name.contains('.')) {
        map.insert(name.clone(), value.clone());
        map.insert(format!("{name}_time"), summary["peak_times"][name].clone());
    }
    for (name, value) in summary["energy_method"].as_object().unwrap() {
        map.insert(format!("energy_method.{name}"), value.clone());
    }
    map.insert("max_energy_residual".into(), summary["max_energy_residual"].clone());
    map.insert("trusted".into(), summary["quality"]["trusted"].clone());
    map
}

/// Compares a row's text cells with the expected values; returns the largest relative difference.
fn compare(row: &BTreeMap<String, String>, expected: &BTreeMap<String, serde_json::Value>, context: &str) -> f64 {
    let mut worst: f64 = 0.0;
    for (name, value) in expected {
        let cell = row.get(name).unwrap_or_else(|| panic!("{context}: no column {name}"));
        if let Some(b) = value.as_bool() {
            assert_eq!(cell, &b.to_string(), "{context}: {name}");
            continue;
        }
        let want = value.as_f64().unwrap();
        let got: f64 = cell.parse().unwrap_or_else(|_| panic!("{context}: {name} = {cell:?}"));
        let rel = if want == got { 0.0 } else { (got - want).abs() / want.abs().max(f64::MIN_POSITIVE) };
        assert!(rel <= 1e-9, "{context}: {name}: sweep {got} vs run {want} ({rel:e} relative)");
        worst = worst.max(rel);
    }
    assert_eq!(row["error"], "", "{context}");
    worst
}

/// A 10-scenario sweep of the default scenario (the converged method, 3 s): the rows come in grid
/// order (drop height outermost, damping fastest), and each equals `answer::run` of its scenario
/// (what `run` prints) in every column; the JSON holds the same rows.
#[test]
fn ten_scenario_sweep_rows_equal_the_single_runs() {
    let dir = tempfile::tempdir().unwrap();
    let (csv, json) = (dir.path().join("rows.csv"), dir.path().join("rows.json"));
    let out = ok(beam_impact()
        .args(["sweep", "--vary", "drop_height=0.3:1.5:5", "--vary", "damping_ratio=0.02,0.05", "--out"])
        .arg(&csv)
        .arg("--json")
        .arg(&json)
        .current_dir(dir.path())
        .output()
        .unwrap());
    assert!(String::from_utf8_lossy(&out.stdout).contains("10 scenarios"));
    let (header, rows) = read_csv(&csv);
    // The FMU's names first; `error` ends them, the former names (duplicates) follow.
    assert_eq!(&header[..3], ["drop_height", "damping_ratio", "peak.lower.tip_deflection"]);
    assert_eq!(header.last().unwrap(), "trusted");
    assert!(header.contains(&"error".to_string()) && header.contains(&"lower_tip_deflection".to_string()));
    assert!(dir.path().join("rows.units.json").is_file(), "the units sidecar");
    assert_eq!(rows.len(), 10);
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let objects = doc.as_array().unwrap();
    assert_eq!(objects.len(), 10);
    let mut worst: f64 = 0.0;
    let mut k = 0;
    for h in [0.3, 0.6, 0.9, 1.2, 1.5] {
        for g in [0.02, 0.05] {
            let row = &rows[k];
            assert_eq!(
                (row["drop_height"].parse::<f64>().unwrap(), row["damping_ratio"].parse::<f64>().unwrap()),
                (h, g)
            );
            let scenario = Scenario { drop_height: h, damping_ratio: g, ..Scenario::default() };
            let answer = beam_impact::answer::run(&scenario, &mut NullRecorder, Default::default()).unwrap();
            let mut summary = serde_json::to_value(&answer.summary).unwrap();
            summary["quality"] = serde_json::to_value(&answer.quality).unwrap();
            let expected = expected_columns(&summary);
            worst = worst.max(compare(row, &expected, &format!("row {k} (h = {h}, gamma = {g})")));
            // The JSON row: the same numbers (shortest round-trip decimals on both sides).
            let object = objects[k].as_object().unwrap();
            assert_eq!(object.keys().len(), header.len());
            for name in &header {
                let cell = &row[name];
                match &object[name] {
                    serde_json::Value::Number(n) => assert_eq!(n.as_f64().unwrap(), cell.parse::<f64>().unwrap()),
                    serde_json::Value::Bool(b) => assert_eq!(&b.to_string(), cell),
                    serde_json::Value::String(s) => assert_eq!(s, cell),
                    serde_json::Value::Null => assert_eq!(cell, "", "row {k}: {name}"),
                    other => panic!("row {k}: {name} = {other}"),
                }
            }
            k += 1;
        }
    }
    println!("largest relative difference sweep vs run over 10 scenarios x {} columns: {worst:e}", header.len() - 3);
}

/// A sweep of a scenario file with `--set`, its rows against `beam-impact run FILE --set ..
/// --json` (the CLI path end to end, automatic steps); integer fields are rounded and
/// deduplicated.
#[test]
fn sweep_rows_equal_run_with_set() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("short.toml");
    std::fs::write(&file, "duration = 0.6\ndamping_ratio = 0.01\n").unwrap();
    let csv = dir.path().join("rows.csv");
    ok(beam_impact()
        .arg("sweep")
        .arg(&file)
        .args(["--set", "upper.mass=14000", "--vary", "lower.elements=6:8:5", "--vary", "step_free=auto,2e-5"])
        .args(["--jobs", "2", "--out"])
        .arg(&csv)
        .output()
        .unwrap());
    let (_, rows) = read_csv(&csv);
    let grid: Vec<(String, String)> =
        rows.iter().map(|r| (r["lower.elements"].clone(), r["step_free"].clone())).collect();
    let expected: Vec<(String, String)> =
        ["6", "7", "8"].iter().flat_map(|e| ["auto", "0.00002"].map(|s| (e.to_string(), s.to_string()))).collect();
    assert_eq!(grid, expected);
    for row in [&rows[1], &rows[4]] {
        let json = dir.path().join("run.json");
        ok(beam_impact()
            .args(["run", "--no-mcap", "--set", "upper.mass=14000"])
            .arg(format!("--set=lower.elements={}", row["lower.elements"]))
            .arg(format!("--set=step_free={}", row["step_free"]))
            .arg("--json")
            .arg(&json)
            .arg(&file)
            .output()
            .unwrap());
        let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        assert_eq!(doc["scenario"]["upper"]["mass"], 14000.0);
        compare(row, &expected_columns(&doc["summary"]), &format!("{row:?}"));
    }
}

/// Scenarios that fail validation (d = 40 m beyond the bridge, a negative drop) are rows with
/// their error naming the field; the others run (d = 10 m too: the default's automatic steps are
/// stable wherever the contact is), the sweep exits 0 and says how many failed.
#[test]
fn a_failing_scenario_is_a_row_with_its_error_and_the_sweep_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    let (csv, json) = (dir.path().join("rows.csv"), dir.path().join("rows.json"));
    let out = ok(beam_impact()
        .args(["sweep", "--set", "duration=0.3", "--vary", "contact_position=13,40,10", "--vary", "drop_height=0.5,-1"])
        .arg("--out")
        .arg(&csv)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("4 of 6 scenarios failed"), "{stderr}");
    let (_, rows) = read_csv(&csv);
    assert_eq!(rows.len(), 6);
    for row in &rows {
        let (d, h) = (row["contact_position"].as_str(), row["drop_height"].as_str());
        let error = &row["error"];
        if d == "40" {
            assert!(error.contains("contact_position must be on the upper beam"), "{error}");
        }
        if h == "-1" {
            assert!(error.contains("drop_height must be >= 0 m, got -1"), "{error}");
        }
        if (d == "13" || d == "10") && h != "-1" {
            assert_eq!(error, "");
            assert!(row["lower_tip_deflection"].parse::<f64>().unwrap() > 0.1);
            assert!(["true", "false"].contains(&row["trusted"].as_str()), "{row:?}");
        } else {
            assert_eq!(row["lower_tip_deflection"], "");
            assert_eq!(row["trusted"], "");
        }
    }
    // Both errors at once for the scenario with two bad fields.
    assert!(rows[3]["error"].contains("drop_height") && rows[3]["error"].contains("contact_position"));
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(doc[2]["lower_tip_deflection"].is_null());
    assert_eq!(doc[2]["error"], rows[2]["error"].as_str());
}

/// Bad options: exit code 2 and one line naming the key.
#[test]
fn bad_options_are_one_line_errors_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let out_csv = dir.path().join("x.csv");
    let cases: [(&[&str], &str); 6] = [
        (&["sweep", "--vary", "upper.lenght=1,2"], "unknown parameter `upper.lenght`"),
        (&["sweep", "--vary", "drop_height=0.1:2"], "--vary drop_height=0.1:2: SPEC is start:stop:count"),
        (&["sweep", "--vary", "drop_height=1", "--vary", "drop_height=2"], "drop_height is given twice"),
        (&["sweep", "--set", "damping_ratio=abc"], "damping_ratio takes a number, got `abc`"),
        (&["run", "--no-mcap", "--set", "upper.mas=1"], "unknown parameter `upper.mas`"),
        (&["run", "--no-mcap", "--set", "upper.mass=-5"], "upper.mass must be > 0 kg, got -5"),
    ];
    for (args, needle) in cases {
        let mut command = beam_impact();
        command.args(args);
        if args[0] == "sweep" {
            command.arg("--out").arg(&out_csv);
        }
        let out = command.output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
    }
}

/// `run --set` logs to a name of its own (`paper-set-<hash>.mcap`), never over `paper.mcap`;
/// an explicit `--mcap` is taken as given.
#[test]
fn run_with_set_never_logs_over_the_paper_log() {
    let dir = tempfile::tempdir().unwrap();
    let out = ok(beam_impact().args(["run", "--set", "duration=0.02"]).current_dir(dir.path()).output().unwrap());
    let names: Vec<String> =
        std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    assert_eq!(names.len(), 1, "{names:?}");
    assert!(names[0].starts_with("paper-set-") && names[0].ends_with(".mcap"), "{names:?}");
    assert!(String::from_utf8_lossy(&out.stdout).contains(&names[0]));
    ok(beam_impact()
        .args(["run", "--set", "duration=0.02", "--mcap", "mine.mcap"])
        .current_dir(dir.path())
        .output()
        .unwrap());
    assert!(dir.path().join("mine.mcap").exists());
    assert!(!dir.path().join("paper.mcap").exists());
    // Every name `beam-impact scenario` prints is accepted by --set (its parameters are).
    for p in parameters::PARAMETERS {
        assert!(beam_impact::studies::sweep::field(p.name).is_ok(), "{}", p.name);
    }
}

/// The runs of `scenarios`, each an answer with its rungs' modes from one shared cache and the
/// same answer without a cache: every peak, figure and verdict equal (`==`, to the bit).
fn assert_cached_answers_are_the_uncached_ones(scenarios: &[(String, Scenario)], cache: &ModalCache) {
    for (what, s) in scenarios {
        let fresh = beam_impact::answer::run(s, &mut NullRecorder, Default::default()).unwrap();
        let cached = beam_impact::answer::run_with(s, &mut NullRecorder, Default::default(), cache).unwrap();
        let bits = |a: &beam_impact::answer::Answer| -> Vec<u64> {
            let mut v: Vec<f64> = [a.summary.peaks, a.summary.first_contact_peaks, a.converged_peaks]
                .iter()
                .flat_map(|p| p.as_array())
                .collect();
            v.extend(a.discretisation_error.as_array());
            v.extend(a.first_contact_discretisation_error.as_array());
            v.extend(a.sensitivity_spread.map_or([f64::NAN; 5], |p| p.as_array()));
            v.extend(a.design.utilisation.as_array());
            v.push(a.summary.max_energy_residual);
            v.iter().map(|x| x.to_bits()).collect()
        };
        assert_eq!(bits(&cached), bits(&fresh), "{what}: peaks and figures");
        assert_eq!(cached.quality, fresh.quality, "{what}: checks and verdict");
        assert_eq!(cached.design, fresh.design, "{what}: design");
        assert_eq!(cached.runs, fresh.runs, "{what}: rungs");
        assert_eq!(cached, fresh, "{what}: the whole answer");
    }
}

/// Issue 29: answers whose rungs take their modes from a cache shared across scenarios that
/// differ in every per-run field (drop height, impact speed, damping in both cut-off classes,
/// Rayleigh terms, steps, duration, tolerances, allowables, yield stresses, tip forces, motion
/// shift) are the uncached answers to the bit, and one geometry needs two entries per rung (the
/// automatic cut-off doubles below damping 0.02), not one per run. Another contact position, and
/// a power-law contact (whose coupled rate follows the impact energy), keep their own modes.
#[test]
fn cached_answers_equal_uncached_ones_to_the_bit() {
    use beam_impact::studies::sweep::{apply_settings, field, Setting};
    let base = Scenario { duration: 0.3, ..Scenario::default() };
    let with = |settings: &[(&str, f64)]| -> (String, Scenario) {
        let mut s = base.clone();
        let settings: Vec<Setting> =
            settings.iter().map(|(name, value)| Setting { field: field(name).unwrap(), value: *value }).collect();
        apply_settings(&mut s, &settings).unwrap();
        (format!("{:?}", settings.iter().map(|s| (s.field.name, s.value)).collect::<Vec<_>>()), s)
    };
    let mut per_run: Vec<(String, Scenario)> = [
        &[][..],
        &[("drop_height", 1.3)],
        &[("impact_angular_velocity", 0.2)],
        &[("damping_ratio", 0.01)],
        &[("damping_ratio", 0.01), ("drop_height", 0.9)],
        &[("damping_ratio", 0.05)],
        &[("rayleigh_alpha", 0.5), ("rayleigh_beta", 2e-6)],
        &[("step_free", 2e-5), ("step_contact", 1e-5)],
        &[("duration", 0.35)],
        &[("energy_tolerance", 0.02), ("discretisation_tolerance", 0.05)],
        &[("upper.allowable_bending_stress", 400e6), ("upper.yield_stress", 355e6), ("upper.tip_force", -1000.0)],
        &[("lower.allowable_bending_stress", 400e6), ("lower.allowable_shear_stress", 200e6)],
        &[("lower.yield_stress", 355e6), ("lower.tip_force", 500.0)],
    ]
    .iter()
    .map(|settings| with(settings))
    .collect();
    // The supports' motion (the vessel example's), at two phases.
    let csv =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/vessel-motion.csv")).unwrap();
    let table = std::sync::Arc::new(beam_impact::model::motion_table::MotionTable::parse(&csv).unwrap());
    for shift in [0.5, 4.5] {
        let mut s = base.clone();
        s.motion.file = "vessel-motion.csv".into();
        s.motion.table = Some(table.clone());
        s.motion.time_shift = shift;
        per_run.push((format!("[(\"motion.time_shift\", {shift})]"), s));
    }
    // A sea (issue 42) moves the supports, never the modes: its fields are per run too.
    let sea_dir = crate::sea_scenario::folder("");
    let text = crate::sea_scenario::sea_toml("").replace("duration = 1.0", "duration = 0.3");
    let sea = beam_impact::scenario_file::from_text(&text, "sea", sea_dir.path(), &mut Vec::new()).unwrap();
    for (name, value) in [("sea.time_shift", 100.0), ("sea.time_shift", 130.0), ("sea.significant_wave_height", 2.0)] {
        let mut s = sea.clone();
        s.sea.as_mut().unwrap().time_shift = 100.0;
        apply_settings(&mut s, &[Setting { field: field(name).unwrap(), value }]).unwrap();
        per_run.push((format!("[(\"{name}\", {value})]"), s));
    }
    // Every per-run field is varied above.
    for name in beam_impact::solver::modal_cache::PER_RUN_FIELDS {
        // A rigid impactor's speed (issue 45) is varied on a mass, a geometry of its own, below.
        if name == "impact_speed" {
            continue;
        }
        assert!(per_run.iter().any(|(what, _)| what.contains(&format!("\"{name}\""))), "{name} is not varied");
    }
    let cache = ModalCache::default();
    assert_cached_answers_are_the_uncached_ones(&per_run, &cache);
    // Issue 43: and the automatic cut-off's reference mesh (the paper mesh's modes), one for all.
    assert_eq!(cache.len(), 7, "printed, check and coarse rungs in two cut-off classes, and the reference mesh");
    let others = [
        with(&[("contact_position", 20.0)]),
        with(&[("contact.law", 1.0), ("contact.exponent", 1.3), ("contact.stiffness", 7.5e7), ("duration", 0.02)]),
        with(&[
            ("contact.law", 1.0),
            ("contact.exponent", 1.3),
            ("contact.stiffness", 7.5e7),
            ("duration", 0.02),
            ("drop_height", 1.3),
        ]),
        with(&[("upper.kind", 1.0), ("upper.mass", 500.0), ("impact_speed", 1.0), ("duration", 0.05)]),
        with(&[("upper.kind", 1.0), ("upper.mass", 500.0), ("impact_speed", 1.5), ("duration", 0.05)]),
    ];
    assert_cached_answers_are_the_uncached_ones(&others, &cache);
    assert!(cache.len() > 7 + 3, "the other geometries have their own entries: {}", cache.len());
}

/// Issue 29: every row keeps its wall time (`wall_time`, s in the units sidecar), and rows run
/// grouped by geometry (here the inner axis) are still written in grid order, each the run of
/// its scenario.
#[test]
fn rows_keep_their_wall_time_and_their_order_when_grouped_by_geometry() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("rows.csv");
    ok(beam_impact()
        .args(["sweep", "--set", "duration=0.2", "--vary", "drop_height=0.3,0.6", "--vary", "contact_position=13,20"])
        .args(["--jobs", "2", "--out"])
        .arg(&csv)
        .output()
        .unwrap());
    let (header, rows) = read_csv(&csv);
    let error = header.iter().position(|c| c == "error").unwrap();
    assert_eq!(header[error - 1], "wall_time", "wall_time just before error");
    let units: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("rows.units.json")).unwrap()).unwrap();
    assert!(units.to_string().contains(r#"{"name":"wall_time","unit":"s"}"#), "{units}");
    let grid: Vec<(&str, &str)> =
        rows.iter().map(|r| (r["drop_height"].as_str(), r["contact_position"].as_str())).collect();
    assert_eq!(grid, [("0.3", "13"), ("0.3", "20"), ("0.6", "13"), ("0.6", "20")]);
    for row in &rows {
        let wall: f64 = row["wall_time"].parse().unwrap();
        assert!(wall > 0.0 && wall.is_finite(), "{row:?}");
        let scenario = Scenario {
            duration: 0.2,
            drop_height: row["drop_height"].parse().unwrap(),
            contact_position: row["contact_position"].parse().unwrap(),
            ..Scenario::default()
        };
        let answer = beam_impact::answer::run(&scenario, &mut NullRecorder, Default::default()).unwrap();
        let mut summary = serde_json::to_value(&answer.summary).unwrap();
        summary["quality"] = serde_json::to_value(&answer.quality).unwrap();
        assert_eq!(compare(row, &expected_columns(&summary), &format!("{row:?}")), 0.0, "to the bit");
    }
}
