//! The scenario's `[sea]` section (issue 42): a sea state, the vessel's RAO file and where the
//! supports stand on it. The sea becomes the supports' motion table ([`SeaSettings::motion_table`]),
//! so every door that takes a motion file (`run`, `sweep`, `verify`, `beam_impact.run`) takes a sea.
//!
//! Defaults and why:
//! - `spectrum = "jonswap"` with DNV's gamma rule (`peak_enhancement` absent): DNV-RP-C205's
//!   recommendation for a sea state given by Hs and Tp alone;
//! - `heading = 180`: head seas, how a walk-to-work vessel on DP is kept;
//! - `components = 1000`: bins of 0.0045 w_p over the default range (0.0035 rad/s at Tp = 8 s),
//!   at which a three-hour record's Hs and a deck point's heave come within 0.4 % of the spectrum's
//!   (`tests/sea_record.rs`); the frequency drawn inside each bin keeps the record from repeating
//!   (equal spacing would repeat it every 2 pi / dw, 30 min at Tp = 8 s);
//! - `frequency_min`, `frequency_max` absent: 0.5 w_p to 5 w_p (99.8 % of a Pierson-Moskowitz
//!   spectrum's variance: its cumulative is exp(-5/4 (w_p / w)^4)), clipped to the RAO file's
//!   frequencies; a range holding less than [`MIN_ENERGY_FRACTION`] of the spectrum's variance is
//!   refused (the record would fall short of the requested Hs);
//! - `seed = 1`, `time_shift = 0`, `arrestor_direction = 180` (the arrestor pointing aft),
//!   `sample_interval = 0.005` s ([`super::record`] states the error it implies).

use std::sync::{Arc, Mutex};

use serde::{Deserialize, Serialize};

use super::components::WaveComponents;
use super::deck_motion::DeckPoints;
use super::raos::RaoTable;
use super::record::SeaRecord;
use super::spectrum::{Spectrum, SpectrumKind};
use crate::error::{Error, Result};
use crate::model::motion_table::MotionTable;

/// Largest significant wave height, m (beyond the 100-year sea of the northern North Sea).
pub const MAX_HS: f64 = 20.0;
/// The peak period's range, s.
pub const PEAK_PERIOD_RANGE: (f64, f64) = (2.0, 30.0);
/// JONSWAP gamma's range (DNV-RP-C205 3.5.5.5's rule gives 1 to 5; measured seas reach 7).
pub const GAMMA_RANGE: (f64, f64) = (1.0, 7.0);
/// Most wave components.
pub const MAX_COMPONENTS: u32 = 100_000;
/// Largest seed: 2^53, so that the parameter form (an f64) holds every seed exactly.
pub const MAX_SEED: u64 = 1 << 53;
/// The sample interval's range, s.
pub const SAMPLE_INTERVAL_RANGE: (f64, f64) = (1e-4, 0.1);
/// Largest record time, s (`time_shift` and the run after it): 11.6 days.
pub const MAX_RECORD_TIME: f64 = 1e6;
/// Largest |coordinate| of a deck point, m.
pub const MAX_DECK_COORDINATE: f64 = 500.0;
/// Most rows of a record's motion table (80 MB of rows).
pub const MAX_RECORD_ROWS: u64 = 1_000_000;
/// Most component evaluations (rows x components) of one record: about 10 s on one core.
pub const MAX_RECORD_WORK: u64 = 1_000_000_000;
/// The smallest share of the spectrum's variance the components' range must hold: 95 % keeps the
/// record's Hs within 2.5 % of the requested.
pub const MIN_ENERGY_FRACTION: f64 = 0.95;

fn head_seas() -> f64 {
    180.0
}
fn one() -> u64 {
    1
}
fn default_components() -> u32 {
    1000
}
fn aft() -> f64 {
    180.0
}
fn default_sample_interval() -> f64 {
    0.005
}

/// A sea state and the vessel the supports stand on (see the module docs).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeaSettings {
    /// Significant wave height Hs, m (> 0, at most 20).
    pub significant_wave_height: f64,
    /// Peak period Tp, s (2 to 30).
    pub peak_period: f64,
    /// `"jonswap"` (the default) or `"pierson-moskowitz"`.
    #[serde(default)]
    pub spectrum: SpectrumKind,
    /// JONSWAP's peak-enhancement factor gamma (1 to 7); absent: DNV-RP-C205 3.5.5.5's rule.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_enhancement: Option<f64>,
    /// The waves' direction of travel from the bow towards port, deg: 180 head seas, 0 following,
    /// 90 beam seas from starboard (see [`super::raos`]).
    #[serde(default = "head_seas")]
    pub heading: f64,
    /// The random components' seed (0 to 2^53).
    #[serde(default = "one")]
    pub seed: u64,
    /// Number of wave components (1 to 100 000).
    #[serde(default = "default_components")]
    pub components: u32,
    /// Lowest component frequency, rad/s; absent: 0.5 w_p (within the RAO file's range).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequency_min: Option<f64>,
    /// Highest component frequency, rad/s; absent: 5 w_p (within the RAO file's range).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequency_max: Option<f64>,
    /// The record's time at the run's t = 0 (the support lost), s (0 to 1e6).
    #[serde(default)]
    pub time_shift: f64,
    /// The vessel's RAO file (our CSV, or VERES `.re1`), relative to the scenario file's folder.
    pub raos: String,
    /// The hinge's deck point [x, y, z], m from the vessel's motion reference point (x forward,
    /// y to port, z up); absent: the hinge stands on a fixed platform.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hinge_point: Option<[f64; 3]>,
    /// The clamp's deck point, m; absent: the clamp stands on a fixed platform.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clamp_point: Option<[f64; 3]>,
    /// The arrestor's axis (clamp to free end) from the bow towards port, deg (180: aft).
    #[serde(default = "aft")]
    pub arrestor_direction: f64,
    /// Interval of the record's samples the supports follow, s (1e-4 to 0.1).
    #[serde(default = "default_sample_interval")]
    pub sample_interval: f64,
    /// The RAO table, read by the CLI from `raos` (not part of the TOML).
    #[serde(skip)]
    pub rao_table: Option<Arc<RaoTable>>,
    /// The RAO file's SHA-256 (hex), read with it.
    #[serde(skip)]
    pub rao_sha256: String,
    /// The record's table as a log stored it (`report`, `load_log`: a log replays without the RAO
    /// file), with the key ([`SeaSettings::key`]) it was made for.
    #[serde(skip)]
    pub recorded: Option<(String, Arc<MotionTable>)>,
    #[serde(skip)]
    cache: RecordCache,
    #[serde(skip)]
    records: RealisationCache,
}

/// The records made for a scenario and its clones (a run's rungs and twin, a sweep's rows), by
/// key: each is made once. Shared between clones; a few kept.
#[derive(Clone, Debug, Default)]
struct RecordCache(Arc<Mutex<Vec<CachedRecord>>>);

/// A record's key, the RAO table it was made from and its table.
type CachedRecord = (TableKey, Arc<RaoTable>, Arc<MotionTable>);

/// What a realisation depends on besides the RAO table ([`SeaSettings::realisation_key`]): every
/// field but `time_shift` and `sample_interval`, the numbers by their bits (equal bits, equal
/// key: what the fields' text gave, without writing them out for every run's every look-up).
#[derive(Clone, Debug, PartialEq)]
struct RealisationKey {
    numbers: Vec<u64>,
    spectrum: SpectrumKind,
    raos: String,
}

/// What a motion table depends on besides the RAO table: the realisation's key with
/// `time_shift`, `sample_interval` and the run's duration, by their bits.
#[derive(Clone, Debug, PartialEq)]
struct TableKey {
    realisation: RealisationKey,
    span: [u64; 3],
}

impl PartialEq for RecordCache {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// The realisations (components and the supports' coefficients) made for a scenario and its
/// clones, by the fields they depend on (all but `time_shift` and `sample_interval`): a campaign's
/// events of one seed share one (issue 43). Shared between clones; a few kept.
#[derive(Clone, Debug, Default)]
struct RealisationCache(Arc<Mutex<Vec<CachedRealisation>>>);

/// A realisation's key, the RAO table it was made from and the record.
type CachedRealisation = (RealisationKey, Arc<RaoTable>, Arc<SeaRecord>);

impl PartialEq for RealisationCache {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// Records a cache keeps.
const CACHED_RECORDS: usize = 8;

impl SeaSettings {
    /// The spectrum of the sea state.
    pub fn spectrum(&self) -> Spectrum {
        match self.spectrum {
            SpectrumKind::Jonswap => {
                Spectrum::jonswap(self.significant_wave_height, self.peak_period, self.peak_enhancement)
            }
            SpectrumKind::PiersonMoskowitz => {
                Spectrum::pierson_moskowitz(self.significant_wave_height, self.peak_period)
            }
        }
    }

    /// The supports' deck points.
    pub fn deck(&self) -> DeckPoints {
        DeckPoints { hinge: self.hinge_point, clamp: self.clamp_point, arrestor_direction: self.arrestor_direction }
    }

    /// The components' frequency range, rad/s: as given, else 0.5 w_p to 5 w_p within `raos`'s
    /// frequencies.
    pub fn frequency_range(&self, raos: Option<&RaoTable>) -> (f64, f64) {
        let wp = 2.0 * std::f64::consts::PI / self.peak_period;
        let (lo, hi) = raos.map_or((0.0, f64::INFINITY), RaoTable::frequency_range);
        (self.frequency_min.unwrap_or((0.5 * wp).max(lo)), self.frequency_max.unwrap_or((5.0 * wp).min(hi)))
    }

    /// The wave components over [`Self::frequency_range`].
    pub fn components(&self, raos: Option<&RaoTable>) -> WaveComponents {
        let (lo, hi) = self.frequency_range(raos);
        WaveComponents::new(&self.spectrum(), self.components as usize, lo, hi, self.seed)
    }

    /// Every field that breaks its rule (those that need no RAO file), each naming the field.
    pub fn validation_errors(&self, duration: f64) -> Vec<Error> {
        let mut errors = Vec::new();
        let mut check = |ok: bool, name: &'static str, rule: String, value: String| {
            if !ok {
                errors.push(Error::invalid(name, rule, value));
            }
        };
        let hs = self.significant_wave_height;
        check(
            hs.is_finite() && hs > 0.0 && hs <= MAX_HS,
            "sea.significant_wave_height",
            format!("> 0 m, at most {MAX_HS} m"),
            hs.to_string(),
        );
        let tp = self.peak_period;
        let (tmin, tmax) = PEAK_PERIOD_RANGE;
        check((tmin..=tmax).contains(&tp), "sea.peak_period", format!("between {tmin} and {tmax} s"), tp.to_string());
        if let Some(gamma) = self.peak_enhancement {
            let (lo, hi) = GAMMA_RANGE;
            check(
                (lo..=hi).contains(&gamma),
                "sea.peak_enhancement",
                format!("between {lo} and {hi} (absent: DNV's rule)"),
                gamma.to_string(),
            );
            check(
                self.spectrum == SpectrumKind::Jonswap,
                "sea.peak_enhancement",
                "left out with spectrum = \"pierson-moskowitz\" (gamma is JONSWAP's)".into(),
                gamma.to_string(),
            );
        }
        if hs.is_finite() && hs > 0.0 && (tmin..=tmax).contains(&tp) {
            // DNV-RP-C205 3.5.11: a sea's average steepness 2 pi Hs / (g Tp^2) stays below 1/15 for
            // Tp <= 8 s, 1/25 for Tp >= 15 s, linear between; a steeper one breaks, beyond a
            // first-order sea.
            let steepness = 2.0 * std::f64::consts::PI * hs / (9.81 * tp * tp);
            let limit = if tp <= 8.0 {
                1.0 / 15.0
            } else if tp >= 15.0 {
                1.0 / 25.0
            } else {
                1.0 / 15.0 + (tp - 8.0) / 7.0 * (1.0 / 25.0 - 1.0 / 15.0)
            };
            if steepness > limit {
                errors.push(Error::Other(format!(
                    "sea.significant_wave_height = {hs} m with sea.peak_period = {tp} s is steeper than a sea can be: \
                     2 pi Hs / (g Tp^2) = {steepness:.4} > {limit:.4} (DNV-RP-C205 3.5.11; the waves would break)"
                )));
            }
        }
        let mut check = |ok: bool, name: &'static str, rule: String, value: String| {
            if !ok {
                errors.push(Error::invalid(name, rule, value));
            }
        };
        check(
            (0.0..=360.0).contains(&self.heading),
            "sea.heading",
            "between 0 and 360 deg".into(),
            self.heading.to_string(),
        );
        check(
            self.seed <= MAX_SEED,
            "sea.seed",
            format!("a whole number from 0 to 2^53 = {MAX_SEED}"),
            self.seed.to_string(),
        );
        check(
            (1..=MAX_COMPONENTS).contains(&self.components),
            "sea.components",
            format!("between 1 and {MAX_COMPONENTS}"),
            self.components.to_string(),
        );
        for (name, value) in [("sea.frequency_min", self.frequency_min), ("sea.frequency_max", self.frequency_max)] {
            if let Some(w) = value {
                check(
                    w > 0.0 && w <= super::raos::MAX_FREQUENCY,
                    name,
                    format!("> 0 rad/s, at most {}", super::raos::MAX_FREQUENCY),
                    w.to_string(),
                );
            }
        }
        if let (Some(lo), Some(hi)) = (self.frequency_min, self.frequency_max) {
            check(lo < hi, "sea.frequency_max", format!("> sea.frequency_min = {lo} rad/s"), hi.to_string());
        }
        check(
            (0.0..=MAX_RECORD_TIME).contains(&self.time_shift),
            "sea.time_shift",
            format!("between 0 and {MAX_RECORD_TIME:e} s"),
            self.time_shift.to_string(),
        );
        check(!self.raos.is_empty(), "sea.raos", "the vessel's RAO file (.csv or .re1)".into(), "''".into());
        for (name, point) in [("sea.hinge_point", self.hinge_point), ("sea.clamp_point", self.clamp_point)] {
            if let Some(p) = point {
                check(
                    p.iter().all(|c| c.is_finite() && c.abs() <= MAX_DECK_COORDINATE),
                    name,
                    format!("[x, y, z] with each |coordinate| <= {MAX_DECK_COORDINATE} m"),
                    format!("{p:?}"),
                );
            }
        }
        if self.hinge_point.is_none() && self.clamp_point.is_none() {
            errors.push(Error::Other(
                "[sea] has neither sea.hinge_point nor sea.clamp_point: give the deck point of the support(s) on the \
                 vessel (one left out stands on a fixed platform)"
                    .into(),
            ));
        }
        let mut check = |ok: bool, name: &'static str, rule: String, value: String| {
            if !ok {
                errors.push(Error::invalid(name, rule, value));
            }
        };
        check(
            (0.0..=360.0).contains(&self.arrestor_direction),
            "sea.arrestor_direction",
            "between 0 and 360 deg".into(),
            self.arrestor_direction.to_string(),
        );
        let (dmin, dmax) = SAMPLE_INTERVAL_RANGE;
        let dt = self.sample_interval;
        check(
            (dmin..=dmax).contains(&dt),
            "sea.sample_interval",
            format!("between {dmin:e} and {dmax} s"),
            dt.to_string(),
        );
        if (dmin..=dmax).contains(&dt) && duration.is_finite() && duration > 0.0 {
            let rows = (duration / dt).ceil() as u64 + 2;
            let work = rows.saturating_mul(u64::from(self.components));
            if rows > MAX_RECORD_ROWS || work > MAX_RECORD_WORK {
                errors.push(Error::Other(format!(
                    "sea: duration {duration} s at sea.sample_interval = {dt} s is {rows} samples of {} components, \
                     more than {MAX_RECORD_ROWS} samples or {MAX_RECORD_WORK:e} component evaluations: raise \
                     sea.sample_interval or lower sea.components",
                    self.components
                )));
            }
        }
        if self.time_shift.is_finite() && duration.is_finite() && self.time_shift + duration > MAX_RECORD_TIME {
            errors.push(Error::Other(format!(
                "sea.time_shift + duration = {} s is beyond the record's {MAX_RECORD_TIME:e} s",
                self.time_shift + duration
            )));
        }
        errors
    }

    /// What needs the RAO table: the components' range inside its frequencies and holding
    /// [`MIN_ENERGY_FRACTION`] of the variance, the heading interpolable.
    pub fn check_against(&self, raos: &RaoTable) -> Result<()> {
        // A realisation made for these fields and this table passed these checks when it was made
        // (every run validates its scenario: a campaign's events would integrate the spectrum
        // again each time).
        if let Ok(entries) = self.records.0.lock() {
            let key = self.realisation_key();
            if entries.iter().any(|(k, r, _)| *k == key && std::ptr::eq(Arc::as_ptr(r), raos)) {
                return Ok(());
            }
        }
        let (lo, hi) = self.frequency_range(Some(raos));
        let (flo, fhi) = raos.frequency_range();
        for (name, w) in [("sea.frequency_min", lo), ("sea.frequency_max", hi)] {
            if !(flo..=fhi).contains(&w) {
                return Err(Error::invalid(
                    name,
                    format!("within the RAO file's frequencies, {flo} to {fhi} rad/s"),
                    format!("{w} rad/s"),
                ));
            }
        }
        if lo >= hi {
            return Err(Error::Other(format!(
                "sea: the components' range {lo} to {hi} rad/s is empty (the RAO file's frequencies {flo} to {fhi} rad/s \
                 and the spectrum's 0.5 to 5 w_p)"
            )));
        }
        let fraction = self.spectrum().energy_fraction(lo, hi);
        if fraction < MIN_ENERGY_FRACTION {
            return Err(Error::Other(format!(
                "sea: the components' range {lo} to {hi} rad/s holds {:.1} % of the spectrum's variance, less than {} %: \
                 the record's Hs would fall {:.1} % short (widen sea.frequency_min/max, or give RAOs over a wider range \
                 than {flo} to {fhi} rad/s)",
                100.0 * fraction,
                100.0 * MIN_ENERGY_FRACTION,
                100.0 * (1.0 - fraction.sqrt())
            )));
        }
        raos.at_heading(self.heading).map_err(|e| Error::Other(format!("sea.heading = {} deg: {e}", self.heading)))?;
        Ok(())
    }

    /// What a realisation depends on besides the RAO table: every field but `time_shift` and
    /// `sample_interval` (each named here: a field added to the section must say whether it
    /// changes the record), the loaded files' contents left out as the TOML leaves them out.
    fn realisation_key(&self) -> RealisationKey {
        let SeaSettings {
            significant_wave_height,
            peak_period,
            spectrum,
            peak_enhancement,
            heading,
            seed,
            components,
            frequency_min,
            frequency_max,
            time_shift: _,
            raos,
            hinge_point,
            clamp_point,
            arrestor_direction,
            sample_interval: _,
            rao_table: _,
            rao_sha256: _,
            recorded: _,
            cache: _,
            records: _,
        } = self;
        let mut numbers = vec![
            significant_wave_height.to_bits(),
            peak_period.to_bits(),
            heading.to_bits(),
            *seed,
            u64::from(*components),
            arrestor_direction.to_bits(),
        ];
        for value in [peak_enhancement, frequency_min, frequency_max] {
            numbers.extend(match value {
                Some(v) => [1, v.to_bits()],
                None => [0, 0],
            });
        }
        for point in [hinge_point, clamp_point] {
            match point {
                Some(p) => numbers.extend([1, p[0].to_bits(), p[1].to_bits(), p[2].to_bits()]),
                None => numbers.extend([0; 4]),
            }
        }
        RealisationKey { numbers, spectrum: *spectrum, raos: raos.clone() }
    }

    /// What the motion table over a run of `duration` s depends on besides the RAO table.
    fn table_key(&self, duration: f64) -> TableKey {
        TableKey {
            realisation: self.realisation_key(),
            span: [self.time_shift.to_bits(), self.sample_interval.to_bits(), duration.to_bits()],
        }
    }

    /// The record (components and the supports' response) for the loaded RAO table: made once
    /// per realisation and RAO table, and kept by the scenario and its clones.
    pub fn record(&self) -> Result<Arc<SeaRecord>> {
        let raos = self.rao_table.as_ref().ok_or_else(|| not_loaded(&self.raos))?;
        let key = self.realisation_key();
        if let Ok(entries) = self.records.0.lock() {
            if let Some((_, _, record)) = entries.iter().find(|(k, r, _)| *k == key && Arc::ptr_eq(r, raos)) {
                return Ok(Arc::clone(record));
            }
        }
        self.check_against(raos)?;
        let record = Arc::new(
            SeaRecord::new(self.components(Some(raos)), raos, self.heading, &self.deck())
                .map_err(|e| Error::Other(format!("sea: {e}")))?,
        );
        if let Ok(mut entries) = self.records.0.lock() {
            entries.retain(|(k, r, _)| !(*k == key && Arc::ptr_eq(r, raos)));
            entries.insert(0, (key, Arc::clone(raos), Arc::clone(&record)));
            entries.truncate(CACHED_RECORDS);
        }
        Ok(record)
    }

    /// The same settings with caches of their own: nothing made for `self` or its clones (records,
    /// tables) is shared with the copy or its clones (a benchmark's fresh campaign).
    pub fn unshared(&self) -> SeaSettings {
        SeaSettings { cache: RecordCache::default(), records: RealisationCache::default(), ..self.clone() }
    }

    /// What a record depends on besides the RAO table: the section's fields and the run's
    /// duration, as text.
    pub fn key(&self, duration: f64) -> String {
        format!("{}duration={:?}", toml::to_string(self).unwrap_or_default(), duration)
    }

    /// The supports' motion table over the run (record times `time_shift` to `time_shift +
    /// duration`, sampled every `sample_interval` on the record's grid): as a log stored it, else
    /// from the RAO table (made once per key and kept by the scenario and its clones).
    pub fn motion_table(&self, duration: f64) -> Result<Arc<MotionTable>> {
        if let Some(e) = self.validation_errors(duration).into_iter().next() {
            return Err(e);
        }
        if let Some((recorded_key, table)) = &self.recorded {
            if *recorded_key == self.key(duration) {
                return Ok(Arc::clone(table));
            }
        }
        let key = self.table_key(duration);
        let raos = self.rao_table.as_ref().ok_or_else(|| not_loaded(&self.raos))?;
        if let Ok(entries) = self.cache.0.lock() {
            if let Some((_, _, table)) = entries.iter().find(|(k, r, _)| *k == key && Arc::ptr_eq(r, raos)) {
                return Ok(Arc::clone(table));
            }
        }
        let record = self.record()?;
        let table = record
            .table(self.time_shift, self.time_shift + duration, self.sample_interval)
            .map_err(|e| Error::Other(format!("sea: {e}")))?;
        let table = Arc::new(table);
        if let Ok(mut entries) = self.cache.0.lock() {
            entries.retain(|(k, r, _)| !(*k == key && Arc::ptr_eq(r, raos)));
            entries.insert(0, (key, Arc::clone(raos), Arc::clone(&table)));
            entries.truncate(CACHED_RECORDS);
        }
        Ok(table)
    }
}

fn not_loaded(file: &str) -> Error {
    Error::invalid(
        "sea.raos",
        "an RAO file the CLI reads (`[sea] raos` in a scenario file, relative to its folder)",
        format!("'{}', not loaded", crate::model::motion_table::quote_cell(file)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::sea::SeaRecord;
    use crate::Scenario;

    /// A vessel that heaves with the wave and pitches with its slope, both cut off in waves
    /// shorter than its hull (made-up RAOs, 0.1 to 3 rad/s, head and following seas): the sharing of the tables, not the vessel, is under test.
    fn scenario(time_shift: f64) -> Scenario {
        let mut raos = String::from(
            "frequency,heading,surge,surge_phase,sway,sway_phase,heave,heave_phase,roll,roll_phase,pitch,pitch_phase,yaw,yaw_phase\n",
        );
        for heading in [0.0, 180.0] {
            for k in 0..30 {
                let w = 0.1 + 0.1 * f64::from(k);
                let hull = 1.0 / (1.0 + (w / 0.7f64).powi(4));
                raos += &format!("{w},{heading},0,0,0,0,{hull},0,0,0,{},-90,0,0\n", hull * (w * w / 9.81).to_degrees());
            }
        }
        let text = format!(
            "duration = 3.0\n[sea]\nsignificant_wave_height = 2.5\npeak_period = 8.0\nseed = 7\ntime_shift = {time_shift}\n\
             raos = \"test.csv\"\nhinge_point = [-10.0, 0.0, 8.0]\nclamp_point = [15.0, 0.0, 8.0]\n"
        );
        let mut s = Scenario::from_toml(&text, "the test's sea").unwrap();
        if let Some(sea) = s.sea.as_mut() {
            sea.rao_table = Some(Arc::new(RaoTable::parse_csv(&raos).unwrap()));
        }
        s
    }

    fn bits(table: &MotionTable) -> Vec<u64> {
        let values = table.motions.iter().flat_map(|m| m.values());
        table.times.iter().copied().chain(values).map(f64::to_bits).collect()
    }

    /// Issue 43: the three runs of an answer (the printed rung, its check, the twin: clones of one
    /// scenario with the same sea) share one motion table, made once; a table made afresh (caches
    /// of its own, [`SeaSettings::unshared`]) is the shared one to the bit, and the run's start
    /// motion is the table's first row continued to the instant, which is the record's own row
    /// there (one block of [`SeaRecord::motions`]), to the bit.
    #[test]
    fn an_answers_runs_share_one_table_equal_to_the_unshared_one_to_the_bit() {
        let printed = scenario(1234.5678);
        let sea = printed.sea.as_ref().unwrap();
        let table = sea.motion_table(printed.duration).unwrap();
        let twin = Scenario { drop_height: printed.drop_height * (1.0 + 1e-9), ..printed.clone() };
        let check = printed.clone();
        for other in [&twin, &check] {
            let shared = other.sea.as_ref().unwrap().motion_table(other.duration).unwrap();
            assert!(Arc::ptr_eq(&shared, &table), "a clone's table is the one made for the scenario");
        }
        let fresh = sea.unshared().motion_table(printed.duration).unwrap();
        assert!(!Arc::ptr_eq(&fresh, &table));
        assert_eq!(bits(&fresh), bits(&table));
        let start = printed.motion_at_start().unwrap();
        let dt = sea.sample_interval;
        let (first, _) = SeaRecord::grid(sea.time_shift, sea.time_shift + printed.duration, dt);
        let row = sea.record().unwrap().motions(first, first, dt)[0];
        let own = row.after(sea.time_shift - first as f64 * dt);
        assert_eq!(start.values().map(f64::to_bits), own.values().map(f64::to_bits));
        assert_eq!(start.values().map(f64::to_bits), table.motion_at(sea.time_shift).values().map(f64::to_bits));
        // Another instant: a table of its own.
        let later = scenario(2000.0);
        let other = later.sea.as_ref().unwrap().motion_table(later.duration).unwrap();
        assert_ne!(bits(&other), bits(&table));
    }
}
