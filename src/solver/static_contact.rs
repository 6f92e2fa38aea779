//! The static contact solution (issue 44 item 1): the bridge resting on the arrestor under
//! gravity and the constant tip forces, the supports at rest, on the same model and mesh as a
//! run's printed rung. It is the denominator of the dynamic amplification factor
//! DAF = dynamic peak / static value of each design quantity, and the static part of a load
//! case's factored stress (gamma_static * static + gamma_dynamic * (peak - static)).
//!
//! The equations: K_0 u = f + P b, where K_0 is the two beams' stiffness without the contact
//! (paper Eq. 2), f the consistent self-weight and tip-mass loads (Eqs. 12-13) plus the tip
//! forces, b the gap's functional (the contact vector of Eq. 4: y_k,u - y_k,l = b . u) and
//! P >= 0 the contact's compression force, given by its law from the compression
//! delta = -(b . u + c) (c the contact's clearance, closed first: the bridge rotates down by c
//! before the contact acts, as in a run). The hinged bridge alone is a mechanism, so K_0 is
//! singular; with a reference rate k_r > 0 (`reference_rate`: about the rate the bridge rests at)
//! K_r = K_0 + k_r b b^T is positive definite (the full stiffness with a contact bar of rate k_r),
//! and with A = K_r^-1 f, B = K_r^-1 b, a = b . A, beta = b . B the one scalar contact equation is
//!
//! g(delta) = beta P(delta) + a + (delta + c) (1 - k_r beta) = 0,
//!
//! then u = A + (P + k_r s) B with s = b . u = -(delta + c). g rises monotonically (P' >= 0,
//! 1 - k_r beta >= 0 by Sherman-Morrison), so the root is unique where g(0) < 0; with g(0) >= 0
//! the loads lift the bridge off the arrestor (no resting state: `None` with the reason). For a
//! linear contact P = k delta it is one division; for a power law P = k delta^n Newton's method
//! on g (bracketed by bisection) to round-off. On the hinged-free bridge the contact force is
//! statically determinate (1 - k_r beta is round-off: P = -a / beta, the loads' moment about the
//! hinge over d), so the law only sets the compression; the same equation also holds for an
//! indeterminate support.
//!
//! A rigid support (`lower.kind = "rigid"`) has no DOF: the contact element alone carries P.
//! Every design quantity is recovered with the run's own functionals: the five probes of
//! [`crate::results::Peaks`] (clamp moment and shear of the first element, the bridge's contact
//! moment by the scenario's `stress_recovery`) and the envelope stations
//! ([`crate::model::stations`]), each element force k_e u_e over its section's modulus or shear
//! area, so DAF compares like with like.

use nalgebra::DVector;

use crate::discretise;
use crate::error::{Error, Result};
use crate::model::contact_law::ContactLaw;
use crate::model::{Model, Probe, Scenario};
use crate::results::{BeamEnvelope, EnvelopePeak, Peaks, StationEnvelope, StressEnvelope, ENVELOPE_PEAK_NAMES};

/// The static state of the bridge resting on the arrestor, per design quantity.
#[derive(Clone, Debug, PartialEq)]
pub struct StaticResponse {
    /// The five design quantities of [`Peaks`] as magnitudes |.| (what the run's peaks are the
    /// largest of): arrestor end deflection (m), clamp bending and shear stress (Pa), the
    /// bridge's bending stress at the contact (Pa), the contact force (N).
    pub peaks: Peaks,
    /// The same five with their signs (y up: a downward deflection is negative; stresses sagging
    /// positive; the contact force negative in compression, as a run's `contact_force`).
    pub signed: Peaks,
    /// The stress envelope of the static state along each beam (|stress| at each station, time 0).
    pub envelope: StressEnvelope,
    /// Each beam's largest |bending| and |shear| stress with its position, in the order of
    /// [`ENVELOPE_PEAK_NAMES`] (None: the beam has no such station).
    pub envelope_peaks: [Option<EnvelopePeak>; 4],
    /// The contact's compression delta beyond the clearance, m.
    pub compression: f64,
    /// The clearance closed before the contact acts, m (the scenario's `contact.clearance`).
    pub clearance: f64,
    /// The support reactions (clamp force N, clamp moment N m, hinge force N; up and
    /// counter-clockwise positive), in the order of [`Model::reactions`].
    pub reactions: [f64; 3],
    /// The arrestor's far support's force (N) and moment (N m) (issue 45, [`Model::far_reactions`]);
    /// 0 for the paper's free end.
    pub far_reactions: [f64; 2],
    /// The mesh it was solved on: arrestor elements, bridge elements to and beyond the contact.
    pub elements: [u32; 3],
    /// The displacement vector over the model's global DOFs, m (rad on rotations).
    pub displacements: DVector<f64>,
}

impl StaticResponse {
    /// The static value of a design quantity by the name `summary.peaks` uses in a run's JSON:
    /// the former field names (`lower_clamp_bending_stress`), the quantity names
    /// (`lower.clamp_bending_stress`) and the envelope peaks (`upper.bending_stress`, ...). None
    /// for an unknown name or an envelope peak the model has no station for. A sweep's `peak.`
    /// prefix (`peak.lower.clamp_bending_stress`) is accepted.
    pub fn value(&self, name: &str) -> Option<f64> {
        // A sweep's column name (`peak.contact.force`) names the same quantity.
        let name = name.strip_prefix("peak.").unwrap_or(name);
        let five = self.peaks.as_array();
        if let Some(k) = crate::vocabulary::PEAK_FIELDS.iter().position(|n| *n == name) {
            return Some(five[k]);
        }
        if let Some(k) = crate::vocabulary::PEAK_QUANTITIES.iter().position(|n| *n == name) {
            return Some(five[k]);
        }
        let k = ENVELOPE_PEAK_NAMES.iter().position(|n| *n == name)?;
        self.envelope_peaks[k].map(|p| p.value)
    }

    /// Every design quantity's name and static value, the five peaks (by their quantity names)
    /// then the envelope peaks that exist.
    pub fn values(&self) -> Vec<(&'static str, f64)> {
        let mut out: Vec<(&'static str, f64)> =
            crate::vocabulary::PEAK_QUANTITIES.iter().copied().zip(self.peaks.as_array()).collect();
        for (name, peak) in ENVELOPE_PEAK_NAMES.iter().zip(self.envelope_peaks) {
            if let Some(p) = peak {
                out.push((name, p.value));
            }
        }
        out
    }
}

/// The outcome of a static contact solve: the resting state, or why there is none.
#[derive(Clone, Debug, PartialEq)]
pub enum StaticOutcome {
    /// The bridge rests on the arrestor (the contact in compression).
    Resting(Box<StaticResponse>),
    /// The loads do not press the bridge onto the arrestor (gravity 0 without a tip force, an
    /// upward tip force that lifts it): the reason, one line with the numbers.
    NotResting(String),
}

/// The static response of `scenario` on its printed rung's mesh ([`discretise::printed`]
/// resolves `"auto"` the way a run does), or None when the bridge does not rest on the arrestor.
/// The public entry for DAF and load cases.
pub fn static_response(scenario: &Scenario) -> Result<Option<StaticResponse>> {
    Ok(match static_outcome(scenario)? {
        StaticOutcome::Resting(r) => Some(*r),
        StaticOutcome::NotResting(_) => None,
    })
}

/// [`static_response`] with the reason when there is no resting state.
pub fn static_outcome(scenario: &Scenario) -> Result<StaticOutcome> {
    let printed = discretise::printed(scenario)?;
    solve(&Model::new(&printed)?)
}

/// The static contact solution of an assembled model (see the module documentation).
pub fn solve(model: &Model) -> Result<StaticOutcome> {
    let s = &model.scenario;
    let b = model.contact_vector();
    let (upper_tip, lower_tip) = model.tip_force_vectors();
    let f = model.gravity_load() + upper_tip * s.upper.tip_force + lower_tip * s.lower.tip_force;
    let stiffness = model.stiffness();
    let k_r = reference_rate(model);
    let k = stiffness + &b * b.transpose() * k_r;
    let cholesky = k.cholesky().ok_or_else(|| {
        Error::Other(format!(
            "the static contact solution: the stiffness with the contact ({} DOFs, contact rate {k_r:e} N/m) is not \
             positive definite",
            model.dofs()
        ))
    })?;
    let a_vec = cholesky.solve(&f);
    let b_vec = cholesky.solve(&b);
    let (a, beta) = (b.dot(&a_vec), b.dot(&b_vec));
    let c = s.contact.clearance;
    let law = s.contact_law().unwrap_or(ContactLaw { stiffness: s.contact_stiffness(), exponent: 1.0, damping: 0.0 });
    let slack = 1.0 - k_r * beta;
    let g = |delta: f64| beta * law.elastic(delta) + a + (delta + c) * slack;
    let g0 = g(0.0);
    if g0 >= 0.0 || !g0.is_finite() {
        return Ok(StaticOutcome::NotResting(not_resting_reason(model, -a / beta)));
    }
    let delta = contact_root(&law, beta, g0, slack, &g);
    let force = law.elastic(delta);
    let gap = -(delta + c);
    let u = &a_vec + &b_vec * (force + k_r * gap);
    Ok(StaticOutcome::Resting(Box::new(recover(model, u, delta, force))))
}

/// The reference rate k_r, N/m: the arrestor's own end stiffness (its flexion's, as the energy
/// method takes it, [`crate::solver::EnergyMethod`]; a rigid support's: the contact's) or the
/// contact's rate, whichever is smaller: about the rate at which the bridge really rests, so that
/// A and B are deflections of the real state's size (a k_r far below it leaves them a huge rigid
/// rotation that u = A + (P + k_r s) B cancels; far above it, a = -P / k_r is a small difference
/// of two large deflections). Any k_r > 0 gives the same solution in exact arithmetic; on the
/// paper model P moved by round-off only (1.5e-8 of it here, 2.7e-8 with the contact's
/// 2.8e10 N/m), the Cholesky solve's own error (see the tests).
fn reference_rate(model: &Model) -> f64 {
    let own = crate::solver::EnergyMethod::new(&model.scenario).flexion_stiffness;
    if own > 0.0 && own.is_finite() {
        own.min(model.bar_stiffness)
    } else {
        model.bar_stiffness
    }
}

/// The root delta > 0 of the scalar contact equation g (rising, g(0) = `g0` < 0): Newton's
/// method from the determinate estimate P = -g(0) / beta, inside a bracket kept by bisection;
/// stops when the correction is below 4 ulp of delta.
fn contact_root(law: &ContactLaw, beta: f64, g0: f64, slack: f64, g: &dyn Fn(f64) -> f64) -> f64 {
    let inverse = |p: f64| libm::pow(p / law.stiffness, 1.0 / law.exponent);
    let mut delta = inverse(-g0 / beta);
    let (mut lo, mut hi) = (0.0_f64, f64::INFINITY);
    for _ in 0..200 {
        let value = g(delta);
        if value == 0.0 {
            return delta;
        }
        if value > 0.0 {
            hi = delta;
        } else {
            lo = delta;
        }
        // g'(delta) = beta n k delta^(n-1) + (1 - k_r beta).
        let slope = beta * law.exponent * law.elastic(delta) / delta + slack;
        let newton = delta - value / slope;
        let next = if newton > lo && newton < hi && newton.is_finite() {
            newton
        } else if hi.is_finite() {
            0.5 * (lo + hi)
        } else {
            2.0 * delta.max(f64::MIN_POSITIVE)
        };
        if (next - delta).abs() <= 4.0 * f64::EPSILON * delta {
            return next;
        }
        delta = next;
    }
    delta
}

/// Why the bridge does not rest: the force the contact would need (`would_be`, N, compression
/// positive), with the loads named.
fn not_resting_reason(model: &Model, would_be: f64) -> String {
    let s = &model.scenario;
    if s.gravity == 0.0 && s.upper.tip_force == 0.0 {
        return "the bridge does not rest on the arrestor: gravity = 0 and upper.tip_force = 0 N, nothing presses it \
                down (no static state to amplify)"
            .to_string();
    }
    format!(
        "the bridge does not rest on the arrestor: the loads about the hinge (gravity {} m/s^2, upper.tip_force {} N, \
         lower.tip_force {} N) would need a contact force of {:.6e} N, a pull (the contact only pushes)",
        s.gravity, s.upper.tip_force, s.lower.tip_force, -would_be
    )
}

/// Every design quantity of the static displacements `u` by the run's own recovery.
fn recover(model: &Model, u: DVector<f64>, compression: f64, force: f64) -> StaticResponse {
    let s = &model.scenario;
    let probe = |p: Probe| model.probes.row(p as usize).transpose().dot(&u);
    let signed = Peaks {
        lower_tip_deflection: probe(Probe::LowerTipDeflection),
        lower_clamp_bending_stress: probe(Probe::ClampMoment) / s.lower.section_modulus,
        lower_clamp_shear_stress: probe(Probe::ClampShear) / s.lower.shear_area,
        upper_contact_bending_stress: probe(Probe::UpperContactMoment) / model.contact_section_modulus,
        contact_force: -force,
    };
    let mut peaks = Peaks::default();
    peaks.raise(&signed.as_array());
    let values = model.station_rows() * &u;
    let stations: Vec<_> = model.stations.all().collect();
    let envelope_of = |range: std::ops::Range<usize>| StationEnvelope {
        positions: range.clone().map(|k| stations[k].x).collect(),
        max: range.clone().map(|k| (values[k] / stations[k].divisor).abs()).collect(),
        times: range.clone().map(|_| 0.0).collect(),
        allowable: range.map(|k| stations[k].allowable).collect(),
    };
    let (lb, ls) = (model.stations.lower.bending.len(), model.stations.lower.shear.len());
    let (ub, us) = (model.stations.upper.bending.len(), model.stations.upper.shear.len());
    let envelope = StressEnvelope {
        lower: BeamEnvelope { bending: envelope_of(0..lb), shear: envelope_of(lb..lb + ls) },
        upper: BeamEnvelope {
            bending: envelope_of(lb + ls..lb + ls + ub),
            shear: envelope_of(lb + ls + ub..lb + ls + ub + us),
        },
        sampled_every: 1,
    };
    let reactions = model.reactions().map(|r| r.stiffness.dot(&u) - r.load);
    let far_reactions = model.far_reactions().map(|r| r.stiffness.dot(&u) - r.load);
    StaticResponse {
        far_reactions,
        envelope_peaks: envelope.peaks(),
        envelope,
        peaks,
        signed,
        compression,
        clearance: s.contact.clearance,
        reactions,
        elements: [s.lower.elements, s.upper.elements_to_contact, s.upper.elements_beyond_contact],
        displacements: u,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::scenario::SupportKind;

    /// A uniform bridge of mass m on a contact at d: P = m g (l_u / 2) / d plus the tip force's
    /// moment F l_u / d, independent of the contact law and of the arrestor (the bridge on a
    /// hinge and one contact is statically determinate). Tolerance 1e-7: the Cholesky solve's
    /// backward error, eps |K| |u| (the fine mesh's element stiffnesses, ~1e13 N/m, times the
    /// bridge's 0.2 m rigid rotation at the contact), is 4e-8 of the loads on the paper model's
    /// 337 DOFs (measured: K_0 u - f - P b = 6e-4 N against 1.6e4 N; P within 2e-8).
    #[test]
    fn the_contact_force_is_the_bridges_moment_about_the_hinge_over_d() {
        let mut s = Scenario::default();
        s.upper.tip_force = -2.0e4;
        let r = static_response(&s).unwrap().unwrap();
        let (m, g, l, d) = (s.upper.mass, s.gravity, s.upper.length, s.contact_position);
        let want = (m * g * l / 2.0 - s.upper.tip_force * l) / d;
        assert!((r.peaks.contact_force / want - 1.0).abs() < 1e-7, "{} vs {want}", r.peaks.contact_force);
        // The same with a power law and with a rigid support.
        let mut power = s.clone();
        power.contact.law = crate::model::contact_law::LawKind::Power;
        power.contact.given_stiffness = Some(3e11); // within the rate bound of model::contact_range
        let p = static_response(&power).unwrap().unwrap();
        assert!((p.peaks.contact_force / want - 1.0).abs() < 1e-7, "{}", p.peaks.contact_force);
        assert!((law_force(&power, p.compression) / p.peaks.contact_force - 1.0).abs() < 1e-12);
        let mut rigid = s.clone();
        rigid.lower.kind = SupportKind::Rigid;
        let q = static_response(&rigid).unwrap().unwrap();
        assert!((q.peaks.contact_force / want - 1.0).abs() < 1e-7, "{}", q.peaks.contact_force);
        assert_eq!(q.peaks.lower_tip_deflection, 0.0);
    }

    fn law_force(s: &Scenario, delta: f64) -> f64 {
        s.contact_law().unwrap().elastic(delta)
    }

    /// The arrestor as a cantilever loaded at its end by P (its own weight made negligible,
    /// 1 kg against the bridge's 12 t): tip deflection P L^3 / (3 E I), clamp moment P L, clamp
    /// shear P (Hermite cubic elements are exact at the nodes for end loads). Tolerance 1e-6:
    /// the arrestor's remaining self-weight, q L^2 / 2 against P L, is 5e-7 of it.
    #[test]
    fn the_arrestor_is_a_cantilever_under_the_contact_force() {
        let mut s = Scenario::default();
        s.lower.mass = 1e-3;
        s.lower.tip_mass = 0.0;
        let r = static_response(&s).unwrap().unwrap();
        let l = &s.lower;
        let p = r.peaks.contact_force;
        let close = |got: f64, want: f64| assert!((got / want - 1.0).abs() < 1e-6, "{got} vs {want}");
        close(r.signed.lower_tip_deflection, -p * l.length.powi(3) / (3.0 * l.elastic_modulus * l.second_moment));
        close(r.peaks.lower_clamp_bending_stress, p * l.length / l.section_modulus);
        close(r.peaks.lower_clamp_shear_stress, p / l.shear_area);
        // The clamp's reactions carry it: force P up, moment P L counter-clockwise.
        close(r.reactions[0], p);
        close(r.reactions[1], p * l.length);
    }

    /// The reactions balance the loads: hinge + contact = the bridge's weight less its tip force;
    /// clamp = the contact force plus the arrestor's own weight and tip mass, less its tip force.
    /// Tolerance 1e-7 as above.
    #[test]
    fn the_static_reactions_balance_the_loads() {
        let mut s = Scenario::default();
        s.lower.tip_force = 1.0e4;
        s.upper.tip_force = -5.0e3;
        let r = static_response(&s).unwrap().unwrap();
        let p = r.peaks.contact_force;
        let bridge = s.upper.mass * s.gravity - s.upper.tip_force;
        assert!(((r.reactions[2] + p) / bridge - 1.0).abs() < 1e-7, "{:?} {p}", r.reactions);
        let arrestor = (s.lower.mass + s.lower.tip_mass) * s.gravity - s.lower.tip_force + p;
        assert!((r.reactions[0] / arrestor - 1.0).abs() < 1e-7, "{:?} {arrestor}", r.reactions);
    }

    /// A clearance is closed first: the same forces and stresses, the bridge's contact point
    /// lower by the clearance.
    #[test]
    fn a_clearance_closes_before_the_contact_acts() {
        let s = Scenario::default();
        let mut gap = s.clone();
        gap.contact.clearance = 0.01;
        let (a, b) = (static_response(&s).unwrap().unwrap(), static_response(&gap).unwrap().unwrap());
        assert!((a.peaks.contact_force / b.peaks.contact_force - 1.0).abs() < 1e-7);
        assert!((a.peaks.lower_clamp_bending_stress / b.peaks.lower_clamp_bending_stress - 1.0).abs() < 1e-7);
        assert_eq!(b.clearance, 0.01);
    }

    /// No resting state without a load pressing the bridge down, or with an upward tip force
    /// larger than the weight's moment: None, and the reason names the loads.
    #[test]
    fn a_bridge_that_does_not_press_on_the_arrestor_has_no_static_state() {
        let mut s =
            Scenario { gravity: 0.0, drop_height: 0.0, impact_angular_velocity: Some(0.1), ..Scenario::default() };
        assert_eq!(static_response(&s).unwrap(), None);
        match static_outcome(&s).unwrap() {
            StaticOutcome::NotResting(why) => assert!(why.contains("gravity = 0"), "{why}"),
            other => panic!("{other:?}"),
        }
        s.gravity = 9.81;
        s.impact_angular_velocity = None;
        s.drop_height = 0.5;
        s.upper.tip_force = 1.0e5;
        match static_outcome(&s).unwrap() {
            StaticOutcome::NotResting(why) => assert!(why.contains("a pull"), "{why}"),
            other => panic!("{other:?}"),
        }
    }

    /// The names `summary.peaks` uses: former, quantity and envelope names give the same values.
    #[test]
    fn values_are_found_by_the_run_documents_names() {
        let r = static_response(&Scenario::default()).unwrap().unwrap();
        assert_eq!(r.value("contact_force"), r.value("contact.force"));
        assert_eq!(r.value("peak.contact.force"), Some(r.peaks.contact_force));
        assert_eq!(r.value("lower.clamp_bending_stress"), Some(r.peaks.lower_clamp_bending_stress));
        assert!(r.value("lower.bending_stress").unwrap() >= r.peaks.lower_clamp_bending_stress * (1.0 - 1e-12));
        assert_eq!(r.value("upper.shear_stress"), None);
        assert_eq!(r.value("nonsense"), None);
    }
}
