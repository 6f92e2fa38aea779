//! The damping study of the paper's Appendix A: the same impact with damping ratios 0 to 0.04.
//! The paper finds the deflections barely change, while the bridge's stress is much higher at
//! gamma = 0 and 0.01 (undamped higher modes) and levels off from gamma = 0.02 on.

use std::fmt::Write;

use crate::error::Result;
use crate::record::{NullRecorder, Recorder, RunInfo};
use crate::results::{ContactEvent, StepResult, Summary};
use crate::{Scenario, Simulation};

/// The damping ratios of Appendix A.
pub const RATIOS: [f64; 6] = [0.0, 0.01, 0.015, 0.02, 0.03, 0.04];

/// Runs `scenario` once per damping ratio.
pub fn run(scenario: &Scenario, ratios: &[f64]) -> Result<Vec<(f64, Summary)>> {
    ratios
        .iter()
        .map(|&damping_ratio| {
            let s = Scenario { damping_ratio, ..scenario.clone() };
            Ok((damping_ratio, Simulation::new(&s)?.run(&mut NullRecorder)?))
        })
        .collect()
}

/// What the study's figures draw of one step (Figures A2-A13: deflections and bending stresses).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HistoryPoint {
    /// Time since impact, s.
    pub time: f64,
    /// Deflection of the arrestor's end, m.
    pub lower_tip_deflection: f64,
    /// Deflection of the bridge's contact node, m.
    pub upper_contact_deflection: f64,
    /// Bending stress at the arrestor's clamp, Pa.
    pub lower_clamp_bending_stress: f64,
    /// Bending stress at the bridge's contact node, Pa.
    pub upper_contact_bending_stress: f64,
}

/// A recorder that keeps the [`HistoryPoint`] of every step (40 bytes a step, not the whole
/// step result and modal coordinates), for the study's figures.
#[derive(Clone, Debug, Default)]
pub struct HistoryRecorder {
    /// Every step, in order.
    pub points: Vec<HistoryPoint>,
}

impl Recorder for HistoryRecorder {
    fn start(&mut self, _: &RunInfo<'_>) -> Result<()> {
        Ok(())
    }
    fn step(&mut self, r: &StepResult, _: &[f64]) -> Result<()> {
        self.points.push(HistoryPoint {
            time: r.time,
            lower_tip_deflection: r.lower_tip_deflection,
            upper_contact_deflection: r.upper_contact_deflection,
            lower_clamp_bending_stress: r.lower_clamp_bending_stress,
            upper_contact_bending_stress: r.upper_contact_bending_stress,
        });
        Ok(())
    }
    fn contact_event(&mut self, _: &ContactEvent) -> Result<()> {
        Ok(())
    }
    fn finish(&mut self) -> Result<()> {
        Ok(())
    }
    fn wants_details(&self) -> bool {
        false
    }
}

/// One run of the study with its time history.
#[derive(Clone, Debug)]
pub struct StudyRun {
    /// The scenario run (the study's scenario with this run's damping ratio).
    pub scenario: Scenario,
    /// Its summary.
    pub summary: Summary,
    /// Every step's deflections and stresses.
    pub history: Vec<HistoryPoint>,
}

/// Runs `scenario` once per damping ratio, keeping each run's time history (for the figures).
pub fn run_with_histories(scenario: &Scenario, ratios: &[f64]) -> Result<Vec<StudyRun>> {
    ratios
        .iter()
        .map(|&damping_ratio| {
            let s = Scenario { damping_ratio, ..scenario.clone() };
            let mut recorder = HistoryRecorder::default();
            let summary = Simulation::new(&s)?.run(&mut recorder)?;
            Ok(StudyRun { scenario: s, summary, history: recorder.points })
        })
        .collect()
}

/// The study as a table of peaks per damping ratio.
pub fn table(rows: &[(f64, Summary)]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "Appendix A. Damping study (peaks max |.| over the run)");
    let _ = writeln!(
        s,
        "{:>7} {:>12} {:>12} {:>12} {:>14} {:>12} {:>13}",
        "gamma", "w_a [m]", "sigma_a[MPa]", "tau_a [MPa]", "sigma_b [MPa]", "contact [s]", "residual [%]"
    );
    for (gamma, summary) in rows {
        let p = &summary.peaks;
        let contact: f64 = summary.contact_windows.iter().map(|w| w.end - w.start).sum();
        let _ = writeln!(
            s,
            "{gamma:7.3} {:12.4} {:12.1} {:12.2} {:14.1} {contact:12.3} {:13.3}{}",
            p.lower_tip_deflection,
            p.lower_clamp_bending_stress * 1e-6,
            p.lower_clamp_shear_stress * 1e-6,
            p.upper_contact_bending_stress * 1e-6,
            summary.quality.energy_residual_fraction * 100.0,
            if summary.quality.trusted { "" } else { "  NOT TRUSTED" }
        );
    }
    let _ = writeln!(
        s,
        "residual: the largest energy residual, % of the energy that flows; a run above its energy_tolerance is \
         NOT TRUSTED"
    );
    s
}
