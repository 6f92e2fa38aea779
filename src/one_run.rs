//! One run as `beam-impact run` makes it, shared by the CLI and the Python package's native
//! module: the answer (the printed run into the caller's recorder, the check rungs and the twin
//! unrecorded; all stoppable between steps), then the answer with its checks attached to the
//! record (`answer.json`, so that `report` can say the run's verdict) and the bending stations'
//! stress histories (`fatigue.json`, issue 44) before the record is finished.

use std::sync::atomic::AtomicBool;

use crate::answer::{Answer, Options};
use crate::error::{Error, Result};
use crate::model::Scenario;
use crate::record::{Recorder, RunInfo};
use crate::results::{ContactEvent, StepResult};
use crate::Simulation;

/// Refuses, before anything is written, a run of `scenario` that needs more than `max_steps`
/// internal steps (builds the model and its modes, steps nothing); else the most steps its plan
/// takes ([`Simulation::step_estimate`]), for the caller to say where it is large.
pub fn check(scenario: &Scenario, max_steps: u64) -> Result<u64> {
    // A load case's fields (issue 44) are the scenario's too: refused here, before anything runs.
    crate::studies::sweep::check_cases(scenario)?;
    Simulation::new(scenario)?.check_step_count(scenario.duration_ns(), max_steps)
}

/// A run whose plan may take more internal steps than this is said before it starts: at a few
/// microseconds a step (the paper method's; the exact advance's contact steps take 2-8 us), a
/// million steps are seconds of work, and the answer runs three more.
pub const LARGE_RUN_STEPS: u64 = 1_000_000;

/// A contact whose rate (N/m, the one its steps are sized for: [`crate::model::system::contact_rate`],
/// the linear bar's k or a power law's tangent stiffness) exceeds this can chatter: each
/// separation rings the bar into the next touch, and every change of contact is located by
/// retaking its step with new exact coefficients for every kept mode. Measured on the default
/// scenario, 3 s, the printed run: 2.8e10 N/m 68 contact windows in 68 ms, 1e11 95 windows, 2e11
/// 104, 3e11 111 (as a power law of exponent 1: 10 472 windows, 3.5 s), 4e11 17 135 windows in
/// 5.7 s, 1e12 9 703 windows in 3.7 s (the answer 8.2 s against the default's 0.18 s, 45x): the
/// onset is erratic above 2e11 N/m, so no estimate of the cost can be given, only the warning.
pub const CHATTER_STIFFNESS: f64 = 2e11;

/// The note said before a run whose contact is stiffer than [`CHATTER_STIFFNESS`] (`None` for any
/// other): what may make it long, with the measured example.
pub fn stiff_contact_note(scenario: &Scenario) -> Option<String> {
    let rate = crate::model::system::contact_rate(scenario);
    (rate > CHATTER_STIFFNESS).then(|| {
        format!(
            "the contact's rate {rate:.3e} N/m (contact.stiffness; the rate its steps are sized for) is above \
             {CHATTER_STIFFNESS:e} N/m: a contact this stiff can chatter, each separation ringing the bar into the next \
             touch, and every change of contact is located by retaking its step (3 s of the default scenario: \
             2.8e10 N/m 68 contact windows, 1e12 N/m 9 703 windows and 45 times the time)"
        )
    })
}

/// Runs `scenario` with its checks into `recorder` and finishes the record with the answer
/// attached; `cancel` set stops every run at its next step ([`Error::Cancelled`]; the record is
/// then neither given the answer nor finished here: an MCAP log completes itself when dropped).
pub fn run(
    scenario: &Scenario,
    recorder: &mut (dyn Recorder + Send),
    options: Options,
    cancel: &AtomicBool,
) -> Result<Answer> {
    let mut deferred = FinishLater { inner: recorder, finish_requested: false };
    let answer = crate::studies::sweep::answer_with_cases(
        scenario,
        &mut deferred,
        options,
        &crate::answer::own_cache(),
        cancel,
    )?;
    if deferred.finish_requested {
        let doc = crate::run_document::answer_attachment(&answer);
        let bytes = serde_json::to_vec_pretty(&doc).map_err(|e| Error::Other(format!("JSON: {e}")))?;
        deferred.inner.attach(crate::record::mcap::ANSWER_ATTACHMENT, "application/json", &bytes)?;
        if let Some(bytes) = crate::run_document::fatigue_attachment(&answer)? {
            deferred.inner.attach(crate::record::log_format::FATIGUE_ATTACHMENT, "application/json", &bytes)?;
        }
        deferred.inner.finish()?;
    }
    Ok(answer)
}

/// Passes everything on to the real recorder but the end of the record, deferred until the
/// answer with its checks is attached.
struct FinishLater<'a> {
    inner: &'a mut (dyn Recorder + Send),
    finish_requested: bool,
}

impl Recorder for FinishLater<'_> {
    fn start(&mut self, info: &RunInfo<'_>) -> Result<()> {
        self.inner.start(info)
    }
    fn step(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        self.inner.step(result, modal_coordinates)
    }
    fn sample_interval_ns(&self) -> u64 {
        self.inner.sample_interval_ns()
    }
    fn sample(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        self.inner.sample(result, modal_coordinates)
    }
    fn contact_event(&mut self, event: &ContactEvent) -> Result<()> {
        self.inner.contact_event(event)
    }
    fn rollback(&mut self, result: &StepResult) -> Result<()> {
        self.inner.rollback(result)
    }
    fn finish(&mut self) -> Result<()> {
        self.finish_requested = true;
        Ok(())
    }
    fn wants_details(&self) -> bool {
        self.inner.wants_details()
    }
    fn keeps(&self, result: &StepResult) -> bool {
        self.inner.keeps(result)
    }
    fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> Result<()> {
        self.inner.attach(name, media_type, data)
    }
    fn stopped_early(&self) -> Option<&str> {
        self.inner.stopped_early()
    }
}
