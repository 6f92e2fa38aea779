//! Dynamic amplification (issue 44 item 1, `src/amplification.rs`) against the closed form of a
//! rigid mass dropped onto a massless spring, in a limit of the beam model.
//!
//! **The closed form.** A mass M falling from rest through h onto a massless linear spring k and
//! staying on it: at the largest compression u_max it is at rest, so M g (h + u_max) =
//! k u_max^2 / 2, whose positive root over delta_st = M g / k is
//! DAF = u_max / delta_st = 1 + sqrt(1 + 2 h / delta_st): 2 at h = 0 (released at rest touching
//! the spring), 1 + sqrt(11) = 4.317 at 2 h / delta_st = 10, 1 + sqrt(101) = 11.05 at 100
//! (Timoshenko & Young, Elements of Strength of Materials, impact loading; Clough & Penzien,
//! Dynamics of Structures, the undamped single-degree-of-freedom system under a step load: 2).
//!
//! **The limit of the beam model.** A bridge far stiffer in bending than the spring (E I = 1e13
//! N m^2 on 29 m: its first flexible mode 2.9e4 rad/s, 400 times its pitching on the spring,
//! 71 rad/s) pitches as a rigid bar about its hinge; a contact spring k_c = 1e6 N/m; an arrestor
//! either rigid (`lower.kind = "rigid"`: the contact element alone is the spring) or a light stiff
//! cantilever (1 g, end stiffness k_a = 1e7 N/m: its first mode 2e5 rad/s; in series with the
//! contact, k = 1 / (1/k_c + 1/k_a)); no damping; the modal cut-off set at 2 000 rad/s, so that
//! every flexible mode of both beams is kept as its static response only (the massless springs of
//! the closed form) and the bridge's rigid pitching is the one dynamic coordinate.
//!
//! For a rigid bar of moment of inertia J about its hinge, its weight's moment about the hinge
//! m g x_g, and the spring at d from the hinge, the same energy argument holds at the contact
//! point: with the bar rotated by theta = u / d beyond touching, the weight works m g x_g u / d =
//! F_st u, F_st = m g x_g / d being the static contact force (moment balance), and the kinetic
//! energy at first touch is J omega_0^2 / 2 = M_r v^2 / 2 with M_r = J / d^2 and v = omega_0 d.
//! At the largest compression F_st (h + u_max) = k u_max^2 / 2 with the equivalent drop
//! h = M_r v^2 / (2 F_st) (for a bar falling from rest: the contact point's own drop d alpha_0,
//! since its kinetic energy is the work of its weight, F_st d alpha_0): the closed form with
//! delta_st = F_st / k. So 2 h / delta_st = M_r v^2 k / F_st^2, and the test states the impact by
//! omega_0 = v / d for each ratio. The contact force and the arrestor's end deflection (k_a times
//! its end force, quasi-static) and its clamp stresses all follow it.

use beam_impact::amplification::{self, Amplification};
use beam_impact::answer::{self, Options};
use beam_impact::model::scenario::SupportKind;
use beam_impact::model::TimeStep;
use beam_impact::record::NullRecorder;
use beam_impact::Scenario;

/// The contact spring, N/m.
const K_CONTACT: f64 = 1e6;
/// The light arrestor's end stiffness 3 E I / l^3, N/m.
const K_ARRESTOR: f64 = 1e7;

/// The stiff bridge on a spring, struck at 2 h / delta_st = `ratio`; `rigid`: the contact on a
/// rigid support, else on the light cantilever.
fn rigid_bridge_on_a_spring(ratio: f64, rigid: bool, damping_ratio: f64) -> Scenario {
    let mut s = Scenario { damping_ratio, duration: 0.06, modal_cutoff: 2000.0, ..Scenario::default() };
    s.upper.mass = 120.0;
    s.upper.elastic_modulus = 1e13;
    s.upper.second_moment = 1.0;
    s.contact.given_stiffness = Some(K_CONTACT);
    s.step_free = TimeStep::Auto;
    s.step_contact = TimeStep::Auto;
    if rigid {
        s.lower.kind = SupportKind::Rigid;
    } else {
        s.lower.mass = 1e-3;
        s.lower.tip_mass = 0.0;
        s.lower.second_moment = K_ARRESTOR * s.lower.length.powi(3) / (3.0 * s.lower.elastic_modulus);
    }
    let k = if rigid { K_CONTACT } else { 1.0 / (1.0 / K_CONTACT + 1.0 / K_ARRESTOR) };
    let (m, l, d, g) = (s.upper.mass, s.upper.length, s.contact_position, s.gravity);
    let static_force = m * g * (l / 2.0) / d;
    let reduced_mass = m * l * l / 3.0 / (d * d);
    let v = static_force * (ratio / (reduced_mass * k)).sqrt();
    s.drop_height = 0.0;
    s.impact_angular_velocity = Some(v / d);
    s
}

fn closed_form(ratio: f64) -> f64 {
    1.0 + (1.0 + ratio).sqrt()
}

fn amplification_of(s: &Scenario) -> Amplification {
    let a = answer::run(s, &mut NullRecorder, Options { sensitivity: false, ..Options::default() }).unwrap();
    amplification::amplification(&a).unwrap()
}

fn daf(a: &Amplification, name: &str) -> f64 {
    a.daf.iter().find(|(n, _)| n == name).and_then(|(_, v)| *v).unwrap_or(f64::NAN)
}

/// The closed-form table: 2 h / delta_st, the formula, the contact force's DAF on the rigid
/// support, the contact force's and the arrestor end deflection's on the light cantilever.
fn table() -> Vec<[f64; 5]> {
    [0.0, 10.0, 100.0]
        .iter()
        .map(|&ratio| {
            let rigid = amplification_of(&rigid_bridge_on_a_spring(ratio, true, 0.0));
            let beam = amplification_of(&rigid_bridge_on_a_spring(ratio, false, 0.0));
            // The energy method's spring on a rigid support is the contact: its DAF is the
            // closed form itself (to round-off).
            let energy = rigid.energy_method.daf.unwrap();
            assert!((energy / closed_form(ratio) - 1.0).abs() < 1e-9, "{ratio}: energy method {energy}");
            [
                ratio,
                closed_form(ratio),
                daf(&rigid, "contact.force"),
                daf(&beam, "contact.force"),
                daf(&beam, "lower.tip_deflection"),
            ]
        })
        .collect()
}

/// Within 0.1 % of 1 + sqrt(1 + 2 h / delta_st) (the issue asks 1 %; the limit's own departures,
/// the arrestor's mass 5e-6 of the bridge's reduced mass and the flexible modes' (71/2.9e4)^2 =
/// 6e-6, are far below 0.1 %, and the converged method's peaks are the cubic's extremes inside a
/// step: measured within 6e-5): 2.000, 4.317, 11.05. The table is printed (`--nocapture`) for
/// docs/amplification.md.
#[test]
fn a_rigid_bridge_dropped_on_a_massless_spring_amplifies_by_one_plus_sqrt_one_plus_2h_over_delta() {
    let rows = table();
    println!("2h/delta_st  formula   F_c rigid support   F_c light arrestor   w arrestor end");
    for r in &rows {
        println!("{:>11}  {:>7.3}  {:>18.4}  {:>19.4}  {:>15.4}", r[0], r[1], r[2], r[3], r[4]);
    }
    for r in &rows {
        for (k, got) in r[2..].iter().enumerate() {
            assert!((got / r[1] - 1.0).abs() < 1e-3, "2h/delta_st {}: column {k} DAF {got} against {}", r[0], r[1]);
        }
    }
    // The published values themselves, to their printed digits.
    assert!((closed_form(10.0) - 4.317).abs() < 5e-4 && (closed_form(100.0) - 11.05).abs() < 5e-3);
}

/// On the light cantilever the clamp's bending and shear stresses are its end force times l and
/// over A_s: they amplify as the contact force does (to 1 %).
#[test]
fn the_arrestors_clamp_stresses_amplify_as_its_end_force() {
    let a = amplification_of(&rigid_bridge_on_a_spring(10.0, false, 0.0));
    let force = daf(&a, "contact.force");
    for name in ["lower.clamp_bending_stress", "lower.clamp_shear_stress", "lower.bending_stress"] {
        assert!((daf(&a, name) / force - 1.0).abs() < 0.01, "{name}: {} against {force}", daf(&a, name));
    }
}

/// Over drop heights 0.1-2 m and damping ratios 0-0.05 on the paper's geometry: every DAF is at
/// least 1 (a dynamic peak includes the static state it oscillates about, before damping settles
/// it) and the static values do not depend on the drop (the same resting state).
#[test]
fn every_daf_is_at_least_one_and_the_static_values_do_not_depend_on_the_drop() {
    let mut statics: Option<Vec<(String, Option<f64>)>> = None;
    for drop in [0.1, 0.5, 2.0] {
        for damping in [0.0, 0.05] {
            let s = Scenario { drop_height: drop, damping_ratio: damping, duration: 0.6, ..Scenario::default() };
            let a = amplification_of(&s);
            for (name, d) in &a.daf {
                if let Some(d) = d {
                    assert!(*d >= 1.0, "drop {drop} m, damping {damping}: {name} DAF {d}");
                }
            }
            let r = a.static_response.as_ref().unwrap();
            let values: Vec<(String, Option<f64>)> =
                amplification::quantity_names().iter().map(|n| (n.to_string(), r.value(n))).collect();
            match &statics {
                None => statics = Some(values),
                Some(first) => assert_eq!(first, &values, "drop {drop} m, damping {damping}"),
            }
        }
    }
}

/// The static solve on scenarios at and beyond their fields' bounds (seeded random choices of
/// hostile literals for the fields it reads): a resting state with finite values, None with a
/// reason, or one line of error naming the field; never a panic. `BEAM_IMPACT_FUZZ_ITERATIONS`
/// sets the number of cases.
#[test]
fn the_static_solve_on_hostile_scenarios_gives_a_state_a_reason_or_one_line() {
    use crate::fuzz_support::{iterations, Rng};
    use beam_impact::model::contact_law::LawKind;
    use beam_impact::solver::static_contact::{static_outcome, StaticOutcome};
    const REALS: &[f64] =
        &[f64::NAN, f64::INFINITY, -1.0, 0.0, 1e-12, 1e-3, 0.5, 1.0, 3.0, 29.0, 1e6, 1e9, 1e13, 1e300];
    let mut rng = Rng(44);
    let (mut resting, mut not_resting, mut refused) = (0, 0, 0);
    for _ in 0..iterations(120) {
        let mut s = Scenario::default();
        for _ in 0..1 + rng.below(4) {
            let x = *rng.pick(REALS);
            match rng.below(12) {
                0 => s.gravity = x,
                1 => s.upper.tip_force = x * rng.pick(&[1.0, -1.0]),
                2 => s.lower.tip_force = x * rng.pick(&[1.0, -1.0]),
                3 => s.upper.mass = x,
                4 => s.upper.elastic_modulus = x,
                5 => s.lower.mass = x,
                6 => s.lower.second_moment = x,
                7 => s.contact.given_stiffness = Some(x),
                8 => s.contact.clearance = x,
                9 => {
                    s.contact.law = LawKind::Power;
                    s.contact.exponent = *rng.pick(&[0.0, 1.0, 1.5, 3.0, 3.5, x]);
                }
                10 => s.contact_position = x,
                _ => s.lower.kind = SupportKind::Rigid,
            }
        }
        s.lower.elements = 7;
        s.upper.elements_to_contact = 7;
        s.upper.elements_beyond_contact = if s.contact_at_free_end() { 0 } else { 7 };
        s.modal_cutoff = 1e3;
        match std::panic::catch_unwind(|| static_outcome(&s)) {
            Err(_) => panic!("the static solve panicked on {s:?}"),
            Ok(Ok(StaticOutcome::Resting(r))) => {
                resting += 1;
                assert!(r.peaks.as_array().iter().all(|v| v.is_finite()), "{:?} on {s:?}", r.peaks);
                assert!(r.peaks.contact_force > 0.0 && r.compression > 0.0, "{:?}", r.peaks);
            }
            Ok(Ok(StaticOutcome::NotResting(why))) => {
                not_resting += 1;
                assert!(!why.contains('\n') && why.contains("does not rest"), "{why}");
            }
            Ok(Err(e)) => {
                refused += 1;
                let line = e.to_string();
                assert!(!line.contains('\n') && line.len() < 1000, "{line}");
            }
        }
    }
    println!("resting {resting}, not resting {not_resting}, refused {refused}");
    assert!(resting > 0 && refused > 0, "resting {resting}, not resting {not_resting}, refused {refused}");
}
