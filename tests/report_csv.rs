//! `beam-impact report --csv FILE` (issue 11): the step channel as CSV, named by the step
//! message's field paths, one row per step the reader keeps, numbers that round-trip.

use std::path::Path;
use std::process::{Command, Output, Stdio};

use beam_impact::record::mcap::{McapRecorder, RecorderOptions};
use beam_impact::record::schema::beam_impact_descriptor;
use beam_impact::record::{Recorder, RunInfo};
use beam_impact::replay::report::read_log;
use beam_impact::results::StepResult;
use beam_impact::Scenario;
use prost::Message;
use prost_types::FileDescriptorSet;

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

fn ok(out: &Output) {
    assert!(out.status.success(), "{:?}: {}", out.status, String::from_utf8_lossy(&out.stderr));
}

/// The columns every CSV has, in order (the Python reader's `dataframe()` order): the quantities
/// by their FMU names, then the renamed ones by their former names, the `beam_impact.Step` field
/// paths (duplicates until 0.2.0).
const HEADER: [&str; 52] = [
    "step",
    "time_ns",
    "time",
    "step_size",
    "contact.active",
    "lower.tip_deflection",
    "upper.contact_deflection",
    "upper.tip_deflection",
    "lower.clamp_bending_stress",
    "lower.clamp_shear_stress",
    "upper.contact_bending_stress",
    "contact.force",
    "contact.stress",
    "lower.clamp_reaction_force",
    "lower.clamp_reaction_moment",
    "upper.hinge_reaction_force",
    "lower.tip_velocity",
    "upper.tip_velocity",
    "lower.far_reaction_force",
    "lower.far_reaction_moment",
    "energy.kinetic",
    "energy.strain",
    "energy.gravity_potential",
    "energy.external_work",
    "energy.damping_dissipation",
    "energy.residual",
    "peak.lower.tip_deflection",
    "peak.lower.clamp_bending_stress",
    "peak.lower.clamp_shear_stress",
    "peak.upper.contact_bending_stress",
    "peak.contact.force",
    "contact",
    "lower_tip_deflection",
    "upper_contact_deflection",
    "upper_tip_deflection",
    "lower_clamp_bending_stress",
    "lower_clamp_shear_stress",
    "upper_contact_bending_stress",
    "contact_force",
    "contact_stress",
    "lower_clamp_reaction_force",
    "lower_clamp_reaction_moment",
    "upper_hinge_reaction_force",
    "lower_tip_velocity",
    "upper_tip_velocity",
    "lower_far_reaction_force",
    "lower_far_reaction_moment",
    "peaks.lower_tip_deflection",
    "peaks.lower_clamp_bending_stress",
    "peaks.lower_clamp_shear_stress",
    "peaks.upper_contact_bending_stress",
    "peaks.contact_force",
];

/// A parsed CSV: the header and the rows as text cells.
struct Csv {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Csv {
    fn parse(text: &str) -> Csv {
        assert!(text.ends_with('\n'), "the last row ends its line");
        let mut lines = text.lines();
        let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
        let rows: Vec<Vec<String>> = lines.map(|l| l.split(',').map(String::from).collect()).collect();
        for (k, row) in rows.iter().enumerate() {
            assert_eq!(row.len(), header.len(), "row {k}: {row:?}");
        }
        Csv { header, rows }
    }

    fn column(&self, name: &str) -> Vec<f64> {
        let k = self.header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"));
        self.rows.iter().map(|r| r[k].parse::<f64>().unwrap_or_else(|e| panic!("{name} = {:?}: {e}", r[k]))).collect()
    }
}

/// Every value of a step, by column name, as the CSV must hold it.
fn expected(r: &StepResult, name: &str) -> String {
    let f = |x: f64| x.to_bits().to_string();
    match name {
        "step" => r.step.to_string(),
        "time_ns" => r.time_ns.to_string(),
        "contact" => r.contact.to_string(),
        "time" => f(r.time),
        "step_size" => f(r.step_size),
        "lower_tip_deflection" => f(r.lower_tip_deflection),
        "upper_contact_deflection" => f(r.upper_contact_deflection),
        "upper_tip_deflection" => f(r.upper_tip_deflection),
        "lower_clamp_bending_stress" => f(r.lower_clamp_bending_stress),
        "lower_clamp_shear_stress" => f(r.lower_clamp_shear_stress),
        "upper_contact_bending_stress" => f(r.upper_contact_bending_stress),
        "contact_force" => f(r.contact_force),
        "contact_stress" => f(r.contact_stress),
        "lower_clamp_reaction_force" => f(r.lower_clamp_reaction_force),
        "lower_clamp_reaction_moment" => f(r.lower_clamp_reaction_moment),
        "upper_hinge_reaction_force" => f(r.upper_hinge_reaction_force),
        "lower_tip_velocity" => f(r.lower_tip_velocity),
        "upper_tip_velocity" => f(r.upper_tip_velocity),
        "lower_far_reaction_force" => f(r.lower_far_reaction_force),
        "lower_far_reaction_moment" => f(r.lower_far_reaction_moment),
        "energy.kinetic" => f(r.energy.kinetic),
        "energy.strain" => f(r.energy.strain),
        "energy.gravity_potential" => f(r.energy.gravity_potential),
        "energy.external_work" => f(r.energy.external_work),
        "energy.damping_dissipation" => f(r.energy.damping_dissipation),
        "energy.residual" => f(r.energy.residual),
        "peaks.lower_tip_deflection" => f(r.peaks.lower_tip_deflection),
        "peaks.lower_clamp_bending_stress" => f(r.peaks.lower_clamp_bending_stress),
        "peaks.lower_clamp_shear_stress" => f(r.peaks.lower_clamp_shear_stress),
        "peaks.upper_contact_bending_stress" => f(r.peaks.upper_contact_bending_stress),
        "peaks.contact_force" => f(r.peaks.contact_force),
        _ => panic!("unexpected column {name}"),
    }
}

/// A cell as the CSV holds it, in the form of [`expected`]: floats as their bits.
fn cell(name: &str, text: &str) -> String {
    match name {
        "step" | "time_ns" | "contact" => text.to_string(),
        _ => text.parse::<f64>().unwrap_or_else(|e| panic!("{name} = {text:?}: {e}")).to_bits().to_string(),
    }
}

/// The step message's field path of a column: the former name of a renamed quantity, else itself.
fn field_path(name: &str) -> &str {
    beam_impact::vocabulary::STEP_RENAMES.iter().find(|(_, n)| *n == name).map_or(name, |(p, _)| p)
}

/// Every row equals the reader's step of the same index, to the bit.
fn assert_rows_are(csv: &Csv, steps: &[StepResult]) {
    assert_eq!(csv.rows.len(), steps.len(), "one row per step kept");
    for (row, r) in csv.rows.iter().zip(steps) {
        for (name, text) in csv.header.iter().zip(row) {
            let path = field_path(name);
            assert_eq!(cell(path, text), expected(r, path), "step {} column {name}: {text}", r.step);
        }
    }
}

/// Whether `path` (`energy.kinetic`) names a field of `beam_impact.Step` in the descriptor that
/// every log embeds.
fn resolves_in_step(set: &FileDescriptorSet, path: &str) -> bool {
    let types: Vec<_> = set.file.iter().flat_map(|f| f.message_type.iter()).collect();
    let mut message = "Step".to_string();
    let parts: Vec<&str> = path.split('.').collect();
    for (k, part) in parts.iter().enumerate() {
        let Some(m) = types.iter().find(|m| m.name() == message) else { return false };
        let Some(f) = m.field.iter().find(|f| f.name() == *part) else { return false };
        if k + 1 < parts.len() {
            message = f.type_name().rsplit('.').next().unwrap_or_default().to_string();
        }
    }
    true
}

/// A short user run with `--mcap` and `--json`, then `report --csv`: the header is the step
/// message's field paths, one row per step message in the log, every value the reader's to the
/// bit, and the largest |deflection| and the last row's running peaks are the run's `--json`
/// peaks. `--csv -` writes the same bytes to standard output without the summary.
#[test]
fn report_csv_is_the_step_channel() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Through the first impact (the largest deflection at about 0.37 s) and into the rebound.
    std::fs::write(d.join("short.toml"), "duration = 0.45\n").unwrap();
    let out = beam_impact()
        .args(["run", "short.toml", "--mcap", "short.mcap", "--json", "short.json"])
        .current_dir(d)
        .output()
        .unwrap();
    ok(&out);
    let out = beam_impact()
        .args(["report", "short.mcap", "--csv", "steps.csv", "--out", "fig"])
        .current_dir(d)
        .output()
        .unwrap();
    ok(&out);
    let summary = String::from_utf8(out.stdout).unwrap();
    assert!(summary.contains("Table 1"), "the report is printed as without --csv:\n{summary}");
    let text = std::fs::read_to_string(d.join("steps.csv")).unwrap();
    let csv = Csv::parse(&text);

    assert_eq!(csv.header, HEADER);
    let set = FileDescriptorSet::decode(beam_impact_descriptor().as_slice()).unwrap();
    // Every column is a field of the step message: by its path, or by the FMU name of a renamed
    // path, and then the two columns are equal cell for cell.
    for name in &csv.header {
        let path =
            beam_impact::vocabulary::STEP_RENAMES.iter().find(|(_, n)| n == name).map_or(name.as_str(), |(p, _)| p);
        assert!(resolves_in_step(&set, path), "{name} ({path}) is not a field path of beam_impact.Step");
        let (i, j) =
            (csv.header.iter().position(|h| h == name).unwrap(), csv.header.iter().position(|h| h == path).unwrap());
        assert!(csv.rows.iter().all(|r| r[i] == r[j]), "{name} and {path} differ");
    }
    let units: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("steps.units.json")).unwrap()).unwrap();
    let unit_names: Vec<&str> =
        units["columns"].as_array().unwrap().iter().map(|c| c["name"].as_str().unwrap()).collect();
    assert_eq!(unit_names, HEADER, "the units sidecar lists every column in order");
    assert_eq!(units["columns"][8]["unit"], "Pa");
    assert_eq!(units["columns"][35]["same_as"], "lower.clamp_bending_stress");

    let log = read_log(&d.join("short.mcap")).unwrap();
    assert!(log.complete && log.rollbacks == 0);
    let messages = log.messages["/beam/step"];
    assert_eq!(csv.rows.len() as u64, messages, "one row per step message");
    assert_rows_are(&csv, &log.steps);
    assert!(summary.contains(&format!("({} step messages)", csv.rows.len())), "{summary}");

    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(d.join("short.json")).unwrap()).unwrap();
    let peaks = &doc["summary"]["peaks"];
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-300);
    let largest = |name: &str| csv.column(name).into_iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for name in [
        "lower_tip_deflection",
        "lower_clamp_bending_stress",
        "lower_clamp_shear_stress",
        "upper_contact_bending_stress",
        "contact_force",
    ] {
        let json = peaks[name].as_f64().unwrap();
        assert!(json > 0.0, "{name}: the run has a peak");
        let last = *csv.column(&format!("peaks.{name}")).last().unwrap();
        assert!(close(last, json), "peaks.{name}: last row {last} vs --json {json}");
        // The converged method's peaks are the largest |value| over each internal step, so at
        // least every step's end value, and within 5e-2 of the largest of them: its exact modal
        // advance steps up to 128x the plan's out of contact and in contact (where the bar's force
        // is a cubic over the step), over which a pulse crests between two step ends (measured on
        // the contact force: 2.4e-2; the clamp shear 3.8e-3; the same peaks from steps of the
        // plan's length move by 5e-5).
        let ends = largest(name);
        let within = 5e-2;
        assert!(ends <= json && json - ends <= within * json, "max |{name}| {ends} vs --json {json}");
    }
    let time = csv.column("time");
    assert!(close(*time.last().unwrap(), doc["summary"]["time"].as_f64().unwrap()));
    assert_eq!(*csv.column("step").last().unwrap(), doc["summary"]["steps"].as_f64().unwrap());
    assert!(time.windows(2).all(|w| w[0] < w[1]), "times increase");
    let contact = csv.header.iter().position(|h| h == "contact").unwrap();
    assert!(csv.rows.iter().any(|r| r[contact] == "true") && csv.rows.iter().any(|r| r[contact] == "false"));

    // `--csv -`: the CSV is the standard output, byte for byte, without the summary.
    let out =
        beam_impact().args(["report", "short.mcap", "--out", "fig", "--csv", "-"]).current_dir(d).output().unwrap();
    ok(&out);
    assert!(out.stdout == text.as_bytes(), "--csv - differs from --csv FILE");
    assert!(out.stderr.is_empty(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// The rows are the steps as the reader keeps them: a rolled-back branch is left out, the branch
/// that replaced it is in, one row per step index.
#[test]
fn report_csv_leaves_out_rolled_back_steps() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rollback.mcap");
    let scenario = Scenario::default();
    let options = RecorderOptions { scene_interval_ns: 0, ..RecorderOptions::default() };
    let mut recorder = McapRecorder::with_options(&path, options).unwrap();
    let shapes = nalgebra::DMatrix::<f64>::zeros(2, 2);
    let info = RunInfo {
        scenario: &scenario,
        lower_nodes: &[0.0, 12.0],
        upper_nodes: &[0.0, 29.0],
        nodal_shapes: &shapes,
        stations: None,
    };
    recorder.start(&info).unwrap();
    let step = |k: u64, branch: f64| {
        let mut r = StepResult {
            step: k,
            time_ns: k * 25_000,
            // As the solver: seconds(time_ns), which the reader also derives from time_ns.
            time: beam_impact::results::seconds(k * 25_000),
            step_size: if k == 0 { 0.0 } else { 25e-6 },
            // Never -0.0: protobuf leaves a zero out, and the reader reads +0.0.
            lower_tip_deflection: -1e-3 * (k + 1) as f64 * branch,
            ..StepResult::default()
        };
        r.peaks.lower_tip_deflection = 1e-3 * (k + 1) as f64 * branch;
        r.energy.residual = 1e-13 / 3.0 * branch;
        r
    };
    for k in 0..=100 {
        recorder.step(&step(k, 1.0), &[0.0, 0.0]).unwrap();
    }
    recorder.rollback(&step(50, 1.0)).unwrap();
    for k in 51..=80 {
        recorder.step(&step(k, 2.0), &[0.0, 0.0]).unwrap();
    }
    recorder.finish().unwrap();

    let out = beam_impact().arg("report").arg(&path).arg("--csv").arg("-").output().unwrap();
    ok(&out);
    let csv = Csv::parse(&String::from_utf8(out.stdout).unwrap());
    let kept: Vec<StepResult> = (0..=80).map(|k| step(k, if k <= 50 { 1.0 } else { 2.0 })).collect();
    assert_eq!(csv.header, HEADER);
    assert_rows_are(&csv, &kept);
    assert_eq!(read_log(&path).unwrap().rollbacks, 1);
}

/// Outputs from strangers, as `--json`: the log itself, a symbolic link and a FIFO are refused
/// (exit 2, one line, nothing touched); `--csv - | head` ends quietly with exit 0.
#[test]
fn report_csv_paths_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("tiny.toml"), "duration = 0.02\n").unwrap();
    ok(&beam_impact().args(["run", "tiny.toml"]).current_dir(d).output().unwrap());
    let log = std::fs::read(d.join("tiny.mcap")).unwrap();
    std::fs::write(d.join("target.txt"), "keep").unwrap();
    std::os::unix::fs::symlink(d.join("target.txt"), d.join("link.csv")).unwrap();
    std::fs::hard_link(d.join("tiny.mcap"), d.join("hard.csv")).unwrap();
    assert!(Command::new("mkfifo").arg(d.join("fifo.csv")).status().unwrap().success());
    for (csv, needle) in [
        ("tiny.mcap", "the log and --csv name the same file"),
        ("./tiny.mcap", "the log and --csv name the same file"),
        ("hard.csv", "the log and --csv name the same file"),
        ("link.csv", "symbolic link"),
        ("fifo.csv", "FIFO"),
    ] {
        let out = beam_impact().args(["report", "tiny.mcap", "--csv", csv]).current_dir(d).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "--csv {csv}");
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains(needle), "--csv {csv}: {stderr}");
        assert!(out.stdout.is_empty(), "--csv {csv}");
    }
    assert!(std::fs::read(d.join("tiny.mcap")).unwrap() == log, "the log is untouched");
    assert_eq!(std::fs::read_to_string(d.join("target.txt")).unwrap(), "keep");
    assert!(!Path::new(&d.join("tiny-figures")).exists(), "nothing was done before the refusal");

    let mut child = beam_impact()
        .args(["report", "tiny.mcap", "--csv", "-"])
        .current_dir(d)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take()); // the reader closes before the CSV is written
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.stderr.is_empty(), "{}", String::from_utf8_lossy(&out.stderr));
}
