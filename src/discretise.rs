//! Resolves a scenario's `"auto"` discretisation into the meshes and modal cut-offs that are run:
//! the rung a run prints and the coarser rung its discretisation check compares it with
//! (see [`crate::model::discretisation`] for the ladder).

use crate::error::Result;
use crate::model::discretisation::{Method, DEFAULT_RUNG, LADDER, PAPER_ELEMENTS};
use crate::model::{Model, Scenario};
use crate::solver::graded::GRADED_RATIO;
use crate::solver::ModalSystem;

/// The scenario's reference frequency, rad/s: the highest natural frequency of either beam on the
/// paper's mesh (7 + 7/7 elements), the scale of the automatic cut-offs. A graded beam's short
/// elements' own modes (above its [`crate::solver::graded::spurious_limit`]) are not counted: the
/// cut-offs follow the frequencies of the mesh's longer elements, never those of a sub-millimetre
/// overhang.
pub fn reference_frequency(scenario: &Scenario) -> Result<f64> {
    let mut coarse = scenario.clone();
    coarse.method = Method::Paper;
    set_elements(&mut coarse, [PAPER_ELEMENTS; 3]);
    let model = Model::new(&coarse)?;
    let modal = ModalSystem::new(&model).map_err(|e| {
        crate::Error::Other(format!("the automatic cut-off's reference mesh ({}): {e}", describe(&coarse)))
    })?;
    Ok(modal.resolved_omega_max(&model))
}

/// A resolved scenario's mesh as the tables print it: `7 + 7/1 elements`.
pub fn describe(s: &Scenario) -> String {
    format!("{} + {}/{} elements", s.lower.elements, s.upper.elements_to_contact, s.upper.elements_beyond_contact)
}

fn set_elements(s: &mut Scenario, [lower, inner, outer]: [u32; 3]) {
    let auto = [s.upper.elements_to_contact == 0, s.upper.elements_beyond_contact == 0];
    if s.lower.elements == 0 {
        s.lower.elements = lower;
    }
    if s.upper.elements_to_contact == 0 {
        s.upper.elements_to_contact = inner;
    }
    if s.upper.elements_beyond_contact == 0 && !s.contact_at_free_end() {
        s.upper.elements_beyond_contact = outer;
    }
    balance_segments(s, auto);
}

/// Automatic counts on a bridge segment much shorter than the other: where equal counts would
/// make the elements of one segment more than [`GRADED_RATIO`] times shorter than the other's (a
/// contact near the free end or the hinge), the shorter segment, if its count is `"auto"`, gets
/// elements about as long as the other's, at least one: `ceil(its length / the other's element)`.
/// (A 1 mm overhang then has one element, not 56 of 18 um.) Counts that make no such mesh are
/// left as they are.
fn balance_segments(s: &mut Scenario, [inner_auto, outer_auto]: [bool; 2]) {
    let inner = s.contact_position;
    let outer = s.upper.length - s.contact_position;
    let (n_inner, n_outer) = (s.upper.elements_to_contact, s.upper.elements_beyond_contact);
    if !(inner > 0.0 && outer > 0.0) || n_inner == 0 || n_outer == 0 {
        return;
    }
    let (h_inner, h_outer) = (inner / f64::from(n_inner), outer / f64::from(n_outer));
    let fit = |length: f64, h: f64| ((length / h).ceil() as u32).max(1);
    if outer_auto && h_inner > GRADED_RATIO * h_outer {
        s.upper.elements_beyond_contact = fit(outer, h_inner).min(n_outer);
    } else if inner_auto && h_outer > GRADED_RATIO * h_inner {
        s.upper.elements_to_contact = fit(inner, h_outer).min(n_inner);
    }
}

/// The scenario as run and printed: `"auto"` element counts become the method's mesh (the
/// paper's 7 per segment, or the ladder's default rung), an `"auto"` cut-off the rung's.
pub fn printed(scenario: &Scenario) -> Result<Scenario> {
    match scenario.method {
        Method::Paper => {
            let mut s = scenario.clone();
            set_elements(&mut s, [PAPER_ELEMENTS; 3]);
            Ok(s)
        }
        Method::Converged => rung(scenario, DEFAULT_RUNG, 1),
    }
}

/// The discretisation a printed run is judged against: for the converged method the coarser rung
/// (the ladder's previous rung, or half of each explicit element count); for the paper method the
/// converged answer itself, with automatic steps (so its figure is the paper mesh's error).
pub fn check(scenario: &Scenario) -> Result<Scenario> {
    match scenario.method {
        Method::Paper => {
            let mut s = scenario.clone();
            s.method = Method::Converged;
            s.lower.elements = 0;
            s.upper.elements_to_contact = 0;
            s.upper.elements_beyond_contact = 0;
            s.modal_cutoff = 0.0;
            s.step_free = crate::model::TimeStep::Auto;
            s.step_contact = crate::model::TimeStep::Auto;
            printed(&s)
        }
        Method::Converged => rung(scenario, DEFAULT_RUNG - 1, 2),
    }
}

/// The rung before [`check`]'s (converged method only): the ladder's rung two below the printed
/// one, or a quarter of each explicit element count.
pub fn coarse(scenario: &Scenario) -> Result<Scenario> {
    rung(scenario, DEFAULT_RUNG - 2, 4)
}

/// The automatic cut-offs' multiplier: [`LIGHT_DAMPING_CUTOFF`] below a damping ratio of
/// [`crate::model::discretisation::LIGHT_DAMPING`], else 1. With little damping the modes above the paper mesh's
/// highest frequency still ring through the first sustained contact (measured at drop 0.3 m,
/// contact 13 m, damping 0.01: first-contact tau_a 1.3 % below the full basis at 1x, 0.2 % at 2x).
pub fn light_damping_factor(scenario: &Scenario) -> f64 {
    if scenario.damping_ratio < crate::model::discretisation::LIGHT_DAMPING {
        LIGHT_DAMPING_CUTOFF
    } else {
        1.0
    }
}

/// The automatic cut-offs' multiplier for lightly damped runs.
pub const LIGHT_DAMPING_CUTOFF: f64 = 2.0;

/// The ladder's rung `index` for `"auto"` fields; explicit element counts are divided by
/// `divisor` (rounded up) so that the check rung of an explicit mesh is half as fine.
fn rung(scenario: &Scenario, index: usize, divisor: u32) -> Result<Scenario> {
    let mut s = scenario.clone();
    let r = LADDER[index];
    let auto = [s.upper.elements_to_contact == 0, s.upper.elements_beyond_contact == 0];
    let at_end = s.contact_at_free_end();
    for count in [&mut s.lower.elements, &mut s.upper.elements_to_contact] {
        *count = if *count == 0 { r.elements } else { count.div_ceil(divisor) };
    }
    // Nothing lies beyond a contact at the bridge's free end.
    let beyond = &mut s.upper.elements_beyond_contact;
    *beyond = if at_end {
        0
    } else if *beyond == 0 {
        r.elements
    } else {
        beyond.div_ceil(divisor)
    };
    balance_segments(&mut s, auto);
    if s.modal_cutoff == 0.0 {
        s.validate()?;
        s.modal_cutoff = r.cutoff_factor * light_damping_factor(scenario) * reference_frequency(scenario)?;
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_resolves_to_the_ladder_and_explicit_counts_are_kept() {
        let s = Scenario::default();
        let p = printed(&s).unwrap();
        assert_eq!(p.lower.elements, LADDER[DEFAULT_RUNG].elements);
        assert!(p.modal_cutoff > 0.0);
        let c = check(&s).unwrap();
        assert_eq!(c.lower.elements, LADDER[DEFAULT_RUNG - 1].elements);
        let mut explicit = s.clone();
        explicit.lower.elements = 40;
        assert_eq!(printed(&explicit).unwrap().lower.elements, 40);
        assert_eq!(check(&explicit).unwrap().lower.elements, 20);
        assert_eq!(coarse(&explicit).unwrap().lower.elements, 10);
        let paper = Scenario::paper();
        assert_eq!(printed(&paper).unwrap(), paper);
        assert_eq!(check(&paper).unwrap().method, Method::Converged);
    }
}
