//! Issue 28: contact laws beyond the paper's bar: a power law F = k delta^n (Hertz, n = 3/2) and
//! Hunt and Crossley's damping F = k delta^n (1 + c delta'), solved as one scalar equation per
//! step. Checked against the dense oracle (to round-off), the linear bar (n = 1, c = 0: the same
//! run), Hertz's closed form for a rigid body, and the energy account.

use beam_impact::record::{NullRecorder, Recorder, RunInfo};
use beam_impact::results::{ContactEvent, StepResult};
use beam_impact::{Result, Scenario, Simulation};

/// A stiff hinged bar (first mode 5.4e3 rad/s) turning at 1 rad/s without gravity onto a rigid
/// support through the given `[contact]` table, at d = 1.5 m of its 2 m.
fn rigid_bar_onto(contact: &str, duration: f64) -> Scenario {
    let text = format!(
        "impact_angular_velocity = 1.0\ngravity = 0.0\ncontact_position = 1.5\ndamping_ratio = 0.0\nduration = {duration}\n\
         method = \"paper\"\n[upper]\nlength = 2.0\nmass = 10.0\nelastic_modulus = 1e10\nsecond_moment = 1e-3\n\
         section_modulus = 1e-3\nelements_to_contact = 12\nelements_beyond_contact = 4\n[lower]\nkind = \"rigid\"\n\
         [contact]\n{contact}"
    );
    Scenario::from_toml(&text, "bar").unwrap()
}

/// Hertz's impact of a rigid body (Johnson, Contact Mechanics, 1985, Sec. 11.4): a mass m at v0
/// on F = k delta^(3/2) compresses it to delta_max = (5 m v0^2 / (4 k))^(2/5), with the force
/// k delta_max^(3/2), for T = 2 (delta_max / v0) int_0^1 dx / sqrt(1 - x^(5/2)) = 2.9432 delta_max
/// / v0 (the integral Gamma(7/5) sqrt(pi) / Gamma(9/10) = 1.4716). The bar about its hinge is
/// m = I_h / d^2 at v0 = omega_0 d. Tolerance 0.1 %: the bar's flexibility (its first mode 13x
/// the contact's tangent frequency) moves both by (1/13)^2 / 20 ~ 3e-4; measured 2.0e-4 and 2.7e-4.
#[test]
fn a_rigid_bar_on_a_hertz_contact_follows_hertzs_closed_form() {
    let k = 1e7;
    let s = rigid_bar_onto(&format!("law = \"power\"\nexponent = 1.5\nstiffness = {k}\n"), 0.02);
    let summary = Simulation::new(&s).unwrap().run(&mut NullRecorder).unwrap();
    let inertia: f64 = 10.0 * 2.0 * 2.0 / 3.0;
    let (m, v0) = (inertia / 1.5f64.powi(2), 1.5);
    let delta_max = (5.0 * m * v0 * v0 / (4.0 * k)).powf(0.4);
    let force = k * delta_max.powf(1.5);
    // int_0^1 dx / sqrt(1 - x^(5/2)) by x = 1 - u^2 (removing the end's square-root singularity),
    // Simpson on 2e4 intervals.
    let integrand = |u: f64| {
        let x: f64 = 1.0 - u * u;
        if u == 0.0 {
            2.0 / 2.5f64.sqrt()
        } else {
            2.0 * u / (1.0 - x.powf(2.5)).sqrt()
        }
    };
    let n = 20_000;
    let h = 1.0 / n as f64;
    let integral: f64 = (0..n)
        .map(|i| {
            let u = i as f64 * h;
            h / 6.0 * (integrand(u) + 4.0 * integrand(u + 0.5 * h) + integrand(u + h))
        })
        .sum();
    assert!((integral - 1.47164).abs() < 1e-4, "{integral}");
    let duration = 2.0 * integral * delta_max / v0;
    let w = &summary.contact_windows[0];
    assert!(((w.end - w.start) - duration).abs() <= 1e-3 * duration, "{} s against {duration} s", w.end - w.start);
    assert!(
        (summary.peaks.contact_force - force).abs() <= 1e-3 * force,
        "{} N against {force} N",
        summary.peaks.contact_force
    );
    assert!(summary.quality.energy_residual_fraction < 1e-6, "{:?}", summary.quality);
}

/// The production stepper and the dense oracle of Eqs. (7)-(11) under a Hertz law with
/// Hunt-Crossley damping: the same steps and contact windows, every peak equal to 1e-8 (the same
/// scalar equation from round-off-close coefficients, over 1.1e5 steps; measured 2.8e-9 on the
/// bridge's stress, where the stiff bar's 5.4e3 rad/s mode rings through the contact).
#[test]
fn the_power_law_stepper_matches_the_dense_oracle_to_round_off() {
    let s = rigid_bar_onto("law = \"power\"\nexponent = 1.5\nstiffness = 1e7\ndamping = 0.3\n", 0.02);
    let fast = Simulation::new(&s).unwrap().run(&mut NullRecorder).unwrap();
    let dense = Simulation::new_dense(&s).unwrap().run(&mut NullRecorder).unwrap();
    assert_eq!(fast.steps, dense.steps);
    assert_eq!(fast.contact_windows, dense.contact_windows);
    for (x, y) in fast.peaks.as_array().into_iter().zip(dense.peaks.as_array()) {
        assert!((x - y).abs() <= 1e-8 * x.abs().max(1e-12), "{x} against {y}");
    }
    // On the arrestor beam too (the paper scenario with an elastomer-like law, 0.3 s): 1e-8, as
    // for the linear bar in tests/stepping.rs (contact changes located to the nanosecond move by
    // 1 ns where the two steppers' round-off differs at a crossing; measured 2.8e-9).
    let mut paper = Scenario { duration: 0.3, ..Scenario::paper() };
    paper.contact.law = beam_impact::model::contact_law::LawKind::Power;
    paper.contact.exponent = 1.3;
    paper.contact.given_stiffness = Some(5e8);
    paper.contact.area = 0.04;
    let fast = Simulation::new(&paper).unwrap().run(&mut NullRecorder).unwrap();
    let dense = Simulation::new_dense(&paper).unwrap().run(&mut NullRecorder).unwrap();
    for (x, y) in fast.peaks.as_array().into_iter().zip(dense.peaks.as_array()) {
        assert!((x - y).abs() <= 1e-8 * x.abs().max(1e-12), "{x} against {y}");
    }
}

/// A power law of exponent 1 without damping is the paper's bar: solved as a scalar equation it
/// gives the Sherman-Morrison run's peaks to 1e-9 on the paper scenario's first 0.5 s.
#[test]
fn a_power_law_of_exponent_one_is_the_linear_bar() {
    let linear = Scenario { duration: 0.5, ..Scenario::paper() };
    let mut power = linear.clone();
    power.contact.law = beam_impact::model::contact_law::LawKind::Power;
    power.contact.exponent = 1.0;
    power.contact.given_stiffness = Some(linear.contact.stiffness());
    let a = Simulation::new(&linear).unwrap().run(&mut NullRecorder).unwrap();
    let b = Simulation::new(&power).unwrap().run(&mut NullRecorder).unwrap();
    assert_eq!(a.contact_windows.len(), b.contact_windows.len());
    for (x, y) in a.peaks.as_array().into_iter().zip(b.peaks.as_array()) {
        assert!((x - y).abs() <= 1e-9 * x.abs(), "{x} against {y}");
    }
}

/// Records the contact events' relative velocities.
struct Events(Vec<f64>);

impl Recorder for Events {
    fn start(&mut self, _: &RunInfo<'_>) -> Result<()> {
        Ok(())
    }
    fn step(&mut self, _: &StepResult, _: &[f64]) -> Result<()> {
        Ok(())
    }
    fn contact_event(&mut self, event: &ContactEvent) -> Result<()> {
        self.0.push(event.relative_velocity);
        Ok(())
    }
    fn finish(&mut self) -> Result<()> {
        Ok(())
    }
}

/// Hunt and Crossley (1975): damping c = 3 (1 - e) / (2 v0) gives a coefficient of restitution
/// e for small 1 - e (their Eq. for the Hertz law; exact to first order in c v0). With e = 0.9
/// at v0 = 1.5 m/s (c = 0.1 s/m) the bar leaves the support at e v0 to 2 % (the first-order
/// relation's second-order error ~ (1 - e)^2 = 1 %), and the energy account, the contact's
/// dissipation booked, closes to 1e-4 of the impact's energy.
#[test]
fn hunt_crossley_damping_gives_its_restitution_and_the_energy_account_closes() {
    let (e, v0) = (0.9, 1.5);
    let c = 3.0 * (1.0 - e) / (2.0 * v0);
    let s = rigid_bar_onto(&format!("law = \"power\"\nexponent = 1.5\nstiffness = 1e7\ndamping = {c}\n"), 0.02);
    let mut sim = Simulation::new(&s).unwrap();
    let mut events = Events(Vec::new());
    let summary = sim.run(&mut events).unwrap();
    // The gap closes at -v0 (start) and opens at +e v0 (the end event's relative velocity).
    let leaving = events.0[1];
    assert!((leaving / v0 - e).abs() <= 0.02 * e, "restitution {} against {e}", leaving / v0);
    assert!(summary.quality.energy_residual_fraction < 1e-4, "{:?}", summary.quality);
    let last = sim.result().energy;
    let lost = 0.5 * (10.0 * 4.0 / 3.0) * (1.0 - (leaving / v0).powi(2));
    assert!((last.damping_dissipation - lost).abs() <= 1e-3 * lost, "{} J against {lost} J", last.damping_dissipation);
}

/// The new fields are refused out of range or contradictory, by name.
#[test]
fn bad_contact_laws_are_refused_by_name() {
    let cases = [
        ("[contact]\nlaw = \"power\"\n", "contact.stiffness must be given with contact.law = \"power\""),
        ("[contact]\nlaw = \"power\"\nstiffness = 1e9\nexponent = 4.0\n", "contact.exponent must be between 1 and 3"),
        ("[contact]\ndamping = -1.0\n", "contact.damping must be >= 0 s/m"),
        ("[contact]\nlaw = \"cubic\"\n", "unknown variant `cubic`"),
    ];
    for (text, expected) in cases {
        let e = Scenario::from_toml(text, "s.toml").unwrap_err().to_string();
        assert!(e.contains(expected), "{text:?}: {e}");
    }
}

/// Issue 40: a nonlinear law runs on the same truncated basis as the linear bar (its static
/// correction's residual flexibility in series with the law) and, in the converged method, with
/// the bar's exact steps (the force a cubic over each step, its end value and rate from the law),
/// and its peaks are those of the full basis under the linear acceleration method it used to need
/// (the paper method on the same mesh, automatic steps: omega_max dt <= 1 on the full basis's top
/// mode): the hertz-buffer example (n = 1.3, Hunt-Crossley c = 0.2), a Hertz law (n = 1.5) and a
/// linear law with damping (both with the buffer's 475 kN at 20 mm), on the check rung's mesh and
/// cut-off (28 elements a segment, modes up to 21 857 rad/s: 46 of 169 coordinates), over the
/// first sustained contact's peaks (0.4 s). Tolerance 1e-3, a tenth of the answer's
/// discretisation tolerance (1 %): the cut-off's own error (the discarded modes' dynamics), the
/// exact steps' force tolerance (1e-4 of the peak force a step) and the full basis's phase error;
/// measured at most 2.2e-4 (the Hertz law's clamp shear), the others below 7e-5.
#[test]
fn nonlinear_laws_on_the_truncated_basis_keep_the_full_bases_peaks() {
    use beam_impact::model::contact_law::LawKind;
    use beam_impact::model::{Method, TimeStep};
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/hertz-buffer.toml")).unwrap();
    let mut buffer = Scenario { duration: 0.4, ..Scenario::from_toml(&text, "hertz-buffer.toml").unwrap() };
    buffer.lower.elements = 28;
    buffer.upper.elements_to_contact = 28;
    buffer.upper.elements_beyond_contact = 28;
    buffer.modal_cutoff = 21857.0;
    let mut hertz = buffer.clone();
    hertz.contact.exponent = 1.5;
    hertz.contact.given_stiffness = Some(4.75e5 / 0.02f64.powf(1.5));
    hertz.contact.damping = 0.0;
    let mut damped_linear = buffer.clone();
    damped_linear.contact.law = LawKind::Linear;
    damped_linear.contact.exponent = 1.0;
    damped_linear.contact.given_stiffness = Some(4.75e5 / 0.02);
    for (name, s) in [("buffer", buffer), ("hertz", hertz), ("damped linear", damped_linear)] {
        let truncated_sim = Simulation::new(&s).unwrap();
        assert!(truncated_sim.modal().is_truncated(), "{name}: the truncated basis");
        let truncated = { truncated_sim }.run(&mut NullRecorder).unwrap();
        let full_basis = Scenario {
            method: Method::Paper,
            modal_cutoff: 0.0,
            step_free: TimeStep::Auto,
            step_contact: TimeStep::Auto,
            ..s.clone()
        };
        let full = Simulation::new(&full_basis).unwrap().run(&mut NullRecorder).unwrap();
        assert!(truncated.steps * 20 < full.steps, "{name}: {} steps against {}", truncated.steps, full.steps);
        for (x, y) in truncated.peaks.as_array().into_iter().zip(full.peaks.as_array()) {
            assert!((x - y).abs() <= 1e-3 * y.abs(), "{name}: {x} against the full basis's {y}");
        }
        assert!(truncated.quality.energy_residual_fraction < 1e-4, "{name}: {:?}", truncated.quality);
    }
}
