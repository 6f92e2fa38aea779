//! The time steps of a run, resolved from the scenario's [`TimeStep`]s and the natural
//! frequencies: checked against the stability limit, and automatic steps chosen energy-safe.
//!
//! Why a step can be stable and still unsafe: for an undamped linear system at a fixed step dt,
//! the linear acceleration method (Newmark gamma = 1/2, beta = 1/6) conserves the modified energy
//! E_h = E - dt^2/24 a^T M a, not E: a mode i keeps its share of E only to within
//! c_i = (omega_i dt)^2 / 12. Every change of dt (the paper's 2:1 step pair at each contact change,
//! the shortened step that locates a contact change, the step that lands on the stop time or on an
//! input change) moves each mode's energy by up to c_i of itself, up or down by the phase. Over
//! many bounces the high modes' energy random-walks upwards, at a rate of order c_max^2 per change:
//! undamped runs blow up. The paper's 5e-5 s out of contact gives omega_max dt = 2.19 (c = 0.40)
//! on its own mesh; an undamped drop of 0.2 m then ends with a residual of 25.8 kJ, more than the
//! whole impact energy. Bounding omega_max dt <= 1 (c <= 1/12) in every stage keeps the residual
//! of undamped runs over drop heights 0.1-2 m and contact positions 10-16 m below 0.1 % of the
//! energy that flows in 3 s, and below 1 % in 30 s (measurements in `tests/energy_safety.rs`).

use super::modal::{ModalSystem, STABILITY_LIMIT};
use crate::error::{Error, Result};
use crate::model::discretisation::auto_step_factor;
use crate::model::scenario::{MIN_STEP, PAPER_STEP_CONTACT, PAPER_STEP_FREE};
use crate::model::{Scenario, TimeStep};
use crate::results::seconds;

/// Largest omega_max dt of an energy-safe step: c = (omega_max dt)^2 / 12 <= 1/12.
pub const ENERGY_SAFE_LIMIT: f64 = 1.0;

/// The resolved time step of each stage, in whole nanoseconds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StepPlan {
    /// Out of contact, ns.
    pub free_ns: u64,
    /// In contact, ns.
    pub contact_ns: u64,
}

/// The largest energy-safe step of a stage, s: omega_max dt <= [`ENERGY_SAFE_LIMIT`], in whole
/// nanoseconds rounded down, never above `cap`, never below 1 ns.
pub fn energy_safe_step(omega_max: f64, cap: f64) -> f64 {
    automatic_step(omega_max, cap, ENERGY_SAFE_LIMIT)
}

/// The automatic step of a stage, s: omega_max dt <= `product`, in whole nanoseconds rounded
/// down, never above `cap`, never below 1 ns.
pub fn automatic_step(omega_max: f64, cap: f64, product: f64) -> f64 {
    let safe = if omega_max > 0.0 { product / omega_max } else { cap };
    seconds(((safe.min(cap) * 1e9).floor() as u64).max(1))
}

/// omega_max dt of the scenario's automatic steps: [`ENERGY_SAFE_LIMIT`], halved for a lightly
/// damped converged run ([`crate::model::discretisation::auto_step_factor`]).
pub fn automatic_product(scenario: &Scenario) -> f64 {
    let linear_acceleration =
        scenario.method == crate::model::Method::Paper || scenario.contact.nonlinear_law().is_some();
    ENERGY_SAFE_LIMIT * auto_step_factor(scenario.method, scenario.damping_ratio, linear_acceleration)
}

/// Rejects `step` if dt * omega_max > sqrt(12) ([`STABILITY_LIMIT`]) in the given stage; the
/// error names the automatic step at omega_max dt = `auto_product`.
pub fn check_stability(
    modal: &ModalSystem,
    name: &'static str,
    step: f64,
    contact: bool,
    auto_product: f64,
) -> Result<()> {
    let omega_max = modal.omega_max(contact);
    let product = step * omega_max;
    if product > STABILITY_LIMIT {
        return Err(Error::UnstableStep {
            name,
            step,
            omega_max,
            product,
            limit: STABILITY_LIMIT / omega_max,
            stage: if contact { "in contact" } else { "out of contact" },
            auto: automatic_step(omega_max, if contact { PAPER_STEP_CONTACT } else { PAPER_STEP_FREE }, auto_product),
        });
    }
    Ok(())
}

/// The highest frequency of a stage and what owns it: one of the beams' highest kept mode, or
/// (in contact) the contact bar coupling them.
pub fn stage_frequency(modal: &ModalSystem, contact: bool) -> String {
    let omega_max = modal.omega_max(contact);
    let (lower, upper) = (modal.lower.omega_max(), modal.upper.omega_max());
    let owner = if contact && omega_max > 1.01 * lower.max(upper) {
        format!("the contact bar (k = {:.4e} N/m) coupling the beams", modal.bar_stiffness)
    } else if lower >= upper {
        "the arrestor's (lower) highest kept mode".to_string()
    } else {
        "the bridge's (upper) highest kept mode".to_string()
    };
    format!("omega_max = {omega_max:.4e} rad/s {}, from {owner}", if contact { "in contact" } else { "out of contact" })
}

impl StepPlan {
    /// Resolves automatic steps ([`automatic_product`]) and checks fixed ones against the
    /// stability limit dt omega_max <= sqrt(12) of their stage (an error that suggests `"auto"`).
    pub fn new(scenario: &Scenario, modal: &ModalSystem) -> Result<StepPlan> {
        let product = automatic_product(scenario);
        let resolve = |name: &'static str, step: TimeStep, contact: bool, cap: f64| -> Result<u64> {
            let dt = match step {
                TimeStep::Auto => {
                    let omega_max = modal.omega_max(contact);
                    // The automatic step never goes below 1 ns (time is counted in whole
                    // nanoseconds): a model whose highest kept mode needs less would run unstable
                    // and end in a non-finite state; refuse it before it starts.
                    if omega_max * MIN_STEP > STABILITY_LIMIT {
                        return Err(Error::Other(format!(
                            "{name} = \"auto\" cannot be stable: {}, and the linear acceleration method needs dt <= \
                             sqrt(12) / omega_max = {:e} s, below the 1 ns the stepper counts in; soften or coarsen \
                             the model",
                            stage_frequency(modal, contact),
                            STABILITY_LIMIT / omega_max
                        )));
                    }
                    automatic_step(omega_max, cap, product)
                }
                TimeStep::Fixed(dt) => {
                    check_stability(modal, name, dt, contact, product)?;
                    dt
                }
            };
            Ok(((dt * 1e9).round() as u64).max(1))
        };
        Ok(StepPlan {
            free_ns: resolve("step_free", scenario.step_free, false, PAPER_STEP_FREE)?,
            contact_ns: resolve("step_contact", scenario.step_contact, true, PAPER_STEP_CONTACT)?,
        })
    }

    /// Why the smaller of the two steps is what it is, for a refusal of the step count: the
    /// stage, whether the step is automatic, and the frequency it follows.
    pub fn reason(&self, scenario: &Scenario, modal: &ModalSystem) -> String {
        let contact = self.contact_ns < self.free_ns;
        let step = if contact { scenario.step_contact } else { scenario.step_free };
        match step {
            TimeStep::Auto => format!(
                "the automatic step {} follows omega_max dt <= {} with {}",
                if contact { "in contact" } else { "out of contact" },
                automatic_product(scenario),
                stage_frequency(modal, contact)
            ),
            TimeStep::Fixed(_) => format!(
                "{} is fixed at {:e} s",
                if contact { "step_contact" } else { "step_free" },
                seconds(self.step_ns(contact))
            ),
        }
    }

    /// The step of a stage, ns.
    pub fn step_ns(&self, contact: bool) -> u64 {
        if contact {
            self.contact_ns
        } else {
            self.free_ns
        }
    }

    /// One line for each fixed step above the energy-safe limit: stable, but a run with little
    /// damping may gain energy at every change of step (see the module documentation). None for
    /// the paper scenario itself: its steps are the paper's, not the user's to change (a user
    /// who sets any field gets the advisory where it applies).
    pub fn advisories(&self, scenario: &Scenario, modal: &ModalSystem) -> Vec<String> {
        let mut lines = Vec::new();
        if scenario.is_paper() {
            return lines;
        }
        for (name, step, contact) in
            [("step_free", scenario.step_free, false), ("step_contact", scenario.step_contact, true)]
        {
            let TimeStep::Fixed(_) = step else { continue };
            let dt = seconds(self.step_ns(contact));
            let omega_max = modal.omega_max(contact);
            let product = dt * omega_max;
            if product > ENERGY_SAFE_LIMIT {
                let cap = if contact { PAPER_STEP_CONTACT } else { PAPER_STEP_FREE };
                lines.push(format!(
                    "{name} = {dt:e} s is stable but not energy-safe: dt * omega_max = {product:.2} > \
                     {ENERGY_SAFE_LIMIT} (omega_max = {omega_max:.0} rad/s {}); with little damping each change \
                     of step can pump energy into the highest modes; \"auto\" gives {:e} s",
                    if contact { "in contact" } else { "out of contact" },
                    automatic_step(omega_max, cap, automatic_product(scenario))
                ));
            }
        }
        lines
    }
}
