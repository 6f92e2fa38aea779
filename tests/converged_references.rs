//! The converged method's answers against references of the same model on fine meshes with the
//! full modal basis (`tests/fixtures/converged_references.json`, made by
//! `tests/fixtures/make_converged_references.py`): the paper scenario and drop 0.3 / 1 / 2 m x
//! contact 10 / 13 / 16 m x damping 0.01 / 0.03, 3 s, at 56 and 112 elements per segment.
//!
//! A reference is a peak on which 56 and 112 elements agree within 0.3 % (where the 112-element
//! run is in the fixture; otherwise the 56-element value, marked so), or, for the first-contact
//! peaks of drop 2 / contact 16 / damping 0.01, 112 and 224 elements do. The rule (issue 15): the
//! first-contact peaks, and the whole-run peaks at damping >= 0.02, are within 1 % of the
//! reference; any other peak is within 1 % or flagged (its discretisation figure above the
//! tolerance, a late-impact peak of a lightly damped run, or the run's sensitivity check failed:
//! not trusted).

use std::sync::OnceLock;

use beam_impact::answer::{self, Answer, PEAK_NAMES};
use beam_impact::model::{Method, TimeStep};
use beam_impact::record::NullRecorder;
use beam_impact::results::Peaks;
use beam_impact::{Scenario, Simulation};
use serde_json::Value;

fn fixture() -> Value {
    let text = include_str!("fixtures/converged_references.json");
    serde_json::from_str(text).unwrap()
}

fn scenario(settings: &Value) -> Scenario {
    // A scenario file (the stepped beams' examples, issue 30), else the defaults.
    let mut s = match settings.get("file").and_then(Value::as_str) {
        Some(file) => {
            let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
            Scenario::from_toml(&std::fs::read_to_string(&path).unwrap(), file).unwrap()
        }
        None => Scenario::default(),
    };
    // Every other field as `--set` takes it (the stiff-contact rows: a rigid support, the power law).
    beam_impact::studies::sweep::apply_fixture_settings(&mut s, settings).unwrap();
    s
}

fn peak(p: &Peaks, name: &str) -> f64 {
    p.as_array()[PEAK_NAMES.iter().position(|n| *n == name).unwrap()]
}

fn names<'a>(row: &'a Value, key: &str, kind: &str) -> Vec<&'a str> {
    row.get(key)
        .and_then(|a| a.get(kind))
        .and_then(Value::as_array)
        .map_or(Vec::new(), |a| a.iter().map(|v| v.as_str().unwrap()).collect())
}

/// The references of `kind` ("peaks" or "first_contact_peaks"): (name, value, from 112 elements
/// or more). Where 56 and 112 elements differ by more than 0.3 % but 112 and 224 agree within it
/// (`agree_224`: a 224-element run to the end of the first sustained contact, first-contact peaks
/// only), the 224-element value is the reference.
fn references<'a>(row: &'a Value, kind: &str) -> Vec<(&'a str, f64, bool)> {
    let fine = row.get("112").map(|r| &r[kind]);
    let agree = names(row, "agree", kind);
    let agree_224 = names(row, "agree_224", kind);
    PEAK_NAMES
        .iter()
        .filter_map(|&name| match fine {
            Some(f) if agree.contains(&name) => Some((name, f[name].as_f64().unwrap(), true)),
            Some(_) if agree_224.contains(&name) => Some((name, row["224"][kind][name].as_f64().unwrap(), true)),
            Some(_) => None,
            None => Some((name, row["56"][kind][name].as_f64().unwrap(), false)),
        })
        .collect()
}

/// Each fixture row run (its name, row, scenario and answer), and the names of the rows waiting.
type Answers = (Vec<(String, Value, Scenario, Answer)>, Vec<String>);

/// The converged answer of every fixture scenario that has its references (the lightly damped ones
/// wait for their 112-element run: without it their references are not known to be converged,
/// their late peaks moving by percents between meshes), run once for the tests below; and the
/// names of those waiting.
fn answers() -> &'static Answers {
    static ANSWERS: OnceLock<Answers> = OnceLock::new();
    ANSWERS.get_or_init(|| {
        let doc = fixture();
        let mut waiting = Vec::new();
        let mut rows = Vec::new();
        for (name, row) in doc.as_object().unwrap() {
            let s = scenario(&row["scenario"]);
            if row.get("112").is_none() && s.damping_ratio < answer::LIGHT_DAMPING {
                waiting.push(name.clone());
                continue;
            }
            let a = answer::run(&s, &mut NullRecorder, Default::default()).unwrap();
            rows.push((name.clone(), row.clone(), s, a));
        }
        (rows, waiting)
    })
}

#[test]
fn converged_answers_are_within_one_percent_of_the_references_or_flagged() {
    let (rows, unfiltered) = answers();
    let mut checked = 0;
    let mut worst: (f64, String) = (0.0, String::new());
    for (name, row, s, a) in rows {
        let tolerance = s.discretisation_tolerance;
        let unreproducible = !a.quality.checks.sensitivity.unwrap().pass;
        for (kind, values, figures) in [
            ("peaks", &a.converged_peaks, &a.discretisation_error),
            ("first_contact_peaks", &a.converged_first_contact_peaks, &a.first_contact_discretisation_error),
        ] {
            for (peak_name, reference, _) in references(row, kind) {
                let value = peak(values, peak_name);
                let error = answer::relative(value, reference);
                let late = kind == "peaks" && a.unvouched_late_peaks.iter().any(|n| n == peak_name);
                let flagged = peak(figures, peak_name) > tolerance || unreproducible || late;
                let must = kind == "first_contact_peaks" || s.damping_ratio >= 0.02;
                let context = format!("{name} {kind}.{peak_name}: {value} vs reference {reference} ({error:e})");
                if must {
                    assert!(error <= 0.01, "{context}");
                } else {
                    assert!(error <= 0.01 || flagged, "{context}, not flagged");
                }
                if error > worst.0 && !flagged {
                    worst = (error, context);
                }
                checked += 1;
            }
        }
    }
    assert!(checked >= 10 * 5, "{checked} peaks checked");
    eprintln!(
        "{checked} peaks checked; largest unflagged error: {}; waiting for 112 elements: {unfiltered:?}",
        worst.1
    );
}

/// Issue 30: the stepped beams' examples (a tapered arrestor, a three-section gangway) hold
/// references too, the full basis at 56 and 112 elements per segment with a node at every section
/// change and automatic steps (`run FILE --set method=paper` with the element counts and steps
/// set; 45 min of two cores each at 112), a reference where the two agree within 0.3 % as for the
/// uniform rows: their five peaks and each beam's worst stress along it (the envelope's peaks)
/// are within 1 % of the references or flagged: the section changes alone raise no false alarm.
/// The envelope's references are the full-basis run's own (`summary.envelope` of that run), not
/// `summary.peaks`'s envelope entries, which for a paper-method run are the converged answer's:
/// until 2026-11-27 the fixture held those, so this test compared the converged answer with a
/// snapshot of itself. Measured against the full basis: the arrestor's and the bridge's worst
/// bending within 0.12 %; the shear beside the tip mass and the contact's point load converges
/// slowly (the converged answer's figure of 12-13 % flags it).
#[test]
fn stepped_beams_hold_their_references() {
    let (rows, _) = answers();
    let mut checked = 0;
    for (name, row, _, a) in rows.iter().filter(|(_, row, _, _)| row["scenario"].get("file").is_some()) {
        let tolerance = a.resolved.discretisation_tolerance;
        let fine = row.get("112").unwrap_or(&row["56"]);
        for (k, envelope) in beam_impact::results::ENVELOPE_PEAK_NAMES.iter().enumerate() {
            let (Some(value), Some(reference)) = (a.envelope_peaks[k], fine["peaks"][*envelope].as_f64()) else {
                continue;
            };
            let coarse = row["56"]["peaks"][*envelope].as_f64().unwrap();
            if (coarse - reference).abs() > 3e-3 * reference.abs() {
                continue; // not converged between the references' meshes: no reference
            }
            let error = (value.value - reference).abs() / reference;
            let figure = a.envelope_discretisation_error[k].unwrap_or(f64::INFINITY);
            assert!(
                error <= 0.01 || figure > tolerance,
                "{name} {envelope}: {} vs {reference} ({error:e})",
                value.value
            );
            checked += 1;
        }
        let unreproducible = !a.quality.checks.sensitivity.unwrap().pass;
        for (peak_name, reference, _) in references(row, "peaks") {
            let value = peak(&a.converged_peaks, peak_name);
            let error = answer::relative(value, reference);
            let flagged = peak(&a.discretisation_error, peak_name) > tolerance || unreproducible;
            assert!(error <= 0.01 || flagged, "{name} {peak_name}: {value} vs {reference} ({error:e})");
            checked += 1;
        }
    }
    assert!(checked >= 10, "{checked} stepped-beam peaks checked");
}

/// Issue 29 item 2: the verdicts are calibrated on the fixture. No false green: no trusted run has
/// a peak more than `discretisation_tolerance` (1 %) from its reference. At most 5 % false alarms:
/// runs not trusted whose every peak (whole-run and first-contact) has a reference within the
/// tolerance of it, apart from the flags that do not come from a figure: a lightly damped run's
/// late-impact peaks (not vouched for whatever the rungs say, the truncated rungs being blind to
/// the modes that ring between impacts) and the twin's (a chaotic peak is not reproducible, however
/// close one run lands). Measured with `examples/calibration.rs` on this fixture: while the figure
/// was the change against the check rung, 2 of the 19 runs were false alarms by this count (tau_a
/// changing 1.30 % between the rungs, 0.36 % from its reference; 4 counting the late-impact
/// flags); with the calibrated figure, 0: the runs whose every peak has a reference now have
/// figures of at most 0.60 % (tau_a, 0.33 % from its reference), so the stepping may move the
/// peaks by 0.5 % without turning one. The 2 lightly damped runs flagged for their late peaks
/// alone remain. No false green before or after.
#[test]
fn the_fixture_verdicts_have_no_false_green_and_at_most_five_percent_false_alarms() {
    let (rows, _) = answers();
    let (mut false_greens, mut false_alarms, mut late_only) = (Vec::new(), Vec::new(), Vec::new());
    for (name, row, s, a) in rows {
        let tolerance = s.discretisation_tolerance;
        let (mut known, mut within) = (true, true);
        for (kind, values) in [("peaks", &a.converged_peaks), ("first_contact_peaks", &a.converged_first_contact_peaks)]
        {
            let refs = references(row, kind);
            known &= refs.len() == PEAK_NAMES.len();
            for (peak_name, reference, _) in refs {
                let error = answer::relative(peak(values, peak_name), reference);
                if error > tolerance {
                    within = false;
                    if a.quality.trusted {
                        false_greens.push(format!("{name} {kind}.{peak_name}: {error:e} off, trusted"));
                    }
                }
            }
        }
        if a.quality.trusted || !(known && within) {
            continue;
        }
        let twin = a.quality.checks.sensitivity.is_some_and(|c| !c.pass);
        if !a.unvouched_late_peaks.is_empty() || twin {
            late_only.push(name.clone());
        } else {
            false_alarms.push(format!("{name}: {:?}", a.quality.reasons));
        }
    }
    eprintln!(
        "{} runs: false greens {}, false alarms {}, not trusted for late-impact or twin flags alone {late_only:?}",
        rows.len(),
        false_greens.len(),
        false_alarms.len()
    );
    assert!(false_greens.is_empty(), "false greens: {false_greens:#?}");
    assert!(
        20 * false_alarms.len() <= rows.len(),
        "{} false alarms of {} runs: {false_alarms:#?}",
        false_alarms.len(),
        rows.len()
    );
}

/// The fixture's stiff-contact rows (issue 40 part 2), made by `make_converged_references.py
/// BINARY stiff-contact`: the contact at the bridge's free end (against the arrestor, or a rigid
/// support), a rigid support at 13 m, and `examples/hertz-buffer.toml`'s power law, 0.5 s each,
/// the full basis at 56, 112 and 224 elements.
const STIFF_CONTACT_ROWS: [&str; 4] = ["free-end", "rigid", "rigid-free-end", "power-law"];

/// Issue 40 part 2: every peak's discretisation figure is at least its true error against its
/// reference (56 and 112, or 112 and 224, elements of the full basis agreeing within 0.3 %; a peak
/// identically zero, the arrestor's of a rigid support or the bridge's moment at its free end, is
/// exact), or the peak is flagged by a figure above the tolerance: on every row of the fixture,
/// the stiff-contact rows included (the contact at the bridge's free end, a rigid support, the
/// power law). No tolerance of its own: the figure is the bound. Before the automatic cut-off
/// followed the contact's own frequency (`discretise::CONTACT_CUTOFF`) the free-end row printed
/// F_c 9.3 % above its reference (a cut-off of 12 131 rad/s, 0.86 x the contact's 14 176) under a
/// figure of 2.56 %: flagged, but its figure 3.6 times below its error and its remedy (a finer
/// mesh) wrong; now 0.04 % off under a figure of 0.94 % (against a rigid support: 10.2 % off under
/// 3.06 %, now 0.04 % under 0.85 %). Before the figure's floor
/// (`answer::FIGURE_FLOOR`, 0.3 %) 43 peaks of the old rows had errors of up to 0.22 % above
/// figures down to 5e-3 %, the error their rungs share.
#[test]
fn the_figure_bounds_the_true_error_on_every_fixture_row() {
    let (rows, _) = answers();
    let (mut checked, mut stiff) = (0, 0);
    let mut missed = Vec::new();
    for (name, row, s, a) in rows {
        let tolerance = s.discretisation_tolerance;
        let stiff_row = STIFF_CONTACT_ROWS.contains(&name.as_str());
        stiff += usize::from(stiff_row);
        for (kind, values, figures) in [
            ("peaks", &a.converged_peaks, &a.discretisation_error),
            ("first_contact_peaks", &a.converged_first_contact_peaks, &a.first_contact_discretisation_error),
        ] {
            for (peak_name, reference, fine) in references(row, kind) {
                assert!(fine || !stiff_row, "{name} {kind}.{peak_name}: a reference from 112 elements or more");
                let value = peak(values, peak_name);
                let error = answer::relative(value, reference);
                let figure = peak(figures, peak_name);
                if !(figure >= error || figure > tolerance) {
                    missed.push(format!(
                        "{name} {kind}.{peak_name}: {value} vs reference {reference}: error {error:e} above its figure \
                         {figure:e}, within the tolerance"
                    ));
                }
                checked += 1;
            }
        }
    }
    assert_eq!(stiff, STIFF_CONTACT_ROWS.len(), "the stiff-contact rows are in the fixture");
    assert!(missed.is_empty(), "{missed:#?}");
    assert!(checked >= 200, "{checked} peaks checked");
}

/// CI recomputes one reference: the paper scenario on 56 elements per segment with the full basis
/// and automatic steps gives the fixture's first-contact peaks (the same code and steps: to 1e-9).
/// The run stops at 1 s, past the first sustained contact (it ends at 0.75 s), a third of the
/// fixture's 3 s run: the first-contact peaks of a longer run are the same numbers.
#[test]
fn one_reference_is_recomputed() {
    let doc = fixture();
    let row = &doc["paper"];
    let mut s = Scenario {
        method: Method::Paper,
        step_free: TimeStep::Auto,
        step_contact: TimeStep::Auto,
        duration: 1.0,
        ..Scenario::default()
    };
    s.lower.elements = 56;
    s.upper.elements_to_contact = 56;
    s.upper.elements_beyond_contact = 56;
    let summary = Simulation::new(&s).unwrap().run(&mut NullRecorder).unwrap();
    let end = summary.first_contact_end.expect("the first sustained contact ends within 1 s");
    assert!(end < 0.9, "first contact ends at {end} s");
    for name in PEAK_NAMES {
        let expected = row["56"]["first_contact_peaks"][name].as_f64().unwrap();
        let got = peak(&summary.first_contact_peaks, name);
        assert!((got - expected).abs() <= 1e-9 * expected.abs(), "{name}: {got} vs fixture {expected}");
        // The fixture's whole-run peak (3 s) holds the first contact's.
        assert!(row["56"]["peaks"][name].as_f64().unwrap() >= expected * (1.0 - 1e-12), "{name}");
    }
}

/// `beam-impact bench` prints the fixture's verdict counts (issue 29 item 4): the same rows as
/// the test above, each from its own scenario (the examples of sections from their files: the
/// bench once ran them as the default scenario and counted 20 false greens).
#[test]
fn the_bench_counts_the_fixtures_verdicts_as_the_test_does() {
    let line = beam_impact::studies::bench::fixture_verdicts().unwrap();
    assert!(line.contains("false greens 0,"), "{line}");
    assert!(line.contains("25 scenarios"), "{line}");
}
