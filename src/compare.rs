//! Text tables of a run beside the paper's values (what `run` and `report` print).

use std::fmt::Write;

use crate::paper;
use crate::results::{ContactWindow, Summary, BOUNCE_GAP, SUSTAINED_CONTACT};
use crate::wording::Wording;

/// Separations between contact windows longer than `min` s, as (start, end) in s.
pub fn separations(windows: &[ContactWindow], min: f64) -> Vec<(f64, f64)> {
    windows.windows(2).map(|w| (w[0].end, w[1].start)).filter(|(a, b)| b - a >= min).collect()
}

/// Contact windows with gaps shorter than `gap` s merged: the stages as a reader sees them,
/// without the chatter of millisecond bounces.
pub fn merged_windows(windows: &[ContactWindow], gap: f64) -> Vec<ContactWindow> {
    let mut out: Vec<ContactWindow> = Vec::new();
    for w in windows {
        match out.last_mut() {
            Some(last) if w.start - last.end < gap => last.end = w.end,
            _ => out.push(*w),
        }
    }
    out
}

/// The longest separation (start, end), s, if the beams ever separate and touch again.
pub fn longest_separation(windows: &[ContactWindow]) -> Option<(f64, f64)> {
    separations(windows, 0.0).into_iter().max_by(|a, b| (a.1 - a.0).total_cmp(&(b.1 - b.0)))
}

fn ratio(value: f64, reference: f64) -> String {
    if reference.is_finite() && reference != 0.0 {
        format!("{:6.3}", value / reference)
    } else {
        "     -".to_string()
    }
}

/// Ratio of `value` to a printed value that stands for `[printed - half, printed + half]`
/// (a value printed to 3 decimals has half = 0.0005): 1 inside that interval, else the ratio of
/// the distance beyond it, `1 +- outside / printed`. The paper's own 2 pi / 546.1 = 0.0115 s
/// prints as 0.012, so a plain ratio would show 0.96 for an exact match.
pub fn printed_ratio(value: f64, printed: f64, half: f64) -> String {
    if !(printed.is_finite() && printed != 0.0 && value.is_finite()) {
        return "     -".to_string();
    }
    let outside = ((value - printed).abs() - half).max(0.0);
    format!("{:6.3}", 1.0 + (value - printed).signum() * outside / printed)
}

/// Table 1 (FEM peaks and the energy approach), with the paper's values and ratios when `paper`.
pub fn table1(summary: &Summary, paper: bool) -> String {
    table1_worded(summary, paper, &Wording::default())
}

/// [`table1`] in the words of `w` (issue 45): the deflection at the contact point, a pin's
/// stresses, and for a rigid impactor no bridge (no sigma_din,b row, no Eq. 36 line).
pub fn table1_worded(summary: &Summary, paper: bool, w: &Wording) -> String {
    let mut s = String::new();
    let p = &summary.peaks;
    let e = &summary.energy_method;
    let deflection = if w.at_contact { CONTACT_DEFLECTION_ROW } else { END_DEFLECTION_ROW };
    let (bending, shear) = if w.first_support == "pin" {
        ("sigma_din,a pin bending stress   [MPa]  ", "tau_din,a pin shear stress       [MPa]  ")
    } else {
        ("sigma_din,a clamp bending stress [MPa]  ", "tau_din,a clamp shear stress     [MPa]  ")
    };
    let all_rows = [
        (deflection, p.lower_tip_deflection, e.tip_deflection, 1.0),
        (bending, p.lower_clamp_bending_stress, e.clamp_bending_stress, 1e-6),
        (shear, p.lower_clamp_shear_stress, e.clamp_shear_stress, 1e-6),
        ("sigma_din,b bridge bending, contact [MPa]", p.upper_contact_bending_stress, e.bridge_bending_stress, 1e-6),
    ];
    // A rigid impactor has no bending stress: its row is left out (never on the paper's scenario).
    let rows = &all_rows[..if w.rigid_impactor { 3 } else { 4 }];
    let _ = writeln!(s, "Table 1. Results comparison (peaks max |.| over the run)");
    if paper {
        let _ = writeln!(
            s,
            "{:42} {:>9} {:>9} {:>6}   {:>9} {:>9} {:>6}",
            "", "FEM", "paper", "ratio", "energy", "paper", "ratio"
        );
    } else {
        let _ = writeln!(s, "{:42} {:>9} {:>9}", "", "FEM", "energy");
    }
    for (k, (name, fem, energy, scale)) in rows.iter().enumerate() {
        let energy_text = if energy.is_finite() { format!("{:9.3}", energy * scale) } else { format!("{:>9}", "-") };
        if paper {
            let (pf, pe) = (paper::TABLE1_FEM[k], paper::TABLE1_ENERGY[k]);
            let _ = writeln!(
                s,
                "{name:42} {:9.3} {:9.3} {}   {energy_text} {:9.3} {}",
                fem * scale,
                pf * scale,
                ratio(*fem, pf),
                pe * scale,
                if energy.is_finite() { ratio(*energy, pe) } else { "     -".into() }
            );
        } else {
            let _ = writeln!(s, "{name:42} {:9.3} {energy_text}", fem * scale);
        }
    }
    let times = &summary.peak_times;
    let _ = write!(
        s,
        "peaks reached at t = {:.4} s (deflection), {:.4} s ({} bending), {:.4} s (shear)",
        times.lower_tip_deflection, times.lower_clamp_bending_stress, w.first_support, times.lower_clamp_shear_stress,
    );
    if w.rigid_impactor {
        let _ = writeln!(s);
    } else {
        let _ = writeln!(s, ", {:.4} s (bridge)", times.upper_contact_bending_stress);
    }
    let spring = if w.uniform_cantilever_tip { "3EI/l^3" } else { "1 / (static deflection per newton at the contact)" };
    let _ = writeln!(
        s,
        "energy approach: k_f = {spring} = {:.1} kN/m, F_din = {:.1} kN, E_def,a = {:.1} kJ{}",
        e.flexion_stiffness / 1e3,
        e.force / 1e3,
        e.strain_energy / 1e3,
        if paper { format!(" (paper {:.1} kJ)", paper::ARRESTOR_STRAIN_ENERGY / 1e3) } else { String::new() }
    );
    if w.rigid_impactor {
        return first_contact_line(s, summary, w);
    }
    let _ = writeln!(
        s,
        "energy approach, bridge rigid about its hinge (Eq. 36): alpha = {:.4} rad/s^2, M(d) = {:.1} kN m, \
         E_def,b = {:.2} kJ = {:.2} % of E_def,a{}",
        e.bridge_deceleration,
        e.bridge_contact_moment / 1e3,
        e.bridge_strain_energy / 1e3,
        100.0 * e.bridge_strain_ratio,
        if paper {
            format!(" (paper {:.1} kJ, {:.1} %)", paper::BRIDGE_STRAIN_ENERGY / 1e3, 100.0 * paper::BRIDGE_STRAIN_RATIO)
        } else {
            String::new()
        }
    );
    if summary.upper_strain_at_peak_deflection.is_finite() {
        let _ = writeln!(
            s,
            "FEM bridge strain energy at the largest arrestor deflection = {:.2} kJ",
            summary.upper_strain_at_peak_deflection / 1e3
        );
    } else {
        let _ = writeln!(
            s,
            "FEM bridge strain energy at the largest arrestor deflection: n/a (the log holds no modal coordinates \
             of that step: recorded without /beam/modes, by --log-channels or --no-modal-coordinates, or rolled back \
             past it)"
        );
    }
    first_contact_line(s, summary, w)
}

/// Table 1's closing line: the first sustained contact's peaks (or that the beams never touch).
fn first_contact_line(mut s: String, summary: &Summary, w: &Wording) -> String {
    let first = &summary.first_contact_peaks;
    if summary.contact_windows.is_empty() {
        let _ = writeln!(
            s,
            "no contact: the beams never touch in the run (t = 0 .. {:.4} s), so no impact peak was reached",
            summary.time
        );
        return s;
    }
    let bridge = if w.rigid_impactor {
        String::new()
    } else {
        format!(
            "sigma_din,b = {:.1} MPa (whole run {:.1} MPa), ",
            first.upper_contact_bending_stress * 1e-6,
            summary.peaks.upper_contact_bending_stress * 1e-6
        )
    };
    let _ = writeln!(
        s,
        "first sustained contact (t = 0 .. {}): {bridge}sigma_din,a = {:.1} MPa, tau_din,a = {:.1} MPa",
        summary.first_contact_end.map_or("end of run".to_string(), |t| format!("{t:.4} s")),
        first.lower_clamp_bending_stress * 1e-6,
        first.lower_clamp_shear_stress * 1e-6
    );
    s
}

/// Tables 2 and 3 (natural frequencies and periods), beside the paper's when `paper`.
pub fn tables23(summary: &Summary, paper: bool) -> String {
    tables23_worded(summary, paper, &Wording::default())
}

/// [`tables23`] with the striking body's column named by `w` (a rigid impactor's one mode is its
/// rigid motion, 0 rad/s).
pub fn tables23_worded(summary: &Summary, paper: bool, w: &Wording) -> String {
    let mut s = String::new();
    let m = &summary.modes;
    let columns = [("arrestor", &m.lower), (w.striker(), &m.upper), ("coupled", &m.coupled)];
    for (title, periods) in [("Table 2. Natural frequencies [rad/s]", false), ("Table 3. Natural periods [s]", true)] {
        // The ratios are only shown beside the paper's values.
        let note = if paper && periods { " (ratio to the interval the paper's 3 decimals stand for)" } else { "" };
        let _ = writeln!(s, "{title}{note}");
        let _ = write!(s, " n");
        for (name, _) in &columns {
            if paper {
                let _ = write!(s, " | {name:>8} {:>8} {:>6}", "paper", "ratio");
            } else {
                let _ = write!(s, " | {name:>8}");
            }
        }
        let _ = writeln!(s);
        for n in 0..5 {
            let _ = write!(s, "{:2}", n + 1);
            for (c, (_, values)) in columns.iter().enumerate() {
                let omega = values.get(n).copied().unwrap_or(f64::NAN);
                let value = if periods { period(omega) } else { omega };
                let (digits, ref_digits) = if periods { (4, 3) } else { (1, 1) };
                let text = if value.is_finite() { format!("{value:8.digits$}") } else { format!("{:>8}", "/") };
                if paper {
                    let reference = if periods { paper::TABLE3[c][n] } else { paper::TABLE2[c][n] };
                    let ref_text = if reference.is_finite() {
                        format!("{reference:8.ref_digits$}")
                    } else {
                        format!("{:>8}", "/")
                    };
                    let r = if periods { printed_ratio(value, reference, 0.0005) } else { ratio(value, reference) };
                    let _ = write!(s, " | {text} {ref_text} {r}");
                } else {
                    let _ = write!(s, " | {text}");
                }
            }
            let _ = writeln!(s);
        }
    }
    s
}

fn period(omega: f64) -> f64 {
    if omega > 0.0 {
        2.0 * std::f64::consts::PI / omega
    } else {
        f64::INFINITY
    }
}

/// Contact windows (bounces closer than 10 ms merged) and the longest separation.
pub fn contact_windows(summary: &Summary, paper: bool) -> String {
    let mut s = String::new();
    let merged = merged_windows(&summary.contact_windows, BOUNCE_GAP);
    if merged.is_empty() {
        let _ = writeln!(s, "Contact: none (the beams never touch in the run)");
        return s;
    }
    let _ = writeln!(
        s,
        "Contact: {} windows ({} after merging bounces closer than 10 ms):",
        summary.contact_windows.len(),
        merged.len()
    );
    for w in &merged {
        let _ = writeln!(s, "  {:7.4} s .. {:7.4} s", w.start, w.end);
    }
    if let Some((a, b)) = longest_separation(&summary.contact_windows) {
        let _ = write!(s, "longest separation: {a:.4} s .. {b:.4} s");
        if paper {
            let (pa, pb) = paper::SEPARATION;
            let _ = write!(s, " (paper, Figure 6: {pa:.2} s .. {pb:.2} s)");
        }
        let _ = writeln!(s);
        let sustained: Vec<ContactWindow> = merged_windows(&summary.contact_windows, BOUNCE_GAP)
            .into_iter()
            .filter(|w| w.end - w.start >= SUSTAINED_CONTACT)
            .collect();
        if let [first, second, ..] = sustained.as_slice() {
            let _ = write!(s, "sustained contact (>= 0.1 s) ends {:.4} s and resumes {:.4} s", first.end, second.start);
            if paper {
                let (pa, pb) = paper::SEPARATION;
                let _ = write!(
                    s,
                    " (paper: {pa:.2} s and {pb:.2} s, differences {:+.3} s and {:+.3} s)",
                    first.end - pa,
                    second.start - pb
                );
            }
            let _ = writeln!(s);
        }
        let long: Vec<String> =
            separations(&summary.contact_windows, 0.05).iter().map(|(a, b)| format!("{a:.3}..{b:.3} s")).collect();
        let long = if long.is_empty() { "none".to_string() } else { long.join(", ") };
        let _ = writeln!(s, "separations longer than 50 ms: {long}");
    }
    s
}

/// Table 1's first row label on the paper's clamped-free arrestor: w_din,a at its free end.
const END_DEFLECTION_ROW: &str = "w_din,a   arrestor end deflection  [m]  ";

/// The same row on two supports (issue 45, `lower.supports`): w_din,a is the deflection at the
/// contact point (the same width, so the columns stay aligned).
const CONTACT_DEFLECTION_ROW: &str = "w_din,a   arrestor at contact      [m]  ";

/// [`comparison`] for `scenario`, in its words ([`Wording::of`], issue 45): where w_din,a is
/// measured, the first support's kind, and no bridge for a rigid impactor; the paper's pair's
/// text is unchanged.
pub fn comparison_for(summary: &Summary, scenario: &crate::Scenario) -> String {
    comparison_worded(summary, scenario.is_paper(), &Wording::of(scenario))
}

/// Everything: Table 1, Tables 2-3, contact windows, steps and the energy balance.
pub fn comparison(summary: &Summary, paper: bool) -> String {
    comparison_worded(summary, paper, &Wording::default())
}

/// [`comparison`] in the words of `w`.
pub fn comparison_worded(summary: &Summary, paper: bool, w: &Wording) -> String {
    let mut s = String::new();
    s.push_str(&table1_worded(summary, paper, w));
    s.push('\n');
    s.push_str(&tables23_worded(summary, paper, w));
    s.push('\n');
    s.push_str(&contact_windows(summary, paper));
    let _ = write!(s, "steps: {} to t = {:.4} s", summary.steps, summary.time);
    if paper {
        let _ = write!(s, " (paper: about {} for 3 s)", paper::STEPS);
    }
    let _ = writeln!(
        s,
        "\nenergy balance residual: {:.1} J at the end, {:.1} J at most",
        summary.final_energy_residual, summary.max_energy_residual
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A value inside the interval its printed digits stand for is a ratio of 1; outside, the
    /// distance beyond the interval counts (Table 3: 0.0115 prints as 0.012).
    #[test]
    fn printed_ratio_measures_from_the_printed_interval() {
        assert_eq!(printed_ratio(0.011505, 0.012, 0.0005), " 1.000");
        assert_eq!(printed_ratio(0.07454, 0.074, 0.0005), " 1.001");
        assert_eq!(printed_ratio(0.0700, 0.074, 0.0005), " 0.953");
        assert_eq!(printed_ratio(f64::INFINITY, f64::NAN, 0.0005), "     -");
    }
}
