//! One run as `beam-impact run` makes it (`src/one_run.rs`), shared with the Python package's
//! `beam_impact.run`: the answer with its checks attached to the record before it is finished,
//! and a run stopped between steps when its caller asks (`src/record/cancel.rs`).
//!
//! Goal: with the flag clear the answer is `answer::run`'s to the bit and the record ends with
//! `answer.json`; a flag set before the run stops it at its first step, one set while it runs
//! stops it at the next step, with `Error::Cancelled`, and the run does not finish the record
//! nor attach an answer (an MCAP log completes itself when dropped: the steps up to the stop,
//! no `answer.json`). No tolerances: the same code on the same scenario.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use beam_impact::answer::{self, Options};
use beam_impact::record::{NullRecorder, Recorder, RunInfo};
use beam_impact::results::{ContactEvent, StepResult};
use beam_impact::{one_run, Error, Scenario};

/// Counts steps, keeps attachments and whether the record was finished.
#[derive(Default)]
struct Watch {
    steps: u64,
    last_step: u64,
    attachments: Vec<(String, Vec<u8>)>,
    finished: bool,
    /// Steps recorded after this many raise the flag it holds.
    raise_after: Option<(u64, &'static AtomicBool)>,
}

impl Recorder for Watch {
    fn start(&mut self, _: &RunInfo<'_>) -> beam_impact::Result<()> {
        Ok(())
    }
    fn step(&mut self, result: &StepResult, _: &[f64]) -> beam_impact::Result<()> {
        self.steps += 1;
        self.last_step = result.step;
        if let Some((after, flag)) = self.raise_after {
            if self.steps >= after {
                flag.store(true, Ordering::SeqCst);
            }
        }
        Ok(())
    }
    fn contact_event(&mut self, _: &ContactEvent) -> beam_impact::Result<()> {
        Ok(())
    }
    fn attach(&mut self, name: &str, _: &str, data: &[u8]) -> beam_impact::Result<()> {
        self.attachments.push((name.to_string(), data.to_vec()));
        Ok(())
    }
    fn finish(&mut self) -> beam_impact::Result<()> {
        self.finished = true;
        Ok(())
    }
}

fn short() -> Scenario {
    Scenario { duration: 0.2, ..Scenario::default() }
}

#[test]
fn with_the_flag_clear_the_answer_is_answer_run_s_and_the_record_ends_with_it() {
    let mut watch = Watch::default();
    let got = one_run::run(&short(), &mut watch, Options::default(), &AtomicBool::new(false)).unwrap();
    let want = answer::run(&short(), &mut NullRecorder, Options::default()).unwrap();
    assert_eq!(got.summary.peaks, want.summary.peaks);
    assert_eq!(got.quality, want.quality);
    assert_eq!(got.runs, want.runs);
    assert!(watch.finished && watch.steps == got.summary.steps + 1, "{} steps recorded", watch.steps);
    // answer.json, then the bending stations' histories (issue 44: fatigue.json).
    assert_eq!(watch.attachments.len(), 2);
    assert_eq!(watch.attachments[1].0, "fatigue.json");
    let (name, bytes) = &watch.attachments[0];
    assert_eq!(name, "answer.json");
    let doc: serde_json::Value = serde_json::from_slice(bytes).unwrap();
    assert_eq!(doc["quality"]["trusted"], serde_json::json!(got.quality.trusted));
    assert_eq!(doc["design"]["pass"], serde_json::json!(got.design.pass));
}

#[test]
fn a_flag_set_before_the_run_stops_it_at_its_first_step() {
    let mut watch = Watch::default();
    let e = one_run::run(&short(), &mut watch, Options::default(), &AtomicBool::new(true)).unwrap_err();
    assert!(matches!(e, Error::Cancelled { step: 0, .. }), "{e}");
    assert_eq!(e.to_string(), "run cancelled at t = 0 s (internal step 0), as asked");
    assert_eq!(watch.steps, 0);
    assert!(!watch.finished && watch.attachments.is_empty(), "a cancelled record is not finished");
}

/// Raised after 1000 recorded steps of a 30 s run (about 70 000 steps): the printed run stops at
/// the next one, and the check rungs and the twin, stepping on other threads, stop too (the
/// call returns long before they could finish).
#[test]
fn a_flag_set_while_it_runs_stops_every_run_of_the_answer_within_a_step() {
    static FLAG: AtomicBool = AtomicBool::new(false);
    let long = Scenario { duration: 30.0, ..Scenario::default() };
    let mut watch = Watch { raise_after: Some((1000, &FLAG)), ..Watch::default() };
    let started = Instant::now();
    let e = one_run::run(&long, &mut watch, Options::default(), &FLAG).unwrap_err();
    assert!(matches!(e, Error::Cancelled { .. }), "{e}");
    assert_eq!(watch.steps, 1000, "stopped at the step after the flag was raised");
    assert!(!watch.finished);
    // Not a speed assertion: the uncancelled answer takes about 30 x the 0.2 s run's stepping;
    // minutes here would mean the check runs went on to their end.
    assert!(started.elapsed() < Duration::from_secs(120), "{:?}", started.elapsed());
}
