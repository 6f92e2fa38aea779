//! The energy method's spring on a beam of sections (issue 45): the struck beam's static point
//! flexibility at the contact, exact for a stepped beam on any of the four support conditions
//! ([`Supports::stepped_point_load`]), against the closed forms: a uniform beam on each support
//! condition (Roark, *Formulas for Stress and Strain*, 7th ed., Table 8.1: P L^3 / 48 EI
//! pinned-pinned and P L^3 / 192 EI clamped-clamped at midspan, and off-centre), and beams of two
//! sections against the unit-load (Maxwell-Mohr) integral worked by hand in each test's comment,
//! the redundant of the propped cantilever solved. The energy method takes that flexibility and
//! the first support's end forces, and the run's own finite elements agree with it.

use beam_impact::model::section::{self, SectionSpec, Segment};
use beam_impact::model::supports::Supports;
use beam_impact::model::Model;
use beam_impact::solver::energy_method::EnergyMethod;
use beam_impact::Scenario;

const ALL: [Supports; 4] =
    [Supports::ClampedFree, Supports::PinnedPinned, Supports::ClampedClamped, Supports::ClampedPinned];

/// A segment of bending stiffness `ei` over [start, end] (its other fields do not enter).
fn segment(start: f64, end: f64, ei: f64) -> Segment {
    Segment {
        start,
        end,
        bending_stiffness: ei,
        mass_per_length: 1.0,
        section_modulus: 1e-3,
        shear_area: 1e-2,
        allowable_bending_stress: 1.0,
        allowable_shear_stress: 0.0,
    }
}

/// Relative difference.
fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// A uniform beam cut into three equal segments of the same E I is the uniform beam: each
/// support condition's flexibility, first-support moment and shear against Roark's closed forms
/// (`Supports::point_load`) at midspan and at 0.3 L, and the midspan values against
/// P L^3 / 48 EI (pinned-pinned), P L^3 / 192 EI (clamped-clamped), 7 P L^3 / 768 EI
/// (clamped-pinned), P (L/2)^3 / 3 EI (clamped-free). The element is exact for point loads, so
/// only round-off separates them: 1e-10 (the solve's condition number on these 4-8 unknowns is
/// below 1e4; a wrong term of the stiffness matrix is off by O(1)).
#[test]
fn uniform_beams_stepped_solve_matches_roarks_closed_forms_on_every_support() {
    let (length, ei) = (6.0_f64, 2.0e7);
    let pieces = [segment(0.0, 2.0, ei), segment(2.0, 4.0, ei), segment(4.0, 6.0, ei)];
    for supports in ALL {
        for a in [0.5 * length, 0.3 * length, length] {
            if a == length && supports.has_far_support() {
                continue;
            }
            let fe = supports.stepped_point_load(&pieces, a);
            let closed = supports.point_load(ei, length, a);
            assert!(relative(fe.flexibility, closed.flexibility) < 1e-10, "{supports:?} at {a}: {fe:?} vs {closed:?}");
            assert!((fe.first_moment - closed.first_moment).abs() < 1e-10 * length, "{supports:?} at {a}: {fe:?}");
            assert!((fe.first_shear - closed.first_shear).abs() < 1e-10, "{supports:?} at {a}: {fe:?}");
        }
        let midspan = match supports {
            Supports::ClampedFree => (length / 2.0).powi(3) / (3.0 * ei),
            Supports::PinnedPinned => length.powi(3) / (48.0 * ei),
            Supports::ClampedClamped => length.powi(3) / (192.0 * ei),
            Supports::ClampedPinned => 7.0 * length.powi(3) / (768.0 * ei),
        };
        let fe = supports.stepped_point_load(&pieces, 0.5 * length);
        assert!(relative(fe.flexibility, midspan) < 1e-10, "{supports:?}: {} vs {midspan}", fe.flexibility);
    }
}

/// A simply supported beam of two sections, E I_1 on [0, L/2] and E I_2 on [L/2, L], loaded at
/// midspan. The bending moment of a unit load there is m(x) = x / 2 on the first half and
/// (L - x) / 2 on the second, so the unit-load integral is
///
/// ```text
/// delta = int_0^L m^2 / EI dx = int_0^{L/2} x^2 / (4 EI_1) dx + int_{L/2}^L (L - x)^2 / (4 EI_2) dx
///       = (L/2)^3 / 12 (1 / EI_1 + 1 / EI_2) = L^3 / 96 (1 / EI_1 + 1 / EI_2)
/// ```
///
/// (L^3 / 48 EI when EI_1 = EI_2). The pins carry no moment, each half the load. Tolerance 1e-10:
/// round-off only (see above).
#[test]
fn two_section_pinned_beam_matches_the_unit_load_integral() {
    let (length, ei1, ei2) = (8.0_f64, 3.0e7, 1.2e7);
    let pieces = [segment(0.0, 4.0, ei1), segment(4.0, 8.0, ei2)];
    let fe = Supports::PinnedPinned.stepped_point_load(&pieces, 4.0);
    let hand = length.powi(3) / 96.0 * (1.0 / ei1 + 1.0 / ei2);
    assert!(relative(fe.flexibility, hand) < 1e-10, "{} vs {hand}", fe.flexibility);
    assert!(fe.first_moment == 0.0 && (fe.first_shear - 0.5).abs() < 1e-10, "{fe:?}");
    // The uniform beam's closed form with the first section's E I (what the energy method took
    // before) is off by (1 + EI_1 / EI_2) / 2 = 1.75 here.
    let first_only = Supports::PinnedPinned.point_load(ei1, length, 4.0).flexibility;
    assert!(relative(fe.flexibility, first_only) > 0.7, "{} vs {first_only}", fe.flexibility);
}

/// A propped cantilever (clamped at 0, pinned at L) of two sections, E I_1 on [0, c] and E I_2
/// on [c, L], loaded at a, by the force method: released at the pin it is a cantilever, whose
/// unit-load integral for the deflection at b under a unit load at a is
///
/// ```text
/// g(b, a) = int_0^{min(a, b)} (b - x) (a - x) / EI(x) dx,
/// int (b - x)(a - x) dx = a b x - (a + b) x^2 / 2 + x^3 / 3      (per piece of constant EI)
/// ```
///
/// The pin's redundant R (up) closes the gap at L: R g(L, L) = g(L, a), so the deflection at a
/// is g(a, a) - R g(a, L) = g(a, a) - g(a, L)^2 / g(L, L), and the clamp's moment
/// |a - R L| and shear 1 - R. Tolerance 1e-10: round-off only.
#[test]
fn two_section_propped_cantilever_matches_the_unit_load_integral_with_its_redundant() {
    let (length, joint, ei1, ei2) = (10.0_f64, 4.0, 5.0e7, 2.0e7);
    let pieces = [segment(0.0, joint, ei1), segment(joint, length, ei2)];
    let primitive = |a: f64, b: f64, x: f64| a * b * x - (a + b) * x * x / 2.0 + x.powi(3) / 3.0;
    let g = |b: f64, a: f64| {
        let top = a.min(b);
        let first = (primitive(a, b, top.min(joint)) - primitive(a, b, 0.0)) / ei1;
        let second = if top > joint { (primitive(a, b, top) - primitive(a, b, joint)) / ei2 } else { 0.0 };
        first + second
    };
    for a in [2.5, 4.0, 7.0] {
        let redundant = g(length, a) / g(length, length);
        let hand = g(a, a) - g(a, length).powi(2) / g(length, length);
        let fe = Supports::ClampedPinned.stepped_point_load(&pieces, a);
        assert!(relative(fe.flexibility, hand) < 1e-10, "at {a}: {} vs {hand}", fe.flexibility);
        assert!(((fe.first_moment - (a - redundant * length).abs()) / a).abs() < 1e-10, "at {a}: {fe:?}");
        assert!((fe.first_shear - (1.0 - redundant)).abs() < 1e-10, "at {a}: {fe:?} vs R = {redundant}");
    }
}

/// A cantilever of sections at its free end: the stepped solve agrees with the tip's unit-load
/// sum the crate has used since issue 30 (`section::tip_flexibility`), to round-off.
#[test]
fn stepped_cantilever_tip_agrees_with_the_tip_flexibility_sum() {
    let pieces = [segment(0.0, 1.5, 9.0e7), segment(1.5, 3.0, 4.0e7), segment(3.0, 4.0, 1.0e7)];
    let fe = Supports::ClampedFree.stepped_point_load(&pieces, 4.0);
    let sum = section::tip_flexibility(&pieces);
    assert!(relative(fe.flexibility, sum) < 1e-10, "{} vs {sum}", fe.flexibility);
    assert!((fe.first_moment - 4.0).abs() < 1e-9 && (fe.first_shear - 1.0).abs() < 1e-10, "{fe:?}");
}

/// No segment, a load off the beam, NaN: NaN back, no panic.
#[test]
fn degenerate_stepped_input_gives_nan_not_a_panic() {
    let pieces = [segment(0.0, 2.0, 1.0e7)];
    for (segments, a) in [(&pieces[..0], 1.0), (&pieces[..], 0.0), (&pieces[..], 3.0), (&pieces[..], f64::NAN)] {
        assert!(Supports::PinnedPinned.stepped_point_load(segments, a).flexibility.is_nan());
    }
    let soft = [segment(0.0, 2.0, 0.0)];
    let r = Supports::ClampedFree.stepped_point_load(&soft, 2.0);
    assert!(!r.flexibility.is_finite(), "{r:?}");
}

/// A section of `length` m of the scenario's steel.
fn spec(length: f64, second_moment: f64, section_modulus: f64) -> SectionSpec {
    SectionSpec {
        length,
        second_moment,
        section_modulus,
        section_modulus_bottom: None,
        shear_area: 0.02,
        mass_per_length: 800.0,
        allowable_bending_stress: None,
        allowable_shear_stress: None,
    }
}

/// The energy method on a deck beam of two sections, pinned-pinned and struck at 0.4 L: its k_f is
/// 1 / the stepped beam's flexibility there, which the run's own finite-element stiffness (the
/// model's lower beam, 40 elements, a static solve of a unit load at the contact node) gives to
/// round-off; and its first-support stresses are F_din times that support's unit-load end forces
/// over the first section's modulus and shear area (0 bending at a pin).
#[test]
fn energy_method_on_a_beam_of_sections_takes_the_stepped_flexibility() {
    for supports in [Supports::PinnedPinned, Supports::ClampedClamped, Supports::ClampedPinned] {
        let mut s = Scenario::paper_mesh();
        s.lower.supports = supports;
        s.lower.tip_mass = 0.0;
        s.lower.elements = 40;
        s.lower.sections = vec![spec(5.0, 4.0e-4, 2.0e-3), spec(7.0, 1.5e-4, 1.0e-3)];
        let (length, mass) = section::totals(&s.lower.sections);
        s.lower.length = length;
        s.lower.mass = mass;
        s.lower.contact_position = 0.4 * length;
        s.lower.second_moment = 4.0e-4;
        s.lower.section_modulus = 2.0e-3;
        s.lower.shear_area = 0.02;
        s.validate().unwrap();
        let em = EnergyMethod::new(&s);
        let point = supports.stepped_point_load(&s.lower_segments(), 0.4 * length);
        assert!(relative(em.flexion_stiffness, 1.0 / point.flexibility) < 1e-12, "{supports:?}");
        // The run's finite elements: a unit load at the contact node of the model's struck beam.
        let model = Model::new(&s).unwrap();
        let node = model.lower_contact_node;
        let load = model.lower.deflection_functional(node);
        let u = model.lower.stiffness.clone().cholesky().unwrap().solve(&load);
        let fe = u[model.lower.mesh.nodes[node].w.unwrap()];
        println!(
            "{supports:?}: energy method flexibility {:.6e} m/N, the run's FE {fe:.6e} m/N, ratio {:.12}; first \
             section's E I alone (Roark) {:.6e} m/N",
            1.0 / em.flexion_stiffness,
            fe * em.flexion_stiffness,
            supports.point_load(s.lower.elastic_modulus * 4.0e-4, length, 0.4 * length).flexibility
        );
        assert!(
            relative(fe, 1.0 / em.flexion_stiffness) < 1e-9,
            "{supports:?}: {fe} vs {}",
            1.0 / em.flexion_stiffness
        );
        let expected_bending = em.force * point.first_moment / 2.0e-3;
        assert!(relative(em.clamp_bending_stress + 1.0, expected_bending + 1.0) < 1e-12, "{supports:?}");
        assert!(relative(em.clamp_shear_stress, em.force * point.first_shear / 0.02) < 1e-12, "{supports:?}");
        if supports == Supports::PinnedPinned {
            assert_eq!(em.clamp_bending_stress, 0.0);
        }
    }
}
