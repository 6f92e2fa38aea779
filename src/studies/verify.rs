//! `beam-impact verify`: is each Table 1 peak, and the contact force F_c, converged in the time
//! step, the mesh and the modal cut-off?
//!
//! Four runs of one scenario: the **base** run at its own mesh and steps; the same mesh at
//! **half the steps** the base run used (both stages, whole nanoseconds); and **2x** and **4x** the
//! element counts of every beam segment with automatic (energy-safe) steps, which finer meshes
//! need since omega_max grows with the square of the element count, and with 2x and 4x the base
//! run's modal cut-off, as the converged method's ladder refines both together: a refined mesh at
//! the base cut-off keeps the same modes and so cannot see the truncation error (issue 29: the
//! truncated basis put late tau_a 13 % below the full basis' where the meshes agreed). A full
//! basis (the paper method, or a cut-off above every frequency) stays full. For each peak:
//! `step_change` = |v_half - v_base| / |v_base|, `mesh_change` = |v_4x - v_2x| / |v_4x|, and a
//! Richardson estimate of the converged value from the three meshes 1x (the base run), 2x, 4x
//! where their differences shrink at a sane observed order. A peak is converged when
//! the printed (base) value is within the tolerance of the half-step run and of the finest mesh.
//! An `"auto"` discretisation is resolved first (the rung a run prints, with its modal cut-off);
//! its 2x and 4x meshes have 2x and 4x that cut-off. The runs are independent and run in parallel.
//!
//! Refined meshes are capped at [`MAX_ELEMENTS`] per segment; a capped refinement is no longer
//! uniform (no Richardson estimate) and is reported in [`Verification::mesh_capped`].

use std::fmt::Write;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use serde::Serialize;

use crate::error::{Error, Result};
use crate::model::scenario::{ImpactorKind, MAX_ELEMENTS};
use crate::model::{Scenario, TimeStep};
use crate::record::{Recorder, RunInfo};
use crate::results::{seconds, ContactEvent, StepResult, Summary, TimeSteps};
use crate::Simulation;

pub use crate::answer::{richardson, Richardson, ORDER_RANGE};

/// Default largest relative change of a converged peak (1 %).
pub const DEFAULT_TOLERANCE: f64 = 0.01;

/// The Table 1 peaks and the contact force, named as in [`crate::results::Peaks`], in its order.
pub const PEAK_NAMES: [&str; 5] = crate::answer::PEAK_NAMES;

/// The four runs, named as in the JSON.
pub const RUN_NAMES: [&str; 4] = ["base", "half_step", "mesh_2x", "mesh_4x"];

/// The four runs as the table and the progress bars name them.
pub const RUN_LABELS: [&str; 4] = ["base", "half step", "2x elements", "4x elements"];

/// One value per run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Runs<T> {
    /// The scenario as given.
    pub base: T,
    /// The base mesh at half the base run's steps.
    pub half_step: T,
    /// Twice the elements of every segment (capped), automatic steps.
    pub mesh_2x: T,
    /// Four times the elements of every segment (capped), automatic steps.
    pub mesh_4x: T,
}

impl<T> Runs<T> {
    fn from_array([base, half_step, mesh_2x, mesh_4x]: [T; 4]) -> Self {
        Runs { base, half_step, mesh_2x, mesh_4x }
    }

    fn into_array(self) -> [T; 4] {
        [self.base, self.half_step, self.mesh_2x, self.mesh_4x]
    }

    /// The values in the order of [`RUN_NAMES`].
    pub fn as_array(&self) -> [&T; 4] {
        [&self.base, &self.half_step, &self.mesh_2x, &self.mesh_4x]
    }

    fn map<U>(&self, f: impl Fn(&T) -> U) -> Runs<U> {
        Runs::from_array(self.as_array().map(f))
    }
}

/// The element counts of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Mesh {
    /// Arrestor elements.
    pub lower: u32,
    /// Bridge elements from the hinge to the contact node.
    pub upper_to_contact: u32,
    /// Bridge elements from the contact node to the free end.
    pub upper_beyond_contact: u32,
}

impl Mesh {
    fn of(s: &Scenario) -> Mesh {
        Mesh {
            lower: s.lower.elements,
            upper_to_contact: s.upper.elements_to_contact,
            upper_beyond_contact: s.upper.elements_beyond_contact,
        }
    }

    /// Every meshed segment times `factor`, each capped at [`MAX_ELEMENTS`]: a rigid impactor's
    /// bridge counts mesh nothing and stay as they are, so that a refinement is finer only where
    /// the arrestor's count grows.
    fn refined(self, factor: u32, kind: ImpactorKind) -> Mesh {
        self.scaled(kind, |n| n.saturating_mul(factor).min(MAX_ELEMENTS))
    }

    /// The mesh refined by `factor` without the cap.
    fn uncapped(self, factor: u32, kind: ImpactorKind) -> Mesh {
        self.scaled(kind, |n| n.saturating_mul(factor))
    }

    /// Each meshed segment's count through `f` (the arrestor's alone for a rigid impactor).
    fn scaled(self, kind: ImpactorKind, f: impl Fn(u32) -> u32) -> Mesh {
        let beam = kind == ImpactorKind::Beam;
        let upper = |n: u32| if beam { f(n) } else { n };
        Mesh {
            lower: f(self.lower),
            upper_to_contact: upper(self.upper_to_contact),
            upper_beyond_contact: upper(self.upper_beyond_contact),
        }
    }

    fn applied_to(self, s: &Scenario) -> Scenario {
        let mut s = s.clone();
        s.lower.elements = self.lower;
        s.upper.elements_to_contact = self.upper_to_contact;
        s.upper.elements_beyond_contact = self.upper_beyond_contact;
        s
    }
}

impl Mesh {
    /// The counts as the table prints them (a rigid impactor's: the arrestor's alone).
    fn counts(&self, kind: ImpactorKind) -> String {
        crate::discretise::element_counts(kind, [self.lower, self.upper_to_contact, self.upper_beyond_contact])
    }
}

impl std::fmt::Display for Mesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} + {}/{}", self.lower, self.upper_to_contact, self.upper_beyond_contact)
    }
}

/// The verdict on one peak.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PeakVerdict {
    /// The base run's peak (m or Pa).
    pub value: f64,
    /// |v_half - v_base| / |v_base|.
    pub step_change: f64,
    /// |v_4x - v_2x| / |v_4x| (see [`Verification::mesh_change_between`] when the mesh is capped).
    pub mesh_change: f64,
    /// |v_base - v_finest| / |v_finest|, v_finest the finest mesh's value: how far the base mesh's
    /// value is from it (`mesh_change` only says whether the two finest meshes agree).
    pub base_mesh_change: f64,
    /// Richardson estimate of the converged value from the meshes 1x, 2x, 4x, where they allow one.
    pub estimate: Option<f64>,
    /// The observed order of that estimate.
    pub order: Option<f64>,
    /// Both changes within the tolerance.
    pub converged: bool,
}

/// The four Table 1 peaks and the contact force, in the order of [`PEAK_NAMES`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PeakVerdicts {
    /// Arrestor end deflection w_din,a.
    pub lower_tip_deflection: PeakVerdict,
    /// Clamp bending stress sigma_din,a.
    pub lower_clamp_bending_stress: PeakVerdict,
    /// Clamp shear stress tau_din,a.
    pub lower_clamp_shear_stress: PeakVerdict,
    /// Bridge bending stress at the contact node sigma_din,b (whole run).
    pub upper_contact_bending_stress: PeakVerdict,
    /// Contact force F_c (whole run): its peak is a short pulse the high modes shape, the first
    /// quantity a truncated basis or a coarse step gets wrong.
    pub contact_force: PeakVerdict,
}

impl PeakVerdicts {
    /// The verdicts in the order of [`PEAK_NAMES`].
    pub fn as_array(&self) -> [&PeakVerdict; 5] {
        [
            &self.lower_tip_deflection,
            &self.lower_clamp_bending_stress,
            &self.lower_clamp_shear_stress,
            &self.upper_contact_bending_stress,
            &self.contact_force,
        ]
    }
}

/// What `beam-impact verify` prints and writes as JSON.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Verification {
    /// One verdict per Table 1 peak and the contact force.
    pub peaks: PeakVerdicts,
    /// Largest relative change of a converged peak (a fraction).
    pub tolerance: f64,
    /// True when every peak is converged.
    pub converged: bool,
    /// The element counts of each run.
    pub meshes: Runs<Mesh>,
    /// The modal cut-off of each run, rad/s (null: the full basis): the base run's, and 2x and 4x
    /// it on the 2x and 4x meshes.
    pub modal_cutoffs: Runs<Option<f64>>,
    /// The time steps each run used, s.
    pub time_steps: Runs<TimeSteps>,
    /// Whether each run's energy balance is within its tolerance (`summary.quality.trusted`).
    pub trusted: Runs<bool>,
    /// Internal steps of each run.
    pub steps: Runs<u64>,
    /// The Table 1 peaks and the contact force of each run, in the order of [`PEAK_NAMES`] (m, Pa, N).
    pub run_peaks: Runs<[f64; 5]>,
    /// When each run reached those peaks, s after impact.
    pub run_peak_times: Runs<[f64; 5]>,
    /// Wall time of each run, s.
    pub wall_time_s: Runs<f64>,
    /// The two runs `mesh_change` compares: `["mesh_2x", "mesh_4x"]` unless capping made them equal.
    pub mesh_change_between: [&'static str; 2],
    /// Why and how the refined meshes were capped at [`MAX_ELEMENTS`] per segment (`None`: not capped).
    pub mesh_capped: Option<String>,
    /// The base scenario.
    pub scenario: Scenario,
}

/// The four runs, built and checked, ready to run.
pub struct Plan {
    scenario: Scenario,
    tolerance: f64,
    simulations: Runs<Simulation>,
    meshes: Runs<Mesh>,
    cutoffs: Runs<Option<f64>>,
    mesh_capped: Option<String>,
    mesh_change_between: [&'static str; 2],
}

impl Plan {
    /// Builds the four runs of `scenario`, to be judged against `tolerance` (a fraction, 0 < t < 1):
    /// every model, mode set and time step is checked now, so that a bad input fails before any
    /// run starts.
    pub fn new(scenario: &Scenario, tolerance: f64) -> Result<Plan> {
        check_tolerance(tolerance)?;
        // "auto" element counts and cut-off resolve to the rung a run prints, which is then refined.
        let scenario = &crate::discretise::printed(scenario)?;
        let base = Simulation::new(scenario)?;
        let plan = *base.step_plan();
        if plan.free_ns < 2 || plan.contact_ns < 2 {
            return Err(Error::Other(format!(
                "verify: the base run's steps ({} ns out of contact, {} ns in contact) cannot be halved in whole \
                 nanoseconds",
                plan.free_ns, plan.contact_ns
            )));
        }
        let half = Scenario {
            step_free: TimeStep::Fixed(seconds(plan.free_ns / 2)),
            step_contact: TimeStep::Fixed(seconds(plan.contact_ns / 2)),
            ..scenario.clone()
        };
        let mesh = Mesh::of(scenario);
        let Refinement { mesh_2x, mesh_4x, mesh_capped, mesh_change_between } =
            Refinement::of(mesh, scenario.upper.kind)?;
        let refined = |m: Mesh, factor: f64| Scenario {
            step_free: TimeStep::Auto,
            step_contact: TimeStep::Auto,
            modal_cutoff: scaled_cutoff(scenario.modal_cutoff, factor),
            ..m.applied_to(scenario)
        };
        // The base scenario's own errors read as `run` reports them; the derived runs' are named.
        let simulations = Runs {
            half_step: Simulation::new(&half).map_err(|e| in_run(1, e))?,
            mesh_2x: Simulation::new(&refined(mesh_2x, 2.0)).map_err(|e| in_run(2, e))?,
            mesh_4x: Simulation::new(&refined(mesh_4x, 4.0)).map_err(|e| in_run(3, e))?,
            base,
        };
        let cutoffs = simulations.map(|s| s.modal().cutoff);
        Ok(Plan {
            scenario: scenario.clone(),
            tolerance,
            simulations,
            meshes: Runs { base: mesh, half_step: mesh, mesh_2x, mesh_4x },
            cutoffs,
            mesh_capped,
            mesh_change_between,
        })
    }

    /// The element counts of the four runs.
    pub fn meshes(&self) -> &Runs<Mesh> {
        &self.meshes
    }

    /// Simulated time of each run, ns (the same for all four).
    pub fn duration_ns(&self) -> u64 {
        self.scenario.duration_ns()
    }

    /// Runs the four simulations on up to `threads` threads (at least one), the most expensive
    /// first, and judges the peaks. `progress(run, ns)` is called from the worker threads with the
    /// run's index in [`RUN_NAMES`] and its simulated time, every thousand steps and at its end.
    /// The first run to fail stops the others; its error names the run.
    pub fn run(self, threads: usize, progress: &(dyn Fn(usize, u64) + Sync)) -> Result<Verification> {
        let Plan { scenario, tolerance, simulations, meshes, cutoffs, mesh_capped, mesh_change_between } = self;
        // A stack popped from the end: the finest mesh first, the cheap base-mesh runs fill in.
        let queue: Mutex<Vec<(usize, Simulation)>> =
            Mutex::new(simulations.into_array().into_iter().enumerate().collect());
        let failed = AtomicBool::new(false);
        let first_error: Mutex<Option<Error>> = Mutex::new(None);
        let done: Mutex<Vec<Option<(Summary, Duration)>>> = Mutex::new(vec![None; RUN_NAMES.len()]);
        let duration_ns = scenario.duration_ns();
        let worker = || loop {
            let job = queue.lock().unwrap_or_else(|e| e.into_inner()).pop();
            let Some((index, mut simulation)) = job else { break };
            if failed.load(Ordering::Relaxed) {
                break;
            }
            let started = Instant::now();
            let mut watch = Watch { run: index, progress, failed: &failed };
            match simulation.run(&mut watch) {
                Ok(summary) => {
                    progress(index, duration_ns);
                    done.lock().unwrap_or_else(|e| e.into_inner())[index] = Some((summary, started.elapsed()));
                }
                Err(Error::Other(ref m)) if m == CANCELLED => break,
                Err(e) => {
                    failed.store(true, Ordering::Relaxed);
                    first_error.lock().unwrap_or_else(|e| e.into_inner()).get_or_insert(in_run(index, e));
                    break;
                }
            }
        };
        std::thread::scope(|scope| {
            let handles: Vec<_> = (0..threads.clamp(1, RUN_NAMES.len())).map(|_| scope.spawn(worker)).collect();
            for handle in handles {
                if let Err(panic) = handle.join() {
                    std::panic::resume_unwind(panic);
                }
            }
        });
        if let Some(e) = first_error.into_inner().unwrap_or_else(|e| e.into_inner()) {
            return Err(e);
        }
        let done = done.into_inner().unwrap_or_else(|e| e.into_inner());
        let mut runs = Vec::with_capacity(RUN_NAMES.len());
        for (name, run) in RUN_NAMES.iter().zip(done) {
            runs.push(run.ok_or_else(|| Error::Other(format!("verify: the {name} run did not finish")))?);
        }
        let runs = Runs::from_array(<[(Summary, Duration); 4]>::try_from(runs).expect("four runs"));
        let uniform = mesh_capped.is_none();
        Ok(judge(
            &runs.map(|(s, _)| s.clone()),
            runs.map(|(_, wall)| wall.as_secs_f64()),
            Judged { tolerance, meshes, cutoffs, uniform, mesh_change_between, mesh_capped, scenario },
        ))
    }
}

/// A resolved cut-off (rad/s; ignored by the paper method) times `factor`, within the largest a
/// scenario accepts (1e12 rad/s, above every mesh's frequencies: the full basis stays full).
fn scaled_cutoff(cutoff: f64, factor: f64) -> f64 {
    (cutoff * factor).min(1e12)
}

/// The two refined meshes of a base mesh, capped at [`MAX_ELEMENTS`] per segment.
#[derive(Clone, Debug, PartialEq)]
struct Refinement {
    mesh_2x: Mesh,
    mesh_4x: Mesh,
    /// The note when a segment was capped.
    mesh_capped: Option<String>,
    /// The runs `mesh_change` compares: 2x and 4x, or the base and 2x when capping made those equal.
    mesh_change_between: [&'static str; 2],
}

impl Refinement {
    /// An error when the base mesh is at the cap in every meshed segment (nothing finer to run);
    /// a rigid impactor's meshes are named by the arrestor's count alone.
    fn of(mesh: Mesh, kind: ImpactorKind) -> Result<Refinement> {
        let (mesh_2x, mesh_4x) = (mesh.refined(2, kind), mesh.refined(4, kind));
        let name = |m: &Mesh| m.counts(kind);
        if mesh_2x == mesh {
            return Err(Error::Other(format!(
                "verify: the mesh {} is already at the largest allowed, {MAX_ELEMENTS} elements per segment: no \
                 finer mesh to compare with",
                name(&mesh)
            )));
        }
        let mesh_change_between = if mesh_4x == mesh_2x { ["base", "mesh_2x"] } else { ["mesh_2x", "mesh_4x"] };
        let mesh_capped = (mesh_4x != mesh.uncapped(4, kind)).then(|| {
            format!(
                "refined meshes capped at {MAX_ELEMENTS} elements per segment: 2x is {}, 4x is {} (base {}); the \
                 refinement is not uniform, so no Richardson estimate{}",
                name(&mesh_2x),
                name(&mesh_4x),
                name(&mesh),
                if mesh_4x == mesh_2x { "; mesh_change compares the base and 2x meshes" } else { "" }
            )
        });
        Ok(Refinement { mesh_2x, mesh_4x, mesh_capped, mesh_change_between })
    }
}

/// An error of run `index` (in [`RUN_NAMES`]), named.
fn in_run(index: usize, e: Error) -> Error {
    Error::Other(format!("verify, {} run: {e}", RUN_LABELS[index]))
}

fn check_tolerance(tolerance: f64) -> Result<()> {
    if tolerance.is_finite() && tolerance > 0.0 && tolerance < 1.0 {
        Ok(())
    } else {
        Err(Error::invalid("--tolerance", "> 0 and < 1 (a fraction: 0.01 is 1 %)", tolerance))
    }
}

/// Everything [`judge`] needs besides the runs.
struct Judged {
    tolerance: f64,
    meshes: Runs<Mesh>,
    cutoffs: Runs<Option<f64>>,
    uniform: bool,
    mesh_change_between: [&'static str; 2],
    mesh_capped: Option<String>,
    scenario: Scenario,
}

/// The verdicts from the four runs' summaries.
fn judge(summaries: &Runs<Summary>, wall_time_s: Runs<f64>, j: Judged) -> Verification {
    let run_peaks = summaries.map(|s| s.peaks.as_array());
    let verdict = |k: usize| {
        let v = run_peaks.map(|p| p[k]);
        let step_change = crate::answer::relative(v.half_step, v.base);
        let mesh_change = if j.mesh_change_between[0] == "base" {
            crate::answer::relative(v.base, v.mesh_2x)
        } else {
            crate::answer::relative(v.mesh_2x, v.mesh_4x)
        };
        let extrapolated = if j.uniform { richardson(v.base, v.mesh_2x, v.mesh_4x) } else { None };
        PeakVerdict {
            value: v.base,
            step_change,
            mesh_change,
            base_mesh_change: crate::answer::relative(v.base, v.mesh_4x),
            estimate: extrapolated.map(|r| r.estimate),
            order: extrapolated.map(|r| r.order),
            // The verdict is about the value printed (the base run's): its change against the
            // finest mesh, not whether the two finer meshes agree with each other.
            converged: step_change <= j.tolerance && crate::answer::relative(v.base, v.mesh_4x) <= j.tolerance,
        }
    };
    let peaks = PeakVerdicts {
        lower_tip_deflection: verdict(0),
        lower_clamp_bending_stress: verdict(1),
        lower_clamp_shear_stress: verdict(2),
        upper_contact_bending_stress: verdict(3),
        contact_force: verdict(4),
    };
    Verification {
        converged: peaks.as_array().iter().all(|p| p.converged),
        peaks,
        tolerance: j.tolerance,
        meshes: j.meshes,
        modal_cutoffs: j.cutoffs,
        time_steps: summaries.map(|s| s.time_steps),
        trusted: summaries.map(|s| s.quality.trusted),
        steps: summaries.map(|s| s.steps),
        run_peaks,
        run_peak_times: summaries.map(|s| s.peak_times.as_array()),
        wall_time_s,
        mesh_change_between: j.mesh_change_between,
        mesh_capped: j.mesh_capped,
        scenario: j.scenario,
    }
}

/// The message of a run stopped because another one failed (never shown: the failure is).
const CANCELLED: &str = "verify: run cancelled";

/// Reports progress and stops the run when another one has failed; keeps nothing.
struct Watch<'a> {
    run: usize,
    progress: &'a (dyn Fn(usize, u64) + Sync),
    failed: &'a AtomicBool,
}

impl Recorder for Watch<'_> {
    fn start(&mut self, _: &RunInfo<'_>) -> Result<()> {
        Ok(())
    }
    fn wants_details(&self) -> bool {
        false
    }
    fn step(&mut self, result: &StepResult, _: &[f64]) -> Result<()> {
        if result.step.is_multiple_of(1000) {
            if self.failed.load(Ordering::Relaxed) {
                return Err(Error::Other(CANCELLED.into()));
            }
            (self.progress)(self.run, result.time_ns);
        }
        Ok(())
    }
    fn contact_event(&mut self, _: &ContactEvent) -> Result<()> {
        Ok(())
    }
    fn finish(&mut self) -> Result<()> {
        Ok(())
    }
}

/// Runs the verification of `scenario` with the default thread count (the machine's cores, at
/// most four) and no progress display.
pub fn verify(scenario: &Scenario, tolerance: f64) -> Result<Verification> {
    Plan::new(scenario, tolerance)?.run(default_threads(), &|_, _| {})
}

/// The machine's cores, at most one per run.
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get()).min(RUN_NAMES.len())
}

/// The verification as a text table.
pub fn table(v: &Verification) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Convergence of the Table 1 peaks and F_c ({} scenario): tolerance {} % on each change",
        if v.scenario.is_paper() { "paper" } else { "user" },
        v.tolerance * 100.0
    );
    let _ = writeln!(
        s,
        "  {:<12} {:>16} {:>14} {:>22} {:>9}  {:<11} {:>7}",
        "run", "elements", "cut-off [rad/s]", "steps free/contact [s]", "steps", "energy", "wall [s]"
    );
    for (k, label) in RUN_LABELS.iter().enumerate() {
        let steps = v.time_steps.as_array()[k];
        let _ = writeln!(
            s,
            "  {label:<12} {:>16} {:>14} {:>22} {:>9}  {:<11} {:>7.2}",
            v.meshes.as_array()[k].counts(v.scenario.upper.kind),
            v.modal_cutoffs.as_array()[k].map_or("full basis".to_string(), |c| format!("{c:.0}")),
            format!("{:e} / {:e}", steps.free, steps.contact),
            v.steps.as_array()[k],
            if *v.trusted.as_array()[k] { "trusted" } else { "NOT TRUSTED" },
            v.wall_time_s.as_array()[k]
        );
    }
    if let Some(note) = &v.mesh_capped {
        let _ = writeln!(s, "  note: {note}");
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "{:<34} {:>10} {:>12} {:>12} {:>10} {:>10} {:>6}  verdict",
        "peak", "value", "step_change", "mesh_change", "1x vs 4x", "estimate", "order"
    );
    let units = [("m", 1.0), ("MPa", 1e-6), ("MPa", 1e-6), ("MPa", 1e-6), ("kN", 1e-3)];
    for ((name, peak), (unit, scale)) in PEAK_NAMES.iter().zip(v.peaks.as_array()).zip(units) {
        let digits = if unit == "m" { 4 } else { 1 };
        let estimate = peak.estimate.map_or("-".to_string(), |e| format!("{:.digits$}", e * scale));
        let order = peak.order.map_or("-".to_string(), |p| format!("{p:.2}"));
        let _ = writeln!(
            s,
            "{:<34} {:>10} {:>11.3}% {:>11.3}% {:>9.3}% {:>10} {order:>6}  {}",
            format!("{name} [{unit}]"),
            format!("{:.digits$}", peak.value * scale),
            peak.step_change * 100.0,
            peak.mesh_change * 100.0,
            peak.base_mesh_change * 100.0,
            estimate,
            if peak.converged { "converged" } else { "NOT converged" }
        );
    }
    let label = |name: &'static str| RUN_NAMES.iter().position(|n| *n == name).map_or(name, |k| RUN_LABELS[k]);
    let _ = writeln!(
        s,
        "step_change: half step vs base; mesh_change: {} vs {}; 1x vs 4x: base vs the finest mesh;\n\
         estimate: Richardson from 1x, 2x, 4x at the observed order (- where the sequence allows none);\n\
         converged: the value printed (the base run's) is within the tolerance of the half-step run and of the\n\
         finest mesh (step_change and 1x vs 4x). An \"auto\" mesh is resolved first: 1x is the rung a run prints\n\
         (its elements and modal cut-off), 2x and 4x refine its elements and multiply its cut-off by 2 and 4\n\
         (a full basis stays full), so that 1x vs 4x sees the truncation error too",
        label(v.mesh_change_between[1]),
        label(v.mesh_change_between[0])
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// v_h = v + C h^p on h = 1, 1/2, 1/4 gives back p and v (up to round-off).
    #[test]
    fn richardson_recovers_order_and_limit_of_a_power_law() {
        for (v, c, p) in [(0.657, 0.05, 2.0), (4.7e8, -3e7, 1.0), (56.9e6, 9e6, 4.0), (1.0, 0.3, 0.75)] {
            let at = |h: f64| v + c * h.powf(p);
            let r = richardson(at(1.0), at(0.5), at(0.25)).expect("a power law allows an estimate");
            assert!((r.order - p).abs() < 1e-9, "order {} for p = {p}", r.order);
            assert!((r.estimate - v).abs() < 1e-9 * v.abs(), "estimate {} for v = {v}", r.estimate);
        }
    }

    /// Oscillating, non-monotone, stagnant or implausibly fast sequences give no estimate.
    #[test]
    fn richardson_refuses_sequences_without_an_asymptotic_order() {
        assert_eq!(richardson(1.0, 2.0, 1.5), None, "oscillating");
        assert_eq!(richardson(1.0, 1.2, 1.5), None, "diverging: differences grow (order < 0)");
        assert_eq!(richardson(1.0, 1.2, 1.19), None, "non-monotone");
        assert_eq!(richardson(1.0, 1.0, 1.0), None, "no differences");
        assert_eq!(richardson(1.0, 1.5, 1.5), None, "zero fine difference");
        assert_eq!(richardson(1.0, 1.5, 1.5 + 0.5 / 128.0), None, "order 7, above the range");
        assert_eq!(richardson(1.0, 1.5, 1.5 + 0.5 / 1.2), None, "order 0.26, below the range");
    }

    /// The paper mesh refines uniformly: 2x and 4x, compared with each other, no note.
    #[test]
    fn paper_mesh_refines_uniformly_without_a_note() {
        let r = Refinement::of(Mesh { lower: 7, upper_to_contact: 7, upper_beyond_contact: 7 }, ImpactorKind::Beam)
            .unwrap();
        assert_eq!(r.mesh_2x, Mesh { lower: 14, upper_to_contact: 14, upper_beyond_contact: 14 });
        assert_eq!(r.mesh_4x, Mesh { lower: 28, upper_to_contact: 28, upper_beyond_contact: 28 });
        assert_eq!((r.mesh_capped, r.mesh_change_between), (None, ["mesh_2x", "mesh_4x"]));
    }

    /// A refinement past the cap stops at MAX_ELEMENTS per segment and says so; when 2x and 4x
    /// come out equal, mesh_change falls back to base vs 2x; at the cap everywhere, an error.
    #[test]
    fn refinement_past_the_cap_is_capped_per_segment_and_noted() {
        let m = Mesh { lower: 7, upper_to_contact: 100, upper_beyond_contact: 90 };
        let r = Refinement::of(m, ImpactorKind::Beam).unwrap();
        assert_eq!(r.mesh_2x, Mesh { lower: 14, upper_to_contact: 200, upper_beyond_contact: 180 });
        assert_eq!(r.mesh_4x, Mesh { lower: 28, upper_to_contact: MAX_ELEMENTS, upper_beyond_contact: MAX_ELEMENTS });
        assert_eq!(r.mesh_change_between, ["mesh_2x", "mesh_4x"]);
        let note = r.mesh_capped.expect("capped");
        let cap = format!("capped at {MAX_ELEMENTS}");
        let mesh = format!("28 + {MAX_ELEMENTS}/{MAX_ELEMENTS}");
        assert!(note.contains(&cap) && note.contains(&mesh), "{note}");

        let at_cap = Mesh { lower: 7, upper_to_contact: 200, upper_beyond_contact: MAX_ELEMENTS };
        let r = Refinement::of(at_cap, ImpactorKind::Beam).unwrap();
        assert_eq!(r.mesh_2x.upper_to_contact, MAX_ELEMENTS);
        assert_eq!(r.mesh_4x, Mesh { lower: 28, ..r.mesh_2x }, "only the arrestor refines further");
        assert_eq!(r.mesh_change_between, ["mesh_2x", "mesh_4x"]);

        let two_only =
            Mesh { lower: MAX_ELEMENTS / 2, upper_to_contact: MAX_ELEMENTS, upper_beyond_contact: MAX_ELEMENTS };
        let r = Refinement::of(two_only, ImpactorKind::Beam).unwrap();
        assert_eq!(r.mesh_4x, r.mesh_2x);
        assert_eq!(r.mesh_change_between, ["base", "mesh_2x"]);
        assert!(r.mesh_capped.unwrap().contains("compares the base and 2x"));

        let full = Mesh { lower: MAX_ELEMENTS, upper_to_contact: MAX_ELEMENTS, upper_beyond_contact: MAX_ELEMENTS };
        let e = Refinement::of(full, ImpactorKind::Beam).unwrap_err().to_string();
        assert!(e.contains("already at the largest allowed"), "{e}");
    }

    /// A rigid impactor's bridge counts mesh nothing: its refinements grow the arrestor's count
    /// alone, and at the cap that count says so (an error, or base against 2x with a note), rather
    /// than comparing two runs whose only difference is the unused counts (a false "converged").
    #[test]
    fn a_mass_impactors_refinement_is_finer_only_in_the_arrestor() {
        let kind = ImpactorKind::Mass;
        let r = Refinement::of(Mesh { lower: 7, upper_to_contact: 200, upper_beyond_contact: 300 }, kind).unwrap();
        assert_eq!(r.mesh_2x, Mesh { lower: 14, upper_to_contact: 200, upper_beyond_contact: 300 });
        assert_eq!(r.mesh_4x, Mesh { lower: 28, upper_to_contact: 200, upper_beyond_contact: 300 });
        assert_eq!((r.mesh_capped, r.mesh_change_between), (None, ["mesh_2x", "mesh_4x"]));

        let half = Mesh { lower: MAX_ELEMENTS / 2, upper_to_contact: 7, upper_beyond_contact: 7 };
        let r = Refinement::of(half, kind).unwrap();
        assert_eq!(r.mesh_4x, r.mesh_2x);
        assert_eq!(r.mesh_change_between, ["base", "mesh_2x"]);
        let note = r.mesh_capped.expect("capped");
        assert!(note.contains(&format!("4x is {MAX_ELEMENTS} (base {})", MAX_ELEMENTS / 2)), "{note}");

        let at_cap = Mesh { lower: MAX_ELEMENTS, upper_to_contact: 7, upper_beyond_contact: 7 };
        let e = Refinement::of(at_cap, kind).unwrap_err().to_string();
        assert!(e.contains(&format!("the mesh {MAX_ELEMENTS} is already at the largest")), "{e}");
        // The same counts for a beam refine the bridge and are no error.
        assert!(Refinement::of(at_cap, ImpactorKind::Beam).is_ok());
    }

    /// The tolerance is a fraction: 1 (meaning 1 %?) and 0 are refused with the rule.
    #[test]
    fn tolerance_must_be_a_fraction() {
        assert!(check_tolerance(0.01).is_ok());
        for bad in [0.0, 1.0, -0.01, f64::NAN] {
            let e = check_tolerance(bad).unwrap_err().to_string();
            assert!(e.starts_with("--tolerance must be > 0 and < 1"), "{e}");
        }
    }
}
