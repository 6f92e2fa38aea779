//! Meshes whose element lengths differ by orders of magnitude (issue 28, item 6;
//! `src/solver/graded.rs`): a sub-millimetre overhang element beyond the contact node of the
//! 29 m bridge, a contact a centimetre from the hinge.
//!
//! Reproduced on main before the fix (`beam-impact run --set contact_position=... --set
//! upper.elements_beyond_contact=1`):
//! - 3 mm (28.997 m), either method: "natural modes: 1 rigid-body modes expected from the
//!   supports, but the lowest elastic eigenvalue omega^2 = 5.409e2 1/s^2 is not positive and
//!   above the largest taken as rigid, |omega^2| = 4.609e3 1/s^2";
//! - 1 mm (28.999 m), converged: "the step from t = 0.000000307 s (step 307) gives a non-finite
//!   state" (an automatic step of 1 ns, the floor, against omega_max = 1.1e11 rad/s: unstable);
//!   paper: 1 ns steps, "this run needs 500000000 steps" for 0.5 s;
//! - 0.1 mm (28.9999 m): "the lowest elastic eigenvalue omega^2 = -9.287e4 1/s^2 is not positive";
//! - 1 cm (28.99 m), converged: a cut-off following the overhang into 8 ns steps, 375 000 000
//!   steps for 3 s; a contact 1 cm from the hinge: 1 ns steps, 500 000 000 for 0.5 s.
//!
//! Closed forms: Euler-Bernoulli frequencies omega_n = (beta_n l / l)^2 sqrt(EI / m), beta_n l =
//! 3.9266, 7.0686, 10.2102, 13.3518 (hinged-free, elastic modes) and 1.8751, 4.6941, 7.8548,
//! 10.9955 (clamped-free) (Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1).

use beam_impact::model::mesh::{Mesh, Support};
use beam_impact::model::{Beam, Method, Model, Scenario, TimeStep};
use beam_impact::record::NullRecorder;
use beam_impact::solver::graded::{self, Grading, MAX_ELEMENT_RATIO};
use beam_impact::solver::{natural_modes, ModalSystem, StepPlan};
use beam_impact::Simulation;

/// The paper's bridge: EI = 210 GPa x 0.01831 m^4, 12 000 kg over 29 m.
const BRIDGE_EI: f64 = 210e9 * 0.01831;
/// The paper's arrestor: EI = 210 GPa x 0.002075 m^4, 10 124 kg over 12 m.
const ARRESTOR_EI: f64 = 210e9 * 0.002075;

const HINGED_FREE: [f64; 4] = [3.926_602_312, 7.068_582_746, 10.210_176_124, 13.351_768_778];
const CLAMPED_FREE: [f64; 4] = [1.875_104_069, 4.694_091_133, 7.854_757_438, 10.995_540_735];

fn equal(from: f64, to: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|i| from + (to - from) * i as f64 / n as f64).collect()
}

/// The largest relative error of the first four elastic frequencies of `omega` (from index
/// `first`) against the closed form `beta` for a beam of `length`, `ei`, `mass`.
fn worst_error(omega: &[f64], first: usize, beta: &[f64; 4], length: f64, ei: f64, mass: f64) -> f64 {
    let root = (ei / (mass / length)).sqrt();
    (0..4).map(|k| (omega[first + k] / ((beta[k] / length).powi(2) * root) - 1.0).abs()).fold(0.0, f64::max)
}

/// Source: the hinged-free closed form. Goal: the 29 m bridge meshed with 56 elements up to a
/// point h short of its end and one element of h beyond (h = 3 mm, 1 mm, 0.1 mm: 1/173 to
/// 1/5178 of the others) keeps its first four elastic frequencies within 1e-5 of the closed form,
/// where the ordinary solve lost them: off by 0.43 % at 3 mm, 0.02 % at 1 mm, and at 0.1 mm no
/// positive elastic eigenvalue at all. Tolerance 1e-5: the 56-element mesh's own discretisation
/// error (Hermite elements converge as h^4; measured 2.2e-6 on the fourth mode of the uniform
/// mesh), with a factor of 4 to spare; the overhang moves nothing beyond 1e-7.
#[test]
fn hinged_free_frequencies_with_a_tiny_overhang_match_the_closed_form() {
    let length = 29.0;
    for h in [3e-3, 1e-3, 1e-4] {
        let mut x = equal(0.0, length - h, 56);
        x.push(length);
        let beam = Beam::assemble(Mesh::new(&x, Support::Hinged), BRIDGE_EI, 12_000.0, 0.0, 9.81);
        let modes = graded::beam_modes(&beam, "the bridge").unwrap();
        assert_eq!(modes.omega[0], 0.0, "h = {h}: the rigid rotation about the hinge");
        let error = worst_error(modes.omega.as_slice(), 1, &HINGED_FREE, length, BRIDGE_EI, 12_000.0);
        assert!(error < 1e-5, "h = {h}: first four elastic frequencies off the closed form by {error:e}");
        // The ordinary solve on the same matrices: wrong or refused.
        match natural_modes(&beam.stiffness, &beam.mass, 1) {
            Ok(m) => {
                let old = worst_error(m.omega.as_slice(), 1, &HINGED_FREE, length, BRIDGE_EI, 12_000.0);
                assert!(old > 1e-4, "h = {h}: the ordinary solve was off by {old:e}");
            }
            Err(e) => assert!(e.to_string().contains("rigid-body modes expected"), "{e}"),
        }
    }
}

/// Source: the hinged-free closed form. Goal: a tiny element at the hinge (1 mm, then 56
/// elements of 0.52 m: a contact a millimetre from the hinge) keeps the first four elastic
/// frequencies within 1e-5 (the tolerance above: the 56 elements' discretisation error).
#[test]
fn hinged_free_frequencies_with_a_tiny_element_at_the_hinge_match_the_closed_form() {
    let length = 29.0;
    let mut x = vec![0.0];
    x.extend(equal(1e-3, length, 56));
    let beam = Beam::assemble(Mesh::new(&x, Support::Hinged), BRIDGE_EI, 12_000.0, 0.0, 9.81);
    let modes = graded::beam_modes(&beam, "the bridge").unwrap();
    assert_eq!(modes.omega[0], 0.0);
    let error = worst_error(modes.omega.as_slice(), 1, &HINGED_FREE, length, BRIDGE_EI, 12_000.0);
    assert!(error < 1e-5, "first four elastic frequencies off the closed form by {error:e}");
}

/// Source: the clamped-free closed form. Goal: the 12 m arrestor (no tip mass) with 56 elements
/// and a last element of 1 mm, then of 0.1 mm, keeps its first four frequencies within 1e-5 (the
/// 56 elements' discretisation error, as above), and has no rigid mode.
#[test]
fn cantilever_frequencies_with_a_tiny_tip_element_match_the_closed_form() {
    let length = 12.0;
    for h in [1e-3, 1e-4] {
        let mut x = equal(0.0, length - h, 56);
        x.push(length);
        let beam = Beam::assemble(Mesh::new(&x, Support::Clamped), ARRESTOR_EI, 10_124.0, 0.0, 9.81);
        let modes = graded::beam_modes(&beam, "the arrestor").unwrap();
        assert!(modes.omega[0] > 0.0);
        let error = worst_error(modes.omega.as_slice(), 0, &CLAMPED_FREE, length, ARRESTOR_EI, 10_124.0);
        assert!(error < 1e-5, "h = {h}: first four frequencies off the closed form by {error:e}");
    }
}

/// The modes of a graded beam are a complete M-orthonormal basis that diagonalises K: Phi^T M Phi
/// = I and Phi^T K Phi = diag(omega^2), to 1e-9 relative to the largest entry of each (the
/// short element's K entries reach EI/h^3 = 4e18 N/m at 1 mm: round-off of that size, relative).
#[test]
fn graded_modes_are_mass_normalised_and_diagonalise_stiffness() {
    let mut x = equal(0.0, 28.999, 14);
    x.push(29.0);
    let beam = Beam::assemble(Mesh::new(&x, Support::Hinged), BRIDGE_EI, 12_000.0, 0.0, 9.81);
    let modes = graded::beam_modes(&beam, "the bridge").unwrap();
    let n = beam.dofs();
    assert_eq!(modes.shapes.shape(), (n, n));
    let mm = modes.shapes.transpose() * &beam.mass * &modes.shapes;
    let identity = nalgebra::DMatrix::<f64>::identity(n, n);
    assert!((&mm - &identity).amax() < 1e-9, "Phi^T M Phi - I: {:e}", (mm - identity).amax());
    let kk = modes.shapes.transpose() * &beam.stiffness * &modes.shapes;
    let scale = modes.omega.amax().powi(2);
    for i in 0..n {
        for j in 0..n {
            let expected = if i == j { modes.omega[i].powi(2) } else { 0.0 };
            assert!((kk[(i, j)] - expected).abs() < 1e-9 * scale, "Phi^T K Phi [{i}, {j}] = {:e}", kk[(i, j)]);
        }
    }
}

/// The message refusing `s`'s run.
fn refusal(s: &Scenario) -> String {
    match Simulation::new(s) {
        Ok(_) => panic!("not refused"),
        Err(e) => e.to_string(),
    }
}

/// The scenario of the reproductions: the paper's beams (default scenario), the contact at
/// `contact` m on the 29 m bridge, one element beyond it, 0.2 s.
fn overhang(method: Method, contact: f64) -> Scenario {
    let mut s = Scenario { method, contact_position: contact, duration: 0.2, ..Scenario::default() };
    s.upper.elements_beyond_contact = 1;
    s
}

/// The reproductions with `method = "paper"` (7 + 7/1 elements): 3 mm and 1 mm overhangs now run
/// (stable, finite peaks, the bridge's first elastic frequency within 1e-4 of the closed form, the
/// 7 elements' own error: Table 2 holds the paper's mesh to 1 %, measured 2e-6 here), at a few
/// thousand steps for 0.2 s: the overhang's own two modes (1.1e10 and 1.1e11 rad/s at 1 mm) are
/// replaced by their static response, so the automatic step follows the 4.1 m elements. The
/// energy account closes within the scenario's tolerance.
#[test]
fn paper_method_runs_a_3_mm_and_a_1_mm_overhang() {
    for contact in [28.997, 28.999] {
        let s = overhang(Method::Paper, contact);
        let mut sim = Simulation::new(&s).unwrap();
        let modal = sim.modal().clone();
        let omega1 = (HINGED_FREE[0] / 29.0).powi(2) * (BRIDGE_EI / (12_000.0 / 29.0)).sqrt();
        assert!((modal.upper.omega[1] / omega1 - 1.0).abs() < 1e-4, "{contact}: {}", modal.upper.omega[1]);
        assert_eq!((modal.dofs(), modal.full_dofs), (29, 31), "{contact}: the overhang's two modes replaced");
        let summary = sim.run(&mut NullRecorder).unwrap();
        assert!(summary.steps < 20_000, "{contact}: {} steps", summary.steps);
        assert!(summary.peaks.as_array().iter().all(|p| p.is_finite()), "{contact}: {:?}", summary.peaks);
        assert!(summary.quality.trusted, "{contact}: {:?}", summary.quality.reasons);
    }
}

/// The paper's own fixed steps (5e-5 s out of contact, 2.5e-5 s in contact) are stable on the
/// 1 mm overhang: the stability check looks at the modes the run keeps.
#[test]
fn paper_steps_are_stable_with_a_1_mm_overhang() {
    let mut s = overhang(Method::Paper, 28.999);
    s.step_free = TimeStep::Fixed(5e-5);
    s.step_contact = TimeStep::Fixed(2.5e-5);
    let sim = Simulation::new(&s).unwrap();
    assert_eq!(sim.step_plan(), &StepPlan { free_ns: 50_000, contact_ns: 25_000 });
}

/// The converged method on the 1 mm and 3 mm overhangs (56 + 56/1 elements, checked by 28 + 28/1
/// and 14 + 14/1): the automatic cut-off comes from the paper mesh's longer elements and the
/// contact's own frequency (93 072 rad/s: 6 omega_c of a contact at the free end, issue 40), not
/// from the overhang (1.1e11 rad/s), so the steps are microseconds, where the run used to die at
/// step 307.
#[test]
fn converged_cutoff_and_steps_do_not_follow_the_overhang() {
    for contact in [28.997, 28.999] {
        let s = overhang(Method::Converged, contact);
        let sim = Simulation::new(&s).unwrap();
        let cutoff = sim.modal().cutoff.unwrap();
        // Far below the overhang's own modes; since issue 40 at least 6 times the contact's own
        // frequency (a contact 1-3 mm from the free end is the free-end case: 93 072 rad/s).
        assert!(cutoff < 1e5, "{contact}: cut-off {cutoff} rad/s");
        // The steps follow the kept modes (about 1 / the cut-off: 11 us), never the overhang's
        // 1.1e11 rad/s (tens of picoseconds, where the run used to die).
        let plan = sim.step_plan();
        assert!(plan.free_ns >= 10_000 && plan.contact_ns >= 10_000, "{contact}: {plan:?}");
        let resolved = sim.scenario();
        assert_eq!([resolved.upper.elements_to_contact, resolved.upper.elements_beyond_contact], [56, 1]);
    }
    // "auto" counts give the overhang one element too (not 56 of 18 um).
    let mut s = overhang(Method::Converged, 28.999);
    s.upper.elements_beyond_contact = 0;
    let resolved = beam_impact::discretise::printed(&s).unwrap();
    assert_eq!([resolved.upper.elements_to_contact, resolved.upper.elements_beyond_contact], [56, 1]);
    let check = beam_impact::discretise::check(&s).unwrap();
    assert_eq!([check.upper.elements_to_contact, check.upper.elements_beyond_contact], [28, 1]);
    let paper = beam_impact::discretise::printed(&Scenario { method: Method::Paper, ..s.clone() }).unwrap();
    assert_eq!([paper.upper.elements_to_contact, paper.upper.elements_beyond_contact], [7, 1]);
    // A contact in the span keeps the ladder's equal counts.
    let span = beam_impact::discretise::printed(&Scenario::default()).unwrap();
    assert_eq!([span.upper.elements_to_contact, span.upper.elements_beyond_contact], [56, 56]);
}

/// A contact 1 cm from the hinge (the paper method's 7 + 7/7 "auto" mesh becomes 7 + 1/7: one
/// 1 cm element, then 4.1 m ones) runs at the paper's step caps where it needed 500 000 000 steps
/// of 1 ns for 0.5 s.
#[test]
fn a_contact_a_centimetre_from_the_hinge_runs() {
    let s = Scenario { method: Method::Paper, contact_position: 0.01, drop_height: 0.3, ..Scenario::default() };
    let sim = Simulation::new(&s).unwrap();
    let resolved = sim.scenario();
    assert_eq!([resolved.upper.elements_to_contact, resolved.upper.elements_beyond_contact], [1, 7]);
    assert!(sim.step_plan().free_ns >= 10_000, "{:?}", sim.step_plan());
}

/// Source: the refusal rule of `src/solver/graded.rs`. Goal: a 0.1 mm overhang on the paper mesh
/// (1/41 428 of the 4.14 m elements, beyond [`MAX_ELEMENT_RATIO`]) is refused before any work with
/// one line naming the beam, the element (index, position, length), its ratio to the longest, the
/// limit and the shortest length allowed; with the converged method the refusal names the run
/// whose mesh it is (here the automatic cut-off's reference, the paper mesh).
#[test]
fn a_beam_beyond_the_supported_ratio_is_refused_naming_the_element() {
    let s = overhang(Method::Paper, 28.9999);
    let message = refusal(&s);
    assert!(message.starts_with("the bridge (upper): element 8") && !message.contains('\n'), "{message}");
    for part in [
        "the bridge (upper): element 8 of 8 (x = 28.999900 to 29.000000 m) is 1.0000e-4 m long, 1/41428 of the \
         longest (element 5, 4.1428 m)",
        "at most 1e4",
        "make it at least 4.1428e-4 m",
    ] {
        assert!(message.contains(part), "{part:?} missing from: {message}");
    }
    let converged = refusal(&overhang(Method::Converged, 28.9999));
    assert!(
        converged.starts_with("the automatic cut-off's reference mesh (7 + 7/1 elements): the bridge"),
        "{converged}"
    );
    // The ratio rule itself: an overhang at 0.99 and at 1.01 of the limit on the paper mesh.
    let beam = |fraction: f64| {
        let h = 29.0 / (7.0 * fraction * MAX_ELEMENT_RATIO + 1.0);
        let mut x = equal(0.0, 29.0 - h, 7);
        x.push(29.0);
        Beam::assemble(Mesh::new(&x, Support::Hinged), BRIDGE_EI, 12_000.0, 0.0, 9.81)
    };
    let (inside, outside) = (beam(0.99), beam(1.01));
    assert!(
        Grading::of(&inside.mesh).ratio() < MAX_ELEMENT_RATIO && Grading::of(&outside.mesh).ratio() > MAX_ELEMENT_RATIO
    );
    assert!(graded::beam_modes(&inside, "the bridge").is_ok());
    let message = graded::beam_modes(&outside, "the bridge").unwrap_err().to_string();
    assert!(message.starts_with("the bridge: element 8 of 8") && !message.contains('\n'), "{message}");
}

/// An automatic run that would need more steps than allowed is refused before it starts, naming
/// why: the stage, the frequency the automatic step follows and what owns it. Here a 16x finer
/// mesh with the converged cut-off above every mode (the full basis) against a limit of 1000 steps.
#[test]
fn an_automatic_run_needing_too_many_steps_is_refused_naming_why() {
    let mut s = Scenario { modal_cutoff: 1e12, duration: 1.0, ..Scenario::default() };
    s.lower.elements = 112;
    s.upper.elements_to_contact = 112;
    s.upper.elements_beyond_contact = 112;
    let sim = Simulation::new(&s).unwrap();
    let message = sim.check_step_count(s.duration_ns(), 1000).unwrap_err().to_string();
    assert!(!message.contains('\n'), "{message}");
    for part in
        ["duration must be at most 1000 steps", "the automatic step", "follows omega_max dt <= 1 with omega_max = "]
    {
        assert!(message.contains(part), "{part:?} missing from: {message}");
    }
    assert!(message.contains("highest kept mode") || message.contains("the contact bar"), "{message}");
}

/// An automatic step that would have to be below the stepper's 1 ns is refused before the run
/// (it used to be clamped to 1 ns and blow up): a 1 cm bridge on 7 + 7/7 elements, whose highest
/// mode is above 1e11 rad/s, is a uniform mesh (no short element to set aside) that no step can
/// follow.
#[test]
fn an_automatic_step_below_one_nanosecond_is_refused() {
    let mut s = Scenario { method: Method::Paper, contact_position: 0.005, drop_height: 0.001, ..Scenario::default() };
    s.upper.length = 0.01;
    let message = refusal(&s);
    assert!(!message.contains('\n'), "{message}");
    assert!(message.starts_with("step_free = \"auto\" cannot be stable: omega_max = "), "{message}");
    assert!(message.contains("below the 1 ns the stepper counts in"), "{message}");
}

/// Meshes that are not graded (longest / shortest element at most 10) keep the ordinary solve:
/// the paper's mesh and the converged rungs give the modes `natural_modes` gives, bit for bit.
#[test]
fn meshes_that_are_not_graded_keep_the_ordinary_solve_bit_for_bit() {
    for s in [Scenario::paper(), beam_impact::discretise::printed(&Scenario::default()).unwrap()] {
        let model = Model::new(&s).unwrap();
        let modal = ModalSystem::new(&model).unwrap();
        let upper = natural_modes(&model.upper.stiffness, &model.upper.mass, 1).unwrap();
        assert_eq!(modal.upper, upper);
        assert!(graded::spurious_limit(&model.upper).is_none() && graded::spurious_limit(&model.lower).is_none());
    }
}
