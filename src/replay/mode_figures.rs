//! Figures 10-12 of the paper: the first natural modes of the arrestor alone (clamped-free with
//! its tip mass), of the bridge alone (hinged-free) and of the two coupled through an
//! always-active contact bar, with their frequencies in the legend.
//!
//! The modes are the solver's ([`crate::solver::ModalSystem`]: the frequencies of Table 2); the
//! shapes are drawn between the nodes with the elements' own cubic Hermite interpolation of the
//! nodal deflections and rotations, so the curve is the finite-element shape, and the nodes are
//! marked. Each mode is scaled to a largest deflection of 1 (over both beams when coupled).

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use super::figures::{
    create_dir, draw_header, draw_panel, mesh_subtitle, write_svg_png, Drawing, LegendEntry, NodeNumbers, Output,
    Panel, Pen, Series,
};
use crate::error::Result;
use crate::model::mesh::Mesh;
use crate::model::Model;
use crate::solver::ModalSystem;

/// Modes drawn per figure: the five of Tables 2 and 3.
pub const MODES_SHOWN: usize = 5;

/// Colours of modes 1, 2, ... (ColorBrewer Dark2).
const PALETTE: [RGBColor; 7] = [
    RGBColor(27, 158, 119),
    RGBColor(217, 95, 2),
    RGBColor(117, 112, 179),
    RGBColor(231, 41, 138),
    RGBColor(102, 166, 30),
    RGBColor(166, 118, 29),
    RGBColor(102, 102, 102),
];

/// Samples of the curve between the nodes of a beam, in all.
const SAMPLES: usize = 600;

/// A mode's legend text: its number and frequency (what the tests read back).
pub fn mode_label(number: usize, omega: f64, rigid_note: &str) -> String {
    if omega > 0.0 {
        format!("mode {number}: {omega:.2} rad/s, T = {:.4} s", 2.0 * std::f64::consts::PI / omega)
    } else {
        format!("mode {number}: 0 rad/s ({rigid_note})")
    }
}

/// A mode shape along one beam: (x m, deflection) points.
#[derive(Clone, Debug)]
struct Shape {
    /// The curve between the nodes.
    curve: Vec<(f64, f64)>,
    /// The nodes.
    nodes: Vec<(f64, f64)>,
}

/// The deflection along a beam of one shape, given its value on each of the beam's free DOFs
/// (`dof`): the cubic Hermite interpolation of each element, and the nodal deflections.
fn beam_shape(mesh: &Mesh, dof: &dyn Fn(usize) -> f64) -> Shape {
    let w = |n: usize| mesh.nodes[n].w.map_or(0.0, dof);
    let theta = |n: usize| mesh.nodes[n].theta.map_or(0.0, dof);
    let per_element = (SAMPLES / mesh.elements().max(1)).max(4);
    let mut curve = vec![(mesh.nodes[0].x, w(0))];
    for e in 0..mesh.elements() {
        let h = mesh.element_length(e);
        let (w1, t1, w2, t2) = (w(e), theta(e), w(e + 1), theta(e + 1));
        for k in 1..=per_element {
            let xi = k as f64 / per_element as f64;
            let (xi2, xi3) = (xi * xi, xi * xi * xi);
            let value = (1.0 - 3.0 * xi2 + 2.0 * xi3) * w1
                + h * (xi - 2.0 * xi2 + xi3) * t1
                + (3.0 * xi2 - 2.0 * xi3) * w2
                + h * (xi3 - xi2) * t2;
            curve.push((mesh.nodes[e].x + xi * h, value));
        }
    }
    let nodes = (0..mesh.nodes.len()).map(|n| (mesh.nodes[n].x, w(n))).collect();
    Shape { curve, nodes }
}

/// Scales shapes (curves and node marks together) so that the largest |deflection| over all of
/// them is 1 and positive.
fn normalise(parts: &mut [Shape]) {
    let values = parts.iter().flat_map(|s| s.curve.iter()).map(|p| p.1);
    let extreme = values.fold(0.0f64, |m, v| if v.abs() > m.abs() { v } else { m });
    if extreme != 0.0 && extreme.is_finite() {
        for shape in parts.iter_mut() {
            for p in shape.curve.iter_mut().chain(shape.nodes.iter_mut()) {
                p.1 /= extreme;
            }
        }
    }
}

/// One beam's panel of a mode figure.
#[derive(Clone, Debug)]
struct BeamPanel {
    title: Option<String>,
    length: f64,
    x_label: String,
    series: Vec<Series>,
    verticals: Vec<f64>,
}

/// A mode-shape figure: caption, subtitle, a legend of the modes and one or two beam panels.
#[derive(Clone, Debug)]
pub struct ModeFigure {
    /// File stem (`fig10-arrestor-modes`).
    pub stem: String,
    /// Caption, after the paper's.
    pub caption: String,
    /// Lines under the caption.
    pub subtitle: Vec<String>,
    /// The legend's texts, one per mode, with the frequencies.
    pub labels: Vec<String>,
    panels: Vec<BeamPanel>,
}

impl Drawing for ModeFigure {
    fn stem(&self) -> &str {
        &self.stem
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, output: Output) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let legend: Vec<LegendEntry> = self
            .labels
            .iter()
            .enumerate()
            .map(|(k, l)| LegendEntry::Line(l.clone(), PALETTE[k % PALETTE.len()], Pen::Thin))
            .collect();
        let body = draw_header(root, &self.caption, &self.subtitle, &legend, output, &self.stem)?;
        let areas = body.split_evenly((self.panels.len(), 1));
        for (area, panel) in areas.iter().zip(&self.panels) {
            let spec = Panel {
                title: panel.title.clone(),
                x: (0.0, panel.length),
                x_label: panel.x_label.clone(),
                y_label: "deflection, largest = 1".into(),
                // The same scale in every panel: the shapes are scaled to a largest |w| of 1.
                y: Some((-1.0, 1.0)),
                series: &panel.series,
                shaded: &[],
                verticals: panel.verticals.clone(),
            };
            draw_panel(area, &spec, output, &self.stem)?;
        }
        root.present().map_err(|e| crate::Error::Other(format!("cannot draw {}: {e}", self.stem)))?;
        Ok(())
    }
}

/// Figures 10-12 of `model` with its modes `modal` (no time step is involved: a mesh too fine
/// for a scenario's fixed steps still has its modes drawn).
pub fn mode_figures(model: &Model, modal: &ModalSystem) -> Vec<ModeFigure> {
    let scenario = &model.scenario;
    let nodes = NodeNumbers::of(scenario);
    let subtitle = vec![
        mesh_subtitle(scenario),
        "Shapes between the nodes by the elements' cubic interpolation; nodes marked; each mode scaled to a largest \
         deflection of 1."
            .to_string(),
    ];
    let (lower, upper) = (&model.lower.mesh, &model.upper.mesh);
    let (nl, nu) = (modal.lower.omega.len(), modal.upper.omega.len());
    let arrestor_x = format!("x from the clamp (node {}) to the end (node {}), m", nodes.clamp, nodes.lower_tip);
    let bridge_x = format!(
        "x from the hinge (node {}) to the free end (node {}), m; dashed: contact node {} at {} m",
        nodes.hinge, nodes.upper_tip, nodes.upper_contact, scenario.contact_position
    );
    let series = |k: usize, label: &str, shape: Shape| Series {
        name: label.to_string(),
        color: PALETTE[k % PALETTE.len()],
        pen: Pen::Thin,
        points: shape.curve,
        marks: shape.nodes,
    };

    // Figure 10: the arrestor alone.
    let count = MODES_SHOWN.min(nl);
    let labels: Vec<String> = (0..count).map(|k| mode_label(k + 1, modal.lower.omega[k], "rigid")).collect();
    let arrestor: Vec<Series> = (0..count)
        .map(|k| {
            let mut parts = [beam_shape(lower, &|i| modal.lower.shapes[(i, k)])];
            normalise(&mut parts);
            let [part] = parts;
            series(k, &labels[k], part)
        })
        .collect();
    let fig10 = ModeFigure {
        stem: "fig10-arrestor-modes".into(),
        caption: format!(
            "Figure 10. Natural modes of arrestor (clamped-free, tip mass {} kg at node {})",
            scenario.lower.tip_mass, nodes.lower_tip
        ),
        subtitle: subtitle.clone(),
        labels,
        panels: vec![BeamPanel {
            title: None,
            length: scenario.lower.length,
            x_label: arrestor_x.clone(),
            series: arrestor,
            verticals: Vec::new(),
        }],
    };

    // Figure 11: the bridge alone, hinged-free: its first mode is the rigid rotation.
    let count = MODES_SHOWN.min(nu);
    let labels: Vec<String> =
        (0..count).map(|k| mode_label(k + 1, modal.upper.omega[k], "rigid rotation about the hinge")).collect();
    let bridge: Vec<Series> = (0..count)
        .map(|k| {
            let mut parts = [beam_shape(upper, &|i| modal.upper.shapes[(i, k)])];
            normalise(&mut parts);
            let [part] = parts;
            series(k, &labels[k], part)
        })
        .collect();
    let fig11 = ModeFigure {
        stem: "fig11-bridge-modes".into(),
        caption: "Figure 11. Natural modes of bridge (hinged-free)".into(),
        subtitle: subtitle.clone(),
        labels,
        panels: vec![BeamPanel {
            title: None,
            length: scenario.upper.length,
            x_label: bridge_x.clone(),
            series: bridge,
            verticals: vec![scenario.contact_position],
        }],
    };

    // Figure 12: coupled through the bar; global coordinates are the arrestor's DOFs, then the bridge's.
    let count = MODES_SHOWN.min(modal.coupled.omega.len());
    let labels: Vec<String> = (0..count).map(|k| mode_label(k + 1, modal.coupled.omega[k], "rigid motion")).collect();
    let (mut on_bridge, mut on_arrestor) = (Vec::new(), Vec::new());
    for (k, label) in labels.iter().enumerate() {
        let shapes = &modal.coupled.shapes;
        let mut parts = [beam_shape(upper, &|i| shapes[(nl + i, k)]), beam_shape(lower, &|i| shapes[(i, k)])];
        normalise(&mut parts);
        let [b, a] = parts;
        on_bridge.push(series(k, label, b));
        on_arrestor.push(series(k, label, a));
    }
    let fig12 = ModeFigure {
        stem: "fig12-coupled-modes".into(),
        caption: "Figure 12. Natural modes of bridge and arrestor, coupled motion (contact bar active)".into(),
        subtitle,
        labels,
        panels: vec![
            BeamPanel {
                title: Some(format!(
                    "bridge (the bar joins its node {} to the arrestor's node {})",
                    nodes.upper_contact, nodes.lower_tip
                )),
                length: scenario.upper.length,
                x_label: bridge_x,
                series: on_bridge,
                verticals: vec![scenario.contact_position],
            },
            BeamPanel {
                title: Some("arrestor (on the bridge's scale)".into()),
                length: scenario.lower.length,
                x_label: arrestor_x,
                series: on_arrestor,
                verticals: Vec::new(),
            },
        ],
    };
    vec![fig10, fig11, fig12]
}

/// Writes Figures 10-12 of `model` with its modes `modal` as SVG and PNG into `dir` (created if
/// missing); returns the files written.
pub fn write_mode_figures(model: &Model, modal: &ModalSystem, dir: &Path) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let mut files = Vec::new();
    for figure in mode_figures(model, modal) {
        files.extend(write_svg_png(&figure, dir)?);
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Scenario, Simulation};

    /// The interpolated curve passes through the nodal deflections, and the legend carries the
    /// solver's frequencies (Table 2's columns) in the mode order.
    #[test]
    fn mode_figures_follow_the_solver() {
        let simulation = Simulation::new(&Scenario::paper()).unwrap();
        let figures = mode_figures(simulation.model(), simulation.modal());
        let stems: Vec<&str> = figures.iter().map(|f| f.stem.as_str()).collect();
        assert_eq!(stems, ["fig10-arrestor-modes", "fig11-bridge-modes", "fig12-coupled-modes"]);
        let table = simulation.mode_table(MODES_SHOWN);
        for (figure, column) in figures.iter().zip([&table.lower, &table.upper, &table.coupled]) {
            assert_eq!(figure.labels.len(), MODES_SHOWN);
            for (k, omega) in column.iter().enumerate() {
                assert!(figure.labels[k].starts_with(&format!("mode {}: ", k + 1)), "{}", figure.labels[k]);
                if *omega > 0.0 {
                    assert!(figure.labels[k].contains(&format!("{omega:.2} rad/s")), "{}", figure.labels[k]);
                }
            }
            for panel in &figure.panels {
                for s in &panel.series {
                    for &(x, w) in &s.marks {
                        let on_curve = s.points.iter().find(|p| (p.0 - x).abs() < 1e-9).map(|p| p.1);
                        assert!(on_curve.is_some_and(|c| (c - w).abs() < 1e-12), "node at {x}: {w} vs {on_curve:?}");
                    }
                }
            }
        }
        assert!(figures[1].labels[0].contains("0 rad/s (rigid rotation about the hinge)"));
        // Normalised: the largest |w| of each shape is 1 (the clamp and hinge rows are 0).
        for s in &figures[0].panels[0].series {
            let max = s.points.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
            assert!((max - 1.0).abs() < 1e-12 && s.points[0].1 == 0.0, "{}: {max}", s.name);
        }
    }
}
