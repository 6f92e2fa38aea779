//! Issue 42: a scenario's `[sea]`: read with its RAO file (relative to the scenario's folder,
//! bounded, hashed), validated field by field with one-line errors, set and swept by name, and
//! run: the supports follow the sea's record as they follow a motion file.

use std::path::Path;

use beam_impact::model::sea::record::SeaRecord;
use beam_impact::record::NullRecorder;
use beam_impact::scenario_file::{from_text, read_file};
use beam_impact::studies::sweep::{apply_settings, parse_setting};
use beam_impact::{Scenario, Simulation};

pub const FIXTURE: &str = include_str!("fixtures/sea-raos.csv");

/// A `[sea]` section on the fixture's RAOs (`raos.csv` beside the scenario), Hs 1 m, Tp 8 s.
pub fn sea_toml(extra: &str) -> String {
    format!(
        "duration = 1.0\n\n[sea]\nsignificant_wave_height = 1.0\npeak_period = 8.0\nseed = 7\ntime_shift = 100.0\n\
         raos = \"raos.csv\"\nhinge_point = [-10.0, 0.0, 8.0]\nclamp_point = [15.0, 0.0, 8.0]\n{extra}"
    )
}

/// A folder with the fixture's RAOs as `raos.csv` and `text` as `s.toml`.
pub fn folder(text: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("raos.csv"), FIXTURE).unwrap();
    std::fs::write(dir.path().join("s.toml"), text).unwrap();
    dir
}

fn read(text: &str) -> beam_impact::Result<Scenario> {
    let dir = folder(text);
    read_file(&dir.path().join("s.toml"), &mut Vec::new())
}

#[test]
fn a_sea_scenario_reads_its_raos_beside_it_with_their_hash() {
    let s = read(&sea_toml("")).unwrap();
    let sea = s.sea.as_ref().unwrap();
    assert!(sea.rao_table.is_some());
    assert!(sea.raos.ends_with("raos.csv") && Path::new(&sea.raos).is_absolute() || sea.raos.contains("raos.csv"));
    // SHA-256 of the fixture's bytes, by `sha256sum tests/fixtures/sea-raos.csv`.
    assert_eq!(sea.rao_sha256.len(), 64);
    let expected = std::process::Command::new("sha256sum")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/sea-raos.csv"))
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).split_whitespace().next().unwrap_or("").to_string());
    if let Ok(expected) = expected {
        assert_eq!(sea.rao_sha256, expected);
    }
    // The defaults: JONSWAP by DNV's rule, head seas, 1000 components, 5 ms samples.
    assert_eq!((sea.heading, sea.components, sea.sample_interval, sea.arrestor_direction), (180.0, 1000, 0.005, 180.0));
    // The scenario reads back from its TOML (the RAO table is the CLI's, not the TOML's).
    let back = Scenario::from_toml(&s.to_toml(), "back").unwrap();
    assert_eq!(back.sea.as_ref().map(|x| x.seed), Some(7));
}

#[test]
fn a_sea_run_follows_the_record_sampled_on_its_grid() {
    let s = read(&sea_toml("")).unwrap();
    let sea = s.sea.as_ref().unwrap();
    let record = sea.record().unwrap();
    let table = sea.motion_table(s.duration).unwrap();
    // Rows on the record's grid k dt, from the last at or before time_shift to the first at or
    // after time_shift + duration: 100 s to 101 s every 5 ms, 201 rows.
    assert_eq!(table.times.len(), 201);
    assert_eq!(table.times[0], 20_000.0 * 0.005);
    // Rows at the record's multiples of ANCHOR_ROWS take their phases from sincos as
    // `SeaRecord::motion` does: the same bits. Between them each phase advances by a complex
    // product per row: at most 31 products' rounding, a few 1e-16 of each term; 1e-13 of the
    // column's scale (the sum of |terms| is below 100x the largest value here) would still catch
    // a phase off by one row (w dt = 5e-3 rad: 0.5 % of the value).
    for (k, t) in table.times.iter().enumerate().step_by(7) {
        let (row, exact) = (table.motions[k].values(), record.motion(*t).values());
        if (20_000 + k) % beam_impact::model::sea::record::ANCHOR_ROWS == 0 {
            assert_eq!(row, exact, "row {k}");
        }
        for (n, (a, b)) in row.iter().zip(exact).enumerate() {
            let scale = table.motions.iter().map(|m| m.values()[n].abs()).fold(0.0, f64::max);
            assert!((a - b).abs() <= 1e-13 * scale, "row {k} column {n}: {a} vs {b}");
        }
    }
    // The run starts from the record's motion at time_shift and follows its rows.
    assert_eq!(s.motion_at_start().unwrap(), record.motion(100.0));
    let changes = s.motion_changes(s.duration_ns()).unwrap();
    assert_eq!(changes.len(), 199);
    assert_eq!(changes[0], (5_000_000, table.motions[1]));
    let summary = Simulation::new(&s).unwrap().run(&mut NullRecorder).unwrap();
    assert!(summary.peaks.as_array().iter().all(|p| p.is_finite()));
    // The supports moved: the run differs from the fixed-support run's.
    let mut fixed = s.clone();
    fixed.sea = None;
    let still = Simulation::new(&fixed).unwrap().run(&mut NullRecorder).unwrap();
    assert_ne!(summary.peaks, still.peaks);
    assert!(record.motion(100.0).values().iter().any(|v| v.abs() > 1e-3));
    let _ = SeaRecord::grid(0.0, 1.0, 0.005);
}

#[test]
fn sea_and_motion_together_are_refused() {
    let dir = folder(&format!("{}\n[motion]\nfile = \"m.csv\"\n", sea_toml("")));
    let motion =
        "time,upper.hinge_heave,upper.hinge_heave_velocity,upper.hinge_heave_acceleration\n0,0,0,0\n1000,0,0,0\n";
    std::fs::write(dir.path().join("m.csv"), motion).unwrap();
    let e = read_file(&dir.path().join("s.toml"), &mut Vec::new()).unwrap_err().to_string();
    assert!(e.contains("[sea] and [motion] are both given"), "{e}");
    // `run --motion FILE` on a [sea] scenario: the same refusal when the run is validated.
    let mut s = read(&sea_toml("")).unwrap();
    beam_impact::scenario_file::load_motion(&mut s, &dir.path().join("m.csv"), &mut Vec::new()).unwrap();
    let e = s.validate().unwrap_err().to_string();
    assert!(e.contains("[sea] and [motion] are both given"), "{e}");
}

#[test]
fn bad_sea_fields_are_one_line_errors_naming_the_field() {
    let base = |field: &str, value: &str| {
        sea_toml("")
            .lines()
            .map(|l| if l.starts_with(&format!("{field} =")) { format!("{field} = {value}") } else { l.to_string() })
            .collect::<Vec<_>>()
            .join("\n")
    };
    let cases: Vec<(String, &str)> = vec![
        (base("significant_wave_height", "-1.0"), "sea.significant_wave_height must be > 0 m, at most 20 m, got -1"),
        (base("significant_wave_height", "nan"), "sea.significant_wave_height must be"),
        (base("peak_period", "50.0"), "sea.peak_period must be between 2 and 30 s, got 50"),
        (base("significant_wave_height", "15.0"), "steeper than a sea can be"),
        (sea_toml("peak_enhancement = 9.0\n"), "sea.peak_enhancement must be between 1 and 7"),
        (
            sea_toml("spectrum = \"pierson-moskowitz\"\npeak_enhancement = 2.0\n"),
            "left out with spectrum = \"pierson-moskowitz\"",
        ),
        (sea_toml("spectrum = \"bretschneider\"\n"), "unknown variant `bretschneider`"),
        (sea_toml("heading = 400.0\n"), "sea.heading must be between 0 and 360 deg, got 400"),
        (sea_toml("components = 0\n"), "sea.components must be between 1 and 100000, got 0"),
        (sea_toml("frequency_min = 2.0\nfrequency_max = 1.0\n"), "sea.frequency_max must be > sea.frequency_min"),
        (
            sea_toml("frequency_min = 0.01\n"),
            "sea.frequency_min must be within the RAO file's frequencies, 0.1 to 4 rad/s",
        ),
        (sea_toml("frequency_min = 1.5\n"), "holds"),
        (sea_toml("sample_interval = 0.0\n"), "sea.sample_interval must be between 1e-4 and 0.1 s, got 0"),
        (sea_toml("arrestor_direction = -1.0\n"), "sea.arrestor_direction must be between 0 and 360 deg"),
        (
            sea_toml("time_shift = -5.0\n").replace("time_shift = 100.0\n", ""),
            "sea.time_shift must be between 0 and 1e6 s",
        ),
        (sea_toml("wave_height = 1.0\n"), "unknown field `wave_height`"),
        (base("hinge_point", "[1.0, 2.0]"), "invalid length 2"),
        (base("hinge_point", "[1e4, 0.0, 0.0]"), "sea.hinge_point must be [x, y, z] with each |coordinate| <= 500 m"),
        (base("raos", "\"../raos.csv\""), "sea.raos must be a path relative to the scenario file's folder"),
        (base("raos", "\"/etc/passwd\""), "sea.raos must be a path relative to the scenario file's folder"),
        (base("raos", "\"missing.csv\""), "cannot read RAO file"),
        (base("raos", "\".\""), "cannot read RAO file"),
        (base("raos", "\"s.toml\""), "is not an RAO CSV header"),
        (
            sea_toml("").replace("hinge_point = [-10.0, 0.0, 8.0]\nclamp_point = [15.0, 0.0, 8.0]\n", ""),
            "has neither sea.hinge_point nor sea.clamp_point",
        ),
        (sea_toml("").replace("significant_wave_height = 1.0\n", ""), "missing field `significant_wave_height`"),
    ];
    for (text, expected) in cases {
        let e = read(&text).unwrap_err().to_string();
        assert!(e.contains(expected), "{expected:?}: {e}");
        assert!(!e.contains('\n'), "{e}");
    }
}

#[test]
fn a_fifo_named_as_the_rao_file_is_refused_at_once() {
    let dir = folder(&sea_toml("").replace("raos.csv", "fifo.csv"));
    let fifo = dir.path().join("fifo.csv");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let started = std::time::Instant::now();
    let e = read_file(&dir.path().join("s.toml"), &mut Vec::new()).unwrap_err().to_string();
    assert!(e.contains("cannot read RAO file") && e.contains("FIFO"), "{e}");
    assert!(started.elapsed().as_secs_f64() < 1.0);
}

#[test]
fn set_and_vary_reach_every_sea_field_by_name() {
    let mut s = read(&sea_toml("")).unwrap();
    let settings: Vec<_> = [
        "sea.significant_wave_height=1.5",
        "sea.peak_period=9",
        "sea.spectrum=pierson-moskowitz",
        "sea.heading=150",
        "sea.seed=123456789012",
        "sea.components=500",
        "sea.frequency_min=0.4",
        "sea.frequency_max=3",
        "sea.time_shift=50",
        "sea.arrestor_direction=170",
        "sea.sample_interval=0.01",
        "sea.hinge_point.x=-12",
        "sea.clamp_point.z=9",
    ]
    .iter()
    .map(|t| parse_setting(t).unwrap())
    .collect();
    apply_settings(&mut s, &settings).unwrap();
    let sea = s.sea.as_ref().unwrap();
    assert_eq!(
        (sea.significant_wave_height, sea.peak_period, sea.heading, sea.seed),
        (1.5, 9.0, 150.0, 123_456_789_012)
    );
    assert_eq!(sea.spectrum, beam_impact::model::sea::SpectrumKind::PiersonMoskowitz);
    assert_eq!((sea.frequency_min, sea.frequency_max, sea.components), (Some(0.4), Some(3.0), 500));
    assert_eq!((sea.hinge_point, sea.clamp_point), (Some([-12.0, 0.0, 8.0]), Some([15.0, 0.0, 9.0])));
    // A setting out of range is validation's error; a [sea] field on a scenario without one, its own.
    let e = apply_settings(&mut s, &[parse_setting("sea.heading=-1").unwrap()]).unwrap_err().to_string();
    assert!(e.contains("sea.heading must be between 0 and 360"), "{e}");
    let e = apply_settings(&mut Scenario::default(), &[parse_setting("sea.seed=2").unwrap()]).unwrap_err().to_string();
    assert!(e.contains("sea.seed is a field of [sea], and the scenario has none"), "{e}");
    let e = parse_setting("sea.spectrum=bretschneider").unwrap_err().to_string();
    assert!(e.contains("jonswap or pierson-moskowitz"), "{e}");
    let e = apply_settings(&mut s, &[parse_setting("sea.seed=1.5").unwrap()]).unwrap_err().to_string();
    assert!(e.contains("sea.seed must be a whole number"), "{e}");
}

#[test]
fn a_scenario_text_names_its_raos_relative_to_the_folder_given() {
    let dir = folder("");
    let s = from_text(&sea_toml(""), "text", dir.path(), &mut Vec::new()).unwrap();
    assert!(s.sea.unwrap().rao_table.is_some());
}
