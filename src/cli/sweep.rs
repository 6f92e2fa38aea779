//! `beam-impact sweep`: a design grid run in parallel, rows to CSV (and JSON).

use std::io::Write;
use std::path::Path;
use std::time::Instant;

use beam_impact::record::output::{check_distinct, shown, OutputFile};
use beam_impact::{Result, Scenario};

use super::args::SweepArgs;
use beam_impact::vocabulary::sweep_former_names;

use super::common::{emit, io, read_scenario, units_sidecars, write_units_sidecars};

pub fn sweep(args: &SweepArgs) -> Result<()> {
    use beam_impact::studies::sweep::{
        apply_settings, column_units_with, default_jobs, parse_axes, parse_settings, Sweep, SweepWriteError,
    };
    let mut base = match &args.file {
        Some(path) => read_scenario(path)?,
        None => Scenario::default(),
    };
    if let Some(motion) = &args.motion {
        super::common::load_motion(&mut base, motion)?;
    }
    apply_settings(&mut base, &parse_settings(&args.set)?)?;
    let mut sweep = Sweep::new(base, parse_axes(&args.vary)?, args.max_steps)?;
    sweep.fatigue = args.fatigue;
    let column_units = |axes: &[beam_impact::studies::sweep::Axis]| column_units_with(axes, args.fatigue);
    let mut summary = beam_impact::studies::sweep_governing::SweepSummary::new(&sweep.base);
    let jobs = args.jobs.map_or_else(default_jobs, |j| usize::try_from(j).unwrap_or(usize::MAX));
    let mut files: Vec<(&str, &Path)> = args.file.as_deref().map(|f| ("the scenario file", f)).into_iter().collect();
    if !sweep.base.motion.file.is_empty() {
        files.push(("the motion file", Path::new(&sweep.base.motion.file)));
    }
    if let Some(sea) = &sweep.base.sea {
        files.push(("the RAO file", Path::new(&sea.raos)));
    }
    files.push(("--out", &args.out));
    files.extend(args.json.as_deref().map(|j| ("--json", j)));
    files.extend(args.html.as_deref().map(|h| ("--html", h)));
    let data: Vec<&Path> = std::iter::once(args.out.as_path()).chain(args.json.as_deref()).collect();
    let sidecars = units_sidecars(&data);
    files.extend(sidecars.iter().map(|(path, _)| ("the units sidecar", path.as_path())));
    check_distinct(&files)?;
    let create = |path: &Path| OutputFile::create(path, true, "cannot create").map(std::io::BufWriter::new);
    let mut csv = create(&args.out)?;
    let mut json = args.json.as_deref().map(create).transpose()?;
    let html = args.html.as_deref().map(|h| OutputFile::create(h, true, "cannot create HTML report")).transpose()?;
    // With --html the JSON rows are kept too (beside the --json file, if any): the page is made of them.
    let mut rows = Tee { file: json.as_mut().map(|j| j as &mut dyn Write), kept: html.as_ref().map(|_| Vec::new()) };
    let keep = rows.file.is_some() || rows.kept.is_some();
    let bar = super::common::progress_bar(sweep.len(), "scenarios");
    let started = Instant::now();
    let tally = sweep
        .write_observed(
            jobs,
            &mut csv,
            keep.then_some(&mut rows as &mut dyn Write),
            &mut |n| bar.set_position(n as u64),
            &mut |row| summary.observe(row),
        )
        .map_err(|e| match e {
            SweepWriteError::Csv(source) => io("cannot write", &args.out, source),
            SweepWriteError::Json(source) => {
                io("cannot write", args.json.as_deref().unwrap_or(Path::new("JSON")), source)
            }
            SweepWriteError::Run(e) => e,
        })?;
    bar.finish_and_clear();
    // Complete: the rows replace the user's earlier files only now.
    let commit = |writer: std::io::BufWriter<OutputFile>, path: &Path| {
        writer.into_inner().map_err(|e| io("cannot write", path, e.into_error()))?.commit()
    };
    let kept = rows.kept.take();
    drop(rows);
    commit(csv, &args.out)?;
    if let (Some(json), Some(path)) = (json, args.json.as_deref()) {
        commit(json, path)?;
    }
    let sidecars = write_units_sidecars(&sidecars, &column_units(&sweep.axes), &sweep_former_names())?;
    let wall = started.elapsed().as_secs_f64();
    if tally.failed > 0 {
        super::common::warn(&format!(
            "{} of {} scenarios failed (their rows hold the error)",
            tally.failed, tally.scenarios
        ));
    }
    if tally.untrusted > 0 {
        super::common::warn(&format!(
            "{} of {} scenarios not trusted (column trusted)",
            tally.untrusted, tally.scenarios
        ));
    }
    let mut text = format!(
        "sweep: {} scenarios on {} threads in {wall:.2} s ({:.1} ms of a thread each): {} ran, {} failed, {} not \
         trusted\nrows written to {}",
        tally.scenarios,
        jobs.min(tally.scenarios.max(1)),
        wall * 1e3 * jobs.min(tally.scenarios.max(1)) as f64 / tally.scenarios.max(1) as f64,
        tally.scenarios - tally.failed,
        tally.failed,
        tally.untrusted,
        shown(&args.out)
    );
    if let Some(path) = &args.json {
        text += &format!(" and {}", shown(path));
    }
    for path in sidecars {
        text += &format!(", units in {}", shown(&path));
    }
    let governing = summary.text(&sweep.axes);
    if !governing.is_empty() {
        text += &format!("\n{}", governing.trim_end());
    }
    if let (Some(target), Some(path), Some(kept)) = (html, args.html.as_deref(), kept) {
        let rows: serde_json::Value = serde_json::from_slice(&kept)
            .map_err(|e| beam_impact::Error::Other(format!("the sweep's rows do not parse as JSON: {e}")))?;
        let named = column_units(&sweep.axes).len() - sweep_former_names().len();
        let page =
            beam_impact::replay::html::sweep_page::sweep_page(&beam_impact::replay::html::sweep_page::SweepPage {
                title: format!("sweep of {}", args.file.as_deref().map_or("the default scenario".into(), shown)),
                // The governing cases and the worst fatigue row, as printed (text on the page).
                source: std::iter::once(format!(
                    "{} scenarios; the rows also in {}",
                    tally.scenarios,
                    shown(&args.out)
                ))
                .chain(governing.lines().map(|l| l.trim().to_string()))
                .collect(),
                axes: sweep.axes.iter().map(|a| a.field.name.to_string()).collect(),
                columns: column_units(&sweep.axes).into_iter().take(named).collect(),
                rows: &rows,
            });
        beam_impact::replay::html::write_page(target, path, &page)?;
        text += &format!("\nHTML report written to {}", shown(path));
    }
    emit(&(text + "\n"))
}

/// The sweep's JSON rows into the --json file, if any, and kept in memory for --html, if asked.
struct Tee<'a> {
    file: Option<&'a mut dyn Write>,
    kept: Option<Vec<u8>>,
}

impl Write for Tee<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if let Some(file) = self.file.as_mut() {
            file.write_all(buf)?;
        }
        if let Some(kept) = self.kept.as_mut() {
            kept.extend_from_slice(buf);
        }
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.file.as_mut().map_or(Ok(()), |f| f.flush())
    }
}
