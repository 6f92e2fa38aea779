//! The damping study of the paper's Appendix A: the same impact with damping ratios 0 to 0.04.
//! The paper finds the deflections barely change, while the bridge's stress is much higher at
//! gamma = 0 and 0.01 (undamped higher modes) and levels off from gamma = 0.02 on.

use std::fmt::Write;

use crate::error::Result;
use crate::record::NullRecorder;
use crate::results::Summary;
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
