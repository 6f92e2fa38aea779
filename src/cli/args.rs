//! The command line: subcommands and their options (clap). What each does is in its own file.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

use beam_impact::record::mcap::{LogChannels, LogCompression};

/// Elastic impact of two beams (Catipovic, Vladimir, Reljic 2008): FEM + linear acceleration method.
#[derive(Parser)]
#[command(name = "beam-impact", version, about)]
#[command(args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// With no subcommand: `run` with these options.
    #[command(flatten)]
    pub run: RunArgs,
}

#[derive(Subcommand)]
pub enum Command {
    /// Run a scenario (default: the paper's) and print Tables 1-3 beside the paper.
    Run(RunArgs),
    /// Print the default scenario as TOML, every field with its unit and range, to start a
    /// scenario file from: the paper's beams with the converged method and automatic energy-safe
    /// steps. A field `x` under `[upper]` is `upper.x` for `--set`, `--vary` and the FMU.
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
        /// Scenario file (default: the paper scenario; with --set and no file, the default
        /// scenario, as `run --set`).
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
        /// The platforms whose binaries go into both FMUs: `all` or a list of linux, windows,
        /// darwin (`linux,windows`). Windows and macOS binaries are cross-built by
        /// scripts/cross-build.sh with the toolchain of scripts/cross-toolchain.sh (in
        /// $BEAM_IMPACT_CROSS_DIR, else .cross/, else ~/.cache/beam-impact-cross/toolchain)
        /// unless given with --windows-library / --darwin-library.
        #[arg(long, default_value = "linux", value_name = "LIST")]
        platforms: String,
        /// The Windows x86-64 DLL to pack, as it is (instead of cross-building it).
        #[arg(long, value_name = "FILE.dll")]
        windows_library: Option<PathBuf>,
        /// The macOS universal2 dylib (x86-64 and arm64) to pack, as it is (instead of
        /// cross-building it).
        #[arg(long, value_name = "FILE.dylib")]
        darwin_library: Option<PathBuf>,
        /// A scenario file to pack as both FMUs' starting scenario, `resources/scenario.toml`
        /// (beams of sections included, which no FMU parameter can state): its values become the
        /// start values of the model descriptions, and the importer's parameters override its
        /// uniform fields. Without it the FMUs start from the paper scenario. With --ssp a
        /// scenario's [sea] goes to the vessel FMU: the SSD binds its sea state and deck points,
        /// its RAO file becomes the vessel FMU's resources/raos.csv (docs/ssp.md).
        #[arg(long, value_name = "FILE.toml")]
        scenario: Option<PathBuf>,
        /// Also write DIR/GangwayOnVessel.ssp (SSP 1.0): the FMI 2.0 FMU and the vessel-motion
        /// FMU (built from fmu/vessel/vessel_motion.c with zig, or the host's cc for Linux, for the
        /// same platforms), connected both ways, with parameter bindings and a default experiment
        /// (docs/ssp.md).
        #[arg(long)]
        ssp: bool,
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

        /// Also write the run as one self-contained HTML page (docs/html-report.md): the scenario,
        /// Table 1, every number with its verdict, the envelope, zoomable time histories.
        #[arg(long, value_name = "FILE.html")]
        html: Option<PathBuf>,
        /// Print the run's fatigue instead (issue 44): every bending station's rainflow cycles and
        /// Miner's damage on the scenario's `[fatigue]` curve and factors, the hot spots, each
        /// beam's worst, the life; from the log's fatigue.json, else rebuilt from /beam/stations.
        #[arg(long, conflicts_with_all = ["csv", "out", "html"])]
        fatigue: bool,
        /// With --fatigue: this S-N curve instead of the scenario's (`D`, `C-2024`, ...).
        #[arg(long, value_name = "NAME", requires = "fatigue")]
        curve: Option<String>,
    },
    /// Time the production stepper against the dense oracle, the per-step cost at finer
    /// meshes, and the recorded run.
    Bench {
        /// Runs per measurement (the median is reported), 1 to 1000.
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u16).range(1..=1000))]
        runs: u16,
    },
    /// Convergence of the four Table 1 peaks and the contact force: the scenario at half its steps
    /// and at 2x and 4x its elements with 2x and 4x its modal cut-off; each peak's changes, a
    /// Richardson estimate and a verdict.
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
    /// Write a scenario's sea (`[sea]`, issue 42) as a motion file: `time` (the record's, s),
    /// `wave_elevation` at the vessel's motion reference point (m) and the nine support-motion
    /// columns, from the record's time 0 to DURATION every SAMPLE-INTERVAL, in the format `run
    /// --motion` reads (`run --motion FILE.csv --set motion.time_shift=S` is the `[sea]` run
    /// with `sea.time_shift = S`, to the bit, on the same grid).
    Sea {
        /// Scenario file with a `[sea]` section.
        file: PathBuf,
        /// Change a scenario field, KEY=VALUE, as `run --set` (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// The record's length, s.
        #[arg(long, value_name = "T")]
        duration: f64,
        /// The CSV file to write.
        #[arg(long, value_name = "FILE.csv")]
        out: PathBuf,
        /// Interval of the rows, s (default: the scenario's `sea.sample_interval`).
        #[arg(long, value_name = "S")]
        sample_interval: Option<f64>,
    },
    /// A design sweep: every combination of the `--vary` values (the last varying fastest), run in
    /// parallel without logs; one CSV row per scenario (peaks, peak times, energy approach,
    /// largest energy residual, trust verdict, error).
    Sweep(SweepArgs),
    /// A campaign of impacts in a sea state (docs/operability.md): EVENTS losses of the support at
    /// instants drawn across SEEDS records, each a converged run with its verdict; one CSV row per
    /// event, the statistics per design quantity (exceedance probability with its Clopper-Pearson
    /// interval, a Gumbel fit of the records' maxima, the most probable maximum), and over a
    /// `--vary` grid of Hs, Tp and heading the operability table.
    Campaign(CampaignArgs),
    /// Print the completion script of a shell to standard output: `beam-impact completions bash >
    /// ~/.local/share/bash-completion/completions/beam-impact`, `completions zsh > ~/.zfunc/_beam-impact`,
    /// `completions fish > ~/.config/fish/completions/beam-impact.fish`.
    Completions {
        /// The shell: bash, zsh, fish, elvish or powershell.
        #[arg(value_enum)]
        shell: clap_complete::Shell,
    },
    /// The fatigue of a stress history (docs/fatigue.md): per stress column of HISTORY.csv (a
    /// `time` column in s and stress columns in Pa) the rainflow cycles (ASTM E1049-85) and the
    /// Palmgren-Miner damage on a DNV-RP-C203 S-N curve, with an SCF, a thickness and a DFF.
    Fatigue(FatigueArgs),
}

#[derive(Args)]
pub struct RunArgs {
    /// Scenario file (TOML); missing fields take the default scenario's values (the paper's beams,
    /// the converged method). Default: the paper scenario
    /// with its method (with --set: the default scenario, as `beam-impact scenario` prints it).
    pub file: Option<PathBuf>,
    /// Write the summary as JSON to this file; `-`: to standard output, instead of the tables (the
    /// warnings stay on standard error).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Record every step to this MCAP file [default: paper.mcap; with --set: <stem>-set-<hash>.mcap].
    #[arg(long, conflicts_with = "no_mcap")]
    pub mcap: Option<PathBuf>,
    /// Do not record.
    #[arg(long)]
    pub no_mcap: bool,
    /// Exit with code 3 when the run is not trusted: when any check that ran fails (the energy
    /// balance against `energy_tolerance`; the peaks' discretisation figure and their spread
    /// against the twin run, against `discretisation_tolerance`; the largest stress against
    /// `yield_stress`, when given; the model's range: deflections, rotations and strains against
    /// the small-deflection, linear-elastic limits). Without it such a run warns and exits 0.
    #[arg(long)]
    pub strict: bool,
    /// Stop the MCAP log at this size, bytes (the run goes on unrecorded, with a warning).
    #[arg(long, default_value_t = beam_impact::record::mcap::MAX_LOG_BYTES)]
    pub max_log_bytes: u64,
    /// Refuse runs that need more internal steps than this (duration over the smaller step).
    #[arg(long, default_value_t = beam_impact::model::scenario::MAX_STEPS, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_steps: u64,
    /// Record every Nth internal step to the MCAP log (for long runs), instead of the dense
    /// output (--log-sample-interval 0). Step 0, the last step, the steps on both sides of a
    /// contact change and every step where a running peak changes are recorded whatever N.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    pub record_every: u64,
    /// The MCAP log's dense output, s of simulated time: the converged method's log holds the
    /// exact state at every multiple of it and wherever a running peak is reached (so the log's
    /// largest values are the printed peaks), the paper method's log one of its own steps at
    /// least this often; both keep the steps where contact starts or ends or a peak rises. 0:
    /// every internal step (thinned by --record-every) [default: 1e-4; with --record-every: 0].
    #[arg(long, value_name = "SECONDS")]
    pub log_sample_interval: Option<f64>,
    /// The topics of the MCAP log, a comma list of model, step, contact, log (always written),
    /// modes (/beam/modes: without it `report` cannot give the bridge's strain energy at the peak
    /// deflection), scene (/beam/scene, Foxglove's 3D panel) and stations (/beam/stations: without
    /// it a killed run's log cannot rebuild the stress envelope), or all: `--log-channels step`
    /// writes the smallest log that replays.
    #[arg(long, value_name = "LIST", default_value = "all")]
    pub log_channels: LogChannels,
    /// The same as leaving `modes` out of --log-channels (kept as an alias).
    #[arg(long)]
    pub no_modal_coordinates: bool,
    /// The same as leaving `stations` out of --log-channels (kept as an alias); the envelope is
    /// still attached when the log is finished and the 3D scene still coloured by utilisation.
    #[arg(long)]
    pub no_station_stresses: bool,
    /// Chunk compression of the MCAP log: zstd (the default, at level -1: the paper log a third
    /// smaller than none), lz4 (larger, and no cheaper to write) or none (the largest file, the
    /// cheapest writer). Every MCAP reader reads all three.
    #[arg(long, value_name = "zstd|lz4|none", default_value = "zstd")]
    pub log_compression: LogCompression,
    /// Change a scenario field, KEY=VALUE with the dotted names of `beam-impact scenario`
    /// (repeatable): `--set upper.mass=14000 --set step_free=auto --set stress_recovery=left`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// The supports' motion, a CSV file: `time` (s) and any of upper.hinge_heave,
    /// lower.clamp_heave, lower.clamp_rotation with their _velocity and _acceleration columns
    /// (all three of a moving support). Between rows each support moves with the row's constant
    /// acceleration. `--set motion.time_shift=S` starts the run at the file's time S.
    #[arg(long, value_name = "FILE.csv")]
    pub motion: Option<PathBuf>,
    /// Also write the run as one self-contained HTML page (docs/html-report.md), its numbers those
    /// of --json and its time histories read back from the run's log (so not with --no-mcap).
    #[arg(long, value_name = "FILE.html", conflicts_with = "no_mcap")]
    pub html: Option<PathBuf>,
}

#[derive(Args)]
pub struct SweepArgs {
    /// Scenario file (TOML) the grid starts from. Default: the default scenario (`beam-impact scenario`: method converged, automatic mesh and steps), as `run --set`.
    pub file: Option<PathBuf>,
    /// A varied field, KEY=SPEC with SPEC `start:stop:count` (inclusive, linear) or a comma list
    /// (repeatable; the first is the outermost loop): `--vary drop_height=0.1:2:100`.
    #[arg(long, value_name = "KEY=SPEC")]
    pub vary: Vec<String>,
    /// Change a field of every scenario, KEY=VALUE (repeatable), as `run --set`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// The supports' motion for every scenario, a CSV file as `run --motion`; vary
    /// motion.time_shift over a wave period to find the worst phase at impact.
    #[arg(long, value_name = "FILE.csv")]
    pub motion: Option<PathBuf>,
    /// The rows, one per scenario in grid order, as CSV.
    #[arg(long, value_name = "FILE.csv")]
    pub out: PathBuf,
    /// Also write the rows as a JSON array of objects.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Scenarios run at once [default: every core].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    pub jobs: Option<u64>,
    /// Refuse runs that need more internal steps than this (a row with the error).
    #[arg(long, default_value_t = beam_impact::model::scenario::MAX_STEPS, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_steps: u64,
    /// Also write the response over the grid as one self-contained HTML page (docs/html-report.md).
    #[arg(long, value_name = "FILE.html")]
    pub html: Option<PathBuf>,
    /// Assess each row's fatigue on the scenario's [fatigue] curve (docs/fatigue-run.md): the
    /// columns fatigue.damage, fatigue.life, fatigue.beam, fatigue.position (about 1.6 times a row's work).
    #[arg(long)]
    pub fatigue: bool,
}

#[derive(Args)]
pub struct CampaignArgs {
    /// Scenario file (TOML) with a `[sea]` section (examples/vessel-sea.toml).
    pub file: PathBuf,
    /// Losses of the support per sea state (cell of the grid), 1 to 1 000 000.
    #[arg(long, default_value_t = 1000, value_parser = clap::value_parser!(u64).range(1..))]
    pub events: u64,
    /// Records (seeds sea.seed, sea.seed + 1, ...) the events are spread over [default: 20, or
    /// --events if fewer].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    pub seeds: Option<u64>,
    /// Length of each record, s (longer than the run's duration, at most 1e6): the instants are
    /// drawn over [0, T - duration].
    #[arg(long, value_name = "T", default_value_t = 10_800.0)]
    pub record_length: f64,
    /// A sea-state axis of the grid, KEY=SPEC as `sweep --vary` (sea.significant_wave_height,
    /// sea.peak_period, sea.heading; repeatable).
    #[arg(long, value_name = "KEY=SPEC")]
    pub vary: Vec<String>,
    /// Change a field of every event, KEY=VALUE (repeatable), as `run --set`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// The events, one row each in the plan's order, as CSV.
    #[arg(long, value_name = "FILE.csv")]
    pub out: PathBuf,
    /// Also write the statistics (per cell and quantity) and the operability limits as JSON.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Also draw the operability figure(s), SVG and PNG, into DIR.
    #[arg(long, value_name = "DIR")]
    pub figures: Option<PathBuf>,
    /// The overload probability per loss of the support a sea state must stay below, between 0
    /// and 1 (exclusive).
    #[arg(long, default_value_t = 0.01)]
    pub target: f64,
    /// Confidence of the intervals (two-sided), from 0.5 to below 1.
    #[arg(long, default_value_t = 0.95)]
    pub confidence: f64,
    /// Judge a cell on the overload probability's estimate rather than its upper bound.
    #[arg(long)]
    pub on_estimate: bool,
    /// Events the most probable maximum is of, 1 to 1e15 [default: 1 / target].
    #[arg(long, value_name = "N")]
    pub exposure: Option<f64>,
    /// Events run at once [default: every core].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    pub jobs: Option<u64>,
    /// Refuse a campaign of more runs (cells x events) than this.
    #[arg(long, default_value_t = beam_impact::studies::campaign::DEFAULT_MAX_EVENTS)]
    pub max_events: u64,
    /// Refuse runs that need more internal steps than this (a row with the error).
    #[arg(long, default_value_t = beam_impact::model::scenario::MAX_STEPS, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_steps: u64,
    /// Assess each event's fatigue on the scenario's [fatigue] curve: the damage per event, its
    /// mean per cell (docs/operability.md).
    #[arg(long)]
    pub fatigue: bool,
    /// The sea states' occurrence, CSV (significant_wave_height, peak_period, [heading,]
    /// probability or hours): with --fatigue, the damage per year weighted over the cells and the life.
    #[arg(long, value_name = "FILE.csv", requires = "fatigue")]
    pub occurrence: Option<PathBuf>,
}

#[derive(Args)]
pub struct FatigueArgs {
    /// The stress history: CSV with a `time` column (s, increasing) and stress columns (Pa).
    pub history: PathBuf,
    /// The S-N curve: `D`, `D-seawater-cp`, `D-free-corrosion`, `C-2024`, ... (an unknown name
    /// lists them all).
    #[arg(long, value_name = "NAME")]
    pub curve: String,
    /// Stress concentration factor on the nominal range, 1 to 20.
    #[arg(long, value_name = "X", default_value_t = 1.0)]
    pub scf: f64,
    /// The detail's thickness, m, for the thickness correction (t / t_ref)^k (none: no correction).
    #[arg(long, value_name = "T")]
    pub thickness: Option<f64>,
    /// Design fatigue factor multiplying the damage, 1 to 10.
    #[arg(long, value_name = "F", default_value_t = 1.0)]
    pub dff: f64,
    /// Write the cycles and damage per column as JSON to this file; `-`: to standard output,
    /// instead of the table.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
}
