//! Stopping a run between two steps: [`Cancellable`] hands every step on to the recorder it wraps
//! and fails the run with [`Error::Cancelled`] once its flag is set. The flag is set by whoever
//! watches the user (the Python package's Ctrl-C watcher); the physics never sees it, and a run
//! whose flag stays clear gives the same numbers to the bit (the wrapper changes nothing it is
//! asked: `wants_details`, attachments, the end of the record).

use std::sync::atomic::{AtomicBool, Ordering};

use crate::error::{Error, Result};
use crate::record::{Recorder, RunInfo};
use crate::results::{ContactEvent, StepResult};

/// A recorder that stops the run at the first step after `flag` is set.
pub struct Cancellable<'a> {
    inner: &'a mut (dyn Recorder + Send),
    flag: &'a AtomicBool,
}

impl<'a> Cancellable<'a> {
    /// Wraps `inner`; the run stops once `flag` holds true.
    pub fn new(inner: &'a mut (dyn Recorder + Send), flag: &'a AtomicBool) -> Self {
        Cancellable { inner, flag }
    }
}

impl Recorder for Cancellable<'_> {
    fn start(&mut self, info: &RunInfo<'_>) -> Result<()> {
        self.inner.start(info)
    }
    /// One relaxed load per step (a few nanoseconds against a step's microseconds).
    fn step(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        if self.flag.load(Ordering::Relaxed) {
            return Err(Error::Cancelled { time: result.time, step: result.step });
        }
        self.inner.step(result, modal_coordinates)
    }
    fn sample_interval_ns(&self) -> u64 {
        self.inner.sample_interval_ns()
    }
    /// A sample is checked as a step is: the step it lies in is where the run stops.
    fn sample(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        if self.flag.load(Ordering::Relaxed) {
            return Err(Error::Cancelled { time: result.time, step: result.step });
        }
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
    fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> Result<()> {
        self.inner.attach(name, media_type, data)
    }
    fn finish(&mut self) -> Result<()> {
        self.inner.finish()
    }
    fn wants_details(&self) -> bool {
        self.inner.wants_details()
    }
    fn keeps(&self, result: &StepResult) -> bool {
        self.inner.keeps(result)
    }
    fn stopped_early(&self) -> Option<&str> {
        self.inner.stopped_early()
    }
}
