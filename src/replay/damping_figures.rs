//! The damping study's figures (`beam-impact damping --figures DIR`), after the paper's
//! Appendix A: for each damping ratio, the deflections of the arrestor's end and the bridge's
//! contact node (Figures A2-A7) and the bending stresses at the arrestor's clamp and the
//! bridge's contact node (Figures A8-A13); and the peaks against the damping ratio.
//!
//! They are of this finite-element model (the scenario's mesh), not of the paper's simplified
//! Figure A1 model, and their captions say so.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use super::figures::{
    create_dir, draw_header, draw_panel, scenario_subtitle, shaded_windows, write_figure, write_svg_png, Drawing,
    Figure, LegendEntry, NodeNumbers, Output, Panel, Pen, Series, ARRESTOR, BRIDGE,
};
use crate::error::Result;
use crate::studies::damping::{StudyRun, RATIOS};
use crate::Scenario;

/// Says whose model the figures show.
pub const MODEL_NOTE: &str = "Of this FE model (the scenario's mesh), not of the paper's simplified Figure A1 model.";

/// The paper's figure numbers for a damping ratio of its Appendix A: (deflection, stress),
/// A2-A7 and A8-A13; none for another ratio.
pub fn paper_numbers(damping_ratio: f64) -> Option<(usize, usize)> {
    RATIOS.iter().position(|&r| r == damping_ratio).map(|i| (2 + i, 2 + RATIOS.len() + i))
}

/// The time-history figures of one run of the study.
pub fn run_figures(run: &StudyRun) -> [Figure; 2] {
    let nodes = NodeNumbers::of(&run.scenario);
    let gamma = run.scenario.damping_ratio;
    let numbers = paper_numbers(gamma);
    let title = |n: Option<usize>, what: &str| match n {
        Some(n) => format!("Figure A{n}. {what}, γ = {gamma}"),
        None => format!("{what}, γ = {gamma}"),
    };
    let stem = |n: Option<usize>, what: &str| match n {
        Some(n) => format!("figA{n}-{what}-gamma-{gamma}"),
        None => format!("damping-{what}-gamma-{gamma}"),
    };
    let subtitle = vec![MODEL_NOTE.to_string(), scenario_subtitle(&run.scenario, Some(run.summary.time_steps))];
    let shaded = shaded_windows(&run.summary);
    let h = &run.history;
    let curve = |f: &dyn Fn(&crate::studies::damping::HistoryPoint) -> f64| h.iter().map(|p| (p.time, f(p))).collect();
    let deflection = Figure {
        stem: stem(numbers.map(|n| n.0), "deflection"),
        caption: title(
            numbers.map(|n| n.0),
            &format!(
                "Deflection of arrestor end (node {}) and bridge contact point (node {})",
                nodes.lower_tip, nodes.upper_contact
            ),
        ),
        subtitle: subtitle.clone(),
        y_label: "deflection, m (up positive)".into(),
        series: vec![
            Series::new(
                format!("arrestor end, node {}", nodes.lower_tip),
                ARRESTOR,
                Pen::Wide,
                curve(&|p| p.lower_tip_deflection),
            ),
            Series::new(
                format!("bridge contact point, node {}", nodes.upper_contact),
                BRIDGE,
                Pen::Thin,
                curve(&|p| p.upper_contact_deflection),
            ),
        ],
        shaded: shaded.clone(),
    };
    let stress = Figure {
        stem: stem(numbers.map(|n| n.1), "bending-stress"),
        caption: title(
            numbers.map(|n| n.1),
            &format!(
                "Bending stress at bridge contact (node {}) and arrestor clamp (node {})",
                nodes.upper_contact, nodes.clamp
            ),
        ),
        subtitle,
        y_label: "bending stress, MPa".into(),
        series: vec![
            Series::new(
                format!("arrestor clamp, node {}", nodes.clamp),
                ARRESTOR,
                Pen::Wide,
                curve(&|p| p.lower_clamp_bending_stress * 1e-6),
            ),
            Series::new(
                format!("bridge contact, node {}", nodes.upper_contact),
                BRIDGE,
                Pen::Thin,
                curve(&|p| p.upper_contact_bending_stress * 1e-6),
            ),
        ],
        shaded,
    };
    [deflection, stress]
}

/// The peaks of the study against the damping ratio: deflection left, stresses right.
#[derive(Clone, Debug)]
pub struct PeaksFigure {
    /// File stem.
    pub stem: String,
    /// Caption.
    pub caption: String,
    /// Lines under the caption.
    pub subtitle: Vec<String>,
    /// The arrestor's end deflection, m, per damping ratio.
    pub deflection: Vec<Series>,
    /// The stresses, MPa, per damping ratio.
    pub stresses: Vec<Series>,
}

/// The peaks-against-damping figure of a study.
pub fn peaks_figure(base: &Scenario, runs: &[StudyRun]) -> PeaksFigure {
    let nodes = NodeNumbers::of(base);
    let points = |f: &dyn Fn(&crate::results::Peaks) -> f64| -> Vec<(f64, f64)> {
        runs.iter().map(|r| (r.scenario.damping_ratio, f(&r.summary.peaks))).collect()
    };
    let marked = |name: String, color: RGBColor, points: Vec<(f64, f64)>| Series {
        name,
        color,
        pen: Pen::Thin,
        marks: points.clone(),
        points,
    };
    PeaksFigure {
        stem: "figA-peaks-vs-damping".into(),
        caption: "Damping study (Appendix A): peaks max |.| over the run against the damping ratio γ".into(),
        subtitle: vec![
            MODEL_NOTE.to_string(),
            format!(
                "{} (every run with the damping ratio of its point)",
                scenario_subtitle(base, runs.first().map(|r| r.summary.time_steps))
            ),
        ],
        deflection: vec![marked(
            format!("arrestor end deflection, node {}, m (left)", nodes.lower_tip),
            RGBColor(70, 70, 70),
            points(&|p| p.lower_tip_deflection),
        )],
        stresses: vec![
            marked(
                format!("arrestor clamp bending, node {}, MPa", nodes.clamp),
                ARRESTOR,
                points(&|p| p.lower_clamp_bending_stress * 1e-6),
            ),
            marked(
                format!("arrestor clamp shear, node {}, MPa", nodes.clamp),
                RGBColor(140, 60, 0),
                points(&|p| p.lower_clamp_shear_stress * 1e-6),
            ),
            marked(
                format!("bridge contact bending, node {}, MPa", nodes.upper_contact),
                BRIDGE,
                points(&|p| p.upper_contact_bending_stress * 1e-6),
            ),
        ],
    }
}

impl Drawing for PeaksFigure {
    fn stem(&self) -> &str {
        &self.stem
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, output: Output) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let legend: Vec<LegendEntry> = self.deflection.iter().chain(&self.stresses).map(LegendEntry::of).collect();
        let body = draw_header(root, &self.caption, &self.subtitle, &legend, output, &self.stem)?;
        let ratios = self.deflection.iter().chain(&self.stresses).flat_map(|s| s.points.iter().map(|p| p.0));
        let (lo, hi) = ratios.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), g| (a.min(g), b.max(g)));
        let (lo, hi) = if lo.is_finite() && hi > lo { (lo, hi) } else { (lo.min(0.0), lo.max(0.0) + 0.01) };
        let pad = (hi - lo) * 0.05;
        let (w, _) = body.dim_in_pixel();
        let (left, right) = body.split_horizontally(w * 45 / 100);
        let x_label = "damping ratio γ (modal, every mode)".to_string();
        let panel = |y_label: &str, series| Panel {
            title: None,
            x: (lo - pad, hi + pad),
            x_label: x_label.clone(),
            y_label: y_label.to_string(),
            // From 0, so that a change reads against the size of the peak.
            y: Some((0.0, 0.0)),
            series,
            shaded: &[],
            verticals: Vec::new(),
        };
        draw_panel(&left, &panel("peak deflection, m", &self.deflection), output, &self.stem)?;
        draw_panel(&right, &panel("peak stress, MPa", &self.stresses), output, &self.stem)?;
        root.present().map_err(|e| crate::Error::Other(format!("cannot draw {}: {e}", self.stem)))?;
        Ok(())
    }
}

/// Writes the study's figures into `dir` (created if missing): two time histories per run and
/// the peaks against the damping ratio, each as SVG and PNG; returns the files written.
pub fn write_damping_figures(base: &Scenario, runs: &[StudyRun], dir: &Path) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let mut files = Vec::new();
    // The paper's order: every deflection figure (A2-A7), then every stress figure (A8-A13).
    let figures: Vec<[Figure; 2]> = runs.iter().map(run_figures).collect();
    for which in 0..2 {
        for pair in &figures {
            files.extend(write_figure(&pair[which], dir)?);
        }
    }
    files.extend(write_svg_png(&peaks_figure(base, runs), dir)?);
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's numbering: gamma 0 is A2 and A8, 0.04 is A7 and A13; other ratios have none.
    #[test]
    fn appendix_a_figure_numbers() {
        assert_eq!(paper_numbers(0.0), Some((2, 8)));
        assert_eq!(paper_numbers(0.015), Some((4, 10)));
        assert_eq!(paper_numbers(0.04), Some((7, 13)));
        assert_eq!(paper_numbers(0.05), None);
    }
}
