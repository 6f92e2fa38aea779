//! The Palmgren-Miner sum of counted cycles on an S-N curve (DNVGL-RP-C203 2016 Sec. 2.2,
//! Eq. 2.2.1: D = sum n_i / N_i), with the factors the designer chooses:
//! - the stress concentration factor multiplies the nominal range before the curve is read
//!   (hot-spot range = SCF x nominal range, RP Sec. 2.3);
//! - the thickness correction (t / t_ref)^k multiplies the range too (2016 Eq. 2.4.3);
//! - the design fatigue factor multiplies the damage: the design damage is DFF x sum n_i / N_i,
//!   acceptable at <= 1 (equivalently the life divided by DFF; DNV-OS-C101 Sec. 6 gives 1, 2, 3).
//!
//! Half cycles count 0.5. No range is left out: the RP's curves have no cut-off (see
//! [`super::sn_curve`]).

use super::rainflow::Cycle;
use super::sn_curve::SnCurve;
use crate::error::{Error, Result};

/// The designer's factors on a detail (what `beam-impact fatigue --scf --thickness --dff` and a
/// scenario's `[fatigue]` set).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SnOptions {
    /// Stress concentration factor on the nominal stress range, [1, 20]: below 1 a hot spot
    /// would be less stressed than the section, which no SCF of the RP gives; above 20 the
    /// nominal beam stress is no longer a fit input (a hot-spot analysis of the detail is).
    pub scf: f64,
    /// The detail's thickness, m, for the thickness correction: none (no correction) or in
    /// (0, 1] m (a gangway's plates are millimetres to centimetres; a metre is a generous bound).
    pub thickness_m: Option<f64>,
    /// Design fatigue factor multiplying the damage, [1, 10]: the RP's and DNV-OS-C101's values
    /// are 1 to 3 (10 for critical, uninspectable details in some codes); below 1 it would credit
    /// life the curve does not give.
    pub design_fatigue_factor: f64,
}

impl Default for SnOptions {
    fn default() -> Self {
        SnOptions { scf: 1.0, thickness_m: None, design_fatigue_factor: 1.0 }
    }
}

/// `name must be rule, got value` when `ok` is false.
fn check(errors: &mut Vec<Error>, ok: bool, name: &'static str, rule: &str, value: f64) {
    if !ok {
        errors.push(Error::InvalidParameter { name: name.into(), rule: rule.into(), value: value.to_string() });
    }
}

impl SnOptions {
    /// Checks the bounds (see the fields); every broken one in one line
    /// (`fatigue.scf must be >= 1 and <= 20, got 0.5`).
    pub fn validate(&self) -> Result<()> {
        let mut errors = Vec::new();
        check(&mut errors, (1.0..=20.0).contains(&self.scf), "fatigue.scf", ">= 1 and <= 20", self.scf);
        if let Some(t) = self.thickness_m {
            check(&mut errors, t > 0.0 && t <= 1.0, "fatigue.thickness", "> 0 m and <= 1 m", t);
        }
        let dff = self.design_fatigue_factor;
        check(&mut errors, (1.0..=10.0).contains(&dff), "fatigue.design_fatigue_factor", ">= 1 and <= 10", dff);
        match errors.len() {
            0 => Ok(()),
            1 => Err(errors.remove(0)),
            _ => Err(Error::Invalid(errors)),
        }
    }

    /// The factor on a nominal range before the curve is read: SCF x (t / t_ref)^k.
    pub fn range_factor(&self, curve: &SnCurve) -> f64 {
        self.scf * curve.thickness_factor(self.thickness_m)
    }
}

/// The design damage of the cycles: DFF x sum count_i / N(range_i x SCF x (t/t_ref)^k). The
/// options are taken as validated ([`SnOptions::validate`]); a zero range adds nothing.
pub fn damage(cycles: &[Cycle], curve: &SnCurve, options: &SnOptions) -> f64 {
    let factor = options.range_factor(curve);
    // From +0 (an empty `sum()` of f64 is -0, printed `-0`).
    let sum = cycles.iter().map(|c| c.count / curve.cycles_to_failure(c.range * factor)).fold(0.0, |a, b| a + b);
    options.design_fatigue_factor * sum
}

/// The fatigue life in years of a damage per event at a number of events per year: 1 / (D n).
/// None when either is not a positive finite number (no damage: no finite life).
pub fn life_years(damage_per_event: f64, events_per_year: f64) -> Option<f64> {
    let rate = damage_per_event * events_per_year;
    (damage_per_event > 0.0 && events_per_year > 0.0 && rate.is_finite()).then(|| 1.0 / rate)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn full(range: f64) -> Cycle {
        Cycle { range, mean: 0.0, count: 1.0, start: 0, end: 1 }
    }

    /// On the first branch N = a S^-m, so an SCF of 2 multiplies the damage by 2^m exactly
    /// (2^3 = 8 on D) and a DFF of 3 by 3; to 1e-12 (a few roundings of powf).
    #[test]
    fn scf_raises_damage_by_its_power_m_and_dff_multiplies_it() {
        let d = SnCurve::by_name("D").unwrap();
        let cycles = [full(100e6), Cycle { count: 0.5, ..full(120e6) }];
        let base = damage(&cycles, &d, &SnOptions::default());
        let expected = 10f64.powf(-12.164) * (100f64.powi(3) + 0.5 * 120f64.powi(3));
        assert!((base / expected - 1.0).abs() < 1e-12);
        let scf = damage(&cycles, &d, &SnOptions { scf: 2.0, ..SnOptions::default() });
        assert!((scf / base - 8.0).abs() < 1e-12);
        let dff = damage(&cycles, &d, &SnOptions { design_fatigue_factor: 3.0, ..SnOptions::default() });
        assert!((dff / base - 3.0).abs() < 1e-12);
    }

    /// Eq. 2.4.3: a 50 mm plate on D (k = 0.2, t_ref = 25 mm) multiplies the range by 2^0.2 and
    /// the first-branch damage by 2^(0.2 x 3) = 2^0.6; a 20 mm plate changes nothing.
    #[test]
    fn thickness_above_the_reference_raises_damage_by_t_ratio_to_the_k_m() {
        let d = SnCurve::by_name("D").unwrap();
        let cycles = [full(150e6)];
        let base = damage(&cycles, &d, &SnOptions::default());
        let thick = damage(&cycles, &d, &SnOptions { thickness_m: Some(0.05), ..SnOptions::default() });
        assert!((thick / base - 2f64.powf(0.6)).abs() < 1e-12);
        let thin = damage(&cycles, &d, &SnOptions { thickness_m: Some(0.02), ..SnOptions::default() });
        assert_eq!(thin, base);
    }

    #[test]
    fn options_out_of_bounds_are_named_in_one_line() {
        let e = SnOptions { scf: 0.5, thickness_m: Some(-1.0), design_fatigue_factor: f64::NAN }.validate();
        assert_eq!(
            e.unwrap_err().to_string(),
            "fatigue.scf must be >= 1 and <= 20, got 0.5; fatigue.thickness must be > 0 m and <= 1 m, got -1; \
             fatigue.design_fatigue_factor must be >= 1 and <= 10, got NaN"
        );
        assert!(SnOptions::default().validate().is_ok());
    }

    #[test]
    fn life_is_the_inverse_of_the_yearly_damage() {
        assert_eq!(life_years(1e-6, 1e3), Some(1.0 / (1e-6 * 1e3)));
        assert_eq!(life_years(0.0, 1e3), None);
        assert_eq!(life_years(1e-6, -1.0), None);
    }
}
