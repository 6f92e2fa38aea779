//! Figures 6-9 of the paper from the step messages of a log, as SVG and PNG (plotters), and the
//! drawing shared with the mode-shape figures ([`super::mode_figures`]) and the damping study's
//! ([`super::damping_figures`]).
//!
//! Text is drawn with DejaVu Sans, compiled into the binary (`fonts/`, Bitstream Vera licence),
//! so the PNGs render the same on a machine without any system font. Each series is reduced to
//! the minimum and the maximum of every horizontal pixel column, which keeps every peak.
//!
//! Every figure has a header above its panels: the caption, the scenario as a subtitle, and the
//! legend, so that no legend covers the data. A time history has two panels: the whole run and
//! the first [`IMPACT_WINDOW`] s (the impact, unreadable at the scale of the whole run). Where
//! two curves coincide (the arrestor's end and the bridge's contact node move together in
//! contact) the first is drawn wide underneath and the second thin on top, so both stay visible.

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{register_font, FontStyle};

use crate::error::{Error, Result};
use crate::model::Scenario;
use crate::results::{StepResult, Summary, TimeSteps};

static FONT: &[u8] = include_bytes!("fonts/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

/// Width and height of every figure, px.
pub const SIZE: (u32, u32) = (1200, 900);

/// The time-history figures' second panel shows the first this many seconds after the impact.
pub const IMPACT_WINDOW: f64 = 0.1;

/// Horizontal resolution of the curves: min-max pairs per panel (about one per pixel column).
const BUCKETS: usize = 1200;

/// Tick labels asked of each axis (plotters places at most this many).
const X_LABELS: usize = 12;
const Y_LABELS: usize = 9;

pub(crate) fn register_fonts() {
    REGISTER.call_once(|| {
        for family in ["sans-serif", "serif", "monospace"] {
            // The font is compiled in and known to parse: a failure here is a build defect.
            register_font(family, FontStyle::Normal, FONT).unwrap_or_else(|_| panic!("embedded font is invalid"));
        }
    });
}

/// How a curve is stroked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pen {
    /// Wide, drawn first: a curve that another may cover (the arrestor in Figures 6-7).
    Wide,
    /// Thin, drawn on top.
    Thin,
    /// Thin and dashed, drawn on top: a limit (an allowable stress).
    Dashed,
}

impl Pen {
    /// Stroke width in an SVG, px.
    pub fn svg_width(self) -> u32 {
        match self {
            Pen::Wide => 6,
            Pen::Thin | Pen::Dashed => 2,
        }
    }

    /// Pixel offsets at which a PNG draws the curve with 1 px lines (see [`Output::Png`]): a
    /// disc 5 px across for the wide pen, 2 x 2 px for the thin one, which then shows as a line
    /// of its own on the wide one where the curves coincide.
    pub fn png_brush(self) -> &'static [(i32, i32)] {
        match self {
            Pen::Wide => &[
                (0, 0),
                (-1, 0),
                (1, 0),
                (0, -1),
                (0, 1),
                (-1, -1),
                (1, 1),
                (-1, 1),
                (1, -1),
                (-2, 0),
                (2, 0),
                (0, -2),
                (0, 2),
                (-2, -1),
                (-2, 1),
                (2, -1),
                (2, 1),
                (-1, -2),
                (1, -2),
                (-1, 2),
                (1, 2),
            ],
            Pen::Thin | Pen::Dashed => &[(0, 0), (1, 0), (0, 1), (1, 1)],
        }
    }

    /// Width of the legend's sample line, px.
    fn legend_width(self, output: Output) -> u32 {
        match output {
            Output::Svg => self.svg_width(),
            Output::Png => match self {
                Pen::Wide => 5,
                Pen::Thin | Pen::Dashed => 2,
            },
        }
    }
}

/// One curve of a figure.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// Line colour.
    pub color: RGBColor,
    /// Stroke.
    pub pen: Pen,
    /// (x, y) points (time s or position m, value), in x order.
    pub points: Vec<(f64, f64)>,
    /// Points marked with a dot (nodes of a mode shape, the runs of the damping study).
    pub marks: Vec<(f64, f64)>,
}

impl Series {
    /// A curve without marks.
    pub fn new(name: impl Into<String>, color: RGBColor, pen: Pen, points: Vec<(f64, f64)>) -> Series {
        Series { name: name.into(), color, pen, points, marks: Vec::new() }
    }
}

/// One time-history figure: a caption, a subtitle, an axis label, its curves and the contact
/// windows shaded behind them.
#[derive(Clone, Debug)]
pub struct Figure {
    /// File stem (`fig6-deflection`).
    pub stem: String,
    /// Caption, after the paper's.
    pub caption: String,
    /// Lines under the caption: the scenario, notes.
    pub subtitle: Vec<String>,
    /// y axis label with unit.
    pub y_label: String,
    /// Curves, drawn in order.
    pub series: Vec<Series>,
    /// Contact windows (start, end), s, shaded.
    pub shaded: Vec<(f64, f64)>,
}

/// The arrestor's colour in every figure.
pub const ARRESTOR: RGBColor = RGBColor(217, 95, 2);
/// The bridge's colour in every figure.
pub const BRIDGE: RGBColor = RGBColor(31, 90, 200);
/// The contact bar's colour.
pub const BAR: RGBColor = RGBColor(40, 140, 60);
const SHADE: RGBColor = RGBColor(228, 228, 228);

/// Radius of a marker (a series of marks alone), px.
const MARKER_RADIUS: i32 = 7;

/// Which file a figure is being drawn into: pens differ (see [`Pen`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    /// SVG: real stroke widths.
    Svg,
    /// PNG: the bitmap backend draws spikes at the corners of wide polylines (plotters 0.3.7),
    /// so lines are 1 px and a pen is a brush of 1 px lines ([`Pen::png_brush`]).
    Png,
}

/// Keeps the minimum and maximum of each of `buckets` equal time slices, in time order.
pub fn min_max_decimate(points: &[(f64, f64)], buckets: usize) -> Vec<(f64, f64)> {
    if points.len() <= 2 * buckets || buckets == 0 {
        return points.to_vec();
    }
    let (t0, t1) = (points[0].0, points[points.len() - 1].0);
    let width = (t1 - t0) / buckets as f64;
    if !(width > 0.0 && width.is_finite()) {
        return points.to_vec();
    }
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
        start = end.max(start + 1);
    }
    out
}

/// Largest magnitude of a time or a plotted value the figures accept: the axes pad the range
/// of the values by 6 %, which must stay finite (a range reaching 1e308 overflows to infinity
/// and the axis ticks never end).
pub const PLOTTABLE: f64 = 1e300;

/// A point the axes can take: both coordinates finite, values beyond [`PLOTTABLE`]
/// clamped to it (the axes pad the range by 6 %, which must stay finite). NaN and infinities
/// are skipped: a run's results are finite, so they only come from a damaged or forged log.
pub fn plottable(point: (f64, f64)) -> Option<(f64, f64)> {
    let limit = PLOTTABLE;
    let (x, y) = point;
    (x.is_finite() && y.is_finite()).then(|| (x.clamp(-limit, limit), y.clamp(-limit, limit)))
}

/// Decimal places of the tick labels plotters puts on `lo..hi` with at most `labels` labels: its
/// steps are 1, 2 or 5 times a power of ten, so the step's own decimals are enough.
pub fn tick_decimals(lo: f64, hi: f64, labels: usize) -> usize {
    if !(lo.is_finite() && hi.is_finite() && hi > lo) {
        return 0;
    }
    let keys = Ranged::key_points(&RangedCoordf64::from(lo..hi), labels);
    let step = keys.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
    if !(step.is_finite() && step > 0.0) {
        return 0;
    }
    (-step.log10() - 1e-6).ceil().clamp(0.0, 12.0) as usize
}

/// A tick label with `decimals` places and never a negative zero ("-0.0" is "0.0"); magnitudes
/// of 1e7 and more in scientific notation.
pub fn tick_label(value: f64, decimals: usize) -> String {
    let text = if value.abs() >= 1e7 { format!("{value:.2e}") } else { format!("{value:.decimals$}") };
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => text,
    }
}

/// Number text without trailing zeros, for subtitles (13 -> "13", 0.567 -> "0.567").
pub(crate) fn number(value: f64) -> String {
    format!("{value}")
}

/// The node numbers of the probes, for any mesh, in the paper's numbering: the arrestor's nodes
/// first (the clamp is node 1, its end node n_l + 1), then the bridge's from its hinge
/// (node n_l + 2), so its contact node is n_l + 2 + elements_to_contact (8 and 16 on the
/// paper's 7 + 7/7 mesh).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NodeNumbers {
    /// The arrestor's clamp.
    pub clamp: u32,
    /// The arrestor's end.
    pub lower_tip: u32,
    /// The bridge's hinge.
    pub hinge: u32,
    /// The bridge's contact node.
    pub upper_contact: u32,
    /// The bridge's free end.
    pub upper_tip: u32,
}

impl NodeNumbers {
    /// The node numbers of a scenario's mesh.
    pub fn of(scenario: &Scenario) -> NodeNumbers {
        let lower = scenario.lower.elements;
        let (inner, outer) = (scenario.upper.elements_to_contact, scenario.upper.elements_beyond_contact);
        NodeNumbers {
            clamp: 1,
            lower_tip: lower + 1,
            hinge: lower + 2,
            upper_contact: lower + 2 + inner,
            upper_tip: lower + 2 + inner + outer,
        }
    }
}

/// The scenario in one line, for subtitles: the paper's or a user's, the mesh with its node
/// numbers, the drop, the damping and the time steps (`steps`, the resolved ones, when known).
pub fn scenario_subtitle(scenario: &Scenario, steps: Option<TimeSteps>) -> String {
    let s = scenario;
    let steps = match steps {
        Some(t) => format!("time steps {:e} s free, {:e} s in contact", t.free, t.contact),
        None => format!("time steps {} free, {} in contact", s.step_free, s.step_contact),
    };
    format!(
        "{}; drop height {} m; damping ratio {}; {steps}",
        mesh_subtitle(s),
        number(s.drop_height),
        number(s.damping_ratio)
    )
}

/// What the natural modes depend on, in one line: the paper's scenario or a user's, the beams
/// and their meshes with the node numbers, the contact node.
pub fn mesh_subtitle(scenario: &Scenario) -> String {
    let s = scenario;
    let n = NodeNumbers::of(s);
    format!(
        "{} scenario: arrestor {} m, {} elements (nodes {}-{}), tip mass {} kg; bridge {} m, {} + {} elements \
         (nodes {}-{}), contact node {} at {} m",
        if s.is_paper() { "The paper's" } else { "User" },
        number(s.lower.length),
        s.lower.elements,
        n.clamp,
        n.lower_tip,
        number(s.lower.tip_mass),
        number(s.upper.length),
        s.upper.elements_to_contact,
        s.upper.elements_beyond_contact,
        n.hinge,
        n.upper_tip,
        n.upper_contact,
        number(s.contact_position),
    )
}

/// The four figures of the paper from the steps of a run, labelled with the mesh's node numbers;
/// `note` ends every caption (a log cut short). Subtitles and shading are left to the caller.
pub fn paper_figures(steps: &[StepResult], nodes: NodeNumbers, note: &str) -> Vec<Figure> {
    let NodeNumbers { clamp, lower_tip, upper_contact, .. } = nodes;
    let series = |name: String, color: RGBColor, pen: Pen, f: &dyn Fn(&StepResult) -> f64| {
        Series::new(name, color, pen, steps.iter().map(|r| (r.time, f(r))).collect())
    };
    let figure = |stem: &str, caption: String, y_label: &str, series: Vec<Series>| Figure {
        stem: stem.to_string(),
        caption: format!("{caption}{note}"),
        subtitle: Vec::new(),
        y_label: y_label.to_string(),
        series,
        shaded: Vec::new(),
    };
    vec![
        figure(
            "fig6-deflection",
            format!(
                "Figure 6. Deflection of arrestor end (node {lower_tip}) and bridge at contact (node {upper_contact})"
            ),
            "deflection, m (up positive)",
            vec![
                series(format!("arrestor end, node {lower_tip}"), ARRESTOR, Pen::Wide, &|r| r.lower_tip_deflection),
                series(format!("bridge at contact, node {upper_contact}"), BRIDGE, Pen::Thin, &|r| {
                    r.upper_contact_deflection
                }),
            ],
        ),
        figure(
            "fig7-bending-stress",
            format!(
                "Figure 7. Bending stress at arrestor clamp (node {clamp}) and bridge contact (node {upper_contact})"
            ),
            "bending stress, MPa",
            vec![
                series(format!("arrestor clamp, node {clamp}"), ARRESTOR, Pen::Wide, &|r| {
                    r.lower_clamp_bending_stress * 1e-6
                }),
                series(format!("bridge at contact, node {upper_contact}"), BRIDGE, Pen::Thin, &|r| {
                    r.upper_contact_bending_stress * 1e-6
                }),
            ],
        ),
        figure(
            "fig8-shear-stress",
            format!("Figure 8. Shear stress of arrestor at the clamp (node {clamp})"),
            "shear stress, MPa",
            vec![series(format!("arrestor clamp, node {clamp}"), ARRESTOR, Pen::Thin, &|r| {
                r.lower_clamp_shear_stress * 1e-6
            })],
        ),
        figure(
            "fig9-contact-stress",
            "Figure 9. Contact element stress".to_string(),
            "contact element stress, MPa",
            vec![series(
                format!("contact bar, arrestor node {lower_tip} to bridge node {upper_contact} (compression negative)"),
                BAR,
                Pen::Thin,
                &|r| r.contact_stress * 1e-6,
            )],
        ),
    ]
}

/// An entry of a figure's legend.
#[derive(Clone, Debug)]
pub enum LegendEntry {
    /// A curve: its name, colour and pen.
    Line(String, RGBColor, Pen),
    /// The shading of contact windows, with its text.
    Shade(String),
    /// A marker (a series of marks alone): its name and colour.
    Mark(String, RGBColor),
}

impl LegendEntry {
    /// The legend entry of a series.
    pub fn of(series: &Series) -> LegendEntry {
        if series.points.is_empty() && !series.marks.is_empty() {
            return LegendEntry::Mark(series.name.clone(), series.color);
        }
        LegendEntry::Line(series.name.clone(), series.color, series.pen)
    }
}

fn draw_error<E: std::error::Error + Send + Sync>(what: &str) -> impl Fn(DrawingAreaErrorKind<E>) -> Error + '_ {
    move |e| Error::Other(format!("cannot draw {what}: {e}"))
}

/// Splits `text` into lines that fit `width` px in `style`, at spaces.
fn wrap<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, text: &str, style: &TextStyle, width: u32) -> Vec<String> {
    let fits = |line: &str| area.estimate_text_size(line, style).map_or(true, |(w, _)| w <= width);
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let candidate = if line.is_empty() { word.to_string() } else { format!("{line} {word}") };
        if fits(&candidate) || line.is_empty() {
            line = candidate;
        } else {
            lines.push(std::mem::replace(&mut line, word.to_string()));
        }
    }
    lines.push(line);
    lines
}

/// Fills `root` white and draws the header: `caption`, the `subtitle` lines (wrapped to the
/// width) and the `legend` in rows; returns the area below it for the panels.
pub(crate) fn draw_header<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    caption: &str,
    subtitle: &[String],
    legend: &[LegendEntry],
    output: Output,
    what: &str,
) -> Result<DrawingArea<DB, Shift>>
where
    DB::ErrorType: 'static,
{
    let err = draw_error(what);
    root.fill(&WHITE).map_err(&err)?;
    let (width, _) = root.dim_in_pixel();
    let centered = |size: f64| TextStyle::from(("sans-serif", size).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
    let mut y = 10;
    root.draw(&Text::new(caption.to_string(), (width as i32 / 2, y), centered(22.0))).map_err(&err)?;
    y += 32;
    let small = centered(15.0);
    for line in subtitle.iter().flat_map(|s| wrap(root, s, &small, width - 40)) {
        root.draw(&Text::new(line, (width as i32 / 2, y), small.clone())).map_err(&err)?;
        y += 20;
    }
    // The legend: entries in rows, each row centred.
    let label = TextStyle::from(("sans-serif", 16.0).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    let sample = 34;
    let widths: Vec<i32> = legend
        .iter()
        .map(|e| {
            let text = match e {
                LegendEntry::Line(name, ..) | LegendEntry::Shade(name) | LegendEntry::Mark(name, _) => name,
            };
            let (w, _) = root.estimate_text_size(text, &label).unwrap_or((8 * text.len() as u32, 16));
            sample + 8 + w as i32 + 28
        })
        .collect();
    let mut rows: Vec<Vec<usize>> = Vec::new();
    let mut used = 0;
    for (i, &w) in widths.iter().enumerate() {
        match rows.last_mut() {
            Some(row) if used + w <= width as i32 - 40 => {
                row.push(i);
                used += w;
            }
            _ => {
                rows.push(vec![i]);
                used = w;
            }
        }
    }
    y += 6;
    for row in rows.iter().filter(|r| !r.is_empty()) {
        let total: i32 = row.iter().map(|&i| widths[i]).sum::<i32>() - 28;
        let mut x = (width as i32 - total) / 2;
        let mid = y + 10;
        for &i in row {
            match &legend[i] {
                LegendEntry::Line(name, color, pen) => {
                    let stroke = pen.legend_width(output);
                    let dashes: &[(i32, i32)] =
                        if *pen == Pen::Dashed { &[(0, 9), (13, 22), (26, sample)] } else { &[(0, sample)] };
                    for &(a, b) in dashes {
                        root.draw(&PathElement::new([(x + a, mid), (x + b, mid)], color.stroke_width(stroke)))
                            .map_err(&err)?;
                    }
                    root.draw(&Text::new(name.clone(), (x + sample + 8, mid), label.clone())).map_err(&err)?;
                }
                LegendEntry::Mark(name, color) => {
                    let centre = (x + sample / 2, mid);
                    root.draw(&Circle::new(centre, MARKER_RADIUS, color.filled())).map_err(&err)?;
                    root.draw(&Circle::new(centre, MARKER_RADIUS, BLACK.stroke_width(1))).map_err(&err)?;
                    root.draw(&Text::new(name.clone(), (x + sample + 8, mid), label.clone())).map_err(&err)?;
                }
                LegendEntry::Shade(name) => {
                    root.draw(&Rectangle::new([(x, mid - 8), (x + sample, mid + 8)], SHADE.filled())).map_err(&err)?;
                    root.draw(&Rectangle::new([(x, mid - 8), (x + sample, mid + 8)], BLACK.mix(0.3))).map_err(&err)?;
                    root.draw(&Text::new(name.clone(), (x + sample + 8, mid), label.clone())).map_err(&err)?;
                }
            }
            x += widths[i];
        }
        y += 26;
    }
    let (_, rest) = root.split_vertically(y + 6);
    Ok(rest)
}

/// One panel of a figure: the axes, the curves, shaded x intervals and dashed vertical lines.
#[derive(Clone, Debug)]
pub(crate) struct Panel<'a> {
    /// Small title above the panel, if any.
    pub title: Option<String>,
    /// x range shown.
    pub x: (f64, f64),
    /// x axis label.
    pub x_label: String,
    /// y axis label.
    pub y_label: String,
    /// y range shown (padded by 6 %); by default that of the curves.
    pub y: Option<(f64, f64)>,
    /// Curves, drawn in order (their points outside `x` are left out).
    pub series: &'a [Series],
    /// x intervals shaded behind the curves.
    pub shaded: &'a [(f64, f64)],
    /// x positions of dashed vertical lines.
    pub verticals: Vec<f64>,
}

/// Draws `panel` into `area`.
pub(crate) fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel<'_>,
    output: Output,
    what: &str,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let err = draw_error(what);
    let (x0, x1) = match (plottable((panel.x.0, 0.0)), plottable((panel.x.1, 0.0))) {
        (Some((a, _)), Some((b, _))) if b > a => (a, b),
        (Some((a, _)), _) => (a, a + 1.0),
        _ => (0.0, 1.0),
    };
    let inside = |p: &(f64, f64)| p.0 >= x0 && p.0 <= x1;
    let curves: Vec<Vec<(f64, f64)>> = panel
        .series
        .iter()
        .map(|s| {
            let points: Vec<(f64, f64)> = s.points.iter().filter_map(|&p| plottable(p)).filter(inside).collect();
            min_max_decimate(&points, BUCKETS)
        })
        .collect();
    let marks: Vec<Vec<(f64, f64)>> =
        panel.series.iter().map(|s| s.marks.iter().filter_map(|&p| plottable(p)).filter(inside).collect()).collect();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &(_, v) in curves.iter().chain(marks.iter()).flatten() {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if let Some((a, b)) = panel.y.and_then(|(a, b)| Some((plottable((0.0, a))?.1, plottable((0.0, b))?.1))) {
        (lo, hi) = (a.min(lo), b.max(hi));
    }
    if !(lo.is_finite() && hi.is_finite()) {
        (lo, hi) = (-1.0, 1.0);
    }
    let pad = ((hi - lo) * 0.06).max(lo.abs().max(hi.abs()) * 1e-3).max(1e-9);
    let (lo, hi) = (lo - pad, hi + pad);
    let mut builder = ChartBuilder::on(area);
    builder.margin_left(14).margin_right(34).margin_top(6).margin_bottom(6).x_label_area_size(52).y_label_area_size(90);
    if let Some(title) = &panel.title {
        builder.caption(title, ("sans-serif", 17));
    }
    let mut chart = builder.build_cartesian_2d(x0..x1, lo..hi).map_err(&err)?;
    let shade = panel.shaded.iter().filter_map(|&(a, b)| {
        let (a, b) = (plottable((a, 0.0))?.0.max(x0), plottable((b, 0.0))?.0.min(x1));
        // A window too short to see is widened to a hairline.
        (b >= a).then(|| Rectangle::new([(a, lo), (b.max(a + (x1 - x0) * 5e-4), hi)], SHADE.filled()))
    });
    chart.draw_series(shade).map_err(&err)?;
    let (xd, yd) = (tick_decimals(x0, x1, X_LABELS), tick_decimals(lo, hi, Y_LABELS));
    let x_format = |v: &f64| tick_label(*v, xd);
    let y_format = |v: &f64| tick_label(*v, yd);
    chart
        .configure_mesh()
        .x_labels(X_LABELS)
        .y_labels(Y_LABELS)
        .x_label_formatter(&x_format)
        .y_label_formatter(&y_format)
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 16))
        .bold_line_style(BLACK.mix(0.12))
        .light_line_style(TRANSPARENT)
        .draw()
        .map_err(&err)?;
    if lo < 0.0 && hi > 0.0 {
        chart.draw_series(LineSeries::new([(x0, 0.0), (x1, 0.0)], BLACK.mix(0.45))).map_err(&err)?;
    }
    for &x in panel.verticals.iter().filter(|&&x| x > x0 && x < x1) {
        chart
            .draw_series(DashedLineSeries::new([(x, lo), (x, hi)], 6, 5, BLACK.mix(0.55).stroke_width(1)))
            .map_err(&err)?;
    }
    // Pixel size in data units, for the PNG's wide brush.
    let (px, py) = chart.plotting_area().get_pixel_range();
    let dx = (x1 - x0) / f64::from((px.end - px.start).max(1));
    let dy = (hi - lo) / f64::from((py.end - py.start).max(1));
    // Wide pens first, so that thin ones are drawn over them.
    let order = (0..curves.len())
        .filter(|&i| panel.series[i].pen == Pen::Wide)
        .chain((0..curves.len()).filter(|&i| panel.series[i].pen != Pen::Wide));
    for i in order {
        let (s, points) = (&panel.series[i], &curves[i]);
        match output {
            Output::Svg if s.pen == Pen::Dashed => {
                let style = s.color.stroke_width(s.pen.svg_width());
                chart.draw_series(DashedLineSeries::new(points.iter().copied(), 10, 7, style)).map_err(&err)?;
            }
            Output::Svg => {
                let style = s.color.stroke_width(s.pen.svg_width());
                chart.draw_series(LineSeries::new(points.iter().copied(), style)).map_err(&err)?;
            }
            Output::Png => {
                for &(ox, oy) in s.pen.png_brush() {
                    let shifted = points.iter().map(|&(x, y)| (x + f64::from(ox) * dx, y + f64::from(oy) * dy));
                    let style = s.color.stroke_width(1);
                    if s.pen == Pen::Dashed {
                        chart.draw_series(DashedLineSeries::new(shifted, 10, 7, style)).map_err(&err)?;
                    } else {
                        chart.draw_series(LineSeries::new(shifted, style)).map_err(&err)?;
                    }
                }
            }
        }
        let color = s.color;
        if s.points.is_empty() {
            // Marks alone are markers: larger, ringed.
            chart.draw_series(marks[i].iter().map(|&p| Circle::new(p, MARKER_RADIUS, color.filled()))).map_err(&err)?;
            chart
                .draw_series(marks[i].iter().map(|&p| Circle::new(p, MARKER_RADIUS, BLACK.stroke_width(1))))
                .map_err(&err)?;
        } else {
            chart.draw_series(marks[i].iter().map(|&p| Circle::new(p, 3, color.filled()))).map_err(&err)?;
        }
    }
    Ok(())
}

/// Something drawn into an SVG and a PNG of the same name.
pub(crate) trait Drawing {
    /// File stem.
    fn stem(&self) -> &str;
    /// Draws into `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, output: Output) -> Result<()>
    where
        DB::ErrorType: 'static;
}

/// Writes `drawing` as `<stem>.svg` and `<stem>.png` into `dir`; returns the two files.
pub(crate) fn write_svg_png(drawing: &impl Drawing, dir: &Path) -> Result<Vec<PathBuf>> {
    register_fonts();
    // Through the output guard: no link or FIFO in the folder is written through.
    let svg = dir.join(format!("{}.svg", drawing.stem()));
    crate::record::output::write_by_path(&svg, "cannot write figure", |partial| {
        drawing.draw(&SVGBackend::new(partial, SIZE).into_drawing_area(), Output::Svg)
    })?;
    let png = dir.join(format!("{}.png", drawing.stem()));
    crate::record::output::write_by_path(&png, "cannot write figure", |partial| {
        drawing.draw(&BitMapBackend::new(partial, SIZE).into_drawing_area(), Output::Png)
    })?;
    Ok(vec![svg, png])
}

/// Creates `dir` (and its parents) if missing; a folder that is a symbolic link is refused.
pub(crate) fn create_dir(dir: &Path) -> Result<()> {
    crate::record::output::create_output_dir(dir, "cannot create figure directory")
}

impl Drawing for Figure {
    fn stem(&self) -> &str {
        &self.stem
    }

    /// The whole run above, the first [`IMPACT_WINDOW`] s below (when the run is longer than
    /// twice that); contact windows shaded in both.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, output: Output) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let mut legend: Vec<LegendEntry> = self.series.iter().map(LegendEntry::of).collect();
        legend.push(LegendEntry::Shade(format!(
            "in contact (bounces under {} ms apart merged)",
            crate::results::BOUNCE_GAP * 1e3
        )));
        let body = draw_header(root, &self.caption, &self.subtitle, &legend, output, &self.stem)?;
        let end = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().filter_map(|&p| plottable(p)))
            .map(|p| p.0)
            .fold(0.0f64, f64::max);
        let end = if end > 0.0 { end } else { 1.0 };
        let x_label = "time since impact, s".to_string();
        let whole = Panel {
            title: None,
            x: (0.0, end),
            x_label: x_label.clone(),
            y_label: self.y_label.clone(),
            y: None,
            series: &self.series,
            shaded: &self.shaded,
            verticals: Vec::new(),
        };
        if end <= 2.0 * IMPACT_WINDOW {
            draw_panel(&body, &whole, output, &self.stem)?;
        } else {
            let (_, h) = body.dim_in_pixel();
            let (top, bottom) = body.split_vertically(h * 56 / 100);
            draw_panel(&top, &whole, output, &self.stem)?;
            let impact = Panel {
                title: Some(format!("The impact: the first {IMPACT_WINDOW} s")),
                x: (0.0, IMPACT_WINDOW),
                ..whole
            };
            draw_panel(&bottom, &impact, output, &self.stem)?;
        }
        root.present().map_err(draw_error(&self.stem))?;
        Ok(())
    }
}

/// A time-history figure as SVG text (the packed FMU's documentation carries it as a file).
pub fn figure_svg(figure: &Figure) -> Result<String> {
    register_fonts();
    let mut svg = String::new();
    {
        let area = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        figure.draw(&area, Output::Svg)?;
    }
    Ok(svg)
}

/// Writes a time-history figure as `<stem>.svg` and `<stem>.png` into `dir`.
pub fn write_figure(figure: &Figure, dir: &Path) -> Result<Vec<PathBuf>> {
    write_svg_png(figure, dir)
}

/// Contact windows merged as the comparison merges them (bounces closer than
/// [`crate::results::BOUNCE_GAP`]): the raw windows would shade as slivers.
pub fn shaded_windows(summary: &Summary) -> Vec<(f64, f64)> {
    crate::compare::merged_windows(&summary.contact_windows, crate::results::BOUNCE_GAP)
        .iter()
        .map(|w| (w.start, w.end))
        .collect()
}

/// Writes Figures 6-9 as `<stem>.svg` and `<stem>.png` into `dir` for a run of `scenario`;
/// returns the files written. Captions and legends name the mesh's nodes, the subtitle the
/// scenario; contact is shaded by window with bounces closer than 10 ms merged.
pub fn write_figures(
    steps: &[StepResult],
    summary: &Summary,
    scenario: &Scenario,
    dir: &Path,
    cut_short: bool,
) -> Result<Vec<PathBuf>> {
    let note = match (cut_short, steps.last()) {
        (true, Some(r)) => format!(" (log cut short at t = {:.3} s)", r.time),
        _ => String::new(),
    };
    let subtitle = vec![scenario_subtitle(scenario, Some(summary.time_steps))];
    let shaded = shaded_windows(summary);
    let mut files = Vec::new();
    for mut figure in paper_figures(steps, NodeNumbers::of(scenario), &note) {
        figure.subtitle.clone_from(&subtitle);
        figure.shaded.clone_from(&shaded);
        files.extend(write_figure(&figure, dir)?);
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
        let mut s = Scenario::paper();
        let paper = NodeNumbers { clamp: 1, lower_tip: 8, hinge: 9, upper_contact: 16, upper_tip: 23 };
        assert_eq!(NodeNumbers::of(&s), paper);
        (s.lower.elements, s.upper.elements_to_contact, s.upper.elements_beyond_contact) = (14, 10, 20);
        let nodes = NodeNumbers::of(&s);
        assert_eq!(nodes, NodeNumbers { clamp: 1, lower_tip: 15, hinge: 16, upper_contact: 26, upper_tip: 46 });
        let figures = paper_figures(&[StepResult::default()], nodes, "");
        assert!(figures[0].caption.contains("node 15") && figures[0].caption.contains("node 26"));
        assert_eq!(figures[0].series[1].name, "bridge at contact, node 26");
        assert!(!figures.iter().any(|f| f.caption.contains("node 8") || f.caption.contains("node 16")));
        let subtitle = scenario_subtitle(&s, None);
        assert!(subtitle.contains("nodes 1-15") && subtitle.contains("nodes 16-46"), "{subtitle}");
        assert!(subtitle.contains("contact node 26 at 13 m"), "{subtitle}");
    }

    /// Tick labels never read "-0.0" and carry the decimals of plotters' tick step.
    #[test]
    fn tick_labels_have_no_negative_zero() {
        assert_eq!(tick_label(-1e-17, 1), "0.0");
        assert_eq!(tick_label(-0.0, 0), "0");
        assert_eq!(tick_label(-0.04, 1), "0.0");
        assert_eq!(tick_label(-0.25, 2), "-0.25");
        assert_eq!(tick_decimals(-0.74, 0.32, Y_LABELS), 1);
        assert_eq!(tick_decimals(-530.0, 210.0, Y_LABELS), 0);
        assert_eq!(tick_decimals(0.0, 0.1, X_LABELS), 2);
        assert_eq!(tick_decimals(0.0, 3.0, X_LABELS), 1);
        // Every label plotters would draw on a deflection axis: distinct, none a negative zero.
        let keys = Ranged::key_points(&RangedCoordf64::from(-0.7..0.3), Y_LABELS);
        let labels: Vec<String> = keys.iter().map(|&v| tick_label(v, tick_decimals(-0.7, 0.3, Y_LABELS))).collect();
        assert!(labels.iter().all(|l| !l.starts_with("-0") || !l.trim_start_matches(['-', '0', '.']).is_empty()));
        assert!(labels.windows(2).all(|w| w[0] != w[1]), "{labels:?}");
        assert!(labels.contains(&"0.0".to_string()), "{labels:?}");
    }

    /// Values the axes cannot scale are skipped or clamped, so a range stays finite.
    #[test]
    fn non_finite_points_are_skipped_and_huge_ones_clamped() {
        assert_eq!(plottable((f64::NAN, 1.0)), None);
        assert_eq!(plottable((1.0, f64::INFINITY)), None);
        assert_eq!(plottable((1.0, -f64::MAX)), Some((1.0, -PLOTTABLE)));
        register_fonts();
        let (w, h) = SIZE;
        let mut pixels = vec![0u8; (w * h * 3) as usize];
        let points = vec![(0.0, f64::NAN), (0.1, f64::MAX), (0.2, -f64::MAX), (f64::INFINITY, 0.0), (0.3, 1.0)];
        let figure = Figure {
            stem: "test".into(),
            caption: "caption".into(),
            subtitle: vec![],
            y_label: "value".into(),
            series: vec![Series::new("a", ARRESTOR, Pen::Wide, points)],
            shaded: vec![(f64::NAN, 1.0), (0.1, f64::INFINITY)],
        };
        let root = BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area();
        figure.draw(&root, Output::Png).unwrap();
    }

    /// The PNG path draws text with the compiled-in font, whatever fonts the machine has: the
    /// caption band of a rendered figure holds dark pixels (glyphs), and only there above the plot.
    #[test]
    fn bitmap_figures_render_text_without_system_fonts() {
        register_fonts();
        let (w, h) = SIZE;
        let mut pixels = vec![0u8; (w * h * 3) as usize];
        let figure = Figure {
            stem: "test".into(),
            caption: "Figure 0. Caption text".into(),
            subtitle: vec!["subtitle".into()],
            y_label: "value".into(),
            series: vec![Series::new("a", ARRESTOR, Pen::Thin, vec![(0.0, 0.0), (1.0, 1.0)])],
            shaded: vec![],
        };
        {
            let root = BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area();
            figure.draw(&root, Output::Png).unwrap();
        }
        let dark_in_rows = |rows: std::ops::Range<u32>| {
            rows.flat_map(|y| (0..w).map(move |x| ((y * w + x) * 3) as usize))
                .filter(|&i| pixels[i] < 100 && pixels[i + 1] < 100 && pixels[i + 2] < 100)
                .count()
        };
        let caption = dark_in_rows(10..36);
        assert!(caption > 200, "only {caption} dark pixels where the caption should be");
    }

    /// In contact the two deflection curves coincide: the wide arrestor line still shows on both
    /// sides of the thin bridge line drawn over it (orange pixels next to blue ones).
    #[test]
    fn both_beams_stay_visible_where_their_curves_coincide() {
        register_fonts();
        let (w, h) = SIZE;
        let mut pixels = vec![0u8; (w * h * 3) as usize];
        let same: Vec<(f64, f64)> = (0..=1000).map(|i| (i as f64 * 1e-3, (i as f64 * 0.01).sin())).collect();
        let figure = Figure {
            stem: "test".into(),
            caption: "c".into(),
            subtitle: vec![],
            y_label: "value".into(),
            series: vec![
                Series::new("arrestor", ARRESTOR, Pen::Wide, same.clone()),
                Series::new("bridge", BRIDGE, Pen::Thin, same),
            ],
            shaded: vec![],
        };
        {
            let root = BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area();
            figure.draw(&root, Output::Png).unwrap();
        }
        // Below the header, every pixel column that shows the thin blue line also shows orange.
        let is = |x: u32, y: u32, c: RGBColor| {
            let i = ((y * w + x) * 3) as usize;
            (pixels[i], pixels[i + 1], pixels[i + 2]) == (c.0, c.1, c.2)
        };
        let column_has = |x: u32, c: RGBColor| (150..h).any(|y| is(x, y, c));
        let blue: Vec<u32> = (0..w).filter(|&x| column_has(x, BRIDGE)).collect();
        let both = blue.iter().filter(|&&x| column_has(x, ARRESTOR)).count();
        assert!(blue.len() > 800, "the thin line shows in only {} columns", blue.len());
        assert!(both * 100 >= blue.len() * 98, "orange beside blue in {both} of {} columns", blue.len());
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
