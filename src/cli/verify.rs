//! `beam-impact verify`: the convergence study of the Table 1 peaks and F_c, with a bar per run.

use std::io::Write;
use std::path::Path;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};

use beam_impact::record::output::{check_distinct, shown, OutputFile};
use beam_impact::{Error, Result};

use super::common::{emit, io, scenario_with_settings};

pub fn verify(file: Option<&Path>, set: &[String], json: Option<&Path>, tolerance: f64) -> Result<()> {
    use beam_impact::studies::verify::{default_threads, table, Plan, RUN_LABELS};
    // The wall time covers the whole study: the plan builds each run's model and modes.
    let started = Instant::now();
    let scenario = scenario_with_settings(file, set)?;
    let plan = Plan::new(&scenario, tolerance)?;
    let mut files: Vec<(&str, &Path)> = file.map(|f| ("the scenario file", f)).into_iter().collect();
    if !scenario.motion.file.is_empty() {
        files.push(("the motion file", Path::new(&scenario.motion.file)));
    }
    if let Some(sea) = &scenario.sea {
        files.push(("the RAO file", Path::new(&sea.raos)));
    }
    files.extend(json.map(|j| ("--json", j)));
    check_distinct(&files)?;
    let json_file = match json {
        Some(path) => Some((path, OutputFile::create(path, true, "cannot create JSON")?)),
        None => None,
    };
    let multi = indicatif::MultiProgress::new();
    let style = ProgressStyle::with_template("{prefix:>12} {bar:40} {pos}/{len} ms simulated, {elapsed}")
        .unwrap_or_else(|_| ProgressStyle::default_bar());
    let bars: Vec<ProgressBar> = RUN_LABELS
        .iter()
        .map(|label| {
            let bar = multi.add(ProgressBar::new(plan.duration_ns() / 1_000_000).with_style(style.clone()));
            bar.set_prefix(*label);
            bar
        })
        .collect();
    let verification = plan.run(default_threads(), &|run, ns| bars[run].set_position(ns / 1_000_000));
    bars.iter().for_each(ProgressBar::finish_and_clear);
    let verification = verification?;
    let mut text = table(&verification);
    text += &format!("wall time: {:.2} s ({} threads)\n", started.elapsed().as_secs_f64(), default_threads());
    if let Some((path, mut file)) = json_file {
        let json = serde_json::to_string_pretty(&verification).map_err(|e| Error::Other(format!("JSON: {e}")))?;
        writeln!(file, "{json}").map_err(|source| io("cannot write JSON", path, source))?;
        file.commit()?;
        text += &format!("verdicts written to {}\n", shown(path));
    }
    emit(&text)
}
