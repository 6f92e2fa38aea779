//! The report that opens in a browser (issue 44 item 4): one self-contained HTML file of a run
//! ([`page`]: `report LOG --html`, `run --html`) or of a sweep ([`sweep_page`]: `sweep --html`),
//! its figures inline SVG ([`charts`]), any block of the run's JSON as tables ([`tables`]), every
//! text through one escape function ([`escape`]). The page makes no request of any kind: no CDN,
//! no font, no image URL; its Content-Security-Policy forbids them (docs/html-report.md).

pub mod charts;
pub mod escape;
pub mod page;
pub mod sweep_page;
pub mod tables;

use std::path::Path;

use serde_json::Value;

use crate::error::{Error, Result};
use crate::model::Scenario;
use crate::record::output::shown;
use crate::replay::report::{read_log, replay_envelope, summary_from_log, LogData};
use crate::results::Summary;
use crate::simulation::Simulation;

/// The run's document rebuilt from a log, with the keys of `run --json`: the scenario, the summary
/// from the steps (with the stored answer's converged peaks and quality), the merged contact
/// windows, and every block of the log's `answer.json` (quality, design, discretisation, and the
/// blocks added later: load cases, DAF, fatigue) at the top, as `run --json` has them.
pub fn log_document(data: &LogData, scenario: &Scenario, summary: &Summary) -> Value {
    let mut summary_json = serde_json::to_value(summary).unwrap_or(Value::Null);
    let answer = data.answer_json.as_deref().and_then(|t| serde_json::from_str::<Value>(t).ok());
    let mut doc = serde_json::json!({
        "scenario": scenario,
        "impact": summary.impact,
        "merged_contact_windows": crate::compare::merged_windows(&summary.contact_windows, crate::results::BOUNCE_GAP),
    });
    if let Some(Value::Object(answer)) = answer {
        for key in ["converged_peaks", "converged_first_contact_peaks", "quality"] {
            if let Some(v) = answer.get(key) {
                summary_json[key] = v.clone();
            }
        }
        for (key, v) in answer {
            if key != "converged_peaks" && key != "converged_first_contact_peaks" {
                doc[key] = v;
            }
        }
    }
    doc["summary"] = summary_json;
    crate::vocabulary::add_quantity_names(&mut doc);
    doc
}

/// The page of the log at `mcap`: its summary rebuilt (the scenario stored in it validated first,
/// as `report` does), its document ([`log_document`]), its steps.
pub fn log_page(mcap: &Path) -> Result<String> {
    let data = read_log(mcap)?;
    let err = |e: String| Error::Other(format!("{}: {e}", shown(mcap)));
    if data.scenario_toml.is_none() {
        return Err(err("the log holds no scenario".into()));
    }
    let refused = |e: Error| err(format!("the scenario stored in the log is refused: {e}"));
    let scenario = data.scenario().map_err(refused)?;
    scenario.validate().map_err(refused)?;
    let simulation = Simulation::new(&scenario).map_err(refused)?;
    let summary = summary_from_log(&data, &simulation).map_err(|e| err(e.to_string()))?;
    let (_, source) = replay_envelope(&data, &summary.peaks, &summary.peak_times, scenario.contact_position);
    let doc = log_document(&data, &scenario, &summary);
    let status = if data.complete && data.stopped_early.is_none() {
        "complete (finished file, every chunk CRC checked)".to_string()
    } else {
        format!(
            "{}: {}; the {} step messages before it",
            if data.complete {
                "STOPPED EARLY"
            } else if data.damaged {
                "DAMAGED"
            } else {
                "CUT SHORT"
            },
            data.stopped_early.as_deref().or(data.problem.as_deref()).unwrap_or("unknown"),
            data.steps.len()
        )
    };
    let mut source_lines = vec![
        format!("MCAP log {} ({} bytes)", shown(mcap), data.file_size),
        format!("status: {status}"),
        crate::replay::report::stored_verdict(data.answer_json.as_deref()),
        "the peaks, windows and histories from the log's steps; the checks and the design as the run stored them (answer.json)"
            .to_string(),
    ];
    source_lines.extend(data.notes());
    Ok(page::run_page(&page::RunPage {
        title: format!("report of {}", shown(mcap)),
        source: source_lines,
        doc: &doc,
        scenario: &scenario,
        summary: &summary,
        steps: &data.steps,
        envelope_source: source.describe(),
        comparison: crate::compare::comparison_for(&summary, &scenario),
    }))
}

/// The page of a run just made: its document `doc` (`run --json`'s), its `summary`, the scenario
/// as given (`scenario`), and the steps read back from its log at `mcap`.
pub fn run_page(scenario: &Scenario, summary: &Summary, doc: &Value, title: &str, mcap: &Path) -> Result<String> {
    let data = read_log(mcap)?;
    let mut source = vec![format!(
        "the run's log {} read back for the time histories ({} step messages)",
        shown(mcap),
        data.steps.len()
    )];
    if let Some(reason) = &data.stopped_early {
        source.push(format!("the log stopped early: {reason}; the histories cover the steps before it"));
    }
    Ok(page::run_page(&page::RunPage {
        title: title.to_string(),
        source,
        doc,
        scenario,
        summary,
        steps: &data.steps,
        envelope_source: "of the run (the same as its log's envelope.json)".into(),
        comparison: crate::compare::comparison_for(summary, scenario),
    }))
}

/// Writes `html` into `target` (an output opened through [`crate::record::output`]), then commits it.
pub fn write_page(mut target: crate::record::output::OutputFile, path: &Path, html: &str) -> Result<()> {
    use std::io::Write;
    target.write_all(html.as_bytes()).map_err(|source| Error::Io {
        action: "cannot write HTML report",
        path: path.display().to_string(),
        source,
    })?;
    target.commit()
}
