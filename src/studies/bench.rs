//! Benchmarks of the production stepper against the dense oracle, and of the per-step cost at
//! growing element counts (`beam-impact bench`). Speed is measured here, never in tests.

use std::fmt::Write;
use std::time::{Duration, Instant};

use crate::error::Result;
use crate::model::TimeStep;
use crate::record::NullRecorder;
use crate::simulation::Simulation;
use crate::solver::Stepper;
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
    let _ = writeln!(out, "paper scenario, 3 s, median of {runs} runs (dense: {}):", runs.min(3));
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
    let paper = time(&|| run(&paper_mesh))?;
    let printed = time(&|| run(&converged))?;
    let mut checks = crate::answer::check_scenarios(&converged)?;
    checks.push(crate::answer::twin_scenario(&converged));
    let check_runs = time(&|| checks.iter().try_for_each(run))?;
    let cpu = cpu_time::ProcessTime::now();
    let whole = time(&|| crate::answer::run(&converged, &mut NullRecorder, Default::default()).map(|_| ()))?;
    let cpu = cpu.elapsed() / runs.max(1) as u32;
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let ratio = |d: Duration| d.as_secs_f64() / paper.as_secs_f64();
    let _ = writeln!(out, "converged answer vs the paper method (paper scenario, 3 s, median of {runs} runs):");
    let _ = writeln!(out, "  paper method, 7 + 7/7, auto steps   : {:8.1} ms  x1.00", ms(paper));
    let _ = writeln!(out, "  converged, printed rung alone       : {:8.1} ms  x{:.2}", ms(printed), ratio(printed));
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
    Ok(out)
}
