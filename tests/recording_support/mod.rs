//! Shared by the MCAP recording tests: a recorder that sends everything to two recorders, so
//! one run fills a log and an in-memory copy to compare it with.

use beam_impact::record::{Recorder, RunInfo};
use beam_impact::results::{ContactEvent, StepResult};

/// Sends everything to two recorders.
pub struct Tee<'a>(pub &'a mut dyn Recorder, pub &'a mut dyn Recorder);

impl Recorder for Tee<'_> {
    fn start(&mut self, info: &RunInfo<'_>) -> beam_impact::Result<()> {
        self.0.start(info)?;
        self.1.start(info)
    }
    fn step(&mut self, result: &StepResult, q: &[f64]) -> beam_impact::Result<()> {
        self.0.step(result, q)?;
        self.1.step(result, q)
    }
    /// The first recorder's interval (the log's): the second gets the same samples.
    fn sample_interval_ns(&self) -> u64 {
        self.0.sample_interval_ns()
    }
    fn sample(&mut self, result: &StepResult, q: &[f64]) -> beam_impact::Result<()> {
        self.0.sample(result, q)?;
        self.1.sample(result, q)
    }
    fn deflection_peak_strain(&mut self, upper_strain: f64) -> beam_impact::Result<()> {
        self.0.deflection_peak_strain(upper_strain)?;
        self.1.deflection_peak_strain(upper_strain)
    }
    fn contact_event(&mut self, event: &ContactEvent) -> beam_impact::Result<()> {
        self.0.contact_event(event)?;
        self.1.contact_event(event)
    }
    fn finish(&mut self) -> beam_impact::Result<()> {
        self.0.finish()?;
        self.1.finish()
    }
}
