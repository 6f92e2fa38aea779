//! Resolves a scenario's `"auto"` discretisation into the meshes and modal cut-offs that are run:
//! the rung a run prints and the coarser rung its discretisation check compares it with
//! (see [`crate::model::discretisation`] for the ladder).

use crate::error::Result;
use crate::model::discretisation::{Method, DEFAULT_RUNG, LADDER, PAPER_ELEMENTS};
use crate::model::scenario::ImpactorKind;
use crate::model::{Model, Scenario};
use crate::solver::graded::GRADED_RATIO;
use crate::solver::{ModalCache, ModalSystem};

/// The scenario's reference frequency, rad/s: the highest natural frequency of either beam on the
/// paper's mesh (7 + 7/7 elements), the scale of the automatic cut-offs. A graded beam's short
/// elements' own modes (above its [`crate::solver::graded::spurious_limit`]) are not counted: the
/// cut-offs follow the frequencies of the mesh's longer elements, never those of a sub-millimetre
/// overhang.
pub fn reference_frequency(scenario: &Scenario) -> Result<f64> {
    Ok(reference_mesh(scenario)?.mesh)
}

/// What the automatic cut-offs scale with, rad/s, from the paper's mesh (7 + 7/7 elements):
/// `mesh`, its highest resolved frequency ([`reference_frequency`]); `contact`, the contact's own
/// frequency on it ([`contact_frequency`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceFrequencies {
    /// The highest natural frequency of either beam on the paper's mesh (its graded beams' short
    /// elements' own modes left out), rad/s.
    pub mesh: f64,
    /// The contact's own frequency sqrt(k_c / m_struck) on the paper's mesh, rad/s.
    pub contact: f64,
}

impl ReferenceFrequencies {
    /// The frequency the ladder's cut-off factors multiply, rad/s: the larger of the mesh's
    /// ([`light_damping_factor`] x `mesh`) and the contact's ([`CONTACT_CUTOFF`] x `contact`).
    pub fn automatic(&self, scenario: &Scenario) -> f64 {
        (light_damping_factor(scenario) * self.mesh).max(CONTACT_CUTOFF * self.contact)
    }
}

/// The paper mesh's [`ReferenceFrequencies`] of a scenario.
pub fn reference_mesh(scenario: &Scenario) -> Result<ReferenceFrequencies> {
    reference_mesh_with(scenario, None)
}

/// [`reference_mesh`] with the paper mesh's modes from `cache` (kept there by the first scenario
/// of its geometry, [`ModalCache::full_modes`]): the same frequencies to the bit, without an
/// eigen-solve per rung resolved (a campaign resolves three rungs an event, issue 43).
pub fn reference_mesh_with(scenario: &Scenario, cache: Option<&ModalCache>) -> Result<ReferenceFrequencies> {
    let mut coarse = scenario.clone();
    coarse.method = Method::Paper;
    set_elements(&mut coarse, [PAPER_ELEMENTS; 3]);
    let cache = cache.filter(|c| c.is_enabled());
    let compute = |model: &Model| {
        let modal = match cache {
            Some(cache) => cache.full_modes(model),
            None => ModalSystem::new(model).map(std::sync::Arc::new),
        }
        .map_err(|e| {
            crate::Error::Other(format!("the automatic cut-off's reference mesh ({}): {e}", describe(&coarse)))
        })?;
        let mesh = modal.resolved_omega_max(model);
        Ok((mesh, contact_frequency_of(model, &modal, mesh)))
    };
    // Kept by the cache by the reference mesh's model (its frequencies read nothing else).
    let (mesh, contact) = match cache {
        Some(cache) => cache.reference(&coarse, compute)?,
        None => compute(&Model::new(&coarse)?)?,
    };
    Ok(ReferenceFrequencies { mesh, contact })
}

/// The automatic cut-off at the printed rung as a multiple of the contact's own frequency
/// ([`contact_frequency`]). Measured on the contact at the bridge's free end (linear bar, struck
/// at 0.1 rad/s, no gravity; `free-end` in `tests/fixtures/converged_references.json`; omega_c =
/// 14 176 rad/s on 56 elements, 15 584 on the paper's mesh): the printed F_c against the full basis
/// on the same 56-element mesh is 9.3 % high at 0.86 omega_c (the mesh's cut-off alone, 12 131
/// rad/s), 4.1 % at 2, 1.8 % at 2.5, 0.59 % at 3, 0.13 % at 3.5 and 4, 0.03 % at 5, 0.07 % at 6,
/// 2e-3 % at 8. At 6 the printed rung is within 0.1 % and the check rung (3 omega_c) within
/// 0.6 %, converging faster than the figure's formal order 2 (0.59 -> 0.07 %, a factor 8 where
/// order 2 gives 4), so the figure, 0.42 of the change between them, bounds the printed error.
/// Every other fixture scenario's mesh cut-off is already above 6 omega_c (the paper scenario:
/// 43 713 rad/s, 6.4 omega_c; rigid support: 8.5; contact 10 m: 10.5), so their answers and cost
/// are unchanged.
pub const CONTACT_CUTOFF: f64 = 6.0;

/// The contact's own frequency, rad/s, on the mesh of `elements` per segment (`"auto"` counts only;
/// the full basis): omega_c = sqrt(k_c / m_struck(omega_c)), where k_c is the contact's rate (the
/// bar's, or a nonlinear law's largest tangent stiffness, as the coupled modes take it) and
/// m_struck(omega) = 1 / sum over the modes of both beams up to omega of (Phi^T b)_i^2, the struck
/// points' mass in series as the modes below omega see it (b the contact vector, the gap's
/// functional: the arrestor's and the bridge's point masses add as 1/m_a + 1/m_b). A point of a beam
/// has less mass the higher the frequency (the mass within a bending wavelength, ~ omega^-1/2): the
/// smallest fixed point of sqrt(k_c sum_{omega_i <= omega} c_i^2) = omega is where the contact's
/// spring rings against that mass. It is a property of the beams, not of the mesh (the free-end
/// scenario: 15 584 / 13 565 / 14 239 / 14 176 / 14 171 rad/s on 7 / 14 / 28 / 56 / 112 elements
/// per segment). Against a stiff contact at a light point (the bridge's free end) it is above what
/// the paper mesh's highest frequency is (14 176 against 12 131 rad/s); the paper scenario's is
/// 6 858 rad/s against 43 713.
pub fn contact_frequency(scenario: &Scenario, elements: u32) -> Result<f64> {
    let mut s = scenario.clone();
    s.method = Method::Paper;
    set_elements(&mut s, [elements; 3]);
    let model = Model::new(&s)?;
    let modal = ModalSystem::new(&model)?;
    Ok(contact_frequency_of(&model, &modal, modal.resolved_omega_max(&model)))
}

/// [`contact_frequency`] on a model's modes, those above `resolved` (a graded beam's short
/// elements' own) left out.
fn contact_frequency_of(model: &Model, modal: &ModalSystem, resolved: f64) -> f64 {
    let omega: Vec<f64> = modal.lower.omega.iter().chain(modal.upper.omega.iter()).copied().collect();
    let (omega, contact): (Vec<f64>, Vec<f64>) =
        omega.iter().zip(modal.contact.iter()).filter(|(w, _)| **w <= resolved).map(|(w, c)| (*w, *c)).unzip();
    struck_frequency(&omega, &contact, model.bar_stiffness)
}

/// The smallest fixed point of omega = sqrt(k sum_{omega_i <= omega} c_i^2) (see
/// [`contact_frequency`]): modes taken in ascending frequency until the next one lies above what
/// the ones taken ring at with the spring k.
pub fn struck_frequency(omega: &[f64], contact: &[f64], k: f64) -> f64 {
    let mut order: Vec<usize> = (0..omega.len()).collect();
    order.sort_by(|&a, &b| omega[a].total_cmp(&omega[b]));
    let mut sum = 0.0;
    for (j, &i) in order.iter().enumerate() {
        sum += contact[i] * contact[i];
        let ring = (k * sum).sqrt();
        match order.get(j + 1) {
            Some(&next) if omega[next] <= ring => {}
            _ => return ring.max(omega[i]),
        }
    }
    0.0
}

/// A resolved scenario's mesh as the tables print it: `7 + 7/1 elements`.
pub fn describe(s: &Scenario) -> String {
    let counts = [s.lower.elements, s.upper.elements_to_contact, s.upper.elements_beyond_contact];
    format!("{} elements", element_counts(s.upper.kind, counts))
}

/// A mesh's element counts (arrestor, bridge to and beyond the contact) as the tables print them:
/// `7 + 7/1`, or the arrestor's alone for a rigid impactor (issue 45), whose bridge counts mesh
/// nothing.
pub fn element_counts(kind: ImpactorKind, [lower, to_contact, beyond_contact]: [u32; 3]) -> String {
    match kind {
        ImpactorKind::Mass => lower.to_string(),
        ImpactorKind::Beam => format!("{lower} + {to_contact}/{beyond_contact}"),
    }
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
    printed_with(scenario, None)
}

/// [`printed`] with the reference mesh's modes from `cache` ([`reference_mesh_with`]): the same
/// scenario to the bit.
pub fn printed_with(scenario: &Scenario, cache: Option<&ModalCache>) -> Result<Scenario> {
    match scenario.method {
        Method::Paper => {
            let mut s = scenario.clone();
            set_elements(&mut s, [PAPER_ELEMENTS; 3]);
            Ok(s)
        }
        Method::Converged => rung(scenario, DEFAULT_RUNG, 1, cache),
    }
}

/// The discretisation a printed run is judged against: for the converged method the coarser rung
/// (the ladder's previous rung, or half of each explicit element count); for the paper method the
/// converged answer itself, with automatic steps (so its figure is the paper mesh's error).
pub fn check(scenario: &Scenario) -> Result<Scenario> {
    check_with(scenario, None)
}

/// [`check`] with the reference mesh's modes from `cache` ([`reference_mesh_with`]): the same
/// scenario to the bit.
pub fn check_with(scenario: &Scenario, cache: Option<&ModalCache>) -> Result<Scenario> {
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
            printed_with(&s, cache)
        }
        Method::Converged => rung(scenario, DEFAULT_RUNG - 1, 2, cache),
    }
}

/// The rung before [`check`]'s (converged method only): the ladder's rung two below the printed
/// one, or a quarter of each explicit element count.
pub fn coarse(scenario: &Scenario) -> Result<Scenario> {
    coarse_with(scenario, None)
}

/// [`coarse`] with the reference mesh's modes from `cache` ([`reference_mesh_with`]): the same
/// scenario to the bit.
pub fn coarse_with(scenario: &Scenario, cache: Option<&ModalCache>) -> Result<Scenario> {
    rung(scenario, DEFAULT_RUNG - 2, 4, cache)
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
/// `divisor` (rounded up) so that the check rung of an explicit mesh is half as fine; the reference
/// mesh's modes from `cache` if given.
fn rung(scenario: &Scenario, index: usize, divisor: u32, cache: Option<&ModalCache>) -> Result<Scenario> {
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
        s.modal_cutoff = r.cutoff_factor * reference_mesh_with(scenario, cache)?.automatic(scenario);
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

    /// Issue 43: the reference mesh's modes from a cache give every rung the uncached scenario to
    /// the bit (its cut-off's bits), whichever run's per-run fields (drop height, damping, a
    /// sea's instant) filled the cache; a second geometry gets its own entry and its own
    /// frequencies.
    #[test]
    fn rungs_resolved_through_a_cache_are_the_uncached_ones_to_the_bit() {
        let cache = ModalCache::default();
        let base = Scenario::default();
        let mut variants = Vec::new();
        for (h, zeta) in [(0.5, 0.02), (1.7, 0.005), (0.2, 0.05)] {
            variants.push(Scenario { drop_height: h, damping_ratio: zeta, ..base.clone() });
        }
        variants.push(Scenario { contact_position: 20.0, ..base.clone() });
        let bits = |r: ReferenceFrequencies| [r.mesh.to_bits(), r.contact.to_bits()];
        for s in &variants {
            assert_eq!(bits(reference_mesh_with(s, Some(&cache)).unwrap()), bits(reference_mesh(s).unwrap()));
            for (cached, fresh) in [
                (printed_with(s, Some(&cache)), printed(s)),
                (check_with(s, Some(&cache)), check(s)),
                (coarse_with(s, Some(&cache)), coarse(s)),
            ] {
                let (cached, fresh) = (cached.unwrap(), fresh.unwrap());
                assert_eq!(cached.modal_cutoff.to_bits(), fresh.modal_cutoff.to_bits());
                assert_eq!(format!("{cached:?}"), format!("{fresh:?}"));
            }
        }
        assert_eq!(cache.len(), 2, "one reference mesh per geometry");
        let other = reference_mesh_with(&variants[3], Some(&cache)).unwrap();
        assert_ne!(bits(other), bits(reference_mesh(&base).unwrap()));
    }

    /// A point mass m on a spring k: one rigid-body mode of modal amplitude 1/sqrt(m) at the
    /// contact, so the contact's frequency is sqrt(k/m) exactly; a second mode above it is left
    /// out, one below it joins the struck mass.
    #[test]
    fn the_struck_frequency_of_a_mass_on_a_spring_is_sqrt_k_over_m() {
        let (k, m) = (4.0e6_f64, 100.0_f64);
        let c = 1.0 / m.sqrt();
        // To round-off: c^2 k is k / m within a few ulps.
        let close = |got: f64, want: f64| assert!((got - want).abs() <= 1e-12 * want, "{got} vs {want}");
        close(struck_frequency(&[0.0], &[c], k), (k / m).sqrt());
        close(struck_frequency(&[0.0, 1e6], &[c, 1.0], k), (k / m).sqrt());
        close(struck_frequency(&[0.0, 10.0], &[c, c], k), (k * 2.0 / m).sqrt());
    }

    /// Issue 40 part 2: the contact at the bridge's free end rings at 14 176 rad/s (56 elements;
    /// 15 584 on the paper mesh), above the paper mesh's highest frequency (12 131): the printed
    /// rung's automatic cut-off is [`CONTACT_CUTOFF`] times the contact's; the paper scenario's
    /// (6 954 rad/s, 6.3 x below its mesh's 43 713) stays the mesh's.
    #[test]
    fn the_automatic_cut_off_follows_the_contact_where_it_rings_above_the_mesh() {
        let mut end = Scenario { contact_position: 29.0, ..Scenario::default() };
        end.upper.elements_beyond_contact = 0;
        let r = reference_mesh(&end).unwrap();
        assert!(r.contact > r.mesh, "{r:?}");
        assert!((r.contact / contact_frequency(&end, 56).unwrap() - 1.0).abs() < 0.15, "{r:?}");
        assert_eq!(printed(&end).unwrap().modal_cutoff, CONTACT_CUTOFF * r.contact);
        let paper = Scenario::default();
        let r = reference_mesh(&paper).unwrap();
        assert!(CONTACT_CUTOFF * r.contact < r.mesh, "{r:?}");
        assert_eq!(printed(&paper).unwrap().modal_cutoff, r.mesh);
    }
}
