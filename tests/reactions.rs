//! Support reactions and tip velocities (issue 8): the forces a system engineer couples the
//! platforms to. Each reaction is the support's row of the unconstrained equations of motion
//! (stiffness, damping, consistent mass, loads): R = k_s . q + c_s . q' + m_s . q'' - f_s, the
//! force (moment) the support exerts on the beam, up (counter-clockwise) positive.

use beam_impact::record::{MemoryRecorder, NullRecorder};
use beam_impact::results::StepResult;
use beam_impact::{Scenario, Simulation};

const G: f64 = 9.81;

/// A named accessor of one step result field.
type Field = (&'static str, fn(&StepResult) -> f64);

/// At t = 0 the arrestor rests in its self-weight deflection (Eq. 26): the clamp carries its
/// weight, (m_l + m_tip) g = 114 777 N, and the moment m_l g L / 2 + m_tip g L = 781 kN m, to
/// round-off (1e-9: the static rows of Hermite elements are exact for a uniform load).
#[test]
fn clamp_carries_the_arrestors_weight_at_rest() {
    let simulation = Simulation::new(&Scenario::paper()).unwrap();
    let r = simulation.result();
    let l = &simulation.scenario().lower;
    let force = (l.mass + l.tip_mass) * G;
    let moment = l.mass * G * l.length / 2.0 + l.tip_mass * G * l.length;
    assert!((r.lower_clamp_reaction_force / force - 1.0).abs() < 1e-9, "{} vs {force}", r.lower_clamp_reaction_force);
    assert!(
        (r.lower_clamp_reaction_moment / moment - 1.0).abs() < 1e-9,
        "{} vs {moment}",
        r.lower_clamp_reaction_moment
    );
    assert_eq!(r.lower_tip_velocity, 0.0);
    assert!(r.upper_tip_velocity < -5.0, "the bridge's end falls at l_u omega_u0: {}", r.upper_tip_velocity);
}

/// The bridge resting on the arrestor, its motion damped out (drop height 0, damping ratio 0.9,
/// 6 s): the contact force is what the lever gives, m_u g (l_u / 2) / d = 131.3 kN at d = 13 m;
/// the hinge carries m_u g minus that (-13.6 kN: it holds the bridge down); the clamp carries the
/// arrestor's weight plus the contact force, and hinge + clamp = the total weight 232.5 kN. Within
/// 1 % of the total weight, as the issue asks (what is left of the motion is far below it), at
/// two contact positions.
#[test]
fn reactions_at_rest_follow_the_lever_and_sum_to_the_total_weight() {
    for contact_position in [13.0, 15.0] {
        let scenario =
            Scenario { drop_height: 0.0, damping_ratio: 0.9, duration: 6.0, contact_position, ..Scenario::default() };
        let mut simulation = Simulation::new(&scenario).unwrap();
        simulation.run(&mut NullRecorder).unwrap();
        let r = simulation.output(); // the outputs at the stop time (inside a step: issue 15)
        let (u, l) = (&scenario.upper, &scenario.lower);
        let total = (u.mass + l.mass + l.tip_mass) * G;
        let contact = u.mass * G * (u.length / 2.0) / contact_position;
        let tolerance = 0.01 * total;
        assert!((-r.contact_force - contact).abs() < tolerance, "d = {contact_position}: {r:?}");
        assert!((r.upper_hinge_reaction_force - (u.mass * G - contact)).abs() < tolerance, "{r:?}");
        assert!((r.lower_clamp_reaction_force - ((l.mass + l.tip_mass) * G + contact)).abs() < tolerance, "{r:?}");
        assert!((r.upper_hinge_reaction_force + r.lower_clamp_reaction_force - total).abs() < tolerance, "{r:?}");
        let moment = l.mass * G * l.length / 2.0 + (l.tip_mass * G + contact) * l.length;
        assert!((r.lower_clamp_reaction_moment - moment).abs() < 0.01 * moment, "{r:?}");
        assert!(r.lower_tip_velocity.abs() < 1e-4 && r.upper_tip_velocity.abs() < 1e-4, "{r:?}");
    }
}

/// Through the impact the reactions carry inertia and damping: the production stepper (modal
/// rows) and the dense oracle (physical rows M Phi (Phi^T row)) agree at every step of 50 ms to
/// 1e-9 of the peak reaction (round-off of the two bases), and the clamp's dynamic force peak
/// exceeds the static one by far (the impact load).
#[test]
fn dynamic_reactions_agree_with_the_dense_oracle_through_the_impact() {
    let scenario = Scenario { duration: 0.05, ..Scenario::paper() };
    let (mut modal, mut dense) = (MemoryRecorder::default(), MemoryRecorder::default());
    Simulation::new(&scenario).unwrap().run(&mut modal).unwrap();
    Simulation::new_dense(&scenario).unwrap().run(&mut dense).unwrap();
    assert_eq!(modal.steps.len(), dense.steps.len());
    let scale =
        |f: fn(&beam_impact::results::StepResult) -> f64| modal.steps.iter().map(|r| f(r).abs()).fold(0.0, f64::max);
    let fields: [Field; 5] = [
        ("clamp force", |r| r.lower_clamp_reaction_force),
        ("clamp moment", |r| r.lower_clamp_reaction_moment),
        ("hinge force", |r| r.upper_hinge_reaction_force),
        ("lower tip velocity", |r| r.lower_tip_velocity),
        ("upper tip velocity", |r| r.upper_tip_velocity),
    ];
    for (name, f) in fields {
        let s = scale(f);
        for (a, b) in modal.steps.iter().zip(&dense.steps) {
            assert!((f(a) - f(b)).abs() <= 1e-9 * s, "{name} at {} ns: {} vs {}", a.time_ns, f(a), f(b));
        }
    }
    let static_force = (scenario.lower.mass + scenario.lower.tip_mass) * G;
    assert!(scale(fields[0].1) > 2.0 * static_force, "impact load {}", scale(fields[0].1));
}
