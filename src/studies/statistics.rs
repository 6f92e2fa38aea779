//! A campaign's statistics (issue 43): how likely a design quantity is to exceed its allowable,
//! with a confidence interval, how many events that takes, and the extremes of the per-record
//! maxima. Pure arithmetic on numbers handed in: no runs, no files.
//!
//! - [`clopper_pearson`] (exact, the interval a campaign states) and [`wilson`] (score) for the
//!   probability that one event exceeds a threshold, from k exceeding events among n;
//! - [`events_needed`]: the fewest events, none beyond, that show p < target (the "sample too small"
//!   warning), and [`events_at_rate`]: how many would if the observed rate held;
//! - [`Gumbel`]: the type I extreme value distribution of maxima, fitted by maximum likelihood
//!   (as `scipy.stats.gumbel_r.fit`) or by moments, and its most probable maximum over an exposure;
//! - [`Empirical`]: the sorted sample, its exceedance count and its quantiles (Weibull plotting
//!   position).
//!
//! Invalid arguments give NaN (or the documented value), never a panic: the callers check what the
//! user typed with [`check_probability`], which gives a one-line error.

use serde::Serialize;
use statrs::function::beta::{checked_beta_reg, inv_beta_reg};
use statrs::function::erf::erf_inv;

/// Euler-Mascheroni constant, the mean of the standard Gumbel distribution (Abramowitz and Stegun
/// 6.1.3).
pub const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;

/// A probability estimate with its confidence interval, all in [0, 1].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Interval {
    /// The point estimate k / n (NaN for n = 0).
    pub probability: f64,
    /// The interval's lower bound.
    pub low: f64,
    /// The interval's upper bound.
    pub high: f64,
}

impl Interval {
    const NAN: Interval = Interval { probability: f64::NAN, low: f64::NAN, high: f64::NAN };
}

/// `value` if it is a probability strictly inside (0, 1), else a one-line error naming `name`
/// ("confidence must be in (0, 1), got 1.5").
pub fn check_probability(name: &str, value: f64) -> Result<f64, String> {
    if value > 0.0 && value < 1.0 {
        Ok(value)
    } else {
        Err(format!("{name} must be in (0, 1), got {value}"))
    }
}

/// Whether (`exceeding`, `events`, `confidence`) can make an interval: k <= n, confidence in (0, 1).
fn valid(exceeding: u64, events: u64, confidence: f64) -> bool {
    exceeding <= events && check_probability("confidence", confidence).is_ok()
}

/// The standard normal quantile z with P(|Z| < z) = `confidence` (two-sided): z = sqrt(2)
/// erf^-1(confidence) (Abramowitz and Stegun 26.2.2 with 7.1.1); 1.959964 at 95 %.
pub fn normal_two_sided(confidence: f64) -> f64 {
    std::f64::consts::SQRT_2 * erf_inv(confidence)
}

/// The Wilson score interval (Wilson 1927; Agresti and Coull 1998, Eq. 2) for k = `exceeding`
/// events beyond the threshold among n = `events`, at two-sided `confidence` (0.95 for 95 %):
/// with p = k/n and z from [`normal_two_sided`],
/// (p + z^2/(2n) -+ z sqrt(p(1-p)/n + z^2/(4n^2))) / (1 + z^2/n).
/// k = 0 gives low 0 exactly, k = n high 1 exactly. n = 0 gives probability NaN and [0, 1] (no
/// information); k > n or a confidence outside (0, 1) give NaN.
pub fn wilson(exceeding: u64, events: u64, confidence: f64) -> Interval {
    if !valid(exceeding, events, confidence) {
        return Interval::NAN;
    }
    if events == 0 {
        return Interval { probability: f64::NAN, low: 0.0, high: 1.0 };
    }
    let (k, n) = (exceeding as f64, events as f64);
    let p = k / n;
    let z = normal_two_sided(confidence);
    let z2n = z * z / n;
    let centre = (p + 0.5 * z2n) / (1.0 + z2n);
    let half = z / (1.0 + z2n) * (p * (1.0 - p) / n + 0.25 * z2n / n).sqrt();
    let low = if exceeding == 0 { 0.0 } else { (centre - half).max(0.0) };
    let high = if exceeding == events { 1.0 } else { (centre + half).min(1.0) };
    Interval { probability: p, low, high }
}

/// The Clopper-Pearson ("exact") interval (Clopper and Pearson 1934) for k = `exceeding` among
/// n = `events` at two-sided `confidence`, alpha = 1 - confidence: low = B^-1(alpha/2; k, n-k+1),
/// high = B^-1(1 - alpha/2; k+1, n-k), B^-1 the quantile of the Beta distribution
/// ([`beta_quantile`]). k = 0: low 0, high 1 - (alpha/2)^(1/n); k = n the mirror, both in closed
/// form. It never covers less than `confidence`. n = 0, k > n and a bad confidence as [`wilson`].
pub fn clopper_pearson(exceeding: u64, events: u64, confidence: f64) -> Interval {
    if !valid(exceeding, events, confidence) {
        return Interval::NAN;
    }
    if events == 0 {
        return Interval { probability: f64::NAN, low: 0.0, high: 1.0 };
    }
    let (k, n) = (exceeding as f64, events as f64);
    let tail = 0.5 * (1.0 - confidence);
    // 1 - tail^(1/n) without cancellation: -expm1(ln(tail) / n).
    let closed = -(tail.ln() / n).exp_m1();
    let low = if exceeding == 0 {
        0.0
    } else if exceeding == events {
        1.0 - closed
    } else {
        beta_quantile(k, n - k + 1.0, tail)
    };
    let high = if exceeding == events {
        1.0
    } else if exceeding == 0 {
        closed
    } else {
        beta_quantile(k + 1.0, n - k, 1.0 - tail)
    };
    Interval { probability: k / n, low, high }
}

/// The `p` quantile of the Beta(`a`, `b`) distribution: x with I_x(a, b) = p, I the regularised
/// incomplete beta function (statrs' `beta_reg`, the continued fraction of Numerical Recipes 6.4).
/// statrs' own inverse (`inv_beta_reg`, AS 64/AS 109) only starts it: at a million events it is
/// 4.5e-4 off scipy's `beta.ppf` (k = 1, 90 %), so the root is bracketed around that start and
/// bisected until the bracket is 4 ulp wide; what is left is `beta_reg`'s own error (1e-9
/// relative at a million events: its ln-gamma differences), measured against scipy in
/// tests/campaign_statistics.rs. NaN unless a, b > 0 and p in [0, 1].
pub fn beta_quantile(a: f64, b: f64, p: f64) -> f64 {
    if !(a > 0.0 && b > 0.0 && (0.0..=1.0).contains(&p)) {
        return f64::NAN;
    }
    if p == 0.0 || p == 1.0 {
        return p;
    }
    // I_x - p, NaN where statrs refuses (it does not for a, b > 0 and x in [0, 1]).
    let f = |x: f64| checked_beta_reg(a, b, x).map_or(f64::NAN, |v| v - p);
    let start = inv_beta_reg(a, b, p);
    // The bracket [lo, hi] with f(lo) <= 0 <= f(hi): around the start if it holds, else [0, 1].
    let (mut lo, mut hi) = (0.0, 1.0);
    if start > 0.0 && start < 1.0 {
        let mut width = 1e-6 * start.min(1.0 - start);
        for _ in 0..60 {
            let (l, h) = ((start - width).max(0.0), (start + width).min(1.0));
            if f(l) <= 0.0 && f(h) >= 0.0 {
                (lo, hi) = (l, h);
                break;
            }
            width *= 4.0;
        }
    }
    for _ in 0..2200 {
        // Halving the ratio while the bracket spans decades (a tail quantile of 1e-12 from [0, 1]).
        let mid = if lo == 0.0 {
            0.25 * hi
        } else if hi > 4.0 * lo {
            (lo * hi).sqrt()
        } else {
            0.5 * (lo + hi)
        };
        if mid <= lo || mid >= hi || hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
        let v = f(mid);
        if v.is_nan() {
            return f64::NAN;
        }
        if v <= 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The fewest events n that, with none beyond the threshold, show p < `target` at `confidence`
/// (one-sided exact: (1 - target)^n <= alpha, so n = ceil(ln(alpha) / ln(1 - target)); the rule of
/// three, n ~ 3/target, at 95 %). 2995 for 1e-3 at 95 %. Note the two-sided Clopper-Pearson
/// high at k = 0, 1 - (alpha/2)^(1/n), needs ln(alpha/2)/ln(1 - target) events (3688 for 1e-3 at
/// 95 %) to fall below the target. `u64::MAX` when an argument is outside (0, 1) or the count
/// would not fit (a target below about 1e-19).
pub fn events_needed(target: f64, confidence: f64) -> u64 {
    if check_probability("target", target).is_err() || check_probability("confidence", confidence).is_err() {
        return u64::MAX;
    }
    let ln_alpha = (1.0 - confidence).ln();
    let ln_keep = (-target).ln_1p();
    let ratio = ln_alpha / ln_keep;
    if !ratio.is_finite() || ratio >= u64::MAX as f64 {
        return u64::MAX;
    }
    let mut n = ratio.ceil().max(1.0) as u64;
    // The rounding of the ratio may put an exact integer one above: check n - 1 itself.
    if n > 1 && (n - 1) as f64 * ln_keep <= ln_alpha {
        n -= 1;
    }
    n
}

/// The most events [`events_at_rate`] counts to: beyond, statrs' ln-gamma differences in the
/// incomplete beta function lose their digits (their absolute error, an ulp of ln Gamma(n) ~
/// n ln n, is 4e-3 at 1e12 events: 0.4 % of the tail probability; 4 at 1e15).
pub const MAX_COUNTED_EVENTS: u64 = 1_000_000_000_000;

/// The fewest events n, at least `events`, whose one-sided Clopper-Pearson upper bound at
/// `confidence` falls below `target` if the overloads keep their observed rate r = k/n0
/// (k = `exceeding` of n0 = `events`): B^-1(confidence; r n + 1, n - r n) < target, the bound
/// of [`clopper_pearson`] with the count r n (continuous between whole counts, exact where r n is
/// whole; n0 itself gives the observed interval). By the Beta-binomial duality the bound is below
/// the target exactly when I_target(r n + 1, n - r n) > confidence, which is checked at each n
/// (doubling from n0, then bisection): the bound falls as n grows at a fixed rate. With no
/// overload (r = 0) this is [`events_needed`], in closed form. None when no count can show it:
/// a rate at or above the target, no events, arguments outside their ranges, or more than
/// [`MAX_COUNTED_EVENTS`] (for k > 0) or `u64::MAX` (for k = 0) events.
pub fn events_at_rate(exceeding: u64, events: u64, target: f64, confidence: f64) -> Option<u64> {
    if events == 0 || !valid(exceeding, events, confidence) || check_probability("target", target).is_err() {
        return None;
    }
    if exceeding == 0 {
        return Some(events_needed(target, confidence)).filter(|n| *n < u64::MAX);
    }
    let rate = exceeding as f64 / events as f64;
    if rate >= target {
        return None;
    }
    let shows = |n: u64| {
        let (n, k) = (n as f64, rate * n as f64);
        checked_beta_reg(k + 1.0, n - k, target).is_ok_and(|p| p > confidence)
    };
    if shows(events) {
        return Some(events);
    }
    // lo does not show it, hi does.
    let (mut lo, mut hi) = (events, events.saturating_mul(2));
    while !shows(hi) {
        if hi >= MAX_COUNTED_EVENTS {
            return None;
        }
        lo = hi;
        hi = hi.saturating_mul(2).min(MAX_COUNTED_EVENTS);
    }
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if shows(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(hi)
}

/// The Gumbel (type I extreme value, maxima) distribution: F(x) = exp(-exp(-(x - location)/scale)),
/// scipy's `gumbel_r(loc=location, scale=scale)`. Its mode is `location`, its mean
/// location + 0.5772 scale, its standard deviation scale pi/sqrt(6).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Gumbel {
    /// Location (the mode), in the unit of the samples.
    pub location: f64,
    /// Scale (> 0), in the unit of the samples.
    pub scale: f64,
}

impl Gumbel {
    /// F(x) = exp(-exp(-(x - location)/scale)).
    pub fn cdf(&self, x: f64) -> f64 {
        (-(-(x - self.location) / self.scale).exp()).exp()
    }

    /// x with F(x) = `p`: location - scale ln(-ln p); NaN outside [0, 1] (-inf at 0, +inf at 1).
    pub fn quantile(&self, p: f64) -> f64 {
        if !(0.0..=1.0).contains(&p) {
            return f64::NAN;
        }
        self.location - self.scale * (-p.ln()).ln()
    }

    /// The most probable maximum (mode) over `exposure` events of the quantity whose maxima over
    /// `events_per_sample` events were fitted: location + scale ln(exposure / events_per_sample).
    /// Derivation: the maximum of k independent maxima, each Gumbel(mu, beta), has
    /// F(x)^k = exp(-k exp(-(x - mu)/beta)) = exp(-exp(-(x - mu - beta ln k)/beta)), a Gumbel of the
    /// same scale with its location (its mode) moved by beta ln k, here k = exposure /
    /// events_per_sample (also for a k that is not whole, as the continuous extrapolation).
    /// NaN unless both counts are finite and > 0. For Rayleigh-like tails, whose maxima are Gumbel
    /// in r^2 rather than r, the extrapolation leans to the safe side: fitted to the maxima of 100
    /// Rayleigh peaks, the mode is 1.7 % under the exact one at the fitted exposure, 0.8 % over it
    /// at 10 times and 4.8 % over at 100 times (tests/campaign_statistics.rs).
    pub fn most_probable_maximum(&self, events_per_sample: f64, exposure: f64) -> f64 {
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if !positive(events_per_sample) || !positive(exposure) {
            return f64::NAN;
        }
        self.location + self.scale * (exposure / events_per_sample).ln()
    }

    /// The maximum likelihood fit, what `scipy.stats.gumbel_r.fit(samples)` computes (its own
    /// `fit`, scipy >= 1.7): the scale solves beta = mean(x) - sum(x w) / sum(w), w = exp(-x/beta)
    /// (the likelihood's stationarity in location eliminated; Johnson, Kotz and Balakrishnan,
    /// *Continuous Univariate Distributions* vol. 2, 22.7), then location = -beta ln(mean(exp(-x/beta))).
    /// The samples are centred on their mean and the exponentials shifted by their largest exponent,
    /// so nothing overflows and large offsets keep their digits. The scale's equation
    /// g(beta) = mean - weighted mean - beta is strictly decreasing (the weighted mean rises with
    /// beta) from mean - min > 0 at 0+ to < 0 at beta = mean - min, so its one root is bracketed;
    /// Newton steps from the moments' scale, kept inside the bracket by bisection, to 1e-15
    /// relative. Errors: fewer than 2 samples, a non-finite sample, all samples equal.
    pub fn fit_maximum_likelihood(samples: &[f64]) -> Result<Gumbel, String> {
        let (mean, std) = check_samples(samples)?;
        // In units of the sample's standard deviation (the fit is equivariant: location and scale
        // follow), so that neither 1e300 nor 1e-300 over- or underflows in the weighted sums.
        let centred: Vec<f64> = samples.iter().map(|x| (x - mean) / std).collect();
        let lowest = centred.iter().copied().fold(f64::INFINITY, f64::min);
        // g(beta) and g'(beta) = -var_w(x)/beta^2 - 1 with the weights w = exp(-(x - lowest)/beta).
        let g = |beta: f64| {
            let (mut sw, mut swx, mut swxx) = (0.0, 0.0, 0.0);
            for &x in &centred {
                let w = (-(x - lowest) / beta).exp();
                sw += w;
                swx += w * x;
                swxx += w * x * x;
            }
            let wmean = swx / sw;
            let wvar = (swxx / sw - wmean * wmean).max(0.0);
            (-wmean - beta, -wvar / (beta * beta) - 1.0)
        };
        let (mut lo, mut hi) = (0.0, -lowest);
        let mut beta = (std * 6f64.sqrt() / std::f64::consts::PI).clamp(0.5 * hi, hi);
        for _ in 0..200 {
            let (value, slope) = g(beta);
            if value > 0.0 {
                lo = beta;
            } else {
                hi = beta;
            }
            let newton = beta - value / slope;
            let next = if newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
            let done = (next - beta).abs() <= 1e-15 * beta || hi - lo <= 1e-15 * hi;
            beta = next;
            if done {
                break;
            }
        }
        let sum: f64 = centred.iter().map(|x| (-(x - lowest) / beta).exp()).sum();
        let location = mean + std * (lowest - beta * (sum / samples.len() as f64).ln());
        let scale = std * beta;
        if !(location.is_finite() && scale.is_finite() && scale > 0.0) {
            return Err(format!(
                "a Gumbel fit of these {} samples (mean {mean:e}, standard deviation {std:e}) gives no finite \
                 location and positive scale",
                samples.len()
            ));
        }
        Ok(Gumbel { location, scale })
    }

    /// The method of moments: scale = s sqrt(6)/pi, location = mean - 0.5772 scale, s the sample
    /// standard deviation (n - 1 in the denominator). Errors as [`Gumbel::fit_maximum_likelihood`].
    pub fn fit_moments(samples: &[f64]) -> Result<Gumbel, String> {
        let (mean, std) = check_samples(samples)?;
        let scale = std * 6f64.sqrt() / std::f64::consts::PI;
        Ok(Gumbel { location: mean - EULER_GAMMA * scale, scale })
    }
}

/// The mean and the sample standard deviation (n - 1) of samples a Gumbel can be fitted to.
fn check_samples(samples: &[f64]) -> Result<(f64, f64), String> {
    if samples.len() < 2 {
        return Err(format!("a Gumbel fit needs at least 2 samples, got {}", samples.len()));
    }
    if let Some((i, x)) = samples.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(format!("a Gumbel fit needs finite samples, sample {i} is {x}"));
    }
    let (mean, std) = mean_std(samples);
    if samples.iter().all(|&x| x == samples[0]) {
        return Err(format!("a Gumbel fit needs samples that differ, all {} are {}", samples.len(), samples[0]));
    }
    if !(mean.is_finite() && std.is_finite() && std > 0.0) {
        return Err(format!(
            "a Gumbel fit of {} samples with mean {mean:e} and standard deviation {std:e}: beyond the range of \
             double precision",
            samples.len()
        ));
    }
    Ok((mean, std))
}

/// The mean and the sample standard deviation (n - 1; NaN for fewer than 2 samples), two-pass.
fn mean_std(samples: &[f64]) -> (f64, f64) {
    let n = samples.len() as f64;
    let mean = samples.iter().sum::<f64>() / n;
    let squares: f64 = samples.iter().map(|x| (x - mean) * (x - mean)).sum();
    (mean, if samples.len() < 2 { f64::NAN } else { (squares / (n - 1.0)).sqrt() })
}

/// The empirical distribution of a sample, sorted ascending.
#[derive(Clone, Debug, PartialEq)]
pub struct Empirical {
    sorted: Vec<f64>,
}

impl Empirical {
    /// The sample, sorted. Error: a sample that is not finite (named by its index and value).
    pub fn new(samples: &[f64]) -> Result<Empirical, String> {
        if let Some((i, x)) = samples.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(format!("an empirical distribution needs finite samples, sample {i} is {x}"));
        }
        let mut sorted = samples.to_vec();
        sorted.sort_by(f64::total_cmp);
        Ok(Empirical { sorted })
    }

    /// The samples, ascending.
    pub fn sorted(&self) -> &[f64] {
        &self.sorted
    }

    /// The number of samples.
    pub fn len(&self) -> usize {
        self.sorted.len()
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.sorted.is_empty()
    }

    /// (k, n): the k samples strictly above `threshold` among n, for [`clopper_pearson`] or
    /// [`wilson`]. A sample equal to the threshold does not exceed it; a NaN threshold is exceeded
    /// by none.
    pub fn exceedance(&self, threshold: f64) -> (u64, u64) {
        if threshold.is_nan() {
            return (0, self.sorted.len() as u64);
        }
        let at_or_below = self.sorted.partition_point(|&x| x <= threshold);
        ((self.sorted.len() - at_or_below) as u64, self.sorted.len() as u64)
    }

    /// The `p` quantile by the Weibull plotting position: the i-th smallest of n (1-based) is put at
    /// probability i/(n+1), linear in between (Hyndman and Fan 1996, definition 6; numpy's
    /// `quantile(.., method="weibull")`); below 1/(n+1) the smallest sample, above n/(n+1) the
    /// largest. NaN for no samples or `p` outside [0, 1].
    pub fn quantile(&self, p: f64) -> f64 {
        let n = self.sorted.len();
        if n == 0 || !(0.0..=1.0).contains(&p) {
            return f64::NAN;
        }
        // 0-based position p (n + 1) - 1, clamped to the samples.
        let h = (p * (n + 1) as f64 - 1.0).clamp(0.0, (n - 1) as f64);
        let i = h.floor() as usize;
        if i + 1 >= n {
            return self.sorted[n - 1];
        }
        let x = self.sorted[i];
        x + (h - i as f64) * (self.sorted[i + 1] - x)
    }

    /// The mean (NaN for no samples).
    pub fn mean(&self) -> f64 {
        mean_std(&self.sorted).0
    }

    /// The sample standard deviation, n - 1 in the denominator (NaN for fewer than 2 samples).
    pub fn std(&self) -> f64 {
        mean_std(&self.sorted).1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With no overload the count is the closed form's: 368 events for 1e-2 at 97.5 % one-sided
    /// (the two-sided 95 % bound the campaign judges), 3688 for 1e-3, at any events run so far.
    #[test]
    fn events_at_rate_without_overloads_is_events_needed() {
        assert_eq!(events_at_rate(0, 60, 0.01, 0.975), Some(368));
        assert_eq!(events_at_rate(0, 1, 0.001, 0.975), Some(events_needed(0.001, 0.975)));
        assert_eq!(events_at_rate(0, 1, 0.001, 0.975), Some(3688));
    }

    /// 1 overload in 200 events (rate 5e-3, target 1e-2): at every 200 events of the returned
    /// count's neighbourhood the rate is a whole count, and there the verdict's own interval
    /// ([`clopper_pearson`], two-sided 95 %) is at or above the target below the count and below
    /// it from the count on; the continuous bound crosses the target between the count's
    /// predecessor and the count.
    #[test]
    fn events_at_rate_puts_the_verdicts_bound_below_the_target_at_the_observed_rate() {
        let (k, n0, target) = (1, 200, 0.01);
        let m = events_at_rate(k, n0, target, 0.975).unwrap();
        let below = |n: u64| clopper_pearson(n / 200, n, 0.95).high < target;
        let (whole_before, whole_from) = (m / 200 * 200, m.div_ceil(200) * 200);
        assert!(!below(whole_before) && below(whole_from), "count {m}");
        let bound = |n: u64| {
            let k = n as f64 / 200.0;
            beta_quantile(k + 1.0, n as f64 - k, 0.975)
        };
        assert!(bound(m) < target && bound(m - 1) >= target, "count {m}: {} .. {}", bound(m - 1), bound(m));
    }

    /// Events whose bound is already below the target need no more; more overloads at the same
    /// events (a rate nearer the target) need more events; a rate at or above the target, no
    /// events and arguments outside their ranges give no count.
    #[test]
    fn events_at_rate_grows_towards_the_target_and_has_none_at_or_above_it() {
        assert!(clopper_pearson(3, 1000, 0.95).high < 0.01 && clopper_pearson(4, 1000, 0.95).high >= 0.01);
        assert_eq!(events_at_rate(3, 1000, 0.01, 0.975), Some(1000));
        let counts: Vec<u64> = (4..=9).map(|k| events_at_rate(k, 1000, 0.01, 0.975).unwrap()).collect();
        assert!(counts[0] > 1000 && counts.windows(2).all(|w| w[0] < w[1]), "{counts:?}");
        assert_eq!(events_at_rate(10, 1000, 0.01, 0.975), None);
        assert_eq!(events_at_rate(22, 150, 0.01, 0.975), None);
        assert_eq!(events_at_rate(0, 0, 0.01, 0.975), None);
        assert_eq!(events_at_rate(1, 100, f64::NAN, 0.975), None);
        assert_eq!(events_at_rate(2, 1, 0.01, 0.975), None);
    }

    /// A target too small for 64 bits (below about 1e-19) gives no count, never `u64::MAX` as
    /// one; a rate so near the target that the count passes [`MAX_COUNTED_EVENTS`] neither.
    #[test]
    fn events_at_rate_gives_no_count_beyond_what_it_can_count() {
        assert_eq!(events_needed(1e-300, 0.975), u64::MAX);
        assert_eq!(events_at_rate(0, 5, 1e-300, 0.975), None);
        assert_eq!(events_at_rate(999_999, 100_000_000, 0.01, 0.975), None);
    }
}
