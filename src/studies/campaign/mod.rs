//! Campaigns of impacts (issue 43): many losses of the gangway's support at instants drawn across
//! several records of a sea state, each event a converged answer with its verdict, and what they
//! say together: per design quantity the distribution of the peaks, the probability of exceeding
//! the allowable with its confidence interval, a Gumbel fit of the records' maxima and the most
//! probable maximum over an exposure ([`summary`]); over a grid of sea states, the operability
//! table ([`operability`]; its figure: [`crate::replay::operability_figure`]).
//!
//! A campaign is a sweep over given points ([`Sweep::of_points`]): each event is the scenario with
//! `sea.seed` and `sea.time_shift` set to its record and instant ([`events`]), each cell of the grid
//! the scenario with its sea-state fields set. The rows come out in the plan's order whatever the
//! number of threads, so the same command writes the same rows. The cells share their seeds (the
//! same random phases, each scaled to its own spectrum): common random numbers, which keep the
//! differences between neighbouring cells from being noise.

pub mod events;
pub mod fatigue;
pub mod operability;
pub mod summary;

use std::fmt::Write as _;
use std::sync::atomic::AtomicBool;

use crate::error::{Error, Result};
use crate::model::scenario::Scenario;
use crate::model::support_motion::{MOTION_NAMES, MOTION_UNITS};
use crate::studies::sweep::{self, expand, field, Axis, Row, Sweep, Tally};

pub use events::{plan, Event};
pub use summary::{CellSummary, Options};

/// The fields a campaign's grid may vary: the sea state's.
pub const CELL_FIELDS: [&str; 3] = ["sea.significant_wave_height", "sea.peak_period", "sea.heading"];

/// Most runs (cells x events) a campaign makes unless told more (`--max-events`): about 17
/// minutes on two cores at the example vessel's 20.5 ms of a core per 3 s event (measured,
/// docs/operability.md).
pub const DEFAULT_MAX_EVENTS: u64 = 100_000;

/// Records a campaign spreads its events over unless told (`--seeds`), or the events' number if
/// fewer ([`default_seeds`]).
pub const DEFAULT_SEEDS: u64 = 20;

/// The records of a campaign of `events` events when `--seeds` is not given: [`DEFAULT_SEEDS`],
/// or one per event if there are fewer events.
pub fn default_seeds(events: u64) -> u64 {
    DEFAULT_SEEDS.min(events).max(1)
}

/// A 3 s event of the example vessel costs about this much of a core, s (docs/operability.md,
/// measured): the `--max-events` message's estimate, scaled by the run's duration.
const EVENT_CORE_SECONDS: f64 = 0.0205;

/// A wall time for a message: seconds under two minutes, minutes under two hours, else hours.
fn duration_text(seconds: f64) -> String {
    if seconds < 120.0 {
        format!("{seconds:.0} s")
    } else if seconds < 7200.0 {
        format!("{:.0} min", seconds / 60.0)
    } else {
        format!("{:.1} h", seconds / 3600.0)
    }
}

/// One cell of the grid: its values (one per grid axis) and, for a sea state the model refuses (a
/// breaking sea, a range outside the RAO file), the reason; its events are then not run.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// The grid axes' values.
    pub values: Vec<f64>,
    /// Why the cell's scenario is refused, if it is.
    pub refused: Option<String>,
}

/// A campaign: the scenario, the grid of sea states, the events of each cell.
#[derive(Clone, Debug)]
pub struct Campaign {
    /// The grid's axes (of [`CELL_FIELDS`]), outermost first; none: one cell, the scenario's sea.
    pub cell_axes: Vec<Axis>,
    /// The cells in grid order.
    pub cells: Vec<Cell>,
    /// The events every cell runs.
    pub events: Vec<Event>,
    /// The statistics' settings.
    pub options: Options,
    /// The runs: for each accepted cell, its events in order.
    sweep: Sweep,
    /// For each run of `sweep`, its cell and event index.
    index: Vec<(usize, usize)>,
    /// The modes of [`Campaign::run_event`]'s runs (one geometry: computed once).
    cache: std::sync::Arc<crate::solver::ModalCache>,
    /// What the campaign sets aside of the scenario, for the user to be told (a `sea.time_shift`,
    /// which each event draws).
    pub notes: Vec<String>,
}

/// One event's row: where it is, the supports' motion at its instant and the run's results.
#[derive(Clone, Debug, PartialEq)]
pub struct EventRow {
    /// The cell's index in [`Campaign::cells`].
    pub cell: usize,
    /// The event's index in [`Campaign::events`].
    pub event: usize,
    /// The supports' motion at the instant, in [`MOTION_NAMES`]' order (None: the row failed).
    pub motion: Option<[f64; 9]>,
    /// The run's row (its values: the grid's, then seed and instant).
    pub row: Row,
}

impl Campaign {
    /// A campaign of `options.events` events on `options.seeds` records for each cell of
    /// `cell_axes` over `base` (which must have a `[sea]`), at most `max_events` runs in all.
    pub fn new(
        base: Scenario,
        cell_axes: Vec<Axis>,
        options: Options,
        max_events: u64,
        max_steps: u64,
    ) -> Result<Self> {
        let Some(sea) = base.sea.as_ref() else {
            return Err(Error::Other(
                "campaign: the scenario has no [sea] section: a campaign draws its events from a sea state's records \
                 (docs/sea-states.md, examples/vessel-sea.toml)"
                    .into(),
            ));
        };
        for axis in &cell_axes {
            if !CELL_FIELDS.contains(&axis.field.name) {
                return Err(Error::Other(format!(
                    "campaign --vary {}: a campaign's grid is of sea states ({}); give other fields with --set",
                    axis.field.name,
                    CELL_FIELDS.join(", ")
                )));
            }
        }
        for axis in &cell_axes {
            // A value given twice would run its cell's events twice and print one row of them.
            let heading = axis.field.name == "sea.heading";
            let mut values: Vec<f64> =
                axis.values.iter().map(|&v| if heading && v == 360.0 { 0.0 } else { v }).collect();
            values.sort_by(f64::total_cmp);
            if let Some(w) = values.windows(2).find(|w| w[0] == w[1]) {
                return Err(Error::Other(format!(
                    "campaign --vary {}: {} is given twice{} (each cell once)",
                    axis.field.name,
                    crate::error::number(w[0]),
                    if heading { " (0 and 360 deg are one heading)" } else { "" }
                )));
            }
        }
        options.check()?;
        let mut notes = Vec::new();
        if sea.time_shift != 0.0 {
            notes.push(format!(
                "sea.time_shift = {} s is not used: each event's instant is drawn over its record (the rows' `instant`)",
                crate::error::number(sea.time_shift)
            ));
        }
        let events = plan(options.events, options.seeds, sea.seed, options.record_length, base.duration)?;
        let grid = sweep::grid_len(&cell_axes)?;
        let total = (grid as u64).saturating_mul(events.len() as u64);
        if total > max_events {
            return Err(Error::Other(format!(
                "campaign of {grid} cells x {} events = {total} runs, more than --max-events {max_events}: lower the \
                 grid or --events, or raise --max-events (about {} on two cores at the example vessel's 20.5 ms of a \
                 core per 3 s event, here {} s)",
                events.len(),
                duration_text(total as f64 * EVENT_CORE_SECONDS * base.duration / 3.0 / 2.0),
                crate::error::number(base.duration)
            )));
        }
        let mut axes = cell_axes.clone();
        axes.push(Axis { field: field("sea.seed")?, values: Vec::new() });
        axes.push(Axis { field: field("sea.time_shift")?, values: Vec::new() });
        let probe = Sweep::new(base.clone(), Vec::new(), max_steps)?;
        let mut cells = Vec::new();
        let mut points = Vec::new();
        let mut index = Vec::new();
        for (c, values) in expand(&cell_axes).into_iter().enumerate() {
            // The cell's scenario at its first event: refused (a breaking sea) or its record made.
            let mut point = values.clone();
            point.extend([events[0].seed as f64, events[0].instant]);
            let check = Sweep { axes: axes.clone(), ..probe.clone() }.scenario(&point).and_then(|s| {
                let sea = s.sea.as_ref().ok_or_else(|| Error::Other("no [sea]".into()))?;
                sea.record().map(|_| ())
            });
            let refused = match check {
                Ok(()) => None,
                // A value the field's rule refuses is the user's to mend, not a sea state the
                // model cannot take (a breaking sea, a range outside the RAO file).
                Err(e) if names_a_field(&e, &cell_axes) => return Err(Error::Other(format!("campaign --vary: {e}"))),
                Err(e) => Some(e.to_string()),
            };
            if refused.is_none() {
                for (k, e) in events.iter().enumerate() {
                    let mut point = values.clone();
                    point.extend([e.seed as f64, e.instant]);
                    points.push(point);
                    index.push((c, k));
                }
            }
            cells.push(Cell { values, refused });
        }
        if let Some(why) =
            cells.iter().map(|c| c.refused.as_ref()).collect::<Option<Vec<_>>>().and_then(|w| w.first().copied())
        {
            return Err(Error::Other(if cells.len() == 1 {
                format!("campaign: the sea state is refused: {why}")
            } else {
                format!("campaign: every cell of the grid is refused, nothing to run; the first: {why}")
            }));
        }
        let sweep = Sweep::of_points(base, axes, points, max_steps)?;
        Ok(Campaign { cell_axes, cells, events, options, sweep, index, cache: Default::default(), notes })
    }

    /// Runs to make (the accepted cells' events).
    pub fn len(&self) -> usize {
        self.sweep.len()
    }

    /// Whether there is nothing to run (every cell refused).
    pub fn is_empty(&self) -> bool {
        self.sweep.is_empty()
    }

    /// Runs every event on `jobs` threads until `cancel` is set, handing each row to `write` in
    /// the plan's order (cells in grid order, then events); `done` after each run with the number
    /// finished.
    pub fn run(
        &self,
        jobs: usize,
        cancel: &AtomicBool,
        done: &mut dyn FnMut(usize),
        write: &mut dyn FnMut(&EventRow) -> Result<()>,
    ) -> Result<Tally> {
        let mut next = 0;
        self.sweep.run_until(jobs, cancel, done, &mut |row| {
            let (cell, event) = self.index[next];
            next += 1;
            let motion = match &row.outcome {
                Ok(_) => Some(self.motion_at(&row.values)?),
                Err(_) => None,
            };
            write(&EventRow { cell, event, motion, row: row.clone() })
        })
    }

    /// Run `index` (0 to [`Campaign::len`]) alone, as [`Campaign::run`] runs it (the Python
    /// package's tasks).
    pub fn run_event(&self, index: usize) -> Result<EventRow> {
        let &(cell, event) = self
            .index
            .get(index)
            .ok_or_else(|| Error::Other(format!("event {index} of a campaign of {} runs", self.len())))?;
        let row = self.sweep.run_one(index, &self.cache);
        let motion = match &row.outcome {
            Ok(_) => Some(self.motion_at(&row.values)?),
            Err(_) => None,
        };
        Ok(EventRow { cell, event, motion, row })
    }

    /// Each run's cell and event index, in the order [`Campaign::run`] writes them.
    pub fn runs(&self) -> &[(usize, usize)] {
        &self.index
    }

    /// Each run's scenario values: the grid's, then `sea.seed` and `sea.time_shift`.
    pub fn points(&self) -> &[Vec<f64>] {
        &self.sweep.points
    }

    /// The summary of each cell from its events' outcomes (None: refused, or no event run).
    pub fn summaries(&self, outcomes: &[Vec<summary::EventOutcome>]) -> Vec<Option<CellSummary>> {
        self.cells
            .iter()
            .zip(outcomes)
            .map(|(cell, o)| (cell.refused.is_none() && !o.is_empty()).then(|| summary::summarise(o, &self.options)))
            .collect()
    }

    /// The operability table's cells from the cells' summaries (those of [`Campaign::summaries`]): each
    /// cell's Hs, Tp and heading (the grid's values, else the scenario's sea's), with its summary or
    /// why it is refused; an accepted cell without events (an interrupted campaign's) as
    /// [`operability::NOT_RUN`].
    pub fn table_cells<'a>(&'a self, summaries: &'a [Option<CellSummary>]) -> Vec<operability::TableCell<'a>> {
        let sea = self.sweep.base.sea.as_ref();
        let value_of = |c: usize, name: &str, default: f64| {
            self.cell_axes.iter().position(|a| a.field.name == name).map_or(default, |k| self.cells[c].values[k])
        };
        self.cells
            .iter()
            .zip(summaries)
            .enumerate()
            .map(|(c, (cell, summary))| {
                let outcome = match (&cell.refused, summary) {
                    (Some(why), _) => Err(why.as_str()),
                    (None, Some(s)) => Ok(s),
                    (None, None) => Err(operability::NOT_RUN),
                };
                operability::TableCell {
                    significant_wave_height: value_of(
                        c,
                        "sea.significant_wave_height",
                        sea.map_or(f64::NAN, |s| s.significant_wave_height),
                    ),
                    peak_period: value_of(c, "sea.peak_period", sea.map_or(f64::NAN, |s| s.peak_period)),
                    heading: value_of(c, "sea.heading", sea.map_or(f64::NAN, |s| s.heading)),
                    outcome,
                }
            })
            .collect()
    }

    /// The supports' motion at the event's instant (the record's exact sums).
    pub fn motion_at(&self, values: &[f64]) -> Result<[f64; 9]> {
        let scenario = self.sweep.scenario(values)?;
        let sea = scenario.sea.as_ref().ok_or_else(|| Error::Other("no [sea]".into()))?;
        Ok(sea.record()?.motion(sea.time_shift).values())
    }

    /// The CSV columns with their units: the grid's fields, `event`, `seed`, `instant`, the supports'
    /// motion at the instant, then a sweep row's results (`peak.<quantity>`, utilisations, design,
    /// trust, wall time, error).
    pub fn column_units(&self) -> Vec<(String, &'static str)> {
        let mut c: Vec<(String, &'static str)> =
            self.cell_axes.iter().map(|a| (a.field.name.to_string(), a.field.unit)).collect();
        c.extend([("event".into(), "1"), ("seed".into(), "1"), ("instant".into(), "s")]);
        c.extend(MOTION_NAMES.iter().zip(MOTION_UNITS).map(|(n, u)| (n.to_string(), u)));
        c.extend(sweep::column_units_with(&[], self.sweep.fatigue));
        c
    }

    /// The CSV header line.
    pub fn csv_header(&self) -> String {
        self.column_units().iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>().join(",") + "\n"
    }

    /// One event's CSV line (numbers as the shortest decimal that gives the same f64).
    pub fn csv_line(&self, row: &EventRow) -> String {
        let mut s = String::new();
        for (axis, v) in self.cell_axes.iter().zip(&row.row.values) {
            let _ = write!(s, "{},", sweep::format_value(axis.field, *v));
        }
        let event = &self.events[row.event];
        let _ = write!(s, "{},{},{:?},", row.event, event.seed, event.instant);
        match &row.motion {
            Some(m) => m.iter().for_each(|v| {
                let _ = write!(s, "{v:?},");
            }),
            None => s.push_str(&",".repeat(MOTION_NAMES.len())),
        }
        let results = Row { values: Vec::new(), ..row.row.clone() };
        s + &sweep::csv_line_with(&[], &results, self.sweep.fatigue)
    }

    /// The cell's name for messages and tables: `Hs 2.5 m, Tp 8 s`, or `the scenario's sea`.
    pub fn cell_name(&self, cell: usize) -> String {
        let names: Vec<String> = self
            .cell_axes
            .iter()
            .zip(&self.cells[cell].values)
            .map(|(a, v)| match a.field.name {
                "sea.significant_wave_height" => format!("Hs {v} m"),
                "sea.peak_period" => format!("Tp {v} s"),
                _ => format!("heading {v} deg"),
            })
            .collect();
        if names.is_empty() {
            "the scenario's sea".into()
        } else {
            names.join(", ")
        }
    }
}

impl Campaign {
    /// Assess each event's fatigue (`campaign --fatigue`, issue 44): the rows get the sweep's
    /// fatigue columns ([`sweep::FATIGUE_COLUMNS`]), each run keeping its stations' turning points.
    pub fn set_fatigue(&mut self, on: bool) {
        self.sweep.fatigue = on;
    }

    /// Whether the events' fatigue is assessed.
    pub fn fatigue(&self) -> bool {
        self.sweep.fatigue
    }

    /// Each cell's sea state `[Hs, Tp, heading]`: the grid's values, else the scenario's sea's.
    pub fn sea_states(&self) -> Vec<[f64; 3]> {
        let sea = self.sweep.base.sea.as_ref();
        let base = [
            sea.map_or(f64::NAN, |s| s.significant_wave_height),
            sea.map_or(f64::NAN, |s| s.peak_period),
            sea.map_or(f64::NAN, |s| s.heading),
        ];
        self.cells
            .iter()
            .map(|cell| {
                let mut state = base;
                for (axis, v) in self.cell_axes.iter().zip(&cell.values) {
                    let k = CELL_FIELDS.iter().position(|f| *f == axis.field.name).unwrap_or(0);
                    state[k] = *v;
                }
                state
            })
            .collect()
    }

    /// The campaign's fatigue ([`fatigue::assess`]) from each cell's events' damages (`damages[c]`:
    /// [`event_damage`] of each event that has one) and failed events, on the scenario's
    /// `[fatigue]` curve, weighted by `occurrence` if given.
    pub fn fatigue_of(
        &self,
        damages: &[Vec<f64>],
        failed: &[usize],
        occurrence: Option<&fatigue::Occurrence>,
    ) -> Result<fatigue::CampaignFatigue> {
        let settings = crate::model::fatigue_fields::of(&self.sweep.base);
        let varies_heading = self.cell_axes.iter().any(|a| a.field.name == "sea.heading");
        fatigue::assess(&self.sea_states(), damages, failed, &settings, occurrence, varies_heading)
    }
}

/// Whether `e` is (or holds) a rule broken by one of the grid's own fields.
fn names_a_field(e: &Error, axes: &[Axis]) -> bool {
    match e {
        Error::InvalidParameter { name, .. } => axes.iter().any(|a| a.field.name == name),
        Error::Invalid(errors) => errors.iter().any(|e| names_a_field(e, axes)),
        _ => false,
    }
}

/// An event's damage (its worst station's Miner sum), if its run ran with fatigue.
pub fn event_damage(row: &EventRow) -> Option<f64> {
    row.row.outcome.as_ref().ok().and_then(|r| r.fatigue).map(|f| f.damage)
}

/// The campaign's statistics as one JSON document: the settings and methods stated, each cell with
/// its grid values and summary (or why it was refused), and the operability limits.
pub fn summary_document(
    campaign: &Campaign,
    summaries: &[Option<CellSummary>],
    table: &[operability::TableCell],
    options: &Options,
) -> serde_json::Value {
    use serde_json::json;
    let cells: Vec<serde_json::Value> = campaign
        .cells
        .iter()
        .zip(summaries)
        .map(|(cell, summary)| {
            let mut object = serde_json::Map::new();
            for (axis, v) in campaign.cell_axes.iter().zip(&cell.values) {
                object.insert(axis.field.name.to_string(), json!(v));
            }
            match (&cell.refused, summary) {
                (Some(why), _) => {
                    object.insert("refused".into(), json!(why));
                }
                (None, Some(s)) => {
                    if let serde_json::Value::Object(m) = s.json(options) {
                        object.extend(m);
                    }
                }
                (None, None) => {
                    object.insert("events".into(), json!(0));
                }
            }
            serde_json::Value::Object(object)
        })
        .collect();
    let limits: Vec<serde_json::Value> = operability::limits(table)
        .iter()
        .map(|l| json!({"heading": l.heading, "peak_period": l.peak_period, "significant_wave_height": l.significant_wave_height}))
        .collect();
    // Each run cell's events, failed ones included: fewer than planned when interrupted.
    let run: usize = summaries.iter().flatten().map(|s| s.events).sum();
    json!({
        "campaign": {
            "events_per_cell": options.events,
            "records_per_cell": options.seeds,
            "events_planned": campaign.len(),
            "events_run": run,
            "interrupted": run < campaign.len(),
            "record_length": options.record_length,
            "first_seed": campaign.events.first().map(|e| e.seed),
            "target": options.target,
            "confidence": options.confidence,
            "criterion": if options.on_upper_bound { "upper bound" } else { "estimate" },
            "exposure": options.exposure(),
            "interval": "Clopper-Pearson (exact, two-sided)",
            "gumbel_method": "maximum likelihood, of each record's largest peak",
            "most_probable_maximum": "the mode of the largest of `exposure` events: location + scale ln(exposure / events_per_record)",
            "overload": "any utilisation > 1 (the design check fails)",
        },
        "cells": cells,
        "operability": {"limits": limits},
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `--max-events` message's estimate reads as a person would say it: seconds, minutes or
    /// hours, never "0 min".
    #[test]
    fn a_wall_time_is_said_in_seconds_minutes_or_hours() {
        assert_eq!(
            [duration_text(0.3), duration_text(90.0), duration_text(600.0), duration_text(10_800.0)],
            ["0 s", "90 s", "10 min", "3.0 h"]
        );
    }
}
