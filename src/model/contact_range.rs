//! The contact's range for every law (issue 40 item 3): the rate the steps are sized for
//! ([`contact_rate`]: the linear bar's k, a power law's or Hertz's tangent stiffness at four
//! times the impact's energy) at most [`MAX_CONTACT_STIFFNESS`], the linear law's own limit. A
//! power law of exponent 1 is the linear bar in its own unit, and above that rate it chatters as
//! the bar did (measured in [`MAX_CONTACT_STIFFNESS`]'s doc and docs/scenario-files.md), so the
//! bound is on the rate, not on k in N/m^n (whose own range, up to
//! [`MAX_POWER_LAW_STIFFNESS`], only keeps the numbers finite).

use super::contact_law::LawKind;
use super::rigid_impactor::RADIUS_RANGE;
use super::scenario::{bound, Scenario, MAX_CONTACT_STIFFNESS, MAX_POWER_LAW_STIFFNESS, SMALLEST_CONTACT_STIFFNESS};
use super::system::contact_rate;
use crate::error::Error;

/// The largest contact rate accepted, N/m, for every law: the linear law's
/// [`MAX_CONTACT_STIFFNESS`] (its measured reason is there).
pub const MAX_CONTACT_RATE: f64 = MAX_CONTACT_STIFFNESS;

/// Why a rate above [`MAX_CONTACT_RATE`] is refused, with the measured example (the default
/// scenario at drop 0.5 m, 3 s, the whole answer's CPU time, on main 4668379 before the bound).
const REASON: &str =
    "stiffer, the contact chatters and the run's cost is erratic (exponent 1 at 1e12 N/m, drop 0.5 m: \
                      2 166 contact windows, 3.6 s against 0.13 s at 4e10 N/m, not trusted)";

/// The refusal of a nonlinear law (`contact.law` = "power" or "hertz") whose rate at this
/// scenario's impact exceeds [`MAX_CONTACT_RATE`], naming the field to change and its largest
/// accepted value here; `None` for any other. Call it on a scenario whose every field is
/// within its own range (then the rate is finite).
pub fn rate_error(s: &Scenario) -> Option<Error> {
    if s.contact.law == LawKind::Linear {
        // k itself, already held to MAX_CONTACT_STIFFNESS by its own range.
        return None;
    }
    let rate = contact_rate(s);
    if rate <= MAX_CONTACT_RATE {
        return None;
    }
    let law = s.contact_law()?;
    let energy = format!(
        "its tangent stiffness at 4 times this impact's energy {} J or at twice its static compression",
        fmt4(s.impact_energy())
    );
    let (name, largest, given) = match s.contact.law {
        LawKind::Hertz => {
            let largest = largest_accepted(s, RADIUS_RANGE.0, s.upper.radius, |t, r| t.upper.radius = r)
                .map_or_else(|| "none".into(), |r| format!("{} m", fmt4(r)));
            let given = format!(
                "{} m (Hertz's constant 4/3 E* sqrt(R) = {} N/m^1.5)",
                bound(s.upper.radius),
                fmt4(law.stiffness)
            );
            ("upper.radius", largest, given)
        }
        _ => {
            let largest = largest_accepted(s, SMALLEST_CONTACT_STIFFNESS, law.stiffness, |t, k| {
                t.contact.given_stiffness = Some(k)
            })
            .map_or_else(|| "none".into(), |k| format!("{} N/m^{}", fmt4(k), law.exponent));
            let given =
                format!("{} N/m^{} with contact.exponent = {}", bound(law.stiffness), law.exponent, law.exponent);
            ("contact.stiffness", largest, given)
        }
    };
    Some(Error::invalid(
        name,
        format!(
            "at most {largest} at this impact, so that the contact's rate ({energy}) is <= {MAX_CONTACT_RATE:e} N/m, \
             the linear law's limit: {REASON}"
        ),
        format!("{given}, a contact rate of {} N/m", fmt4(rate)),
    ))
}

impl Scenario {
    /// [`rate_error`] of this scenario: what `Scenario::validate` adds once every field is in
    /// its own range (a method here, so that scenario.rs needs no path to this file).
    pub fn contact_rate_error(&self) -> Option<Error> {
        rate_error(self)
    }
}

/// The largest k (N/m^n) of `s`'s power law whose rate at `s`'s impact is within
/// [`MAX_CONTACT_RATE`] (`None` for the linear law and Hertz's, whose constant is not given, or
/// when none is): what the refusal names, and the top of the range `beam-impact bench` runs.
pub fn largest_power_stiffness(s: &Scenario) -> Option<f64> {
    if s.contact.law != LawKind::Power {
        return None;
    }
    largest_accepted(s, SMALLEST_CONTACT_STIFFNESS, MAX_POWER_LAW_STIFFNESS, |t, k| t.contact.given_stiffness = Some(k))
}

/// The largest value of one field (set on a copy of `s` by `put`) in `low..=high` whose
/// contact rate is within [`MAX_CONTACT_RATE`] (the rate rises with it: a stiffer law or a
/// larger sphere), by bisection in its logarithm to 1e-12 relative; `None` when even `low`'s
/// rate is above it.
fn largest_accepted(s: &Scenario, low: f64, high: f64, put: impl Fn(&mut Scenario, f64)) -> Option<f64> {
    let mut trial = s.clone();
    let mut rate_at = |x: f64| {
        put(&mut trial, x);
        contact_rate(&trial)
    };
    let within = |rate: f64| rate <= MAX_CONTACT_RATE; // false for NaN
    if !within(rate_at(low)) {
        return None;
    }
    let (mut lo, mut hi) = (low.ln(), high.ln());
    for _ in 0..200 {
        if hi - lo <= 1e-12 {
            break;
        }
        let mid = 0.5 * (lo + hi);
        if within(rate_at(mid.exp())) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(lo.exp())
}

/// Four significant digits, in the exponent form for the large and the small.
fn fmt4(x: f64) -> String {
    if x.is_finite() && x != 0.0 && !(1e-3..1e4).contains(&x.abs()) {
        format!("{x:.4e}")
    } else {
        format!("{}", (x * 1e4).round() / 1e4)
    }
}

// MAX_POWER_LAW_STIFFNESS still bounds k's own unit: for the exponents above 1 a large k in
// N/m^n may have a small rate at a small compression.
const _: () = assert!(MAX_POWER_LAW_STIFFNESS > MAX_CONTACT_RATE);
