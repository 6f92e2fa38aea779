//! Wave spectra in Hs/Tp form (DNV-RP-C205 (2010/2019) 3.5.5): Pierson-Moskowitz and JONSWAP,
//! S in m^2 s/rad over the angular frequency w (rad/s), w_p = 2 pi / Tp:
//!
//! - S_PM(w) = 5/16 Hs^2 w_p^4 w^-5 exp(-5/4 (w / w_p)^-4)                        (3.5.5.1)
//! - S_J(w) = (1 - 0.287 ln gamma) S_PM(w) gamma^exp(-(w - w_p)^2 / (2 sigma^2 w_p^2)),
//!   sigma = 0.07 for w <= w_p, 0.09 above                                        (3.5.5.2)
//! - gamma by DNV's rule from Tp / sqrt(Hs) (Tp in s, Hs in m): 5 below 3.6, exp(5.75 - 1.15
//!   Tp / sqrt(Hs)) between, 1 from 5                                             (3.5.5.5)
//!
//! The JONSWAP normalising factor (1 - 0.287 ln gamma) is DNV's approximation: m0 is Hs^2/16
//! within 0.3 % for gamma 1 to 5 and 1.8 % at gamma 7 (`tests/sea_spectrum.rs`; Hs 2.5 m, Tp 7 s:
//! gamma 1.932, m0 0.3897 m^2 against Hs^2/16 = 0.3906 m^2, the `jonswap` crate's published
//! example).

use serde::{Deserialize, Serialize};

/// Which spectrum.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum SpectrumKind {
    /// JONSWAP (the default): a fetch-limited sea, the peak enhanced by gamma.
    #[default]
    #[serde(rename = "jonswap")]
    Jonswap,
    /// Pierson-Moskowitz: a fully developed sea (JONSWAP with gamma = 1).
    #[serde(rename = "pierson-moskowitz")]
    PiersonMoskowitz,
}

impl SpectrumKind {
    /// The parameter form (`--set sea.spectrum=...`): 0 JONSWAP, 1 Pierson-Moskowitz.
    pub fn index(self) -> u32 {
        match self {
            SpectrumKind::Jonswap => 0,
            SpectrumKind::PiersonMoskowitz => 1,
        }
    }

    /// From the parameter form; `None` outside 0..=1.
    pub fn from_index(value: f64) -> Option<SpectrumKind> {
        match value {
            0.0 => Some(SpectrumKind::Jonswap),
            1.0 => Some(SpectrumKind::PiersonMoskowitz),
            _ => None,
        }
    }

    /// The name in a scenario file.
    pub fn name(self) -> &'static str {
        match self {
            SpectrumKind::Jonswap => "jonswap",
            SpectrumKind::PiersonMoskowitz => "pierson-moskowitz",
        }
    }
}

/// DNV-RP-C205 3.5.5.5's peak-enhancement factor gamma from Hs (m) and Tp (s).
pub fn dnv_gamma(hs: f64, tp: f64) -> f64 {
    let p = tp / hs.sqrt();
    if p <= 3.6 {
        5.0
    } else if p < 5.0 {
        libm::exp(5.75 - 1.15 * p)
    } else {
        1.0
    }
}

/// A wave spectrum with its parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spectrum {
    /// Significant wave height Hs, m.
    pub hs: f64,
    /// Peak period Tp, s.
    pub tp: f64,
    /// Peak-enhancement factor gamma (1 for Pierson-Moskowitz).
    pub gamma: f64,
}

impl Spectrum {
    /// Pierson-Moskowitz (gamma = 1).
    pub fn pierson_moskowitz(hs: f64, tp: f64) -> Spectrum {
        Spectrum { hs, tp, gamma: 1.0 }
    }

    /// JONSWAP with `gamma`, or DNV's rule ([`dnv_gamma`]) when `None`.
    pub fn jonswap(hs: f64, tp: f64, gamma: Option<f64>) -> Spectrum {
        Spectrum { hs, tp, gamma: gamma.unwrap_or_else(|| dnv_gamma(hs, tp)) }
    }

    /// The peak frequency w_p = 2 pi / Tp, rad/s.
    pub fn peak_frequency(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.tp
    }

    /// The spectral density S(w), m^2 s/rad (0 at w <= 0).
    pub fn density(&self, w: f64) -> f64 {
        if w <= 0.0 {
            return 0.0;
        }
        let wp = self.peak_frequency();
        let r = wp / w;
        let r4 = r * r * r * r;
        let pm = 5.0 / 16.0 * self.hs * self.hs * r4 / w * libm::exp(-1.25 * r4);
        if self.gamma == 1.0 {
            return pm;
        }
        let sigma = if w <= wp { 0.07 } else { 0.09 };
        let x = (w - wp) / (sigma * wp);
        (1.0 - 0.287 * libm::log(self.gamma)) * pm * libm::pow(self.gamma, libm::exp(-0.5 * x * x))
    }

    /// The spectral moment m_n = int_lo^hi w^n S(w) dw (n = 0, 1, 2), by composite Simpson's
    /// rule on 20 000 intervals (the integrand is smooth; its error is below 1e-9 of m0 for the
    /// ranges used here).
    pub fn moment_between(&self, n: i32, lo: f64, hi: f64) -> f64 {
        let intervals = 20_000;
        let h = (hi - lo) / intervals as f64;
        let f = |w: f64| if w <= 0.0 { 0.0 } else { libm::pow(w, f64::from(n)) * self.density(w) };
        let mut sum = f(lo) + f(hi);
        for k in 1..intervals {
            let w = lo + h * k as f64;
            sum += if k % 2 == 1 { 4.0 } else { 2.0 } * f(w);
        }
        sum * h / 3.0
    }

    /// The spectral moment m_n over 0 < w < infinity (n = 0, 1, 2): Simpson's rule up to 30 w_p
    /// and above it the tail of w^n C w^-5 in closed form, C W^(n-4) / (4 - n), with C = 5/16
    /// Hs^2 w_p^4 (1 - 0.287 ln gamma) (there the exponential and the peak factor are 1 within
    /// 2e-6).
    pub fn moment(&self, n: i32) -> f64 {
        let wp = self.peak_frequency();
        let top = 30.0 * wp;
        let factor = if self.gamma == 1.0 { 1.0 } else { 1.0 - 0.287 * libm::log(self.gamma) };
        let c = 5.0 / 16.0 * self.hs * self.hs * wp.powi(4) * factor;
        self.moment_between(n, 0.0, top) + c * libm::pow(top, f64::from(n - 4)) / f64::from(4 - n)
    }

    /// The fraction of m0 between `lo` and `hi`.
    pub fn energy_fraction(&self, lo: f64, hi: f64) -> f64 {
        self.moment_between(0, lo, hi) / self.moment(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dnv_rule_is_continuous_at_its_ends_and_gives_the_published_gamma() {
        // Hs 2.5 m, Tp 7 s: Tp / sqrt(Hs) = 4.427, gamma = exp(5.75 - 1.15 * 4.427) = 1.932.
        assert!((dnv_gamma(2.5, 7.0) - 1.932).abs() < 5e-4, "{}", dnv_gamma(2.5, 7.0));
        // exp(5.75 - 1.15 * 3.6) = exp(1.61) = 5.003 and exp(5.75 - 5.75) = 1: the rule's pieces meet
        // to 0.06 %, as DNV rounded them.
        assert_eq!(dnv_gamma(1.0, 3.6), 5.0);
        assert!((dnv_gamma(1.0, 3.6001) - 5.0).abs() < 0.01);
        assert_eq!(dnv_gamma(1.0, 5.0), 1.0);
        assert!((dnv_gamma(1.0, 4.9999) - 1.0).abs() < 1e-3);
    }

    #[test]
    fn the_spectrum_peaks_at_the_peak_frequency() {
        for s in [Spectrum::pierson_moskowitz(2.0, 8.0), Spectrum::jonswap(2.0, 8.0, Some(3.3))] {
            let wp = s.peak_frequency();
            assert!(s.density(wp) > s.density(wp * 0.99) && s.density(wp) > s.density(wp * 1.01));
        }
    }
}
