//! What a cell's events say together (issue 43): per design quantity (the sweep's peak names) the
//! empirical distribution of the peaks, the probability of exceeding the allowable with its
//! Clopper-Pearson interval, a Gumbel fit (maximum likelihood) of the records' maxima and the most
//! probable maximum over a stated exposure; for the cell, the probability of an overload (any
//! utilisation above 1: the design check fails) with its interval. Each estimate says when its
//! sample is too small for it: no event beyond the allowable gives an upper bound, not zero.

use serde_json::{json, Value};

use crate::error::{Error, Result};
use crate::results::ENVELOPE_PEAK_NAMES;
use crate::studies::statistics::{clopper_pearson, events_needed, Empirical, Gumbel, Interval};
use crate::studies::sweep::RowResults;
use crate::vocabulary::{PEAK_QUANTITIES, PEAK_UNITS};

/// The design quantities summarised, as the sweep names their peaks (`peak.<name>`).
pub const QUANTITIES: [&str; 9] = [
    PEAK_QUANTITIES[0],
    PEAK_QUANTITIES[1],
    PEAK_QUANTITIES[2],
    PEAK_QUANTITIES[3],
    PEAK_QUANTITIES[4],
    ENVELOPE_PEAK_NAMES[0],
    ENVELOPE_PEAK_NAMES[1],
    ENVELOPE_PEAK_NAMES[2],
    ENVELOPE_PEAK_NAMES[3],
];

/// The SI units of [`QUANTITIES`].
pub const UNITS: [&str; 9] =
    [PEAK_UNITS[0], PEAK_UNITS[1], PEAK_UNITS[2], PEAK_UNITS[3], PEAK_UNITS[4], "Pa", "Pa", "Pa", "Pa"];

/// Fewer records than this and the Gumbel fit says it rests on few maxima.
pub const FEW_RECORDS: usize = 10;

/// A campaign's settings besides its grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// Events per cell.
    pub events: u64,
    /// Records (seeds) per cell.
    pub seeds: u64,
    /// Length of each record, s (the events' instants lie in it).
    pub record_length: f64,
    /// The overload probability a cell must stay below to be operable.
    pub target: f64,
    /// The confidence of the intervals (two-sided).
    pub confidence: f64,
    /// Events the most probable maximum is of; None: 1 / target.
    pub exposure: Option<f64>,
    /// Whether a cell is operable on its interval's upper bound (true) or its estimate.
    pub on_upper_bound: bool,
}

impl Default for Options {
    /// 1000 events on 20 three-hour records, target 1e-2 on the 95 % upper bound.
    fn default() -> Self {
        Options {
            events: 1000,
            seeds: 20,
            record_length: 10_800.0,
            target: 0.01,
            confidence: 0.95,
            exposure: None,
            on_upper_bound: true,
        }
    }
}

impl Options {
    /// Every setting inside its range, or a one-line error naming it.
    pub fn check(&self) -> Result<()> {
        if !(self.target > 0.0 && self.target < 1.0) {
            return Err(Error::invalid("--target", "a probability between 0 and 1 (exclusive)", self.target));
        }
        if !(self.confidence >= 0.5 && self.confidence < 1.0) {
            return Err(Error::invalid("--confidence", "between 0.5 and 1 (exclusive)", self.confidence));
        }
        if let Some(n) = self.exposure {
            if !(n.is_finite() && (1.0..=1e15).contains(&n)) {
                return Err(Error::invalid("--exposure", "a number of events from 1 to 1e15", n));
            }
        }
        Ok(())
    }

    /// The events the most probable maximum is of: as given, else 1 / target (the largest peak of
    /// as many losses of the support as the target allows one overload in).
    pub fn exposure(&self) -> f64 {
        self.exposure.unwrap_or_else(|| (1.0 / self.target).round().max(1.0))
    }
}

/// What one event gives the statistics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventResults {
    /// Each quantity's peak (None: the run has no such value, e.g. no shear area given).
    pub peaks: [Option<f64>; 9],
    /// Each quantity's utilisation (None: no allowable).
    pub utilisation: [Option<f64>; 9],
    /// The design check passed (every utilisation <= 1).
    pub design_pass: bool,
    /// The run's verdict.
    pub trusted: bool,
}

impl From<&RowResults> for EventResults {
    fn from(r: &RowResults) -> Self {
        let p = r.peaks.as_array();
        let u = r.utilisation.as_array();
        let e = r.envelope_peaks.map(|e| e.map(|e| e.value));
        let eu = r.utilisation.envelope();
        let finite = |x: f64| x.is_finite().then_some(x);
        EventResults {
            peaks: [Some(p[0]), Some(p[1]), Some(p[2]), Some(p[3]), Some(p[4]), e[0], e[1], e[2], e[3]],
            utilisation: [None, finite(u[0]), finite(u[1]), finite(u[2]), None, eu[0], eu[1], eu[2], eu[3]]
                .map(|x| x.and_then(finite)),
            design_pass: r.design_pass,
            trusted: r.trusted,
        }
    }
}

/// An event as the summary takes it: its record and its results (None: the run failed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventOutcome {
    /// The record's seed.
    pub seed: u64,
    /// The results.
    pub results: Option<EventResults>,
}

/// A probability estimated from `exceeding` of `events`, with its interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exceedance {
    /// Events beyond.
    pub exceeding: u64,
    /// Events in all.
    pub events: u64,
    /// The estimate and its Clopper-Pearson interval.
    pub interval: Interval,
}

impl Exceedance {
    fn new(exceeding: u64, events: u64, confidence: f64) -> Self {
        Exceedance { exceeding, events, interval: clopper_pearson(exceeding, events, confidence) }
    }

    fn json(&self) -> Value {
        json!({
            "probability": self.interval.probability, "low": self.interval.low, "high": self.interval.high,
            "exceeding": self.exceeding, "events": self.events,
        })
    }
}

/// One quantity over a cell's events.
#[derive(Clone, Debug, PartialEq)]
pub struct QuantitySummary {
    /// The quantity's name ([`QUANTITIES`]).
    pub name: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// The events that have it.
    pub samples: usize,
    /// Mean, standard deviation, smallest and largest peak.
    pub mean: f64,
    /// Standard deviation (n - 1).
    pub std: f64,
    /// Smallest peak.
    pub min: f64,
    /// Largest peak.
    pub max: f64,
    /// The 50, 90 and 99 % quantiles (Weibull plotting positions).
    pub quantiles: [f64; 3],
    /// Beyond the allowable (utilisation > 1); None: no allowable.
    pub exceedance: Option<Exceedance>,
    /// The Gumbel fit of the records' maxima, or why there is none.
    pub gumbel: std::result::Result<Gumbel, String>,
    /// The most probable maximum over [`Options::exposure`] events (None without a fit).
    pub most_probable_maximum: Option<f64>,
    /// What the sample cannot vouch for.
    pub warnings: Vec<String>,
}

/// A cell's events together.
#[derive(Clone, Debug, PartialEq)]
pub struct CellSummary {
    /// Events run (failed included).
    pub events: usize,
    /// Events whose run failed (their error in the rows); not in the statistics.
    pub failed: usize,
    /// Events that ran but are not trusted (in the statistics, and counted here).
    pub untrusted: usize,
    /// Records with at least one event.
    pub records: usize,
    /// The overload (the design check fails) probability, of the events that ran.
    pub overload: Exceedance,
    /// What the verdict judges: the overloads with every failed event and every untrusted one
    /// that passed counted as overloads, of all the events (the overload's own when every event
    /// ran and is trusted).
    pub judged_on: Exceedance,
    /// Whether the cell is operable: [`CellSummary::judged_on`]'s estimate or upper bound (as
    /// [`Options::on_upper_bound`]) below the target.
    pub operable: bool,
    /// Each quantity that any event has.
    pub quantities: Vec<QuantitySummary>,
    /// What the cell's sample cannot vouch for.
    pub warnings: Vec<String>,
}

/// The summary of one cell's events.
pub fn summarise(outcomes: &[EventOutcome], options: &Options) -> CellSummary {
    let ok: Vec<(u64, &EventResults)> =
        outcomes.iter().filter_map(|o| o.results.as_ref().map(|r| (o.seed, r))).collect();
    let n = ok.len() as u64;
    let mut seeds: Vec<u64> = ok.iter().map(|(s, _)| *s).collect();
    seeds.dedup();
    seeds.sort_unstable();
    seeds.dedup();
    let overloads = ok.iter().filter(|(_, r)| !r.design_pass).count() as u64;
    let overload = Exceedance::new(overloads, n, options.confidence);
    // The verdict counts every event the model cannot vouch for as an overload: a failed one (the
    // sea beyond the model's range) and an untrusted one that passed.
    let failed = outcomes.len() - ok.len();
    let doubtful = ok.iter().filter(|(_, r)| !r.trusted && r.design_pass).count() as u64;
    let judged_on = Exceedance::new(overloads + doubtful + failed as u64, outcomes.len() as u64, options.confidence);
    let judged = if options.on_upper_bound { judged_on.interval.high } else { judged_on.interval.probability };
    let mut warnings = Vec::new();
    let needed = events_needed(options.target, one_sided(options.confidence));
    if n < needed {
        warnings.push(format!(
            "{n} events cannot show an overload probability below the target {}: at least {needed} with none \
             beyond the allowable are needed (Clopper-Pearson, {} % one-sided)",
            options.target,
            100.0 * one_sided(options.confidence)
        ));
    }
    if overloads == 0 && n > 0 {
        warnings.push(format!(
            "no event overloads: the probability is below {:.3e} ({} % upper bound), not zero",
            overload.interval.high,
            100.0 * options.confidence
        ));
    }
    let untrusted = ok.iter().filter(|(_, r)| !r.trusted).count();
    if untrusted > 0 {
        warnings.push(format!(
            "{untrusted} of {n} events are not trusted (column quality.trusted): the verdict counts them as overloads"
        ));
    }
    if failed > 0 {
        warnings.push(format!(
            "{failed} of {} events failed (column error: e.g. the sea drove the supports beyond the model's range): left \
             out of the statistics, which may then read low, and counted as overloads in the verdict",
            outcomes.len()
        ));
    }
    let quantities = (0..QUANTITIES.len()).filter_map(|q| quantity(q, &ok, &seeds, options)).collect();
    CellSummary {
        events: outcomes.len(),
        failed,
        untrusted,
        records: seeds.len(),
        overload,
        judged_on,
        operable: n > 0 && judged < options.target,
        quantities,
        warnings,
    }
}

/// The one-sided confidence of a two-sided interval's bound: (1 + c) / 2.
fn one_sided(confidence: f64) -> f64 {
    0.5 * (1.0 + confidence)
}

fn quantity(q: usize, ok: &[(u64, &EventResults)], seeds: &[u64], options: &Options) -> Option<QuantitySummary> {
    let given: Vec<(u64, f64)> = ok.iter().filter_map(|(s, r)| r.peaks[q].map(|v| (*s, v))).collect();
    // A converged answer's peaks are finite; one that is not is left out and said.
    let values: Vec<(u64, f64)> = given.iter().copied().filter(|(_, v)| v.is_finite()).collect();
    if values.is_empty() {
        return None;
    }
    let mut warnings = Vec::new();
    if values.len() < given.len() {
        warnings.push(format!("{} events' peaks are not finite and left out", given.len() - values.len()));
    }
    let samples: Vec<f64> = values.iter().map(|(_, v)| *v).collect();
    let empirical = Empirical::new(&samples).ok()?;
    let utilisations: Vec<f64> = ok.iter().filter_map(|(_, r)| r.utilisation[q]).filter(|u| !u.is_nan()).collect();
    let exceedance = (!utilisations.is_empty()).then(|| {
        let k = utilisations.iter().filter(|u| **u > 1.0).count() as u64;
        let e = Exceedance::new(k, utilisations.len() as u64, options.confidence);
        if k == 0 {
            warnings.push(format!(
                "no event beyond the allowable: the probability is below {:.3e}, an upper bound, not zero",
                e.interval.high
            ));
        }
        e
    });
    // The records' maxima.
    let maxima: Vec<f64> = seeds
        .iter()
        .filter_map(|s| values.iter().filter(|(seed, _)| seed == s).map(|(_, v)| *v).reduce(f64::max))
        .collect();
    let gumbel = Gumbel::fit_maximum_likelihood(&maxima);
    if gumbel.is_ok() && maxima.len() < FEW_RECORDS {
        warnings.push(format!("the Gumbel fit rests on {} records' maxima (fewer than {FEW_RECORDS})", maxima.len()));
    }
    let per_record = values.len() as f64 / maxima.len().max(1) as f64;
    let most_probable_maximum = gumbel.as_ref().ok().map(|g| g.most_probable_maximum(per_record, options.exposure()));
    Some(QuantitySummary {
        name: QUANTITIES[q],
        unit: UNITS[q],
        samples: values.len(),
        mean: empirical.mean(),
        std: empirical.std(),
        min: empirical.sorted()[0],
        max: empirical.sorted()[empirical.len() - 1],
        quantiles: [0.5, 0.9, 0.99].map(|p| empirical.quantile(p)),
        exceedance,
        gumbel,
        most_probable_maximum,
        warnings,
    })
}

impl QuantitySummary {
    /// The quantity as the summary JSON gives it.
    pub fn json(&self, options: &Options, per_record: f64) -> Value {
        json!({
            "unit": self.unit,
            "samples": self.samples,
            "mean": self.mean, "std": self.std, "min": self.min, "max": self.max,
            "quantiles": {"0.5": self.quantiles[0], "0.9": self.quantiles[1], "0.99": self.quantiles[2]},
            "exceedance": self.exceedance.as_ref().map(Exceedance::json),
            "gumbel": match &self.gumbel {
                Ok(g) => json!({"location": g.location, "scale": g.scale}),
                Err(_) => Value::Null,
            },
            "gumbel_note": self.gumbel.as_ref().err(),
            "most_probable_maximum": self.most_probable_maximum,
            "exposure": options.exposure(),
            "events_per_record": per_record,
            "warnings": self.warnings,
        })
    }
}

impl CellSummary {
    /// The cell as the summary JSON gives it (without its grid values).
    pub fn json(&self, options: &Options) -> Value {
        let quantities: serde_json::Map<String, Value> = self
            .quantities
            .iter()
            .map(|q| (q.name.to_string(), q.json(options, q.samples as f64 / self.records.max(1) as f64)))
            .collect();
        json!({
            "events": self.events, "failed": self.failed, "untrusted": self.untrusted, "records": self.records,
            "overload": self.overload.json(),
            "judged_on": self.judged_on.json(),
            "operable": self.operable,
            "quantities": quantities,
            "warnings": self.warnings,
        })
    }
}

/// A quantity's unit as printed and the factor from SI to it (MPa, kN, m).
fn printed_unit(unit: &str) -> (&'static str, f64) {
    match unit {
        "Pa" => ("MPa", 1e-6),
        "N" => ("kN", 1e-3),
        _ => ("m", 1.0),
    }
}

/// A probability as printed: 0 as 0, others to four significant digits.
fn probability(p: f64) -> String {
    if p == 0.0 {
        "0".into()
    } else {
        format!("{p:.3e}")
    }
}

/// A cell's summary as printed: its events, the overload probability with its interval and
/// verdict, a line per quantity, and the warnings.
pub fn text(cell: &str, s: &CellSummary, options: &Options) -> String {
    use std::fmt::Write as _;
    let mut t = String::new();
    let c = 100.0 * options.confidence;
    let _ = writeln!(
        t,
        "{cell}: {} events on {} records ({} failed, {} not trusted)",
        s.events, s.records, s.failed, s.untrusted
    );
    let i = s.overload.interval;
    if s.overload.events == 0 {
        let _ = writeln!(t, "overload: no event ran without error, no estimate");
    } else {
        let _ = writeln!(
        t,
        "overload (any utilisation > 1): {} of {}, probability {} ({c} % Clopper-Pearson {} .. {:.3e}): {} (target \
         {} on {})",
        s.overload.exceeding,
        s.overload.events,
        probability(i.probability),
        probability(i.low),
        i.high,
        if s.operable { "operable" } else { "not operable" },
        options.target,
        if options.on_upper_bound { "the upper bound" } else { "the estimate" }
        );
    }
    if (s.judged_on.exceeding, s.judged_on.events) != (s.overload.exceeding, s.overload.events) {
        let j = s.judged_on.interval;
        let _ = writeln!(
            t,
            "judged with the {} failed and untrusted events as overloads: {} of {}, probability {} ({c} % \
             Clopper-Pearson {} .. {:.3e})",
            s.judged_on.exceeding - s.overload.exceeding,
            s.judged_on.exceeding,
            s.judged_on.events,
            probability(j.probability),
            probability(j.low),
            j.high
        );
    }
    let exposure = options.exposure();
    let _ = writeln!(
        t,
        "{:<36} {:>10} {:>10} {:>10} {:>24} {:>21} {:>10}",
        "quantity",
        "mean",
        "p99",
        "max",
        format!("P(> allowable) [{c} %]"),
        "Gumbel loc / scale",
        format!("MPM {exposure}")
    );
    for q in &s.quantities {
        let (unit, k) = printed_unit(q.unit);
        let p = q.exceedance.map_or("no allowable".to_string(), |e| {
            let i = e.interval;
            if e.exceeding == 0 {
                format!("0 (< {:.2e})", i.high)
            } else {
                format!("{:.2e} [{:.1e}, {:.1e}]", i.probability, i.low, i.high)
            }
        });
        let g =
            q.gumbel.as_ref().map_or("no fit".to_string(), |g| format!("{:.2} / {:.3}", g.location * k, g.scale * k));
        let mpm = q.most_probable_maximum.map_or("-".to_string(), |m| format!("{:.2}", m * k));
        let _ = writeln!(
            t,
            "{:<36} {:>10.3} {:>10.3} {:>10.3} {p:>24} {g:>21} {mpm:>10}",
            format!("{} [{unit}]", q.name),
            q.mean * k,
            q.quantiles[2] * k,
            q.max * k
        );
    }
    for w in &s.warnings {
        let _ = writeln!(t, "note: {w}");
    }
    let mut notes: Vec<&String> = s.quantities.iter().flat_map(|q| &q.warnings).collect();
    notes.sort();
    notes.dedup();
    for w in notes {
        let _ = writeln!(t, "note: {w}");
    }
    t
}
