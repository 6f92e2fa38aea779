//! The stress envelope along each beam (issue 30), as SVG and PNG: `envelope.svg` / `.png`.
//!
//! Two panels, the arrestor from its clamp and the bridge from its hinge; in each, the largest
//! |bending stress| and |shear stress| over the run at every station (MPa), the allowables of the
//! sections as dashed lines (a step where the section changes), and markers where the paper's
//! three points sit with their peaks: sigma_din,a and tau_din,a at the clamp (x = 0 of the
//! arrestor), sigma_din,b at the bridge's contact point. Where the envelope rises above a
//! marker, the beam's worst stress is not at the paper's point.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use super::figures::{draw_header, draw_panel, number, Drawing, LegendEntry, Output, Panel, Pen, Series};
use crate::error::Result;
use crate::model::Scenario;
use crate::results::{BeamEnvelope, Peaks, StationEnvelope, StressEnvelope};

/// File stem of the figure.
pub const STEM: &str = "envelope";

/// The bending envelope's colour.
const BENDING: RGBColor = RGBColor(31, 90, 200);
/// The shear envelope's colour.
const SHEAR: RGBColor = RGBColor(40, 140, 60);
/// The paper's bending points' marker colour.
const BENDING_POINT: RGBColor = RGBColor(215, 35, 35);
/// The paper's shear point's marker colour.
const SHEAR_POINT: RGBColor = RGBColor(150, 60, 175);

/// One panel: a beam's envelopes along it.
#[derive(Clone, Debug)]
struct BeamPanel {
    title: String,
    x_label: String,
    length: f64,
    series: Vec<Series>,
    verticals: Vec<f64>,
}

/// The envelope figure of a run.
#[derive(Clone, Debug)]
pub struct EnvelopeFigure {
    caption: String,
    subtitle: Vec<String>,
    panels: Vec<BeamPanel>,
}

/// (position, MPa) of each station of `e`, in order (two at one x make a step).
fn stress_points(e: &StationEnvelope) -> Vec<(f64, f64)> {
    e.positions.iter().zip(&e.max).map(|(&x, &v)| (x, v * 1e-6)).collect()
}

/// The allowables of `e` as a step line (stations without one left out), MPa.
fn allowable_points(e: &StationEnvelope) -> Vec<(f64, f64)> {
    e.positions.iter().zip(&e.allowable).filter(|(_, &a)| a > 0.0).map(|(&x, &a)| (x, a * 1e-6)).collect()
}

/// The worst of one envelope, in words: "512.3 MPa at x = 0 m, t = 0.123 s (utilisation 0.85)".
fn worst(e: &StationEnvelope) -> Option<String> {
    let p = e.peak()?;
    let utilisation = p.utilisation.map_or(String::new(), |u| {
        format!(", utilisation {u:.3} at x = {} m", number(p.utilisation_position.unwrap_or(0.0)))
    });
    Some(format!("{:.1} MPa at x = {} m, t = {:.4} s{utilisation}", p.value * 1e-6, number(p.position), p.time))
}

/// The series of one beam: its two envelopes, their allowables, and `markers` (name, colour,
/// (x, MPa)).
fn beam_series(beam: &BeamEnvelope, markers: Vec<(String, RGBColor, (f64, f64))>) -> Vec<Series> {
    let mut series = Vec::new();
    let curves = [
        (&beam.bending, "largest |bending stress| |M| / W", "allowable bending stress", BENDING),
        (&beam.shear, "largest |shear stress| |Q| / A_s", "allowable shear stress", SHEAR),
    ];
    for (e, name, _, color) in curves {
        if !e.max.is_empty() {
            series.push(Series::new(name, color, Pen::Wide, stress_points(e)));
        }
    }
    for (e, _, name, color) in curves {
        let allowable = allowable_points(e);
        if !allowable.is_empty() {
            series.push(Series::new(name, color, Pen::Dashed, allowable));
        }
    }
    for (name, color, point) in markers {
        series.push(Series { name, color, pen: Pen::Thin, points: Vec::new(), marks: vec![point] });
    }
    series
}

/// The figure of `envelope`, a run of `scenario` whose paper points peaked at `peaks`; `source`
/// says where the envelope comes from (the log's attachment, or rebuilt), `subtitle` the scenario.
pub fn envelope_figure(
    envelope: &StressEnvelope,
    peaks: &Peaks,
    scenario: &Scenario,
    subtitle: &str,
    source: &str,
) -> EnvelopeFigure {
    let mut lines = vec![subtitle.to_string(), format!("Envelope {source}.")];
    let beams = [("arrestor", &envelope.lower), ("bridge", &envelope.upper)];
    for (name, beam) in beams {
        let parts: Vec<String> = [("bending", &beam.bending), ("shear", &beam.shear)]
            .into_iter()
            .filter_map(|(stress, e)| worst(e).map(|w| format!("{stress} {w}")))
            .collect();
        if !parts.is_empty() {
            lines.push(format!("Worst on the {name}: {}.", parts.join("; ")));
        }
    }
    let mut panels = Vec::new();
    if !(envelope.lower.bending.max.is_empty() && envelope.lower.shear.max.is_empty()) {
        let markers = vec![
            (
                format!("paper's sigma_din,a at the clamp: {:.1} MPa", peaks.lower_clamp_bending_stress * 1e-6),
                BENDING_POINT,
                (0.0, peaks.lower_clamp_bending_stress * 1e-6),
            ),
            (
                format!("paper's tau_din,a at the clamp: {:.1} MPa", peaks.lower_clamp_shear_stress * 1e-6),
                SHEAR_POINT,
                (0.0, peaks.lower_clamp_shear_stress * 1e-6),
            ),
        ];
        panels.push(BeamPanel {
            title: "Arrestor".into(),
            x_label: "x from the clamp, m".into(),
            length: scenario.lower.length,
            series: beam_series(&envelope.lower, markers),
            verticals: Vec::new(),
        });
    }
    if !(envelope.upper.bending.max.is_empty() && envelope.upper.shear.max.is_empty()) {
        let markers = vec![(
            format!(
                "paper's sigma_din,b at the contact point ({} m): {:.1} MPa",
                number(scenario.contact_position),
                peaks.upper_contact_bending_stress * 1e-6
            ),
            BENDING_POINT,
            (scenario.contact_position, peaks.upper_contact_bending_stress * 1e-6),
        )];
        panels.push(BeamPanel {
            title: "Bridge".into(),
            x_label: format!(
                "x from the hinge, m; dashed vertical: the contact point at {} m",
                number(scenario.contact_position)
            ),
            length: scenario.upper.length,
            series: beam_series(&envelope.upper, markers),
            verticals: vec![scenario.contact_position],
        });
    }
    EnvelopeFigure {
        caption: "Stress envelope: the largest |stress| at every station along each beam over the run".into(),
        subtitle: lines,
        panels,
    }
}

impl Drawing for EnvelopeFigure {
    fn stem(&self) -> &str {
        STEM
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, output: Output) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        // One legend entry per name: both panels use the same curves' names and colours.
        let mut legend: Vec<LegendEntry> = Vec::new();
        let mut names: Vec<&str> = Vec::new();
        for s in self.panels.iter().flat_map(|p| &p.series) {
            if !names.contains(&s.name.as_str()) {
                names.push(&s.name);
                legend.push(LegendEntry::of(s));
            }
        }
        let body = draw_header(root, &self.caption, &self.subtitle, &legend, output, STEM)?;
        let areas = match self.panels.len() {
            0 => Vec::new(),
            1 => vec![body],
            n => body.split_evenly((n, 1)),
        };
        for (panel, area) in self.panels.iter().zip(&areas) {
            let spec = Panel {
                title: Some(panel.title.clone()),
                x: (0.0, if panel.length > 0.0 { panel.length } else { 1.0 }),
                x_label: panel.x_label.clone(),
                y_label: "stress, MPa".into(),
                y: Some((0.0, 0.0)),
                series: &panel.series,
                shaded: &[],
                verticals: panel.verticals.clone(),
            };
            draw_panel(area, &spec, output, STEM)?;
        }
        root.present().map_err(|e| crate::Error::Other(format!("cannot draw {STEM}: {e}")))?;
        Ok(())
    }
}

/// Writes the envelope figure as `envelope.svg` and `envelope.png` into `dir`; returns the files.
pub fn write_envelope_figure(figure: &EnvelopeFigure, dir: &Path) -> Result<Vec<PathBuf>> {
    super::figures::write_svg_png(figure, dir)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::replay::figures::{register_fonts, SIZE};

    /// Every curve of a stepped run's envelope is drawn: both beams, both stresses, their
    /// allowables and the three markers, in the figure's legend once each.
    #[test]
    fn the_figure_holds_both_beams_their_allowables_and_the_papers_points() {
        let e = |positions: Vec<f64>, max: Vec<f64>, allowable: f64| StationEnvelope {
            times: vec![0.01; positions.len()],
            allowable: vec![allowable; positions.len()],
            positions,
            max,
        };
        let envelope = StressEnvelope {
            lower: BeamEnvelope {
                bending: e(vec![0.0, 6.0, 6.0, 12.0], vec![4e8, 2e8, 3e8, 0.0], 5e8),
                shear: e(vec![0.0, 12.0], vec![6e7, 5e7], 2e8),
            },
            upper: BeamEnvelope {
                bending: e(vec![0.0, 13.0, 29.0], vec![1e8, 3e8, 0.0], 4e8),
                shear: Default::default(),
            },
            sampled_every: 1,
        };
        let peaks = Peaks {
            lower_clamp_bending_stress: 4e8,
            lower_clamp_shear_stress: 6e7,
            upper_contact_bending_stress: 3e8,
            ..Peaks::default()
        };
        let figure = envelope_figure(&envelope, &peaks, &Scenario::paper(), "subtitle", "from the log");
        assert_eq!(figure.panels.len(), 2);
        assert_eq!(figure.panels[0].series.len(), 2 + 2 + 2);
        assert_eq!(figure.panels[1].series.len(), 1 + 1 + 1);
        assert!(figure.subtitle.iter().any(|l| l.contains("Worst on the arrestor: bending 400.0 MPa at x = 0 m")));
        register_fonts();
        let (w, h) = SIZE;
        let mut pixels = vec![0u8; (w * h * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area();
            figure.draw(&root, Output::Png).unwrap();
        }
        let count = |c: RGBColor| pixels.chunks_exact(3).filter(|p| (p[0], p[1], p[2]) == (c.0, c.1, c.2)).count();
        for color in [BENDING, SHEAR, BENDING_POINT, SHEAR_POINT] {
            assert!(count(color) > 50, "{color:?}: {} pixels", count(color));
        }
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
            figure.draw(&root, Output::Svg).unwrap();
        }
        assert!(svg.contains("sigma_din,b at the contact point (13 m)"), "the legend names the paper's point");
    }
}
