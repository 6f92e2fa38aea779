//! Beams of sections (issue 30) against closed forms and an independent exact solution.
//!
//! References (`tests/fixtures/stepped_beam_references.json`, how each number was made in
//! `stepped_beam_references.md`):
//! - the static tip deflection and rotation of a stepped cantilever under a tip load, by the
//!   unit-load integral sum int (l - x)^2 / EI dx (any strength-of-materials text), in exact
//!   rational arithmetic;
//! - the natural frequencies of two-step cantilevers and of a three-section hinged-free beam, from
//!   the exact (transfer-matrix) frequency determinant of the Euler-Bernoulli equation with the
//!   matching conditions at each step, solved at 50 digits (an independent code; it reproduces the
//!   uniform beam's tabulated roots, Blevins Table 8-1, to all 9 printed digits). No published
//!   stepped-beam table could be verified from this machine (see the md): the exact solution
//!   stands in for one;
//! - a published table of a non-uniform cantilever: Mabie & Rogers' double-tapered beam (the
//!   reference of Code_Aster's SDLL09), the taper as 16 and 32 sections extrapolated.

use beam_impact::model::mesh::{Mesh, Support};
use beam_impact::model::section::{self, SectionSpec};
use beam_impact::model::{Method, Model, Scenario, TimeStep};
use beam_impact::solver::natural_modes;
use beam_impact::{Error, Simulation};
use serde_json::Value;

fn references() -> Value {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/stepped_beam_references.json"))
            .expect("the stepped beams' references");
    serde_json::from_str(&text).unwrap()
}

/// A symmetric section of `length` m with the beam's allowables (none of its own).
fn section_spec(
    length: f64,
    second_moment: f64,
    section_modulus: f64,
    shear_area: f64,
    mass_per_length: f64,
) -> SectionSpec {
    SectionSpec {
        length,
        second_moment,
        section_modulus,
        section_modulus_bottom: None,
        shear_area,
        mass_per_length,
        allowable_bending_stress: None,
        allowable_shear_stress: None,
    }
}

/// The sections of a reference case (mass per length 1 kg/m where it gives none).
fn sections(case: &Value) -> Vec<SectionSpec> {
    case["segments"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let length = s["length"].as_f64().unwrap();
            let second_moment = s["second_moment"].as_f64().unwrap();
            section_spec(length, second_moment, 0.01, 0.01, s["mass_per_length"].as_f64().unwrap_or(1.0))
        })
        .collect()
}

/// A paper-method scenario whose arrestor is `sections` (no tip mass), `elements` elements.
fn arrestor(sections: Vec<SectionSpec>, elastic_modulus: f64, elements: u32) -> Scenario {
    let mut s = Scenario::paper_mesh();
    let (length, mass) = section::totals(&sections);
    s.lower.length = length;
    s.lower.mass = mass;
    s.lower.second_moment = sections[0].second_moment;
    s.lower.section_modulus = sections[0].section_modulus;
    s.lower.shear_area = sections[0].shear_area;
    s.lower.elastic_modulus = elastic_modulus;
    s.lower.tip_mass = 0.0;
    s.lower.elements = elements;
    s.lower.sections = sections;
    s
}

/// Static tip load on stepped cantilevers: the Hermite element is exact at its nodes for nodal
/// loads, and the mesh has a node at every step, so the finite-element tip deflection and
/// rotation equal the closed form to round-off (1e-10: the stiffness solve's conditioning on the
/// stiff-bracket case, 1e-12 elsewhere, the references' own advice). The closed form of
/// `section::tip_flexibility` (the energy method's flexion, Eq. 29 for sections) agrees to 1e-13.
#[test]
fn stepped_cantilever_tip_deflection_matches_the_unit_load_integral() {
    for case in references()["static_tip_load"].as_array().unwrap() {
        let e = case["elastic_modulus"].as_f64().unwrap();
        let load = case["tip_load"].as_f64().unwrap();
        let expected = (case["tip_deflection"].as_f64().unwrap(), case["tip_rotation"].as_f64().unwrap());
        let scenario = arrestor(sections(case), e, 7);
        let model = Model::new(&scenario).unwrap();
        let beam = &model.lower;
        let tip = beam.mesh.tip();
        let mut f = nalgebra::DVector::zeros(beam.dofs());
        f[tip.w.unwrap()] = load;
        let u = beam.stiffness.clone().cholesky().unwrap().solve(&f);
        let (w, theta) = (u[tip.w.unwrap()], u[tip.theta.unwrap()]);
        let name = case["name"].as_str().unwrap();
        let tolerance = if name.contains("bracket") { 1e-10 } else { 1e-12 };
        assert!((w / expected.0 - 1.0).abs() < tolerance, "{name}: tip deflection {w} vs {}", expected.0);
        assert!((theta / expected.1 - 1.0).abs() < tolerance, "{name}: tip rotation {theta} vs {}", expected.1);
        // Every step has its node.
        let mut x = 0.0;
        for s in &scenario.lower.sections {
            x += s.length;
            assert!(beam.mesh.nodes.iter().any(|n| (n.x - x).abs() < 1e-12), "{name}: no node at the step {x}");
        }
        let flexibility = section::tip_flexibility(&scenario.lower_segments());
        assert!((load * flexibility / expected.0 - 1.0).abs() < 1e-13, "{name}: closed form {flexibility}");
    }
}

/// Natural frequencies of two-step cantilevers: 32 Hermite elements, first three modes within
/// 1e-4 of the exact solution (the references measured at most 5.7e-5 for mode 3 at 16 elements;
/// eigenvalues converge as h^4, so 32 elements is ~16x inside) and never below it (consistent mass
/// converges from above) by more than the dense eigen solver's round-off, eps (omega_max /
/// omega_1)^2 ~ 4e-9 relative at 32 elements (1e-8); any wrong element section moves them by
/// percents.
#[test]
fn two_step_cantilever_frequencies_match_the_exact_solution() {
    for case in references()["cantilever_frequencies"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let scenario = arrestor(sections(case), case["elastic_modulus"].as_f64().unwrap(), 32);
        let model = Model::new(&scenario).unwrap();
        let beam = &model.lower;
        let modes = natural_modes(&beam.stiffness, &beam.mass, 0).unwrap();
        for (n, exact) in case["omega"].as_array().unwrap().iter().enumerate() {
            let exact = exact.as_f64().unwrap();
            let rel = modes.omega[n] / exact - 1.0;
            assert!(
                rel < 1e-4 && rel > -1e-8,
                "{name} mode {}: FE {} vs exact {exact} ({rel:e})",
                n + 1,
                modes.omega[n]
            );
        }
    }
}

/// The bridge of three sections, hinged-free: one rigid mode, then the exact solution's three
/// (64 elements over 29 m, the same h^4 convergence: within 1e-4; round-off as above).
#[test]
fn three_section_hinged_free_frequencies_match_the_exact_solution() {
    for case in references()["hinged_free_frequencies"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let mut s = Scenario::paper_mesh();
        s.upper.sections = sections(case);
        let (length, mass) = section::totals(&s.upper.sections);
        s.upper.length = length;
        s.upper.mass = mass;
        s.upper.second_moment = s.upper.sections[0].second_moment;
        s.upper.section_modulus = s.upper.sections[0].section_modulus;
        s.upper.shear_area = s.upper.sections[0].shear_area;
        s.upper.elastic_modulus = case["elastic_modulus"].as_f64().unwrap();
        s.upper.elements_to_contact = 32;
        s.upper.elements_beyond_contact = 32;
        s.contact_position = 13.0;
        let model = Model::new(&s).unwrap();
        let beam = &model.upper;
        assert_eq!(beam.mesh.support, Support::Hinged);
        let modes = natural_modes(&beam.stiffness, &beam.mass, 1).unwrap();
        assert_eq!(modes.omega[0], 0.0, "{name}: the rigid rotation about the hinge");
        for (n, exact) in case["omega"].as_array().unwrap().iter().enumerate() {
            let exact = exact.as_f64().unwrap();
            let rel = modes.omega[n + 1] / exact - 1.0;
            assert!(
                rel < 1e-4 && rel > -1e-8,
                "{name} mode {}: FE {} vs exact {exact} ({rel:e})",
                n + 1,
                modes.omega[n + 1]
            );
        }
    }
}

/// A published table: the double-tapered cantilever of Mabie & Rogers, "Transverse vibrations of
/// double-tapered cantilever beams", J. Acoust. Soc. Am. 51 (1972) 1771-1774, the reference of
/// test SDLL09 of the French validation guide (VPCS, SFM/AFNOR 1990) and of Code_Aster's V2.02.009:
/// height and width both taper linearly from h0 = 4 h1, b0 = 4 b1 at the clamp to h1, b1 at the
/// free end, f_i = lambda_i h1 / (2 pi L^2) sqrt(E / (12 rho)), lambda = 23.289, 73.9, 165.23,
/// 299.7, 478.1 (beta = 4).
///
/// Our beams are piecewise uniform: the taper as 16 and as 32 sections (each slice's mid-length
/// section, 4 elements per slice: the elements' own error is below 1e-6), Richardson-extrapolated
/// at the stepping's second order (measured: the 16- and 32-section frequencies sit 0.5-1.1 % and
/// 0.14-0.27 % below the continuous taper). Tolerance 5e-4 relative: the table's own accuracy. An
/// independent Hermite code of the continuous taper (exact quadrature, 200 elements, numpy) gives
/// lambda = 23.2923, 73.919, 165.285, 299.780, 478.180: the published values sit 1.4e-4 to 3.3e-4
/// below it, and our extrapolation within 1.1e-4 of it. Clamping the wrong end gives lambda_1 = 1.88.
#[test]
fn a_double_tapered_cantilever_matches_the_published_frequencies() {
    const PUBLISHED: [f64; 5] = [23.289, 73.9, 165.23, 299.7, 478.1];
    let (length, e, rho) = (12.0, 2.1e11, 7800.0);
    let (h1, b1) = (0.1, 0.1);
    let frequencies = |slices: usize| -> Vec<f64> {
        let specs: Vec<SectionSpec> = (0..slices)
            .map(|k| {
                // From the clamp (x = 0, h0 = 4 h1) to the free end (h1), at the slice's middle.
                let s = (k as f64 + 0.5) / slices as f64;
                let (h, b) = (h1 * (4.0 - 3.0 * s), b1 * (4.0 - 3.0 * s));
                let second_moment = b * h * h * h / 12.0;
                section_spec(length / slices as f64, second_moment, second_moment / (0.5 * h), b * h, rho * b * h)
            })
            .collect();
        let scenario = arrestor(specs, e, 4 * slices as u32);
        let model = Model::new(&scenario).unwrap();
        let beam = &model.lower;
        natural_modes(&beam.stiffness, &beam.mass, 0).unwrap().omega.iter().take(5).copied().collect()
    };
    let (coarse, fine) = (frequencies(16), frequencies(32));
    let scale = h1 / (length * length) * (e / (12.0 * rho)).sqrt();
    for (n, published) in PUBLISHED.iter().enumerate() {
        let extrapolated = (4.0 * fine[n] - coarse[n]) / 3.0 / scale;
        let rel = extrapolated / published - 1.0;
        assert!(
            rel.abs() < 5e-4,
            "mode {}: lambda {extrapolated} (16 sections {}, 32 sections {}) vs published {published} ({rel:e})",
            n + 1,
            coarse[n] / scale,
            fine[n] / scale
        );
    }
}

/// A beam cut into identical sections is the uniform beam: the same mesh (nodes at the cuts
/// added) gives the same frequencies to 1e-9 and the same converged peaks to 1e-6 (the meshes
/// differ by the nodes at the cuts, the answer by its discretisation, far inside 1e-3).
#[test]
fn a_beam_of_identical_sections_is_the_uniform_beam() {
    let uniform = Scenario { duration: 0.3, ..Scenario::default() };
    let mut cut = uniform.clone();
    let l = &uniform.lower;
    let piece = |length: f64| section_spec(length, l.second_moment, l.section_modulus, l.shear_area, l.mass / l.length);
    cut.lower.sections = vec![piece(3.0), piece(9.0)];
    let a = beam_impact::answer::run(&uniform, &mut beam_impact::record::NullRecorder, Default::default()).unwrap();
    let b = beam_impact::answer::run(&cut, &mut beam_impact::record::NullRecorder, Default::default()).unwrap();
    for (k, (x, y)) in a.converged_peaks.as_array().into_iter().zip(b.converged_peaks.as_array()).enumerate() {
        assert!((x / y - 1.0).abs() < 1e-3, "peak {k}: uniform {x}, two identical sections {y}");
    }
}

/// The envelope holds the paper's two points as stations: on the paper's uniform beams its
/// maximum is the clamp's sigma_a and the contact node's sigma_b where it sits there (the same
/// functionals, raised by the same within-step peaks; to 1e-12, the round-off of summing the
/// modal products in another order); and nowhere along a beam is it below them.
#[test]
fn the_envelope_maximum_is_the_two_point_peaks_where_it_sits_at_them() {
    for s in [Scenario::paper(), Scenario { duration: 1.0, ..Scenario::default() }] {
        let mut simulation = Simulation::new(&s).unwrap();
        let summary = simulation.run(&mut beam_impact::record::NullRecorder).unwrap();
        let e = &summary.envelope;
        let [upper_bending, _, lower_bending, lower_shear] = e.peaks();
        let (upper_bending, lower_bending, lower_shear) =
            (upper_bending.unwrap(), lower_bending.unwrap(), lower_shear.unwrap());
        let p = &summary.peaks;
        let same = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-12;
        assert!(lower_bending.value >= p.lower_clamp_bending_stress);
        assert!(upper_bending.value >= p.upper_contact_bending_stress);
        assert!(lower_shear.value >= p.lower_clamp_shear_stress);
        if lower_bending.position == 0.0 {
            assert!(same(lower_bending.value, p.lower_clamp_bending_stress), "{:?}", s.method);
        }
        assert!(same(e.lower.bending.max[0], p.lower_clamp_bending_stress));
        assert!(same(e.lower.shear.max[0], p.lower_clamp_shear_stress));
        let contact = e.upper.bending.positions.iter().position(|x| *x == s.contact_position).unwrap();
        assert!(same(e.upper.bending.max[contact], p.upper_contact_bending_stress));
        if upper_bending.position == s.contact_position {
            assert!(same(upper_bending.value, p.upper_contact_bending_stress));
        }
        // Each station's time is within the run, each value finite.
        for env in [&e.lower.bending, &e.lower.shear, &e.upper.bending] {
            assert!(env.max.iter().all(|v| v.is_finite() && *v >= 0.0));
            assert!(env.times.iter().all(|t| *t >= 0.0 && *t <= s.duration));
        }
    }
}

/// Bad sections: one-line errors naming the section (1-based, from the support) and its field.
#[test]
fn bad_sections_are_refused_by_name() {
    let base = "[[lower.sections]]\nlength = 6.0\nsecond_moment = 0.002\nsection_modulus = 0.01\nshear_area = 0.01\nmass_per_length = 800.0\n";
    let message = |text: &str| Scenario::from_toml(text, "x.toml").unwrap_err().to_string();
    let second = |field: &str, value: &str| {
        let mut two = format!("{base}{base}");
        let at = two.rfind(&format!("\n{field} = ")).unwrap() + 1;
        let end = at + two[at..].find('\n').unwrap();
        two.replace_range(at..end, &format!("{field} = {value}"));
        message(&two)
    };
    let m = second("second_moment", "-1.0");
    assert!(m.contains("lower.sections[2].second_moment") && m.contains("-1"), "{m}");
    let m = second("length", "0.0");
    assert!(m.contains("lower.sections[2].length"), "{m}");
    let m = second("mass_per_length", "nan");
    assert!(m.contains("lower.sections[2].mass_per_length"), "{m}");
    // Shorter than the mesh can resolve beside the others.
    let m = second("length", "0.001");
    assert!(m.contains("lower.sections[2].length") && m.contains("resolve"), "{m}");
    // A given length or mass that disagrees with the sections.
    let m = message(&format!("[lower]\nlength = 13.0\n{base}{base}"));
    assert!(m.contains("lower.length") && m.contains("12"), "{m}");
    // More sections than the limit.
    let many: String = std::iter::repeat_n(base, section::MAX_SECTIONS + 1).collect();
    let m = message(&many);
    assert!(m.contains("lower.sections") && m.contains(&section::MAX_SECTIONS.to_string()), "{m}");
    // An unknown field.
    let m = message(&format!("{base}stiffness = 3.0\n"));
    assert!(m.contains("stiffness"), "{m}");
    // The contact off the bridge of sections.
    let bridge = "contact_position = 30.0\n[[upper.sections]]\nlength = 29.0\nsecond_moment = 0.018\nsection_modulus = 0.01\nshear_area = 0.01\nmass_per_length = 400.0\n";
    let m = message(bridge);
    assert!(m.contains("contact_position") && m.contains("29"), "{m}");
    // Each is one line.
    for m in [second("second_moment", "-1.0"), message(bridge)] {
        assert!(!m.contains('\n'), "{m}");
    }
    // `--set` of a field the sections fix.
    let mut s = Scenario::from_toml(&format!("{base}{base}"), "x.toml").unwrap();
    s.lower.second_moment = 0.003;
    assert!(matches!(s.validate(), Err(Error::InvalidParameter { ref name, .. }) if name == "lower.second_moment"));
}

/// The length and mass of a beam of sections follow from them (and the uniform fields take the
/// first section's), and the scenario's TOML reads back to the same scenario.
#[test]
fn a_beam_of_sections_states_its_length_and_mass_and_reads_back() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/tapered-arrestor.toml")).unwrap();
    let s = Scenario::from_toml(&text, "tapered-arrestor.toml").unwrap();
    assert_eq!(s.lower.length, 12.0);
    assert!((s.lower.mass - 4.0 * (980.0 + 843.7 + 700.0)).abs() < 1e-9);
    assert_eq!(s.lower.second_moment, 0.0030);
    let back = Scenario::from_toml(&s.to_toml(), "back.toml").unwrap();
    assert_eq!(back, s);
    // The converged method resolves a mesh with a node at each step.
    let resolved = beam_impact::discretise::printed(&s).unwrap();
    assert_eq!(resolved.method, Method::Converged);
    let model = Model::new(&resolved).unwrap();
    for x in [4.0, 8.0] {
        assert!(model.lower.mesh.nodes.iter().any(|n| n.x == x), "no node at {x}");
    }
    let _ = (TimeStep::Auto, Mesh::cantilever(1.0, 1));
}

/// The paper's three utilisations use the allowables of the sections where the stresses sit: the
/// clamp's first section for sigma_a and tau_a, and for sigma_b at a change of section the worse
/// side's |M| / (W allowable). Closed form: W 0.02 | 0.01 m^3 with allowables 300 | 500 MPa give
/// capacities W allowable 6 | 5 MN m, sigma_b = |M| / 0.01 and an effective allowable 5e6 / 0.01
/// = 500 MPa; allowables 500 | 300 MPa give 10 | 3 MN m, 300 MPa.
#[test]
fn paper_utilisations_use_the_allowables_of_the_sections_where_they_sit() {
    let u = Scenario::default().upper.clone();
    let piece = |length: f64, section_modulus: f64, allowable: f64| SectionSpec {
        allowable_bending_stress: Some(allowable),
        ..section_spec(length, u.second_moment, section_modulus, 0.01, u.mass / u.length)
    };
    let mut s = Scenario::default();
    let d = s.contact_position;
    s.upper.sections = vec![piece(d, 0.02, 300e6), piece(u.length - d, 0.01, 500e6)];
    assert_eq!(section::bending_check_at(&s.upper_segments(), d), (0.01, 500e6));
    s.upper.sections = vec![piece(d, 0.02, 500e6), piece(u.length - d, 0.01, 300e6)];
    assert_eq!(section::bending_check_at(&s.upper_segments(), d), (0.01, 300e6));
    // Inside a section: its own; the arrestor's first section's allowables at the clamp.
    assert_eq!(section::bending_check_at(&s.upper_segments(), d / 2.0), (0.02, 500e6));
    let l = s.lower.clone();
    s.lower.sections = vec![
        SectionSpec {
            allowable_bending_stress: Some(400e6),
            allowable_shear_stress: Some(200e6),
            ..section_spec(4.0, l.second_moment, l.section_modulus, l.shear_area, l.mass / l.length)
        },
        section_spec(l.length - 4.0, l.second_moment, l.section_modulus, l.shear_area, l.mass / l.length),
    ];
    s.lower.length = l.length;
    assert_eq!(s.paper_allowables(), [400e6, 200e6, 300e6]);
    // A uniform scenario keeps its beams' own fields.
    let paper = Scenario::default();
    assert_eq!(
        paper.paper_allowables(),
        [
            paper.lower.allowable_bending_stress,
            paper.lower.allowable_shear_stress,
            paper.upper.allowable_bending_stress
        ]
    );
}

/// A run that stops inside an internal step (durations off the step grid) prints peaks raised by
/// the step's first part up to the stop; the envelope's paper points are those very peaks, with
/// their times (helper-10's finding: 113.4 against 114.6 MPa at the clamp at 0.05 s before).
#[test]
fn a_run_stopping_inside_a_step_puts_its_printed_peaks_on_the_envelope() {
    for duration in [0.05, 0.0503, 0.4117, 1.01] {
        let s = Scenario { duration, ..Scenario::default() };
        let mut simulation = Simulation::new(&s).unwrap();
        let summary = simulation.run(&mut beam_impact::record::NullRecorder).unwrap();
        let (e, p, t) = (&summary.envelope, &summary.peaks, &summary.peak_times);
        assert_eq!(e.lower.bending.max[0], p.lower_clamp_bending_stress, "duration {duration}");
        assert_eq!(e.lower.bending.times[0], t.lower_clamp_bending_stress, "duration {duration}");
        assert_eq!(e.lower.shear.max[0], p.lower_clamp_shear_stress, "duration {duration}");
        let contact = e.upper.bending.positions.iter().position(|x| *x == s.contact_position).unwrap();
        assert!(e.upper.bending.max[contact] >= p.upper_contact_bending_stress);
        assert!((e.upper.bending.max[contact] / p.upper_contact_bending_stress - 1.0).abs() < 1e-12);
        for time in t.as_array() {
            assert!((0.0..=summary.time).contains(&time), "a peak time {time} s outside the run of {} s", summary.time);
        }
    }
}

/// Issue 40 (part 5) item 5: two sections whose bending stiffnesses differ by 1e12 failed at the
/// natural modes with "0 rigid-body modes expected ... the lowest elastic eigenvalue is not
/// positive", naming no section. Now the scenario is refused before any work, naming the
/// softest and the stiffest section with their EI and the ratio's limit; within it, accepted.
#[test]
fn sections_too_unlike_in_stiffness_are_refused_by_name() {
    let section = |second_moment: f64| {
        format!(
            "[[lower.sections]]\nlength = 6.0\nsecond_moment = {second_moment:e}\nsection_modulus = 0.01\n\
             shear_area = 0.01\nmass_per_length = 800.0\n"
        )
    };
    let text = format!("{}{}", section(1e-12), section(1.0));
    let message = Scenario::from_toml(&text, "x.toml").unwrap_err().to_string();
    for needle in ["lower.sections[1]", "lower.sections[2]", "2.1e-1 N m^2", "2.1e11 N m^2", "factor 1e12", "1e6"] {
        assert!(message.contains(needle), "{needle:?} in: {message}");
    }
    assert!(!message.contains('\n'), "{message}");
    // Either way round, on the bridge too.
    let bridge = format!(
        "contact_position = 13.0\n{}",
        format!("{}{}", section(1e-6), section(1e3)).replace("lower.", "upper.").replace("6.0", "14.5")
    );
    let message = Scenario::from_toml(&bridge, "x.toml").unwrap_err().to_string();
    assert!(message.contains("upper.sections[1]") && message.contains("upper.sections[2]"), "{message}");
    // Within the limit: accepted (a factor 1e5).
    assert!(Scenario::from_toml(&format!("{}{}", section(1e-2), section(1e3)), "x.toml").is_ok());
}
