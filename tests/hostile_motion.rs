//! Issue 27, hostile inputs round three, the CLI's side: the motion file is an input like any
//! other. Each test is one reproduction of the issue, run as the user ran it.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use beam_impact::record::mcap::McapRecorder;
use beam_impact::record::{Recorder, RunInfo};
use beam_impact::results::{ContactEvent, StepResult};
use beam_impact::{Result, Scenario, Simulation};

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

fn text(out: &Output) -> (String, String) {
    (String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// The vessel example (scenario and motion file) copied into `dir`, shortened to 0.2 s.
fn vessel_in(dir: &Path) -> (PathBuf, PathBuf) {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let scenario = dir.join("vessel.toml");
    let motion = dir.join("vessel-motion.csv");
    let toml =
        std::fs::read_to_string(examples.join("vessel.toml")).unwrap().replace("duration = 3.0", "duration = 0.2");
    assert!(toml.contains("duration = 0.2"));
    std::fs::write(&scenario, toml).unwrap();
    std::fs::copy(examples.join("vessel-motion.csv"), &motion).unwrap();
    (scenario, motion)
}

/// Item 1: a log of a run with moving supports replays by itself: `report`, `report --csv` and
/// the figures read the motion table from the log (the file is gone), not from disk.
#[test]
fn a_moving_support_run_is_reported_from_its_log_alone() {
    let dir = tempfile::tempdir().unwrap();
    let (scenario, motion) = vessel_in(dir.path());
    let log = dir.path().join("v.mcap");
    let out =
        beam_impact().args(["run", "--set", "method=paper"]).arg(&scenario).arg("--mcap").arg(&log).output().unwrap();
    assert!(out.status.code() == Some(0), "{:?}", text(&out));
    std::fs::remove_file(&motion).unwrap();
    let data = beam_impact::replay::report::read_log(&log).unwrap();
    let rows = data.motion_csv.as_deref().expect("the log holds motion.csv").lines().count();
    assert!(rows > 300, "{rows} lines of motion table");
    let stored = data.scenario().unwrap();
    assert_eq!(stored.motion.table.as_ref().map(|t| t.times.len()), Some(rows - 1));
    let figures = dir.path().join("figures");
    let out = beam_impact().arg("report").arg(&log).arg("--out").arg(&figures).output().unwrap();
    let (stdout, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(0), "{stdout}\n{stderr}");
    assert!(stdout.contains("status: complete") && !stdout.contains("note:"), "{stdout}");
    assert!(figures.join("fig6-deflection.svg").exists() || std::fs::read_dir(&figures).unwrap().count() > 3);
    let csv = dir.path().join("steps.csv");
    let out = beam_impact().arg("report").arg(&log).arg("--csv").arg(&csv).output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{:?}", text(&out));
    assert!(std::fs::metadata(&csv).unwrap().len() > 1000);
}

/// Forwards to an MCAP recorder, storing the scenario without its motion table: a log as the
/// versions before issue 27 wrote it (the scenario names the file; no `motion.csv`).
struct FormerRecorder(McapRecorder);

impl Recorder for FormerRecorder {
    fn start(&mut self, info: &RunInfo<'_>) -> Result<()> {
        let mut scenario = info.scenario.clone();
        scenario.motion.table = None;
        self.0.start(&RunInfo { scenario: &scenario, ..*info })
    }
    fn step(&mut self, result: &StepResult, q: &[f64]) -> Result<()> {
        self.0.step(result, q)
    }
    fn contact_event(&mut self, event: &ContactEvent) -> Result<()> {
        self.0.contact_event(event)
    }
    fn finish(&mut self) -> Result<()> {
        self.0.finish()
    }
}

/// Item 1: a log written before logs carried the motion table is reported with a note, not
/// refused.
#[test]
fn a_former_moving_support_log_is_reported_with_a_note() {
    let dir = tempfile::tempdir().unwrap();
    let (scenario_file, _) = vessel_in(dir.path());
    // The scenario as the CLI reads it (its motion table loaded), run through the library.
    let mut scenario = Scenario::from_toml(&std::fs::read_to_string(&scenario_file).unwrap(), "v").unwrap();
    let csv = std::fs::read_to_string(dir.path().join("vessel-motion.csv")).unwrap();
    scenario.motion.table =
        Some(std::sync::Arc::new(beam_impact::model::motion_table::MotionTable::parse(&csv).unwrap()));
    scenario.method = beam_impact::model::Method::Paper;
    let log = dir.path().join("former.mcap");
    let mut recorder = FormerRecorder(McapRecorder::create(&log).unwrap());
    let mut sim = Simulation::new(&scenario).unwrap();
    sim.run(&mut recorder).unwrap();
    let out = beam_impact().arg("report").arg(&log).arg("--out").arg(dir.path().join("f")).output().unwrap();
    let (stdout, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(0), "{stdout}\n{stderr}");
    assert!(
        stdout.contains("note: the run's supports moved (vessel-motion.csv), but the log holds no motion table"),
        "{stdout}"
    );
}

/// Item 2: the motion CSV is among the inputs the same-file guard compares, for `run --json`,
/// `run --mcap`, `sweep --out` and `verify --json`; the file is left as it was.
#[test]
fn the_motion_file_is_never_overwritten_by_an_output() {
    let dir = tempfile::tempdir().unwrap();
    let (scenario, motion) = vessel_in(dir.path());
    let before = std::fs::read(&motion).unwrap();
    let m = motion.to_str().unwrap();
    let s = scenario.to_str().unwrap();
    let cases: Vec<Vec<&str>> = vec![
        vec!["run", "--no-mcap", "--motion", m, "--json", m],
        vec!["run", "--motion", m, "--mcap", m],
        vec!["run", s, "--no-mcap", "--json", m],
        vec!["sweep", s, "--vary", "drop_height=0.2:0.4:2", "--out", m],
        vec!["verify", s, "--json", m],
    ];
    for args in cases {
        let out = beam_impact().args(&args).current_dir(dir.path()).output().unwrap();
        let (_, stderr) = text(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains("the motion file and") && stderr.contains("name the same file"), "{args:?}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
        assert_eq!(std::fs::read(&motion).unwrap(), before, "{args:?} changed the motion file");
    }
}

/// Item 4: a stranger's scenario cannot make the CLI print another file: `[motion] file` is a
/// relative path inside the scenario's folder, and no error quotes a line of a file that is not
/// a motion CSV; escape sequences in a file name reach no terminal.
#[test]
fn a_strangers_scenario_reaches_no_file_outside_its_folder_and_discloses_none() {
    let dir = tempfile::tempdir().unwrap();
    let secret = dir.path().join("secret.txt");
    std::fs::write(&secret, "SECRET_TOKEN=hunter2\n").unwrap();
    let inner = dir.path().join("inner");
    std::fs::create_dir(&inner).unwrap();
    for file in [secret.to_str().unwrap(), "../secret.txt", "/proc/self/environ", "sub/../../secret.txt"] {
        let scenario = inner.join("s.toml");
        std::fs::write(&scenario, format!("[motion]\nfile = {file:?}\n")).unwrap();
        let out =
            beam_impact().args(["run", "--no-mcap"]).arg(&scenario).env("SECRET_TOKEN", "hunter2").output().unwrap();
        let (_, stderr) = text(&out);
        assert_eq!(out.status.code(), Some(2), "{file}: {stderr}");
        assert!(
            stderr.contains("motion.file must be a path relative to the scenario file's folder"),
            "{file}: {stderr}"
        );
        assert!(!stderr.contains("hunter2"), "{file}: {stderr}");
    }
    // Inside the folder, a file that is not a motion CSV: named, nothing of it quoted.
    std::fs::copy(&secret, inner.join("secret.txt")).unwrap();
    std::fs::write(inner.join("s.toml"), "[motion]\nfile = \"secret.txt\"\n").unwrap();
    let out = beam_impact().args(["run", "--no-mcap"]).arg(inner.join("s.toml")).output().unwrap();
    let (_, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("is not a motion-file header") && !stderr.contains("hunter2"), "{stderr}");
    // `--motion` is the user's own choice of file: any path, still nothing quoted.
    let out = beam_impact().args(["run", "--no-mcap", "--motion"]).arg(&secret).output().unwrap();
    let (_, stderr) = text(&out);
    assert!(out.status.code() == Some(2) && !stderr.contains("hunter2"), "{stderr}");
    // A file name with an escape sequence is printed escaped.
    let hostile = inner.join("m\u{1b}[31m.csv");
    std::fs::write(&hostile, "time,upper.hinge_heave\n").unwrap();
    let out = beam_impact().args(["run", "--no-mcap", "--motion"]).arg(&hostile).output().unwrap();
    let (_, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(!stderr.contains('\u{1b}') && stderr.contains("m\\u{1b}[31m.csv"), "{stderr}");
}

/// Item 5: the motion file's size is checked from its metadata before a byte is read: a 2 GB
/// sparse file is refused at once; a 300 MB file of NUL bytes (beyond the 256 MiB limit) too.
#[test]
fn motion_files_are_bounded_before_they_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let sparse = dir.path().join("sparse.csv");
    std::fs::File::create(&sparse).unwrap().set_len(2_000_000_000).unwrap();
    let started = Instant::now();
    let out = beam_impact().args(["run", "--no-mcap", "--motion"]).arg(&sparse).output().unwrap();
    let (_, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("the motion file is 2000000000 bytes, larger than 268435456 bytes (the limit)"),
        "{stderr}"
    );
    // Refused before reading: a read of 256 MiB would take seconds and a quarter GiB of memory.
    // (Not a timed assertion of speed: a generous bound that only a read of the file breaks.)
    assert!(started.elapsed() < Duration::from_secs(20));
    // A FIFO: refused at once, without suggesting `--motion -` (which is no motion source).
    #[cfg(unix)]
    {
        let fifo = dir.path().join("fifo.csv");
        assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
        let out = beam_impact().args(["run", "--no-mcap", "--motion"]).arg(&fifo).output().unwrap();
        let (_, stderr) = text(&out);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(!stderr.contains("use - for"), "{stderr}");
    }
}

/// Item 6: support motion beyond the model's range is refused (a clamp rotation of 1.5 rad,
/// a heave acceleration of 1e5 m/s^2), naming the row and the input.
#[test]
fn support_motion_beyond_the_models_range_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let rotation = "time,lower.clamp_rotation,lower.clamp_rotation_velocity,lower.clamp_rotation_acceleration\n";
    let heave = "time,lower.clamp_heave,lower.clamp_heave_velocity,lower.clamp_heave_acceleration\n";
    let cases = [
        (
            format!("{rotation}0,1.5,0,0\n10,1.5,0,0\n"),
            "row 1 (line 2): lower.clamp_rotation must be finite with |value| <= 0.1 rad",
        ),
        (format!("{rotation}0,1000,0,0\n10,1000,0,0\n"), "lower.clamp_rotation must be finite with |value| <= 0.1 rad"),
        (
            format!("{heave}0,0,0,1e5\n10,0,0,1e5\n"),
            "lower.clamp_heave_acceleration must be finite with |value| <= 100 m/s2",
        ),
    ];
    for (i, (csv, expected)) in cases.iter().enumerate() {
        let path = dir.path().join(format!("m{i}.csv"));
        std::fs::write(&path, csv).unwrap();
        let out = beam_impact().args(["run", "--no-mcap", "--motion"]).arg(&path).output().unwrap();
        let (_, stderr) = text(&out);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(expected), "{stderr}");
    }
}

/// Item 6: a run whose arrestor deflects beyond the small-deflection range is not trusted, with
/// the reason (a heave acceleration within its bound, on a slender arrestor).
#[test]
fn a_run_beyond_the_small_deflection_range_is_not_trusted() {
    let mut scenario = Scenario::paper();
    scenario.method = beam_impact::model::Method::Paper;
    scenario.duration = 0.3;
    // A 100x softer arrestor under the drop: its end deflects metres.
    scenario.lower.elastic_modulus /= 100.0;
    let mut sim = Simulation::new(&scenario).unwrap();
    sim.run(&mut beam_impact::record::NullRecorder).unwrap();
    let quality = sim.quality();
    let peak = sim.result().peaks.lower_tip_deflection;
    assert!(peak > 1.2, "the arrestor's end deflects {peak} m");
    assert!(!quality.trusted);
    assert!(quality.reasons.iter().any(|r| r.starts_with("small deflection: the arrestor deflects")), "{quality:?}");
    // The paper's run stays within it (0.1 m of 12 m).
    let mut paper = Simulation::new(&Scenario::paper()).unwrap();
    paper.run(&mut beam_impact::record::NullRecorder).unwrap();
    assert!(!paper.quality().reasons.iter().any(|r| r.contains("small deflection")));
}

/// Item 7: an unwritable standard error (`2>/dev/full`) loses the warnings, never the run: the
/// exit code stays 0/3, the JSON is written, no `.partial` is left.
#[cfg(target_os = "linux")]
#[test]
fn an_unwritable_stderr_never_aborts_a_run() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("r.json");
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
    // The paper run warns (results not trusted: the paper mesh): the warning goes to /dev/full.
    let out = beam_impact()
        .args(["run", "--no-mcap", "--json"])
        .arg(&json)
        .current_dir(dir.path())
        .stderr(full)
        .output()
        .unwrap();
    assert!(matches!(out.status.code(), Some(0 | 3)), "exit {:?}", out.status);
    assert!(std::fs::read_to_string(&json).unwrap().contains("\"summary\""));
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().ends_with(".partial"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

/// Item 8: a scenario from standard input names its motion file relative to the current
/// folder; `motion.time_shift` without a motion file is refused, not ignored.
#[test]
fn stdin_scenarios_find_their_motion_file_and_a_shift_needs_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let (scenario, _) = vessel_in(dir.path());
    let mut child = beam_impact()
        .args(["run", "--set", "method=paper", "--no-mcap", "-"])
        .current_dir(dir.path())
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child.stdin.take().unwrap().write_all(&std::fs::read(&scenario).unwrap()).unwrap();
    let out = child.wait_with_output().unwrap();
    let (stdout, stderr) = text(&out);
    assert!(matches!(out.status.code(), Some(0 | 3)), "{stderr}");
    assert!(stdout.contains("supports moving: vessel-motion.csv"), "{stdout}");
    let out = beam_impact().args(["run", "--no-mcap", "--set", "motion.time_shift=2"]).output().unwrap();
    let (_, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("motion.time_shift must be 0 s without a motion file"), "{stderr}");
}

/// Item 8: an overflowing motion's error names the motion (it named only the tip forces).
#[test]
fn a_non_finite_step_names_the_support_motion() {
    let mut scenario = Scenario::paper();
    scenario.method = beam_impact::model::Method::Paper;
    scenario.duration = 0.01;
    let mut sim = Simulation::new(&scenario).unwrap();
    let motion = beam_impact::model::SupportMotion::from_values([0.0, 0.0, 1e308, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    sim.set_support_motion(motion);
    let e = sim.run(&mut beam_impact::record::NullRecorder).unwrap_err().to_string();
    assert!(e.contains("support motion: upper.hinge_heave_acceleration = 1.000000e308"), "{e}");
    assert!(e.len() < 400, "{e}");
}
