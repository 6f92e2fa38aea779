//! The pipeline: scenario -> validated model -> stepper -> step results -> recorder.
//! Time is counted in integer nanoseconds, so communication points and log stamps are exact.

use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::model::system::PROBES;
use crate::model::{Method, Model, Probe, Scenario, SupportMotion, TimeStep};
use crate::record::stations::{FeedEnd, StationLayout, StationProbe};
use crate::record::{NullRecorder, Recorder, RunInfo};
use crate::results::{
    seconds, ContactEvent, ContactWindow, EnergyAccount, FirstContact, Impact, ModeTable, Peaks, Quality, StepResult,
    Summary, TimeSteps,
};
use crate::solver::contact::{self, Stage};
use crate::solver::envelope::{EnvelopeScope, Running, StationRows, StationState};
use crate::solver::initial::Pitching;
use crate::solver::model_range::{ModelRange, RangeCheck, RangeRows, StrainPeak};
use crate::solver::static_correction::LOADS;
use crate::solver::turning_points::TurningPoints;
use crate::solver::{
    DenseStepper, Energies, EnergyMethod, Excitation, Kinematics, ModalCache, ModalStepper, ModalSystem, StepPlan,
    Stepper, TipForces,
};

mod tangent;
pub use tangent::{Linearised, GRAZE_FRACTION, SCREEN_FRACTION};

/// Everything that changes during a run: enough to restore it exactly (FMU state, rollback).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunState {
    /// The stepper's state (modal coordinates for the production stepper).
    pub kinematics: Kinematics,
    /// Results of the latest step (step 0: the initial state).
    pub result: StepResult,
    /// y_k,u - y_k,l of the latest state, m (Eq. 6 decides the next stage from it).
    pub gap: f64,
    /// Tip forces applied from now on (FMU inputs).
    pub forces: TipForces,
    /// Tip forces of the latest step (for the trapezoidal external work).
    pub last_forces: TipForces,
    /// Total energy at t = 0, J.
    pub initial_energy: f64,
    /// v^T C v at the latest state, W.
    pub dissipation_rate: f64,
    /// When each running peak was reached, s.
    pub peak_times: Peaks,
    /// Bridge strain energy at the largest arrestor deflection so far, J.
    pub upper_strain_at_peak: f64,
    /// Contact intervals so far (the last one may still be open).
    pub contact_windows: Vec<ContactWindow>,
    /// Largest |energy residual| so far, J.
    pub max_residual: f64,
    /// Largest strain energy (beams and bar) reached so far, J.
    pub max_strain_energy: f64,
    /// Largest |external work| reached so far, J.
    pub max_external_work: f64,
    /// Time of the outputs, ns: the latest communication point, at or after the latest internal
    /// step (the outputs between are interpolated within the next internal step).
    pub output_ns: u64,
    /// Tip forces set by the importer at `output_ns`, applied from there on (an input change
    /// ends the internal step at its communication point).
    pub input_forces: TipForces,
    /// Peaks of the first sustained contact.
    pub first_contact: FirstContact,
    /// The supports' motion at `motion_ns`, from which it moves with constant accelerations until
    /// the next change (issue 17; all zero for fixed supports).
    #[serde(default)]
    pub motion: SupportMotion,
    /// When `motion` was given, ns.
    #[serde(default)]
    pub motion_ns: u64,
    /// The support motion set by the importer at `output_ns`, applied from there on.
    #[serde(default)]
    pub input_motion: SupportMotion,
    /// The supports' inertial potential at the latest state under the current accelerations, J
    /// (its change over a step is the supports' work on the beams in their own frame).
    #[serde(default)]
    pub inertial_potential: f64,
    /// The exact advance's step level: the next step is the plan's times 2^level (see
    /// [`Simulation::next_step_ns`]).
    #[serde(default)]
    pub step_level: u32,
    /// The stress envelope so far: each station's largest |stress|, Pa, in the order of
    /// [`crate::model::stations::Stations::all`] (issue 30).
    #[serde(default)]
    pub envelope: Vec<f64>,
    /// When each station's largest stress was reached, s.
    #[serde(default)]
    pub envelope_times: Vec<f64>,
    /// Every node's largest deflection and rotation so far, the model's range (issue 40).
    #[serde(default)]
    pub range: ModelRange,
}

impl RunState {
    /// Checks a state that comes from outside the process (a deserialized FMU state) before it is
    /// restored into a model of `dofs` coordinates whose longer internal step is `longest_step_ns`:
    /// the vectors of the model's size and every number finite, step and time consistent (time =
    /// seconds(time_ns), at least 1 ns per step, the outputs' time within the next internal step),
    /// the contact windows ordered and within the run, peaks and their times plausible, the tip
    /// forces within the input bound. The error names the field and the value. A real state
    /// holds no NaN or infinity (nothing in it is undefined), so none is accepted.
    pub fn validate(&self, dofs: usize, longest_step_ns: u64) -> Result<()> {
        let invalid = |field: &str, detail: String| Err(Error::StateInvalid { field: field.to_string(), detail });
        let k = &self.kinematics;
        for (field, v) in [
            ("kinematics.displacement", &k.displacement),
            ("kinematics.velocity", &k.velocity),
            ("kinematics.acceleration", &k.acceleration),
        ] {
            if v.len() != dofs {
                return Err(Error::StateCoordinates { found: v.len(), expected: dofs });
            }
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return invalid(&format!("{field}[{i}]"), format!("= {} is not finite", v[i]));
            }
        }
        if self.step_level > MAX_STEP_LEVEL {
            return invalid("step_level", format!("= {} is above the largest level {MAX_STEP_LEVEL}", self.step_level));
        }
        if !self.range.is_plausible(self.result.time) {
            return invalid(
                "range",
                format!("= {:?} holds a value that is not finite and >= 0, or a time outside the run", self.range),
            );
        }
        let r = &self.result;
        let e = &r.energy;
        let numbers = [
            ("gap", self.gap),
            ("initial_energy", self.initial_energy),
            ("dissipation_rate", self.dissipation_rate),
            ("upper_strain_at_peak", self.upper_strain_at_peak),
            ("max_residual", self.max_residual),
            ("max_strain_energy", self.max_strain_energy),
            ("max_external_work", self.max_external_work),
            ("result.step_size", r.step_size),
            ("result.lower_tip_deflection", r.lower_tip_deflection),
            ("result.upper_contact_deflection", r.upper_contact_deflection),
            ("result.upper_tip_deflection", r.upper_tip_deflection),
            ("result.lower_clamp_bending_stress", r.lower_clamp_bending_stress),
            ("result.lower_clamp_shear_stress", r.lower_clamp_shear_stress),
            ("result.upper_contact_bending_stress", r.upper_contact_bending_stress),
            ("result.contact_force", r.contact_force),
            ("result.contact_stress", r.contact_stress),
            ("result.lower_clamp_reaction_force", r.lower_clamp_reaction_force),
            ("result.lower_clamp_reaction_moment", r.lower_clamp_reaction_moment),
            ("result.upper_hinge_reaction_force", r.upper_hinge_reaction_force),
            ("result.lower_tip_velocity", r.lower_tip_velocity),
            ("result.upper_tip_velocity", r.upper_tip_velocity),
            ("result.energy.kinetic", e.kinetic),
            ("result.energy.strain", e.strain),
            ("result.energy.gravity_potential", e.gravity_potential),
            ("result.energy.external_work", e.external_work),
            ("result.energy.damping_dissipation", e.damping_dissipation),
            ("result.energy.residual", e.residual),
            ("result.upper_support_displacement", r.upper_support_displacement),
            ("result.lower_support_displacement", r.lower_support_displacement),
            ("inertial_potential", self.inertial_potential),
        ];
        if let Some((field, value)) = numbers.iter().find(|(_, x)| !x.is_finite()) {
            return invalid(field, format!("= {value} is not finite"));
        }
        let non_negative = [
            ("max_residual", self.max_residual),
            ("max_external_work", self.max_external_work),
            ("result.step_size", r.step_size),
        ];
        if let Some((field, value)) = non_negative.iter().find(|(_, x)| *x < 0.0) {
            return invalid(field, format!("= {value} is negative"));
        }
        for (field, f) in
            [("forces", self.forces), ("last_forces", self.last_forces), ("input_forces", self.input_forces)]
        {
            for (tip, value) in [("upper", f.upper), ("lower", f.lower)] {
                if !(value.is_finite() && value.abs() <= crate::model::scenario::MAX_TIP_FORCE) {
                    return invalid(
                        &format!("{field}.{tip}"),
                        format!(
                            "= {value} N is not a tip force (finite, |F| <= {:e} N)",
                            crate::model::scenario::MAX_TIP_FORCE
                        ),
                    );
                }
            }
        }
        for (field, motion) in [("motion", self.motion), ("input_motion", self.input_motion)] {
            let values = motion.values();
            if let Some(k) = values.iter().position(|v| !v.is_finite()) {
                let name = crate::model::support_motion::MOTION_NAMES[k];
                return invalid(&format!("{field}.{name}"), format!("= {} is not finite", values[k]));
            }
        }
        if self.motion_ns > self.output_ns {
            return invalid(
                "motion_ns",
                format!("= {} ns is after the outputs' time output_ns = {} ns", self.motion_ns, self.output_ns),
            );
        }
        if r.time.to_bits() != seconds(r.time_ns).to_bits() {
            return invalid("result.time", format!("= {} s is not result.time_ns = {} ns", r.time, r.time_ns));
        }
        if (r.step == 0) != (r.time_ns == 0) || r.step > r.time_ns {
            return invalid(
                "result.step",
                format!("= {} steps in result.time_ns = {} ns (each step lasts >= 1 ns)", r.step, r.time_ns),
            );
        }
        if self.output_ns < r.time_ns || self.output_ns - r.time_ns > longest_step_ns {
            return invalid(
                "output_ns",
                format!(
                    "= {} ns is not within the internal step after result.time_ns = {} ns (at most {longest_step_ns} ns)",
                    self.output_ns, r.time_ns
                ),
            );
        }
        let peaks = [("result.peaks", r.peaks), ("first_contact.peaks", self.first_contact.peaks)];
        for (field, p) in peaks {
            if let Some(v) = p.as_array().into_iter().find(|v| !(v.is_finite() && *v >= 0.0)) {
                return invalid(field, format!("holds {v}, not a peak (finite, >= 0)"));
            }
        }
        if let Some(t) = self.peak_times.as_array().into_iter().find(|t| !(*t >= 0.0 && *t <= r.time)) {
            return invalid("peak_times", format!("holds {t} s, outside the run (0 to {} s)", r.time));
        }
        if self.contact_windows.len() as u64 > r.step.saturating_add(1) {
            return invalid(
                "contact_windows",
                format!("holds {} windows in {} steps", self.contact_windows.len(), r.step),
            );
        }
        let mut previous_end = 0.0;
        for (i, w) in self.contact_windows.iter().enumerate() {
            if !(w.start >= previous_end && w.start <= w.end && w.end <= r.time) {
                return invalid(
                    &format!("contact_windows[{i}]"),
                    format!(
                        "= {} to {} s is not ordered within the run (after {previous_end} s, before {} s)",
                        w.start, w.end, r.time
                    ),
                );
            }
            previous_end = w.end;
        }
        Ok(())
    }
}

/// How an [`Simulation::advance_to`] call ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Advance {
    /// The target time was reached.
    Reached,
    /// Stopped early at a contact change (only when asked to).
    ContactChanged,
}

/// A running two-beam impact simulation.
#[derive(Clone, Debug)]
pub struct Simulation<S: Stepper = ModalStepper> {
    model: Model,
    modal: ModalSystem,
    stepper: S,
    energy_method: EnergyMethod,
    nodal_shapes: std::sync::Arc<DMatrix<f64>>,
    plan: StepPlan,
    state: RunState,
    /// The state before the current step, to retake it when a stage change is located.
    backup: Kinematics,
    /// The latest step's end as the peaks' cubic saw it: the next step's start, not measured again.
    step_end: Option<StepEnd>,
    /// The outputs at `state.output_ns` (interpolated inside the next internal step when the
    /// communication point falls inside one).
    output: StepResult,
    /// When each of the outputs' running peaks was reached (the state's `peak_times`, or
    /// within the next internal step where the point inside it raised a peak).
    output_peak_times: Peaks,
    /// The impact as the initial state starts it.
    impact: Impact,
    /// The stress envelope's stations in modal coordinates.
    stations: std::sync::Arc<StationRows>,
    /// The run's own envelope work: the scratch of the stations' values.
    envelope_work: crate::solver::envelope::EnvelopeWork,
    /// The recorder's feed of the stations' per-step loads and the run's envelope (issue 30).
    feed: FeedEnd,
    /// Every station's turning points, when kept (issue 44: [`Self::keep_turning_points`]).
    turning_points: Option<TurningPoints>,
    /// Each contact window's start, end, peak force and speeds (issue 45), as the run steps.
    sub_impacts: Vec<crate::results::SubImpact>,
    /// Every node's deflection and rotation rows, for the model's range (issue 40).
    range_rows: std::sync::Arc<RangeRows>,
    /// The most internal steps the run may take, checked at every step (issue 40).
    max_steps: u64,
    /// The instants inside the latest internal step at which a running peak was raised, ns (the
    /// exact advance: [`Self::exact_extremes`]); the log records the state at each (issue 41).
    peak_instants: Vec<u64>,
    /// The same for the outputs at a point inside the next internal step ([`Self::interpolate`]).
    output_peak_instants: Vec<u64>,
    /// The struck beam's far support's reaction rows (issue 45; none for a free far end).
    far_support: Option<std::sync::Arc<crate::solver::far_support::FarSupport>>,
    /// Whether each step raises the model's range ([`Self::without_model_range`]).
    follows_range: bool,
    /// Whether the outputs at an advance's end get their support reactions and tip velocities
    /// (false only inside [`Self::run`] into a recorder that wants no details: no one reads them
    /// between the motion rows; see [`Self::settle_details`]).
    outputs_details: bool,
    /// The latest step result whose details [`Self::outputs_at_latest_step`] left out, as it
    /// was then.
    skipped_details: Option<StepResult>,
    /// The twin's difference carried alongside (issue 43: [`Self::follow_tangent`]).
    tangent: Option<Box<tangent::Tangent<S::TangentWork>>>,
    /// The kept modes' gap functional b (the modal probes' gap row), contiguous: [`Self::modal_gap`]
    /// reads it at every step.
    gap_row: Vec<f64>,
}

impl Simulation<ModalStepper> {
    /// Validates `scenario`, resolves its `"auto"` discretisation (see [`crate::discretise::printed`]),
    /// assembles the model, computes the modes (truncated at the converged method's cut-off, with
    /// the static correction), checks the time steps and sets the initial conditions, with the
    /// production stepper.
    pub fn new(scenario: &Scenario) -> Result<Self> {
        Self::starting_with(scenario, scenario.motion_at_start()?)
    }

    /// [`Simulation::new`] with the supports' motion at t = 0 given (an FMU's inputs at the end of
    /// its initialisation); the scenario's motion table, if any, drives the run from there.
    pub fn starting_with(scenario: &Scenario, motion: SupportMotion) -> Result<Self> {
        Self::starting_with_cache(scenario, motion, None)
    }

    /// [`Simulation::new`] with the modes taken from `cache` when a run of the same geometry put
    /// them there (else computed and put there): the same run to the bit, without the eigen
    /// decompositions (see [`crate::solver::modal_cache`]).
    pub fn new_cached(scenario: &Scenario, cache: &ModalCache) -> Result<Self> {
        Self::starting_with_cache(scenario, scenario.motion_at_start()?, Some(cache))
    }

    fn starting_with_cache(scenario: &Scenario, motion: SupportMotion, cache: Option<&ModalCache>) -> Result<Self> {
        // The reference mesh of an automatic cut-off shares the cache too (issue 43: one
        // eigen-solve per geometry, not per run), and so do the assembled model and what the
        // initial state takes from the geometry alone (the same bits: see
        // [`crate::solver::modal_cache`]).
        let resolved = crate::discretise::printed_with(scenario, cache)?;
        let cache = cache.filter(|c| c.is_enabled());
        let model = match cache {
            Some(cache) => cache.model(&resolved)?,
            None => Model::new(&resolved)?,
        };
        let (full, run, projector, factors, range) = match cache {
            Some(cache) => {
                let modes = cache.modes(&model)?;
                (modes.full, modes.run, modes.projector, Some(modes.initial), Some(modes.rows))
            }
            None => (std::sync::Arc::new(ModalSystem::new(&model)?), None, None, None, None),
        };
        let physical = initial_physical_state_with(&model, &full, &motion, factors.as_deref())?;
        let (modal, projector) = match (run, projector) {
            (Some(run), Some(projector)) => (run, projector),
            (Some(run), None) => {
                let projector = std::sync::Arc::new(crate::solver::stepper::projector(&model, &run));
                (run, projector)
            }
            (None, _) => {
                let run = std::sync::Arc::unwrap_or_clone(full).with_damping(&model.scenario).for_run(&model)?;
                let projector = std::sync::Arc::new(crate::solver::stepper::projector(&model, &run));
                (run, projector)
            }
        };
        let exact = model.scenario.method == Method::Converged;
        let stepper = ModalStepper::with_projector(modal.clone(), projector).with_exact(exact);
        Self::with_stepper(model, modal, stepper, &physical, motion, range.as_deref())
    }
}

impl Simulation<DenseStepper> {
    /// The same run with the dense oracle of Eqs. (7)-(11) (tests and benchmarks): the full
    /// modal basis of the resolved mesh, whatever the method.
    pub fn new_dense(scenario: &Scenario) -> Result<Self> {
        let model = Model::new(&crate::discretise::printed(scenario)?)?;
        let modal = ModalSystem::new(&model)?;
        let motion = scenario.motion_at_start()?;
        let physical = initial_physical_state(&model, &modal, &motion)?;
        let stepper = DenseStepper::new(&model, &modal);
        Self::with_stepper(model, modal, stepper, &physical, motion, None)
    }
}

/// The initial state in physical coordinates (from the full basis: the bridge's quasi-static
/// deflection of Eq. 24 in every mode), under the supports' motion at t = 0.
fn initial_physical_state(model: &Model, full: &ModalSystem, motion: &SupportMotion) -> Result<Kinematics> {
    initial_physical_state_with(model, full, motion, None)
}

/// [`initial_physical_state`] with what it takes from the geometry alone given (a cache's, for
/// `model`'s geometry and `full`): the same state to the bit.
fn initial_physical_state_with(
    model: &Model,
    full: &ModalSystem,
    motion: &SupportMotion,
    factors: Option<&crate::solver::initial::InitialFactors>,
) -> Result<Kinematics> {
    let forces = TipForces { upper: model.scenario.upper.tip_force, lower: model.scenario.lower.tip_force };
    crate::solver::initial::initial_state_with(model, full, &excitation(model, forces, motion), factors)
}

/// The excitation of the tip forces and the supports' motion at one instant.
/// The excitation of the supports' `motion` and the tip `forces`. The contact acts on the gap
/// plus the supports' offset plus the contact's clearance (issue 28): a clearance c makes the
/// contact act only once the beams have closed c beyond touching.
fn excitation(model: &Model, forces: TipForces, motion: &SupportMotion) -> Excitation {
    // The arm of the clamp's rotation at the contact point (issue 45: its free end by default).
    let length = model.scenario.lower_contact_position();
    let clearance = model.scenario.contact.clearance;
    let offset = motion.gap_offset(length);
    Excitation {
        forces,
        support_acceleration: motion.accelerations(),
        gap_offset: if clearance == 0.0 { offset } else { offset + clearance },
        gap_offset_rate: motion.gap_offset_rate(length),
        gap_offset_acceleration: motion.gap_offset_acceleration(length),
    }
}

/// A step's end as measured for the peaks' cubic: its probes and rates, in its stage.
#[derive(Clone, Copy, Debug)]
struct StepEnd {
    time_ns: u64,
    step: u64,
    stage: Stage,
    probes: [f64; PROBES],
    rates: [f64; PROBES],
}

/// The exact advance's largest step, as a power of two of the plan's.
pub const MAX_STEP_LEVEL: u32 = 7;

/// The exact advance's tolerance on a peak output's miss inside a step out of contact, as a
/// fraction of its largest value so far (see `free_step_level`; a bound, the misses are smaller).
/// Measured on the reference fixture's damped scenarios and the paper scenario: every peak's error
/// against its reference the same to 0.01 % at 1e-4 and 1e-3, 12 % fewer steps at 1e-3 (paper
/// scenario 9 144 against 10 638).
pub const FREE_PEAK_TOLERANCE: f64 = 1e-3;

/// The exact advance's tolerance on the bar force's estimated departure from the cubic a contact
/// step takes, as a fraction of the largest contact force so far. Measured on the paper scenario
/// (converged printed rung, with the out-of-contact control) against the same run at 2 us contact
/// steps (818 345 steps): 4 903 steps at 1e-4, every peak within 4.4e-4 (the bridge's stress);
/// 5 703 at 1e-5, within 2.5e-5; 4 499 at 1e-3, within 9.7e-4 (the clamp shear). The straight
/// ramp the contact force took before needed 9 144 steps at 1e-4 for 1.9e-3. On the reference
/// fixture (`tests/converged_references.rs`): 13 of 21 runs trusted (12 with the ramp), no false
/// green, no false alarm.
pub const FORCE_RAMP_TOLERANCE: f64 = 1e-4;

/// [`FORCE_RAMP_TOLERANCE`] below [`crate::model::discretisation::LIGHT_DAMPING`]: the later
/// impacts of a lightly damped run hang on the bounces before them. With the cubic contact force,
/// damping 0.01 and drops of 0.56-1.79 m: the bridge's whole-run sigma_b at 1e-5 within 0.11-0.48 %
/// of the same runs at 2.8 us and 0.7 us contact steps (which agree to 1e-6), at 1e-4 up to 2.8 %
/// off (drop 1.635 m) for 20 % fewer steps.
pub const LIGHT_DAMPING_FORCE_RAMP_TOLERANCE: f64 = 1e-5;

impl<S: Stepper> Simulation<S> {
    /// The run from its parts; `rows`: a cache's rows of `modal`'s run basis (filled here where
    /// empty, else taken from it: the same rows).
    fn with_stepper(
        model: Model,
        modal: ModalSystem,
        stepper: S,
        physical: &Kinematics,
        motion: SupportMotion,
        rows: Option<&crate::solver::modal_cache::RunRows>,
    ) -> Result<Self> {
        let plan = StepPlan::new(&model.scenario, &modal)?;
        let forces = TipForces { upper: model.scenario.upper.tip_force, lower: model.scenario.lower.tip_force };
        let kinematics = stepper.own_coordinates(physical);
        // The basis's shapes, made only where a cache's rows do not hold what is made of them.
        let shapes = std::cell::OnceCell::new();
        let shapes = || shapes.get_or_init(|| modal.shapes());
        let in_modes = stepper.modal_coordinates();
        let rows = rows.filter(|_| in_modes);
        let nodal_shapes = match rows {
            Some(rows) => rows.nodal_shapes.get_or_init(|| std::sync::Arc::new(nodal_shapes(&model, shapes()))).clone(),
            None => std::sync::Arc::new(nodal_shapes(&model, shapes())),
        };
        let energy_method = EnergyMethod::new(&model.scenario);
        let state = RunState {
            kinematics,
            result: StepResult::default(),
            gap: 0.0,
            forces,
            last_forces: forces,
            initial_energy: 0.0,
            dissipation_rate: 0.0,
            peak_times: Peaks::default(),
            upper_strain_at_peak: 0.0,
            contact_windows: Vec::new(),
            max_residual: 0.0,
            max_strain_energy: 0.0,
            max_external_work: 0.0,
            output_ns: 0,
            input_forces: forces,
            first_contact: FirstContact::default(),
            motion,
            motion_ns: 0,
            input_motion: motion,
            inertial_potential: 0.0,
            step_level: 0,
            envelope: vec![0.0; model.stations.len()],
            envelope_times: vec![0.0; model.stations.len()],
            range: ModelRange::default(),
        };
        let range_rows = match rows {
            Some(rows) => {
                rows.range.get_or_init(|| std::sync::Arc::new(range_rows(&model, &modal, shapes(), true))).clone()
            }
            None => std::sync::Arc::new(range_rows(&model, &modal, shapes(), in_modes)),
        };
        let stations = if in_modes {
            let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
            let allowables: Vec<f64> = model.stations.all().map(|s| s.allowable).collect();
            let groups = crate::solver::envelope::groups(&model);
            let make = || std::sync::Arc::new(StationRows::new(&modal, &divisors, &allowables, groups.clone()));
            match rows {
                Some(rows) => {
                    let bits = divisors.iter().chain(&allowables).map(|v| v.to_bits());
                    let key: Vec<u64> = bits.chain(groups.iter().map(|&g| u64::from(g))).collect();
                    let (kept, shared) = rows.stations.get_or_init(|| (key.clone(), make()));
                    if *kept == key {
                        shared.clone()
                    } else {
                        make()
                    }
                }
                None => make(),
            }
        } else {
            std::sync::Arc::default()
        };
        let backup = state.kinematics.clone();
        let output = StepResult::default();
        let impact = Impact {
            // A rigid impactor does not turn (issue 45): its speed is the closing speed's.
            angular_velocity: if model.scenario.upper.kind == crate::model::scenario::ImpactorKind::Mass {
                0.0
            } else {
                Pitching::of(&model.scenario, model.scenario.gravity + motion.accelerations()[0]).angular_velocity
            },
            // 0 - x, not -x: a zero closing speed is +0 (the JSON and the FMU output read "-0").
            closing_speed: 0.0
                - ((model.probes.row(Probe::Gap as usize) * &physical.velocity)[0]
                    + motion.gap_offset_rate(model.scenario.lower_contact_position())),
        };
        let mut simulation = Simulation {
            model,
            modal,
            stepper,
            energy_method,
            nodal_shapes,
            plan,
            state,
            backup,
            step_end: None,
            output,
            output_peak_times: Peaks::default(),
            impact,
            stations,
            envelope_work: Default::default(),
            feed: FeedEnd::default(),
            turning_points: None,
            sub_impacts: Vec::new(),
            range_rows,
            follows_range: true,
            outputs_details: true,
            skipped_details: None,
            max_steps: crate::model::scenario::MAX_STEPS,
            peak_instants: Vec::new(),
            output_peak_instants: Vec::new(),
            far_support: None,
            tangent: None,
            gap_row: Vec::new(),
        };
        simulation.gap_row = simulation.modal.probes.row(Probe::Gap as usize).iter().copied().collect();
        simulation.far_support =
            crate::solver::far_support::FarSupport::new(&simulation.model, &simulation.modal).map(std::sync::Arc::new);
        simulation.evaluate_initial();
        Ok(simulation)
    }

    /// Which of the stress envelope's running values this run keeps exact: every station's (the
    /// default, what a log and `report` draw) or each envelope's peak only
    /// ([`EnvelopeScope::Peaks`]: an answer's check runs, a sweep's rows; the peaks are the same
    /// to the bit, the run faster).
    pub fn set_envelope_scope(&mut self, scope: EnvelopeScope) {
        self.envelope_work.set_scope(scope);
        if scope == EnvelopeScope::Peaks {
            // Its stations' values are partial: no history.
            self.turning_points = None;
        }
    }

    /// Keeps every station's turning points from here on (issue 44, fatigue: each station's
    /// signed stress at every step the envelope takes, with the crests inside the exact
    /// advance's contact steps; [`crate::solver::turning_points`]), starting with the current
    /// state. Only with every station's envelope ([`EnvelopeScope::Stations`], the default) and
    /// before the first step; else nothing is kept.
    pub fn keep_turning_points(&mut self) {
        if self.stations.is_empty()
            || self.envelope_work.scope() != EnvelopeScope::Stations
            || self.state.result.step != 0
        {
            return;
        }
        let excitation = self.excitation_at(self.state.result.time_ns);
        let loads = self.correction_loads(own(&self.state.kinematics), Stage::Free, &excitation);
        let mut values = vec![0.0; self.stations.len()];
        self.stations.stresses(self.state.kinematics.displacement.as_slice(), loads.as_ref(), &mut values);
        // The bending stations (the curves are of direct stress ranges): the arrestor's first, then
        // the bridge's, after the arrestor's shear stations.
        let st = &self.model.stations;
        let (lower, upper) = (st.lower.bending.len(), st.upper.bending.len());
        let upper_start = lower + st.lower.shear.len();
        let mut points = TurningPoints::new(vec![0..lower, upper_start..upper_start + upper]);
        let at = self.state.result.time_ns;
        points.begin_step(at, at);
        points.push(&values);
        self.turning_points = Some(points);
    }

    /// Every station's turning points up to the run's last internal step, if kept
    /// ([`Self::keep_turning_points`]), in the order of [`crate::model::stations::Stations::all`];
    /// with the stride every station was sampled at (1: every step; see
    /// [`crate::solver::envelope::ENVELOPE_BUDGET`]).
    pub fn turning_points(&self) -> Option<(TurningPoints, u64)> {
        let mut points = self.turning_points.clone()?;
        points.finish(self.state.result.time_ns);
        Some((points, self.stations.stride))
    }

    /// Adds the step `span` (ns) the envelope took as `observed` to the turning points, if kept.
    fn observe_turning_points(&mut self, span: (u64, u64), observed: Observed) {
        let Some(points) = &mut self.turning_points else { return };
        points.begin_step(span.0, span.1);
        match observed {
            Observed::Nothing => {}
            Observed::End => points.push(self.envelope_work.values()),
            Observed::Cubic(h) => {
                let (start, end) = self.envelope_work.step_ends();
                points.push_cubic(start, end, h);
            }
        }
    }

    /// Chunks of stations the envelope was asked to evaluate and those it skipped by their bound.
    pub fn envelope_skips(&self) -> (u64, u64) {
        (self.envelope_work.asked, self.envelope_work.skipped)
    }

    /// Raises the stress envelope by the current state, whose correction load coefficients are
    /// `loads` ([`Self::correction_loads`]), at `time` s.
    fn observe_envelope(&mut self, loads: Option<&[f64; LOADS]>, time: f64, step: u64) -> Observed {
        self.envelope_work.release_end();
        if self.stations.is_empty() || !step.is_multiple_of(self.stations.stride) {
            return Observed::Nothing;
        }
        let state = &mut self.state;
        self.stations.observe(
            &mut self.envelope_work,
            state.kinematics.displacement.as_slice(),
            loads,
            time,
            Running { max: &mut state.envelope, times: &mut state.envelope_times },
        );
        Observed::End
    }

    /// Raises the model's range (every node's deflection and rotation) by the current state,
    /// whose correction load coefficients are `loads`.
    fn observe_range(&mut self, loads: Option<&[f64; LOADS]>, time: f64) {
        if !self.follows_range {
            return;
        }
        let q = self.state.kinematics.displacement.as_slice();
        self.range_rows.observe(q, loads, time, &mut self.state.range);
    }

    /// Raises the stress envelope over the exact advance's contact step just taken (from
    /// `start_ns`, the state before it in `self.backup`), by the cubic through each station's
    /// values and rates at the step's ends: its steps are long in contact (the bar's force is a
    /// cubic over them), and a station's crest between two ends would be missed. Other steps
    /// (and every `stride`-th step of a large model's envelope) take the end alone
    /// ([`Self::observe_envelope`]).
    /// The end state's correction load coefficients are `loads`.
    fn observe_envelope_over_step(
        &mut self,
        stage: Stage,
        excitation: &Excitation,
        (start_ns, end_ns): (u64, u64),
        step: u64,
        loads: Option<&[f64; LOADS]>,
    ) -> Observed {
        let stride = self.stations.stride;
        if !(stage.is_contact() && self.stepper.adapts_steps() && stride == 1) || self.stations.is_empty() {
            return self.observe_envelope(loads, seconds(end_ns), step);
        }
        if !self.envelope_work.holds_end_of(step - 1, start_ns) {
            let start_excitation = self.excitation_at(start_ns);
            let (q0, v0) = (self.backup.displacement.as_slice(), self.backup.velocity.as_slice());
            let loads = self.correction_loads((q0, v0), stage, &start_excitation);
            let load_rates = self.correction_load_rates(&self.backup, stage, &start_excitation);
            let start = StationState { q: q0, v: v0, loads: loads.as_ref(), load_rates: load_rates.as_ref() };
            self.stations.set_start(&mut self.envelope_work, start);
        }
        let load_rates = self.correction_load_rates(&self.state.kinematics, stage, excitation);
        let RunState { kinematics, envelope, envelope_times, .. } = &mut self.state;
        let (q1, v1) = (kinematics.displacement.as_slice(), kinematics.velocity.as_slice());
        let end = StationState { q: q1, v: v1, loads, load_rates: load_rates.as_ref() };
        let start = (self.backup.displacement.as_slice(), self.backup.velocity.as_slice());
        self.stations.observe_step(
            &mut self.envelope_work,
            start,
            end,
            (step, end_ns),
            (seconds(start_ns), seconds(end_ns)),
            seconds(end_ns - start_ns),
            Running { max: envelope, times: envelope_times },
        );
        Observed::Cubic(seconds(end_ns - start_ns))
    }

    /// The rates of [`Self::correction_loads`] for `kinematics`: only the contact load moves
    /// within a stage, -k (b^T v + d') in contact, with the kept modes' gap rate (the load follows
    /// the modal gap b^T q + s + d, not the corrected gap the probes report); the other loads
    /// change with the inputs only.
    fn correction_load_rates(
        &self,
        kinematics: &Kinematics,
        stage: Stage,
        excitation: &Excitation,
    ) -> Option<[f64; LOADS]> {
        self.modal.is_truncated().then(|| {
            let mut rates = [0.0; LOADS];
            if stage.is_contact() {
                let gap_rate = self.modal_gap(kinematics.velocity.as_slice()) + excitation.gap_offset_rate;
                // A nonlinear law's P = G(D, V) moves with the gap's acceleration too.
                rates[crate::solver::static_correction::CONTACT] = match self.modal.law {
                    None => -self.modal.bar_stiffness * gap_rate,
                    Some(_) => {
                        let gap = self.modal_gap(kinematics.displacement.as_slice()) + excitation.gap_offset;
                        let acceleration = self.modal_gap(kinematics.acceleration.as_slice());
                        let law = self.modal.correction.law_load_rate(gap, (gap_rate, acceleration), excitation);
                        law.unwrap_or(0.0)
                    }
                };
            }
            rates
        })
    }

    /// The discarded modes' load coefficients at the state `(q, v)` (in `stage` under
    /// `excitation`; v read by a damped contact law), as the stepper's measurements take them;
    /// None for a full basis.
    fn correction_loads(
        &self,
        (q, v): (&[f64], &[f64]),
        stage: Stage,
        excitation: &Excitation,
    ) -> Option<[f64; LOADS]> {
        self.modal.is_truncated().then(|| {
            let gap = self.modal_gap(q) + excitation.gap_offset;
            let damped = self.modal.law.is_some_and(|law| law.damping > 0.0);
            let rate = if damped { self.modal_gap(v) + excitation.gap_offset_rate } else { 0.0 };
            self.modal.correction.loads(gap, rate, stage.is_contact(), excitation)
        })
    }

    /// The kept modes' gap functional b^T x of own coordinates `x` (displacements or their rates),
    /// without the supports' offset.
    fn modal_gap(&self, x: &[f64]) -> f64 {
        self.gap_row.iter().zip(x).map(|(b, x)| b * x).sum::<f64>()
    }

    /// Sends `result` with its own coordinates q (of `kinematics`) to `recorder`, after telling
    /// the stations' feed (if a recorder holds it) the step's load coefficients, from which with
    /// q the log's per-step stresses follow.
    /// Hands a step to the recorder. What only a recorded row needs, the support reactions and
    /// tip velocities ([`Recorder::wants_details`], a fifth of a step's cost) and the stations'
    /// load coefficients, is computed here for the steps the recorder keeps ([`Recorder::keeps`])
    /// and those it may record later (`must`: the step before a contact event, the last of an
    /// advance, a stop point). The run's E_def,b as of the step goes first
    /// ([`Recorder::deflection_peak_strain`]).
    fn record(
        &self,
        recorder: &mut dyn Recorder,
        result: &StepResult,
        kinematics: &Kinematics,
        must: bool,
    ) -> Result<()> {
        recorder.deflection_peak_strain(self.state.upper_strain_at_peak)?;
        if !(must || recorder.keeps(result)) {
            return recorder.step(result, kinematics.displacement.as_slice());
        }
        let (feed, details) = (self.feed.listened(), recorder.wants_details());
        if feed.is_none() && !details {
            // A recorder that keeps no stations and wants no details (a batch run's).
            return recorder.step(result, kinematics.displacement.as_slice());
        }
        let excitation = self.excitation_at(result.time_ns);
        let stage = if result.contact { Stage::Contact } else { Stage::Free };
        if let Some(feed) = feed {
            feed.set_loads(self.correction_loads(own(kinematics), stage, &excitation));
            self.publish_maxima(feed);
        }
        if details {
            let mut detailed = *result;
            self.set_support_and_tips(&mut detailed, kinematics, &excitation);
            return recorder.step(&detailed, kinematics.displacement.as_slice());
        }
        recorder.step(result, kinematics.displacement.as_slice())
    }

    /// Hands the run's envelope so far to the stations' feed, if a recorder holds it (the log
    /// attaches the latest when it is finished).
    fn publish_envelope(&self) {
        if let Some(feed) = self.feed.listened() {
            feed.set_envelope(self.envelope());
        }
    }

    fn evaluate_initial(&mut self) {
        let excitation = self.excitation_at(0);
        let (probes, energies) = self.stepper.measure(&self.state.kinematics, Stage::Free, &excitation);
        // The state's correction load coefficients, once for the envelope and the range.
        let loads = self.correction_loads(own(&self.state.kinematics), Stage::Free, &excitation);
        let _ = self.observe_envelope(loads.as_ref(), 0.0, 0);
        self.observe_range(loads.as_ref(), 0.0);
        let mut result = self.outputs(&probes, Stage::Free, &self.motion_at(0), 0.0);
        self.set_support_and_tips(&mut result, &self.state.kinematics, &excitation);
        self.state.inertial_potential = energies.inertial_potential;
        self.state.gap = probes[Probe::Gap as usize];
        result.energy.kinetic = energies.kinetic;
        result.energy.strain = energies.beam_strain;
        result.energy.gravity_potential = energies.gravity_potential;
        self.state.initial_energy = energies.kinetic + energies.beam_strain + energies.gravity_potential;
        self.state.dissipation_rate = energies.dissipation_rate;
        self.state.max_strain_energy = energies.beam_strain;
        self.state.result = result;
        self.update_peaks(energies.upper_strain, None);
        self.output = self.state.result;
        self.output_peak_times = self.state.peak_times;
    }

    /// The supports' motion at `at_ns` (at or after the current motion's start), continued with
    /// its constant accelerations.
    pub fn motion_at(&self, at_ns: u64) -> SupportMotion {
        let state = &self.state;
        state.motion.after(seconds(at_ns.saturating_sub(state.motion_ns)))
    }

    /// The excitation at `at_ns` under the current tip forces and support motion.
    fn excitation_at(&self, at_ns: u64) -> Excitation {
        self.excitation_of(&self.motion_at(at_ns))
    }

    /// The excitation of the supports' `motion` under the current tip forces.
    fn excitation_of(&self, motion: &SupportMotion) -> Excitation {
        excitation(&self.model, self.state.forces, motion)
    }

    /// Sets the support reactions and tip velocities of `kinematics` on `result`.
    /// The stage is the one `result`'s step was taken in, the excitation that at its time.
    fn set_support_and_tips(&self, result: &mut StepResult, kinematics: &Kinematics, excitation: &Excitation) {
        let stage = if result.contact { Stage::Contact } else { Stage::Free };
        let d = self.stepper.support_and_tips(kinematics, stage, excitation);
        result.lower_clamp_reaction_force = d.clamp_force;
        result.lower_clamp_reaction_moment = d.clamp_moment;
        result.upper_hinge_reaction_force = d.hinge_force;
        result.lower_tip_velocity = d.lower_tip_velocity;
        result.upper_tip_velocity = d.upper_tip_velocity;
        if let Some(far) = &self.far_support {
            let modal = self.stepper.modal_coordinates();
            let loads = if modal { self.correction_loads(own(kinematics), stage, excitation) } else { None };
            let (q, v, a) = (
                kinematics.displacement.as_slice(),
                kinematics.velocity.as_slice(),
                kinematics.acceleration.as_slice(),
            );
            let [force, moment] = far.evaluate(modal, q, v, a, loads.as_ref());
            result.lower_far_reaction_force = force;
            result.lower_far_reaction_moment = moment;
        }
    }

    /// The contact force (N, negative in compression) at gap `gap` closing at `rate` (m/s): the
    /// linear bar's k gap (Eq. 5), or a nonlinear law's -P(-gap, -rate).
    fn contact_force(&self, gap: f64, rate: f64, stage: Stage) -> f64 {
        match self.modal.law {
            Some(law) if stage.is_contact() => -law.force(-gap, -rate),
            _ => contact::bar_force(self.model.bar_stiffness, gap, stage),
        }
    }

    /// The gap's rate of `kinematics` (m/s) where a nonlinear law needs it (its damping), else 0.
    fn gap_rate(&self, kinematics: &Kinematics, stage: Stage, excitation: &Excitation) -> f64 {
        match self.modal.law {
            Some(_) if stage.is_contact() => self.stepper.rates(kinematics, stage, excitation)[Probe::Gap as usize],
            _ => 0.0,
        }
    }

    /// The contact's dissipation rate (W) under a nonlinear law with damping, else 0.
    fn contact_dissipation_rate(&self, gap: f64, rate: f64, stage: Stage) -> f64 {
        match self.modal.law {
            Some(law) if stage.is_contact() => law.dissipation_rate(-gap, -rate),
            _ => 0.0,
        }
    }

    /// The outputs of the displacement probes `probes` with the supports at `motion`, without
    /// time or energy.
    fn outputs(&self, probes: &[f64; PROBES], stage: Stage, motion: &SupportMotion, rate: f64) -> StepResult {
        let s = &self.model.scenario;
        let force = self.contact_force(probes[Probe::Gap as usize], rate, stage);
        let (hinge, clamp, rotation) = (motion.hinge_heave, motion.clamp_heave, motion.clamp_rotation);
        StepResult {
            upper_support_displacement: hinge.displacement,
            lower_support_displacement: clamp.displacement + rotation.displacement * s.lower.length,
            contact: stage.is_contact(),
            lower_tip_deflection: probes[Probe::LowerTipDeflection as usize],
            upper_contact_deflection: probes[Probe::UpperContactDeflection as usize],
            upper_tip_deflection: probes[Probe::UpperTipDeflection as usize],
            lower_clamp_bending_stress: probes[Probe::ClampMoment as usize] / s.lower.section_modulus,
            lower_clamp_shear_stress: probes[Probe::ClampShear as usize] / s.lower.shear_area,
            upper_contact_bending_stress: probes[Probe::UpperContactMoment as usize]
                / self.model.contact_section_modulus,
            contact_force: force,
            contact_stress: force / s.contact.area,
            ..StepResult::default()
        }
    }

    /// Raises the running peaks by the latest step: its end values, or with `within_step` (the
    /// converged method) the largest |value| of each output over the step and when it was reached;
    /// `upper_strain` is the bridge's strain energy where the arrestor's deflection peaks.
    fn update_peaks(&mut self, upper_strain: f64, within_step: Option<[(f64, f64); 5]>) {
        let r = &mut self.state.result;
        let extremes = match within_step {
            Some(extremes) => extremes,
            None => r.peak_magnitudes().map(|v| (v, r.time)),
        };
        self.state.first_contact.observe_values(r, &extremes.map(|(v, _)| v));
        // By value, not through `as_mut_array`'s references (which the loop kept as pointers).
        let (mut peaks, mut times) = (r.peaks.as_array(), self.state.peak_times.as_array());
        for (k, &(value, time)) in extremes.iter().enumerate() {
            if value > peaks[k] || r.step == 0 {
                peaks[k] = value;
                times[k] = time;
                if k == 0 {
                    self.state.upper_strain_at_peak = upper_strain;
                }
            }
        }
        r.peaks = Peaks::from_array(peaks);
        self.state.peak_times = Peaks::from_array(times);
    }

    /// The bridge's strain energy (J) at the instant of the arrestor's largest deflection over the
    /// step just taken from `previous` (E_def,b where the deflection peaks): with `within_step`
    /// (the converged method) at the instant inside the step where it peaks, from the state there
    /// ([`Self::point_kinematics`], the state the log's row at that instant holds), else at the
    /// step's end (`end`'s). Only evaluated inside the step when that raises the running peak.
    fn upper_strain_at_deflection_peak(
        &mut self,
        previous: &StepResult,
        stage: Stage,
        within_step: Option<&[(f64, f64); 5]>,
        end: &Energies,
    ) -> f64 {
        let Some(&(value, at)) = within_step.map(|e| &e[0]) else { return end.upper_strain };
        let at_ns = (at * 1e9).round() as u64;
        let inside = at_ns > previous.time_ns && at_ns < self.state.result.time_ns;
        if !(inside && value > previous.peaks.lower_tip_deflection) {
            return end.upper_strain;
        }
        let kinematics = self.point_kinematics(previous.time_ns, at_ns, stage);
        self.stepper.measure(&kinematics, stage, &self.excitation_at(at_ns)).1.upper_strain
    }

    /// Whether the running peaks are the largest |value| over each internal step (the converged
    /// method) rather than at the steps' ends (the paper's method, as its Table 1 was made).
    fn polynomial_peaks(&self) -> bool {
        self.model.scenario.method == Method::Converged
    }

    /// The largest |value| of each peak output over the first `fraction` of the step just taken
    /// (from `backup` to the current kinematics, in `stage`), with its time, s: the
    /// cubic of each output from its values and rates at the step's ends
    /// ([`crate::solver::step_extrema`]). `end` holds the probes at the step's end.
    /// Returns the end's rates too (the next step's start: [`StepEnd`]). With `floors` (the
    /// peaks so far, in the order of [`Peaks::as_array`]), an output whose cubic is bounded below
    /// its floor (|H00 p0 + H01 p1| <= max(|p0|, |p1|), |H10|, |H11| <= 4/27 on [0, 1]) is not
    /// sought: its step-end value stands in, which raises no peak, as the cubic's would not.
    /// `e1` is the excitation at the step's end (its caller's: not evaluated again).
    fn step_extremes(
        &self,
        start: &StepResult,
        (end, e1): (&[f64; PROBES], &Excitation),
        stage: Stage,
        fraction: f64,
        floors: Option<[f64; 5]>,
    ) -> ([(f64, f64); 5], [f64; PROBES]) {
        let s = &self.model.scenario;
        let (k0, k1) = (&self.backup, &self.state.kinematics);
        let dt = seconds(self.state.result.time_ns - start.time_ns);
        let (p0, r0) = match &self.step_end {
            Some(c) if c.time_ns == start.time_ns && c.step == start.step && c.stage == stage => (c.probes, c.rates),
            _ => {
                let e0 = self.excitation_at(start.time_ns);
                (self.stepper.measure(k0, stage, &e0).0, self.stepper.rates(k0, stage, &e0))
            }
        };
        let r1 = self.stepper.rates(k1, stage, e1);
        let bar = if stage.is_contact() { self.model.bar_stiffness } else { 0.0 };
        let outputs = [
            (Probe::LowerTipDeflection, 1.0),
            (Probe::ClampMoment, 1.0 / s.lower.section_modulus),
            (Probe::ClampShear, 1.0 / s.lower.shear_area),
            (Probe::UpperContactMoment, 1.0 / self.model.contact_section_modulus),
            (Probe::Gap, bar),
        ];
        let law = self.modal.law.filter(|_| stage.is_contact());
        // A loop, not a map over the outputs: the map's closure stayed a call of its own, five a step.
        let mut extremes = [(0.0, 0.0); 5];
        for (index, (probe, scale)) in outputs.into_iter().enumerate() {
            let k = probe as usize;
            let floor = floors.as_ref().map(|f| f[index]);
            if let (Some(floor), None) = (floor, law) {
                let reach =
                    (p0[k].abs().max(end[k].abs()) + 4.0 / 27.0 * dt * (r0[k].abs() + r1[k].abs())) * scale.abs();
                // A margin far above the bound's and the cubic's round-off.
                if reach * (1.0 + 1e-10) < floor {
                    extremes[index] = (end[k].abs() * scale.abs(), self.state.result.time);
                    continue;
                }
            }
            let (value, at) =
                crate::solver::step_extrema::cubic_extremum(p0[k], end[k], r0[k] * dt, r1[k] * dt, fraction);
            // The time within the run (never past the step's end by round-off).
            let at = (seconds(start.time_ns) + at * dt).min(self.state.result.time);
            extremes[index] = match (probe, law) {
                // With damping the force crests before the largest compression: the largest of
                // the force's own cubic over the step.
                (Probe::Gap, Some(law)) if law.damping > 0.0 => {
                    let gap = (p0[k], end[k], r0[k] * dt, r1[k] * dt);
                    let accelerations =
                        (self.stepper.probes(&k0.acceleration)[k], self.stepper.probes(&k1.acceleration)[k]);
                    let (force, at) =
                        crate::solver::step_extrema::law_force_extremum(&law, gap, accelerations, dt, fraction);
                    (force, (seconds(start.time_ns) + at * dt).min(self.state.result.time))
                }
                // A nonlinear law's force at the step's largest compression (its elastic part),
                // or at the step's end, whichever is larger.
                (Probe::Gap, Some(law)) => {
                    let end_force = law.force(-end[k], -r1[k]);
                    let inside = law.elastic(value);
                    if end_force > inside {
                        (end_force, self.state.result.time)
                    } else {
                        (inside, at)
                    }
                }
                _ => (value * scale.abs(), at),
            };
        }
        (extremes, r1)
    }

    /// The exact advance's in-step extremes made values of its own solution (issue 41): the
    /// cubic through a step's ends locates each output's largest |value| inside the step, and
    /// where that raises a peak (the run's, or the first sustained contact's while it lasts) the
    /// output is taken from the exact advance's own step to that instant, to the nanosecond,
    /// moved by one Newton step on the output's own rate and curvature there (kept if larger),
    /// or the step's end `end` ((ns, its peak values)) where that is larger. So a printed peak is
    /// a value the solution takes at its printed time, which the log records (each instant is
    /// added to `instants`), and no other instant's value exceeds it by more than the
    /// nanosecond's rounding (|f''| dt^2 / 2: 1e-11 of it at 1e4 rad/s). The linear acceleration
    /// method's cubic is its own solution inside the step: its extremes stand.
    fn exact_extremes(
        &mut self,
        start: &StepResult,
        (end_ns, ends): (u64, [f64; 5]),
        stage: Stage,
        extremes: &mut [(f64, f64); 5],
        instants: &mut Vec<u64>,
    ) {
        if !self.stepper.adapts_steps() {
            return;
        }
        let first = &self.state.first_contact;
        let open = first.end().is_none();
        let (running, first_peaks) = (start.peaks.as_array(), first.peaks.as_array());
        let damped_law = self.modal.law.is_some_and(|l| l.damping > 0.0) && stage.is_contact();
        let inside = |t: f64| t > start.time_ns as f64 && t < end_ns as f64;
        // The instants evaluated in this step, with their peak values (outputs share instants).
        let mut taken: Vec<(u64, [f64; 5], Kinematics)> = Vec::new();
        for k in 0..5 {
            let (value, at) = extremes[k];
            let floor = if open { running[k].min(first_peaks[k]) } else { running[k] };
            // Most outputs raise no peak: their instant is not rounded (a call, five a step).
            let raises = value > floor;
            if !raises {
                continue;
            }
            let at_ns = (at * 1e9).round();
            if !inside(at_ns) {
                continue;
            }
            let mut best = self.values_at(start, at_ns as u64, stage, &mut taken);
            // One Newton step towards the output's own extremum (not for a damped law's force,
            // whose crest is not the gap's).
            let probe = PEAK_PROBES[k] as usize;
            if !(k == 4 && damped_law) {
                let kinematics = &taken.iter().find(|(t, ..)| *t == best.0).expect("just evaluated").2;
                let excitation = self.excitation_at(best.0);
                let rate = self.stepper.rates(kinematics, stage, &excitation)[probe];
                let curvature = self.stepper.probes(&kinematics.acceleration)[probe];
                let moved = (best.0 as f64 - rate / curvature * 1e9).round();
                if curvature != 0.0 && moved.is_finite() && inside(moved) && moved as u64 != best.0 {
                    let other = self.values_at(start, moved as u64, stage, &mut taken);
                    if other.1[k] > best.1[k] {
                        best = other;
                    }
                }
            }
            let (at_ns, values) = best;
            extremes[k] = if values[k] >= ends[k] { (values[k], seconds(at_ns)) } else { (ends[k], seconds(end_ns)) };
            if values[k] >= ends[k] && !instants.contains(&at_ns) {
                instants.push(at_ns);
            }
        }
    }

    /// The peak values at `at_ns` inside the step from `start` ([`Self::point`]), from `taken` if
    /// evaluated already (else evaluated and kept there).
    fn values_at(
        &mut self,
        start: &StepResult,
        at_ns: u64,
        stage: Stage,
        taken: &mut Vec<(u64, [f64; 5], Kinematics)>,
    ) -> (u64, [f64; 5]) {
        if let Some((t, v, _)) = taken.iter().find(|(t, ..)| *t == at_ns) {
            return (*t, *v);
        }
        let (row, kinematics) = self.point(start, at_ns, stage);
        let values = row.peak_magnitudes();
        taken.push((at_ns, values, kinematics));
        (at_ns, values)
    }

    /// The own coordinates at `at_ns` inside the step just taken from `self.backup` (at
    /// `start_ns`, in `stage`) to the current state: the exact advance's own step to the point,
    /// else the linear acceleration's cubic displacement and quadratic velocity (the method's
    /// solution inside its step).
    fn point_kinematics(&mut self, start_ns: u64, at_ns: u64, stage: Stage) -> Kinematics {
        let tau = seconds(at_ns - start_ns);
        if self.stepper.adapts_steps() {
            let mut k = self.backup.clone();
            self.stepper.step_aside(&mut k, stage, tau, &self.excitation_at(at_ns));
            k
        } else {
            let dt = seconds(self.state.result.time_ns - start_ns);
            linear_acceleration_within(&self.backup, &self.state.kinematics, dt, tau)
        }
    }

    /// The outputs of `kinematics` at `at_ns` in `stage`, without support reactions, energies or
    /// peaks.
    fn point_outputs(&self, kinematics: &Kinematics, at_ns: u64, stage: Stage) -> StepResult {
        let excitation = self.excitation_at(at_ns);
        let (probes, _) = self.stepper.measure(kinematics, stage, &excitation);
        let rate = self.gap_rate(kinematics, stage, &excitation);
        let mut result = self.outputs(&probes, stage, &self.motion_at(at_ns), rate);
        result.time_ns = at_ns;
        result.time = seconds(at_ns);
        result
    }

    /// The outputs and own coordinates at `at_ns` inside the step just taken from `self.backup`
    /// (the state of `start`, in `stage`): [`Self::point_kinematics`], [`Self::point_outputs`].
    fn point(&mut self, start: &StepResult, at_ns: u64, stage: Stage) -> (StepResult, Kinematics) {
        let kinematics = self.point_kinematics(start.time_ns, at_ns, stage);
        (self.point_outputs(&kinematics, at_ns, stage), kinematics)
    }

    /// The next internal step in `stage`, ns: the plan's, or with the exact advance the plan's
    /// times 2^level: out of contact as the modes' amplitudes allow, in contact as the force's
    /// smoothness allows: see `adapt_step`).
    pub fn next_step_ns(&self, stage: Stage) -> u64 {
        let base = self.plan.step_ns(stage.is_contact());
        base.saturating_mul(1 << self.step_level(stage))
    }

    /// The power of two of the plan's step that the next step in `stage` takes: 0 but for the
    /// exact advance's automatic steps (a fixed step is the user's: taken as given).
    fn step_level(&self, stage: Stage) -> u32 {
        let s = &self.model.scenario;
        let automatic = if stage.is_contact() { s.step_contact } else { s.step_free } == TimeStep::Auto;
        match (self.stepper.adapts_steps() && automatic, stage.is_contact()) {
            (false, _) => 0,
            (true, _) => self.state.step_level,
        }
    }

    /// The longest internal step the run may take, ns: the plan's longer step, times
    /// 2^[`MAX_STEP_LEVEL`] for the exact advance.
    pub fn longest_step_ns(&self) -> u64 {
        let longest = self.plan.free_ns.max(self.plan.contact_ns);
        if self.stepper.adapts_steps() {
            longest.saturating_mul(1 << MAX_STEP_LEVEL)
        } else {
            longest
        }
    }

    /// The step-size control of the exact advance in contact: down one level when the bar's force
    /// strayed from the step's ramp by more than [`FORCE_RAMP_TOLERANCE`] of the largest force so
    /// far, up one when by less than a sixteenth of it (a doubled step's error grows ~4-8x), back
    /// to the plan's step at every contact change.
    fn adapt_step(&mut self, stage: Stage, next: Stage, step_ns: u64, probes: &[f64; PROBES]) {
        if !self.stepper.adapts_steps() {
            return;
        }
        if !next.is_contact() {
            if self.model.scenario.step_free == TimeStep::Auto {
                self.state.step_level = self.free_step_level(probes);
            }
            return;
        }
        if self.model.scenario.step_contact != TimeStep::Auto {
            return;
        }
        let level = &mut self.state.step_level;
        if next != stage {
            *level = 0;
            return;
        }
        let Some(error) = self.stepper.force_ramp_error() else { return };
        if step_ns < self.plan.step_ns(true) << *level {
            // A shortened step (landing on an output time) says little of the level's.
            return;
        }
        let scale = self.state.result.peaks.contact_force.max(self.state.result.contact_force.abs());
        let fraction = if self.model.scenario.damping_ratio < crate::model::discretisation::LIGHT_DAMPING {
            LIGHT_DAMPING_FORCE_RAMP_TOLERANCE
        } else {
            FORCE_RAMP_TOLERANCE
        };
        let tolerance = fraction * scale;
        if error > tolerance {
            *level = level.saturating_sub(1);
        } else if error < tolerance / 16.0 && *level < MAX_STEP_LEVEL {
            *level += 1;
        }
    }

    /// The exact advance's level out of contact: the longest step over which the cubic through
    /// each peak output's values and rates at the step's ends (the peaks inside a step) can miss
    /// by at most [`FREE_PEAK_TOLERANCE`] of its largest value so far, and the gap's by at most
    /// half the gap (so that no touch hides inside a step): a Hermite cubic misses by at most
    /// h^4 / 384 max|p^(4)|, bounded by the modes' amplitudes.
    fn free_step_level(&mut self, probes: &[f64; PROBES]) -> u32 {
        let Some(fourth) = self.stepper.free_fourth_derivatives(&self.state.kinematics) else { return 0 };
        let s = &self.model.scenario;
        let peaks = &self.state.result.peaks;
        let limits = [
            (Probe::LowerTipDeflection, FREE_PEAK_TOLERANCE * peaks.lower_tip_deflection),
            (Probe::ClampMoment, FREE_PEAK_TOLERANCE * peaks.lower_clamp_bending_stress * s.lower.section_modulus),
            (Probe::ClampShear, FREE_PEAK_TOLERANCE * peaks.lower_clamp_shear_stress * s.lower.shear_area),
            (
                Probe::UpperContactMoment,
                FREE_PEAK_TOLERANCE * peaks.upper_contact_bending_stress * self.model.contact_section_modulus,
            ),
            (Probe::Gap, 0.5 * probes[Probe::Gap as usize]),
        ];
        let base = seconds(self.plan.free_ns);
        (0..=MAX_STEP_LEVEL)
            .rev()
            .find(|&level| {
                let h = base * f64::from(1u32 << level);
                let factor = (h * h) * (h * h) / 384.0;
                limits.iter().all(|&(probe, limit)| factor * fourth[probe as usize] <= limit)
            })
            .unwrap_or(0)
    }

    /// Stage of the next step, by Eq. (6) on the current state.
    pub fn next_stage(&self) -> Stage {
        contact::stage(self.state.gap)
    }

    /// Takes one internal step of at most `max_step_ns` (the stage's own step otherwise) and
    /// returns the contact event if Eq. (6) gives the next step the other stage: the change is
    /// located at the end of this step, which is when the event is reported. A step that would
    /// leave a non-finite state (an absurd tip force) is undone and reported as an error.
    /// With `details`, the step's support reactions and tip velocities are set too.
    pub fn step(&mut self, max_step_ns: u64, details: bool) -> Result<Option<ContactEvent>> {
        let stage = self.next_stage();
        let previous = self.state.result;
        if previous.step >= self.max_steps {
            return Err(Error::StepLimit {
                limit: self.max_steps,
                estimate: self.step_estimate(self.model.scenario.duration_ns()),
                time: previous.time,
                duration: self.model.scenario.duration,
                last_step: previous.step_size,
                planned: seconds(self.plan.free_ns.min(self.plan.contact_ns)),
            });
        }
        let mut step_ns = self.next_step_ns(stage).min(max_step_ns).max(1);
        let mut dt = seconds(step_ns);
        let forces = self.state.forces;
        self.backup.copy_from(&self.state.kinematics);
        // The supports' motion at the step's end: its excitation, outputs and energy account.
        let mut motion = self.motion_at(previous.time_ns + step_ns);
        let mut excitation = self.excitation_of(&motion);
        let (mut probes, mut energies) = self.stepper.step_measured(&mut self.state.kinematics, stage, dt, &excitation);
        if contact::stage(probes[Probe::Gap as usize]) != stage && step_ns > 1 {
            // The located step's end as its last retake measured it (the same sums).
            (step_ns, probes, energies) = self.locate_stage_change(stage, step_ns, probes[Probe::Gap as usize]);
            dt = seconds(step_ns);
            motion = self.motion_at(previous.time_ns + step_ns);
            excitation = self.excitation_of(&motion);
        }
        if !(probes.iter().all(|p| p.is_finite()) && energies.kinetic.is_finite() && energies.beam_strain.is_finite()) {
            self.state.kinematics.copy_from(&self.backup);
            return Err(Error::Numerical {
                what: "time step",
                detail: format!(
                    "the step from t = {} s (step {}) gives a non-finite state; tip forces: upper {:.6e} N, lower \
                     {:.6e} N; support motion: {}",
                    previous.time,
                    previous.step,
                    forces.upper,
                    forces.lower,
                    describe_motion(&self.state.motion)
                ),
            });
        }
        if self.tangent.is_some() {
            self.tangent_advance(stage, previous.time_ns, step_ns);
        }
        self.state.gap = probes[Probe::Gap as usize];
        let span = (previous.time_ns, previous.time_ns + step_ns);
        // The end state's correction load coefficients, once for the envelope and the range.
        let loads = self.correction_loads(own(&self.state.kinematics), stage, &excitation);
        let observed = self.observe_envelope_over_step(stage, &excitation, span, previous.step + 1, loads.as_ref());
        self.observe_turning_points(span, observed);
        self.observe_range(loads.as_ref(), seconds(span.1));
        let rate = self.gap_rate(&self.state.kinematics, stage, &excitation);
        energies.dissipation_rate += self.contact_dissipation_rate(self.state.gap, rate, stage);
        let mut result = self.outputs(&probes, stage, &motion, rate);
        if details {
            self.set_support_and_tips(&mut result, &self.state.kinematics, &excitation);
        }
        result.step = previous.step + 1;
        result.time_ns = previous.time_ns + step_ns;
        result.time = seconds(result.time_ns);
        result.step_size = dt;
        result.peaks = previous.peaks;
        // `self.state` still describes the step's start (its result, forces and dissipation rate
        // are updated below).
        // The damping's work over the step: the exact advance's own, else the rate's trapezoid.
        let dissipated = self
            .stepper
            .step_dissipation()
            .unwrap_or(0.5 * dt * (self.state.dissipation_rate + energies.dissipation_rate));
        let energy = self.energy_account(
            &self.state,
            (&result, &motion),
            stage,
            probes[Probe::Gap as usize],
            &energies,
            dissipated,
        );
        result.energy = energy;
        self.state.max_residual = self.state.max_residual.max(energy.residual.abs());
        self.state.max_strain_energy = self.state.max_strain_energy.max(energy.strain);
        self.state.max_external_work = self.state.max_external_work.max(energy.external_work.abs());
        self.state.dissipation_rate = energies.dissipation_rate;
        self.state.inertial_potential = energies.inertial_potential;
        self.state.last_forces = forces;
        self.state.result = result;
        let within_step = if self.polynomial_peaks() {
            // Once the first contact's peaks are settled, only the run's own can rise.
            let floors = self.state.first_contact.end().is_some().then(|| previous.peaks.as_array());
            let (mut extremes, rates) = self.step_extremes(&previous, (&probes, &excitation), stage, 1.0, floors);
            let ends = result.peak_magnitudes();
            self.peak_instants.clear();
            let mut instants = std::mem::take(&mut self.peak_instants);
            self.exact_extremes(&previous, (result.time_ns, ends), stage, &mut extremes, &mut instants);
            self.peak_instants = instants;
            self.step_end = Some(StepEnd { time_ns: result.time_ns, step: result.step, stage, probes, rates });
            Some(extremes)
        } else {
            None
        };
        let force_peak = within_step.map_or((result.contact_force.abs(), result.time), |e| e[4]);
        let first_before =
            self.tangent.as_ref().map(|_| (self.state.first_contact.peaks, self.state.first_contact.ended));
        let upper_strain = self.upper_strain_at_deflection_peak(&previous, stage, within_step.as_ref(), &energies);
        self.update_peaks(upper_strain, within_step);
        if let Some(first_before) = first_before {
            self.tangent_after_step(stage, &previous, step_ns, within_step.as_ref(), first_before);
        }
        if stage.is_contact() {
            if let Some(last) = self.sub_impacts.last_mut() {
                last.observe(result.time, force_peak);
            }
        }

        let windows = &mut self.state.contact_windows;
        if stage.is_contact() {
            if let Some(w) = windows.last_mut() {
                w.end = result.time;
            }
        }
        let next = contact::stage(self.state.gap);
        self.adapt_step(stage, next, step_ns, &probes);
        let windows = &mut self.state.contact_windows;
        if next == stage {
            return Ok(None);
        }
        if next.is_contact() {
            windows.push(ContactWindow { start: result.time, end: result.time });
        }
        let relative_velocity =
            self.stepper.probes(&self.state.kinematics.velocity)[Probe::Gap as usize] + excitation.gap_offset_rate;
        if next.is_contact() {
            self.sub_impacts.push(crate::results::SubImpact::starting(result.time, relative_velocity));
        } else if let Some(last) = self.sub_impacts.last_mut() {
            last.separate(result.time, relative_velocity);
        }
        Ok(Some(ContactEvent {
            start: next.is_contact(),
            time_ns: result.time_ns,
            step: result.step + 1,
            relative_velocity,
        }))
    }

    /// The step from `backup` ended in the other stage (gap `gap_end` after `step_ns`): retakes it
    /// with the shortest whole-nanosecond step after which Eq. (6) has changed, so that every stage
    /// starts where the gap crosses zero, whatever the step phase. The exact advance's first guess
    /// is the first whole nanosecond past the root of the gap's Taylor series about the step's
    /// nearer end ([`Self::series_root_ns`]; the root of the gap's cubic over the step where the
    /// series cannot tell), and each retake's gap and gap rate give the next by Newton's method
    /// (the first whole nanosecond past the root, or the one before the bracket's end); a retake in
    /// the other stage whose Newton root lies within the nanosecond before it ends the search (the
    /// nanosecond before is this stage's, up to a thousandth of a nanosecond's curvature). Each
    /// retake is a new step size whose coefficients cost more than the step: measured on the sea
    /// example (its three runs, 379 changes), the series' first guess is the located nanosecond for
    /// 95 % of the changes out of contact and 61 % of those in contact (the cubic's: 22 % and 7 %);
    /// on 20 events of its campaign 1.47 retakes a change against the cubic's 2.03. In contact a
    /// Newton break that the retake's own error could move is checked on the nanosecond before
    /// ([`Self::retake_slope_in_doubt`]). Otherwise, and whenever Newton leaves the bracket,
    /// regula falsi on the nearly linear gap(t), alternating with bisection so that the bracket
    /// always shrinks (a pure regula falsi stalls on one side). Returns the step taken, ns, with its
    /// end's probes and energies (the last retake's measurement); the state is left at its end.
    // Out of line (its callers' rare path): inlined, `step` grew and its common path cost more
    // (6.8943e9 against 6.9001e9 instructions on 20 campaign events).
    #[inline(never)]
    fn locate_stage_change(&mut self, stage: Stage, step_ns: u64, gap_end: f64) -> (u64, [f64; PROBES], Energies) {
        let start_ns = self.state.result.time_ns;
        let threshold = -contact::GAP_TOLERANCE;
        let gap_start = self.state.gap;
        let (mut lo, mut hi) = (0u64, step_ns);
        let (mut f_lo, mut f_hi) = (gap_start - threshold, gap_end - threshold);
        // The measurement of the latest retake, when it was `hi`'s.
        let mut at_hi: Option<([f64; PROBES], Energies)> = None;
        let newton = self.stepper.adapts_steps();
        // The gap (less the threshold) after a retake of `ns`, its rate (m/s; with `newton`) and
        // the retake's measurement.
        let retake = |simulation: &mut Self, ns: u64| {
            simulation.state.kinematics.copy_from(&simulation.backup);
            let excitation = simulation.excitation_at(start_ns + ns);
            simulation.stepper.step(&mut simulation.state.kinematics, stage, seconds(ns), &excitation);
            let measured = simulation.stepper.measure(&simulation.state.kinematics, stage, &excitation);
            let gap = measured.0[Probe::Gap as usize] - threshold;
            let rate = if newton {
                simulation.stepper.rates(&simulation.state.kinematics, stage, &excitation)[Probe::Gap as usize]
            } else {
                0.0
            };
            (gap, rate, measured)
        };
        // The supports' gap offset moves at a constant acceleration over the step.
        let (e0, e1) = (self.excitation_at(start_ns), self.excitation_at(start_ns + step_ns));
        let offset_acceleration = (e1.gap_offset_rate - e0.gap_offset_rate) / seconds(step_ns);
        let cubic = self.cubic_root_ns(stage, step_ns, gap_end, threshold);
        let mut next = cubic.map(|c| {
            // The series about the step's end nearer to the cubic's root.
            let gap = Probe::Gap as usize;
            let at = if 2 * c > step_ns {
                let rate = self.stepper.rates(&self.state.kinematics, stage, &e1)[gap];
                (&self.state.kinematics, &e1, step_ns, gap_end - threshold, rate)
            } else {
                (&self.backup, &e0, 0, gap_start - threshold, self.stepper.rates(&self.backup, stage, &e0)[gap])
            };
            self.series_root_ns(stage, at, offset_acceleration, c as f64, (0, step_ns)).unwrap_or(c)
        });
        let mut bisect = false;
        // A nonlinear law's retakes follow their own end gap, not the state's rate: the force's
        // cubic over a step that ends near a separation departs from the law's (k x^n is not
        // smooth at x = 0), so the end gap moves with the step at other than the gap's rate
        // (measured on the hertz-buffer example: 0.045 m/s against a rate of 0.226 m/s, and
        // Newton crept to the crossing in 16 retakes). There the secant through the last two
        // retakes gives the slope, once they differ.
        let secant = newton && self.modal.law.is_some();
        let mut previous: Option<(u64, f64)> = None;
        while hi - lo > 1 {
            let guess = if let Some(g) = next.take().filter(|&g| g > lo && g < hi) {
                g
            } else if bisect || f_lo == f_hi {
                lo + (hi - lo) / 2
            } else {
                let t = f_lo / (f_lo - f_hi);
                (lo + (t * (hi - lo) as f64).round() as u64).clamp(lo + 1, hi - 1)
            };
            let (f, rate, measured) = retake(self, guess);
            let rate = match previous {
                Some((g0, f0)) if secant && g0 != guess && f != f0 => (f - f0) / ((guess as f64 - g0 as f64) * 1e-9),
                _ => rate,
            };
            previous = Some((guess, f));
            let changed = contact::stage(f + threshold) != stage;
            if changed {
                hi = guess;
                f_hi = f;
                at_hi = Some(measured);
                // Newton from here puts the crossing within the nanosecond before: the one
                // before is the other stage's (the gap's curvature moves it by ~|gap''| / 2 1e-18
                // m, a thousandth of a nanosecond's worth of its rate or less), no retake needed.
                let root = guess as f64 - f / (rate * 1e-9);
                if newton && rate != 0.0 && root.is_finite() && root > (guess - 1) as f64 && root <= guess as f64 {
                    if guess - 1 == lo || !self.retake_slope_in_doubt(stage, guess, rate, root - (guess - 1) as f64) {
                        break;
                    }
                    // The nanosecond before, taken aside (the state and the stepper's account
                    // stay this retake's): this stage's ends the search, else it goes on below.
                    let mut before = self.backup.clone();
                    let excitation = self.excitation_at(start_ns + guess - 1);
                    self.stepper.step_aside(&mut before, stage, seconds(guess - 1), &excitation);
                    let f_before = self.stepper.measure(&before, stage, &excitation).0[Probe::Gap as usize] - threshold;
                    if contact::stage(f_before + threshold) == stage {
                        break;
                    }
                    (hi, f_hi, at_hi) = (guess - 1, f_before, None);
                }
            } else {
                lo = guess;
                f_lo = f;
                at_hi = None;
            }
            bisect = !bisect && hi - lo > 2;
            if newton && rate != 0.0 {
                // The root by Newton from this retake, ns; test the first whole ns past it, or
                // the one before `hi` when that is it. (The gap's series from here would do no
                // better: out of contact Newton's next retake is the located one already, in
                // contact a retake's own error moves the root (measured on the sea example: 352
                // retakes against 336).)
                let root = guess as f64 - f / (rate * 1e-9);
                if root.is_finite() && root > lo as f64 && root < hi as f64 {
                    let past = (root.ceil() as u64).clamp(lo + 1, hi);
                    next = Some(if past >= hi { hi - 1 } else { past });
                }
            }
        }
        let (probes, energies) = match at_hi {
            Some(measured) => measured,
            None => retake(self, hi).2,
        };
        (hi, probes, energies)
    }

    /// For the exact advance: the first whole nanosecond past where the cubic through the gap's
    /// values and rates at the step's ends crosses `threshold` (`None` for other steppers or when
    /// the cubic does not cross).
    fn cubic_root_ns(&self, stage: Stage, step_ns: u64, gap_end: f64, threshold: f64) -> Option<u64> {
        if !self.stepper.adapts_steps() || step_ns < 4 {
            return None;
        }
        let start_ns = self.state.result.time_ns;
        let (e0, e1) = (self.excitation_at(start_ns), self.excitation_at(start_ns + step_ns));
        let gap = Probe::Gap as usize;
        let h = seconds(step_ns);
        let d0 = self.stepper.rates(&self.backup, stage, &e0)[gap] * h;
        let d1 = self.stepper.rates(&self.state.kinematics, stage, &e1)[gap] * h;
        let (p0, p1) = (self.state.gap - threshold, gap_end - threshold);
        let (c2, c3) = crate::solver::step_extrema::cubic_coefficients(p0, p1, d0, d1);
        let value = |x: f64| p0 + x * (d0 + x * (c2 + x * c3));
        // The first crossing: scan the cubic finely, then bisect the first bracket.
        let n = 64;
        let (mut a, mut b) = (0.0, 0.0);
        let mut found = false;
        for k in 1..=n {
            let x = k as f64 / n as f64;
            if (value(x) > 0.0) != (p0 > 0.0) {
                (a, b) = ((k - 1) as f64 / n as f64, x);
                found = true;
                break;
            }
        }
        if !found {
            return None;
        }
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if (value(m) > 0.0) == (p0 > 0.0) {
                a = m;
            } else {
                b = m;
            }
        }
        Some(((b * step_ns as f64).ceil() as u64).clamp(1, step_ns - 1))
    }

    /// For the exact advance of modal coordinates under the linear bar (out of contact under any
    /// law): the gap's Taylor series of order [`GAP_SERIES_ORDER`] about a state `at` of the step
    /// (its kinematics and excitation, its time from the step's start, ns, its gap less the
    /// threshold and its rate), solved by Newton's method from `guess` (ns from the step's start):
    /// the first whole nanosecond past its root inside the bracket `(lo, hi)`, the one before `hi`
    /// when that is it. Within a step the loads are constant (the supports' accelerations are, the
    /// gap offset's being `offset_acceleration`), so each kept mode obeys q'' = f - c q' - omega^2
    /// q - k b B (B = b^T q + s + d the bar's stretch, in contact only), whose derivatives follow
    /// from the state's q, q' and q'' ([`Self::gap_derivatives`]); the gap's own value and rate are
    /// the measured ones, its higher derivatives the kept modes' scaled by the measured rate's
    /// ratio to the kept modes' (the static correction's share of the contact load moves with the
    /// kept modes' gap). Out of contact that is the exact solution, whose retakes sample it; in
    /// contact a retake's cubic force departs from it by the step's force error (a few
    /// nanoseconds on long steps). `None` where the series has not converged at its root (its last
    /// term moves the gap by more than a twentieth of a nanosecond's worth of its rate: a mode of
    /// omega tau >~ 10 away), Newton does not settle or leaves the bracket.
    #[inline(never)]
    fn series_root_ns(
        &self,
        stage: Stage,
        (kinematics, excitation, origin_ns, value, rate): (&Kinematics, &Excitation, u64, f64, f64),
        offset_acceleration: f64,
        guess: f64,
        (lo, hi): (u64, u64),
    ) -> Option<u64> {
        let law_contact = self.modal.law.is_some() && stage.is_contact();
        if !(self.stepper.adapts_steps() && self.stepper.modal_coordinates()) || law_contact || hi - lo < 2 {
            return None;
        }
        let mut series = self.gap_derivatives(kinematics, stage, excitation, offset_acceleration);
        // Taylor coefficients in nanoseconds: g^(k) / k! 1e-9^k, the measured value and rate first.
        let scale = if series[1] != 0.0 && (rate / series[1]).is_finite() { rate / series[1] } else { 1.0 };
        series[0] = value;
        series[1] = rate;
        let mut factor = 1.0;
        for (k, term) in series.iter_mut().enumerate() {
            if k >= 2 {
                *term *= scale;
            }
            *term *= factor;
            factor *= 1e-9 / (k + 1) as f64;
        }
        let polynomial = |x: f64| {
            let (mut v, mut d) = (0.0, 0.0);
            for &c in series.iter().rev() {
                d = d * x + v;
                v = v * x + c;
            }
            (v, d)
        };
        let origin = origin_ns as f64;
        let (low, high) = (lo as f64 - origin, hi as f64 - origin);
        let mut x = guess - origin;
        let mut settled = false;
        for _ in 0..16 {
            let (v, d) = polynomial(x);
            let moved = (x - v / d).clamp(low, high);
            if !moved.is_finite() {
                return None;
            }
            let change = (moved - x).abs();
            x = moved;
            if change < 1e-3 {
                settled = true;
                break;
            }
        }
        let (_, d) = polynomial(x);
        let last = (0..GAP_SERIES_ORDER).fold(series[GAP_SERIES_ORDER], |term, _| term * x);
        let root = origin + x;
        if !settled || d == 0.0 || last.abs() > 0.05 * d.abs() || root <= lo as f64 || root >= hi as f64 {
            return None;
        }
        let past = (root.ceil() as u64).clamp(lo + 1, hi);
        Some(if past >= hi { hi - 1 } else { past })
    }

    /// The kept modes' gap b^T q + d (probe row b, the supports' offset d) and its derivatives
    /// 0..=[`GAP_SERIES_ORDER`] at `kinematics` in `stage` under constant loads, the offset moving
    /// at `offset_acceleration`: from each mode's q, q' and q'', q^(k+2) = -c q^(k+1) - omega^2
    /// q^(k) (- k b B^(k) in contact, B = b^T q + s + d the bar's stretch, the static correction's
    /// shift s constant) for k >= 1. One pass over the modes an order.
    #[inline(never)]
    fn gap_derivatives(
        &self,
        kinematics: &Kinematics,
        stage: Stage,
        excitation: &Excitation,
        offset_acceleration: f64,
    ) -> [f64; GAP_SERIES_ORDER + 1] {
        let m = &self.modal;
        let n = kinematics.displacement.len().min(m.probes.ncols()).min(m.omega2.len());
        let (omega2, damping, b) = (&m.omega2.as_slice()[..n], &m.damping.as_slice()[..n], &m.contact.as_slice()[..n]);
        let (velocity, acceleration) = (&kinematics.velocity.as_slice()[..n], &kinematics.acceleration.as_slice()[..n]);
        // The probes' matrix is column-major: one coordinate's probes side by side.
        let (probes, stride, at) = (m.probes.as_slice(), m.probes.nrows(), Probe::Gap as usize);
        let mut series = [0.0; GAP_SERIES_ORDER + 1];
        // The value is the measured one (series[0] stays 0).
        if !stage.is_contact() {
            // The modes apart: each mode's derivatives in turn, added to the gap's.
            for i in 0..n {
                let (row, c, w2) = (probes[i * stride + at], damping[i], omega2[i]);
                let (mut older, mut newer) = (velocity[i], acceleration[i]);
                series[1] += row * older;
                series[2] += row * newer;
                for term in series.iter_mut().skip(3) {
                    let next = -c * newer - w2 * older;
                    *term += row * next;
                    (older, newer) = (newer, next);
                }
            }
            series[1] += excitation.gap_offset_rate;
            series[2] += offset_acceleration;
            return series;
        }
        // In contact the bar's force couples the modes: one pass over them an order.
        let bar = m.bar_stiffness;
        let gap_row: Vec<f64> = (0..n).map(|i| probes[i * stride + at]).collect();
        let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).fold(0.0, |sum, (a, b)| sum + a * b);
        // Two consecutive derivatives of every mode, the older overwritten by the next.
        let (mut older, mut newer) = (velocity.to_vec(), acceleration.to_vec());
        series[1] = dot(&gap_row, &older) + excitation.gap_offset_rate;
        series[2] = dot(&gap_row, &newer) + offset_acceleration;
        // The bar's stretch B^(k) and B^(k+1).
        let mut stretch = dot(b, &older) + excitation.gap_offset_rate;
        let mut stretch_next = dot(b, &newer) + offset_acceleration;
        for term in series.iter_mut().skip(3) {
            let force = bar * stretch;
            let (mut gap, mut next_stretch) = (0.0, 0.0);
            for i in 0..n {
                let next = -damping[i] * newer[i] - omega2[i] * older[i] - force * b[i];
                older[i] = next;
                gap += gap_row[i] * next;
                next_stretch += b[i] * next;
            }
            std::mem::swap(&mut older, &mut newer);
            *term = gap;
            (stretch, stretch_next) = (stretch_next, next_stretch);
        }
        series
    }
    /// Whether a contact retake of `guess_ns` that changed the stage, its gap rate `rate` (m/s)
    /// putting the crossing `fraction` of a nanosecond past the nanosecond before, may have the
    /// nanosecond before changed too: a retake's end departs from the exact solution by about its
    /// force error over the bar's stiffness, an error of order dt^4 (see `ModalStepper`'s contact
    /// step), so the retakes' gap moves with their length at the rate give or take 4 e / (dt
    /// rate). Measured on 100 events of the sea example (12 001 separations, the nanosecond before
    /// each Newton break retaken): the 49 whose nanosecond before had changed too (0.4 %) all had
    /// a fraction below 20 e / (dt rate) (five times that bound), as had 370 of all; out of contact
    /// none of 12 321 had (a retake there is the exact solution). False for a nonlinear law (its
    /// retakes take their secant slope) and out of contact.
    fn retake_slope_in_doubt(&self, stage: Stage, guess_ns: u64, rate: f64, fraction: f64) -> bool {
        if !stage.is_contact() || self.modal.law.is_some() {
            return false;
        }
        let Some(force_error) = self.stepper.force_ramp_error() else { return false };
        let bound = 4.0 * force_error / (self.modal.bar_stiffness * seconds(guess_ns) * rate.abs());
        // A bound that is no number (no rate) leaves the doubt.
        bound.is_nan() || fraction <= 5.0 * bound
    }

    /// Steps until `target_ns`, landing on it exactly (the last step is shortened: the stop time
    /// breaks the step grid), sending every step to `recorder`. With `stop_at_contact_change`,
    /// returns early at a contact change: after the step at whose end Eq. (6) changes (the located
    /// change), before the new stage's first step.
    pub fn advance_to(
        &mut self,
        target_ns: u64,
        recorder: &mut dyn Recorder,
        stop_at_contact_change: bool,
    ) -> Result<Advance> {
        self.apply_input(recorder)?;
        let advance = self.land_at(target_ns, recorder, stop_at_contact_change)?;
        self.outputs_at_latest_step();
        self.publish_envelope();
        Ok(advance)
    }

    /// Ends the run at the stop time `target_ns`. The converged method does not break its step
    /// grid there: whole internal steps up to it are taken, and the stop point inside the next
    /// step is interpolated on that step's polynomial and recorded as the run's last record, so
    /// a peak (or any value) at a time does not depend on whether that time is the stop time.
    /// The paper method keeps its step-end values and shortens its last step ([`Self::advance_to`]).
    pub fn finish_at(
        &mut self,
        target_ns: u64,
        recorder: &mut dyn Recorder,
        stop_at_contact_change: bool,
    ) -> Result<Advance> {
        if !self.polynomial_peaks() {
            return self.advance_to(target_ns, recorder, stop_at_contact_change);
        }
        let advance = self.advance_outputs_to(target_ns, recorder, stop_at_contact_change)?;
        if advance == Advance::Reached && self.output.time_ns > self.state.result.time_ns {
            if self.samples_for(recorder) {
                // The dense output before the stop point, inside the step it breaks: that step
                // taken again (as the point was interpolated on it), then left untaken.
                let saved = (self.state.clone(), self.backup.clone(), self.step_end);
                // The sub-impacts live beside the state: the step left untaken leaves them too (as
                // `advance_outputs_to` does), or a logged run's last sub-impact would end past the
                // stop time while an unlogged one's does not.
                let saved_impacts = (self.sub_impacts.len(), self.sub_impacts.last().copied());
                let instants = self.output_peak_instants.clone();
                let peaks = (self.output.peaks, self.output_peak_times);
                let sent = self
                    .step(u64::MAX, false)
                    .and_then(|_| self.record_samples(recorder, &saved.0, self.output.time_ns, &instants, peaks));
                (self.state, self.backup, self.step_end) = saved;
                self.envelope_work.forget();
                self.sub_impacts.truncate(saved_impacts.0);
                if let (Some(last), Some(kept)) = (self.sub_impacts.last_mut(), saved_impacts.1) {
                    *last = kept;
                }
                sent?;
            }
            let record = self.stop_record();
            let kinematics = self.kinematics_at(self.output.time_ns)?;
            self.record(recorder, &record, &kinematics, true)?;
        }
        Ok(advance)
    }

    /// The outputs at a stop point inside the next internal step, as a log record: the step
    /// being taken, observed at the stop point.
    fn stop_record(&self) -> StepResult {
        let mut record = self.output;
        record.step = self.state.result.step + 1;
        record.step_size = seconds(record.time_ns - self.state.result.time_ns);
        record
    }

    /// The own coordinates at `at_ns` inside the next internal step (its cubic; the exact
    /// advance's own step to it, as [`Self::interpolate`] takes the outputs there), the state left
    /// as it was.
    fn kinematics_at(&mut self, at_ns: u64) -> Result<Kinematics> {
        if self.stepper.adapts_steps() {
            let stage = self.next_stage();
            let mut k = self.state.kinematics.clone();
            let tau = seconds(at_ns - self.state.result.time_ns);
            self.stepper.step(&mut k, stage, tau, &self.excitation_at(at_ns));
            return Ok(k);
        }
        let saved = (self.state.clone(), self.backup.clone());
        let stepped = self.step(u64::MAX, false);
        let kinematics = stepped.map(|_| {
            let (k0, k1) = (&self.backup, &self.state.kinematics);
            let dt = seconds(self.state.result.time_ns - saved.0.result.time_ns);
            let tau = seconds(at_ns - saved.0.result.time_ns);
            linear_acceleration_within(k0, k1, dt, tau)
        });
        (self.state, self.backup) = saved;
        self.envelope_work.forget();
        kinematics
    }

    /// Moves the outputs to the communication point `target_ns` without breaking the internal
    /// step grid: whole internal steps up to it are taken and recorded, and when the point falls
    /// inside the next step, the outputs there come from that step's own polynomial (the linear
    /// acceleration gives displacement and velocity at any instant of the step), while the step
    /// itself is taken by the next call. With constant inputs the internal steps, and so the
    /// log and the peaks, are those of a run without communication points.
    pub fn advance_outputs_to(
        &mut self,
        target_ns: u64,
        recorder: &mut dyn Recorder,
        stop_at_contact_change: bool,
    ) -> Result<Advance> {
        let advance = self.advance_outputs(target_ns, recorder, stop_at_contact_change);
        self.publish_envelope();
        advance
    }

    /// [`Self::advance_outputs_to`]'s steps.
    fn advance_outputs(
        &mut self,
        target_ns: u64,
        recorder: &mut dyn Recorder,
        stop_at_contact_change: bool,
    ) -> Result<Advance> {
        self.apply_input(recorder)?;
        let target_ns = target_ns.max(self.state.output_ns);
        while self.state.result.time_ns < target_ns {
            let stage = self.next_stage();
            let start_ns = self.state.result.time_ns;
            let full_step_fits = start_ns + self.next_step_ns(stage) <= target_ns;
            let saved = (!full_step_fits || self.samples_for(recorder)).then(|| self.state.clone());
            // The sub-impacts live beside the state: a step left untaken leaves them too.
            let saved_impacts = (self.sub_impacts.len(), self.sub_impacts.last().copied());
            let event = self.step(u64::MAX, false)?;
            let last = event.is_some() || self.state.result.time_ns >= target_ns;
            if let Some(saved) = saved {
                if self.state.result.time_ns > target_ns {
                    // The point falls inside this step: interpolate, and leave the step untaken.
                    (self.output, self.output_peak_times) = self.interpolate(&saved, target_ns, stage);
                    self.state = saved;
                    // The envelope's kept peaks may be the untaken step's: taken again from the
                    // restored state's running values.
                    self.envelope_work.forget();
                    self.sub_impacts.truncate(saved_impacts.0);
                    if let (Some(last), Some(kept)) = (self.sub_impacts.last_mut(), saved_impacts.1) {
                        *last = kept;
                    }
                    self.state.output_ns = target_ns;
                    return Ok(Advance::Reached);
                }
                let sampled = self.samples_for(recorder).then_some(&saved);
                self.record_step(recorder, sampled, last)?;
            } else {
                self.record(recorder, &self.state.result, &self.state.kinematics, last)?;
            }
            if let Some(e) = &event {
                recorder.contact_event(e)?;
                if stop_at_contact_change {
                    self.outputs_at_latest_step();
                    return Ok(Advance::ContactChanged);
                }
            }
        }
        self.outputs_at_latest_step();
        Ok(Advance::Reached)
    }

    /// The outputs are the latest internal step's, with its support reactions and tip velocities
    /// (left out inside a run whose recorder wants none: [`Self::settle_details`]).
    fn outputs_at_latest_step(&mut self) {
        let mut result = self.state.result;
        if self.outputs_details {
            let excitation = self.excitation_at(result.time_ns);
            self.set_support_and_tips(&mut result, &self.state.kinematics, &excitation);
        } else {
            self.skipped_details = Some(result);
        }
        self.state.result = result;
        self.state.output_ns = result.time_ns;
        self.output = result;
        self.output_peak_times = self.state.peak_times;
    }

    /// Takes internal steps until `target_ns`, the last one shortened to land on it.
    fn land_at(
        &mut self,
        target_ns: u64,
        recorder: &mut dyn Recorder,
        stop_at_contact_change: bool,
    ) -> Result<Advance> {
        while self.state.result.time_ns < target_ns {
            let before = self.samples_for(recorder).then(|| self.state.clone());
            let event = self.step(target_ns - self.state.result.time_ns, false)?;
            let last = event.is_some() || self.state.result.time_ns >= target_ns;
            self.record_step(recorder, before.as_ref(), last)?;
            if let Some(e) = &event {
                recorder.contact_event(e)?;
                if stop_at_contact_change {
                    return Ok(Advance::ContactChanged);
                }
            }
        }
        Ok(Advance::Reached)
    }

    /// An input change takes effect at its communication point as a true step: the internal
    /// step ends there (taken with the previous forces and motion), and the acceleration is
    /// recomputed for the new load, which holds over the following steps. A support motion that
    /// continues the current one (to round-off) is no change: the step grid stays unbroken.
    fn apply_input(&mut self, recorder: &mut dyn Recorder) -> Result<()> {
        // The supports' offset or the load may change at the point: measure the next start anew.
        self.step_end = None;
        let motion_changed = !continues(&self.motion_at(self.state.output_ns), &self.state.input_motion);
        if self.state.input_forces == self.state.forces && !motion_changed {
            return Ok(());
        }
        let at = self.state.output_ns;
        if self.state.result.time_ns < at {
            self.land_at(at, recorder, false)?;
        }
        let forces = self.state.input_forces;
        if motion_changed {
            self.state.motion = self.state.input_motion;
            self.state.motion_ns = at;
        }
        self.state.forces = forces;
        self.state.last_forces = forces;
        let stage = self.next_stage();
        let excitation = self.excitation_at(at);
        self.stepper.equilibrium_acceleration(&mut self.state.kinematics, stage, &excitation);
        let (probes, energies) = self.stepper.measure(&self.state.kinematics, stage, &excitation);
        // The gap moves with a jump of the supports' position (a master's inconsistent input).
        self.state.gap = probes[Probe::Gap as usize];
        self.state.inertial_potential = energies.inertial_potential;
        if self.polynomial_peaks() && self.next_stage() == stage && self.state.result.time_ns == at {
            // The next step's start as its peaks' cubic takes it (`step_extremes` would measure
            // the same state under the same excitation again: a sea's row every 5 ms).
            let rates = self.stepper.rates(&self.state.kinematics, stage, &excitation);
            let step = self.state.result.step;
            self.step_end = Some(StepEnd { time_ns: at, step, stage, probes, rates });
        }
        self.outputs_at_latest_step();
        Ok(())
    }

    /// The outputs at `at_ns` inside the step just taken from `start` (backup) to the current
    /// state: the method's cubic displacement and quadratic velocity over the step (the exact
    /// advance: its own advance to the point). Work and
    /// dissipation are booked up to the point as the step books them; the peaks stay those of
    /// the whole internal steps taken so far.
    fn interpolate(&mut self, before: &RunState, at_ns: u64, stage: Stage) -> (StepResult, Peaks) {
        let (mut result, _) = self.point_record(before, at_ns, stage, None);
        let start = before.result;
        result.step = start.step;
        let mut times = before.peak_times;
        self.output_peak_instants.clear();
        if self.polynomial_peaks() {
            // The running peaks up to the point: the largest |value| over the step's first part too,
            // so that a peak output is never below an output at a communication point.
            let end_ns = self.state.result.time_ns;
            let fraction = seconds(at_ns - start.time_ns) / seconds(end_ns - start.time_ns);
            let end_excitation = self.excitation_at(end_ns);
            let (end, _) = self.stepper.measure(&self.state.kinematics, stage, &end_excitation);
            let (mut extremes, _) = self.step_extremes(&start, (&end, &end_excitation), stage, fraction, None);
            // The exact advance's point is its own value, not the cubic's: a peak is never below
            // an output.
            let own = result.peak_magnitudes();
            let mut instants = std::mem::take(&mut self.output_peak_instants);
            self.exact_extremes(&start, (at_ns, own), stage, &mut extremes, &mut instants);
            self.output_peak_instants = instants;
            let at = seconds(at_ns);
            let peaks = result.peaks.as_mut_array();
            let when = times.as_mut_array();
            for k in 0..5 {
                for (value, time) in [extremes[k], (own[k], at)] {
                    if value > *peaks[k] {
                        // Never past the point by the cubic's round-off.
                        (*peaks[k], *when[k]) = (value, time.min(at));
                    }
                }
            }
        }
        (result, times)
    }

    /// The record of the state at `at_ns` inside the step just taken from `before` (whose
    /// kinematics are `self.backup`) to the current state, in `stage`: [`Self::point`]'s outputs
    /// with the support reactions and tip velocities, and the energy account with the work and
    /// the dissipation booked up to the point as the step books them; its peaks are `before`'s
    /// and its `step_size` the whole step's.
    fn point_record(
        &mut self,
        before: &RunState,
        at_ns: u64,
        stage: Stage,
        given: Option<Kinematics>,
    ) -> (StepResult, Kinematics) {
        let dt = seconds(self.state.result.time_ns - before.result.time_ns);
        let tau = seconds(at_ns - before.result.time_ns);
        let kinematics = given.unwrap_or_else(|| self.point_kinematics(before.result.time_ns, at_ns, stage));
        let mut result = self.point_outputs(&kinematics, at_ns, stage);
        let excitation = self.excitation_at(at_ns);
        let (probes, mut energies) = self.stepper.measure(&kinematics, stage, &excitation);
        let rate = self.gap_rate(&kinematics, stage, &excitation);
        energies.dissipation_rate += self.contact_dissipation_rate(probes[Probe::Gap as usize], rate, stage);
        self.set_support_and_tips(&mut result, &kinematics, &excitation);
        let dissipated = 0.5 * tau * (before.dissipation_rate + energies.dissipation_rate);
        let reached = (&result, &self.motion_at(at_ns));
        result.energy = self.energy_account(before, reached, stage, probes[Probe::Gap as usize], &energies, dissipated);
        result.step = before.result.step;
        result.step_size = dt;
        result.peaks = before.result.peaks;
        (result, kinematics)
    }

    /// Whether `recorder` gets the dense output inside each internal step (issue 41): it asks
    /// for a sample interval and the run is the converged method's, whose steps are long and
    /// whose peaks lie inside them (the paper method's log keeps its own step ends, one at least
    /// every sample interval: the recorder decimates them).
    fn samples_for(&self, recorder: &dyn Recorder) -> bool {
        recorder.sample_interval_ns() > 0 && self.polynomial_peaks()
    }

    /// Sends `recorder` the dense output inside the step just taken from `before` (issue 41):
    /// the state at every multiple of its sample interval and at every instant in `instants`
    /// (where a running peak was raised), in time order, before `until_ns`. Each sample's peaks
    /// are the run's up to its time: `before`'s, raised by `peaks` (the step's, with their times)
    /// where they were reached by then.
    fn record_samples(
        &mut self,
        recorder: &mut dyn Recorder,
        before: &RunState,
        until_ns: u64,
        instants: &[u64],
        (peaks, peak_times): (Peaks, Peaks),
    ) -> Result<()> {
        let interval = recorder.sample_interval_ns();
        let start_ns = before.result.time_ns;
        let stage = contact::stage(before.gap);
        let mut times: Vec<u64> = instants.iter().copied().filter(|&t| t > start_ns && t < until_ns).collect();
        let mut grid = (start_ns / interval + 1).saturating_mul(interval);
        while grid < until_ns {
            times.push(grid);
            grid = grid.saturating_add(interval);
        }
        times.sort_unstable();
        times.dedup();
        let (values, when) = (peaks.as_array(), peak_times.as_array());
        // Out of contact the grid's samples follow each other by exact steps of the interval
        // (whose coefficients the stepper keeps; the free stage's forcing is the step's own, so
        // they are the step's solution to round-off). In contact each sample, and everywhere each
        // peak's instant, is the exact advance from the step's start, as [`Self::exact_extremes`]
        // took the peak (its printed value, to the bit) and [`Self::interpolate`] the outputs at
        // a communication point (the FMU's outputs there, to the bit): the bar's force is the
        // cubic of the advance taken, and a chain of shorter advances would follow another.
        let chained = self.stepper.adapts_steps() && !stage.is_contact();
        let mut walker = (start_ns, self.backup.clone());
        for at_ns in times {
            let given = if chained && !instants.contains(&at_ns) {
                let excitation = self.excitation_at(at_ns);
                self.stepper.step_aside(&mut walker.1, stage, seconds(at_ns - walker.0), &excitation);
                walker.0 = at_ns;
                Some(walker.1.clone())
            } else {
                None
            };
            let (mut row, kinematics) = self.point_record(before, at_ns, stage, given);
            row.step = before.result.step + 1;
            row.step_size = seconds(at_ns - start_ns);
            let at = seconds(at_ns);
            let reached = row.peak_magnitudes();
            for (k, peak) in row.peaks.as_mut_array().into_iter().enumerate() {
                if when[k] > seconds(start_ns) && when[k] <= at {
                    *peak = peak.max(values[k]);
                }
                // Its own value too, as the outputs at a communication point take it.
                *peak = peak.max(reached[k]);
            }
            if let Some(feed) = self.feed.listened() {
                feed.set_loads(self.correction_loads(own(&kinematics), stage, &self.excitation_at(at_ns)));
            }
            // E_def,b as of this row: its own where its deflection is the largest so far (at the
            // step's peak instant the very state and sums the step took it from), else the step's
            // once its peak is passed, else the run's before.
            let deflection = row.peaks.lower_tip_deflection;
            let strain = if deflection > before.result.peaks.lower_tip_deflection && reached[0] >= deflection {
                self.stepper.measure(&kinematics, stage, &self.excitation_at(at_ns)).1.upper_strain
            } else if when[0] > seconds(start_ns) && when[0] <= at {
                self.state.upper_strain_at_peak
            } else {
                before.upper_strain_at_peak
            };
            recorder.deflection_peak_strain(strain)?;
            recorder.sample(&row, kinematics.displacement.as_slice())?;
        }
        Ok(())
    }

    /// Records the internal step just taken from `before` (when the recorder takes samples: see
    /// [`Self::samples_for`]): its dense output, then its end.
    fn record_step(&mut self, recorder: &mut dyn Recorder, before: Option<&RunState>, must: bool) -> Result<()> {
        if let Some(before) = before {
            let instants = std::mem::take(&mut self.peak_instants);
            let peaks = (self.state.result.peaks, self.state.peak_times);
            let sent = self.record_samples(recorder, before, self.state.result.time_ns, &instants, peaks);
            self.peak_instants = instants;
            sent?;
        }
        self.record(recorder, &self.state.result, &self.state.kinematics, must)
    }

    /// The energy account at `reached` (the supports' motion there `reached_motion`) after
    /// `before`'s latest step (a whole step's end, or a point inside the step), the damping having done `dissipated` J since (the exact advance's
    /// own, or the dissipation rate's trapezoid): the tip forces' work as a trapezoid over the
    /// deflection change, the bar's energy in contact, and
    /// the residual against the initial total. One function so that [`Self::step`] and the
    /// interpolated outputs book them the same way.
    ///
    /// Moving supports (issue 17) are booked in their own frame: the energies are those of the
    /// beams' motion relative to the supports, and the external work adds the supports' work
    /// on them: their inertia loads' (minus the change of the inertial potential, exact for the
    /// constant accelerations of a step) and the bar's through the supports' relative
    /// displacement (F_c dd, a trapezoid like the tip forces').
    fn energy_account(
        &self,
        before: &RunState,
        (reached, reached_motion): (&StepResult, &SupportMotion),
        stage: Stage,
        gap: f64,
        energies: &Energies,
        dissipated: f64,
    ) -> EnergyAccount {
        let start = &before.result;
        let (last, forces) = (before.last_forces, before.forces);
        let work = 0.5 * (last.upper + forces.upper) * (reached.upper_tip_deflection - start.upper_tip_deflection)
            + 0.5 * (last.lower + forces.lower) * (reached.lower_tip_deflection - start.lower_tip_deflection);
        let length = self.model.scenario.lower_contact_position();
        let offset_change = reached_motion.gap_offset(length) - self.motion_at(start.time_ns).gap_offset(length);
        let supports = -(energies.inertial_potential - before.inertial_potential)
            + 0.5 * (start.contact_force + reached.contact_force) * offset_change;
        let bar = match self.modal.law {
            _ if !stage.is_contact() => 0.0,
            Some(law) => law.energy(-gap),
            None => contact::bar_energy(self.model.bar_stiffness, gap),
        };
        let mut energy = EnergyAccount {
            kinetic: energies.kinetic,
            strain: energies.beam_strain + bar,
            gravity_potential: energies.gravity_potential,
            external_work: start.energy.external_work + work + supports,
            damping_dissipation: start.energy.damping_dissipation + dissipated,
            residual: 0.0,
        };
        energy.residual = energy.kinetic + energy.strain + energy.gravity_potential + energy.damping_dissipation
            - energy.external_work
            - self.state.initial_energy;
        energy
    }

    /// Sends the run's description and the initial state (step 0) to `recorder`.
    pub fn start_recording(&self, recorder: &mut dyn Recorder) -> Result<()> {
        let (lower_nodes, upper_nodes) = self.model.node_positions();
        // The stress stations and their feed (issue 30): a recorder that keeps them holds the feed.
        let probe = (!self.stations.is_empty()).then(|| StationProbe {
            layout: StationLayout::of(&self.model.stations, self.stations.stride),
            rows: std::sync::Arc::clone(&self.stations),
            feed: self.feed.share(),
        });
        recorder.start(&RunInfo {
            scenario: &self.model.scenario,
            lower_nodes: &lower_nodes,
            upper_nodes: &upper_nodes,
            nodal_shapes: &self.nodal_shapes,
            stations: probe.as_ref(),
        })?;
        drop(probe);
        self.record(recorder, &self.state.result, &self.state.kinematics, true)?;
        self.publish_envelope();
        Ok(())
    }

    /// Runs the scenario's whole duration into `recorder` (start, every step, finish).
    /// With a motion table in the scenario, each row inside the run takes effect at its time as
    /// an FMU's inputs do at a communication point (the same calls in the same order), so a file
    /// sampled at the communication points reproduces the FMU's run.
    ///
    /// The outputs at the rows (their support reactions and tip velocities) are computed only
    /// for a recorder that wants details: no one else reads them before the next step replaces
    /// them (a sea's row every 5 ms: 3 % of a campaign's work); those still standing when the run
    /// finishes are settled then, so the run ends in the same state to the bit.
    pub fn run(&mut self, recorder: &mut dyn Recorder) -> Result<Summary> {
        self.start_recording(recorder)?;
        let end_ns = self.model.scenario.duration_ns();
        let polynomial = self.polynomial_peaks();
        let changes = self.model.scenario.motion_changes(end_ns)?;
        self.outputs_details = recorder.wants_details();
        for (at_ns, motion) in changes {
            let advanced = if polynomial {
                self.advance_to_row(at_ns, &motion, recorder)
            } else {
                self.advance_to(at_ns, recorder, false)
            };
            if let Err(e) = advanced {
                self.outputs_details = true;
                self.settle_details();
                return Err(e);
            }
            self.set_support_motion(motion);
        }
        self.outputs_details = true;
        self.settle_details();
        self.finish_at(end_ns, recorder, false)?;
        recorder.finish()?;
        Ok(self.summary())
    }

    /// Sets the support reactions and tip velocities that [`Self::outputs_at_latest_step`] left
    /// out on the latest result and the outputs, if they still hold that result: the state
    /// and the kinematics are those it had then (only a step, which replaces the result, or an
    /// input applied, which measures the outputs again, change them), so they are the values it
    /// would have set, to the bit.
    fn settle_details(&mut self) {
        let Some(skipped) = self.skipped_details.take() else { return };
        if self.state.result != skipped {
            return;
        }
        let mut result = skipped;
        let excitation = self.excitation_at(result.time_ns);
        self.set_support_and_tips(&mut result, &self.state.kinematics, &excitation);
        self.state.result = result;
        if self.output == skipped {
            self.output = result;
        }
    }

    /// [`Self::advance_outputs_to`] a motion row's time `at_ns`, from which the supports move as
    /// `motion`. Where the row breaks the step grid (its motion does not continue the current
    /// one: [`Self::apply_input`] will end the internal step there), the last step lands on the
    /// row at once: the step across it that `advance_outputs_to` would take, interpolate and leave
    /// untaken is never taken (a row every 5 ms of a sea's record: a tenth of the run's steps and
    /// their interpolations, whose outputs the landing replaced). The same steps, but what a step
    /// reuses from the one before (its start's measurements, the exact coefficients' cache) is no
    /// longer what the untaken step left: the peaks found inside a step may move by round-off
    /// (measured on 100 events of `examples/vessel-sea.toml`: 97 the same to the bit, 3 with the
    /// bridge's contact stress peak 3e-10 to 2.5e-6 from the former, with its time and
    /// utilisation; every other column the same).
    ///
    /// A located contact change inside the landing step is searched from the landing's end, not
    /// the untaken step's: the same nanosecond, but for a gap that crosses twice inside a step.
    fn advance_to_row(&mut self, at_ns: u64, motion: &SupportMotion, recorder: &mut dyn Recorder) -> Result<Advance> {
        self.apply_input(recorder)?;
        if continues(&self.motion_at(at_ns), motion) || at_ns <= self.state.output_ns {
            return self.advance_outputs_to(at_ns, recorder, false);
        }
        let advance = self.land_at(at_ns, recorder, false)?;
        self.outputs_at_latest_step();
        self.publish_envelope();
        Ok(advance)
    }

    /// Sets the two external tip forces, N (up positive), from the outputs' time on: the next
    /// advance first ends the internal step there if the forces changed.
    pub fn set_tip_forces(&mut self, forces: TipForces) {
        self.state.input_forces = forces;
    }

    /// Sets the supports' motion from the outputs' time on (it moves with constant accelerations
    /// until the next change): the next advance first ends the internal step there unless it
    /// continues the current motion (to round-off).
    pub fn set_support_motion(&mut self, motion: SupportMotion) {
        self.state.input_motion = motion;
    }

    /// How the support motion set for the outputs' time disagrees with the motion since the last
    /// change (see [`SupportMotion::mismatch`]), or `None`.
    pub fn motion_mismatch(&self) -> Option<crate::model::support_motion::MotionMismatch> {
        let state = &self.state;
        let interval = seconds(state.output_ns.saturating_sub(state.motion_ns));
        if interval <= 0.0 {
            // Set again at the instant the current motion was given (at t = 0: after the initial
            // state was computed from it): any change is a jump.
            let (given, expected) = (state.input_motion.values(), state.motion.values());
            let k = (0..9).find(|&k| !continues_value(expected[k], given[k]))?;
            return Some(crate::model::support_motion::MotionMismatch {
                name: crate::model::support_motion::MOTION_NAMES[k],
                given: given[k],
                expected: expected[k],
                interval: 0.0,
            });
        }
        state.motion.mismatch(&state.input_motion, interval)
    }

    /// Results of the latest internal step.
    pub fn result(&self) -> &StepResult {
        &self.state.result
    }

    /// The outputs at the latest communication point (`advance_outputs_to`'s target): the latest
    /// internal step's results, or values interpolated inside the next internal step.
    pub fn output(&self) -> &StepResult {
        &self.output
    }

    /// Refuses a run of `duration_ns` that would need more than `max_steps` internal steps (at
    /// the smaller of the two time steps): an error naming the duration, the step and the count;
    /// else the count ([`Self::step_estimate`]).
    pub fn check_step_count(&self, duration_ns: u64, max_steps: u64) -> Result<u64> {
        let step_ns = self.plan.free_ns.min(self.plan.contact_ns).max(1);
        let steps = self.step_estimate(duration_ns);
        if steps > max_steps {
            return Err(Error::invalid(
                "duration",
                format!(
                    "at most {max_steps} steps of {:e} s (the smaller time step), i.e. <= {} s; this run needs {steps} \
                     steps ({}; raise the limit with --max-steps, or coarsen the mesh)",
                    seconds(step_ns),
                    seconds(step_ns.saturating_mul(max_steps)),
                    self.plan.reason(&self.model.scenario, &self.modal)
                ),
                seconds(duration_ns),
            ));
        }
        Ok(steps)
    }

    /// The most internal steps a run of `duration_ns` takes by its plan: the duration over the
    /// smaller of the two time steps (the exact advance's steps are the plan's or longer; located
    /// stage changes and communication points add a few).
    pub fn step_estimate(&self, duration_ns: u64) -> u64 {
        duration_ns.div_ceil(self.plan.free_ns.min(self.plan.contact_ns).max(1))
    }

    /// Limits the run to `max_steps` internal steps in all, checked before each step: a run whose
    /// steps shrink beyond what [`Self::check_step_count`] foresaw stops with
    /// [`Error::StepLimit`] instead of running on (default [`crate::model::scenario::MAX_STEPS`]).
    pub fn set_max_steps(&mut self, max_steps: u64) {
        self.max_steps = max_steps;
    }

    /// The resolved time steps of both stages.
    pub fn step_plan(&self) -> &StepPlan {
        &self.plan
    }

    /// The run's energy verdict so far: the largest residual as a fraction of the energy that
    /// flows in the run (the larger of m_u g h + |external work| and the largest strain energy),
    /// against the scenario's `energy_tolerance`; and fixed time steps above the energy-safe limit.
    ///
    /// A run that leaves the linear model's range anywhere along either beam is not trusted, with
    /// the reason ([`Self::model_range`]).
    pub fn quality(&self) -> Quality {
        self.quality_within(&self.model_range())
    }

    /// [`Self::quality`] with the model's range `range` ([`Self::model_range`]) already taken.
    fn quality_within(&self, range: &RangeCheck) -> Quality {
        let s = &self.model.scenario;
        let state = &self.state;
        let mut quality = Quality::assess(
            state.max_residual,
            s.impact_energy(),
            state.max_external_work,
            state.max_strain_energy,
            s.energy_tolerance,
            self.plan.advisories(s, &self.modal),
        );
        let reasons = range.reasons();
        if !reasons.is_empty() {
            quality.trusted = false;
            quality.reasons.extend(reasons);
        }
        quality
    }

    /// The model's range so far: every node's largest deflection and rotation, the arrestor's
    /// tip deflection within the steps (its peak), and each beam's largest strain from its stress
    /// envelope, against [`crate::solver::model_range::SMALL_DEFLECTION`],
    /// [`crate::solver::model_range::SMALL_ROTATION`] and [`crate::solver::model_range::ELASTIC_STRAIN`].
    pub fn model_range(&self) -> RangeCheck {
        self.model_range_of(&self.envelope())
    }

    /// [`Self::model_range`] with the run's stress envelope `envelope` ([`Self::envelope`]).
    fn model_range_of(&self, envelope: &crate::results::StressEnvelope) -> RangeCheck {
        let s = &self.model.scenario;
        let mut range = self.state.range;
        let (peaks, times) = self.last_peaks();
        let tip = peaks.lower_tip_deflection.abs();
        if tip > range.lower_deflection.value || tip.is_nan() {
            range.lower_deflection = crate::solver::model_range::RangePeak {
                value: tip,
                // The peak deflection is the contact point's (issue 45: the free end by default).
                position: Some(s.lower_contact_position()),
                time: times.lower_tip_deflection,
            };
        }
        let strain = |beam: &crate::results::BeamEnvelope, modulus: f64| -> Option<StrainPeak> {
            let bending = beam.bending.peak().map(|p| (p.value, p.position, p.time, "bending"));
            let shear = beam.shear.peak().map(|p| (3f64.sqrt() * p.value, p.position, p.time, "shear"));
            let worst = match (bending, shear) {
                (Some(b), Some(t)) => Some(if t.0 > b.0 { t } else { b }),
                (b, t) => b.or(t),
            }?;
            Some(StrainPeak {
                value: worst.0 / modulus,
                stress: worst.0,
                position: worst.1,
                time: worst.2,
                shear: worst.3 == "shear",
            })
        };
        RangeCheck {
            range,
            lower_strain: strain(&envelope.lower, s.lower.elastic_modulus),
            upper_strain: strain(&envelope.upper, s.upper.elastic_modulus),
            lengths: [s.lower.length, s.upper.length],
        }
    }

    /// The run state, for saving (FMU state, rollback).
    pub fn state(&self) -> &RunState {
        &self.state
    }

    /// Restores a state saved from a simulation of the same scenario, after
    /// [`RunState::validate`]; a refused state leaves the simulation as it was.
    pub fn restore(&mut self, state: RunState) -> Result<()> {
        state.validate(self.modal.dofs(), self.longest_step_ns())?;
        // The envelope's held step end belongs to the run before, and so do the turning points.
        self.envelope_work.forget();
        self.turning_points = None;
        // The stress envelope: one value per station of this model, each a finite |stress|
        // reached at a time within the run.
        let stations = self.model.stations.len();
        for (field, values) in [("envelope", &state.envelope), ("envelope_times", &state.envelope_times)] {
            if values.len() != stations {
                return Err(Error::StateInvalid {
                    field: field.to_string(),
                    detail: format!("has {} values, this model has {stations} stress stations", values.len()),
                });
            }
            if let Some(k) = values.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
                return Err(Error::StateInvalid {
                    field: format!("{field}[{k}]"),
                    detail: format!("= {} is not a finite value >= 0", values[k]),
                });
            }
        }
        if let Some(k) = state.envelope_times.iter().position(|t| *t > state.result.time) {
            return Err(Error::StateInvalid {
                field: format!("envelope_times[{k}]"),
                detail: format!("= {} s is after the state's time {} s", state.envelope_times[k], state.result.time),
            });
        }
        let previous = std::mem::replace(&mut self.state, state);
        let previous_output = (self.output, self.output_peak_times);
        // The sub-impacts up to the restored state's windows (issue 45; the FMU reports none).
        let previous_impacts = self.sub_impacts.clone();
        self.sub_impacts.truncate(self.state.contact_windows.len());
        self.step_end = None;
        // The outputs at a communication point inside a step are recomputed from that step.
        let (at, forces, motion) = (self.state.output_ns, self.state.input_forces, self.state.input_motion);
        self.state.input_forces = self.state.forces;
        self.state.input_motion = self.motion_at(self.state.result.time_ns);
        self.state.output_ns = self.state.result.time_ns;
        self.output = self.state.result;
        self.output_peak_times = self.state.peak_times;
        if let Err(e) = self.advance_outputs_to(at, &mut NullRecorder, false) {
            // Leave the simulation as it was: a refused state changes nothing.
            self.state = previous;
            self.sub_impacts = previous_impacts;
            (self.output, self.output_peak_times) = previous_output;
            self.publish_envelope();
            return Err(e);
        }
        self.state.input_forces = forces;
        self.state.input_motion = motion;
        Ok(())
    }

    /// The scenario.
    pub fn scenario(&self) -> &Scenario {
        &self.model.scenario
    }

    /// The assembled model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Modes of the beams and of the coupled system.
    pub fn modal(&self) -> &ModalSystem {
        &self.modal
    }

    /// The energy approach of Section 3 for this scenario.
    pub fn energy_method(&self) -> &EnergyMethod {
        &self.energy_method
    }

    /// Modal coordinates to nodal deflections (arrestor nodes, then bridge nodes), m.
    pub fn nodal_shapes(&self) -> &DMatrix<f64> {
        &self.nodal_shapes
    }

    /// Natural frequencies, the first `count` of each column of Table 2, rad/s.
    pub fn mode_table(&self, count: usize) -> ModeTable {
        let first = |m: &crate::solver::Modes| m.omega.iter().take(count).copied().collect();
        ModeTable {
            lower: first(&self.modal.lower),
            upper: first(&self.modal.upper),
            coupled: first(&self.modal.coupled),
        }
    }

    /// The summary of the run so far.
    pub fn summary(&self) -> Summary {
        let s = &self.state;
        // A stop point inside the next internal step (see `finish_at`) is the run's last record.
        let last = if self.output.time_ns > s.result.time_ns { self.stop_record() } else { s.result };
        // The envelope and the range once, for the summary and its quality.
        let envelope = self.envelope();
        let model_range = self.model_range_of(&envelope);
        Summary {
            steps: last.step,
            time: last.time,
            peaks: last.peaks,
            peak_times: self.last_peaks().1,
            upper_strain_at_peak_deflection: s.upper_strain_at_peak,
            contact_windows: self.windows_to(&last),
            final_energy_residual: last.energy.residual,
            // The last record's too: a stop point's, which no step's end booked.
            max_energy_residual: s.max_residual.max(last.energy.residual.abs()),
            energy_method: self.energy_method,
            modes: self.mode_table(5),
            quality: self.quality_within(&model_range),
            first_contact_peaks: s.first_contact.peaks,
            first_contact_end: s.first_contact.end(),
            time_steps: TimeSteps { free: seconds(self.plan.free_ns), contact: seconds(self.plan.contact_ns) },
            impact: self.impact,
            envelope,
            model_range,
            sub_impacts: self.sub_impacts.clone(),
        }
    }

    /// The contact windows up to the run's last record `last`: one still open there (a stop point
    /// inside a step taken in contact) ends at it, not at the last step's end before it.
    fn windows_to(&self, last: &StepResult) -> Vec<ContactWindow> {
        let mut windows = self.state.contact_windows.clone();
        if let (true, Some(w)) = (last.contact, windows.last_mut()) {
            w.end = w.end.max(last.time);
        }
        windows
    }

    /// Keeps no energy account from here on: the modal stepper's measurements leave the energy
    /// terms 0, so the run's energies, residual and energy quality say nothing; its states,
    /// probes, peaks and envelope are the same to the bit. For runs whose peaks alone are read
    /// (an answer's check rungs and twin): the energies are about a seventh of a step's work.
    pub fn without_energy_account(&mut self) {
        self.stepper.keep_energies(false);
    }

    /// Follows no model range from here on (issue 40's every node's deflection and rotation): the
    /// run's [`Summary::model_range`] and its range reasons then hold the initial state's range,
    /// the envelope's strains and the tip deflection's peak; its states, peaks and envelope are
    /// the same to the bit. For runs whose peaks alone are read (an answer's check rungs and twin: the answer's
    /// range is the printed run's): a thirtieth of a step's work.
    pub fn without_model_range(&mut self) {
        self.follows_range = false;
    }

    /// Every station's stress, Pa, at the modal coordinates `q` of a full basis (the paper
    /// method's: no static correction), into `out` (one per station, in the order of
    /// [`crate::model::stations::Stations::all`]): the envelope's own product, to the bit. For
    /// tests that rebuild the stations' histories from a recorder's coordinates (issue 44).
    pub fn station_stresses(&self, q: &[f64], out: &mut [f64]) {
        self.stations.stresses(q, None, out);
    }

    /// Takes no stress envelope from here on (its stations' values stay as they are): the
    /// bench's side-by-side measure of what the envelope costs per step.
    pub fn without_envelope(&mut self) {
        self.stations = std::sync::Arc::default();
        self.turning_points = None;
    }

    /// The running peaks and their times at the run's last record: a stop point inside the next
    /// internal step (see `finish_at`), else the latest internal step.
    fn last_peaks(&self) -> (Peaks, Peaks) {
        if self.output.time_ns > self.state.result.time_ns {
            (self.output.peaks, self.output_peak_times)
        } else {
            (self.state.result.peaks, self.state.peak_times)
        }
    }

    /// The stress envelope so far (issue 30).
    pub fn envelope(&self) -> crate::results::StressEnvelope {
        use crate::model::stations::Station;
        use crate::results::{BeamEnvelope, StationEnvelope};
        let st = &self.model.stations;
        let (mut max, mut times) = (self.state.envelope.clone(), self.state.envelope_times.clone());
        self.paper_points_stand(&mut max, &mut times);
        let mut offset = 0;
        let mut take = |stations: &[Station]| {
            let range = offset..offset + stations.len();
            offset += stations.len();
            StationEnvelope {
                positions: stations.iter().map(|s| s.x).collect(),
                max: max.get(range.clone()).map_or_else(Vec::new, <[f64]>::to_vec),
                times: times.get(range).map_or_else(Vec::new, <[f64]>::to_vec),
                allowable: stations.iter().map(|s| s.allowable).collect(),
            }
        };
        let lower = BeamEnvelope { bending: take(&st.lower.bending), shear: take(&st.lower.shear) };
        let upper = BeamEnvelope { bending: take(&st.upper.bending), shear: take(&st.upper.shear) };
        crate::results::StressEnvelope { lower, upper, sampled_every: self.stations.stride }
    }

    /// Sets the paper's three points in the envelope's flat maxima `max` (Pa) and their `times`
    /// (s), in the stations' order: they are stations too, the same functionals; their peaks,
    /// resolved within the steps by the probes' cubic (up to the outputs' point), raise them; the
    /// exact advance's peaks are its solution's own values where the cubic found them (issue 41,
    /// [`Self::exact_extremes`]), which the stations' cubic may overshoot: they stand there.
    fn paper_points_stand(&self, max: &mut [f64], times: &mut [f64]) {
        let st = &self.model.stations;
        let (peaks, peak_times) = self.last_peaks();
        let exact = self.stepper.adapts_steps();
        let mut raise = |k: usize, value: f64, time: f64| {
            if k < max.len() && k < times.len() && (value > max[k] || exact) {
                (max[k], times[k]) = (value, time);
            }
        };
        let (lower_bending, lower_shear) = (st.lower.bending.len(), st.lower.shear.len());
        if lower_bending > 0 {
            raise(0, peaks.lower_clamp_bending_stress, peak_times.lower_clamp_bending_stress);
        }
        if lower_shear > 0 {
            raise(lower_bending, peaks.lower_clamp_shear_stress, peak_times.lower_clamp_shear_stress);
        }
        let contact = self.model.contact_node;
        let at_contact: Vec<usize> =
            st.upper.bending.iter().enumerate().filter(|(_, s)| s.node == contact).map(|(k, _)| k).collect();
        if let [k] = at_contact[..] {
            let k = lower_bending + lower_shear + k;
            raise(k, peaks.upper_contact_bending_stress, peak_times.upper_contact_bending_stress);
        }
    }

    /// Hands the envelope so far, as the flat maxima and times of [`Self::envelope`], to the
    /// stations' feed for the row about to be recorded (issue 41: a log cut short rebuilds the
    /// envelope from its last row's).
    fn publish_maxima(&self, feed: &crate::record::stations::StationFeed) {
        feed.set_maxima_with(&self.state.envelope, &self.state.envelope_times, |max, times| {
            self.paper_points_stand(max, times)
        });
    }

    /// The impact's angular velocity and closing speed at t = 0.
    pub fn impact(&self) -> Impact {
        self.impact
    }
}

/// How the envelope took a step: not at all (a stride's skipped step), by its end, or by the
/// cubic over it (its length, s).
#[derive(Clone, Copy, Debug)]
enum Observed {
    Nothing,
    End,
    Cubic(f64),
}

/// True when `given` is `expected` to round-off (1e-12 of each value, or of 1): a master that sends
/// the continued motion changes nothing, whatever its communication step.
fn continues(expected: &SupportMotion, given: &SupportMotion) -> bool {
    expected.values().iter().zip(given.values()).all(|(e, g)| continues_value(*e, g))
}

/// One value of [`continues`].
fn continues_value(expected: f64, given: f64) -> bool {
    (expected - given).abs() <= 1e-12 * expected.abs().max(given.abs()).max(1.0)
}

/// The model's range rows (issue 40) for a stepper in modal coordinates (`modal`'s, whose
/// `shapes` they are) or in physical ones (the dense oracle): the deflections without the rigid
/// modes' motion, the rotations with it.
fn range_rows(model: &Model, modal: &ModalSystem, shapes: &DMatrix<f64>, in_modes: bool) -> RangeRows {
    let rigid: Vec<usize> = (0..modal.dofs()).filter(|&j| modal.omega2[j] == 0.0).collect();
    if in_modes {
        let mut elastic = shapes.clone();
        for &j in &rigid {
            elastic.column_mut(j).fill(0.0);
        }
        return RangeRows::new(model, shapes, &elastic, modal.lower_dofs, &modal.correction.dofs);
    }
    // Physical coordinates: the elastic part is u less its M-projection on the rigid modes
    // (mass-normalised), (I - Phi_r Phi_r^T M) u.
    let n = model.dofs();
    let total = DMatrix::identity(n, n);
    let mass = model.mass();
    let mut elastic = total.clone();
    for &j in &rigid {
        let phi = shapes.column(j);
        let projection = phi * (phi.transpose() * &mass);
        elastic -= projection;
    }
    RangeRows::new(model, &total, &elastic, model.lower.dofs(), &[])
}

/// The state `tau` s into a linear-acceleration step of `dt` s from `k0` to `k1`: the
/// acceleration linear over the step (Eq. 11's assumption), so the displacement cubic and the
/// velocity quadratic.
/// The probe of each peak output, in the order of [`Peaks::as_array`] (the contact force's: the gap).
const PEAK_PROBES: [Probe; 5] =
    [Probe::LowerTipDeflection, Probe::ClampMoment, Probe::ClampShear, Probe::UpperContactMoment, Probe::Gap];

fn linear_acceleration_within(k0: &Kinematics, k1: &Kinematics, dt: f64, tau: f64) -> Kinematics {
    let jerk = (&k1.acceleration - &k0.acceleration) / dt;
    Kinematics {
        displacement: &k0.displacement
            + &k0.velocity * tau
            + &k0.acceleration * (0.5 * tau * tau)
            + &jerk * (tau * tau * tau / 6.0),
        velocity: &k0.velocity + &k0.acceleration * tau + &jerk * (0.5 * tau * tau),
        acceleration: &k0.acceleration + &jerk * tau,
    }
}

/// Rows: every node of the arrestor, then of the bridge; columns: global modal coordinates.
fn nodal_shapes(model: &Model, shapes: &DMatrix<f64>) -> DMatrix<f64> {
    let nodes: Vec<Option<usize>> = model
        .lower
        .mesh
        .nodes
        .iter()
        .map(|n| n.w)
        .chain(model.upper.mesh.nodes.iter().map(|n| n.w.map(|i| i + model.lower.dofs())))
        .collect();
    DMatrix::from_fn(nodes.len(), shapes.ncols(), |r, c| nodes[r].map_or(0.0, |i| shapes[(i, c)]))
}

/// The support motion as an error names it: "fixed", or each moving coordinate's values.
/// The displacements and velocities of `kinematics`, as slices.
fn own(kinematics: &Kinematics) -> (&[f64], &[f64]) {
    (kinematics.displacement.as_slice(), kinematics.velocity.as_slice())
}

fn describe_motion(motion: &SupportMotion) -> String {
    if motion.is_rest() {
        return "fixed".into();
    }
    let names = crate::model::support_motion::MOTION_NAMES;
    let moving: Vec<String> =
        names.iter().zip(motion.values()).filter(|(_, v)| *v != 0.0).map(|(n, v)| format!("{n} = {v:.6e}")).collect();
    moving.join(", ")
}

/// The order of the gap's Taylor series that guesses a located contact change
/// ([`Simulation::series_root_ns`]): measured on the sea example's 191 changes out of contact, the
/// nearer end's series' root was the located nanosecond for 69 % of them at order 4, 93 % at 6,
/// 95 % at 8 and 10 (in contact, 188 changes: 38 %, 59 %, 61 %, 61 %); each order costs one pass
/// over the modes.
const GAP_SERIES_ORDER: usize = 8;

#[cfg(test)]
mod tests {
    use super::*;

    /// The gap's Taylor series that guesses a located change ([`Simulation::gap_derivatives`],
    /// [`GAP_SERIES_ORDER`]) is the exact advance's own solution out of contact: from a state of
    /// the default scenario's approach (truncated, 65 kept modes up to 4.4e4 rad/s, the gap
    /// closing at 0.19 m/s), the series at 1 and 10 us against the exact advance's closed-form
    /// steps of those lengths. Tolerance 1e-6 of a nanosecond's worth of the gap's rate (1.9e-16
    /// m), far below the half nanosecond the guess needs: the remainder at 10 us is at most
    /// (omega_max tau)^9 / 9! = 2e-9 of the highest mode's share, the exact step's round-off
    /// 1e-16 of the modes' amplitudes (measured 7e-18 m at 1 us, 7e-17 m at 10 us). At 100 us
    /// (omega_max tau = 4.4) the series misses by hundreds of nanoseconds' worth, and its last
    /// term says so: above the twentieth of a nanosecond's worth at which
    /// [`Simulation::series_root_ns`] leaves the guess to the cubic.
    #[test]
    fn the_gaps_series_follows_the_exact_advance_out_of_contact() {
        let mut sim = Simulation::new(&Scenario::default()).unwrap();
        for _ in 0..20 {
            sim.step(u64::MAX, false).unwrap();
        }
        assert_eq!(sim.next_stage(), Stage::Free);
        let (stage, t0) = (Stage::Free, sim.state.result.time_ns);
        let start = sim.state.kinematics.clone();
        let (e0, e1) = (sim.excitation_at(t0), sim.excitation_at(t0 + 1000));
        let offset_acceleration = (e1.gap_offset_rate - e0.gap_offset_rate) / seconds(1000);
        let gap = Probe::Gap as usize;
        let value = sim.stepper.measure(&start, stage, &e0).0[gap];
        let rate = sim.stepper.rates(&start, stage, &e0)[gap];
        let series = sim.gap_derivatives(&start, stage, &e0, offset_acceleration);
        assert!((series[1] - rate).abs() <= 1e-12 * rate.abs(), "{} vs {rate}", series[1]);
        for tau_ns in [1_000u64, 10_000, 100_000] {
            let tau = seconds(tau_ns);
            let (mut predicted, mut power) = (value + rate * tau, tau);
            for (k, derivative) in series.iter().enumerate().skip(2) {
                power *= tau / k as f64;
                predicted += derivative * power;
            }
            let last = (series[GAP_SERIES_ORDER] * power).abs();
            let mut k = start.clone();
            let excitation = sim.excitation_at(t0 + tau_ns);
            sim.stepper.step(&mut k, stage, tau, &excitation);
            let exact = sim.stepper.measure(&k, stage, &excitation).0[gap];
            let nanosecond = rate.abs() * 1e-9;
            if tau_ns <= 10_000 {
                assert!((predicted - exact).abs() <= 1e-6 * nanosecond, "{tau_ns} ns: {predicted} vs {exact} m");
            } else {
                assert!((predicted - exact).abs() > 0.5 * nanosecond, "{tau_ns} ns: {predicted} vs {exact} m");
                assert!(last > 0.05 * nanosecond, "{tau_ns} ns: last term {last} m");
            }
        }
    }

    /// Every located contact change is the first whole nanosecond after which Eq. (6) has
    /// changed: the step of one nanosecond less, retaken from the same start, ends in the stage
    /// the step started in. The default scenario to 0.1 s (its first contact, bounces and
    /// separations: 30 changes or more), each change checked.
    #[test]
    fn each_located_change_is_the_first_changed_nanosecond() {
        let scenario = Scenario { duration: 0.1, ..Scenario::default() };
        let mut sim = Simulation::new(&scenario).unwrap();
        let duration = scenario.duration_ns();
        let mut changes = 0;
        while sim.state.result.time_ns < duration {
            let (t0, stage) = (sim.state.result.time_ns, sim.next_stage());
            let event = sim.step(duration - t0, false).unwrap();
            if event.is_none() {
                continue;
            }
            changes += 1;
            let located = sim.state.result.time_ns - t0;
            assert_ne!(sim.next_stage(), stage);
            if located > 1 {
                let mut k = sim.backup.clone();
                let excitation = sim.excitation_at(t0 + located - 1);
                sim.stepper.step_aside(&mut k, stage, seconds(located - 1), &excitation);
                let gap = sim.stepper.measure(&k, stage, &excitation).0[Probe::Gap as usize];
                assert_eq!(contact::stage(gap), stage, "the change at {} ns: the nanosecond before", t0 + located);
            }
        }
        assert!(changes >= 30, "{changes} changes");
    }

    /// The stations' rates that the envelope's in-step cubic takes (the modes' velocities and the
    /// contact load's rate -k_eff (b^T v + d'), from the kept modes' gap) are the time derivative
    /// of the stations' values: against the one-sided second-order difference
    /// (-3 y(0) + 4 y(h) - y(2h)) / 2h over exact steps of h = 10 ns from a state in contact (the
    /// converged printed rung of the default scenario: truncated, so the static correction's
    /// contact load moves with the gap). Tolerance 1e-6 of the largest rate: the difference's
    /// error is of order (omega_max h)^2 / 3 = 6e-8 for the highest kept mode (4.4e4 rad/s;
    /// measured 1.3e-8), round-off 1e-16 of the stresses over 10 ns far below; the corrected gap's
    /// rate (the probes' own, 1.4 % below the modal gap's here) for the load is 1.2e-2 off.
    #[test]
    fn the_stations_rates_are_the_derivative_of_their_values() {
        let mut sim = Simulation::new(&Scenario::default()).unwrap();
        assert!(sim.modal.is_truncated());
        while sim.next_stage() != Stage::Contact {
            sim.step(u64::MAX, false).unwrap();
        }
        sim.step(u64::MAX, false).unwrap();
        assert_eq!(sim.next_stage(), Stage::Contact);
        let stage = Stage::Contact;
        let t0 = sim.state.result.time_ns;
        let h = 10u64;
        let start = sim.state.kinematics.clone();
        let values = |sim: &mut Simulation, steps: u64| {
            let mut k = start.clone();
            let at = t0 + steps * h;
            if steps > 0 {
                sim.stepper.step(&mut k, stage, seconds(steps * h), &sim.excitation_at(at));
            }
            let loads = sim.correction_loads(own(&k), stage, &sim.excitation_at(at));
            let mut out = vec![0.0; sim.stations.len()];
            sim.stations.stresses(k.displacement.as_slice(), loads.as_ref(), &mut out);
            out
        };
        let (y0, y1, y2) = (values(&mut sim, 0), values(&mut sim, 1), values(&mut sim, 2));
        let excitation = sim.excitation_at(t0);
        let load_rates = sim.correction_load_rates(&start, stage, &excitation);
        let mut rates = vec![0.0; sim.stations.len()];
        sim.stations.stresses(start.velocity.as_slice(), load_rates.as_ref(), &mut rates);
        let largest = rates.iter().fold(0.0f64, |m, r| m.max(r.abs()));
        assert!(largest > 0.0);
        let dt = seconds(h);
        for (k, rate) in rates.iter().enumerate() {
            let difference = (-3.0 * y0[k] + 4.0 * y1[k] - y2[k]) / (2.0 * dt);
            assert!((rate - difference).abs() <= 1e-6 * largest, "station {k}: {rate} vs {difference} Pa/s");
        }
    }

    /// A run that follows no model range (an answer's check rungs and twin) takes the same steps
    /// to the same peaks and envelope, to the bit, as one that does; its range stays the initial
    /// state's.
    /// The default scenario, shortened to 0.1 s (its first contact and the bounces after).
    #[test]
    fn a_run_without_its_model_range_has_the_same_peaks_and_envelope_to_the_bit() {
        let scenario = Scenario { duration: 0.1, ..Scenario::default() };
        let mut with = Simulation::new(&scenario).unwrap();
        let mut without = Simulation::new(&scenario).unwrap();
        without.without_model_range();
        let (a, b) = (with.run(&mut NullRecorder).unwrap(), without.run(&mut NullRecorder).unwrap());
        assert!(!a.contact_windows.is_empty());
        assert_eq!(a.steps, b.steps);
        let bits = |p: &Peaks| p.as_array().map(f64::to_bits);
        assert_eq!(bits(&a.peaks), bits(&b.peaks));
        assert_eq!(bits(&a.first_contact_peaks), bits(&b.first_contact_peaks));
        assert_eq!(a.envelope, b.envelope);
        // The range holds the initial state only (observed when the run was made), the full run's
        // more.
        let (full, initial) = (with.state.range, without.state.range);
        assert!(full.lower_deflection.value > initial.lower_deflection.value);
        assert!(full.lower_deflection.time > 0.0);
        let times =
            [initial.lower_deflection, initial.upper_deflection, initial.lower_rotation, initial.upper_rotation];
        assert!(times.iter().all(|p| p.time == 0.0), "{initial:?}");
    }

    /// The outputs' support reactions and tip velocities left out at an advance's end (a batch
    /// run's motion rows: `outputs_details` off) and settled afterwards are those computed at
    /// once, to the bit, in the state and in the outputs; left out, they differ (the clamp
    /// carries the beams' weight), so the test sees a missing settle.
    #[test]
    fn details_left_out_at_an_output_are_settled_to_the_bit() {
        let scenario = Scenario { duration: 0.02, ..Scenario::default() };
        let mut detailed = Simulation::new(&scenario).unwrap();
        detailed.advance_to(3_000_000, &mut NullRecorder, false).unwrap();
        let mut settled = detailed.clone();
        settled.outputs_details = false;
        for s in [&mut detailed, &mut settled] {
            s.advance_to(7_000_000, &mut NullRecorder, false).unwrap();
        }
        assert_ne!(detailed.state().result, settled.state().result);
        assert_ne!(detailed.state().result.lower_clamp_reaction_force, 0.0);
        settled.outputs_details = true;
        settled.settle_details();
        assert_eq!(detailed.state(), settled.state());
        assert_eq!(detailed.output(), settled.output());
        // Settled once: a second call changes nothing.
        settled.settle_details();
        assert_eq!(detailed.state(), settled.state());
    }

    /// A step left untaken at a communication point inside it leaves no peak of its own in the
    /// peaks-only envelope's kept peaks (which skip stations): after each point they are
    /// forgotten or those of the restored state's running values. The default scenario through
    /// its first contacts, a point every 37 us (most inside a step, many in contact).
    #[test]
    fn an_untaken_step_leaves_the_kept_peaks_to_the_restored_state() {
        let scenario = Scenario { duration: 0.1, ..Scenario::default() };
        let mut sim = Simulation::new(&scenario).unwrap();
        sim.set_envelope_scope(EnvelopeScope::Peaks);
        let groups = crate::solver::envelope::groups(&sim.model);
        let mut untaken = 0;
        for target in (1..).map(|k| k * 37_000).take_while(|&t| t <= scenario.duration_ns()) {
            sim.advance_outputs_to(target, &mut NullRecorder, false).unwrap();
            untaken += u32::from(sim.state.result.time_ns < target);
            let Some(peaks) = sim.envelope_work.peaks() else { continue };
            for (g, peak) in peaks.iter().enumerate() {
                let envelope = &sim.state.envelope;
                let largest = (0..envelope.len()).filter(|&k| groups[k] as usize == g).map(|k| envelope[k]);
                assert_eq!(peak.to_bits(), largest.fold(0.0, f64::max).to_bits(), "{target} ns, envelope {g}");
            }
        }
        assert!(untaken > 1000, "{untaken} steps left untaken");
    }
}
