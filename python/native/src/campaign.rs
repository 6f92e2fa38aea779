//! `beam_impact.campaign` (issue 43) through the crate's campaign, the code of `beam-impact
//! campaign`: the plan (cells, records, instants), each event's row (the CLI's CSV columns, in
//! their order), and the statistics, operability table and figures of the rows run. The Python
//! side only moves rows: on threads (the crate's own pool, [`Campaign::run`], the GIL released) or
//! as a cluster's tasks (one event each, [`Campaign::run_event`] in a worker, which builds the
//! same campaign from the texts its caller read: [`campaign_sources`]).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use beam_impact::record::output::{
    check_size, open_input, open_regular_input, read_bounded, shown, MAX_SCENARIO_BYTES,
};
use beam_impact::scenario_file::{attach_raos, file_of_scenario, MAX_RAO_BYTES};
use beam_impact::studies::campaign::summary::{self, EventOutcome, EventResults};
use beam_impact::studies::campaign::{self as campaign, operability, EventRow, Options};
use beam_impact::studies::sweep::{self, Row};
use beam_impact::{Error, Scenario};
use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;

use crate::value_error;

/// How often the calling thread looks for Ctrl-C and moves the progress bar while the threads run.
const WATCH_INTERVAL: Duration = Duration::from_millis(50);

/// What the statistics take of one event: each quantity's peak and utilisation (None: none), the
/// design check's verdict and the run's ([`EventResults`]' fields), and its fatigue damage (None:
/// no fatigue asked).
type Results = (Vec<Option<f64>>, Vec<Option<f64>>, bool, bool, Option<f64>);

/// One event as Python gets it: its index in the plan, its row as JSON (an array of the cells
/// before the results, then the results' object, the CLI's columns in order) and its results for
/// the statistics (None: the run failed).
type EventOut = (usize, String, String, Option<Results>);

/// What a campaign's scenario is made of, as read here: (its name in messages, its TOML, the RAO
/// file's path and text when it has a `[sea]`). `path`: a scenario file (read through the CLI's
/// bounded readers); else `text`, whose RAO file is relative to the current folder (as standard
/// input's is). A cluster's workers build the campaign from these texts, never from a file.
#[pyfunction]
#[pyo3(signature = (path=None, text=None))]
pub fn campaign_sources(
    py: Python<'_>,
    path: Option<PathBuf>,
    text: Option<String>,
) -> PyResult<(String, String, Option<String>, Option<String>)> {
    if let Some(p) = &path {
        crate::refuse_nul("the scenario file", p)?;
    }
    py.detach(|| -> beam_impact::Result<_> {
        let (name, text, folder) = match (&path, text) {
            (Some(p), _) => {
                let file = open_input(p, "cannot read scenario")?;
                let text = check_size(&file, MAX_SCENARIO_BYTES, "the scenario")
                    .and_then(|()| read_bounded(file, MAX_SCENARIO_BYTES, "the scenario"))
                    .map_err(|source| Error::Io { action: "cannot read scenario", path: shown(p), source })?;
                (shown(p), text, p.parent().unwrap_or(Path::new("")).to_path_buf())
            }
            (None, Some(t)) => ("text".to_string(), t, PathBuf::new()),
            (None, None) => return Err(Error::Other("campaign: give a scenario (a file or its TOML text)".into())),
        };
        let scenario = Scenario::from_toml(&text, &name)?;
        let raos = match scenario.sea {
            None => None,
            Some(sea) => {
                let p = file_of_scenario("sea.raos", &sea.raos, &folder, "")?;
                let file = open_regular_input(&p, "cannot read RAO file")?;
                let raos = check_size(&file, MAX_RAO_BYTES, "the RAO file")
                    .and_then(|()| read_bounded(file, MAX_RAO_BYTES, "the RAO file"))
                    .map_err(|source| Error::Io { action: "cannot read RAO file", path: shown(&p), source })?;
                Some((p.display().to_string(), raos))
            }
        };
        let (raos_path, raos_text) = raos.unzip();
        Ok((name, text, raos_path, raos_text))
    })
    .map_err(value_error)
}

/// A campaign planned, as `beam-impact campaign` plans it: the scenario from its texts
/// ([`campaign_sources`]), `set` and `vary` as the CLI's `--set` and `--vary` texts, the settings
/// as its options. ValueError with the crate's one-line message for anything it refuses.
#[pyclass(frozen, module = "beam_impact._native")]
pub struct Campaign {
    inner: campaign::Campaign,
    /// The sea states' occurrence (`--occurrence`), if given.
    occurrence: Option<campaign::fatigue::Occurrence>,
}

#[pymethods]
impl Campaign {
    #[new]
    #[pyo3(signature = (name, text, raos_path, raos_text, set, vary, events, seeds, record_length, target, confidence,
        exposure, on_estimate, max_events, max_steps, fatigue=false, occurrence=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        name: String,
        text: String,
        raos_path: Option<String>,
        raos_text: Option<String>,
        set: Vec<String>,
        vary: Vec<String>,
        events: u64,
        seeds: u64,
        record_length: f64,
        target: f64,
        confidence: f64,
        exposure: Option<f64>,
        on_estimate: bool,
        max_events: u64,
        max_steps: u64,
        fatigue: bool,
        occurrence: Option<String>,
    ) -> PyResult<Self> {
        let options =
            Options { events, seeds, record_length, target, confidence, exposure, on_upper_bound: !on_estimate };
        py.detach(|| -> beam_impact::Result<Self> {
            if text.len() as u64 > MAX_SCENARIO_BYTES {
                return Err(Error::Other(format!(
                    "{name}: {} bytes of scenario, more than the limit of {MAX_SCENARIO_BYTES}",
                    text.len()
                )));
            }
            let mut base = Scenario::from_toml(&text, &name)?;
            if let (Some(path), Some(raos)) = (&raos_path, &raos_text) {
                attach_raos(&mut base, Path::new(path), raos)?;
            }
            sweep::apply_settings(&mut base, &sweep::parse_settings(&set)?)?;
            let mut inner =
                campaign::Campaign::new(base.clone(), sweep::parse_axes(&vary)?, options, max_events, max_steps)?;
            inner.set_fatigue(fatigue);
            if fatigue {
                // A bad curve or factor is refused before any event runs, as the CLI does.
                let mut errors = beam_impact::model::fatigue_fields::of(&base).validation_errors();
                if !errors.is_empty() {
                    return Err(if errors.len() == 1 { errors.remove(0) } else { Error::Invalid(errors) });
                }
            }
            // The occurrence table parsed and matched to the grid before any event runs.
            let occurrence = occurrence.map(|text| campaign::fatigue::Occurrence::parse(&text)).transpose()?;
            if let Some(table) = &occurrence {
                let varies_heading = inner.cell_axes.iter().any(|a| a.field.name == "sea.heading");
                table.weights(&inner.sea_states(), varies_heading)?;
            }
            Ok(Campaign { inner, occurrence })
        })
        .map_err(value_error)
    }

    /// Runs to make (the accepted cells' events).
    fn __len__(&self) -> usize {
        self.inner.len()
    }

    /// The CSV's columns (`beam-impact campaign --out`'s header), in order.
    fn columns(&self) -> Vec<String> {
        self.inner.column_units().into_iter().map(|(n, _)| n).collect()
    }

    /// The columns with their units (the CLI's units sidecar).
    fn column_units(&self) -> Vec<(String, String)> {
        self.inner.column_units().into_iter().map(|(n, u)| (n, u.to_string())).collect()
    }

    /// Each run's (cell, event) index, in the plan's order.
    fn runs(&self) -> Vec<(usize, usize)> {
        self.inner.runs().to_vec()
    }

    /// The events every cell runs: (seed, instant in s).
    fn events(&self) -> Vec<(u64, f64)> {
        self.inner.events.iter().map(|e| (e.seed, e.instant)).collect()
    }

    /// The cells in grid order: (the grid's values, why the cell is refused or None).
    fn cells(&self) -> Vec<(Vec<f64>, Option<String>)> {
        self.inner.cells.iter().map(|c| (c.values.clone(), c.refused.clone())).collect()
    }

    /// What the campaign sets aside of the scenario (a `sea.time_shift`), for a warning.
    fn notes(&self) -> Vec<String> {
        self.inner.notes.clone()
    }

    /// The cells' names as messages give them (`Hs 2.5 m, Tp 8 s`).
    fn cell_names(&self) -> Vec<String> {
        (0..self.inner.cells.len()).map(|c| self.inner.cell_name(c)).collect()
    }

    /// The grid's fields, outermost first.
    fn grid_fields(&self) -> Vec<String> {
        self.inner.cell_axes.iter().map(|a| a.field.name.to_string()).collect()
    }

    /// Run `index` of the plan alone, as the threads run it (a cluster's task); the GIL released.
    fn run_event(&self, py: Python<'_>, index: usize) -> PyResult<EventOut> {
        py.detach(|| self.inner.run_event(index).map(|row| self.event_out(index, &row))).map_err(value_error)
    }

    /// Runs every event on `jobs` threads (None: one per core; the CLI's pool, rows in the plan's order), the GIL
    /// released; `progress(n)` on the calling thread as events finish. Ctrl-C (on the main thread):
    /// no new event starts, and the rows before the first not run come back. Returns (the rows,
    /// whether interrupted).
    #[pyo3(signature = (jobs=None, progress=None))]
    fn run(&self, py: Python<'_>, jobs: Option<usize>, progress: Option<Py<PyAny>>) -> PyResult<(Vec<EventOut>, bool)> {
        let jobs = jobs.unwrap_or_else(sweep::default_jobs);
        let cancel = AtomicBool::new(false);
        let done = AtomicUsize::new(0);
        let mut interrupted = false;
        let mut failure: Option<PyErr> = None;
        let rows = py.detach(|| {
            std::thread::scope(|scope| {
                let (cancel, done) = (&cancel, &done);
                let worker = scope.spawn(move || {
                    let mut rows = Vec::with_capacity(self.inner.len());
                    self.inner
                        .run(jobs.max(1), cancel, &mut |n| done.store(n, Ordering::Relaxed), &mut |row| {
                            rows.push(self.event_out(rows.len(), row));
                            Ok(())
                        })
                        .map(|_| rows)
                });
                let mut shown = 0;
                while !worker.is_finished() {
                    std::thread::park_timeout(WATCH_INTERVAL);
                    Python::attach(|py| {
                        // Signal handlers run on the main thread only; elsewhere this returns Ok.
                        if !interrupted && py.check_signals().is_err() {
                            interrupted = true;
                            cancel.store(true, Ordering::SeqCst);
                        }
                        let n = done.load(Ordering::Relaxed);
                        if let (Some(callback), true, None) = (&progress, n != shown, &failure) {
                            shown = n;
                            if let Err(e) = callback.call1(py, (n,)) {
                                // Ctrl-C while the bar moved is Ctrl-C: the rows done are kept.
                                if e.is_instance_of::<PyKeyboardInterrupt>(py) {
                                    interrupted = true;
                                } else {
                                    failure = Some(e);
                                }
                                cancel.store(true, Ordering::SeqCst);
                            }
                        }
                    });
                }
                worker.join().unwrap_or_else(|_| Err(Error::Other("internal error: the campaign panicked".into())))
            })
        });
        if let Some(e) = failure {
            return Err(e);
        }
        Ok((rows.map_err(value_error)?, interrupted))
    }

    /// The statistics of the events run (`outcomes`: (plan index, results) as [`Campaign::run`]
    /// gives them, in any order): the `--json` document (as JSON text), the summary the CLI prints
    /// (each cell's, then the operability table over a grid) and the operability table.
    fn summarise(&self, py: Python<'_>, outcomes: Vec<(usize, Option<Results>)>) -> PyResult<(String, String, String)> {
        let (per_cell, damages, failed) = self.per_cell(outcomes)?;
        py.detach(|| -> beam_impact::Result<(String, String, String)> {
            let options = &self.inner.options;
            let summaries = self.inner.summaries(&per_cell);
            let cells = self.inner.table_cells(&summaries);
            let mut document = campaign::summary_document(&self.inner, &summaries, &cells, options);
            let fatigue = if self.inner.fatigue() {
                Some(self.inner.fatigue_of(&damages, &failed, self.occurrence.as_ref())?)
            } else {
                None
            };
            if let Some(f) = &fatigue {
                document["fatigue"] = serde_json::to_value(f).map_err(|e| Error::Other(format!("JSON: {e}")))?;
            }
            let json = serde_json::to_string(&document).map_err(|e| Error::Other(format!("JSON: {e}")))?;
            let mut text = String::new();
            for (c, s) in summaries.iter().enumerate() {
                if let Some(s) = s {
                    text += &summary::text(&self.inner.cell_name(c), s, options);
                }
            }
            let table = operability::table(&cells, options);
            if self.inner.cells.len() > 1 {
                text += &table;
            }
            if let Some(f) = &fatigue {
                text += &f.text(&(0..self.inner.cells.len()).map(|c| self.inner.cell_name(c)).collect::<Vec<_>>());
            }
            Ok((json, text, table))
        })
        .map_err(value_error)
    }

    /// Writes the operability figures of the events run (`outcomes` as [`Campaign::summarise`]
    /// takes them) into `folder` (created if missing) as the CLI's `--figures` does, with `note`
    /// under their titles; returns the files written.
    fn figures(
        &self,
        py: Python<'_>,
        outcomes: Vec<(usize, Option<Results>)>,
        folder: PathBuf,
        note: &str,
    ) -> PyResult<Vec<String>> {
        crate::refuse_nul("the figures' folder", &folder)?;
        let (per_cell, _, _) = self.per_cell(outcomes)?;
        py.detach(|| {
            let options = &self.inner.options;
            let summaries = self.inner.summaries(&per_cell);
            let cells = self.inner.table_cells(&summaries);
            let figures = beam_impact::replay::operability_figure::operability_figures(&cells, options, note);
            beam_impact::replay::operability_figure::write_operability_figures(&figures, &folder)
        })
        .map(|paths| paths.iter().map(|p| p.display().to_string()).collect())
        .map_err(value_error)
    }
}

impl Campaign {
    /// The row of plan index `index` as Python takes it (see [`EventOut`]).
    fn event_out(&self, index: usize, row: &EventRow) -> EventOut {
        let event = &self.inner.events[row.event];
        let mut head: Vec<serde_json::Value> =
            row.row.values[..self.inner.cell_axes.len()].iter().map(|v| (*v).into()).collect();
        head.extend([row.event.into(), event.seed.into(), event.instant.into()]);
        match &row.motion {
            Some(m) => head.extend(m.iter().map(|v| serde_json::Value::from(*v))),
            None => head.extend(std::iter::repeat_n(serde_json::Value::Null, 9)),
        }
        let head = serde_json::Value::Array(head).to_string();
        let results = Row { values: Vec::new(), ..row.row.clone() };
        let outcome =
            row.row.outcome.as_ref().ok().map(EventResults::from).map(|r| {
                (r.peaks.to_vec(), r.utilisation.to_vec(), r.design_pass, r.trusted, campaign::event_damage(row))
            });
        (index, head, sweep::json_object_with(&[], &results, self.inner.fatigue()), outcome)
    }

    /// The outcomes by cell, in the plan's order, as the statistics take them; each cell's events'
    /// fatigue damages and the number of its events without one.
    #[allow(clippy::type_complexity)]
    fn per_cell(
        &self,
        mut outcomes: Vec<(usize, Option<Results>)>,
    ) -> PyResult<(Vec<Vec<EventOutcome>>, Vec<Vec<f64>>, Vec<usize>)> {
        outcomes.sort_by_key(|(index, _)| *index);
        let runs = self.inner.runs();
        let mut per_cell = vec![Vec::new(); self.inner.cells.len()];
        let mut damages = vec![Vec::new(); self.inner.cells.len()];
        let mut failed = vec![0; self.inner.cells.len()];
        for (index, results) in outcomes {
            let &(cell, event) = runs
                .get(index)
                .ok_or_else(|| value_error(format!("event {index} of a campaign of {} runs", runs.len())))?;
            match results.as_ref().and_then(|r| r.4) {
                Some(d) => damages[cell].push(d),
                None => failed[cell] += 1,
            }
            let results = match results {
                None => None,
                Some((peaks, utilisation, design_pass, trusted, _)) => {
                    let nine = |v: Vec<Option<f64>>, what: &str| -> PyResult<[Option<f64>; 9]> {
                        v.try_into().map_err(|v: Vec<_>| value_error(format!("{what}: 9 values, got {}", v.len())))
                    };
                    Some(EventResults {
                        peaks: nine(peaks, "peaks")?,
                        utilisation: nine(utilisation, "utilisations")?,
                        design_pass,
                        trusted,
                    })
                }
            };
            per_cell[cell].push(EventOutcome { seed: self.inner.events[event].seed, results });
        }
        Ok((per_cell, damages, failed))
    }
}

/// The text of an occurrence table file (`beam_impact.campaign(occurrence=PATH)`), read through
/// the CLI's bounded reader (a regular file of at most
/// [`beam_impact::studies::campaign::fatigue::MAX_TABLE_BYTES`]).
#[pyfunction]
pub fn occurrence_text(py: Python<'_>, path: PathBuf) -> PyResult<String> {
    use beam_impact::studies::campaign::fatigue::MAX_TABLE_BYTES;
    crate::refuse_nul("the occurrence table", &path)?;
    py.detach(|| -> beam_impact::Result<String> {
        let file = open_regular_input(&path, "cannot read the occurrence table")?;
        check_size(&file, MAX_TABLE_BYTES, "the occurrence table")
            .and_then(|()| read_bounded(file, MAX_TABLE_BYTES, "the occurrence table"))
            .map_err(|source| Error::Io { action: "cannot read the occurrence table", path: shown(&path), source })
    })
    .map_err(value_error)
}
