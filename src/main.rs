//! `beam-impact`: run the paper scenario or a user scenario, print the comparison with the
//! paper, write FMUs, replay logs, benchmark. Thin: everything happens in the library.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::{Args, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};

use beam_impact::model::TimeStep;
use beam_impact::record::mcap::{LogCompression, McapRecorder, RecorderOptions};
use beam_impact::record::output::{check_distinct, open_input, read_bounded, OutputFile, MAX_SCENARIO_BYTES};
use beam_impact::record::{NullRecorder, Recorder, RunInfo};
use beam_impact::results::{ContactEvent, StepResult};
use beam_impact::{compare, Error, Result, Scenario, Simulation};

/// Elastic impact of two beams (Catipovic, Vladimir, Reljic 2008): FEM + linear acceleration method.
#[derive(Parser)]
#[command(name = "beam-impact", version, about)]
#[command(args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// With no subcommand: `run` with these options.
    #[command(flatten)]
    run: RunArgs,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scenario (default: the paper's) and print Tables 1-3 beside the paper.
    Run(RunArgs),
    /// Print the default scenario as TOML (the paper's, with automatic energy-safe time steps),
    /// to start a scenario file from.
    Scenario,
    /// The damping study of Appendix A: peaks for damping ratios 0 to 0.04.
    Damping {
        /// Scenario file (default: the paper scenario; with --set and no file, the default
        /// scenario, as `run --set`).
        file: Option<PathBuf>,
        /// Change a scenario field, KEY=VALUE, as `run --set` (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Also write the study's figures (SVG and PNG) into DIR: per damping ratio the
        /// deflections (Figures A2-A7) and bending stresses (A8-A13), and the peaks against the
        /// damping ratio; of this FE model, not of the paper's simplified Figure A1 model.
        #[arg(long, value_name = "DIR")]
        figures: Option<PathBuf>,
    },
    /// Figures 10-12 of a scenario (default: the paper's): the first natural modes of the
    /// arrestor alone, the bridge alone and the two coupled, with their frequencies (SVG and PNG;
    /// `report` writes them too, beside Figures 6-9).
    Modes {
        /// Scenario file (default: the paper scenario).
        file: Option<PathBuf>,
        /// Change a scenario field, KEY=VALUE, as `run --set` (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Directory for the figures.
        #[arg(long, value_name = "DIR", default_value = "modes-figures")]
        out: PathBuf,
    },
    /// Write the FMI 2.0 and FMI 3.0 co-simulation FMUs. With cargo-zigbuild on PATH the library
    /// is first built for glibc 2.17 (manylinux2014) and that build is packed; without it, the
    /// host build (with a warning: it needs this machine's glibc).
    Pack {
        /// Output directory; the FMUs go to DIR/fmi2/BeamImpact.fmu and DIR/fmi3/BeamImpact.fmu.
        #[arg(long, default_value = "target/fmu")]
        out: PathBuf,
        /// The shared library to pack, as it is (default: the glibc 2.17 build, or the host build
        /// libbeam_impact.so next to this executable).
        #[arg(long)]
        library: Option<PathBuf>,
        /// Pack the host build next to this executable even when cargo-zigbuild is on PATH.
        #[arg(long)]
        no_zigbuild: bool,
    },
    /// Read an MCAP log: print its summary and write Figures 6-9 (SVG and PNG), and Figures 10-12
    /// (natural modes) of its scenario.
    Report {
        /// The log.
        file: PathBuf,
        /// Directory for the figures (default: <log stem>-figures next to the log).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Also write the step channel as CSV to this file (`-`: standard output, instead of the
        /// summary): a header row of the `beam_impact.Step` field paths (`energy.kinetic`,
        /// `peaks.contact_force`, ...), one row per step kept (after rollbacks), numbers that
        /// round-trip. SI units: time s, time_ns ns, deflections m, stresses Pa, forces N,
        /// moment N m, velocities m/s, energies J; contact true/false.
        #[arg(long, value_name = "FILE.csv")]
        csv: Option<PathBuf>,
    },
    /// Time the production stepper against the dense oracle, the per-step cost at finer
    /// meshes, and the recorded run.
    Bench {
        /// Runs per measurement (the median is reported).
        #[arg(long, default_value_t = 5)]
        runs: usize,
    },
    /// Convergence of the four Table 1 peaks: the scenario at half its steps and at 2x and 4x its
    /// elements; each peak's changes, a Richardson estimate and a verdict.
    Verify {
        /// Scenario file (default: the paper scenario; with --set and no file, the default
        /// scenario, as `run --set`).
        file: Option<PathBuf>,
        /// Change a scenario field, KEY=VALUE, as `run --set` (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Write the verdicts as JSON to this file.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Largest relative change of a converged peak, a fraction (0.01 is 1 %).
        #[arg(long, default_value_t = beam_impact::studies::verify::DEFAULT_TOLERANCE)]
        tolerance: f64,
    },
    /// A design sweep: every combination of the `--vary` values (the last varying fastest), run in
    /// parallel without logs; one CSV row per scenario (peaks, peak times, energy approach,
    /// largest energy residual, trust verdict, error).
    Sweep(SweepArgs),
}

#[derive(Args)]
struct RunArgs {
    /// Scenario file (TOML); missing fields take the paper's values. Default: the paper scenario.
    file: Option<PathBuf>,
    /// Write the summary as JSON to this file.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Record every step to this MCAP file [default: paper.mcap; with --set: <stem>-set-<hash>.mcap].
    #[arg(long, conflicts_with = "no_mcap")]
    mcap: Option<PathBuf>,
    /// Do not record.
    #[arg(long)]
    no_mcap: bool,
    /// Exit with code 3 when the run is not trusted (its energy residual is above the scenario's
    /// `energy_tolerance`).
    #[arg(long)]
    strict: bool,
    /// Stop the MCAP log at this size, bytes (the run goes on unrecorded, with a warning).
    #[arg(long, default_value_t = beam_impact::record::mcap::MAX_LOG_BYTES)]
    max_log_bytes: u64,
    /// Refuse runs that need more internal steps than this (duration over the smaller step).
    #[arg(long, default_value_t = beam_impact::model::scenario::MAX_STEPS)]
    max_steps: u64,
    /// Record every Nth internal step to the MCAP log (for long runs). Step 0, the last step,
    /// the steps on both sides of a contact change and every step where a running peak changes
    /// are recorded whatever N.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    record_every: u64,
    /// Leave the modal coordinates (topic /beam/modes) out of the MCAP log; the 3D scene is still
    /// drawn, `report` then cannot give the bridge's strain energy at the peak deflection.
    #[arg(long)]
    no_modal_coordinates: bool,
    /// Chunk compression of the MCAP log: none (the default: recording keeps pace with the
    /// solver), lz4 (~20 % smaller, about 2x the writer's work) or zstd (~35 % smaller, slower).
    #[arg(long, value_name = "none|lz4|zstd", default_value = "none")]
    log_compression: LogCompression,
    /// Change a scenario field, KEY=VALUE with the dotted names of `beam-impact scenario`
    /// (repeatable): `--set upper.mass=14000 --set step_free=auto --set stress_recovery=left`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
}

#[derive(Args)]
struct SweepArgs {
    /// Scenario file (TOML) the grid starts from. Default: the default scenario (`beam-impact scenario`: method converged, automatic mesh and steps), as `run --set`.
    file: Option<PathBuf>,
    /// A varied field, KEY=SPEC with SPEC `start:stop:count` (inclusive, linear) or a comma list
    /// (repeatable; the first is the outermost loop): `--vary drop_height=0.1:2:100`.
    #[arg(long, value_name = "KEY=SPEC")]
    vary: Vec<String>,
    /// Change a field of every scenario, KEY=VALUE (repeatable), as `run --set`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// The rows, one per scenario in grid order, as CSV.
    #[arg(long, value_name = "FILE.csv")]
    out: PathBuf,
    /// Also write the rows as a JSON array of objects.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Scenarios run at once [default: every core].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    jobs: Option<u64>,
    /// Refuse runs that need more internal steps than this (a row with the error).
    #[arg(long, default_value_t = beam_impact::model::scenario::MAX_STEPS)]
    max_steps: u64,
}

/// Exit code of a run that completed but whose numbers are not trusted (with `--strict`).
const UNTRUSTED: u8 = 3;

fn main() -> ExitCode {
    std::panic::set_hook(Box::new(|info| {
        eprintln!("beam-impact: internal error: {info}");
    }));
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // Help and version print as clap prints them; a usage error is one bounded line like
        // every other error (it echoed a 120 KB argument three times over seven lines).
        Err(e) if !e.use_stderr() => e.exit(),
        Err(e) => {
            let text = e.to_string();
            eprintln!("beam-impact: {}", bounded_line(text.trim().trim_start_matches("error: ")));
            return ExitCode::from(2);
        }
    };
    let outcome = match cli.command.unwrap_or(Command::Run(cli.run)) {
        Command::Run(args) => match run(&args) {
            Ok(false) if args.strict => return ExitCode::from(UNTRUSTED),
            outcome => outcome.map(|_| ()),
        },
        Command::Scenario => emit(&beam_impact::model::parameters::annotate_toml(&Scenario::default().to_toml())),
        Command::Damping { file, set, figures } => damping(file.as_deref(), &set, figures.as_deref()),
        Command::Modes { file, set, out } => modes(file.as_deref(), &set, &out),
        Command::Pack { out, library, no_zigbuild } => pack(&out, library, no_zigbuild),
        Command::Report { file, out, csv } => report(&file, out, csv.as_deref()),
        Command::Bench { runs } => bench(runs),
        Command::Verify { file, set, json, tolerance } => verify(file.as_deref(), &set, json.as_deref(), tolerance),
        Command::Sweep(args) => sweep(&args),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("beam-impact: {}", bounded_line(&e.to_string()));
            ExitCode::from(2)
        }
    }
}

/// An error as one line of bounded length: a value quoted from a hostile input (a 4 MiB string in
/// a scenario) must not become a megabyte of standard error. Lines longer than 600 characters
/// keep their first 400 and last 150, with the count cut between.
fn bounded_line(message: &str) -> String {
    // Control characters (a terminal's escape sequences from a hostile file) are shown, not sent.
    let line: String = message
        .chars()
        .map(|c| {
            if c == '\n' || c == '\r' || c == '\t' {
                ' '
            } else if c.is_control() {
                '\u{FFFD}'
            } else {
                c
            }
        })
        .collect();
    let chars: Vec<char> = line.chars().collect();
    if chars.len() <= 600 {
        return line;
    }
    let head: String = chars[..400].iter().collect();
    let tail: String = chars[chars.len() - 150..].iter().collect();
    format!("{head} [... {} characters cut ...] {tail}", chars.len() - 550)
}

/// Runs a scenario; returns whether its numbers are trusted.
fn run(args: &RunArgs) -> Result<bool> {
    let settings = beam_impact::studies::sweep::parse_settings(&args.set)?;
    // Only a bare `beam-impact` runs the paper's method; a file or `--set` starts from the defaults.
    let mut scenario = match &args.file {
        Some(path) => read_scenario(path)?,
        None if settings.is_empty() => Scenario::paper(),
        None => Scenario::default(),
    };
    beam_impact::studies::sweep::apply_settings(&mut scenario, &settings)?;
    let mcap = args
        .mcap
        .clone()
        .unwrap_or_else(|| beam_impact::studies::sweep::default_log(args.file.as_deref(), &settings, &scenario));
    let paper = scenario.is_paper();
    let started = Instant::now();
    let simulation = Simulation::new(&scenario)?;
    simulation.check_step_count(scenario.duration_ns(), args.max_steps)?;
    drop(simulation);
    // No two of the files name one (device and inode, or folder and name for a new file), and
    // every output is open before the run, so that a bad path fails at once, not after it; the
    // JSON is written beside and renamed into place at the end, so a failed run leaves the user's
    // earlier file as it was.
    let mut files: Vec<(&str, &Path)> = Vec::new();
    if let Some(file) = args.file.as_deref() {
        files.push(("the scenario file", file));
    }
    if let Some(json) = args.json.as_deref() {
        files.push(("--json", json));
    }
    if !args.no_mcap {
        if mcap.as_os_str() == "-" {
            return Err(beam_impact::Error::Other(
                "--mcap -: an MCAP log cannot go to standard output (the writer goes back to finish its summary); \
                 give a file name, or --no-mcap"
                    .into(),
            ));
        }
        files.push(("--mcap", &mcap));
    }
    check_distinct(&files)?;
    let json_file = match &args.json {
        Some(path) if path.as_os_str() == "-" => Some((path, None)),
        Some(path) => Some((path, Some(OutputFile::create(path, true, "cannot create JSON")?))),
        None => None,
    };
    let mut recorder: Box<dyn Recorder + Send> = if args.no_mcap {
        Box::new(NullRecorder)
    } else {
        let options = RecorderOptions {
            allow_devices: true,
            max_bytes: args.max_log_bytes,
            record_every: args.record_every,
            modal_coordinates: !args.no_modal_coordinates,
            compression: args.log_compression,
            ..RecorderOptions::default()
        };
        Box::new(McapRecorder::with_options(&mcap, options)?)
    };
    let mut progress = Progress::new(recorder.as_mut(), scenario.duration_ns());
    let options = beam_impact::answer::Options { max_steps: args.max_steps, ..Default::default() };
    let answer = beam_impact::answer::run(&scenario, &mut progress, options)?;
    progress.complete(&answer)?;
    progress.bar.finish_and_clear();
    if let Some(reason) = progress.stopped_early() {
        eprintln!("beam-impact: warning: {reason}");
    }
    let wall = started.elapsed();
    let summary = &answer.summary;
    let resolved = &answer.resolved;

    let mut text = format!(
        "beam-impact: {} scenario, method {}, {} + {} elements, {:.3} s simulated\n\n",
        if paper { "paper" } else { "user" },
        if resolved.method == beam_impact::model::Method::Paper { "paper" } else { "converged" },
        resolved.lower.elements,
        resolved.upper.elements_to_contact + resolved.upper.elements_beyond_contact,
        scenario.duration
    );
    text += &compare::comparison(summary, paper);
    if paper {
        text += "(Table 1's FEM column is bound to the paper's 7 + 7/7 mesh; the converged answer follows.)\n";
    }
    text += "\n";
    text += &beam_impact::answer::table(&answer);
    let quality = &answer.quality;
    text += &format!(
        "time steps: {:e} s out of contact, {:e} s in contact{}\n",
        summary.time_steps.free,
        summary.time_steps.contact,
        if scenario.step_free == TimeStep::Auto || scenario.step_contact == TimeStep::Auto {
            " (auto: energy-safe)"
        } else {
            ""
        },
    );
    for line in quality.advisories.iter() {
        eprintln!("beam-impact: note: {line}");
    }
    for line in quality.reasons.iter() {
        eprintln!("beam-impact: warning: results not trusted: {line}");
    }
    text += &format!("wall time: {:.1} ms (assembly, modes and stepping", wall.as_secs_f64() * 1e3);
    if !args.no_mcap {
        text += &format!(", recorded to {}", mcap.display());
    }
    text += ")\n";
    if let Some((path, file)) = json_file {
        let mut summary_json = serde_json::to_value(summary).map_err(|e| Error::Other(format!("JSON: {e}")))?;
        summary_json["converged_peaks"] = serde_json::json!(answer.converged_peaks);
        summary_json["converged_first_contact_peaks"] = serde_json::json!(answer.converged_first_contact_peaks);
        summary_json["quality"] = serde_json::json!(answer.quality);
        let doc = serde_json::json!({
            "scenario": resolved,
            "scenario_as_given": scenario,
            "summary": summary_json,
            "quality": answer.quality,
            "design": answer.design,
            "discretisation": discretisation_json(&answer),
            "merged_contact_windows": compare::merged_windows(&summary.contact_windows, beam_impact::results::BOUNCE_GAP),
            "units": json_units(),
            "wall_time_s": wall.as_secs_f64(),
        });
        let json = serde_json::to_string_pretty(&doc).map_err(|e| Error::Other(format!("JSON: {e}")))?;
        match file {
            Some(mut file) => {
                writeln!(file, "{json}").map_err(|source| io("cannot write JSON", path, source))?;
                file.commit()?;
                text += &format!("results written to {}\n", path.display());
            }
            // `--json -`: the JSON is the standard output, without the tables.
            None => return emit(&format!("{json}\n")).map(|()| answer.quality.trusted),
        }
    }
    emit(&text)?;
    Ok(answer.quality.trusted)
}

/// Reads and validates a scenario file (missing fields take their defaults); `-` is the standard
/// input. A FIFO or socket is refused rather than waited on.
fn read_scenario(path: &Path) -> Result<Scenario> {
    if path.as_os_str() == "-" {
        let text = read_bounded(std::io::stdin().lock(), MAX_SCENARIO_BYTES, "the scenario")
            .map_err(|source| io("cannot read scenario", Path::new("standard input"), source))?;
        return Scenario::from_toml(&text, "standard input");
    }
    let file = open_input(path, "cannot read scenario")?;
    let text = read_bounded(file, MAX_SCENARIO_BYTES, "the scenario")
        .map_err(|source| io("cannot read scenario", path, source))?;
    Scenario::from_toml(&text, &path.display().to_string())
}

/// The `discretisation` block of `--json` and of the log's `answer.json`: each peak's figure, the
/// twin's spread, the late peaks not vouched for, and the runs (rungs) behind the answer.
fn discretisation_json(answer: &beam_impact::answer::Answer) -> serde_json::Value {
    serde_json::json!({
        "peaks": answer.discretisation_error,
        "first_contact_peaks": answer.first_contact_discretisation_error,
        "sensitivity_spread": answer.sensitivity_spread,
        "unvouched_late_peaks": answer.unvouched_late_peaks,
        "runs": answer.runs,
    })
}

/// The SI units of the `--json` fields (by name; nested names with dots).
fn json_units() -> serde_json::Value {
    serde_json::json!({
        "time, times, contact windows, time_steps, first_contact_end": "s",
        "lower_tip_deflection, tip_deflection": "m",
        "*_stress (peaks, first_contact_peaks, energy_method)": "Pa",
        "contact_force, energy_method.force": "N",
        "energies, residuals, strain_energy, bridge_strain_energy, upper_strain_at_peak_deflection": "J",
        "energy_method.flexion_stiffness": "N/m",
        "energy_method.bridge_deceleration": "rad/s^2",
        "energy_method.bridge_contact_moment": "N m",
        "modes": "rad/s",
        "energy_residual_fraction, energy_tolerance, bridge_strain_ratio": "1 (fraction)",
        "scenario": "SI, as in `beam-impact scenario`",
        "wall_time_s": "s"
    })
}

fn io(action: &'static str, path: &Path, source: std::io::Error) -> Error {
    Error::Io { action, path: path.display().to_string(), source }
}

/// Writes to standard output; a reader that went away (`| head`) ends the output quietly.
fn emit(text: &str) -> Result<()> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(io("cannot write", Path::new("standard output"), e))
        }
        _ => Ok(()),
    }
}

/// Shows a progress bar (on a terminal) while passing every step on to the real recorder.
struct Progress<'a> {
    inner: &'a mut (dyn Recorder + Send),
    bar: ProgressBar,
    /// The run asked to finish the record: deferred until its answer is attached.
    finish_requested: bool,
}

impl<'a> Progress<'a> {
    fn new(inner: &'a mut (dyn Recorder + Send), end_ns: u64) -> Self {
        let bar = ProgressBar::new(end_ns / 1_000_000);
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} ms simulated, {elapsed} ({eta} left)")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Progress { inner, bar, finish_requested: false }
    }
}

impl Progress<'_> {
    /// Stores the answer with its checks in the record (`answer.json`) and finishes it.
    fn complete(&mut self, answer: &beam_impact::answer::Answer) -> Result<()> {
        if self.finish_requested {
            let doc = serde_json::json!({
                "quality": answer.quality,
                "design": answer.design,
                "converged_peaks": answer.converged_peaks,
                "converged_first_contact_peaks": answer.converged_first_contact_peaks,
                "discretisation": discretisation_json(answer),
            });
            let bytes = serde_json::to_vec_pretty(&doc).map_err(|e| Error::Other(format!("JSON: {e}")))?;
            self.inner.attach(beam_impact::record::mcap::ANSWER_ATTACHMENT, "application/json", &bytes)?;
        }
        self.inner.finish()
    }
}

impl Recorder for Progress<'_> {
    fn start(&mut self, info: &RunInfo<'_>) -> Result<()> {
        self.inner.start(info)
    }
    fn step(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        if result.step.is_multiple_of(1000) {
            self.bar.set_position(result.time_ns / 1_000_000);
        }
        self.inner.step(result, modal_coordinates)
    }
    fn contact_event(&mut self, event: &ContactEvent) -> Result<()> {
        self.inner.contact_event(event)
    }
    /// Deferred: the answer with its checks is attached first ([`Progress::complete`]).
    fn finish(&mut self) -> Result<()> {
        self.finish_requested = true;
        Ok(())
    }
    fn wants_details(&self) -> bool {
        self.inner.wants_details()
    }
    fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> Result<()> {
        self.inner.attach(name, media_type, data)
    }
    fn stopped_early(&self) -> Option<&str> {
        self.inner.stopped_early()
    }
}

/// The scenario of a subcommand: the file's, else the paper's, else (with `--set` and no file)
/// the default, with the `--set` changes, as `run` reads it.
fn scenario_with_settings(file: Option<&Path>, set: &[String]) -> Result<Scenario> {
    let settings = beam_impact::studies::sweep::parse_settings(set)?;
    let mut scenario = match file {
        Some(path) => read_scenario(path)?,
        None if settings.is_empty() => Scenario::paper(),
        None => Scenario::default(),
    };
    beam_impact::studies::sweep::apply_settings(&mut scenario, &settings)?;
    Ok(scenario)
}

fn damping(file: Option<&Path>, set: &[String], figures: Option<&Path>) -> Result<()> {
    use beam_impact::studies::damping::{run_with_histories, table, RATIOS};
    let scenario = scenario_with_settings(file, set)?;
    let Some(dir) = figures else {
        let rows = beam_impact::studies::damping::run(&scenario, &RATIOS)?;
        return emit(&table(&rows));
    };
    let runs = run_with_histories(&scenario, &RATIOS)?;
    let rows: Vec<_> = runs.iter().map(|r| (r.scenario.damping_ratio, r.summary.clone())).collect();
    let mut text = table(&rows);
    text += "\nfigures (of this FE model, not of the paper's simplified Figure A1 model):\n";
    for file in beam_impact::replay::damping_figures::write_damping_figures(&scenario, &runs, dir)? {
        text += &format!("  {}\n", file.display());
    }
    emit(&text)
}

/// Figures 10-12 of a scenario, with the frequencies of Table 2.
fn modes(file: Option<&Path>, set: &[String], out: &Path) -> Result<()> {
    let mut scenario = match file {
        Some(path) => read_scenario(path)?,
        None => Scenario::paper(),
    };
    beam_impact::studies::sweep::apply_settings(&mut scenario, &beam_impact::studies::sweep::parse_settings(set)?)?;
    // The model and its modes only: no time step is involved ("auto" element counts resolved as a
    // run resolves them).
    if let Some(path) = file {
        beam_impact::record::output::check_not_in_figure_folder("the scenario file", path, out)?;
    }
    let model = beam_impact::model::Model::new(&beam_impact::discretise::printed(&scenario)?)?;
    let modal = beam_impact::solver::ModalSystem::new(&model)?;
    let mut text = String::from("natural frequencies, rad/s (the first 5 of each column of Table 2):\n");
    for (name, modes) in [("arrestor", &modal.lower), ("bridge", &modal.upper), ("coupled", &modal.coupled)] {
        let values: Vec<String> = modes.omega.iter().take(5).map(|w| format!("{w:.2}")).collect();
        text += &format!("  {name:9} {}\n", values.join(", "));
    }
    text += "figures:\n";
    for file in beam_impact::replay::mode_figures::write_mode_figures(&model, &modal, out)? {
        text += &format!("  {}\n", file.display());
    }
    emit(&text)
}

/// Packs `library`, or else the glibc 2.17 build that cargo-zigbuild makes when it is on PATH (and
/// `no_zigbuild` is not set), or else the host build next to this executable. The build runs here,
/// in the CLI, not in `fmi::pack`: that module is part of the shared library loaded into every
/// FMU host, which has no business spawning cargo; `fmi::pack` packs the file it is given.
fn pack(out: &Path, library: Option<PathBuf>, no_zigbuild: bool) -> Result<()> {
    /// The target cargo-zigbuild builds for: x86_64 Linux, linked against glibc 2.17 symbols
    /// (manylinux2014: loads on RHEL 7/8, Ubuntu 20.04, Debian 11 and later).
    const TARGET: &str = "x86_64-unknown-linux-gnu.2.17";

    /// An executable named `name` in a directory of PATH.
    fn on_path(name: &str) -> Option<PathBuf> {
        use std::os::unix::fs::PermissionsExt;
        let paths = std::env::var_os("PATH")?;
        std::env::split_paths(&paths)
            .map(|dir| dir.join(name))
            .find(|p| p.metadata().is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0))
    }

    /// Runs `cargo zigbuild` on this crate's source into its own target directory
    /// (`<target>/zigbuild`, so that the host build's artifacts are neither locked nor rebuilt)
    /// and returns the library it built.
    fn zigbuild(zigbuild: &Path) -> Result<PathBuf> {
        let source = Path::new(env!("CARGO_MANIFEST_DIR"));
        let manifest = source.join("Cargo.toml");
        if !manifest.is_file() {
            return Err(Error::Other(format!(
                "cannot build the library for glibc 2.17: the crate's source {} is gone (pass --library FILE or \
                 --no-zigbuild)",
                source.display()
            )));
        }
        let target_dir =
            std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| source.join("target"), PathBuf::from).join("zigbuild");
        eprintln!("beam-impact: building the library for glibc 2.17 with {}", zigbuild.display());
        let started = Instant::now();
        let status = std::process::Command::new(zigbuild)
            .args(["zigbuild", "--release", "--lib", "--target", TARGET, "--manifest-path"])
            .arg(&manifest)
            .arg("--target-dir")
            .arg(&target_dir)
            .status()
            .map_err(|source| io("cannot run", zigbuild, source))?;
        if !status.success() {
            return Err(Error::Other(format!(
                "`{} zigbuild --release --lib --target {TARGET}` failed ({status}); --no-zigbuild packs the host build",
                zigbuild.display()
            )));
        }
        let library = target_dir.join("x86_64-unknown-linux-gnu").join("release").join("libbeam_impact.so");
        eprintln!(
            "beam-impact: built {} for glibc 2.17 in {:.1} s",
            library.display(),
            started.elapsed().as_secs_f64()
        );
        Ok(library)
    }

    let library = match library {
        Some(path) => path,
        None => {
            let zig = if no_zigbuild { None } else { on_path("cargo-zigbuild") };
            match zig {
                Some(zig) => zigbuild(&zig)?,
                None => {
                    if !no_zigbuild {
                        eprintln!(
                            "beam-impact: warning: cargo-zigbuild is not on PATH: packing the host build, which needs \
                             this machine's glibc or newer (pip install ziglang cargo-zigbuild for a glibc 2.17 build)"
                        );
                    }
                    host_library()?
                }
            }
        }
    };
    for path in beam_impact::fmi::pack::pack(&library, out)? {
        emit(&format!("wrote {}\n", path.display()))?;
    }
    Ok(())
}

/// The host build of the library: beside the running executable (`cargo build`), or in its
/// `deps/` (`cargo test` builds it there only); an installed executable has none, so the error
/// says how to pack one.
fn host_library() -> Result<PathBuf> {
    let exe = std::env::current_exe().map_err(|source| Error::Io {
        action: "cannot locate",
        path: "the running executable".into(),
        source,
    })?;
    let beside = exe.with_file_name("libbeam_impact.so");
    let candidates = [beside.clone(), exe.with_file_name("deps").join("libbeam_impact.so")];
    candidates.into_iter().find(|p| p.is_file()).ok_or_else(|| {
        Error::Other(format!(
            "no libbeam_impact.so beside {} (an installed beam-impact carries no library): run `cargo run --release \
             -- pack` in the source tree, or pass --library PATH to a built libbeam_impact.so",
            exe.display()
        ))
    })
}

fn report(file: &Path, out: Option<PathBuf>, csv: Option<&Path>) -> Result<()> {
    let out = out.unwrap_or_else(|| beam_impact::replay::report::default_out_dir(file));
    let stdout = std::io::stdout();
    let mut lock = stdout.lock();
    let csv_to_stdout = csv.is_some_and(|path| path.as_os_str() == "-");
    beam_impact::record::output::check_not_in_figure_folder("the log", file, &out)?;
    if let Some(path) = csv {
        check_distinct(&[("the log", file), ("--csv", path)])?;
        if !csv_to_stdout && beam_impact::record::output::same_folder(path, &out) {
            return Err(Error::Other(format!(
                "--csv {} is inside the figure folder {}, which the figures are written to; give another folder",
                path.display(),
                out.display()
            )));
        }
        // Opened before the log is read, so that a bad path fails at once.
        let target = if csv_to_stdout { None } else { Some(OutputFile::create(path, true, "cannot create CSV")?) };
        let data = beam_impact::replay::report::read_log(file)?;
        if csv_to_stdout && (!data.complete || data.stopped_early.is_some()) {
            // The summary, which would say so, is not printed.
            eprintln!(
                "beam-impact: warning: {}: {}; the CSV holds the {} step messages before it",
                file.display(),
                data.problem.as_deref().or(data.stopped_early.as_deref()).unwrap_or("incomplete log"),
                data.steps.len()
            );
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
    lock.flush().ok();
    Ok(())
}

fn bench(runs: usize) -> Result<()> {
    let runs = runs.max(1);
    eprintln!("beam-impact bench: 1/2 production stepper vs dense oracle, per-step cost ({runs} runs each)...");
    emit(&beam_impact::studies::bench::stepper_benchmark(runs)?)?;
    eprintln!("beam-impact bench: 2/2 recorded vs unrecorded paper run ({runs} runs each)...");
    emit(&format!("\n{}", beam_impact::record::bench::recording_benchmark(runs)?))
}

fn verify(file: Option<&Path>, set: &[String], json: Option<&Path>, tolerance: f64) -> Result<()> {
    use beam_impact::studies::verify::{default_threads, table, Plan, RUN_LABELS};
    let scenario = scenario_with_settings(file, set)?;
    let plan = Plan::new(&scenario, tolerance)?;
    let mut files: Vec<(&str, &Path)> = file.map(|f| ("the scenario file", f)).into_iter().collect();
    files.extend(json.map(|j| ("--json", j)));
    check_distinct(&files)?;
    let json_file = match json {
        Some(path) => Some((path, OutputFile::create(path, true, "cannot create JSON")?)),
        None => None,
    };
    let started = Instant::now();
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
        text += &format!("verdicts written to {}\n", path.display());
    }
    emit(&text)
}

fn sweep(args: &SweepArgs) -> Result<()> {
    use beam_impact::studies::sweep::{
        apply_settings, default_jobs, parse_axes, parse_settings, Sweep, SweepWriteError,
    };
    let mut base = match &args.file {
        Some(path) => read_scenario(path)?,
        None => Scenario::default(),
    };
    apply_settings(&mut base, &parse_settings(&args.set)?)?;
    let sweep = Sweep::new(base, parse_axes(&args.vary)?, args.max_steps)?;
    let jobs = args.jobs.map_or_else(default_jobs, |j| usize::try_from(j).unwrap_or(usize::MAX));
    let mut files: Vec<(&str, &Path)> = args.file.as_deref().map(|f| ("the scenario file", f)).into_iter().collect();
    files.push(("--out", &args.out));
    files.extend(args.json.as_deref().map(|j| ("--json", j)));
    check_distinct(&files)?;
    let create = |path: &Path| OutputFile::create(path, true, "cannot create").map(std::io::BufWriter::new);
    let mut csv = create(&args.out)?;
    let mut json = args.json.as_deref().map(create).transpose()?;
    let bar = ProgressBar::new(sweep.len() as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} scenarios, {elapsed} ({eta} left)")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let started = Instant::now();
    let tally = sweep
        .write(jobs, &mut csv, json.as_mut().map(|j| j as &mut dyn Write), &mut |n| bar.set_position(n as u64))
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
    commit(csv, &args.out)?;
    if let (Some(json), Some(path)) = (json, args.json.as_deref()) {
        commit(json, path)?;
    }
    let wall = started.elapsed().as_secs_f64();
    if tally.failed > 0 {
        eprintln!(
            "beam-impact: warning: {} of {} scenarios failed (their rows hold the error)",
            tally.failed, tally.scenarios
        );
    }
    if tally.untrusted > 0 {
        eprintln!(
            "beam-impact: warning: {} of {} scenarios not trusted (column trusted)",
            tally.untrusted, tally.scenarios
        );
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
        args.out.display()
    );
    if let Some(path) = &args.json {
        text += &format!(" and {}", path.display());
    }
    emit(&(text + "\n"))
}
