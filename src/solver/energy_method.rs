//! The energy-conservation cross-check (paper Section 3, Eqs. 27-36).
//!
//! **Arrestor** (Eqs. 27-35): the bridge's potential energy becomes the strain energy of the
//! arrestor, a spring of stiffness k_f = 3 E I / l^3 at its end:
//! m_u g (h + h_din) = F_din w_din / 2 (Eq. 27) with h_din = l_u w_din / (2 d) (Eq. 28) and
//! F_din = k_f w_din (Eq. 29) is the quadratic (31), whose positive root is w_din (Eq. 33);
//! the clamp stresses are F_din l_a / W_a and F_din / A_s,a, and E_def,a = F_din w_din / 2 (Eq. 35).
//!
//! **Bridge** (Eq. 36, Table 1's sigma_din,b = 219 MPa; the paper does not print the steps, they
//! are reconstructed in `docs/scenario.md`): at the largest arrestor deflection the bridge is at rest
//! (Section 3: "zero velocity at maximum deflection") but still pressed by F_din. Taken as a rigid
//! body rotating about its hinge, J_u = m_u l_u^2 / 3, it decelerates its fall at
//!
//! ```text
//! alpha = (F_din d - m_u g l_u / 2) / J_u          (upward angular acceleration, rad/s^2)
//! ```
//!
//! With x from the hinge and loads positive downward, the beam carries gravity q = m_u g / l_u and
//! its d'Alembert inertia c x, c = m_u alpha / l_u (the upward acceleration alpha x reversed):
//! p(x) = q + c x. F_din pushes up at x = d, and the hinge reaction (up) is, from the vertical
//! equilibrium, R = m_u g + m_u alpha l_u / 2 - F_din. The bending moment, sagging positive as
//! everywhere in this crate, is a cubic on each side of d:
//!
//! ```text
//! 0 <= x <= d:   M(x) = R x - q x^2 / 2 - c x^3 / 6                   (cut, part towards the hinge)
//! d <= x <= l:   M(x) = -(q + c l) xi^2 / 2 + c xi^3 / 6,  xi = l - x  (cut, the overhang)
//! ```
//!
//! so M(0) = 0 (hinge) and M(l) = 0 (free end) by construction, and the two pieces meet at d
//! exactly when the moments about the hinge balance, F_din d = q l^2 / 2 + c l^3 / 3, which is the
//! definition of alpha; the shear Q = dM/dx jumps by F_din at d. Loaded that way the overhang
//! bends the bridge hogging over the contact point: M(d) < 0 (-2.185 MN m on the paper scenario),
//! and sigma_b = |M(d)| / W_b, a magnitude like every stress of the energy approach (Table 1).
//!
//! The strain energy of Eq. (36), E_def,b = 1/2 * integral_0^l M^2 / (E_b I_b) dx, is integrated
//! in closed form per piece: with t in [0, 1] along a piece of length L and
//! M = b1 t + b2 t^2 + b3 t^3,
//!
//! ```text
//! integral M^2 dx = L (b1^2/3 + b1 b2/2 + (b2^2 + 2 b1 b3)/5 + b2 b3/3 + b3^2/7)
//! ```
//!
//! (hinge side: t = x / d, b1 = R d, b2 = -q d^2 / 2, b3 = -c d^3 / 6; overhang: t = xi / (l - d),
//! b1 = 0, b2 = -(q + c l) (l - d)^2 / 2, b3 = c (l - d)^3 / 6). On the paper scenario it is
//! 4.41 kJ (4408 J), 2.95 % of E_def,a (149.2 kJ): the paper's 4.4 kJ and "3,0 %".

use serde::{Deserialize, Serialize};

use crate::model::Scenario;

/// Results of the energy approach (Table 1, column 2, and Eqs. 35-36).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EnergyMethod {
    /// Flexion coefficient k_f of the arrestor at the contact, N/m: 3 E I / l^3 at a uniform
    /// cantilever's free end (the paper), else 1 / its static point flexibility there.
    pub flexion_stiffness: f64,
    /// Dynamic deflection of the arrestor's end w_din, m (Eq. 33).
    pub tip_deflection: f64,
    /// Dynamic contact force F_din = k_f w_din, N (Eq. 29).
    pub force: f64,
    /// Bending stress at the first support F_din m_1 / W, Pa (m_1 its moment per newton at the
    /// contact: l at a cantilever's free end, 0 at a pin).
    pub clamp_bending_stress: f64,
    /// Shear stress at the first support F_din r_1 / A_s, Pa (r_1 its share of a newton).
    pub clamp_shear_stress: f64,
    /// Strain energy of the arrestor E_def,a = F_din w_din / 2, J (Eq. 35).
    pub strain_energy: f64,
    /// Angular deceleration of the bridge's fall at the largest arrestor deflection,
    /// alpha = (F_din d - m_u g l_u / 2) / J_u, rad/s^2 (positive: the fall slows down).
    pub bridge_deceleration: f64,
    /// Bending moment of the bridge at the contact point M(d), N m, sagging positive
    /// (negative: hogging over the contact point).
    pub bridge_contact_moment: f64,
    /// Bending stress of the bridge at the contact point |M(d)| / W_b, Pa (Table 1, sigma_din,b).
    pub bridge_bending_stress: f64,
    /// Strain energy of the bridge E_def,b = 1/2 integral M^2 / (E_b I_b) dx, J (Eq. 36).
    pub bridge_strain_energy: f64,
    /// E_def,b / E_def,a, a fraction (the paper: 3.0 %).
    pub bridge_strain_ratio: f64,
}

impl EnergyMethod {
    /// Eqs. (29), (33), (35), (36) for a scenario.
    pub fn new(s: &Scenario) -> EnergyMethod {
        let l = &s.lower;
        // The support's spring: the arrestor's flexion (Eq. 29), or for a rigid support the
        // contact element alone.
        let rigid = s.lower.kind == crate::model::scenario::SupportKind::Rigid;
        // The arrestor's spring is its static point flexibility at the contact (issue 45): the
        // paper's 3 E I / l^3 at a uniform cantilever's free end; elsewhere on a uniform beam,
        // Roark's closed forms (Table 8.1); on a beam of sections, the exact static solution of
        // the stepped beam on its supports ([`Supports::stepped_point_load`], the unit-load
        // integral with the indeterminate supports' redundants solved). The first support's
        // stresses take that section's modulus and shear area.
        let segments = s.lower_segments();
        let point = arrestor_point_load(s);
        let (first_modulus, first_shear_area) =
            segments.first().map_or((l.section_modulus, l.shear_area), |g| (g.section_modulus, g.shear_area));
        let k_f = if rigid { s.contact_stiffness() } else { arrestor_stiffness(s) };
        let weight = s.upper.mass * s.gravity;
        let (d, h) = (s.contact_position, s.drop_height);
        // The weight's lever W l_u / 2 about the hinge: twice the centre of gravity's distance
        // for a bridge of sections (its deceleration below stays the uniform bar's estimate).
        let lu = if s.upper.sections.is_empty() {
            s.upper.length
        } else {
            let (m, first, _) = crate::model::section::mass_moments(&s.upper_segments());
            2.0 * first / m
        };
        // The arrestor's strain energy 1/2 k_f w^2 takes the impact's energy E_0 and the bridge's
        // weight's further work W l_u w / (2 d): for a drop E_0 = W h (the paper's form below);
        // for a stated speed E_0 is the bridge's kinetic energy (and W may be 0).
        // A rigid impactor (issue 45): its weight works through the whole deflection,
        // 1/2 k_f w^2 = E_0 + W w, so w = (W + sqrt(W^2 + 2 k_f E_0)) / k_f, E_0 = 1/2 m v^2.
        let mass = s.upper.kind == crate::model::scenario::ImpactorKind::Mass;
        let w = match s.impact_angular_velocity {
            _ if mass => (weight + (weight * weight + 2.0 * k_f * s.impact_energy()).sqrt()) / k_f,
            None => (weight * lu + (weight * (8.0 * d * d * h * k_f + weight * lu * lu)).sqrt()) / (2.0 * d * k_f),
            Some(_) => {
                let lever = weight * lu / d;
                (lever + (lever * lever + 8.0 * k_f * s.impact_energy()).sqrt()) / (2.0 * k_f)
            }
        };
        let force = k_f * w;
        let strain_energy = 0.5 * force * w;
        let bridge = DeceleratedBridge::new(s.upper.mass, s.upper.length, s.gravity, d, force);
        let u = &s.upper;
        let bridge_contact_moment = bridge.moment(d);
        let bridge_strain_energy = 0.5 * bridge.moment_squared_integral() / (u.elastic_modulus * u.second_moment);
        if mass {
            // A rigid body stores no strain energy and has no bending stress.
            return EnergyMethod {
                flexion_stiffness: k_f,
                tip_deflection: w,
                force,
                clamp_bending_stress: if rigid { 0.0 } else { force * point.first_moment / first_modulus },
                clamp_shear_stress: if rigid { 0.0 } else { force * point.first_shear / first_shear_area },
                strain_energy,
                bridge_deceleration: 0.0,
                bridge_contact_moment: 0.0,
                bridge_bending_stress: 0.0,
                bridge_strain_energy: 0.0,
                bridge_strain_ratio: 0.0,
            };
        }
        EnergyMethod {
            flexion_stiffness: k_f,
            tip_deflection: w,
            force,
            clamp_bending_stress: if rigid { 0.0 } else { force * point.first_moment / first_modulus },
            clamp_shear_stress: if rigid { 0.0 } else { force * point.first_shear / first_shear_area },
            strain_energy,
            bridge_deceleration: bridge.deceleration,
            bridge_contact_moment,
            bridge_bending_stress: bridge_contact_moment.abs() / u.section_modulus,
            bridge_strain_energy,
            bridge_strain_ratio: bridge_strain_energy / strain_energy,
        }
    }
}

/// The struck beam's static response to a unit point load at the contact (issue 45): Roark's
/// closed forms on a uniform beam ([`crate::model::supports::Supports::point_load`]), the exact
/// stepped-beam solution on a beam of sections
/// ([`crate::model::supports::Supports::stepped_point_load`]).
pub fn arrestor_point_load(s: &Scenario) -> crate::model::supports::PointLoad {
    let l = &s.lower;
    let x = s.lower_contact_position();
    if l.sections.is_empty() {
        l.supports.point_load(l.elastic_modulus * l.second_moment, l.length, x)
    } else {
        l.supports.stepped_point_load(&s.lower_segments(), x)
    }
}

/// The struck beam's point stiffness at the contact, N/m, the energy method's k_f and psi's
/// k_arrestor: the paper's 3 E I / l^3 at a uniform cantilever's free end (bit for bit), the
/// tip's unit-load sum on a cantilever of sections, else 1 / [`arrestor_point_load`]'s
/// flexibility.
pub fn arrestor_stiffness(s: &Scenario) -> f64 {
    let l = &s.lower;
    let x = s.lower_contact_position();
    if l.supports.has_far_support() || x != l.length {
        1.0 / arrestor_point_load(s).flexibility
    } else if l.sections.is_empty() {
        3.0 * l.elastic_modulus * l.second_moment / l.length.powi(3)
    } else {
        1.0 / crate::model::section::tip_flexibility(&s.lower_segments())
    }
}

/// The bridge of the energy approach: a uniform rigid body hinged at x = 0, free at x = `length`,
/// pushed up by `force` at x = `contact_position`, loaded by gravity and by its own d'Alembert
/// inertia (see the module documentation for the derivation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeceleratedBridge {
    /// Length l_u, m.
    pub length: f64,
    /// Contact position d from the hinge, m (0 < d < l_u).
    pub contact_position: f64,
    /// Upward contact force F_din, N.
    pub force: f64,
    /// Gravity load q = m_u g / l_u, N/m (down).
    pub weight_per_length: f64,
    /// Upward angular acceleration alpha = (F d - m_u g l_u / 2) / (m_u l_u^2 / 3), rad/s^2.
    pub deceleration: f64,
    /// Slope c = m_u alpha / l_u of the d'Alembert load c x, N/m^2 (down for alpha > 0).
    pub inertia_slope: f64,
    /// Hinge reaction R = m_u g + m_u alpha l_u / 2 - F, N (up positive).
    pub hinge_reaction: f64,
}

impl DeceleratedBridge {
    /// The rigid-body deceleration and the reactions for mass `mass` (kg), length `length` (m),
    /// gravity `gravity` (m/s^2) and an upward force `force` (N) at `contact_position` (m).
    pub fn new(mass: f64, length: f64, gravity: f64, contact_position: f64, force: f64) -> DeceleratedBridge {
        let inertia = mass * length * length / 3.0;
        let deceleration = (force * contact_position - mass * gravity * length / 2.0) / inertia;
        DeceleratedBridge {
            length,
            contact_position,
            force,
            weight_per_length: mass * gravity / length,
            deceleration,
            inertia_slope: mass * deceleration / length,
            hinge_reaction: mass * gravity + mass * deceleration * length / 2.0 - force,
        }
    }

    /// The cubic M = b1 t + b2 t^2 + b3 t^3 of each piece, t in [0, 1]: (L, [b1, b2, b3]) for the
    /// hinge side (t = x / d) and for the overhang (t = (l - x) / (l - d)).
    fn pieces(&self) -> [(f64, [f64; 3]); 2] {
        let (l, d, q, c) = (self.length, self.contact_position, self.weight_per_length, self.inertia_slope);
        let e = l - d;
        [
            (d, [self.hinge_reaction * d, -q * d * d / 2.0, -c * d.powi(3) / 6.0]),
            (e, [0.0, -(q + c * l) * e * e / 2.0, c * e.powi(3) / 6.0]),
        ]
    }

    /// Bending moment M(x), N m, sagging positive, x from the hinge (0 <= x <= l).
    pub fn moment(&self, x: f64) -> f64 {
        let [hinge, overhang] = self.pieces();
        let (piece, t) = if x <= self.contact_position {
            (hinge, x / self.contact_position)
        } else {
            (overhang, (self.length - x) / (self.length - self.contact_position))
        };
        let [b1, b2, b3] = piece.1;
        t * (b1 + t * (b2 + t * b3))
    }

    /// integral_0^l M(x)^2 dx, N^2 m^3, in closed form (module documentation).
    pub fn moment_squared_integral(&self) -> f64 {
        self.pieces()
            .iter()
            .map(|&(len, [b1, b2, b3])| {
                len * (b1 * b1 / 3.0 + b1 * b2 / 2.0 + (b2 * b2 + 2.0 * b1 * b3) / 5.0 + b2 * b3 / 3.0 + b3 * b3 / 7.0)
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Source: SCENARIO.md ("What the paper reports"): on the paper scenario the rigid bridge
    /// decelerates at alpha = 1.3288 rad/s^2 and M(d) = -2.185 MN m (hogging). Tolerances are the
    /// digits printed there (half a unit of the last digit).
    #[test]
    fn paper_bridge_deceleration_and_contact_moment_match_scenario_md() {
        let e = EnergyMethod::new(&Scenario::default());
        assert!((e.bridge_deceleration - 1.3288).abs() < 0.5e-4, "{}", e.bridge_deceleration);
        assert!((e.bridge_contact_moment + 2.185e6).abs() < 0.5e3, "{}", e.bridge_contact_moment);
    }

    /// Limiting case alpha = 0 (F d = m g l / 2: the force that holds the bridge statically, the
    /// textbook beam on a hinge and a support at d with an overhang). Source: statics of a uniform
    /// load q: the overhang is a cantilever, M(d) = -q (l - d)^2 / 2 and integral of M^2 over it
    /// q^2 (l - d)^5 / 20; the span carries M = R x - q x^2 / 2 with R = q l - F, whose square
    /// integrates to R^2 d^3 / 3 - R q d^4 / 4 + q^2 d^5 / 20. Both independent of the piece
    /// polynomials of the code; equal to round-off (1e-12 relative).
    #[test]
    fn static_limit_alpha_zero_is_the_beam_with_an_overhang() {
        let (m, l, g, d) = (12_000.0, 29.0, 9.81, 13.0);
        let f = m * g * l / (2.0 * d);
        let b = DeceleratedBridge::new(m, l, g, d, f);
        assert!(b.deceleration.abs() < 1e-12, "{}", b.deceleration);
        let q = m * g / l;
        let (e, r) = (l - d, q * l - f);
        assert!((b.hinge_reaction - r).abs() < 1e-9 * f, "{} vs {r}", b.hinge_reaction);
        let m_d = -q * e * e / 2.0;
        assert!((b.moment(d) - m_d).abs() < 1e-12 * m_d.abs(), "{} vs {m_d}", b.moment(d));
        let expected =
            q * q * e.powi(5) / 20.0 + r * r * d.powi(3) / 3.0 - r * q * d.powi(4) / 4.0 + q * q * d.powi(5) / 20.0;
        let integral = b.moment_squared_integral();
        assert!((integral - expected).abs() <= 1e-12 * expected, "{integral} vs {expected}");
    }
}
