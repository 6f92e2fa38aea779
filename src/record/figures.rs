//! Figures 6-9 of the paper from the step messages of a log, as SVG and PNG (plotters).
//!
//! Text is drawn with DejaVu Sans, compiled into the binary (`fonts/`, Bitstream Vera licence),
//! so the PNGs render the same on a machine without any system font. Each series is reduced to
//! the minimum and the maximum of every horizontal pixel column, which keeps every peak.

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use crate::error::{Error, Result};
use crate::results::{StepResult, Summary};

static FONT: &[u8] = include_bytes!("fonts/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

/// Width and height of every figure, px.
pub const SIZE: (u32, u32) = (1200, 620);

fn register_fonts() {
    REGISTER.call_once(|| {
        for family in ["sans-serif", "serif", "monospace"] {
            // The font is compiled in and known to parse: a failure here is a build defect.
            register_font(family, FontStyle::Normal, FONT).unwrap_or_else(|_| panic!("embedded font is invalid"));
        }
    });
}

/// One curve of a figure.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// Line colour.
    pub color: RGBColor,
    /// (time s, value) points.
    pub points: Vec<(f64, f64)>,
}

/// One figure: a caption, an axis label and its curves.
#[derive(Clone, Debug)]
pub struct Figure {
    /// File stem (`fig6-deflection`).
    pub stem: &'static str,
    /// Caption, after the paper's.
    pub caption: String,
    /// y axis label with unit.
    pub y_label: &'static str,
    /// Curves.
    pub series: Vec<Series>,
}

const ARRESTOR: RGBColor = RGBColor(217, 95, 2);
const BRIDGE: RGBColor = RGBColor(31, 90, 200);
const SHADE: RGBColor = RGBColor(232, 232, 232);

/// Keeps the minimum and maximum of each of `buckets` equal time slices, in time order.
pub fn min_max_decimate(points: &[(f64, f64)], buckets: usize) -> Vec<(f64, f64)> {
    if points.len() <= 2 * buckets || buckets == 0 {
        return points.to_vec();
    }
    let (t0, t1) = (points[0].0, points[points.len() - 1].0);
    let width = (t1 - t0) / buckets as f64;
    let mut out = Vec::with_capacity(2 * buckets + 2);
    let mut start = 0;
    while start < points.len() {
        let bucket = (((points[start].0 - t0) / width) as usize).min(buckets - 1);
        let mut end = start;
        let (mut lo, mut hi) = (start, start);
        while end < points.len() && (((points[end].0 - t0) / width) as usize).min(buckets - 1) == bucket {
            if points[end].1 < points[lo].1 {
                lo = end;
            }
            if points[end].1 > points[hi].1 {
                hi = end;
            }
            end += 1;
        }
        let (a, b) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        out.push(points[a]);
        if b != a {
            out.push(points[b]);
        }
        start = end;
    }
    out
}

/// The paper's node numbers of the probes, for any mesh: the arrestor's nodes first (the clamp is
/// node 1, its end node n_l + 1), then the bridge's from its hinge, so its contact node is
/// n_l + 2 + elements_to_contact (8 and 16 on the paper's 7 + 7/7 mesh).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NodeNumbers {
    /// The arrestor's clamp.
    pub clamp: u32,
    /// The arrestor's end.
    pub lower_tip: u32,
    /// The bridge's contact node.
    pub upper_contact: u32,
}

impl NodeNumbers {
    /// The node numbers of a scenario's mesh.
    pub fn of(scenario: &crate::model::Scenario) -> NodeNumbers {
        let lower = scenario.lower.elements;
        NodeNumbers { clamp: 1, lower_tip: lower + 1, upper_contact: lower + 2 + scenario.upper.elements_to_contact }
    }
}

/// The four figures of the paper from the steps of a run, labelled with the mesh's node numbers.
pub fn paper_figures(steps: &[StepResult], cut_short: bool, nodes: NodeNumbers) -> Vec<Figure> {
    let NodeNumbers { clamp, lower_tip, upper_contact } = nodes;
    let series = |name: &str, color: RGBColor, f: &dyn Fn(&StepResult) -> f64| Series {
        name: name.to_string(),
        color,
        points: min_max_decimate(&steps.iter().map(|r| (r.time, f(r))).collect::<Vec<_>>(), 1500),
    };
    let note = match (cut_short, steps.last()) {
        (true, Some(r)) => format!(" (log cut short at t = {:.3} s)", r.time),
        _ => String::new(),
    };
    vec![
        Figure {
            stem: "fig6-deflection",
            caption: format!(
                "Figure 6. Deflection of arrestor end (node {lower_tip}) and bridge at contact (node {upper_contact}){note}"
            ),
            y_label: "deflection, m (up positive)",
            series: vec![
                series(&format!("arrestor end, node {lower_tip}"), ARRESTOR, &|r| r.lower_tip_deflection),
                series(&format!("bridge contact, node {upper_contact}"), BRIDGE, &|r| r.upper_contact_deflection),
            ],
        },
        Figure {
            stem: "fig7-bending-stress",
            caption: format!(
                "Figure 7. Bending stress at arrestor clamp (node {clamp}) and bridge contact (node {upper_contact}){note}"
            ),
            y_label: "bending stress, MPa",
            series: vec![
                series(&format!("arrestor clamp, node {clamp}"), ARRESTOR, &|r| r.lower_clamp_bending_stress * 1e-6),
                series(&format!("bridge contact, node {upper_contact}"), BRIDGE, &|r| r.upper_contact_bending_stress * 1e-6),
            ],
        },
        Figure {
            stem: "fig8-shear-stress",
            caption: format!("Figure 8. Shear stress of arrestor at the clamp (node {clamp}){note}"),
            y_label: "shear stress, MPa",
            series: vec![series(&format!("arrestor clamp, node {clamp}"), ARRESTOR, &|r| r.lower_clamp_shear_stress * 1e-6)],
        },
        Figure {
            stem: "fig9-contact-stress",
            caption: format!("Figure 9. Contact element stress{note}"),
            y_label: "contact element stress, MPa",
            series: vec![series("contact bar", RGBColor(40, 140, 60), &|r| r.contact_stress * 1e-6)],
        },
    ]
}

/// Draws `figure` with curves `width` px wide. The bitmap backend draws spikes for wide, nearly
/// vertical segments (plotters 0.3.7), so the PNGs use 1 px lines.
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    figure: &Figure,
    windows: &[(f64, f64)],
    width: u32,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| Error::Other(format!("cannot draw {}: {e}", figure.stem));
    root.fill(&WHITE).map_err(err)?;
    let all = figure.series.iter().flat_map(|s| s.points.iter());
    let (mut t1, mut lo, mut hi) = (0.0f64, f64::INFINITY, f64::NEG_INFINITY);
    for &(t, v) in all {
        t1 = t1.max(t);
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        (lo, hi) = (-1.0, 1.0);
    }
    let pad = ((hi - lo) * 0.06).max(1e-9);
    let (lo, hi) = (lo - pad, hi + pad);
    let t1 = if t1 > 0.0 { t1 } else { 1.0 };
    let mut chart = ChartBuilder::on(root)
        .caption(&figure.caption, ("sans-serif", 22))
        .margin(14)
        .x_label_area_size(48)
        .y_label_area_size(80)
        .build_cartesian_2d(0.0..t1, lo..hi)
        .map_err(err)?;
    // Contact stages as shaded bands behind the curves.
    chart
        .draw_series(
            windows.iter().map(|&(a, b)| Rectangle::new([(a, lo), (b.max(a + t1 * 1e-4), hi)], SHADE.filled())),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("time since impact, s (shaded: in contact)")
        .y_desc(figure.y_label)
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 18))
        .light_line_style(RGBColor(245, 245, 245))
        .draw()
        .map_err(err)?;
    chart.draw_series(LineSeries::new([(0.0, 0.0), (t1, 0.0)], BLACK.mix(0.4))).map_err(err)?;
    for s in &figure.series {
        let color = s.color;
        chart
            .draw_series(LineSeries::new(s.points.iter().copied(), color.stroke_width(width)))
            .map_err(err)?
            .label(s.name.as_str())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 24, y)], color.stroke_width(3)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .label_font(("sans-serif", 16))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .draw()
        .map_err(err)?;
    root.present().map_err(err)?;
    Ok(())
}

/// Writes Figures 6-9 as `<stem>.svg` and `<stem>.png` into `dir`; returns the files written.
/// Contact is shaded by window with bounces closer than 10 ms merged (raw windows would shade as
/// slivers).
pub fn write_figures(
    steps: &[StepResult],
    summary: &Summary,
    nodes: NodeNumbers,
    dir: &Path,
    cut_short: bool,
) -> Result<Vec<PathBuf>> {
    register_fonts();
    let windows: Vec<(f64, f64)> = crate::compare::merged_windows(&summary.contact_windows, crate::results::BOUNCE_GAP)
        .iter()
        .map(|w| (w.start, w.end))
        .collect();
    let mut files = Vec::new();
    for figure in paper_figures(steps, cut_short, nodes) {
        let svg = dir.join(format!("{}.svg", figure.stem));
        draw(&SVGBackend::new(&svg, SIZE).into_drawing_area(), &figure, &windows, 2)?;
        files.push(svg);
        let png = dir.join(format!("{}.png", figure.stem));
        draw(&BitMapBackend::new(&png, SIZE).into_drawing_area(), &figure, &windows, 1)?;
        files.push(png);
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Captions and legends name the model's nodes (issue 11): the paper's 7 + 7/7 mesh gives
    /// nodes 1, 8 and 16; 14 arrestor and 10 + 20 bridge elements give 1, 15 and 26.
    #[test]
    fn figures_name_the_nodes_of_the_model() {
        let mut s = crate::model::Scenario::paper();
        assert_eq!(NodeNumbers::of(&s), NodeNumbers { clamp: 1, lower_tip: 8, upper_contact: 16 });
        (s.lower.elements, s.upper.elements_to_contact, s.upper.elements_beyond_contact) = (14, 10, 20);
        let nodes = NodeNumbers::of(&s);
        assert_eq!(nodes, NodeNumbers { clamp: 1, lower_tip: 15, upper_contact: 26 });
        let figures = paper_figures(&[StepResult::default()], false, nodes);
        assert!(figures[0].caption.contains("node 15") && figures[0].caption.contains("node 26"));
        assert_eq!(figures[0].series[1].name, "bridge contact, node 26");
        assert!(!figures.iter().any(|f| f.caption.contains("node 8") || f.caption.contains("node 16")));
    }

    /// The PNG path draws text with the compiled-in font, whatever fonts the machine has: the
    /// caption band of a rendered figure holds dark pixels (glyphs), and only there above the plot.
    #[test]
    fn bitmap_figures_render_text_without_system_fonts() {
        register_fonts();
        let (w, h) = SIZE;
        let mut pixels = vec![0u8; (w * h * 3) as usize];
        let figure = Figure {
            stem: "test",
            caption: "Figure 0. Caption text".into(),
            y_label: "value",
            series: vec![Series { name: "a".into(), color: ARRESTOR, points: vec![(0.0, 0.0), (1.0, 1.0)] }],
        };
        {
            let root = BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area();
            draw(&root, &figure, &[], 1).unwrap();
        }
        let dark_in_rows = |rows: std::ops::Range<u32>| {
            rows.flat_map(|y| (0..w).map(move |x| ((y * w + x) * 3) as usize))
                .filter(|&i| pixels[i] < 100 && pixels[i + 1] < 100 && pixels[i + 2] < 100)
                .count()
        };
        let caption = dark_in_rows(10..36);
        assert!(caption > 200, "only {caption} dark pixels where the caption should be");
    }

    #[test]
    fn decimation_keeps_extremes_in_time_order() {
        let points: Vec<(f64, f64)> = (0..10_000).map(|i| (i as f64, ((i * 7919) % 1000) as f64)).collect();
        let kept = min_max_decimate(&points, 100);
        assert!(kept.len() <= 200);
        assert!(kept.windows(2).all(|p| p[0].0 < p[1].0));
        let max = kept.iter().map(|p| p.1).fold(f64::MIN, f64::max);
        let min = kept.iter().map(|p| p.1).fold(f64::MAX, f64::min);
        assert_eq!((min, max), (0.0, 999.0));
    }
}
