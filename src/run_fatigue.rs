//! The fatigue of one run (issue 44 item 3): every bending station's stress history, as its
//! turning points ([`StationHistories`], kept while the printed run steps:
//! [`crate::solver::turning_points`], or rebuilt from a log's `/beam/stations` rows), counted by
//! rainflow (ASTM E1049-85, [`crate::fatigue::count`]) and summed by Palmgren-Miner on the
//! scenario's S-N curve with its factors ([`crate::model::fatigue_settings`]): the damage of one
//! impact (one event) per station, each beam's worst station, the hot spots (the arrestor's
//! clamp, the bridge's contact point, each side of a section change, each beam's largest
//! |stress|), and with a number of events a year the life 1 / (damage x events).
//!
//! Only the bending (direct) stresses are assessed: the RP's S-N curves are of direct stress
//! ranges; the shear stations' histories are not kept. Pure numbers: the run document, the log's
//! `fatigue.json` and `report --fatigue` take their text from here, and write nothing here.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::fatigue::{count, damage, life_years};
use crate::model::fatigue_settings::FatigueSettings;

/// The name of a history kept at every step of the printed run.
pub const EVERY_STEP: &str = "every step";

/// The name of a history rebuilt from a log's `/beam/stations` rows.
pub const LOG_ROWS: &str = "the log's /beam/stations rows";

/// The note on a history rebuilt from a log's rows.
pub const LOG_ROWS_NOTE: &str = "rebuilt from the log's /beam/stations rows (sampled every 1 ms by default, not every \
                                 step): cycles faster than the rows are missed, the damage is a lower bound";

/// The format number of `fatigue.json`.
pub const FORMAT: u32 = 1;

/// One bending station's history.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StationHistory {
    /// `"lower"` (the arrestor, from its clamp) or `"upper"` (the bridge, from its hinge).
    pub beam: String,
    /// Position along the beam, m from its support.
    pub position: f64,
    /// The stress's turning points, Pa, in time order (the first and the last sample included).
    pub reversals: Vec<f64>,
}

/// Every bending station's history of a run: what the log attaches as `fatigue.json`, from
/// which any curve can be applied.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StationHistories {
    /// `fatigue.json`'s format ([`FORMAT`]).
    pub format: u32,
    /// Where the samples come from: [`EVERY_STEP`] or [`LOG_ROWS`].
    pub source: String,
    /// Each station sampled every this many internal steps (1: every step; a large model's
    /// envelope strides: [`crate::solver::envelope::ENVELOPE_BUDGET`]).
    pub sampled_every: u64,
    /// The bridge's contact point, m from the hinge (its hot spot).
    pub contact_position: f64,
    /// The stations: the arrestor's from its clamp, then the bridge's from its hinge.
    pub stations: Vec<StationHistory>,
}

impl StationHistories {
    /// The histories of a run's stations from the simulation's turning points `points` (kept
    /// with [`crate::Simulation::keep_turning_points`]) sampled every `stride` steps, the
    /// stations of `model`.
    pub fn of_run(
        model: &crate::model::Model,
        points: &crate::solver::turning_points::TurningPoints,
        stride: u64,
    ) -> StationHistories {
        let st = &model.stations;
        let (lower, lower_shear) = (st.lower.bending.len(), st.lower.shear.len());
        let stations = points
            .stations()
            .iter()
            .enumerate()
            .map(|(i, &k)| {
                let (beam, station) = if k < lower {
                    ("lower", &st.lower.bending[k])
                } else {
                    ("upper", &st.upper.bending[k - lower - lower_shear])
                };
                StationHistory { beam: beam.into(), position: station.x, reversals: points.of(i) }
            })
            .collect();
        StationHistories {
            format: FORMAT,
            source: EVERY_STEP.into(),
            sampled_every: stride,
            contact_position: model.scenario.contact_position,
            stations,
        }
    }

    /// Reads `fatigue.json`'s text, checking what a stranger's file could break (the format,
    /// the beams' names, finite numbers).
    pub fn from_json(text: &str) -> Result<StationHistories> {
        let h: StationHistories = serde_json::from_str(text)
            .map_err(|e| Error::Other(format!("fatigue.json: not a station history: {e}")))?;
        if h.format != FORMAT {
            return Err(Error::Other(format!("fatigue.json: format {} (this build reads {FORMAT})", h.format)));
        }
        for (k, s) in h.stations.iter().enumerate() {
            if s.beam != "lower" && s.beam != "upper" {
                return Err(Error::Other(format!("fatigue.json: station {k}'s beam is `{}`", s.beam.escape_debug())));
            }
            if let Some(v) = std::iter::once(&s.position).chain(&s.reversals).find(|v| !v.is_finite()) {
                return Err(Error::Other(format!("fatigue.json: station {k} holds {v}, not a finite number")));
            }
        }
        Ok(h)
    }
}

/// A station's fatigue, or a hot spot's.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HotSpot {
    /// `"lower"` or `"upper"`.
    pub beam: String,
    /// What it is: `clamp`, `contact`, `section change`, `largest stress`, `worst`.
    pub name: String,
    /// Position along the beam, m from its support.
    pub position: f64,
    /// Miner's sum of one event, with the SCF, thickness correction and DFF.
    pub damage: f64,
    /// Cycles counted (half cycles as 0.5).
    pub cycles: f64,
    /// The largest nominal stress range, Pa (before the SCF).
    pub largest_range: f64,
}

/// Each beam's worst station.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Worst {
    /// The bridge's.
    pub upper: Option<HotSpot>,
    /// The arrestor's.
    pub lower: Option<HotSpot>,
}

/// Every station's damage along one beam.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BeamDamage {
    /// Positions, m from the support.
    pub positions: Vec<f64>,
    /// Damage of one event at each.
    pub damage: Vec<f64>,
}

/// The fatigue of a run: the `fatigue` block of `run --json` and what `report --fatigue` prints.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunFatigue {
    /// The S-N curve's name.
    pub curve: String,
    /// The stress concentration factor.
    pub scf: f64,
    /// The detail's thickness, m (None: no correction).
    pub thickness: Option<f64>,
    /// The design fatigue factor.
    pub design_fatigue_factor: f64,
    /// Events a year (None: no life).
    pub events_per_year: Option<f64>,
    /// Where the histories come from ([`EVERY_STEP`], [`LOG_ROWS`]).
    pub source: String,
    /// Each station sampled every this many internal steps.
    pub sampled_every: u64,
    /// The hot spots, the arrestor's first.
    pub hot_spots: Vec<HotSpot>,
    /// Each beam's worst station.
    pub worst: Worst,
    /// The life of the worst station, years: 1 / (damage x events_per_year).
    pub life_years: Option<f64>,
    /// Every station's damage along each beam.
    pub stations: StationDamage,
    /// What the reader should know of the histories (a rebuilt one's sampling), if anything.
    pub note: Option<String>,
}

/// Every station's damage, per beam.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StationDamage {
    /// The bridge's.
    pub upper: BeamDamage,
    /// The arrestor's.
    pub lower: BeamDamage,
}

/// One station's fatigue.
fn station(s: &StationHistory, settings: &FatigueSettings, name: &str) -> Result<HotSpot> {
    let curve = settings.curve()?;
    let cycles = count(&s.reversals);
    Ok(HotSpot {
        beam: s.beam.clone(),
        name: name.into(),
        position: s.position,
        damage: damage(&cycles, &curve, &settings.options()),
        cycles: cycles.iter().map(|c| c.count).sum(),
        largest_range: cycles.iter().fold(0.0, |a, c| a.max(c.range)),
    })
}

/// The fatigue of `histories` on the curve and factors of `settings` (validated here: a bad one
/// is the error of its field).
pub fn assess(histories: &StationHistories, settings: &FatigueSettings) -> Result<RunFatigue> {
    let mut errors = settings.validation_errors();
    if !errors.is_empty() {
        return Err(if errors.len() == 1 { errors.remove(0) } else { Error::Invalid(errors) });
    }
    let all: Vec<HotSpot> =
        histories.stations.iter().map(|s| station(s, settings, "station")).collect::<Result<_>>()?;
    let mut hot_spots = Vec::new();
    let mut worst = Worst::default();
    let mut stations = StationDamage::default();
    for beam in ["lower", "upper"] {
        let indices: Vec<usize> = (0..all.len()).filter(|&k| all[k].beam == beam).collect();
        let Some(&first) = indices.first() else { continue };
        let named = |k: usize, name: &str| HotSpot { name: name.into(), ..all[k].clone() };
        if beam == "lower" {
            hot_spots.push(named(first, "clamp"));
        } else if let Some(&k) = indices.iter().min_by(|&&a, &&b| {
            let d = |k: usize| (all[k].position - histories.contact_position).abs();
            d(a).total_cmp(&d(b))
        }) {
            // The bridge's station at its contact point (the nearest: the contact node's).
            hot_spots.push(named(k, "contact"));
        }
        // Each section change: two stations at one position (each side's section); the worse.
        for pair in indices.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            if all[a].position == all[b].position {
                let k = if all[b].damage > all[a].damage { b } else { a };
                hot_spots.push(named(k, "section change"));
            }
        }
        // The largest |stress|: the largest |turning point| (a history's extremes are turning
        // points).
        let peak = |k: usize| histories.stations[k].reversals.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        if let Some(&k) = indices.iter().max_by(|&&a, &&b| peak(a).total_cmp(&peak(b))) {
            hot_spots.push(named(k, "largest stress"));
        }
        let w =
            indices.iter().copied().max_by(|&a, &b| all[a].damage.total_cmp(&all[b].damage)).map(|k| named(k, "worst"));
        let damage = BeamDamage {
            positions: indices.iter().map(|&k| all[k].position).collect(),
            damage: indices.iter().map(|&k| all[k].damage).collect(),
        };
        if beam == "lower" {
            (worst.lower, stations.lower) = (w, damage);
        } else {
            (worst.upper, stations.upper) = (w, damage);
        }
    }
    let largest = [&worst.lower, &worst.upper].into_iter().flatten().fold(0.0f64, |a, h| a.max(h.damage));
    Ok(RunFatigue {
        curve: settings.curve()?.name,
        scf: settings.scf,
        thickness: settings.thickness,
        design_fatigue_factor: settings.design_fatigue_factor,
        events_per_year: settings.events_per_year,
        source: histories.source.clone(),
        sampled_every: histories.sampled_every,
        hot_spots,
        worst,
        // A damage too small for its life to be a finite number (below ~1e-300) has none.
        life_years: settings.events_per_year.and_then(|n| life_years(largest, n)).filter(|l| l.is_finite()),
        stations,
        note: (histories.source != EVERY_STEP).then(|| LOG_ROWS_NOTE.to_string()),
    })
}

impl RunFatigue {
    /// The worst station of both beams.
    pub fn worst(&self) -> Option<&HotSpot> {
        [&self.worst.lower, &self.worst.upper].into_iter().flatten().max_by(|a, b| a.damage.total_cmp(&b.damage))
    }

    /// The two lines `run` prints: the worst station's damage per event with its curve and
    /// factors, and the life (or how to get one).
    pub fn lines(&self) -> [String; 2] {
        let beam = |b: &str| if b == "upper" { "bridge" } else { "arrestor" };
        let first = match self.worst() {
            Some(w) => format!(
                "fatigue ({}, SCF {}, DFF {}{}): worst {} at {:.3} m, damage {:.3e} per impact ({} cycles, largest \
                 range {:.1} MPa; {})",
                self.curve,
                self.scf,
                self.design_fatigue_factor,
                self.thickness.map_or_else(String::new, |t| format!(", t {t} m")),
                beam(&w.beam),
                w.position,
                w.damage,
                w.cycles,
                w.largest_range * 1e-6,
                self.source
            ),
            None => "fatigue: no bending station".to_string(),
        };
        let second = match (self.life_years, self.events_per_year) {
            (Some(life), Some(n)) => format!("fatigue life at {n} impacts a year: {} years", years(life)),
            (None, Some(n)) => format!("fatigue life at {n} impacts a year: unbounded (no damage)"),
            _ => "fatigue life: give [fatigue] events_per_year (or --set fatigue.events_per_year=N)".to_string(),
        };
        [first, second]
    }
}

/// A life in years as the lines print it: three decimals from 0.001 to a million, else
/// scientific (also the sweep's and the campaign's lines).
pub fn years(life: f64) -> String {
    if (1e-3..1e6).contains(&life) {
        format!("{life:.3}")
    } else {
        format!("{life:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant-amplitude history of n full cycles of range S on the D curve's first branch
    /// (S and S/2 above the switch range 52.63 MPa): damage n / N(S) = n S^3 / 10^12.164 (S in MPa,
    /// DNV-RP-C203 2016 Table 2-1, m1 = 3, log a1 = 12.164), times SCF^3 with an SCF, times DFF.
    /// Relative 1e-12: one power and a sum of n terms.
    #[test]
    fn constant_amplitude_damage_is_n_over_the_curves_cycles() {
        let (n, s_mpa) = (40usize, 200.0);
        let mut reversals = vec![0.0];
        for _ in 0..n {
            reversals.extend([s_mpa * 1e6 / 2.0, -s_mpa * 1e6 / 2.0]);
        }
        reversals.push(0.0);
        let histories = StationHistories {
            format: FORMAT,
            source: EVERY_STEP.into(),
            sampled_every: 1,
            contact_position: 0.0,
            stations: vec![StationHistory { beam: "lower".into(), position: 0.0, reversals }],
        };
        let base = assess(&histories, &FatigueSettings::default()).unwrap();
        let w = base.worst.lower.as_ref().unwrap();
        // Counted by ASTM E1049's rainflow: n - 1 full cycles of S, and the residue 0, S/2, -S/2,
        // 0 as half cycles S/2, S, S/2 (S/2 = 100 MPa: on the first branch too).
        let expected = ((n - 1) as f64 + 0.5) * s_mpa.powi(3) / 10f64.powf(12.164)
            + 2.0 * 0.5 * (s_mpa / 2.0).powi(3) / 10f64.powf(12.164);
        assert!((w.damage / expected - 1.0).abs() < 1e-12, "{} {expected}", w.damage);
        let settings = FatigueSettings { scf: 1.2, design_fatigue_factor: 2.0, ..Default::default() };
        let scaled = assess(&histories, &settings).unwrap();
        let ratio = scaled.worst.lower.as_ref().unwrap().damage / w.damage;
        assert!((ratio / (2.0 * 1.2f64.powi(3)) - 1.0).abs() < 1e-12, "{ratio}");
    }
}
