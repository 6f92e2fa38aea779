//! `beam-impact fatigue HISTORY.csv --curve NAME`: the fatigue of a stress history a user brings
//! (issue 44): the file read bounded, each stress column's rainflow cycles and damage from the
//! library (`beam_impact::fatigue`), a table on standard output and `--json` through the output
//! guard.

use std::io::Write;
use std::path::Path;

use beam_impact::fatigue::history::{StressHistory, MAX_HISTORY_BYTES};
use beam_impact::fatigue::summary::HistoryFatigue;
use beam_impact::fatigue::{SnCurve, SnOptions};
use beam_impact::record::output::{check_distinct, check_size, open_regular_input, read_bounded, shown, OutputFile};
use beam_impact::{Error, Result};

use super::args::FatigueArgs;
use super::common::{emit, io};

/// Most cycles printed per column (all of them are in `--json`).
const MAX_PRINTED_CYCLES: usize = 40;

pub fn fatigue(args: &FatigueArgs) -> Result<()> {
    let curve = SnCurve::by_name(&args.curve).map_err(|e| Error::Other(format!("--curve: {e}")))?;
    let options = SnOptions { scf: args.scf, thickness_m: args.thickness, design_fatigue_factor: args.dff };
    options.validate()?;
    let path = args.history.as_path();
    let mut files: Vec<(&str, &Path)> = vec![("the stress history", path)];
    files.extend(args.json.as_deref().map(|j| ("--json", j)));
    check_distinct(&files)?;
    let file = open_regular_input(path, "cannot read stress history")?;
    let text = check_size(&file, MAX_HISTORY_BYTES, "the stress history")
        .and_then(|()| read_bounded(file, MAX_HISTORY_BYTES, "the stress history"))
        .map_err(|source| io("cannot read stress history", path, source))?;
    let history =
        StressHistory::parse(&text).map_err(|e| Error::Other(format!("stress history {}: {e}", shown(path))))?;
    drop(text);
    let doc = HistoryFatigue::new(&history, &curve, &options);
    let mut out = format!(
        "stress history {}: {} rows, time {} to {} s, {} stress column(s)\n",
        shown(path),
        history.rows,
        history.time_span.0,
        history.time_span.1,
        history.names.len()
    );
    out += &doc.table(MAX_PRINTED_CYCLES);
    if let Some(json_path) = args.json.as_deref() {
        let json = serde_json::to_string_pretty(&doc).map_err(|e| Error::Other(format!("JSON: {e}")))?;
        if json_path.as_os_str() == "-" {
            return emit(&format!("{json}\n"));
        }
        let mut file = OutputFile::create(json_path, true, "cannot create JSON")?;
        writeln!(file, "{json}").map_err(|source| io("cannot write JSON", json_path, source))?;
        file.commit()?;
        out += &format!("\ncycles and damage written to {}\n", shown(json_path));
    }
    emit(&out)
}
