//! Benchmarks of the production stepper against the dense oracle, and of the per-step cost at
//! growing element counts (`beam-impact bench`). Speed is measured here, never in tests.

use std::fmt::Write;
use std::time::{Duration, Instant};

use crate::error::Result;
use crate::model::sea::SeaSettings;
use crate::model::TimeStep;
use crate::record::NullRecorder;
use crate::simulation::Simulation;
use crate::solver::Stepper;
use crate::studies::campaign::summary::counted;
use crate::Scenario;

/// The median of timing samples (zero for none; the mean of the middle two for an even count).
pub fn median(mut samples: Vec<Duration>) -> Duration {
    samples.sort();
    match samples.len() {
        0 => Duration::ZERO,
        n if n % 2 == 1 => samples[n / 2],
        n => (samples[n / 2 - 1] + samples[n / 2]) / 2,
    }
}

fn time_run<S: Stepper>(make: impl Fn() -> Result<Simulation<S>>, runs: usize) -> Result<(Duration, u64)> {
    let mut samples = Vec::with_capacity(runs);
    let mut steps = 0;
    for _ in 0..runs {
        let mut simulation = make()?;
        let start = Instant::now();
        let summary = simulation.run(&mut NullRecorder)?;
        samples.push(start.elapsed());
        steps = summary.steps;
    }
    Ok((median(samples), steps))
}

/// The paper scenario with the element counts multiplied by `factor` and automatic (energy-safe)
/// steps, which finer meshes, with their higher frequencies, need.
pub fn refined(factor: u32) -> Result<Scenario> {
    let mut s = Scenario::paper();
    s.lower.elements *= factor;
    s.upper.elements_to_contact *= factor;
    s.upper.elements_beyond_contact *= factor;
    s.step_free = TimeStep::Auto;
    s.step_contact = TimeStep::Auto;
    Ok(s)
}

/// Runs the benchmark and returns its report: production vs dense on the paper scenario
/// (median of `runs`), then the production stepper's cost per step at 1x, 4x and 16x elements.
pub fn stepper_benchmark(runs: usize) -> Result<String> {
    let mut out = String::new();
    let paper = Scenario::paper();
    let setup = Instant::now();
    Simulation::new(&paper)?;
    let setup = setup.elapsed();
    let (fast, steps) = time_run(|| Simulation::new(&paper), runs)?;
    let (dense, dense_steps) = time_run(|| Simulation::new_dense(&paper), runs.min(3))?;
    let _ = writeln!(out, "paper scenario, 3 s, median of {} (dense: {}):", runs_of(runs), runs.min(3));
    let _ = writeln!(out, "  model setup (assembly, modes, initial state): {:8.2} ms", setup.as_secs_f64() * 1e3);
    let per = |d: Duration, n: u64| d.as_secs_f64() * 1e9 / n as f64;
    let _ = writeln!(
        out,
        "  production (modal, O(n)) : {:8.2} ms  {steps} steps  {:7.0} ns/step",
        fast.as_secs_f64() * 1e3,
        per(fast, steps)
    );
    let _ = writeln!(
        out,
        "  dense oracle (Eqs. 7-11) : {:8.2} ms  {dense_steps} steps  {:7.0} ns/step",
        dense.as_secs_f64() * 1e3,
        per(dense, dense_steps)
    );
    let _ = writeln!(out, "  speed-up: {:.1}x", dense.as_secs_f64() / fast.as_secs_f64());
    let _ = writeln!(out, "per-step cost of the production stepper vs element count (fixed 20 000 steps):");
    let mut base = None;
    for factor in [1, 4, 16] {
        let s = refined(factor)?;
        let mut samples = Vec::new();
        let mut dofs = 0;
        for _ in 0..runs.max(1) {
            let mut sim = Simulation::new(&s)?;
            dofs = sim.model().dofs();
            let start = Instant::now();
            for _ in 0..20_000 {
                sim.step(u64::MAX, false)?;
            }
            samples.push(start.elapsed());
        }
        let ns = median(samples).as_secs_f64() * 1e9 / 20_000.0;
        let (b_ns, b_dofs) = *base.get_or_insert((ns, dofs));
        let _ = writeln!(
            out,
            "  {factor:2}x elements: {dofs:4} DOFs  {ns:8.0} ns/step  {:6.2} ns/step/DOF  cost x{:.2} for DOFs x{:.2}",
            ns / dofs as f64,
            ns / b_ns,
            dofs as f64 / b_dofs as f64
        );
    }
    out += &converged_benchmark(runs)?;
    out += &motion_benchmark(runs)?;
    out += &sea_benchmark(runs)?;
    out += &campaign_benchmark(runs)?;
    out += &stiff_contact_benchmark(runs)?;
    out += &contact_law_benchmark(runs)?;
    Ok(out)
}

/// The cost per step of the contact laws (issue 28), side by side in one process, on the paper
/// scenario (paper method, 3 s): the paper's linear bar (Sherman-Morrison, closed form), the same
/// bar posed as a power law of exponent 1 (the scalar equation solved each contact step: the
/// solver's cost alone, the same run), a Hertz law (n = 3/2) at the top of every law's rate
/// ([`crate::model::contact_range::MAX_CONTACT_RATE`] at the paper's impact) and the same with
/// Hunt-Crossley damping (each its own run: their steps differ). Medians of `runs`.
pub fn contact_law_benchmark(runs: usize) -> Result<String> {
    use crate::model::contact_law::LawKind;
    let mut out = String::new();
    let paper = Scenario::paper();
    let law = |exponent: f64, stiffness: f64, damping: f64| {
        let mut s = paper.clone();
        s.contact.law = LawKind::Power;
        s.contact.exponent = exponent;
        s.contact.given_stiffness = Some(stiffness);
        s.contact.damping = damping;
        s
    };
    let bar = paper.contact.stiffness();
    let as_power = law(1.0, bar, 0.0);
    // A Hertz law (n = 3/2) at the top of every law's rate (issue 40 item 3): the one carrying
    // the paper's 475 kN at the bar's 17 um (6.8e12 N/m^1.5) has a rate of 4e11 N/m, refused.
    let top = crate::model::contact_range::largest_power_stiffness(&law(1.5, bar, 0.0)).unwrap_or(bar);
    let hertz = law(1.5, top, 0.0);
    let damped = law(1.5, hertz.contact.given_stiffness.unwrap_or(bar), 0.2);
    let (linear, linear_steps) = time_run(|| Simulation::new(&paper), runs)?;
    let mut rows = vec![("linear bar (Sherman-Morrison)      ", linear, linear_steps)];
    for (what, s) in [
        ("power law n = 1 (the same run)     ", &as_power),
        ("Hertz n = 3/2 at the top rate      ", &hertz),
        ("Hertz top, Hunt-Crossley c 0.2     ", &damped),
    ] {
        let (d, n) = time_run(|| Simulation::new(s), runs)?;
        rows.push((what, d, n));
    }
    let per = |d: Duration, n: u64| d.as_secs_f64() * 1e9 / n as f64;
    let base = per(linear, linear_steps);
    let _ = writeln!(out, "contact laws (paper scenario, paper method, 3 s, median of {}):", runs_of(runs));
    for (what, d, n) in rows {
        let ns = per(d, n);
        let _ =
            writeln!(out, "  {what}: {:8.2} ms  {n} steps  {ns:6.0} ns/step  x{:.2}", d.as_secs_f64() * 1e3, ns / base);
    }
    out += &converged_contact_law_benchmark(runs)?;
    Ok(out)
}

/// The contact laws side by side in the converged method (issue 40), the default scenario for 3 s:
/// the paper's linear bar, a linear bar as soft as the elastomer buffer (its 475 kN at 20 mm),
/// `examples/hertz-buffer.toml` (n = 1.3, Hunt-Crossley c = 0.2), a Hertz law (n = 3/2) and a
/// linear law with damping c = 0.2 (both with the buffer's 475 kN at 20 mm): the printed rung's
/// time and steps (median of `runs`), and the whole answer's wall time (`answer::run`: the four
/// runs on the available cores), each against the paper's bar.
pub fn converged_contact_law_benchmark(runs: usize) -> Result<String> {
    use crate::model::contact_law::LawKind;
    let mut out = String::new();
    let base = Scenario::default();
    let buffer = Scenario::from_toml(include_str!("../../examples/hertz-buffer.toml"), "examples/hertz-buffer.toml")?;
    let law = |kind: LawKind, exponent: f64, stiffness: f64, damping: f64| {
        let mut s = base.clone();
        s.contact.law = kind;
        s.contact.exponent = exponent;
        s.contact.given_stiffness = Some(stiffness);
        s.contact.damping = damping;
        s
    };
    let cases = [
        ("paper's linear bar (2.8e10 N/m)       ", base.clone()),
        ("soft linear bar (buffer's 2.4e7 N/m)  ", law(LawKind::Linear, 1.0, 4.75e5 / 0.02, 0.0)),
        ("hertz-buffer example (n 1.3, c 0.2)   ", buffer),
        ("Hertz n = 3/2 (buffer's rate)         ", law(LawKind::Power, 1.5, 4.75e5 / 0.02f64.powf(1.5), 0.0)),
        ("linear law, c 0.2 (buffer's rate)     ", law(LawKind::Linear, 1.0, 4.75e5 / 0.02, 0.2)),
    ];
    let answer = |s: &Scenario| -> Result<Duration> {
        let mut samples = Vec::with_capacity(runs.max(1));
        for _ in 0..runs.max(1) {
            let start = Instant::now();
            crate::answer::run(s, &mut NullRecorder, Default::default())?;
            samples.push(start.elapsed());
        }
        Ok(median(samples))
    };
    let _ = writeln!(out, "contact laws, converged method (default scenario, 3 s, median of {}):", runs_of(runs));
    let mut reference = None;
    for (what, s) in cases {
        // One untimed run first (cold caches).
        Simulation::new(&s)?.run(&mut NullRecorder)?;
        let (printed, steps) = time_run(|| Simulation::new(&s), runs)?;
        let whole = answer(&s)?;
        let (p0, w0) = *reference.get_or_insert((printed, whole));
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        let _ = writeln!(
            out,
            "  {what}: printed rung {:8.2} ms  {steps:6} steps  x{:.2};  answer {:8.1} ms  x{:.2}",
            ms(printed),
            printed.as_secs_f64() / p0.as_secs_f64(),
            ms(whole),
            whole.as_secs_f64() / w0.as_secs_f64()
        );
    }
    Ok(out)
}

/// The cost per step with and without support motion (issue 17), side by side in one process, on
/// the paper scenario (paper method, 3 s): fixed supports; all three supports moving with
/// constant accelerations (one motion over the run: the stepper's extra work alone, an O(1) gap
/// offset and, in the measured steps, one more dot product); and a sine heave of the hinge given
/// every 1 ms (a vessel model's communication step: each row ends an internal step there and
/// recomputes the load, O(n)). Medians of `runs`.
pub fn motion_benchmark(runs: usize) -> Result<String> {
    use crate::model::motion_table::MotionTable;
    use crate::model::{SupportMotion, Track};
    let mut out = String::new();
    let paper = Scenario::paper();
    let moving = SupportMotion {
        hinge_heave: Track { displacement: 0.0, velocity: 0.2, acceleration: -1.0 },
        clamp_heave: Track { displacement: 0.0, velocity: -0.1, acceleration: 0.5 },
        clamp_rotation: Track { displacement: 0.0, velocity: 0.002, acceleration: -0.01 },
    };
    let omega = 2.0 * std::f64::consts::PI * 0.15;
    let mut text = String::from("time,upper.hinge_heave,upper.hinge_heave_velocity,upper.hinge_heave_acceleration\n");
    for n in 0..=3000 {
        let t = n as f64 * 1e-3;
        let (s, c) = (omega * t).sin_cos();
        let _ = writeln!(text, "{t},{},{},{}", 0.5 * s, 0.5 * omega * c, -0.5 * omega * omega * s);
    }
    let table = MotionTable::parse(&text).map_err(crate::Error::Other)?;
    let mut sampled = paper.clone();
    sampled.motion.file = "1 ms sine heave".into();
    sampled.motion.table = Some(std::sync::Arc::new(table));
    // The same trajectory (to 1e-13) with and without the motion machinery: gravity g + 2 m/s^2
    // against both supports accelerating upwards at 2 m/s^2.
    let heavier = Scenario { gravity: paper.gravity + 2.0, ..paper.clone() };
    let lift = Track { displacement: 0.0, velocity: 0.0, acceleration: 2.0 };
    let lifted = SupportMotion { hinge_heave: lift, clamp_heave: lift, ..SupportMotion::default() };
    let (fixed, fixed_steps) = time_run(|| Simulation::new(&heavier), runs)?;
    let (same, same_steps) = time_run(|| Simulation::starting_with(&paper, lifted), runs)?;
    let (constant, constant_steps) = time_run(|| Simulation::starting_with(&paper, moving), runs)?;
    let (rows, rows_steps) = time_run(|| Simulation::new(&sampled), runs)?;
    let per = |d: Duration, n: u64| d.as_secs_f64() * 1e9 / n as f64;
    let base = per(fixed, fixed_steps);
    let _ = writeln!(out, "support motion (paper scenario, 3 s, median of {}):", runs_of(runs));
    for (what, d, n) in [
        ("fixed supports, gravity g + 2 m/s^2   ", fixed, fixed_steps),
        ("both supports at +2 m/s^2 (same run)  ", same, same_steps),
        ("all three moving, constant accel.     ", constant, constant_steps),
        ("hinge heave given every 1 ms          ", rows, rows_steps),
    ] {
        let ns = per(d, n);
        let _ =
            writeln!(out, "  {what}: {:8.2} ms  {n} steps  {ns:6.0} ns/step  x{:.2}", d.as_secs_f64() * 1e3, ns / base);
    }
    Ok(out)
}

/// A ship-like RAO table for [`sea_benchmark`] (our CSV): in long waves heave 1 in phase with the
/// wave and pitch the wave's slope k = w^2 / g (deg/m) a quarter period behind in head seas, both
/// cut off in short waves by 1 / (1 + (w / 0.7)^4) (a hull averages waves shorter than itself);
/// 30 frequencies 0.1 to 3 rad/s, headings 0 to 180 every 45 deg. Any table costs the same: the
/// record sums one cosine per component and coordinate.
fn long_wave_raos() -> String {
    let mut text = String::from(
        "frequency,heading,surge,surge_phase,sway,sway_phase,heave,heave_phase,roll,roll_phase,pitch,pitch_phase,yaw,yaw_phase\n",
    );
    for heading in [0.0, 45.0, 90.0, 135.0, 180.0] {
        for k in 0..30 {
            let w = 0.1 + 0.1 * k as f64;
            let hull = 1.0 / (1.0 + (w / 0.7f64).powi(4));
            let slope = hull * (w * w / 9.81).to_degrees() * (heading * std::f64::consts::PI / 180.0).cos().abs();
            let _ = writeln!(text, "{w},{heading},0,0,0,0,{hull},0,0,0,{slope},-90,0,0");
        }
    }
    text
}

/// The cost of a sea state (issue 42) beside fixed supports, side by side in one process: the
/// default scenario (converged method, 3 s) with fixed supports, and on a vessel in a JONSWAP sea
/// (Hs 2.5 m, Tp 8 s, head seas, 1000 components, the hinge 10 m aft and the clamp 15 m forward,
/// the ship-like RAOs of `long_wave_raos`): the record's motion table built (1000 components
/// at the 601 samples of 3 s every 5 ms), then the run with it; medians of `runs`.
pub fn sea_benchmark(runs: usize) -> Result<String> {
    use crate::model::sea::RaoTable;
    let mut out = String::new();
    let fixed = Scenario::default();
    let text = "duration = 3.0\n[sea]\nsignificant_wave_height = 2.5\npeak_period = 8.0\nheading = 180.0\nseed = 1\n\
                raos = \"long-wave.csv\"\nhinge_point = [-10.0, 0.0, 8.0]\nclamp_point = [15.0, 0.0, 8.0]\n";
    let mut sea = Scenario::from_toml(text, "the bench's sea")?;
    let table = RaoTable::parse_csv(&long_wave_raos()).map_err(crate::Error::Other)?;
    if let Some(settings) = sea.sea.as_mut() {
        settings.check_against(&table)?;
        settings.rao_table = Some(std::sync::Arc::new(table));
    }
    let settings = sea.sea.clone().ok_or_else(|| crate::Error::Other("the bench's sea has no [sea]".into()))?;
    let mut builds = Vec::with_capacity(runs);
    for _ in 0..runs {
        let start = Instant::now();
        let record = settings.record()?;
        let rows = record.table(settings.time_shift, settings.time_shift + sea.duration, settings.sample_interval);
        builds.push(start.elapsed());
        rows.map_err(crate::Error::Other)?;
    }
    let build = median(builds);
    let (still, still_steps) = time_run(|| Simulation::new(&fixed), runs)?;
    let (moving, moving_steps) = time_run(|| Simulation::new(&sea), runs)?;
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let _ = writeln!(
        out,
        "sea state (default scenario, converged method's printed rung, 3 s, median of {}):",
        runs_of(runs)
    );
    let _ = writeln!(out, "  fixed supports                        : {:8.2} ms  {still_steps} steps  x1.00", ms(still));
    let _ = writeln!(
        out,
        "  Hs 2.5 m, Tp 8 s, 1000 components     : {:8.2} ms  {moving_steps} steps  x{:.2} (the record's table {:.2} ms more)",
        ms(moving),
        moving.as_secs_f64() / still.as_secs_f64().max(f64::MIN_POSITIVE),
        ms(build)
    );
    Ok(out)
}

/// A campaign's cost (issue 43): [`sea_benchmark`]'s vessel in its sea, converged answers with
/// their verdicts (as `beam-impact campaign`) on 4 records of an hour, on every core. A fresh
/// campaign pays once for what its events share (the records' realisations, the modes of each
/// rung: ~25 ms) and then its events: timing campaigns of [`CAMPAIGN_EVENTS`] and of twice as many
/// events separates the two, the per-event wall (T(2E) - T(E)) / E and the setup T(E) - E x that
/// (at least 0), so that the projection for 10 000 events counts the setup once, not 500 times
/// (the bar: 60 s on two cores); each part the median of `runs` pairs of campaigns.
pub fn campaign_benchmark(runs: usize) -> Result<String> {
    use crate::model::sea::RaoTable;
    use crate::studies::campaign::{Campaign, Options};
    let mut out = String::new();
    let text = "duration = 3.0\n[sea]\nsignificant_wave_height = 2.5\npeak_period = 8.0\nheading = 180.0\nseed = 1\n\
                raos = \"long-wave.csv\"\nhinge_point = [-10.0, 0.0, 8.0]\nclamp_point = [15.0, 0.0, 8.0]\n";
    let mut sea = Scenario::from_toml(text, "the bench's sea")?;
    let table = std::sync::Arc::new(RaoTable::parse_csv(&long_wave_raos()).map_err(crate::Error::Other)?);
    if let Some(settings) = sea.sea.as_mut() {
        settings.rao_table = Some(table);
    }
    let jobs = crate::studies::sweep::default_jobs();
    // A fresh campaign of `events` (a scenario of its own: no record, table or mode made by an
    // earlier one), its records and modes computed inside the timing.
    let time = |events: u64| -> Result<Duration> {
        let fresh = Scenario { sea: sea.sea.as_ref().map(SeaSettings::unshared), ..sea.clone() };
        let options = Options { events, seeds: 4, record_length: 3600.0, ..Options::default() };
        let campaign = Campaign::new(fresh, Vec::new(), options, events, crate::model::scenario::MAX_STEPS)?;
        let start = Instant::now();
        let tally = campaign.run(jobs, &std::sync::atomic::AtomicBool::new(false), &mut |_| {}, &mut |_| Ok(()))?;
        let wall = start.elapsed();
        if tally.failed > 0 {
            return Err(crate::Error::Other(format!(
                "the bench's campaign: {} of {events} events failed",
                tally.failed
            )));
        }
        Ok(wall)
    };
    const EVENTS: u64 = CAMPAIGN_EVENTS;
    // Each run times the two campaigns back to back (the machine's load alike for both) and
    // splits them; the parts are the medians of the runs' splits.
    let (mut onces, mut twices, mut setups, mut pers) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for _ in 0..runs.max(1) {
        let (once, twice) = (time(EVENTS)?, time(2 * EVENTS)?);
        let split = CampaignCost::of(once.as_secs_f64(), twice.as_secs_f64(), EVENTS);
        onces.push(once);
        twices.push(twice);
        setups.push(Duration::from_secs_f64(split.setup));
        pers.push(Duration::from_secs_f64(split.per_event));
    }
    let (once, twice) = (median(onces).as_secs_f64(), median(twices).as_secs_f64());
    let split = CampaignCost { setup: median(setups).as_secs_f64(), per_event: median(pers).as_secs_f64() };
    let _ = writeln!(out, "campaign (the sea state above, 3 s runs, converged answers, median of {}):", runs_of(runs));
    let projected = split.projected(10_000);
    let _ = writeln!(
        out,
        "  {EVENTS} events on {}: {:8.2} ms, {} events: {:8.2} ms; setup {:.1} ms once + {:.2} ms of wall per event; \
         10 000 events: {projected:.0} s projected on this machine (bar: {CAMPAIGN_BAR:.0} s on two cores: {}{})",
        counted(jobs as u64, "thread", "threads"),
        once * 1e3,
        2 * EVENTS,
        twice * 1e3,
        split.setup * 1e3,
        split.per_event * 1e3,
        bar_verdict(projected),
        if jobs == 2 {
            String::new()
        } else {
            format!(", measured on {} here", counted(jobs as u64, "thread", "threads"))
        }
    );
    Ok(out)
}

/// The bar for a campaign (issue 43): 10 000 events in this many seconds on two cores.
pub const CAMPAIGN_BAR: f64 = 60.0;

/// Whether a projected wall for 10 000 events meets [`CAMPAIGN_BAR`]: "met" at or under it,
/// "not met" above (or for a projection that is not a number).
pub fn bar_verdict(projected: f64) -> &'static str {
    if projected <= CAMPAIGN_BAR {
        "met"
    } else {
        "not met"
    }
}

/// "median of 1 run", "median of 3 runs": the runs a median is of.
fn runs_of(runs: usize) -> String {
    counted(runs as u64, "run", "runs")
}

/// Events of [`campaign_benchmark`]'s smaller campaign (the larger has twice as many).
pub const CAMPAIGN_EVENTS: u64 = 20;

/// A campaign's wall time split into its one-off setup and its cost per event, s, from the walls
/// of campaigns of E and 2E events (the same setup, E more events): per event (T(2E) - T(E)) / E,
/// the setup T(E) - E x per event = 2 T(E) - T(2E). Timing noise can make either difference
/// negative: each is held at 0 or more (a negative per-event cost: the larger campaign's wall over
/// its 2E events, the setup 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CampaignCost {
    /// The one-off setup (records, modes), s.
    pub setup: f64,
    /// Wall per event after the setup, s.
    pub per_event: f64,
}

impl CampaignCost {
    /// The split of `once` (E = `events` events) and `twice` (2E events), s.
    pub fn of(once: f64, twice: f64, events: u64) -> CampaignCost {
        let e = events.max(1) as f64;
        let per_event = (twice - once) / e;
        if per_event > 0.0 {
            CampaignCost { setup: (once - e * per_event).max(0.0), per_event }
        } else {
            CampaignCost { setup: 0.0, per_event: twice.max(0.0) / (2.0 * e) }
        }
    }

    /// The wall of a campaign of `events` events, s: the setup once plus each event.
    pub fn projected(&self, events: u64) -> f64 {
        self.setup + events as f64 * self.per_event
    }
}

/// A stiff contact's cost beside the default's (issue 40 item 3), side by side in one process:
/// the whole converged answer (`answer::run`: the printed rung, its checks and the twin, on the
/// available cores, as `beam-impact run`) of the default scenario dropped from 0.5 m with the
/// paper's bar (2.8e10 N/m) and with the linear law's stiffest contact
/// ([`crate::model::scenario::MAX_CONTACT_STIFFNESS`]), and a power law of exponent 1 at the top
/// of the rate every law is held to ([`crate::model::contact_range::MAX_CONTACT_RATE`]: the same
/// bar in its own unit, solved as a scalar equation each step); their wall times, contact windows
/// and ratios; medians of `runs`.
pub fn stiff_contact_benchmark(runs: usize) -> Result<String> {
    use crate::model::contact_law::LawKind;
    use crate::model::contact_range::MAX_CONTACT_RATE;
    use crate::model::scenario::MAX_CONTACT_STIFFNESS;
    let default = Scenario { drop_height: 0.5, ..Scenario::default() };
    let mut stiff = default.clone();
    stiff.contact.given_stiffness = Some(MAX_CONTACT_STIFFNESS);
    let mut power = default.clone();
    power.contact.law = LawKind::Power;
    power.contact.exponent = 1.0;
    power.contact.given_stiffness = Some(MAX_CONTACT_RATE);
    let time = |s: &Scenario| -> Result<(Duration, usize)> {
        let mut samples = Vec::with_capacity(runs.max(1));
        let mut windows = 0;
        for _ in 0..runs.max(1) {
            let start = Instant::now();
            let answer = crate::answer::run(s, &mut NullRecorder, Default::default())?;
            samples.push(start.elapsed());
            windows = answer.summary.contact_windows.len();
        }
        Ok((median(samples), windows))
    };
    let (base, base_windows) = time(&default)?;
    let (slow, stiff_windows) = time(&stiff)?;
    let (power_time, power_windows) = time(&power)?;
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "stiff contact (default scenario, drop 0.5 m, the whole converged answer, median of {}):",
        runs_of(runs)
    );
    let _ = writeln!(
        out,
        "  the paper's bar, 2.8e10 N/m      : {:8.1} ms  {base_windows} contact windows  x1.00",
        ms(base)
    );
    let _ = writeln!(
        out,
        "  the linear law's top, {MAX_CONTACT_STIFFNESS:.0e} N/m : {:8.1} ms  {stiff_windows} contact windows  x{:.2}",
        ms(slow),
        slow.as_secs_f64() / base.as_secs_f64().max(f64::MIN_POSITIVE)
    );
    let _ = writeln!(
        out,
        "  power law n = 1 at its top rate, {MAX_CONTACT_RATE:.0e} N/m^1: {:8.1} ms  {power_windows} contact windows  \
         x{:.2} (x{:.2} the linear law's top)",
        ms(power_time),
        power_time.as_secs_f64() / base.as_secs_f64().max(f64::MIN_POSITIVE),
        power_time.as_secs_f64() / slow.as_secs_f64().max(f64::MIN_POSITIVE)
    );
    Ok(out)
}

/// The cost of a converged answer against the paper method, side by side in one process: the
/// paper's 7 + 7/7 mesh with automatic steps (the reference cost), the converged method's printed
/// rung alone, its check runs alone (the two coarser rungs and the twin), and the whole answer
/// (`answer::run`: the four runs, on the available cores) and its CPU time; medians of `runs`.
pub fn converged_benchmark(runs: usize) -> Result<String> {
    let mut out = String::new();
    let paper_mesh = Scenario::paper_mesh();
    let converged = Scenario::default();
    let time = |f: &dyn Fn() -> Result<()>| -> Result<Duration> {
        let mut samples = Vec::with_capacity(runs);
        for _ in 0..runs.max(1) {
            let start = Instant::now();
            f()?;
            samples.push(start.elapsed());
        }
        Ok(median(samples))
    };
    let run = |s: &Scenario| -> Result<()> { Simulation::new(s)?.run(&mut NullRecorder).map(|_| ()) };
    // One untimed run of each first: the first run in a process pays for cold caches and page
    // faults (measured: the paper run's median 51-108 ms without it).
    run(&paper_mesh)?;
    crate::answer::run(&converged, &mut NullRecorder, Default::default())?;
    let paper = time(&|| run(&paper_mesh))?;
    let printed = time(&|| run(&converged))?;
    // The stress envelope's cost: the printed rung without it, side by side.
    let steps = Simulation::new(&converged)?.run(&mut NullRecorder)?.steps.max(1);
    let bare = time(&|| {
        let mut simulation = Simulation::new(&converged)?;
        simulation.without_envelope();
        simulation.run(&mut NullRecorder).map(|_| ())
    })?;
    // The fatigue's cost (issue 44): the printed rung keeping every bending station's turning
    // points, as `run` does.
    let with_fatigue = time(&|| {
        let mut simulation = Simulation::new(&converged)?;
        simulation.keep_turning_points();
        simulation.run(&mut NullRecorder).map(|_| ())
    })?;
    let mut checks = crate::answer::check_scenarios(&converged)?;
    checks.push(crate::answer::twin_scenario(&converged));
    let check_runs = time(&|| checks.iter().try_for_each(run))?;
    let cpu = cpu_time::ProcessTime::now();
    let whole = time(&|| crate::answer::run(&converged, &mut NullRecorder, Default::default()).map(|_| ()))?;
    let cpu = cpu.elapsed() / runs.max(1) as u32;
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let ratio = |d: Duration| d.as_secs_f64() / paper.as_secs_f64();
    let _ = writeln!(out, "converged answer vs the paper method (paper scenario, 3 s, median of {}):", runs_of(runs));
    let _ = writeln!(out, "  paper method, 7 + 7/7, auto steps   : {:8.1} ms  x1.00", ms(paper));
    let _ = writeln!(out, "  converged, printed rung alone       : {:8.1} ms  x{:.2}", ms(printed), ratio(printed));
    let _ = writeln!(
        out,
        "  the same without the stress envelope: {:8.1} ms  x{:.2}: the envelope {:.0} ns per step of {steps} ({:.2}x the rung)",
        ms(bare),
        ratio(bare),
        (printed.as_secs_f64() - bare.as_secs_f64()) / steps as f64 * 1e9,
        printed.as_secs_f64() / bare.as_secs_f64()
    );
    let _ = writeln!(
        out,
        "  the same keeping turning points     : {:8.1} ms  x{:.2}: the fatigue's histories {:.0} ns per step ({:.2}x the rung)",
        ms(with_fatigue),
        ratio(with_fatigue),
        (with_fatigue.as_secs_f64() - printed.as_secs_f64()) / steps as f64 * 1e9,
        with_fatigue.as_secs_f64() / printed.as_secs_f64()
    );
    let _ = writeln!(
        out,
        "  its checks alone (2 rungs + twin)   : {:8.1} ms  x{:.2} (one after another)",
        ms(check_runs),
        ratio(check_runs)
    );
    let _ = writeln!(
        out,
        "  the whole answer (answer::run)      : {:8.1} ms  x{:.2} wall, {:.1} ms CPU x{:.2}",
        ms(whole),
        ratio(whole),
        ms(cpu),
        ratio(cpu)
    );
    out += &sweep_projection()?;
    out += &fixture_verdicts()?;
    Ok(out)
}

/// The 1000-scenario grid of docs/cli.md's "Design sweeps" (drop 0.1:2:100 x damping
/// 0.005:0.05:10, 3 s each, converged answers with their checks) projected from a sample run as
/// `beam-impact sweep` runs it (every core, the rows sharing their modes): the ten damping ratios
/// at three drop heights (0.1, 1.05, 2 m), so that the sample's mix of lightly damped (slower) and
/// damped rows is the grid's.
pub fn sweep_projection() -> Result<String> {
    use crate::studies::sweep::{field, linspace, Axis, Sweep};
    let axes = vec![
        Axis { field: field("drop_height")?, values: vec![0.1, 1.05, 2.0] },
        Axis { field: field("damping_ratio")?, values: linspace(0.005, 0.05, 10) },
    ];
    let sweep = Sweep::new(Scenario::default(), axes, crate::model::scenario::MAX_STEPS)?;
    let jobs = std::thread::available_parallelism().map_or(1, |n| n.get());
    let (start, cpu) = (Instant::now(), cpu_time::ProcessTime::now());
    let mut failed = 0;
    sweep.run(jobs, &mut |_| {}, &mut |row| {
        failed += usize::from(row.outcome.is_err());
        Ok(())
    })?;
    let (wall, cpu) = (start.elapsed().as_secs_f64(), cpu.elapsed().as_secs_f64());
    let scale = 1000.0 / sweep.len() as f64;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "the 1000-scenario grid of docs/cli.md (drop 0.1:2:100 x damping 0.005:0.05:10, 3 s), projected from {} \
         rows (drop 0.1 / 1.05 / 2 m x every damping ratio) on {}:",
        sweep.len(),
        counted(jobs as u64, "thread", "threads")
    );
    let _ = writeln!(
        out,
        "  sample {:.2} s wall, {:.2} s CPU ({:.0} ms CPU a row{}): projected {:.0} s wall, {:.0} s CPU",
        wall,
        cpu,
        cpu / sweep.len() as f64 * 1e3,
        if failed > 0 { format!(", {} failed", counted(failed as u64, "row", "rows")) } else { String::new() },
        wall * scale,
        cpu * scale
    );
    Ok(out)
}

/// The verdicts on the reference fixture (`tests/fixtures/converged_references.json`: 19
/// scenarios with 56/112-element full-basis references, the rule of
/// `tests/converged_references.rs`): false greens (a peak further than `discretisation_tolerance`
/// from its reference in a trusted run) and false alarms (a run not trusted, by its figures, whose
/// every peak has a reference within its tolerance; a lightly damped run flagged only for its
/// late-impact peaks or by its twin is counted apart, those flags being wanted).
pub fn fixture_verdicts() -> Result<String> {
    use crate::answer::PEAK_NAMES;
    use serde_json::Value;
    let doc: Value = serde_json::from_str(include_str!("../../tests/fixtures/converged_references.json"))
        .map_err(|e| crate::Error::Other(format!("the reference fixture: {e}")))?;
    let rows = doc.as_object().map(|o| o.iter().collect::<Vec<_>>()).unwrap_or_default();
    let names = |row: &Value, key: &str, kind: &str| -> Vec<String> {
        row.get(key)
            .and_then(|a| a.get(kind))
            .and_then(Value::as_array)
            .map_or(Vec::new(), |a| a.iter().filter_map(|v| v.as_str().map(String::from)).collect())
    };
    let start = Instant::now();
    let (mut runs, mut trusted, mut false_greens, mut false_alarms, mut wanted) = (0, 0, 0, 0, 0);
    for (_, row) in rows {
        let settings = &row["scenario"];
        // A row of an example file (beams of sections): that file, embedded; any other file is
        // not this build's to judge.
        let mut s = match settings.get("file").and_then(Value::as_str) {
            None => Scenario::default(),
            Some(file) => {
                let text = match file {
                    "examples/tapered-arrestor.toml" => include_str!("../../examples/tapered-arrestor.toml"),
                    "examples/three-section-gangway.toml" => include_str!("../../examples/three-section-gangway.toml"),
                    _ => continue,
                };
                Scenario::from_toml(text, file)?
            }
        };
        crate::studies::sweep::apply_fixture_settings(&mut s, settings)?;
        if row.get("112").is_none() && s.damping_ratio < crate::model::discretisation::LIGHT_DAMPING {
            continue;
        }
        let a = crate::answer::run(&s, &mut NullRecorder, Default::default())?;
        runs += 1;
        trusted += usize::from(a.quality.trusted);
        let (mut known, mut within) = (true, true);
        for (kind, values) in [("peaks", a.converged_peaks), ("first_contact_peaks", a.converged_first_contact_peaks)] {
            let (agree, agree_224) = (names(row, "agree", kind), names(row, "agree_224", kind));
            for (k, name) in PEAK_NAMES.iter().enumerate() {
                let reference = match row.get("112") {
                    Some(fine) if agree.iter().any(|n| n == name) => fine[kind][name].as_f64(),
                    Some(_) if agree_224.iter().any(|n| n == name) => row["224"][kind][name].as_f64(),
                    Some(_) => None,
                    None => row["56"][kind][name].as_f64(),
                };
                let Some(reference) = reference else {
                    known = false;
                    continue;
                };
                let error = crate::answer::relative(values.as_array()[k], reference);
                if error > s.discretisation_tolerance {
                    within = false;
                    false_greens += usize::from(a.quality.trusted);
                }
            }
        }
        if !a.quality.trusted && known && within {
            let twin = a.quality.checks.sensitivity.is_some_and(|c| !c.pass);
            if !a.unvouched_late_peaks.is_empty() || twin {
                wanted += 1;
            } else {
                false_alarms += 1;
            }
        }
    }
    let mut out = String::new();
    let _ = writeln!(
        out,
        "verdicts on the reference fixture ({runs} scenarios, {:.1} s): {trusted} trusted; false greens {false_greens}, \
         false alarms {false_alarms} ({:.1} % of the runs); {wanted} not trusted for late-impact or twin flags alone \
         (lightly damped, wanted)",
        start.elapsed().as_secs_f64(),
        100.0 * false_alarms as f64 / runs.max(1) as f64
    );
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Campaigns costing s + n p (setup s = 25 ms, p = 12 ms an event): the split of 20 and 40
    /// events gives s and p back (to round-off: a few ulps of 0.5 s), and 10 000 events project to
    /// s + 10 000 p = 120.025 s, not 10 000 (s / 20 + p) = 132.5 s.
    #[test]
    fn the_split_of_two_campaigns_gives_the_setup_once_and_the_cost_per_event() {
        let (s, p) = (0.025, 0.012);
        let cost = CampaignCost::of(s + 20.0 * p, s + 40.0 * p, 20);
        assert!((cost.setup - s).abs() < 1e-12 && (cost.per_event - p).abs() < 1e-12, "{cost:?}");
        assert!((cost.projected(10_000) - (s + 10_000.0 * p)).abs() < 1e-9, "{cost:?}");
    }

    /// The campaign line's verdict beside the bar: met at or under 60 s, not met above
    /// (92 s, the tester's projection) or for no number.
    #[test]
    fn the_bar_is_met_at_or_under_sixty_seconds_only() {
        assert_eq!([bar_verdict(59.9), bar_verdict(60.0)], ["met", "met"]);
        assert_eq!([bar_verdict(60.1), bar_verdict(92.0), bar_verdict(f64::NAN)], ["not met"; 3]);
        assert_eq!(runs_of(1), "1 run");
    }

    /// Noise that makes the larger campaign no slower (or the setup negative) gives no negative
    /// part: the larger campaign's wall per event, no setup; or a setup of 0.
    #[test]
    fn noisy_timings_give_no_negative_part() {
        let cost = CampaignCost::of(0.5, 0.4, 20);
        assert_eq!(cost, CampaignCost { setup: 0.0, per_event: 0.4 / 40.0 });
        let cost = CampaignCost::of(0.2, 0.5, 20);
        assert_eq!(cost.setup, 0.0);
        assert!((cost.per_event - 0.015).abs() < 1e-15);
    }
}
