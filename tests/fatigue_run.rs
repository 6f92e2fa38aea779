//! Issue 44 item 3, the fatigue of a run: every bending station's stress history kept as turning
//! points while the printed run steps, counted by rainflow and summed by Miner on the scenario's
//! `[fatigue]` curve; the same from the log (`report --fatigue`, `load_log`); the `[fatigue]`
//! fields' bounds.

use std::process::Command;
use std::sync::atomic::AtomicBool;

use beam_impact::fatigue::{count, damage, reversals};
use beam_impact::model::fatigue_settings::FatigueSettings;
use beam_impact::model::Scenario;
use beam_impact::record::{MemoryRecorder, NullRecorder};
use beam_impact::run_fatigue::{assess, StationHistories};
use beam_impact::Simulation;

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

/// The paper method's run keeps each station's value at every step's end (its steps are short
/// and fixed; no cubic inside them): its turning points are those of the stresses at every
/// recorded step, rebuilt here from the recorder's modal coordinates with the envelope's own
/// product. Their rainflow cycles and Miner's damage (F1's library on the rebuilt f64 histories)
/// equal the run's to 1e-9 relative: the same samples, so the same turning points; the bound
/// only allows the summation order of the damage (~1e-15).
#[test]
fn a_runs_damage_is_rainflow_and_miner_of_its_every_step_stresses() {
    let scenario = Scenario { duration: 0.6, ..Scenario::paper() };
    let mut sim = Simulation::new(&scenario).unwrap();
    sim.keep_turning_points();
    let mut recorder = MemoryRecorder::default();
    sim.run(&mut recorder).unwrap();
    let (points, stride) = sim.turning_points().expect("kept");
    assert_eq!(stride, 1);
    let histories = StationHistories::of_run(sim.model(), &points, stride);
    let settings = FatigueSettings::default();
    let run = assess(&histories, &settings).unwrap();
    // Every recorded step's stresses (step 0 the initial state).
    let n = sim.model().stations.len();
    let mut rows = Vec::new();
    let mut out = vec![0.0; n];
    for q in &recorder.coordinates {
        sim.station_stresses(q, &mut out);
        rows.push(out.clone());
    }
    assert_eq!(rows.len() as u64, recorder.steps.last().unwrap().step + 1, "every step recorded");
    let (curve, options) = (settings.curve().unwrap(), settings.options());
    let mut compared = 0;
    for (i, &k) in points.stations().iter().enumerate() {
        let history: Vec<f64> = rows.iter().map(|r| r[k]).collect();
        let expected = reversals(&history).unwrap();
        assert_eq!(histories.stations[i].reversals, expected, "station {k}'s turning points");
        let d = damage(&count(&expected), &curve, &options);
        let beam = &histories.stations[i].beam;
        let got = if beam == "upper" { &run.stations.upper } else { &run.stations.lower };
        let j = histories.stations[..i].iter().filter(|s| &s.beam == beam).count();
        assert!((got.damage[j] - d).abs() <= 1e-9 * d.abs(), "station {k}: {} vs {d}", got.damage[j]);
        compared += 1;
    }
    assert!(compared > 20, "{compared}");
    assert!(run.worst().unwrap().damage > 0.0);
}

/// On a one-slope curve (D in free corrosion: m = 3 throughout, DNV-RP-C203 2016 Table 2-4) the
/// damage scales as SCF^3 exactly, and with the DFF linearly: every station of a run, to 1e-12
/// (one factor in each term's power).
#[test]
fn damage_scales_as_scf_to_the_slope_and_with_the_dff() {
    let scenario = Scenario { duration: 0.5, ..Scenario::default() };
    let mut sim = Simulation::new(&scenario).unwrap();
    sim.keep_turning_points();
    sim.run(&mut NullRecorder).unwrap();
    let (points, stride) = sim.turning_points().unwrap();
    let histories = StationHistories::of_run(sim.model(), &points, stride);
    let base = FatigueSettings { curve: "D-free-corrosion".into(), ..Default::default() };
    let one = assess(&histories, &base).unwrap();
    let scaled = assess(&histories, &FatigueSettings { scf: 1.7, design_fatigue_factor: 3.0, ..base.clone() }).unwrap();
    let factor = 1.7f64.powi(3) * 3.0;
    for (a, b) in one
        .stations
        .lower
        .damage
        .iter()
        .chain(&one.stations.upper.damage)
        .zip(scaled.stations.lower.damage.iter().chain(&scaled.stations.upper.damage))
    {
        assert!((b - a * factor).abs() <= 1e-12 * b.abs(), "{a} {b}");
    }
    // On the bilinear D in air, between the branches' SCF^3 and SCF^5.
    let air = assess(&histories, &FatigueSettings::default()).unwrap().worst().unwrap().damage;
    let air2 = assess(&histories, &FatigueSettings { scf: 2.0, ..Default::default() }).unwrap().worst().unwrap().damage;
    assert!(air2 >= 8.0 * air * (1.0 - 1e-12) && air2 <= 32.0 * air * (1.0 + 1e-12), "{air} {air2}");
}

/// A grid of drop heights 0.1 to 2 m (the default scenario, 1 s): the worst station's damage per
/// impact grows with the drop height (each higher drop strikes harder: larger ranges).
#[test]
fn damage_grows_with_the_drop_height() {
    let mut previous = 0.0;
    for h in [0.1, 0.3, 0.6, 1.0, 1.5, 2.0] {
        let scenario = Scenario { drop_height: h, duration: 1.0, ..Scenario::default() };
        let mut sim = Simulation::new(&scenario).unwrap();
        sim.keep_turning_points();
        sim.run(&mut NullRecorder).unwrap();
        let (points, stride) = sim.turning_points().unwrap();
        let f = assess(&StationHistories::of_run(sim.model(), &points, stride), &FatigueSettings::default()).unwrap();
        let d = f.worst().unwrap().damage;
        assert!(d > previous, "drop {h} m: damage {d} after {previous}");
        previous = d;
    }
}

/// `run --json`'s fatigue block, the log's `report --fatigue` and the library's replay of the
/// log agree: the same histories (the log's fatigue.json) give the same numbers, to the bit.
#[test]
fn report_replays_the_runs_fatigue() {
    let dir = tempfile::tempdir().unwrap();
    let (log, json) = (dir.path().join("run.mcap"), dir.path().join("run.json"));
    let out = beam_impact()
        .args(["run", "--set", "duration=1", "--set", "fatigue.events_per_year=500", "--set", "fatigue.scf=1.3"])
        .arg("--mcap")
        .arg(&log)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("fatigue (D, SCF 1.3, DFF 1): worst "), "{text}");
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let block = &doc["fatigue"];
    assert_eq!(block["source"], "every step");
    assert!(block["life_years"].as_f64().unwrap() > 0.0);
    let data = beam_impact::replay::report::read_log(&log).unwrap();
    let replayed = beam_impact::replay::fatigue::fatigue_of_log(&data, None).unwrap();
    assert_eq!(&serde_json::to_value(&replayed).unwrap(), block);
    // The printed report says the worst damage as the run's line does.
    let out = beam_impact().arg("report").arg(&log).arg("--fatigue").output().unwrap();
    assert!(out.status.success());
    let report = String::from_utf8_lossy(&out.stdout);
    let worst = block["worst"]["upper"]["damage"].as_f64().unwrap();
    assert!(report.contains(&format!("{worst:.4e}")), "{report}");
    // Another curve from the same log: F3 lies below D, so more damage.
    let f3 = beam_impact::replay::fatigue::fatigue_of_log(&data, Some("F3")).unwrap();
    assert!(f3.worst().unwrap().damage > replayed.worst().unwrap().damage);
    // Rebuilt from the /beam/stations rows when the attachment is missing: said so, and a lower
    // bound in practice (rows every 1 ms in single precision miss faster cycles); within a factor.
    let mut without = data.clone();
    without.fatigue_json = None;
    let rebuilt = beam_impact::replay::fatigue::fatigue_of_log(&without, None).unwrap();
    assert_eq!(rebuilt.source, beam_impact::run_fatigue::LOG_ROWS);
    assert!(rebuilt.note.as_deref().unwrap_or("").contains("lower bound"));
    let (r, e) = (rebuilt.worst().unwrap().damage, replayed.worst().unwrap().damage);
    assert!(r > 0.0 && r < 1.5 * e, "{r} {e}");
}

/// Hostile `[fatigue]` values, by `--set`, in a scenario file and in a stored fatigue.json: one
/// line naming the field, exit 2 from the CLI, never a panic.
#[test]
fn hostile_fatigue_fields_are_refused_in_one_line() {
    let cases = [
        ("fatigue.scf=0.5", "fatigue.scf"),
        ("fatigue.scf=nan", "fatigue.scf"),
        ("fatigue.scf=1e300", "fatigue.scf"),
        ("fatigue.thickness=-1", "fatigue.thickness"),
        ("fatigue.thickness=inf", "fatigue.thickness"),
        ("fatigue.design_fatigue_factor=0", "fatigue.design_fatigue_factor"),
        ("fatigue.events_per_year=-3", "fatigue.events_per_year"),
        ("fatigue.events_per_year=1e308", "fatigue.events_per_year"),
        ("fatigue.curve=Q", "fatigue.curve"),
        ("fatigue.curve=99", "fatigue.curve"),
        ("fatigue.curve=-1", "fatigue.curve"),
    ];
    for (setting, name) in cases {
        let out =
            beam_impact().args(["run", "--no-mcap", "--set", "duration=0.01", "--set", setting]).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{setting}: {err}");
        assert!(err.contains(name) && err.trim().lines().count() == 1, "{setting}: {err}");
    }
    for (toml, key) in [
        ("[fatigue]\ncurve = 3\n", "curve"),
        ("[fatigue]\nscf = \"big\"\n", "scf"),
        ("[fatigue]\nunknown = 1\n", "unknown"),
        ("[fatigue]\ncurve = \"<script>\"\n", "fatigue.curve"),
        ("[fatigue]\nthickness = 0.0\n", "fatigue.thickness"),
    ] {
        let result = Scenario::from_toml(toml, "hostile.toml").and_then(|s| s.validate().map(|_| s));
        let e = result.expect_err(toml).to_string();
        assert!(e.lines().count() == 1 && e.contains(key), "{toml}: {e}");
    }
    // A hostile stored history: refused by name, never a panic.
    for text in [
        "",
        "{}",
        "{\"format\":2,\"source\":\"x\",\"sampled_every\":1,\"contact_position\":0,\"stations\":[]}",
        "{\"format\":1,\"source\":\"x\",\"sampled_every\":1,\"contact_position\":0,\"stations\":[{\"beam\":\"mid\",\"position\":0,\"reversals\":[]}]}",
        "{\"format\":1,\"source\":\"x\",\"sampled_every\":1,\"contact_position\":0,\"stations\":[{\"beam\":\"upper\",\"position\":0,\"reversals\":[1e400]}]}",
    ] {
        assert!(StationHistories::from_json(text).is_err(), "{text}");
    }
    // Degenerate but valid histories: no station, one sample, a constant: no damage, no panic.
    for reversals in [vec![], vec![1.0], vec![2.0, 2.0]] {
        let h = StationHistories {
            format: 1,
            source: "x".into(),
            sampled_every: 1,
            contact_position: f64::NAN,
            stations: vec![beam_impact::run_fatigue::StationHistory { beam: "upper".into(), position: 0.0, reversals }],
        };
        let f = assess(&h, &FatigueSettings { events_per_year: Some(10.0), ..Default::default() }).unwrap();
        assert_eq!(f.worst().unwrap().damage, 0.0);
        assert_eq!(f.life_years, None);
    }
}

/// `one_run::run` attaches fatigue.json only with every station's envelope (a sweep's row keeps
/// the peaks and pays nothing for fatigue).
#[test]
fn only_a_run_with_every_stations_envelope_keeps_the_histories() {
    let scenario = Scenario { duration: 0.2, ..Scenario::default() };
    let cancel = AtomicBool::new(false);
    let options = beam_impact::answer::Options { sensitivity: false, ..Default::default() };
    let full = beam_impact::one_run::run(&scenario, &mut NullRecorder, options, &cancel).unwrap();
    assert!(full.station_histories.is_some());
    let peaks = beam_impact::answer::Options { station_envelope: false, ..options };
    let row = beam_impact::one_run::run(&scenario, &mut NullRecorder, peaks, &cancel).unwrap();
    assert!(row.station_histories.is_none());
    let doc = beam_impact::run_document::document(&scenario, &row, 0.0).unwrap();
    assert!(doc["fatigue"].is_null());
}

/// Keeping the turning points changes nothing of the run: its summary (peaks, times, envelope,
/// energies) is the same to the bit with and without, on the exact advance and the paper method.
#[test]
fn keeping_turning_points_changes_nothing_of_the_run() {
    for scenario in [Scenario { duration: 0.5, ..Scenario::default() }, Scenario { duration: 0.3, ..Scenario::paper() }]
    {
        let mut plain = Simulation::new(&scenario).unwrap();
        let a = plain.run(&mut NullRecorder).unwrap();
        let mut kept = Simulation::new(&scenario).unwrap();
        kept.keep_turning_points();
        let b = kept.run(&mut NullRecorder).unwrap();
        assert_eq!(format!("{a:?}"), format!("{b:?}"));
    }
}

/// Hostile values for every `[fatigue]` field through `--set`'s parser and the scenario's
/// validation (random bit patterns, the extremes, the words): each is accepted within its bounds
/// or refused in one line naming the field; a fatigue assessed with an accepted one is finite or
/// zero, never NaN, and nothing panics.
#[test]
fn random_fatigue_settings_are_bounded_or_refused() {
    use beam_impact::studies::sweep::{apply_settings, parse_setting};
    let mut seed = 0x00FA_7165u64;
    let mut random = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        seed
    };
    let histories = StationHistories {
        format: 1,
        source: "x".into(),
        sampled_every: 1,
        contact_position: 0.0,
        stations: vec![beam_impact::run_fatigue::StationHistory {
            beam: "lower".into(),
            position: 0.0,
            reversals: vec![0.0, 3e8, -2e8, 1e8, -4e8, 0.0],
        }],
    };
    let fields = [
        "fatigue.curve",
        "fatigue.scf",
        "fatigue.thickness",
        "fatigue.design_fatigue_factor",
        "fatigue.events_per_year",
    ];
    let words = ["nan", "inf", "-inf", "-0", "0", "1e-320", "1e308", "D", "W3-free-corrosion", "", "x", "1e999"];
    let (mut accepted, mut refused) = (0, 0);
    for i in 0..3000 {
        let field = fields[i % fields.len()];
        let value = if i % 3 == 0 {
            words[(i / 3) % words.len()].to_string()
        } else {
            format!("{:e}", f64::from_bits(random()))
        };
        let Ok(setting) = parse_setting(&format!("{field}={value}")) else {
            refused += 1;
            continue;
        };
        let mut scenario = Scenario::default();
        match apply_settings(&mut scenario, &[setting]) {
            Ok(()) => {
                accepted += 1;
                let settings = scenario.fatigue.clone().unwrap_or_default();
                let f = assess(&histories, &settings).unwrap();
                let d = f.worst().unwrap().damage;
                assert!(d.is_finite() && d > 0.0, "{field}={value}: {d}");
                assert!(f.life_years.is_none_or(|l| l.is_finite() && l > 0.0), "{field}={value}");
            }
            Err(e) => {
                refused += 1;
                let text = e.to_string();
                assert!(text.contains(field) && text.lines().count() == 1, "{field}={value}: {text}");
            }
        }
    }
    assert!(accepted > 50 && refused > 500, "{accepted} accepted, {refused} refused");
}
