//! Dynamic amplification (issue 44 item 1): per design quantity, DAF = the converged dynamic peak
//! over the static value of the same quantity with the bridge resting on the arrestor under the
//! same gravity and tip forces ([`crate::solver::static_contact`], the same model, mesh and stress
//! recovery). Beside it two estimates a designer meets in codes and hand calculations:
//!
//! - **the energy method** the paper already prints (Section 3, Eqs. 27-33,
//!   [`crate::solver::EnergyMethod`]): the arrestor as a spring k_f taking the drop's energy and
//!   the weight's further work. Its DAF is its force over its own static force W l_u / (2 d)
//!   (= its deflection over W l_u / (2 d k_f)): 1 + sqrt(1 + 2 h_c / delta_st) with h_c = 2 d h / l_u
//!   the contact point's drop, exactly the rigid-mass-on-a-massless-spring formula.
//! - **the crane-style factor** psi = 1 + v sqrt(k / (g W)), W = m g: the large-drop limit of that
//!   formula, 1 + sqrt(2 h / delta_st) with v^2 = 2 g h and delta_st = W / k, as hoist and
//!   buffer clauses write it (issue 44 states it as 1 + v sqrt(k / (g m)), which is in m^-1/2 s^-1
//!   times m/s unless m is read as the weight m g; the dimensionless form is used). Its inputs for
//!   this system: v, the contact point's closing speed at impact (omega_0 d, the run's
//!   `impact.closing_speed`: the speed the bridge brings to the contact); k, the arrestor's end
//!   stiffness in series with the contact's (the springs the bridge's momentum is stopped by;
//!   a rigid support: the contact's alone; a power law: its tangent at the static compression);
//!   m, the bridge's mass reduced to the contact point, J_hinge / d^2 (the bridge pitches about
//!   its hinge: its kinetic energy J omega^2 / 2 is m v^2 / 2 with that m, so the kinetic energy
//!   the contact must absorb is right); g, the scenario's gravity. With W = m g instead of the
//!   static contact force (m_u g l_u / (2 d) for a uniform bridge, 0.75 m g at d = 13 m on 29 m)
//!   psi is the code's estimate, not this model's; the DAF above is the model's.

use serde::Serialize;

use crate::answer::Answer;
use crate::error::Result;
use crate::model::scenario::SupportKind;
use crate::model::section;
use crate::model::Method;
use crate::results::ENVELOPE_PEAK_NAMES;
use crate::solver::static_contact::{self, StaticOutcome, StaticResponse};
use crate::vocabulary::PEAK_QUANTITIES;

/// A name and a value, in the order of the design quantities.
pub type Named = Vec<(String, Option<f64>)>;

/// The energy method's estimate as a DAF.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EnergyMethodDaf {
    /// Its dynamic force F_din = k_f w_din, N (Eq. 29).
    pub force: f64,
    /// Its static force, the weight's moment about the hinge over d, W l_u / (2 d), N.
    pub static_force: f64,
    /// F_din over it (also w_din over its static deflection): the energy method's DAF.
    pub daf: Option<f64>,
    /// The spring it takes, k_f, N/m (the arrestor's end stiffness; a rigid support's contact).
    pub stiffness: f64,
}

/// The crane-style factor psi = 1 + v sqrt(k / (g W)), W = m g, with its inputs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CranePsi {
    /// psi (None without gravity or mass).
    pub psi: Option<f64>,
    /// The contact point's closing speed at impact, m/s.
    pub v: f64,
    /// The arrestor's end stiffness in series with the contact's, N/m.
    pub k: f64,
    /// The arrestor's end stiffness, N/m (None: a rigid support).
    pub k_arrestor: Option<f64>,
    /// The contact's stiffness, N/m (a power law's tangent at the static compression).
    pub k_contact: f64,
    /// Gravity, m/s^2.
    pub g: f64,
    /// The bridge's mass reduced to the contact point, J_hinge / d^2, kg.
    pub m: f64,
    /// The bridge's moment of inertia about its hinge, kg m^2.
    pub j_hinge: f64,
    /// The contact's distance from the hinge, m.
    pub d: f64,
    /// What each input is.
    pub definitions: &'static str,
}

/// The dynamic amplification of one run.
#[derive(Clone, Debug, PartialEq)]
pub struct Amplification {
    /// The static state (None: the bridge does not rest on the arrestor).
    pub static_response: Option<StaticResponse>,
    /// Each design quantity's converged dynamic peak, by its quantity name.
    pub dynamic: Named,
    /// Each design quantity's DAF = dynamic / static (None: no static value, or a static 0).
    pub daf: Named,
    /// The energy method's DAF.
    pub energy_method: EnergyMethodDaf,
    /// The crane-style psi.
    pub crane_psi: CranePsi,
    /// What the numbers are, or why there is no static state.
    pub note: String,
    /// The striking body's name in the printed lines: `"bridge"`, or `"impactor"` for a rigid
    /// impactor (issue 45; [`crate::wording::Wording::striker`]).
    pub striker: &'static str,
}

/// The design quantities' names, in order: the five peaks' quantity names, then the envelope
/// peaks' ([`ENVELOPE_PEAK_NAMES`]).
pub fn quantity_names() -> Vec<&'static str> {
    PEAK_QUANTITIES.iter().chain(ENVELOPE_PEAK_NAMES.iter()).copied().collect()
}

/// The DAF of an answer: its converged peaks over the static solution on the mesh they come
/// from: the printed rung for the converged method; for the paper method, whose converged peaks
/// are the converged answer's beside its 7 + 7/7 mesh, that answer's rung
/// ([`crate::discretise::check`]; on the paper scenario the clamp shear's static value differs by
/// the first element's q l_e / 2, 3 % on 7 elements).
pub fn amplification(answer: &Answer) -> Result<Amplification> {
    let outcome = if answer.resolved.method == Method::Paper {
        static_contact::solve(&crate::model::Model::new(&crate::discretise::check(&answer.resolved)?)?)?
    } else {
        static_contact::static_outcome(&answer.resolved)?
    };
    Ok(of(answer, outcome))
}

/// The DAF of an answer with its static outcome already solved.
pub fn of(answer: &Answer, outcome: StaticOutcome) -> Amplification {
    let five = answer.converged_peaks.as_array();
    let dynamic: Vec<Option<f64>> =
        five.iter().map(|v| Some(*v)).chain(answer.envelope_peaks.iter().map(|p| p.map(|p| p.value))).collect();
    let names = quantity_names();
    let dynamic: Named = names.iter().map(|n| n.to_string()).zip(dynamic).collect();
    let striker = crate::wording::Wording::of(&answer.resolved).striker();
    let (static_response, note) = match outcome {
        StaticOutcome::Resting(r) => (
            Some(*r),
            format!(
                "DAF = the converged dynamic peak over the static value of the same quantity with the {striker} \
                 resting on the arrestor (same gravity, tip forces, mesh and stress recovery; clearance closed; \
                 supports at rest); an envelope peak's over the static envelope's largest value along the same beam \
                 (their positions may differ)"
            ),
        ),
        StaticOutcome::NotResting(why) => (None, why),
    };
    let daf: Named = dynamic
        .iter()
        .map(|(name, peak)| {
            let value = static_response.as_ref().and_then(|r| r.value(name));
            let ratio = match (peak, value) {
                (Some(p), Some(s)) if s > 0.0 => Some(p / s),
                _ => None,
            };
            (name.clone(), ratio)
        })
        .collect();
    let energy_method = energy_method_daf(answer);
    let crane_psi = crane_psi(answer, static_response.as_ref());
    Amplification { static_response, dynamic, daf, energy_method, crane_psi, note, striker }
}

/// The energy method's DAF of the answer's scenario (see the module documentation).
fn energy_method_daf(answer: &Answer) -> EnergyMethodDaf {
    let s = &answer.resolved;
    let e = &answer.summary.energy_method;
    let lever = if s.upper.sections.is_empty() {
        s.upper.length / 2.0
    } else {
        let (m, first, _) = section::mass_moments(&s.upper_segments());
        first / m
    };
    let mut static_force = s.upper.mass * s.gravity * lever / s.contact_position;
    // A rigid impactor (issue 45) rests with its whole weight on the contact.
    if s.upper.kind == crate::model::scenario::ImpactorKind::Mass {
        static_force = s.upper.mass * s.gravity;
    }
    EnergyMethodDaf {
        force: e.force,
        static_force,
        daf: (static_force > 0.0).then(|| e.force / static_force),
        stiffness: e.flexion_stiffness,
    }
}

/// The crane-style psi of the answer's scenario (see the module documentation).
fn crane_psi(answer: &Answer, resting: Option<&StaticResponse>) -> CranePsi {
    let s = &answer.resolved;
    let d = s.contact_position;
    let j_hinge = if s.upper.sections.is_empty() {
        s.upper.mass * s.upper.length * s.upper.length / 3.0
    } else {
        section::mass_moments(&s.upper_segments()).2
    };
    // A rigid impactor (issue 45) strikes with its whole mass.
    let m = if s.upper.kind == crate::model::scenario::ImpactorKind::Mass { s.upper.mass } else { j_hinge / (d * d) };
    // Issue 45: the struck beam's point stiffness at the contact, the energy method's own (a beam
    // of sections on any supports by its exact stepped solution).
    let k_arrestor = (s.lower.kind == SupportKind::Beam).then(|| crate::solver::energy_method::arrestor_stiffness(s));
    let k_contact = match (s.contact_law(), resting) {
        (Some(law), Some(r)) if law.exponent != 1.0 => law.exponent * law.elastic(r.compression) / r.compression,
        (Some(law), None) if law.exponent != 1.0 => crate::model::system::contact_rate(s),
        _ => s.contact_stiffness(),
    };
    let k = match k_arrestor {
        Some(ka) => 1.0 / (1.0 / ka + 1.0 / k_contact),
        None => k_contact,
    };
    let v = answer.summary.impact.closing_speed.abs();
    let g = s.gravity;
    let psi = (g > 0.0 && m > 0.0 && k.is_finite()).then(|| psi(v, k, g, m));
    CranePsi {
        psi,
        v,
        k,
        k_arrestor,
        k_contact,
        g,
        m,
        j_hinge,
        d,
        definitions: "psi = 1 + v sqrt(k / (g W)), W = m g (= 1 + (v / g) sqrt(k / m)); v: the contact point's \
                      closing speed at impact, m/s; k: the arrestor's end stiffness in series with the contact's, N/m \
                      (a rigid support: the contact's; a power law: its tangent at the static compression); m: the \
                      bridge's mass reduced to the contact point, J_hinge / d^2, kg; g: gravity, m/s^2",
    }
}

/// The crane-style factor psi = 1 + v sqrt(k / (g W)), W = m g: closing speed `v` (m/s), spring
/// `k` (N/m), gravity `g` (m/s^2), mass `m` (kg).
pub fn psi(v: f64, k: f64, g: f64, m: f64) -> f64 {
    1.0 + v * (k / (g * m * g)).sqrt()
}

impl Amplification {
    /// The `dynamic_amplification` block of `run --json` and `answer.json`:
    /// `{static: {name: value}, static_positions, daf: {name: value}, energy_method, crane_psi, note}`.
    pub fn to_json(&self) -> serde_json::Value {
        let map = |named: &Named| {
            serde_json::Value::Object(named.iter().map(|(n, v)| (n.clone(), serde_json::json!(v))).collect())
        };
        let names = quantity_names();
        let statics: Named =
            names.iter().map(|n| (n.to_string(), self.static_response.as_ref().and_then(|r| r.value(n)))).collect();
        let positions: serde_json::Map<String, serde_json::Value> = ENVELOPE_PEAK_NAMES
            .iter()
            .enumerate()
            .map(|(k, n)| {
                let p = self.static_response.as_ref().and_then(|r| r.envelope_peaks[k]).map(|p| p.position);
                (n.to_string(), serde_json::json!(p))
            })
            .collect();
        serde_json::json!({
            "static": map(&statics),
            "static_positions": positions,
            "static_compression": self.static_response.as_ref().map(|r| r.compression),
            "daf": map(&self.daf),
            "energy_method": self.energy_method,
            "crane_psi": self.crane_psi,
            "note": self.note,
            "units": {
                "static": "the quantity's own: m (tip_deflection), Pa (*_stress), N (force)",
                "static_positions": "m from the beam's support", "static_compression": "m",
                "daf, energy_method.daf, crane_psi.psi": "1",
                "energy_method.force, energy_method.static_force": "N",
                "energy_method.stiffness, crane_psi.k, crane_psi.k_arrestor, crane_psi.k_contact": "N/m",
                "crane_psi.v": "m/s", "crane_psi.g": "m/s^2", "crane_psi.m": "kg", "crane_psi.j_hinge": "kg m^2",
                "crane_psi.d": "m"
            },
        })
    }

    /// Lines for `run`'s printed text: the DAF per quantity, the energy method's and psi.
    pub fn lines(&self) -> String {
        let Some(_) = &self.static_response else {
            return format!("dynamic amplification: none ({})\n", self.note);
        };
        let shown: Vec<String> =
            self.daf.iter().filter_map(|(name, daf)| daf.map(|d| format!("{name} {d:.3}"))).collect::<Vec<_>>();
        let striker = self.striker;
        let mut text =
            format!("dynamic amplification (peak / static, {striker} resting on the arrestor): {}\n", shown.join(", "));
        let em = self.energy_method.daf.map_or("-".to_string(), |d| format!("{d:.3}"));
        let psi = self.crane_psi.psi.map_or("-".to_string(), |p| format!("{p:.3}"));
        let c = &self.crane_psi;
        text += &format!(
            "  energy method's DAF {em}; crane-style psi = 1 + (v / g) sqrt(k / m) = {psi} (v {:.4} m/s closing \
             speed, k {:.4e} N/m arrestor and contact in series, m {:.1} kg {} g {} m/s^2)\n",
            c.v,
            c.k,
            c.m,
            if self.striker == "impactor" { "impactor," } else { "bridge reduced to the contact," },
            c.g
        );
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// psi is the large-drop limit of a mass m dropped from h onto a spring k: with v^2 = 2 g h
    /// and delta_st = m g / k, psi - 1 = sqrt(2 h / delta_st) exactly (to round-off, 1e-12). It
    /// lies below 1 + sqrt(1 + 2 h / delta_st) by 1 / (2 sqrt(2 h / delta_st)) or so: 3.6 % at
    /// 2 h / delta_st = 10 (4.162 against 4.317), 0.45 % at 100 (11.00 against 11.05).
    #[test]
    fn psi_is_the_drop_formulas_large_drop_limit() {
        let (m, k, g) = (2_000.0_f64, 5e6_f64, 9.81_f64);
        let delta = m * g / k;
        for h in [0.01_f64, 0.5, 3.0] {
            let v = (2.0 * g * h).sqrt();
            let want = (2.0 * h / delta).sqrt();
            assert!(((psi(v, k, g, m) - 1.0) / want - 1.0).abs() < 1e-12, "h {h}");
        }
        let below = |x: f64| {
            let v = (2.0 * g * x * delta / 2.0).sqrt();
            let exact = 1.0 + (1.0 + x).sqrt();
            (exact - psi(v, k, g, m)) / exact
        };
        assert!((below(10.0) - 0.0360).abs() < 5e-4, "{}", below(10.0));
        assert!((below(100.0) - 0.0045).abs() < 5e-4, "{}", below(100.0));
    }
}
