//! `beam-impact`: run the paper scenario or a user scenario, print the comparison with the
//! paper, write FMUs, replay logs, benchmark. Thin: everything happens in the library.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::{Args, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};

use beam_impact::model::TimeStep;
use beam_impact::record::mcap::McapRecorder;
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
        /// Scenario file (default: the paper scenario).
        file: Option<PathBuf>,
    },
    /// Write the FMI 2.0 and FMI 3.0 co-simulation FMUs.
    Pack {
        /// Output directory; the FMUs go to DIR/fmi2/BeamImpact.fmu and DIR/fmi3/BeamImpact.fmu.
        #[arg(long, default_value = "target/fmu")]
        out: PathBuf,
        /// The shared library to pack (default: libbeam_impact.so next to this executable).
        #[arg(long)]
        library: Option<PathBuf>,
    },
    /// Read an MCAP log: print its summary and write Figures 6-9 (SVG and PNG).
    Report {
        /// The log.
        file: PathBuf,
        /// Directory for the figures (default: <log stem>-figures next to the log).
        #[arg(long)]
        out: Option<PathBuf>,
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
        /// Scenario file (default: the paper scenario).
        file: Option<PathBuf>,
        /// Write the verdicts as JSON to this file.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Largest relative change of a converged peak, a fraction (0.01 is 1 %).
        #[arg(long, default_value_t = beam_impact::verify::DEFAULT_TOLERANCE)]
        tolerance: f64,
    },
}

#[derive(Args)]
struct RunArgs {
    /// Scenario file (TOML); missing fields take the paper's values. Default: the paper scenario.
    file: Option<PathBuf>,
    /// Write the summary as JSON to this file.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Record every step to this MCAP file.
    #[arg(long, default_value = "paper.mcap", conflicts_with = "no_mcap")]
    mcap: PathBuf,
    /// Do not record.
    #[arg(long)]
    no_mcap: bool,
    /// Exit with code 3 when the run is not trusted (its energy residual is above the scenario's
    /// `energy_tolerance`).
    #[arg(long)]
    strict: bool,
    /// Refuse runs that need more internal steps than this (duration over the smaller step).
    #[arg(long, default_value_t = beam_impact::model::scenario::MAX_STEPS)]
    max_steps: u64,
}

/// Exit code of a run that completed but whose numbers are not trusted (with `--strict`).
const UNTRUSTED: u8 = 3;

fn main() -> ExitCode {
    std::panic::set_hook(Box::new(|info| {
        eprintln!("beam-impact: internal error: {info}");
    }));
    let cli = Cli::parse();
    let outcome = match cli.command.unwrap_or(Command::Run(cli.run)) {
        Command::Run(args) => match run(&args) {
            Ok(false) if args.strict => return ExitCode::from(UNTRUSTED),
            outcome => outcome.map(|_| ()),
        },
        Command::Scenario => emit(&Scenario::default().to_toml()),
        Command::Damping { file } => damping(file.as_deref()),
        Command::Pack { out, library } => pack(&out, library),
        Command::Report { file, out } => report(&file, out),
        Command::Bench { runs } => bench(runs),
        Command::Verify { file, json, tolerance } => verify(file.as_deref(), json.as_deref(), tolerance),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("beam-impact: {e}");
            ExitCode::from(2)
        }
    }
}

/// Runs a scenario; returns whether its numbers are trusted.
fn run(args: &RunArgs) -> Result<bool> {
    let scenario = match &args.file {
        Some(path) => read_scenario(path)?,
        None => Scenario::paper(),
    };
    let paper = scenario.is_paper();
    let started = Instant::now();
    let mut simulation = Simulation::new(&scenario)?;
    simulation.check_step_count(scenario.duration_ns(), args.max_steps)?;
    // Open every output before the run, so that a bad path fails at once, not after it.
    let json_file = match &args.json {
        Some(path) => {
            Some((path, std::fs::File::create(path).map_err(|source| io("cannot create JSON", path, source))?))
        }
        None => None,
    };
    let mut recorder: Box<dyn Recorder> =
        if args.no_mcap { Box::new(NullRecorder) } else { Box::new(McapRecorder::create(&args.mcap)?) };
    let mut progress = Progress::new(recorder.as_mut(), scenario.duration_ns());
    simulation.run(&mut progress)?;
    progress.bar.finish_and_clear();
    let wall = started.elapsed();
    let summary = simulation.summary();

    let mut text = format!(
        "beam-impact: {} scenario, {} + {} elements, {:.3} s simulated\n\n",
        if paper { "paper" } else { "user" },
        scenario.lower.elements,
        scenario.upper.elements_to_contact + scenario.upper.elements_beyond_contact,
        scenario.duration
    );
    text += &compare::comparison(&summary, paper);
    let quality = &summary.quality;
    text += &format!(
        "time steps: {:e} s out of contact, {:e} s in contact{}\nquality: {} (energy residual {:.4} % of the energy \
         that flows, tolerance {} %)\n",
        summary.time_steps.free,
        summary.time_steps.contact,
        if scenario.step_free == TimeStep::Auto || scenario.step_contact == TimeStep::Auto {
            " (auto: energy-safe)"
        } else {
            ""
        },
        if quality.trusted { "trusted" } else { "NOT TRUSTED" },
        quality.energy_residual_fraction * 100.0,
        quality.energy_tolerance * 100.0
    );
    for line in quality.advisories.iter() {
        eprintln!("beam-impact: note: {line}");
    }
    for line in quality.reasons.iter() {
        eprintln!("beam-impact: warning: results not trusted: {line}");
    }
    text += &format!("wall time: {:.1} ms (assembly, modes and stepping", wall.as_secs_f64() * 1e3);
    if !args.no_mcap {
        text += &format!(", recorded to {}", args.mcap.display());
    }
    text += ")\n";
    if let Some((path, mut file)) = json_file {
        let doc = serde_json::json!({
            "scenario": scenario,
            "summary": summary,
            "quality": summary.quality,
            "wall_time_s": wall.as_secs_f64(),
        });
        let json = serde_json::to_string_pretty(&doc).map_err(|e| Error::Other(format!("JSON: {e}")))?;
        writeln!(file, "{json}").map_err(|source| io("cannot write JSON", path, source))?;
        text += &format!("results written to {}\n", path.display());
    }
    emit(&text)?;
    Ok(summary.quality.trusted)
}

/// Reads and validates a scenario file (missing fields take the paper's values).
fn read_scenario(path: &Path) -> Result<Scenario> {
    let text = std::fs::read_to_string(path).map_err(|source| io("cannot read scenario", path, source))?;
    Scenario::from_toml(&text, &path.display().to_string())
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
    inner: &'a mut dyn Recorder,
    bar: ProgressBar,
}

impl<'a> Progress<'a> {
    fn new(inner: &'a mut dyn Recorder, end_ns: u64) -> Self {
        let bar = ProgressBar::new(end_ns / 1_000_000);
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} ms simulated, {elapsed} ({eta} left)")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Progress { inner, bar }
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
    fn finish(&mut self) -> Result<()> {
        self.inner.finish()
    }
    fn wants_details(&self) -> bool {
        self.inner.wants_details()
    }
}

fn damping(file: Option<&Path>) -> Result<()> {
    let scenario = match file {
        Some(path) => read_scenario(path)?,
        None => Scenario::paper(),
    };
    let rows = beam_impact::damping_study::run(&scenario, &beam_impact::damping_study::RATIOS)?;
    emit(&beam_impact::damping_study::table(&rows))
}

fn pack(out: &Path, library: Option<PathBuf>) -> Result<()> {
    let library = match library {
        Some(path) => path,
        None => std::env::current_exe()
            .map_err(|source| Error::Io { action: "cannot locate", path: "the running executable".into(), source })?
            .with_file_name("libbeam_impact.so"),
    };
    for path in beam_impact::fmi::pack::pack(&library, out)? {
        emit(&format!("wrote {}\n", path.display()))?;
    }
    Ok(())
}

fn report(file: &Path, out: Option<PathBuf>) -> Result<()> {
    let out = out.unwrap_or_else(|| beam_impact::record::report::default_out_dir(file));
    let stdout = std::io::stdout();
    let mut lock = stdout.lock();
    beam_impact::record::report::report(file, &out, &mut lock)?;
    lock.flush().ok();
    Ok(())
}

fn bench(runs: usize) -> Result<()> {
    let runs = runs.max(1);
    emit(&beam_impact::bench::stepper_benchmark(runs)?)?;
    emit(&format!("\n{}", beam_impact::record::bench::recording_benchmark(runs)?))
}

fn verify(file: Option<&Path>, json: Option<&Path>, tolerance: f64) -> Result<()> {
    use beam_impact::verify::{default_threads, table, Plan, RUN_LABELS};
    let scenario = match file {
        Some(path) => read_scenario(path)?,
        None => Scenario::paper(),
    };
    let plan = Plan::new(&scenario, tolerance)?;
    let json_file = match json {
        Some(path) => {
            Some((path, std::fs::File::create(path).map_err(|source| io("cannot create JSON", path, source))?))
        }
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
        text += &format!("verdicts written to {}\n", path.display());
    }
    emit(&text)
}
