//! `beam-impact report`: a log's summary and figures, and its steps as CSV.

use std::io::Write;
use std::path::{Path, PathBuf};

use beam_impact::record::output::{check_distinct, shown, OutputFile};
use beam_impact::{Error, Result};

use super::common::{io, units_sidecars, write_units_sidecars};

pub fn report(file: &Path, out: Option<PathBuf>, csv: Option<&Path>, html: Option<&Path>) -> Result<()> {
    let out = out.unwrap_or_else(|| beam_impact::replay::report::default_out_dir(file));
    // Opened before the log is read, so that a bad path fails at once.
    let html = match html {
        Some(path) => {
            check_distinct(&[("the log", file), ("--html", path)])?;
            Some((path, OutputFile::create(path, true, "cannot create HTML report")?))
        }
        None => None,
    };
    let stdout = std::io::stdout();
    let mut lock = stdout.lock();
    let csv_to_stdout = csv.is_some_and(|path| path.as_os_str() == "-");
    beam_impact::record::output::check_not_in_figure_folder("the log", file, &out)?;
    if let Some(path) = csv {
        let sidecars = units_sidecars(&[path]);
        let mut files = vec![("the log", file), ("--csv", path)];
        files.extend(sidecars.iter().map(|(p, _)| ("the units sidecar", p.as_path())));
        check_distinct(&files)?;
        if !csv_to_stdout && beam_impact::record::output::same_folder(path, &out) {
            return Err(Error::Other(format!(
                "--csv {} is inside the figure folder {}, which the figures are written to; give another folder",
                shown(path),
                shown(&out)
            )));
        }
        // Opened before the log is read, so that a bad path fails at once.
        let target = if csv_to_stdout { None } else { Some(OutputFile::create(path, true, "cannot create CSV")?) };
        let data = beam_impact::replay::report::read_log(file)?;
        if csv_to_stdout && (!data.complete || data.stopped_early.is_some()) {
            // The summary, which would say so, is not printed.
            super::common::warn(&format!(
                "{}: {}; the CSV holds the {} step messages before it",
                shown(file),
                data.problem.as_deref().or(data.stopped_early.as_deref()).unwrap_or("incomplete log"),
                data.steps.len()
            ));
        }
        let written = match target {
            Some(mut target) => {
                let mut buffered = std::io::BufWriter::new(&mut target);
                beam_impact::replay::csv::write_steps(&data.steps, &mut buffered)
                    .and_then(|()| buffered.flush())
                    .map_err(|source| io("cannot write CSV", path, source))?;
                drop(buffered);
                target.commit()
            }
            None => match beam_impact::replay::csv::write_steps(&data.steps, &mut std::io::BufWriter::new(&mut lock)) {
                // `report log.mcap --csv - | head`: the reader went away, quietly.
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => return Ok(()),
                outcome => outcome.map_err(|source| io("cannot write", Path::new("standard output"), source)),
            },
        };
        written?;
        write_units_sidecars(
            &sidecars,
            &beam_impact::replay::csv::column_units(),
            &beam_impact::replay::csv::former_names(),
        )?;
    }
    // With `--csv -` the standard output is the CSV: the summary goes nowhere, the figures are
    // still written.
    let mut sink = std::io::sink();
    let summary: &mut dyn Write = if csv_to_stdout { &mut sink } else { &mut lock };
    // A reader that went away (`report log.mcap | head`) ends the output quietly, as `run` does.
    match beam_impact::replay::report::report(file, &out, summary) {
        Err(Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::BrokenPipe => return Ok(()),
        outcome => outcome?,
    }
    if let Some((path, target)) = html {
        let page = beam_impact::replay::html::log_page(file)?;
        beam_impact::replay::html::write_page(target, path, &page)?;
        writeln!(summary, "HTML report written to {}", shown(path)).ok();
    }
    lock.flush().ok();
    Ok(())
}

/// `report LOG --fatigue [--curve NAME]`: the run's fatigue (issue 44,
/// [`beam_impact::replay::fatigue`]) to standard output.
pub fn fatigue(file: &Path, curve: Option<&str>) -> Result<()> {
    let data = beam_impact::replay::report::read_log(file)?;
    let fatigue = beam_impact::replay::fatigue::fatigue_of_log(&data, curve)?;
    super::common::emit(&beam_impact::replay::fatigue::fatigue_text(&fatigue))
}
