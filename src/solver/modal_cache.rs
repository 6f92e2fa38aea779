//! The modes a geometry fixes, computed once and shared by the runs of a sweep.
//!
//! A run's setup assembles the model and decomposes it into modes ([`ModalSystem::new`], a
//! symmetric eigenproblem per beam, then [`ModalSystem::for_run`]'s truncation and static
//! correction). Runs that differ only in their initial conditions, damping, steps or checks (a
//! sweep over drop height, impact speed or damping ratio) share all of it but the damping, which
//! [`ModalSystem::with_damping`] sets per run. A [`ModalCache`] keeps those systems, keyed by the
//! exact bits of everything they can depend on, so that a cached run is the uncached one to the
//! bit (`tests/sweep.rs` holds every peak, figure and verdict of a few rows to `==`).
//!
//! The key is the resolved scenario with the [`PER_RUN_FIELDS`] reset, written out in full
//! (serde's shortest round-trip decimals: one text per f64 bit pattern) and compared whole, not
//! by a hash, plus the contact's rate in the coupled modes (which for a nonlinear law follows
//! the impact energy). A field missing from [`PER_RUN_FIELDS`] only costs sharing; a field
//! wrongly in it would share modes that differ, and the tests vary each of them.
//!
//! The automatic cut-off's reference mesh (the paper mesh's modes,
//! [`crate::discretise::reference_mesh_with`]) is kept here too, by the same key, so that the rungs
//! a sweep or a campaign resolves share one eigen-solve per geometry (issue 43).
//!
//! The assembled [`Model`] of a scenario is kept too ([`ModalCache::model`]), by the scenario less
//! the fields no part of a model reads (a campaign's events differ only by the sea's instant: its
//! three runs and their rungs build six models an event from three meshes), and so is what each
//! run's initial state takes from its geometry alone (the arrestor's stiffness factored, the
//! bridge's shapes transposed: [`RunModes::initial`]) and the reference mesh's frequencies
//! ([`ModalCache::reference`]). Each is what a fresh computation gives, to the bit (the same
//! operations on the same inputs), as the tests below hold.
//!
//! Measured (issue 29, the default scenario, perf): the setup is about 4 % of a run's time, the
//! eigen decompositions most of it; stepping is the rest.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};

use nalgebra::DMatrix;

use super::envelope::StationRows;
use super::initial::InitialFactors;
use super::modal::ModalSystem;
use super::model_range::RangeRows;
use crate::error::Result;
use crate::model::{Model, Scenario};

/// The scenario fields no part of a [`ModalSystem`] depends on except its damping (which
/// [`ModalSystem::with_damping`] sets per run), by their dotted names: a sweep over them shares
/// the modes of each rung (the sweep runs rows that differ in other fields apart, see
/// `studies::sweep`). `motion.file` and the motion table go with `motion.time_shift`; the key leaves
/// out the whole `[sea]` (a sea moves the supports, never the modes: every `sea.*` field is per
/// run, `tests/sweep.rs` holds its cached answers to the bit).
pub const PER_RUN_FIELDS: [&str; 19] = [
    "drop_height",
    "impact_speed",
    "impact_angular_velocity",
    "damping_ratio",
    "rayleigh_alpha",
    "rayleigh_beta",
    "step_free",
    "step_contact",
    "duration",
    "energy_tolerance",
    "discretisation_tolerance",
    "upper.allowable_bending_stress",
    "upper.yield_stress",
    "upper.tip_force",
    "lower.allowable_bending_stress",
    "lower.allowable_shear_stress",
    "lower.yield_stress",
    "lower.tip_force",
    "motion.time_shift",
];

/// Entries a cache holds by default: the three rungs of a converged answer, in both of the
/// automatic cut-off's damping classes, for five geometries.
pub const DEFAULT_ENTRIES: usize = 30;

/// Bytes of matrices a cache holds by default (an entry of the default rung is about 3 MB; of the
/// finest meshes, 256 elements per segment, about 80 MB).
pub const DEFAULT_BYTES: usize = 512 << 20;

/// What a geometry's rung fixes: the full modal system (the initial state's basis) and the basis
/// a run steps in, both with the damping of the run that computed them.
#[derive(Debug)]
struct Shared {
    full: Arc<ModalSystem>,
    /// `None` when [`ModalSystem::for_run`] failed: each run then computes it again and meets
    /// its own error, in its own order.
    run: Option<ModalSystem>,
    /// The run basis's [`crate::solver::stepper::projector`].
    projector: Option<Arc<DMatrix<f64>>>,
    /// What the initial state takes from the geometry alone.
    initial: Arc<InitialFactors>,
    /// The rows the runs stepping in the run basis read, filled by the first of them.
    rows: Arc<RunRows>,
    bytes: usize,
}

/// One key's slot: filled by the first run that needs it, while later ones wait on its lock.
type Slot = Arc<Mutex<Option<Arc<Shared>>>>;

/// A bounded, thread-safe store of modal systems keyed by geometry (see the module
/// documentation). Each run gets its own copy of the systems, with its own damping.
#[derive(Debug)]
pub struct ModalCache {
    /// Most recently used first.
    entries: Mutex<VecDeque<(Key, Slot)>>,
    /// Assembled models by [`model_key`], most recently used first.
    models: Mutex<VecDeque<(String, Arc<Model>)>>,
    /// The reference mesh's frequencies by [`model_key`] and contact rate, most recent first.
    references: Mutex<VecDeque<(Key, (f64, f64))>>,
    max_entries: usize,
    max_bytes: usize,
}

#[derive(Clone, Debug, PartialEq, Eq)]
struct Key {
    scenario: String,
    bar_stiffness: u64,
}

impl Default for ModalCache {
    fn default() -> Self {
        ModalCache::new(DEFAULT_ENTRIES, DEFAULT_BYTES)
    }
}

/// The modes of one run, from a cache: the full system and the basis it steps in.
pub struct RunModes {
    /// The full modal system (every mode of the mesh) as the cache keeps it, shared: with the
    /// damping of the run that computed it ([`ModalSystem::with_damping`] gives a run's own; the
    /// initial state reads none).
    pub full: Arc<ModalSystem>,
    /// The basis the run steps in, with the run's damping; `None`: compute it from `full` (its
    /// error is the run's).
    pub run: Option<ModalSystem>,
    /// `run`'s projector Phi^T M (with `run`).
    pub projector: Option<Arc<DMatrix<f64>>>,
    /// What the initial state takes from the geometry alone ([`InitialFactors`]).
    pub initial: Arc<InitialFactors>,
    /// The rows the runs stepping in `run` read ([`RunRows`]), filled by the first of them.
    pub rows: Arc<RunRows>,
}

/// The rows a run stepping in a cached run basis builds from the basis and its model alone,
/// filled by the first such run and shared by the later ones (they read the basis's shapes and
/// stations, which the damping leaves alone; each is what that run builds, to the bit).
#[derive(Debug, Default)]
pub struct RunRows {
    /// The model-range rows ([`crate::solver::model_range`]).
    pub range: OnceLock<Arc<RangeRows>>,
    /// The stress stations' rows ([`StationRows`]) with the bits of the divisors, allowables and
    /// groups they were made for (the allowables are per run: a run of others makes its own).
    pub stations: OnceLock<(Vec<u64>, Arc<StationRows>)>,
    /// The deflection rows of the basis's shapes at every node ([`crate::simulation::Simulation::nodal_shapes`]).
    pub nodal_shapes: OnceLock<Arc<DMatrix<f64>>>,
}

impl ModalCache {
    /// A cache of at most `max_entries` rungs and about `max_bytes` of matrices (the least
    /// recently used leave first; a system larger than `max_bytes` is computed but not kept).
    /// `max_entries` 0 keeps nothing.
    pub fn new(max_entries: usize, max_bytes: usize) -> ModalCache {
        ModalCache {
            entries: Mutex::new(VecDeque::new()),
            models: Mutex::new(VecDeque::new()),
            references: Mutex::new(VecDeque::new()),
            max_entries,
            max_bytes,
        }
    }

    /// A cache that keeps nothing: every run computes its own modes ([`crate::answer::run`]).
    pub fn disabled() -> ModalCache {
        ModalCache::new(0, 0)
    }

    /// Whether the cache keeps anything (`max_entries` > 0).
    pub fn is_enabled(&self) -> bool {
        self.max_entries > 0
    }

    /// Rungs held now.
    pub fn len(&self) -> usize {
        lock(&self.entries).len()
    }

    /// Whether no rung is held.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The modes of `model` (built by [`Model::new`] from a resolved scenario) with its damping:
    /// [`ModalSystem::new`] and [`ModalSystem::for_run`] of the model, from the cache when a run
    /// of the same geometry computed them, else computed here and kept. Errors of
    /// [`ModalSystem::new`] are returned, never kept.
    pub fn modes(&self, model: &Model) -> Result<RunModes> {
        let shared = self.shared(model)?;
        let s = &model.scenario;
        Ok(RunModes {
            full: shared.full.clone(),
            run: shared.run.clone().map(|m| m.with_damping(s)),
            projector: shared.projector.clone(),
            initial: shared.initial.clone(),
            rows: shared.rows.clone(),
        })
    }

    /// The full modal system of `model` and what its initial state takes from the geometry alone
    /// ([`InitialFactors`]), from the cache as [`Self::modes`] keeps them, without a copy of the
    /// run basis (a run that only starts from `model`'s state: the tangent's twin).
    pub fn initial_modes(&self, model: &Model) -> Result<(Arc<ModalSystem>, Arc<InitialFactors>)> {
        let shared = self.shared(model)?;
        Ok((shared.full.clone(), shared.initial.clone()))
    }

    /// The assembled model of `scenario` ([`Model::new`]): a clone of the one built for a scenario
    /// of the same key (the scenario less the fields no model reads), with this scenario and its
    /// contact rate ([`crate::model::system::contact_rate`], which follows the impact energy for a
    /// nonlinear law), else built here and kept. The scenario is validated either way (its own errors, in
    /// [`Model::new`]'s order: a kept model's element counts passed that check already, and they
    /// are in the key).
    pub fn model(&self, scenario: &Scenario) -> Result<Model> {
        if !self.is_enabled() {
            return Model::new(scenario);
        }
        let key = model_key(scenario);
        let kept = {
            let mut models = lock(&self.models);
            let found = models.iter().position(|(k, _)| *k == key);
            found.and_then(|i| models.remove(i)).inspect(|entry| models.push_front(entry.clone()))
        };
        match kept {
            Some((_, kept)) => {
                scenario.validate()?;
                let mut model = Model::clone(&kept);
                model.scenario = scenario.clone();
                model.bar_stiffness = crate::model::system::contact_rate(scenario);
                Ok(model)
            }
            None => {
                let model = Model::new(scenario)?;
                let mut models = lock(&self.models);
                models.retain(|(k, _)| *k != key);
                models.push_front((key, Arc::new(model.clone())));
                models.truncate(self.max_entries);
                Ok(model)
            }
        }
    }

    /// The automatic cut-off's reference frequencies of the reference mesh's `scenario` (what
    /// [`crate::discretise::reference_mesh_with`] computes from its model and modes with
    /// `compute`), kept by its model's key and contact rate: a scenario of a kept key is only
    /// validated (its own errors; a kept key's model was built, so its element counts pass);
    /// `compute` runs on a miss, its errors are returned, never kept.
    pub fn reference(
        &self,
        scenario: &Scenario,
        compute: impl FnOnce(&Model) -> Result<(f64, f64)>,
    ) -> Result<(f64, f64)> {
        if !self.is_enabled() {
            return compute(&Model::new(scenario)?);
        }
        scenario.validate()?;
        let rate = crate::model::system::contact_rate(scenario);
        let key = Key { scenario: model_key(scenario), bar_stiffness: rate.to_bits() };
        if let Some((_, value)) = lock(&self.references).iter().find(|(k, _)| *k == key) {
            return Ok(*value);
        }
        let value = compute(&self.model(scenario)?)?;
        let mut references = lock(&self.references);
        references.retain(|(k, _)| *k != key);
        references.push_front((key, value));
        references.truncate(self.max_entries);
        Ok(value)
    }

    /// The full modal system of `model` ([`ModalSystem::new`], every mode of its mesh, with the
    /// damping of the run that computed it) from the cache, else computed and kept as
    /// [`Self::modes`] keeps it: what reads only the frequencies and shapes (the automatic
    /// cut-off's reference mesh, [`crate::discretise::reference_mesh_with`]) shares it whatever the
    /// per-run fields.
    pub fn full_modes(&self, model: &Model) -> Result<Arc<ModalSystem>> {
        Ok(self.shared(model)?.full.clone())
    }

    /// What `model`'s key holds, filled here on a miss (a system of no key, or of a cache that
    /// keeps nothing, is computed and not kept).
    fn shared(&self, model: &Model) -> Result<Arc<Shared>> {
        Ok(match self.slot(model) {
            None => Arc::new(compute(model)?),
            Some(slot) => {
                let mut filled = lock(&slot);
                match &*filled {
                    Some(shared) => shared.clone(),
                    None => {
                        let shared = Arc::new(compute(model)?);
                        *filled = Some(shared.clone());
                        drop(filled);
                        self.trim();
                        shared
                    }
                }
            }
        })
    }

    /// The slot of `model`'s key, made most recent (a new, empty one when missing); `None` when the
    /// cache keeps nothing or the key cannot be written.
    fn slot(&self, model: &Model) -> Option<Slot> {
        if !self.is_enabled() {
            return None;
        }
        let key = key(model)?;
        let mut entries = lock(&self.entries);
        let slot = match entries.iter().position(|(k, _)| *k == key) {
            Some(i) => entries.remove(i).map(|(_, slot)| slot)?,
            None => Arc::new(Mutex::new(None)),
        };
        entries.push_front((key, slot.clone()));
        Some(slot)
    }

    /// Drops the least recently used filled slots beyond the limits (slots being filled stay).
    fn trim(&self) {
        let mut entries = lock(&self.entries);
        let size = |slot: &Slot| slot.try_lock().ok().and_then(|s| s.as_ref().map(|s| s.bytes)).unwrap_or(0);
        let mut bytes: usize = entries.iter().map(|(_, slot)| size(slot)).sum();
        while entries.len() > self.max_entries || (bytes > self.max_bytes && !entries.is_empty()) {
            let Some((_, slot)) = entries.pop_back() else { break };
            bytes -= size(&slot).min(bytes);
        }
    }
}

/// A lock whose holder panicked is still good: the slots hold either nothing or a whole system.
fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

fn compute(model: &Model) -> Result<Shared> {
    let full = ModalSystem::new(model)?;
    let run = full.clone().for_run(model).ok();
    let projector = run.as_ref().map(|r| Arc::new(crate::solver::stepper::projector(model, r)));
    let initial = Arc::new(InitialFactors::new(model, &full));
    let bytes = approximate_bytes(&full)
        + run.as_ref().map_or(0, approximate_bytes)
        + 8 * projector.as_ref().map_or(0, |p| p.len())
        + 8 * (initial.upper_shapes_transposed.len() + model.lower.stiffness.len());
    Ok(Shared { full: Arc::new(full), run, projector, initial, rows: Arc::default(), bytes })
}

/// The matrices' and vectors' bytes of a system.
fn approximate_bytes(m: &ModalSystem) -> usize {
    let matrices = m.lower.shapes.len() + m.upper.shapes.len() + m.coupled.shapes.len() + m.probes.len();
    let vectors = 12 * m.dofs() + m.lower.omega.len() + m.upper.omega.len() + m.coupled.omega.len();
    8 * (matrices + vectors)
}

/// The key of `model`: its scenario without the [`PER_RUN_FIELDS`], written out in full, and the
/// contact's rate. `None` if it cannot be written (then nothing is shared).
fn key(model: &Model) -> Option<Key> {
    let d = Scenario::default();
    let mut s = without_run_fields(&model.scenario, &d);
    s.upper.allowable_bending_stress = d.upper.allowable_bending_stress;
    s.upper.yield_stress = d.upper.yield_stress;
    s.lower.allowable_bending_stress = d.lower.allowable_bending_stress;
    s.lower.allowable_shear_stress = d.lower.allowable_shear_stress;
    s.lower.yield_stress = d.lower.yield_stress;
    s.motion = d.motion;
    s.sea = d.sea;
    s.fatigue = d.fatigue;
    let scenario = serde_json::to_string(&s).ok()?;
    Some(Key { scenario, bar_stiffness: model.bar_stiffness.to_bits() })
}

/// The key of [`ModalCache::model`]: `scenario` without the fields [`Model::new`] does not read
/// (the impact's, the damping's, the steps', the duration, the tolerances, the tip forces, the
/// supports' motion, the sea, the fatigue section; the contact rate, which reads the impact, is
/// set per scenario), written by `Debug` (every f64 as its shortest round-trip decimal, -0 as
/// -0.0: equal text, equal bits).
fn model_key(scenario: &Scenario) -> String {
    let d = Scenario::default();
    let s = Scenario { motion: d.motion.clone(), sea: None, fatigue: None, ..without_run_fields(scenario, &d) };
    format!("{s:?}")
}

/// `scenario` with the fields neither the assembled model nor its modes read set to `d`'s (the
/// impact's, the damping's, the steps', the duration, the tolerances, the tip forces): the part
/// both cache keys share.
fn without_run_fields(scenario: &Scenario, d: &Scenario) -> Scenario {
    let mut s = scenario.clone();
    s.drop_height = d.drop_height;
    s.impact_angular_velocity = d.impact_angular_velocity;
    s.impact_speed = d.impact_speed;
    s.damping_ratio = d.damping_ratio;
    s.rayleigh_alpha = d.rayleigh_alpha;
    s.rayleigh_beta = d.rayleigh_beta;
    s.step_free = d.step_free;
    s.step_contact = d.step_contact;
    s.duration = d.duration;
    s.energy_tolerance = d.energy_tolerance;
    s.discretisation_tolerance = d.discretisation_tolerance;
    s.upper.tip_force = d.upper.tip_force;
    s.lower.tip_force = d.lower.tip_force;
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(s: &Scenario) -> Model {
        Model::new(&crate::discretise::printed(s).unwrap()).unwrap()
    }

    /// Debug prints every f64 as its shortest round-trip decimal (and -0 as -0.0): equal text,
    /// equal bits.
    fn bits(m: &ModalSystem) -> String {
        format!("{m:?}")
    }

    /// A cached system is the fresh one to the bit, whatever the per-run fields of the run that
    /// computed it; a different geometry gets its own entry.
    #[test]
    fn cached_modes_equal_fresh_ones_to_the_bit() {
        let cache = ModalCache::default();
        let base = Scenario::default();
        let mut variants = vec![base.clone()];
        for (h, zeta, beta) in [(1.7, 0.05, 0.0), (0.2, 0.03, 1e-5)] {
            let mut s = base.clone();
            s.drop_height = h;
            s.damping_ratio = zeta;
            s.rayleigh_beta = beta;
            variants.push(s);
        }
        let mut other = base.clone();
        other.contact_position = 20.0;
        variants.push(other);
        for s in &variants {
            let m = model(s);
            let cached = cache.modes(&m).unwrap();
            let full = ModalSystem::new(&m).unwrap();
            let run = full.clone().for_run(&m).unwrap();
            assert_eq!(bits(&(*cached.full).clone().with_damping(s)), bits(&full), "full, {}", s.drop_height);
            assert_eq!(bits(cached.run.as_ref().unwrap()), bits(&run), "run, {}", s.drop_height);
        }
        assert_eq!(cache.len(), 2, "one entry per geometry");
    }

    /// Issue 43: a model from the cache is [`Model::new`]'s to the bit whatever the per-run fields
    /// of the scenario that filled it (drop, speed, damping, tip forces, the sea's instant), its
    /// contact rate the scenario's own where a nonlinear law makes it follow the impact energy; a
    /// bad per-run field is refused as [`Model::new`] refuses it; another mesh gets its own entry.
    #[test]
    fn cached_models_equal_fresh_ones_to_the_bit() {
        let power = Scenario::from_toml("[contact]\nlaw = \"power\"\nstiffness = 1e10\n", "the test's law").unwrap();
        for base in [Scenario::default(), power] {
            let cache = ModalCache::default();
            let base = crate::discretise::printed(&base).unwrap();
            let mut variants = vec![base.clone()];
            for (h, zeta, tip) in [(1.7, 0.05, 0.0), (0.2, 0.0, 3e3)] {
                let mut s = Scenario { drop_height: h, damping_ratio: zeta, duration: 0.3, ..base.clone() };
                s.upper.tip_force = tip;
                variants.push(s);
            }
            variants.push(Scenario { impact_angular_velocity: Some(0.4), drop_height: 0.0, ..base.clone() });
            for s in &variants {
                let (cached, fresh) = (cache.model(s).unwrap(), Model::new(s).unwrap());
                assert_eq!(format!("{cached:?}"), format!("{fresh:?}"), "drop {}", s.drop_height);
            }
            let rates: Vec<u64> = variants.iter().map(|s| cache.model(s).unwrap().bar_stiffness.to_bits()).collect();
            let linear = base.contact_law().is_none();
            assert_eq!(rates.iter().all(|r| *r == rates[0]), linear, "the rate follows the impact only for a law");
            let bad = Scenario { drop_height: -1.0, ..base.clone() };
            assert_eq!(cache.model(&bad).unwrap_err().to_string(), Model::new(&bad).unwrap_err().to_string());
            assert_eq!(lock(&cache.models).len(), 1, "one model per mesh");
            let coarser = crate::discretise::check(&base).unwrap();
            assert_eq!(format!("{:?}", cache.model(&coarser).unwrap()), format!("{:?}", Model::new(&coarser).unwrap()));
            assert_eq!(lock(&cache.models).len(), 2);
        }
    }

    /// Issue 43: the initial state from the cached factors (the arrestor's stiffness factored, the
    /// bridge's shapes transposed, made for the geometry by another run) is the one computed
    /// afresh, to the bit, for other drops, speeds, tip forces and supports' motions.
    #[test]
    fn the_initial_state_from_cached_factors_is_the_fresh_one_to_the_bit() {
        use crate::solver::initial::{initial_state, initial_state_with};
        use crate::solver::kinematics::{Excitation, TipForces};
        let cache = ModalCache::default();
        let base = crate::discretise::printed(&Scenario::default()).unwrap();
        cache.modes(&cache.model(&base).unwrap()).unwrap();
        let excitations = [
            Excitation::default(),
            Excitation {
                forces: TipForces { upper: 2e3, lower: -5e2 },
                support_acceleration: [0.7, -0.3, 0.05],
                gap_offset: 0.012,
                gap_offset_rate: -0.2,
                gap_offset_acceleration: 0.4,
            },
        ];
        for s in [
            Scenario { drop_height: 1.3, ..base.clone() },
            Scenario { impact_angular_velocity: Some(0.3), drop_height: 0.0, ..base },
        ] {
            let model = cache.model(&s).unwrap();
            let modes = cache.modes(&model).unwrap();
            for e in &excitations {
                let cached = initial_state_with(&model, &modes.full, e, Some(&modes.initial)).unwrap();
                let fresh = initial_state(&model, &ModalSystem::new(&model).unwrap(), e).unwrap();
                assert_eq!(format!("{cached:?}"), format!("{fresh:?}"));
            }
        }
    }

    /// The cache stays within its entries, and one of no entries keeps nothing.
    #[test]
    fn the_cache_is_bounded() {
        let cache = ModalCache::new(1, DEFAULT_BYTES);
        for position in [10.0, 13.0, 20.0] {
            let s = Scenario { contact_position: position, ..Scenario::paper() };
            cache.modes(&model(&s)).unwrap();
            assert_eq!(cache.len(), 1);
        }
        let none = ModalCache::disabled();
        none.modes(&model(&Scenario::paper())).unwrap();
        assert!(none.is_empty() && !none.is_enabled());
        let small = ModalCache::new(10, 1000);
        small.modes(&model(&Scenario::paper())).unwrap();
        assert!(small.is_empty(), "a system above the byte limit is not kept");
    }
}
