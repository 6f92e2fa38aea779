//! `beam-impact run`: one scenario with its answer, tables and checks; the log with the answer
//! attached; `--json` for scripts.

use std::io::Write;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};

use beam_impact::model::TimeStep;
use beam_impact::record::mcap::{McapRecorder, RecorderOptions};
use beam_impact::record::output::{check_distinct, shown, OutputFile};
use beam_impact::record::{NullRecorder, Recorder, RunInfo};
use beam_impact::results::{ContactEvent, StepResult};
use beam_impact::{compare, Error, Result, Scenario};

use super::args::RunArgs;
use super::common::{emit, io, read_scenario};

/// Runs a scenario; returns whether its numbers are trusted.
pub fn run(args: &RunArgs) -> Result<bool> {
    let settings = beam_impact::studies::sweep::parse_settings(&args.set)?;
    // Only a bare `beam-impact` runs the paper's method; a file or `--set` starts from the defaults.
    let mut scenario = match &args.file {
        Some(path) => read_scenario(path)?,
        None if settings.is_empty() => Scenario::paper(),
        None => Scenario::default(),
    };
    if let Some(motion) = &args.motion {
        super::common::load_motion(&mut scenario, motion)?;
    }
    beam_impact::studies::sweep::apply_settings(&mut scenario, &settings)?;
    let mcap = args
        .mcap
        .clone()
        .unwrap_or_else(|| beam_impact::studies::sweep::default_log(args.file.as_deref(), &settings, &scenario));
    let paper = scenario.is_paper();
    let started = Instant::now();
    let planned_steps = beam_impact::one_run::check(&scenario, args.max_steps)?;
    if let Some(line) = beam_impact::one_run::large_run_note(planned_steps, scenario.duration) {
        super::common::note(&format!("beam-impact: note: {line}: progress follows"));
    }
    // No two of the files name one (device and inode, or folder and name for a new file), and
    // every output is open before the run, so that a bad path fails at once, not after it; the
    // JSON is written beside and renamed into place at the end, so a failed run leaves the user's
    // earlier file as it was.
    let mut files: Vec<(&str, &Path)> = Vec::new();
    if let Some(file) = args.file.as_deref() {
        files.push(("the scenario file", file));
    }
    if !scenario.motion.file.is_empty() {
        files.push(("the motion file", Path::new(&scenario.motion.file)));
    }
    if let Some(sea) = &scenario.sea {
        files.push(("the RAO file", Path::new(&sea.raos)));
    }
    if let Some(json) = args.json.as_deref() {
        files.push(("--json", json));
    }
    if let Some(html) = args.html.as_deref() {
        files.push(("--html", html));
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
    let html_file = match &args.html {
        Some(path) => Some((path, OutputFile::create(path, true, "cannot create HTML report")?)),
        None => None,
    };
    let mut recorder: Box<dyn Recorder + Send> = if args.no_mcap {
        Box::new(NullRecorder)
    } else {
        let sample_interval_ns = match (args.log_sample_interval, args.record_every) {
            (None, 1) => beam_impact::record::options::DEFAULT_SAMPLE_INTERVAL_NS,
            (None, _) => 0,
            (Some(seconds), every) => {
                let ns = beam_impact::record::options::sample_interval_ns("--log-sample-interval", seconds)
                    .map_err(beam_impact::Error::Other)?;
                if ns > 0 && every > 1 {
                    return Err(beam_impact::Error::Other(format!(
                        "--record-every {every} thins a log of every internal step: give --log-sample-interval 0 \
                         with it, or leave it out for the dense output every {seconds} s"
                    )));
                }
                ns
            }
        };
        let options = RecorderOptions {
            allow_devices: true,
            max_bytes: args.max_log_bytes,
            record_every: args.record_every,
            sample_interval_ns,
            channels: args.log_channels,
            modal_coordinates: !args.no_modal_coordinates,
            station_stresses: !args.no_station_stresses,
            compression: args.log_compression,
            ..RecorderOptions::default()
        };
        Box::new(McapRecorder::with_options(&mcap, options)?)
    };
    let mut progress = Progress::new(recorder.as_mut(), scenario.duration_ns());
    let options = beam_impact::answer::Options { max_steps: args.max_steps, ..Default::default() };
    let answer = beam_impact::one_run::run(&scenario, &mut progress, options, &AtomicBool::new(false))?;
    progress.bar.finish_and_clear();
    if let Some(reason) = progress.stopped_early() {
        super::common::warn(reason);
    }
    let wall = started.elapsed();
    let summary = &answer.summary;
    let resolved = &answer.resolved;

    let mut text = format!(
        "beam-impact: {} scenario, method {}, {}, {:.3} s simulated\n\n",
        if paper { "paper" } else { "user" },
        if resolved.method == beam_impact::model::Method::Paper { "paper" } else { "converged" },
        header_mesh(resolved),
        scenario.duration
    );
    let impact = summary.impact;
    if scenario.upper.kind == beam_impact::model::scenario::ImpactorKind::Mass {
        text += &mass_impact_line(&scenario, impact.closing_speed);
    } else {
        text += &format!(
            "impact: the bridge turns at {} rad/s about its hinge ({}), its contact point closing at {} m/s\n\n",
            speed(impact.angular_velocity),
            match scenario.impact_angular_velocity {
                Some(_) => "as stated: impact_angular_velocity".to_string(),
                None => format!(
                    "from drop_height = {} m: omega_0 = sqrt(3 g alpha_0 / l_u), alpha_0 = atan(2 h / l_u), Eqs. 20-22",
                    // Bounded: `{}` of a hostile 1e-300 is 302 characters (issue 40's re-test).
                    beam_impact::error::number(scenario.drop_height)
                ),
            },
            speed(impact.closing_speed)
        );
    }
    if let Some(table) = &scenario.motion.table {
        text += &format!(
            "supports moving: {} ({} rows of {}, each with its velocity and acceleration), from its time {} s; \
             deflections are relative to the supports, the energy approach's column assumes fixed ones\n\n",
            shown(Path::new(&scenario.motion.file)),
            table.times.len(),
            table
                .columns
                .iter()
                .filter(|c| !c.ends_with("_velocity") && !c.ends_with("_acceleration"))
                .copied()
                .collect::<Vec<_>>()
                .join(", "),
            scenario.motion.time_shift
        );
    }
    if let Some(sea) = &scenario.sea {
        let spectrum = sea.spectrum();
        text += &format!(
            "supports on a vessel in a sea state: Hs {} m, Tp {} s, {} (gamma {:.3}), heading {} deg, seed {}, {} \
             components; the vessel's RAOs from {}; the record from its time {} s, sampled every {} s{}{}; \
             deflections are relative to the supports, the energy approach's column assumes fixed ones\n\n",
            sea.significant_wave_height,
            sea.peak_period,
            sea.spectrum.name(),
            spectrum.gamma,
            sea.heading,
            sea.seed,
            sea.components,
            shown(Path::new(&sea.raos)),
            sea.time_shift,
            sea.sample_interval,
            sea.hinge_point.map_or(String::new(), |p| format!("; hinge at {p:?} m")),
            sea.clamp_point
                .map_or(String::new(), |p| format!("; clamp at {p:?} m, arrestor at {} deg", sea.arrestor_direction)),
        );
    }
    text += &compare::comparison_for(summary, &scenario);
    if paper {
        text += "(Table 1's FEM column is bound to the paper's 7 + 7/7 mesh; the converged answer follows.)\n";
    }
    text += "\n";
    text += &beam_impact::answer::table(&answer);
    // A rigid impactor's rebounds (issue 45); a bridge's windows are listed above.
    if scenario.upper.kind == beam_impact::model::scenario::ImpactorKind::Mass {
        text += &beam_impact::sub_impacts::lines(&summary.sub_impacts);
    }
    if let Ok(amplification) = beam_impact::amplification::amplification(&answer) {
        text += &amplification.lines();
    }
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
    text += &fatigue_lines(&answer)?;
    for line in quality.advisories.iter() {
        super::common::note(&format!("beam-impact: note: {}", super::common::bounded_line(line)));
    }
    for line in quality.reasons.iter() {
        super::common::warn(&format!("results not trusted: {line}"));
    }
    text += &format!("wall time: {:.1} ms (assembly, modes and stepping", wall.as_secs_f64() * 1e3);
    if !args.no_mcap {
        text += &format!(", recorded to {}", shown(&mcap));
    }
    text += ")\n";
    if let Some((path, target)) = html_file {
        let doc = beam_impact::run_document::document(&scenario, &answer, wall.as_secs_f64())?;
        let title = match &args.file {
            Some(file) => format!("run of {}", shown(file)),
            None => format!("run of the {} scenario", if paper { "paper" } else { "default" }),
        };
        let page = beam_impact::replay::html::run_page(&scenario, summary, &doc, &title, &mcap)?;
        beam_impact::replay::html::write_page(target, path, &page)?;
        text += &format!("HTML report written to {}\n", shown(path));
    }
    if let Some((path, file)) = json_file {
        let doc = beam_impact::run_document::document(&scenario, &answer, wall.as_secs_f64())?;
        let json = serde_json::to_string_pretty(&doc).map_err(|e| Error::Other(format!("JSON: {e}")))?;
        match file {
            Some(mut file) => {
                writeln!(file, "{json}").map_err(|source| io("cannot write JSON", path, source))?;
                file.commit()?;
                text += &format!("results written to {}\n", shown(path));
            }
            // `--json -`: the JSON is the standard output, without the tables.
            None => return emit(&format!("{json}\n")).map(|()| answer.quality.trusted),
        }
    }
    emit(&text)?;
    Ok(answer.quality.trusted)
}

/// A speed on the impact line, as it is: six decimals; a zero as "0.000000" (a negative zero,
/// the closing speed of a drop of 0, printed "-0.000000"), and a speed too small for six
/// decimals in scientific form (1e-9 rad/s printed "0.000000", a speed that is not 0).
fn speed(x: f64) -> String {
    if x == 0.0 {
        format!("{:.6}", 0.0)
    } else if x.abs() < 5e-7 {
        format!("{x:.3e}")
    } else {
        format!("{x:.6}")
    }
}

/// Shows a progress bar (on a terminal) while passing every step on to the real recorder; where
/// no terminal shows it (a pipe, a CI log), a run still going after [`QUIET_FOR`] says how far it
/// is, one line every [`PROGRESS_EVERY`].
pub struct Progress<'a> {
    inner: &'a mut (dyn Recorder + Send),
    bar: ProgressBar,
    started: Instant,
    /// When the last progress line was written (None: none yet).
    said: Option<Instant>,
    end_ns: u64,
}

/// How long a run goes without a word where no progress bar shows.
const QUIET_FOR: std::time::Duration = std::time::Duration::from_secs(2);

/// How often a long run's progress line is repeated.
const PROGRESS_EVERY: std::time::Duration = std::time::Duration::from_secs(10);

impl<'a> Progress<'a> {
    fn new(inner: &'a mut (dyn Recorder + Send), end_ns: u64) -> Self {
        let bar = ProgressBar::new(end_ns / 1_000_000);
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} ms simulated, {elapsed} ({eta} left)")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Progress { inner, bar, started: Instant::now(), said: None, end_ns }
    }

    /// The progress line of a long run where the bar does not show.
    fn say_progress(&mut self, result: &StepResult) {
        let now = Instant::now();
        let due = match self.said {
            None => now.duration_since(self.started) >= QUIET_FOR,
            Some(at) => now.duration_since(at) >= PROGRESS_EVERY,
        };
        if due {
            self.said = Some(now);
            super::common::note(&format!(
                "beam-impact: {:.4} of {:.4} s simulated ({} internal steps), {:.0} s elapsed",
                result.time,
                self.end_ns as f64 * 1e-9,
                result.step,
                now.duration_since(self.started).as_secs_f64()
            ));
        }
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
        if result.step.is_multiple_of(64) && self.bar.is_hidden() {
            self.say_progress(result);
        }
        self.inner.step(result, modal_coordinates)
    }
    fn sample_interval_ns(&self) -> u64 {
        self.inner.sample_interval_ns()
    }
    fn sample(&mut self, result: &StepResult, modal_coordinates: &[f64]) -> Result<()> {
        self.inner.sample(result, modal_coordinates)
    }
    fn deflection_peak_strain(&mut self, upper_strain: f64) -> Result<()> {
        self.inner.deflection_peak_strain(upper_strain)
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
    fn keeps(&self, result: &StepResult) -> bool {
        self.inner.keeps(result)
    }
    fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> Result<()> {
        self.inner.attach(name, media_type, data)
    }
    fn stopped_early(&self) -> Option<&str> {
        self.inner.stopped_early()
    }
}

/// The run's two fatigue lines (issue 44): the worst station's damage per impact and the life
/// ([`beam_impact::run_fatigue::RunFatigue::lines`]); none without the stations' histories.
fn fatigue_lines(answer: &beam_impact::answer::Answer) -> Result<String> {
    let Some(histories) = &answer.station_histories else { return Ok(String::new()) };
    let settings = beam_impact::model::fatigue_fields::of(&answer.resolved);
    let fatigue = beam_impact::run_fatigue::assess(histories, &settings)?;
    Ok(fatigue.lines().iter().map(|l| format!("{l}\n")).collect())
}

/// The impact line of a rigid impactor (issue 45): its mass, speed and where the speed comes from.
fn mass_impact_line(scenario: &beam_impact::Scenario, closing_speed: f64) -> String {
    format!(
        "impact: a rigid mass of {} kg strikes at {} m/s ({}), its contact point closing at {} m/s\n\n",
        scenario.upper.mass,
        speed(beam_impact::model::rigid_impactor::impact_speed(scenario)),
        if scenario.impact_speed != 0.0 {
            "as stated: impact_speed".to_string()
        } else {
            format!("from drop_height = {} m: v = sqrt(2 g h)", beam_impact::error::number(scenario.drop_height))
        },
        speed(closing_speed)
    )
}

/// The header's mesh: `56 + 56/1 elements (arrestor + bridge to/beyond the contact)`, or for a
/// rigid impactor (issue 45), which has no elements, the arrestor's alone.
fn header_mesh(resolved: &beam_impact::Scenario) -> String {
    if resolved.upper.kind == beam_impact::model::scenario::ImpactorKind::Mass {
        format!("{} elements (the arrestor; the impactor is rigid)", resolved.lower.elements)
    } else {
        format!(
            "{} + {}/{} elements (arrestor + bridge to/beyond the contact)",
            resolved.lower.elements, resolved.upper.elements_to_contact, resolved.upper.elements_beyond_contact
        )
    }
}
