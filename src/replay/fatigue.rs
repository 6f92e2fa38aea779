//! A log's fatigue (`beam-impact report LOG --fatigue [--curve NAME]`, `load_log(...).fatigue`;
//! issue 44): the bending stations' stress histories from the log's `fatigue.json` (the turning
//! points of every step of the printed run, stored by `run`), or, from a log without it (an FMU's,
//! a run killed before its end, one written before issue 44), rebuilt from the `/beam/stations`
//! rows (single precision, sampled every 1 ms by default: faster cycles are missed, and the
//! result says so); then assessed on the log's scenario's `[fatigue]` curve and factors, or
//! another curve ([`crate::run_fatigue::assess`]).

use crate::error::{Error, Result};
use crate::model::fatigue_settings::FatigueSettings;
use crate::model::Scenario;
use crate::record::log_format::{FATIGUE_ATTACHMENT, SCENARIO_ATTACHMENT};
use crate::replay::report::LogData;
use crate::run_fatigue::{assess, RunFatigue, StationHistories, StationHistory, FORMAT, LOG_ROWS};

/// The log's station histories: its `fatigue.json`, else rebuilt from its `/beam/stations` rows.
pub fn histories_of_log(data: &LogData) -> Result<StationHistories> {
    if let Some(text) = &data.fatigue_json {
        return StationHistories::from_json(text);
    }
    let record = &data.stations;
    let Some(layout) = &record.layout else {
        return Err(Error::Other(format!(
            "the log holds neither {FATIGUE_ATTACHMENT} nor stress stations (/beam/stations): no stress history to \
             count"
        )));
    };
    let width = record.width();
    if record.rows() == 0 || width == 0 {
        return Err(Error::Other(format!(
            "the log holds neither {FATIGUE_ATTACHMENT} nor stresses at its stations (/beam/stations rows): no \
             stress history to count"
        )));
    }
    let lower = layout.lower_bending.positions.len();
    let upper_start = lower + layout.lower_shear.positions.len();
    let columns = (0..lower)
        .map(|k| ("lower", layout.lower_bending.positions[k], k))
        .chain(layout.upper_bending.positions.iter().enumerate().map(|(k, &x)| ("upper", x, upper_start + k)));
    let rows = record.rows().min(record.values.len() / width);
    let mut stations = Vec::new();
    for (beam, position, column) in columns {
        let history: Vec<f64> = (0..rows).map(|r| f64::from(record.values[r * width + column])).collect();
        let reversals = crate::fatigue::reversals(&history)
            .map_err(|e| Error::Other(format!("the log's /beam/stations rows, {beam} station at {position} m: {e}")))?;
        stations.push(StationHistory { beam: beam.into(), position, reversals });
    }
    Ok(StationHistories {
        format: FORMAT,
        source: LOG_ROWS.into(),
        sampled_every: layout.sampled_every,
        contact_position: scenario_of(data).map_or(f64::NAN, |s| s.contact_position),
        stations,
    })
}

/// The log's stored scenario, if it parses.
fn scenario_of(data: &LogData) -> Option<Scenario> {
    data.scenario_toml.as_deref().and_then(|t| Scenario::from_toml(t, SCENARIO_ATTACHMENT).ok())
}

/// The log's fatigue on its scenario's `[fatigue]` settings (the defaults without them), the
/// curve `curve` instead of the scenario's when given.
pub fn fatigue_of_log(data: &LogData, curve: Option<&str>) -> Result<RunFatigue> {
    let histories = histories_of_log(data)?;
    let mut settings = scenario_of(data).and_then(|s| s.fatigue).unwrap_or_default();
    if let Some(name) = curve {
        settings = FatigueSettings { curve: name.to_string(), ..settings };
    }
    assess(&histories, &settings)
}

/// `report --fatigue`'s text: the curve and factors, where the histories come from, each hot
/// spot and each beam's worst station, and the life.
pub fn fatigue_text(f: &RunFatigue) -> String {
    let beam = |b: &str| if b == "upper" { "bridge" } else { "arrestor" };
    let mut text = format!(
        "fatigue: S-N curve {}, SCF {}, thickness {}, DFF {}; histories from {} (every {} step{})\n",
        f.curve,
        f.scf,
        f.thickness.map_or_else(|| "none (no correction)".to_string(), |t| format!("{t} m")),
        f.design_fatigue_factor,
        f.source,
        f.sampled_every,
        if f.sampled_every == 1 { "" } else { "s" }
    );
    if let Some(note) = &f.note {
        text += &format!("note: {note}\n");
    }
    text += &format!(
        "{:<10} {:<16} {:>9} {:>12} {:>10} {:>17}\n",
        "beam", "hot spot", "at [m]", "damage", "cycles", "largest range [MPa]"
    );
    let worst = [&f.worst.lower, &f.worst.upper].into_iter().flatten();
    for h in f.hot_spots.iter().chain(worst) {
        text += &format!(
            "{:<10} {:<16} {:>9.3} {:>12.4e} {:>10} {:>17.2}\n",
            beam(&h.beam),
            h.name,
            h.position,
            h.damage,
            h.cycles,
            h.largest_range * 1e-6
        );
    }
    text += &format!("{}\n", f.lines()[1]);
    text
}
