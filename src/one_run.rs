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

/// The note said before a run whose plan may take more than [`LARGE_RUN_STEPS`] internal steps
/// (`None` for any other): the count, over `duration` s, and that its checks take as many again.
pub fn large_run_note(planned_steps: u64, duration: f64) -> Option<String> {
    (planned_steps > LARGE_RUN_STEPS).then(|| {
        format!(
            "this run may take up to {planned_steps} internal steps ({duration} s at its smaller time step), and its \
             checks as many again"
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
    fn deflection_peak_strain(&mut self, upper_strain: f64) -> Result<()> {
        self.inner.deflection_peak_strain(upper_strain)
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
