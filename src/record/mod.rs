//! Writing results: the [`Recorder`] the simulation writes into, the MCAP log ([`mcap`], its
//! writer thread [`writer`], its names [`log_format`] and [`options`], the messages [`schema`] and
//! their encoding [`step_encoding`], the Foxglove scene [`scene`], the stress stations' layout and
//! feed [`stations`]), the guard every output file goes through ([`output`]), the wrapper that
//! stops a run between steps when asked ([`cancel`]) and the recording benchmark ([`mod@bench`]). The physics never sees a file format; reading a log back
//! and drawing it is [`crate::replay`]'s.

use nalgebra::DMatrix;

use crate::error::Result;
use crate::model::Scenario;
use crate::results::{ContactEvent, StepResult};

/// What a recorder learns once, before the first step.
#[derive(Clone, Debug)]
pub struct RunInfo<'a> {
    /// The scenario of the run.
    pub scenario: &'a Scenario,
    /// Node positions of the arrestor from the clamp, m.
    pub lower_nodes: &'a [f64],
    /// Node positions of the bridge from the hinge, m.
    pub upper_nodes: &'a [f64],
    /// Maps the modal coordinates of a step to the nodal deflections of the arrestor's nodes
    /// followed by the bridge's nodes, m: w = shapes * q (rows of supported nodes are zero).
    pub nodal_shapes: &'a DMatrix<f64>,
    /// The stress stations (issue 30): where they are, how a step's stresses follow from its
    /// modal coordinates, and the feed of what they do not say ([`stations`]); None for a run
    /// without them (the dense oracle) and for runs described by hand.
    pub stations: Option<&'a stations::StationProbe>,
}

/// Receives every internal step of a run.
pub trait Recorder {
    /// Called once before the first step (the initial state at t = 0 follows as step 0).
    fn start(&mut self, info: &RunInfo<'_>) -> Result<()>;
    /// One internal step, with the modal coordinates from which the deflected shapes follow.
    fn step(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()>;
    /// The simulated time between two samples of the dense output the recorder asks for, ns (0:
    /// none, every internal step is what it gets). See [`Recorder::sample`].
    fn sample_interval_ns(&self) -> u64 {
        0
    }
    /// A sample of the dense output (issue 41): the state at an instant inside the internal step
    /// `result.step` (every multiple of [`Recorder::sample_interval_ns`], and every instant where
    /// a running peak was reached), from the exact solution there, with its modal coordinates;
    /// sent before that step's end, in time order. `result.step_size` is the time since the
    /// step's start, and its peaks the run's up to the sample.
    fn sample(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        let _ = (result, modal_coordinates);
        Ok(())
    }
    /// The bridge's strain energy at the arrestor's largest deflection so far as of the row just
    /// handed over ([`Recorder::step`] or [`Recorder::sample`]), J, sent after each row that raised
    /// that deflection's running peak: the run's E_def,b there, the value it prints (the log keeps
    /// it with that row's modal coordinates, so that `report` replays it).
    fn deflection_peak_strain(&mut self, upper_strain: f64) -> Result<()> {
        let _ = upper_strain;
        Ok(())
    }
    /// A contact stage starts or ends.
    fn contact_event(&mut self, event: &ContactEvent) -> Result<()>;
    /// The run was rolled back (an FMU state was restored) to `result`: the steps after it that
    /// were already recorded are superseded by those that follow.
    fn rollback(&mut self, result: &StepResult) -> Result<()> {
        let _ = result;
        Ok(())
    }
    /// Adds a document to the record, between the last step and [`Recorder::finish`] (the CLI
    /// stores its answer with the checks, `answer.json`, so that `report` can say what the run's
    /// verdict was); a recorder that keeps nothing ignores it.
    fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> Result<()> {
        let _ = (name, media_type, data);
        Ok(())
    }
    /// Completes the record (for a file: summary and footer). Must be called and checked.
    fn finish(&mut self) -> Result<()>;
    /// Whether every step needs its support reactions and tip velocities (a recorder that keeps
    /// nothing says no: they cost about a third of a step; the simulation still sets them at the
    /// end of every advance, where outputs are read).
    fn wants_details(&self) -> bool {
        true
    }
    /// Whether the internal step `result` (final but for its details) is one the recorder
    /// records now, or needs for a scene or modes tick: the simulation computes the details
    /// ([`Recorder::wants_details`]) and the stations' loads only for those, and for the steps it
    /// knows a recorder may record later (before a contact event, at an advance's end). A
    /// recorder that thins the steps says no for the others; by default every step is kept.
    fn keeps(&self, result: &StepResult) -> bool {
        let _ = result;
        true
    }
    /// Why the record stopped before the run's end (a log at its size cap), if it did.
    fn stopped_early(&self) -> Option<&str> {
        None
    }
}

/// A recorder that keeps nothing.
#[derive(Clone, Copy, Debug, Default)]
pub struct NullRecorder;

impl Recorder for NullRecorder {
    fn start(&mut self, _: &RunInfo<'_>) -> Result<()> {
        Ok(())
    }
    fn wants_details(&self) -> bool {
        false
    }
    fn step(&mut self, _: &StepResult, _: &[f64]) -> Result<()> {
        Ok(())
    }
    fn contact_event(&mut self, _: &ContactEvent) -> Result<()> {
        Ok(())
    }
    fn finish(&mut self) -> Result<()> {
        Ok(())
    }
}

/// A recorder that keeps everything in memory, for tests.
#[derive(Clone, Debug, Default)]
pub struct MemoryRecorder {
    /// Whether `start` was called.
    pub started: bool,
    /// Every step, in order.
    pub steps: Vec<StepResult>,
    /// Modal coordinates of every step.
    pub coordinates: Vec<Vec<f64>>,
    /// Contact events, in order.
    pub events: Vec<ContactEvent>,
    /// Whether `finish` was called.
    pub finished: bool,
    /// The nodal shape matrix given at start.
    pub nodal_shapes: Option<DMatrix<f64>>,
    /// The dense output's interval it asks for, ns (0: none).
    pub sample_interval_ns: u64,
    /// Every sample of the dense output, in order.
    pub samples: Vec<StepResult>,
}

impl Recorder for MemoryRecorder {
    fn start(&mut self, info: &RunInfo<'_>) -> Result<()> {
        self.started = true;
        self.nodal_shapes = Some(info.nodal_shapes.clone());
        Ok(())
    }
    fn step(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        self.steps.push(*result);
        self.coordinates.push(modal_coordinates.to_vec());
        Ok(())
    }
    fn sample_interval_ns(&self) -> u64 {
        self.sample_interval_ns
    }
    fn sample(&mut self, result: &StepResult, _: &[f64]) -> Result<()> {
        self.samples.push(*result);
        Ok(())
    }
    fn contact_event(&mut self, event: &ContactEvent) -> Result<()> {
        self.events.push(*event);
        Ok(())
    }
    fn finish(&mut self) -> Result<()> {
        self.finished = true;
        Ok(())
    }
}

pub mod cancel;
pub mod mcap;
pub mod output;

pub mod bench;
pub mod log_format;
pub mod options;
pub mod scene;
pub mod schema;
pub mod stations;
pub mod step_encoding;
pub mod writer;
