//! What a cell's events say together (issue 43): per design quantity (the sweep's peak names) the
//! empirical distribution of the peaks, the probability of exceeding the allowable with its
//! Clopper-Pearson interval, a Gumbel fit (maximum likelihood) of the records' maxima and the most
//! probable maximum over a stated exposure; for the cell, the probability of an overload (any
//! utilisation above 1: the design check fails) with its interval. Each estimate says when its
//! sample is too small for it: no event beyond the allowable gives an upper bound, not zero.

use serde_json::{json, Value};

use crate::error::{Error, Result};
use crate::results::ENVELOPE_PEAK_NAMES;
use crate::studies::statistics::{clopper_pearson, events_at_rate, Empirical, Gumbel, Interval, MAX_COUNTED_EVENTS};
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

/// The largest `--exposure`, events.
pub const MAX_EXPOSURE: f64 = 1e15;

/// The smallest `--target`: 1 / target is the default exposure, held to `--exposure`'s range
/// (no campaign could show less anyway: 3.7e15 events without an overload).
pub const MIN_TARGET: f64 = 1.0 / MAX_EXPOSURE;

/// An exposure more than this many times the events a fit rests on is noted as an extrapolation:
/// fitted to the maxima of 100 Rayleigh peaks, the Gumbel mode is 4.8 % over the exact one at 100
/// times the fitted exposure and the gap grows with ln of the ratio (statistics.rs,
/// [`Gumbel::most_probable_maximum`]), while the fit's own scatter is multiplied by that ln.
pub const EXTRAPOLATION: f64 = 100.0;

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
        if !(self.target >= MIN_TARGET && self.target < 1.0) {
            return Err(Error::invalid(
                "--target",
                "a probability from 1e-15 to 1 (exclusive; 1 / target is the default --exposure)",
                significant(self.target),
            ));
        }
        if !(self.confidence >= 0.5 && self.confidence < 1.0) {
            return Err(Error::invalid("--confidence", "between 0.5 and 1 (exclusive)", self.confidence));
        }
        if let Some(n) = self.exposure {
            if !(n.is_finite() && (1.0..=MAX_EXPOSURE).contains(&n)) {
                return Err(Error::invalid("--exposure", "a number of events from 1 to 1e15", significant(n)));
            }
        }
        Ok(())
    }

    /// The events the most probable maximum is of: as given, else 1 / target (the largest peak of
    /// as many losses of the support as the target allows one overload in), held to `--exposure`'s
    /// range (options that [`Options::check`] passes need no holding).
    pub fn exposure(&self) -> f64 {
        // A target outside its range (NaN included) gives 1, as a target of 1 would.
        self.exposure.unwrap_or_else(|| match (1.0 / self.target).round() {
            e if e >= 1.0 => e.min(MAX_EXPOSURE),
            _ => 1.0,
        })
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
    warnings.extend(events_note(&judged_on, n, options));
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
            "{untrusted} of {} {} not trusted (column quality.trusted): the verdict counts {}",
            counted(n, "event", "events"),
            if untrusted == 1 { "is" } else { "are" },
            if untrusted == 1 { "it as an overload" } else { "them as overloads" }
        ));
    }
    if failed > 0 {
        warnings.push(format!(
            "{failed} of {} failed (column error: e.g. the sea drove the supports beyond the model's range): left \
             out of the statistics, which may then read low, and counted as overloads in the verdict",
            counted(outcomes.len() as u64, "event", "events")
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

/// What the verdict's counts (`judged`: k overloads of N events) cannot show, when their
/// interval's upper bound is not below the target. With no overload: the fewest events, none of
/// them an overload, that would show it. With overloads at a rate below the target: the events
/// that would show it if the rate held (the Clopper-Pearson bound of the observed rate,
/// [`events_at_rate`]; more if the rate rises). At or above the target: that more events at this
/// rate cannot. None when the bound is below the target, or when no event ran (`ran`: nothing to
/// go on, the failed events' note says why).
fn events_note(judged: &Exceedance, ran: u64, options: &Options) -> Option<String> {
    let (k, n) = (judged.exceeding, judged.events);
    if ran == 0 || n == 0 || judged.interval.high < options.target {
        return None;
    }
    let level = one_sided(options.confidence);
    let target = significant(options.target);
    let method = format!("Clopper-Pearson, {} % one-sided", 100.0 * level);
    let rate = judged.interval.probability;
    let needed = events_at_rate(k, n, options.target, level);
    let overloads = format!(
        "{k} of the {} judged {}",
        counted(n, "event", "events"),
        if k == 1 { "is an overload" } else { "are overloads" }
    );
    Some(if k == 0 {
        let needed = needed.map_or(format!("more than {:.1e}", u64::MAX as f64), |m| m.to_string());
        format!(
            "{} cannot show an overload probability below the target {target}: at least {needed} with none beyond \
             the allowable are needed ({method})",
            counted(n, "event", "events")
        )
    } else if rate >= options.target {
        format!(
            "{overloads}, an estimate of {} at or above the target {target}: more events at this rate will not show \
             the overload probability below it",
            probability(rate)
        )
    } else {
        let needed = needed.map_or(format!("more than {:.0e}", MAX_COUNTED_EVENTS as f64), |m| format!("about {m}"));
        format!(
            "{overloads}, an estimate of {} whose upper bound {:.3e} is not below the target {target}: at this rate \
             {needed} events would show it below ({method}, of the observed rate; more if the rate rises)",
            probability(rate),
            judged.interval.high
        )
    })
}

/// `n` and its noun, singular for one: "1 event", "2 events".
pub fn counted(n: u64, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// A number as printed, to four significant digits: plainly from 1e-4 to 1e6 (0.01, 100, 13.5),
/// else with an exponent (1e-15, 3.689e300), so that neither a tiny target nor a huge exposure
/// prints hundreds of digits. Non-finite values as Rust writes them.
pub fn significant(x: f64) -> String {
    fn trimmed(s: &str) -> &str {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.')
        } else {
            s
        }
    }
    if !x.is_finite() || x == 0.0 {
        return format!("{x}");
    }
    let exponent = x.abs().log10().floor();
    if (-4.0..6.0).contains(&exponent) {
        let decimals = (3.0 - exponent).max(0.0) as usize;
        trimmed(&format!("{x:.decimals$}")).to_string()
    } else {
        let s = format!("{x:.3e}");
        let (mantissa, power) = s.split_once('e').unwrap_or((&s, "0"));
        format!("{}e{power}", trimmed(mantissa))
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
        let left_out = given.len() - values.len();
        warnings.push(if left_out == 1 {
            "1 event's peak is not finite and left out".to_string()
        } else {
            format!("{left_out} events' peaks are not finite and left out")
        });
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
    let exposure = options.exposure();
    if gumbel.is_ok() {
        warnings.extend(exposure_note(exposure, values.len(), per_record));
    }
    let most_probable_maximum = gumbel.as_ref().ok().map(|g| g.most_probable_maximum(per_record, exposure));
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

/// What the most probable maximum over `exposure` events cannot vouch for, fitted to the maxima
/// of records of `per_record` events, `events` in all: more than [`EXTRAPOLATION`] times the
/// events is an extrapolation of the fit's tail; fewer than a record's events moves the records'
/// mode down, which is not the largest of that many events (below the mean, with a small enough
/// exposure).
fn exposure_note(exposure: f64, events: usize, per_record: f64) -> Option<String> {
    if exposure > EXTRAPOLATION * events as f64 {
        Some(format!(
            "the most probable maximum over {} events extrapolates the fit {} times beyond the {} it rests \
             on (more than {EXTRAPOLATION}: the tail is the Gumbel's, not the sample's)",
            significant(exposure),
            significant(exposure / events as f64),
            counted(events as u64, "event", "events")
        ))
    } else if exposure < per_record {
        Some(format!(
            "the exposure ({}) is fewer events than the {} per record whose maxima are fitted: the most probable \
             maximum then moves the records' maxima down and is not the largest peak of that many events",
            significant(exposure),
            significant(per_record)
        ))
    } else {
        None
    }
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
        "{cell}: {} on {} ({} failed, {} not trusted)",
        counted(s.events as u64, "event", "events"),
        counted(s.records as u64, "record", "records"),
        s.failed,
        s.untrusted
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
        significant(options.target),
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
    if !s.quantities.is_empty() {
        let _ = writeln!(
            t,
            "{:<36} {:>10} {:>10} {:>10} {:>24} {:>21} {:>10}",
            "quantity",
            "mean",
            "p99",
            "max",
            format!("P(> allowable) [{c} %]"),
            "Gumbel loc / scale",
            format!("MPM {}", significant(options.exposure()))
        );
    }
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
    for (names, w) in quantity_notes(&s.quantities) {
        let _ = writeln!(t, "note ({names}): {w}");
    }
    t
}

/// The quantities' notes, each once with the quantities it is of (in the table's order): their
/// names, "every quantity" when all have it, "every quantity with an allowable" when exactly
/// those with an exceedance have it.
fn quantity_notes(quantities: &[QuantitySummary]) -> Vec<(String, &String)> {
    let mut notes: Vec<(&String, Vec<&QuantitySummary>)> = Vec::new();
    for q in quantities {
        for w in &q.warnings {
            match notes.iter_mut().find(|(note, _)| *note == w) {
                Some((_, of)) => of.push(q),
                None => notes.push((w, vec![q])),
            }
        }
    }
    let with_allowable = quantities.iter().filter(|q| q.exceedance.is_some()).count();
    notes
        .into_iter()
        .map(|(w, of)| {
            let names = if of.len() == quantities.len() && of.len() > 1 {
                "every quantity".to_string()
            } else if of.len() == with_allowable && of.len() > 1 && of.iter().all(|q| q.exceedance.is_some()) {
                "every quantity with an allowable".to_string()
            } else {
                of.iter().map(|q| q.name).collect::<Vec<_>>().join(", ")
            };
            (names, w)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An event on record `seed` with clamp bending stress `stress` (utilisation `stress` / 500
    /// MPa) and the clamp shear stress at 0.1 of its allowable; None: its run failed.
    fn event(seed: u64, stress: Option<f64>) -> EventOutcome {
        let results = stress.map(|s| {
            let mut peaks = [None; 9];
            let mut utilisation = [None; 9];
            peaks[0] = Some(0.5 + s * 1e-10);
            (peaks[1], utilisation[1]) = (Some(s), Some(s / 500e6));
            (peaks[2], utilisation[2]) = (Some(1e7 + s * 1e-3), Some(0.1));
            EventResults { peaks, utilisation, design_pass: s <= 500e6, trusted: true }
        });
        EventOutcome { seed, results }
    }

    /// `n` events over `records` records, the `overloads` first beyond the allowable, the `failed`
    /// last failed; the stresses differ event to event.
    fn cell(n: u64, records: u64, overloads: u64, failed: u64) -> Vec<EventOutcome> {
        (0..n)
            .map(|i| {
                let stress =
                    if i < overloads { 510e6 + i as f64 * 1e5 } else { 300e6 + (i * 7919 % 1000) as f64 * 1e5 };
                event(i % records, (i < n - failed).then_some(stress))
            })
            .collect()
    }

    fn options() -> Options {
        Options { events: 150, seeds: 10, ..Options::default() }
    }

    /// The defect's cell (22 of 150 judged, 7 overloads of 135 run and 15 failed): an estimate
    /// already above the target is told that more events will not bring it below, with the
    /// verdict's counts, not "135 events cannot show ... at least 368 ... are needed".
    #[test]
    fn a_cell_already_above_its_target_is_told_more_events_will_not_bring_it_below() {
        let s = summarise(&cell(150, 10, 7, 15), &options());
        assert_eq!((s.judged_on.exceeding, s.judged_on.events), (22, 150));
        let note = s.warnings.iter().find(|w| w.contains("judged")).expect("a note on the judged events");
        assert!(
            note.starts_with(
                "22 of the 150 events judged are overloads, an estimate of 1.467e-1 at or above the target \
             0.01: more events at this rate will not show"
            ),
            "{note}"
        );
        assert!(!s.warnings.iter().any(|w| w.contains("cannot show") || w.contains("at least")), "{:?}", s.warnings);
    }

    /// Overloads at a rate below the target whose bound is not yet below it: the note gives the
    /// events that would show it at that rate ([`events_at_rate`] of the judged counts: 15 of 150,
    /// all failed, target 0.12).
    #[test]
    fn overloads_below_the_target_give_the_events_their_rate_needs() {
        let options = Options { target: 0.12, ..options() };
        let s = summarise(&cell(150, 10, 0, 15), &options);
        let needed = events_at_rate(15, 150, 0.12, 0.975).unwrap();
        assert!(needed > 150, "{needed}");
        let note = s.warnings.iter().find(|w| w.contains("judged")).expect("a note on the judged events");
        assert!(
            note.starts_with("15 of the 150 events judged are overloads, an estimate of 1.000e-1 whose upper bound"),
            "{note}"
        );
        assert!(note.contains(&format!("at this rate about {needed} events would show it below")), "{note}");
    }

    /// With no overload the note keeps its closed form, of the events judged: 60 events, 368
    /// needed at 0.01; a cell whose bound is below the target has no such note.
    #[test]
    fn no_overload_gives_the_events_needed_with_none_beyond() {
        let s = summarise(&cell(60, 6, 0, 0), &options());
        assert!(s.warnings.contains(
            &"60 events cannot show an overload probability below the target 0.01: at least 368 with none beyond the \
              allowable are needed (Clopper-Pearson, 97.5 % one-sided)"
                .to_string()
        ));
        let s = summarise(&cell(400, 10, 0, 0), &options());
        assert!(s.operable && !s.warnings.iter().any(|w| w.contains("cannot show")), "{:?}", s.warnings);
    }

    /// No event ran (all failed): no count of events is made up from nothing ("0 events cannot
    /// show ..."); the failed events' note says what happened.
    #[test]
    fn no_event_run_gives_no_events_note() {
        let s = summarise(&cell(150, 10, 0, 150), &options());
        assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
        assert!(s.warnings[0].starts_with("150 of 150 events failed"), "{:?}", s.warnings);
        assert!(!text("c", &s, &options()).contains("quantity"), "no table header without quantities");
    }

    /// A target of 1e-300 (past the check, as a library caller may): printed as 1e-300, its count
    /// beyond 64 bits said as "more than 1.8e19", never u64::MAX; the default exposure held to
    /// 1e15 in the header and the JSON; and the check refuses it, naming the bound.
    #[test]
    fn a_tiny_target_prints_no_sentinel_and_no_long_numbers() {
        let options = Options { events: 5, seeds: 5, target: 1e-300, ..Options::default() };
        let s = summarise(&cell(5, 5, 0, 0), &options);
        let t = text("c", &s, &options);
        assert!(
            t.contains("target 1e-300") && t.contains("more than 1.8e19 with none") && t.contains("MPM 1e15"),
            "{t}"
        );
        assert!(!t.contains(&u64::MAX.to_string()) && !t.contains("0000000000"), "{t}");
        assert_eq!(options.exposure(), 1e15);
        assert_eq!(s.json(&options)["quantities"]["lower.clamp_bending_stress"]["exposure"], 1e15);
        let e = options.check().unwrap_err().to_string();
        assert_eq!(
            e,
            "--target must be a probability from 1e-15 to 1 (exclusive; 1 / target is the default --exposure), got 1e-300"
        );
        assert!(Options { target: 1e-15, ..options.clone() }.check().is_ok());
    }

    /// The notes under the table name their quantities: the clamp shear's "no event beyond the
    /// allowable" is not printed bare under a clamp bending stress with exceedances; a note every
    /// quantity has says so.
    #[test]
    fn each_note_names_its_quantities() {
        let s = summarise(&cell(60, 6, 3, 0), &options());
        let t = text("c", &s, &options());
        assert!(
            t.contains("note (lower.clamp_shear_stress): no event beyond the allowable: the probability is below"),
            "{t}"
        );
        assert!(t.contains("note (every quantity): the Gumbel fit rests on 6 records' maxima"), "{t}");
        assert!(!t.lines().any(|l| l.starts_with("note: no event beyond")), "{t}");
        let s = summarise(&cell(60, 6, 0, 0), &options());
        let t = text("c", &s, &options());
        assert!(t.contains("note (every quantity with an allowable): no event beyond the allowable"), "{t}");
    }

    /// An exposure more than 100 times the events fitted is noted as an extrapolation (60 events:
    /// 6000 is not, 6001 is); one below a record's events (10 here) is noted as not the largest of
    /// that many; the default (1 / target = 100) is neither.
    #[test]
    fn an_exposure_far_beyond_the_sample_or_below_a_record_is_noted() {
        let outcomes = cell(60, 6, 0, 0);
        let notes = |exposure: Option<f64>| {
            let s = summarise(&outcomes, &Options { exposure, ..options() });
            s.quantities[1].warnings.clone()
        };
        let extrapolates = |w: &Vec<String>| w.iter().any(|w| w.contains("extrapolates the fit"));
        let below = |w: &Vec<String>| w.iter().any(|w| w.contains("fewer events than the 10 per record"));
        assert!(!extrapolates(&notes(Some(6000.0))) && extrapolates(&notes(Some(6001.0))));
        let far = notes(Some(1e15));
        assert!(
            far.iter().any(|w| w.starts_with(
                "the most probable maximum over 1e15 events extrapolates the fit 1.667e13 times beyond the 60 events"
            )),
            "{far:?}"
        );
        assert!(below(&notes(Some(1.0))) && !below(&notes(Some(10.0))));
        assert!(!extrapolates(&notes(None)) && !below(&notes(None)));
    }

    /// Counts of one are singular in the printed summary.
    #[test]
    fn one_event_on_one_record_is_singular() {
        let s = summarise(&cell(1, 1, 0, 0), &options());
        let t = text("c", &s, &options());
        assert!(t.starts_with("c: 1 event on 1 record (0 failed, 0 not trusted)"), "{t}");
        assert!(t.contains("1 event cannot show"), "{t}");
        assert_eq!(counted(2, "event", "events"), "2 events");
        let mut untrusted = cell(5, 1, 0, 0);
        if let Some(r) = untrusted[0].results.as_mut() {
            r.trusted = false;
        }
        let s = summarise(&untrusted, &options());
        assert!(
            s.warnings
                .iter()
                .any(|w| w.starts_with("1 of 5 events is not trusted") && w.ends_with("counts it as an overload")),
            "{:?}",
            s.warnings
        );
    }

    /// Four significant digits at most; plain from 1e-4 to 1e6, an exponent outside.
    #[test]
    fn significant_prints_no_long_numbers() {
        let cases = [
            (0.01, "0.01"),
            (100.0, "100"),
            (13.5, "13.5"),
            (1.0 / 3.0, "0.3333"),
            (21.428_571, "21.43"),
            (0.000_1, "0.0001"),
            (999_999.0, "999999"),
            (1e6, "1e6"),
            (1e15, "1e15"),
            (1e-15, "1e-15"),
            (1e-300, "1e-300"),
            (3.688_879e300, "3.689e300"),
            (0.0, "0"),
            (f64::NAN, "NaN"),
        ];
        for (x, shown) in cases {
            assert_eq!(significant(x), shown, "{x:e}");
        }
    }
}
