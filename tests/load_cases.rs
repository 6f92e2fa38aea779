//! Issue 44 item 2: a scenario's `[[load_cases]]`. A unit case reproduces the plain design check;
//! a case that changes fields is the converged answer of that scenario, to the bit; the factors act
//! on their own parts as `model::load_case` states; `design.pass` is every case's verdict; the
//! governing case of a quantity is its largest factored utilisation; bad cases are refused in one
//! line naming the case; `report` and the log's `answer.json` replay the cases the run printed and
//! its dynamic amplification.

use std::collections::BTreeMap;
use std::process::Command;

use beam_impact::answer::{self, Answer};
use beam_impact::model::load_case::{LoadCase, SetValue};
use beam_impact::record::NullRecorder;
use beam_impact::Scenario;

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

/// The default scenario over `duration` s (the first impact and its rebound: 0.6 s holds the
/// clamp's first crest at 0.36 s) with the given cases.
fn scenario(duration: f64, cases: Vec<LoadCase>) -> Scenario {
    Scenario { duration, load_cases: cases, ..Scenario::default() }
}

/// The answer with its cases judged, as `run` (CLI and Python), a sweep's rows and a campaign's
/// events make it.
fn answer_of(s: &Scenario) -> Answer {
    let cache = answer::own_cache();
    beam_impact::studies::sweep::answer_with_cases(
        s,
        &mut NullRecorder,
        Default::default(),
        &cache,
        &Default::default(),
    )
    .unwrap()
}

/// The plain check's utilisation of each quantity by the FMU's names.
fn plain_utilisation(a: &Answer) -> BTreeMap<String, f64> {
    let u = &a.design.utilisation;
    let mut m: BTreeMap<String, f64> = answer::DesignUtilisation::NAMES
        .iter()
        .zip(u.as_array())
        .map(|(n, v)| (beam_impact::vocabulary::quantity_name(n).to_string(), v))
        .collect();
    for (n, v) in beam_impact::results::ENVELOPE_PEAK_NAMES.iter().zip(u.envelope()) {
        if let Some(v) = v {
            m.insert(n.to_string(), v);
        }
    }
    m
}

/// Unit factors and no field changed: S + max(P - S, 0) = P, so every factored utilisation is the
/// plain check's (to round-off: the division by A and the sum S + (P - S) differ in the last
/// bits, 1e-12 relative), across drop heights 0.1-2 m and damping 0-0.05.
#[test]
fn a_unit_case_reproduces_the_plain_design_check_across_the_grid() {
    for (drop_height, damping_ratio) in [(0.1, 0.0), (0.567, 0.03), (2.0, 0.05)] {
        let s = Scenario { drop_height, damping_ratio, ..scenario(0.6, vec![LoadCase::named("plain")]) };
        let a = answer_of(&s);
        let cases = a.load_cases.as_ref().expect("the cases are judged");
        let plain = plain_utilisation(&a);
        let case = &cases.cases[0];
        assert_eq!(case.quantities.len(), plain.len(), "h = {drop_height}: {:?}", case.quantities.keys());
        for (name, u) in &plain {
            let got = case.quantities[name].utilisation;
            assert!((got - u).abs() <= 1e-12 * u.abs().max(1e-300), "h = {drop_height}, {name}: {got} vs plain {u}");
        }
        assert_eq!(case.pass, plain.values().all(|u| *u <= 1.0));
        assert_eq!(a.design.pass, case.pass);
    }
}

/// A case that sets fields is judged on the converged answer of the scenario with them set, as
/// `run --set` gives it: its peaks are that answer's to the bit.
#[test]
fn a_case_that_sets_fields_is_judged_on_that_scenarios_own_answer() {
    let mut heavy = LoadCase::named("heavy-tip");
    heavy.set.insert("drop_height".into(), SetValue::Number(1.2));
    heavy.set.insert("lower.tip_mass".into(), SetValue::Number(2500.0));
    heavy.set.insert("step_free".into(), SetValue::Word("auto".into()));
    let a = answer_of(&scenario(0.6, vec![LoadCase::named("plain"), heavy]));
    let direct = answer_of(&Scenario {
        drop_height: 1.2,
        lower: beam_impact::model::scenario::LowerBeam { tip_mass: 2500.0, ..Default::default() },
        ..scenario(0.6, vec![])
    });
    let case = &a.load_cases.as_ref().unwrap().cases[1];
    assert_eq!(case.name, "heavy-tip");
    assert_eq!(case.quantities["lower.clamp_bending_stress"].peak, direct.converged_peaks.lower_clamp_bending_stress);
    assert_eq!(
        case.quantities["upper.contact_bending_stress"].peak,
        direct.converged_peaks.upper_contact_bending_stress
    );
    assert_eq!(case.trusted, direct.quality.trusted);
    // Its unit factors give the direct answer's own plain utilisations.
    for (name, u) in plain_utilisation(&direct) {
        let got = case.quantities[&name].utilisation;
        assert!((got - u).abs() <= 1e-12 * u, "{name}: {got} vs {u}");
    }
    assert_eq!(case.set["drop_height"], "1.2");
}

/// The allowable and material factors scale every utilisation by gamma_M / f_A exactly; a case
/// that fails fails the design though the plain check passes, and it governs every quantity.
#[test]
fn design_pass_is_every_cases_verdict_and_the_governing_case_is_the_largest() {
    let strict = LoadCase { allowable_factor: 0.8, material_factor: 1.25, ..LoadCase::named("strict") };
    let lenient = LoadCase { allowable_factor: 1.5, ..LoadCase::named("lenient") };
    let a = answer_of(&scenario(0.6, vec![lenient, strict]));
    let plain = plain_utilisation(&a);
    let cases = a.load_cases.as_ref().unwrap();
    let worst_plain = plain.values().cloned().fold(0.0, f64::max);
    assert!(worst_plain < 1.0 && worst_plain * 1.25 / 0.8 > 1.0, "the default's worst plain utilisation {worst_plain}");
    for (name, u) in &plain {
        let strict = cases.cases[1].quantities[name].utilisation;
        let lenient = cases.cases[0].quantities[name].utilisation;
        // Unit load factors: u_case = u_plain gamma_M / f_A (1e-12: round-off of two products).
        assert!((strict - u * 1.25 / 0.8).abs() <= 1e-12 * strict, "{name}");
        assert!((lenient - u / 1.5).abs() <= 1e-12 * lenient, "{name}");
        assert_eq!(cases.governing[name].case, "strict", "{name}");
        assert_eq!(cases.governing[name].utilisation, strict);
    }
    assert!(cases.cases[0].pass && !cases.cases[1].pass);
    assert!(!cases.pass && !a.design.pass);
    // The plain check's own utilisations are untouched.
    assert!(a.design.utilisation.as_array().iter().all(|u| *u < 1.0));
}

/// Without load cases the answer is today's: no block, `design.pass` the plain check's.
#[test]
fn a_scenario_without_cases_has_no_load_case_block() {
    let a = answer_of(&scenario(0.3, vec![]));
    assert!(a.load_cases.is_none());
    let doc = beam_impact::run_document::document(&a.resolved, &a, 0.0).unwrap();
    assert!(doc["load_cases"].is_null());
}

fn run_cli(dir: &std::path::Path, text: &str, extra: &[&str]) -> std::process::Output {
    std::fs::write(dir.join("s.toml"), text).unwrap();
    beam_impact().arg("run").arg("s.toml").args(extra).current_dir(dir).output().unwrap()
}

/// Bad cases: each refused before any run, in one line that names the case and the field.
#[test]
fn bad_cases_are_refused_in_one_line_naming_the_case() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("[[load_cases]]\nname = \"a\"\nset = { no_such_field = 1 }\n", "load case \"a\""),
        ("[[load_cases]]\nname = \"a\"\nset = { drop_height = -3 }\n", "drop_height"),
        ("[[load_cases]]\nname = \"a\"\ndynamic_factor = 13\n", "dynamic_factor must be >= 0 and at most 10, got 13"),
        ("[[load_cases]]\nname = \"a\"\nmaterial_factor = 0\n", "material_factor must be > 0"),
        ("[[load_cases]]\nname = \"<script>\"\n", "load_cases[0].name must be"),
        ("[[load_cases]]\nname = \"a\"\n[[load_cases]]\nname = \"a\"\n", "names an earlier case"),
        ("[[load_cases]]\nname = \"a\"\nset = { duration = 5 }\n", "set.duration cannot differ"),
        ("[[load_cases]]\nname = \"a\"\nfactor = 2\n", "unknown field `factor`"),
        ("[[load_cases]]\nname = \"a\"\nset = { \"lower.kind\" = \"wobbly\" }\n", "lower.kind"),
    ];
    for (text, expected) in cases {
        let o = run_cli(dir.path(), &format!("duration = 0.2\n{text}"), &["--no-mcap"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{text}: {err}");
        assert!(err.contains(expected), "{text}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{text}: {err}");
    }
}

/// The run prints the cases; `--json` holds them; the log's `answer.json` keeps them and `report`
/// prints the same lines the run printed.
#[test]
fn report_replays_the_cases_the_run_printed() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/load-cases.toml")).unwrap();
    let o = run_cli(dir.path(), &format!("duration = 0.6\n{text}"), &["--json", "run.json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let printed = String::from_utf8_lossy(&o.stdout).to_string();
    let block: Vec<&str> = printed
        .lines()
        .skip_while(|l| !l.starts_with("Load cases"))
        .take_while(|l| !l.starts_with("design:"))
        .collect();
    assert!(block.len() >= 5, "{printed}");
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("run.json")).unwrap()).unwrap();
    assert_eq!(doc["load_cases"]["cases"].as_array().unwrap().len(), 3);
    assert_eq!(doc["design"]["pass"], doc["load_cases"]["pass"]);
    let r = beam_impact().arg("report").arg("s.mcap").current_dir(dir.path()).output().unwrap();
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let report = String::from_utf8_lossy(&r.stdout).to_string();
    for line in &block {
        assert!(report.contains(line), "report lacks {line:?}:\n{report}");
    }
    // The dynamic amplification the run stored, each DAF as the run's JSON has it (3 decimals).
    let daf = doc["dynamic_amplification"]["daf"].as_object().unwrap();
    let line = report.lines().find(|l| l.starts_with("dynamic amplification stored")).expect("a DAF line");
    for (name, value) in daf.iter().filter(|(_, v)| v.is_number()) {
        assert!(line.contains(&format!("{name} {:.3}", value.as_f64().unwrap())), "{name}: {line}");
    }
}

/// The static part is the bridge resting on the arrestor (`solver::static_contact`, the case's own
/// printed mesh): each quantity's S is that solution's value, and the factors act on S and on
/// P - S as `LoadCase::utilisation` states: gamma_S = 2, gamma_D = 0.5 gives (2 S + 0.5 (P - S)) / A
/// (1e-12: round-off of a few products).
#[test]
fn the_static_part_is_the_resting_solution_and_each_factor_acts_on_its_part() {
    let case = LoadCase { static_factor: 2.0, dynamic_factor: 0.5, ..LoadCase::named("parts") };
    let s = scenario(0.6, vec![case]);
    let a = answer_of(&s);
    let resting = beam_impact::solver::static_contact::static_response(&s).unwrap().expect("the bridge rests");
    let judged = &a.load_cases.as_ref().unwrap().cases[0];
    assert!(judged.static_solution);
    for (name, q) in &judged.quantities {
        let expected_s = resting.value(name).unwrap().abs();
        assert_eq!(q.static_value, expected_s, "{name}");
        assert!(q.static_value > 0.0 && q.static_value < q.peak, "{name}: S {} P {}", q.static_value, q.peak);
        let u = (2.0 * q.static_value + 0.5 * (q.peak - q.static_value)) / q.allowable;
        assert!((q.utilisation - u).abs() <= 1e-12 * u, "{name}: {} vs {u}", q.utilisation);
    }
    // Without gravity the bridge cannot rest: S = 0, said, and the dynamic factor takes the peak.
    let weightless = Scenario { gravity: 0.0, impact_angular_velocity: Some(0.2), drop_height: 0.0, ..s };
    let a = answer_of(&weightless);
    let judged = &a.load_cases.as_ref().unwrap().cases[0];
    assert!(!judged.static_solution);
    for (name, q) in &judged.quantities {
        assert_eq!(q.static_value, 0.0, "{name}");
        assert!((q.utilisation - 0.5 * q.peak / q.allowable).abs() <= 1e-12 * q.utilisation, "{name}");
    }
}
