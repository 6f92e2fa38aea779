//! `beam-impact campaign`: a campaign of impacts in a sea state (issue 43), rows to CSV, the
//! statistics and operability table printed (and to JSON), the operability figures.

use std::io::Write;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

use beam_impact::record::output::{check_distinct, shown, OutputFile};
use beam_impact::studies::campaign::operability;
use beam_impact::studies::campaign::summary::{EventOutcome, EventResults};
use beam_impact::studies::campaign::{Campaign, Options};
use beam_impact::studies::sweep::{apply_settings, default_jobs, parse_axes, parse_settings};
use beam_impact::vocabulary::sweep_former_names;
use beam_impact::{Error, Result};

use super::args::CampaignArgs;
use super::common::{emit, io, read_scenario, units_sidecars, warn, write_units_sidecars};
use super::Outcome;

pub fn campaign(args: &CampaignArgs) -> Result<Outcome> {
    // Standard output carries the statistics and the table: the files need names of their own.
    for (flag, path) in [("--out", Some(args.out.as_path())), ("--json", args.json.as_deref())] {
        if path.is_some_and(|p| p.as_os_str() == "-") {
            return Err(Error::Other(format!(
                "campaign {flag} -: standard output carries the campaign's statistics and table; give a file name"
            )));
        }
    }
    let mut base = read_scenario(&args.file)?;
    apply_settings(&mut base, &parse_settings(&args.set)?)?;
    let options = Options {
        events: args.events,
        seeds: args.seeds.unwrap_or_else(|| beam_impact::studies::campaign::default_seeds(args.events)),
        record_length: args.record_length,
        target: args.target,
        confidence: args.confidence,
        exposure: args.exposure,
        on_upper_bound: !args.on_estimate,
    };
    let mut campaign =
        Campaign::new(base.clone(), parse_axes(&args.vary)?, options.clone(), args.max_events, args.max_steps)?;
    campaign.set_fatigue(args.fatigue);
    if args.fatigue {
        // A bad curve or factor is refused before any event runs.
        let mut errors = beam_impact::model::fatigue_fields::of(&base).validation_errors();
        if !errors.is_empty() {
            return Err(if errors.len() == 1 { errors.remove(0) } else { Error::Invalid(errors) });
        }
    }
    // The occurrence table is read and matched to the grid before any event runs.
    let occurrence = args.occurrence.as_deref().map(read_occurrence).transpose()?;
    if let Some(table) = &occurrence {
        let varies_heading = campaign.cell_axes.iter().any(|a| a.field.name == "sea.heading");
        table.weights(&campaign.sea_states(), varies_heading).map_err(|e| {
            Error::Other(format!("{}: {e}", shown(args.occurrence.as_deref().unwrap_or(Path::new("--occurrence")))))
        })?;
    }
    let jobs = args.jobs.map_or_else(default_jobs, |j| usize::try_from(j).unwrap_or(usize::MAX));
    let mut files: Vec<(&str, &Path)> = vec![("the scenario file", args.file.as_path())];
    if let Some(sea) = &base.sea {
        files.push(("the RAO file", Path::new(&sea.raos)));
    }
    files.extend(args.occurrence.as_deref().map(|o| ("--occurrence", o)));
    files.push(("--out", &args.out));
    files.extend(args.json.as_deref().map(|j| ("--json", j)));
    let sidecars = units_sidecars(&[args.out.as_path()]);
    files.extend(sidecars.iter().map(|(path, _)| ("the units sidecar", path.as_path())));
    check_distinct(&files)?;
    let mut csv = std::io::BufWriter::new(OutputFile::create(&args.out, true, "cannot create")?);
    let mut json = args.json.as_deref().map(|p| OutputFile::create(p, true, "cannot create")).transpose()?;
    csv.write_all(campaign.csv_header().as_bytes()).map_err(|e| io("cannot write", &args.out, e))?;

    for note in &campaign.notes {
        warn(note);
    }
    // Ctrl-C, and the SIGTERM or SIGHUP of a scheduler or a closed session: no new event starts;
    // the rows done are written and kept.
    let interrupted = Arc::new(AtomicBool::new(false));
    {
        let flag = Arc::clone(&interrupted);
        // A second handler cannot be set in one process (tests call this once); without one,
        // Ctrl-C ends the process as before.
        let _ = ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst));
    }
    for (c, cell) in campaign.cells.iter().enumerate() {
        if let Some(why) = &cell.refused {
            warn(&format!("{}: refused, its events not run: {why}", campaign.cell_name(c)));
        }
    }
    let bar = super::common::progress_bar(campaign.len(), "events");
    let started = Instant::now();
    let mut outcomes: Vec<Vec<EventOutcome>> = vec![Vec::new(); campaign.cells.len()];
    let mut damages: Vec<Vec<f64>> = vec![Vec::new(); campaign.cells.len()];
    let mut failed: Vec<usize> = vec![0; campaign.cells.len()];
    let tally = campaign.run(jobs, &interrupted, &mut |n| bar.set_position(n as u64), &mut |row| {
        let event = campaign.events[row.event];
        let results = row.row.outcome.as_ref().ok().map(EventResults::from);
        outcomes[row.cell].push(EventOutcome { seed: event.seed, results });
        match beam_impact::studies::campaign::event_damage(row) {
            Some(d) => damages[row.cell].push(d),
            None => failed[row.cell] += 1,
        }
        csv.write_all(campaign.csv_line(row).as_bytes()).map_err(|e| io("cannot write", &args.out, e))
    })?;
    bar.finish_and_clear();
    let wall = started.elapsed().as_secs_f64();
    let stopped = interrupted.load(Ordering::SeqCst) && tally.scenarios < campaign.len();
    let csv = csv.into_inner().map_err(|e| io("cannot write", &args.out, e.into_error()))?;
    csv.commit()?;
    let mut units = campaign.column_units();
    units.dedup_by(|a, b| a.0 == b.0);
    let sidecars = write_units_sidecars(&sidecars, &units, &sweep_former_names())?;

    let summaries = campaign.summaries(&outcomes);
    let table_cells = campaign.table_cells(&summaries);

    let mut text = String::new();
    for (c, summary) in summaries.iter().enumerate() {
        if let Some(s) = summary {
            text += &beam_impact::studies::campaign::summary::text(&campaign.cell_name(c), s, &options);
        }
    }
    if campaign.cells.len() > 1 {
        text += &operability::table(&table_cells, &options);
    }
    let fatigue = if args.fatigue {
        let f = campaign.fatigue_of(&damages, &failed, occurrence.as_ref())?;
        let names: Vec<String> = (0..campaign.cells.len()).map(|c| campaign.cell_name(c)).collect();
        text += &f.text(&names);
        Some(f)
    } else {
        None
    };
    if let (Some(file), Some(path)) = (json.as_mut(), args.json.as_deref()) {
        let mut document =
            beam_impact::studies::campaign::summary_document(&campaign, &summaries, &table_cells, &options);
        if let Some(f) = &fatigue {
            document["fatigue"] = serde_json::to_value(f).map_err(|e| Error::Other(format!("JSON: {e}")))?;
        }
        let body = serde_json::to_string_pretty(&document).map_err(|e| Error::Other(format!("JSON: {e}")))? + "\n";
        file.write_all(body.as_bytes()).map_err(|e| io("cannot write", path, e))?;
    }
    if let (Some(file), Some(path)) = (json, args.json.as_deref()) {
        let _ = path;
        file.commit()?;
    }
    let mut written = Vec::new();
    if let Some(dir) = &args.figures {
        let planned =
            format!("{} events per cell over {} records of {} s", options.events, options.seeds, options.record_length);
        let note = if stopped {
            format!(
                "interrupted: {} of {} events run ({planned}); {}",
                tally.scenarios,
                campaign.len(),
                shown(&args.file)
            )
        } else {
            format!("{planned}; {}", shown(&args.file))
        };
        let figures = beam_impact::replay::operability_figure::operability_figures(&table_cells, &options, &note);
        written = beam_impact::replay::operability_figure::write_operability_figures(&figures, dir)?;
    }
    let threads = jobs.min(tally.scenarios.max(1));
    text += &format!(
        "campaign: {} events on {threads} threads in {wall:.2} s ({:.1} ms of a thread each): {} ran, {} failed, {} not \
         trusted\nrows written to {}",
        tally.scenarios,
        wall * 1e3 * threads as f64 / tally.scenarios.max(1) as f64,
        tally.scenarios - tally.failed,
        tally.failed,
        tally.untrusted,
        shown(&args.out)
    );
    if let Some(path) = &args.json {
        text += &format!(", statistics to {}", shown(path));
    }
    for path in &sidecars {
        text += &format!(", units in {}", shown(path));
    }
    if !written.is_empty() {
        text += &format!("\nfigures: {}", written.iter().map(|p| shown(p)).collect::<Vec<_>>().join(", "));
    }
    emit(&(text + "\n"))?;
    if stopped {
        warn(&format!(
            "interrupted: {} of {} events run and written to {} (the statistics above are of them)",
            tally.scenarios,
            campaign.len(),
            shown(&args.out)
        ));
        return Ok(Outcome::Interrupted);
    }
    Ok(Outcome::Done)
}

/// Reads `--occurrence FILE.csv` (a regular file of at most
/// [`beam_impact::studies::campaign::fatigue::MAX_TABLE_BYTES`]), parsed and checked.
fn read_occurrence(path: &Path) -> Result<beam_impact::studies::campaign::fatigue::Occurrence> {
    use beam_impact::record::output::{check_size, open_regular_input, read_bounded};
    use beam_impact::studies::campaign::fatigue::{Occurrence, MAX_TABLE_BYTES};
    let file = open_regular_input(path, "cannot read the occurrence table")?;
    let text = check_size(&file, MAX_TABLE_BYTES, "the occurrence table")
        .and_then(|()| read_bounded(file, MAX_TABLE_BYTES, "the occurrence table"))
        .map_err(|source| io("cannot read the occurrence table", path, source))?;
    Occurrence::parse(&text).map_err(|e| Error::Other(format!("{}: {e}", shown(path))))
}
