//! The report's figures as inline SVG, drawn here rather than by plotters so that every text in
//! them goes through [`super::escape`] and the time histories carry what the page's script needs to
//! zoom them: the data group is drawn in pixels over the whole x range `data-x0..data-x1` and the
//! script scales it horizontally (`vector-effect: non-scaling-stroke` keeps the lines thin), its
//! visible range in `data-view-x0` / `data-view-x1`, and rebuilds the x ticks.
//!
//! Ticks are steps of 1, 2 or 5 times a power of ten (as plotters chooses them), at most
//! [`TICKS`] per axis; the page's script uses the same rule.

use std::fmt::Write as _;

use super::escape::escape;

/// Width of a chart, px (its viewBox; the page scales it to the column).
pub const WIDTH: f64 = 900.0;
/// Height of a chart, px.
pub const HEIGHT: f64 = 300.0;
/// Plot area: left, right, top and bottom margins, px.
const LEFT: f64 = 78.0;
const RIGHT: f64 = 16.0;
const TOP: f64 = 12.0;
const BOTTOM: f64 = 44.0;
/// At most this many ticks per axis.
pub const TICKS: f64 = 8.0;

/// A line of a chart: its legend name, CSS colour, dashed or not, and its points (x, y).
#[derive(Clone, Debug)]
pub struct Line {
    /// Legend text.
    pub name: String,
    /// A CSS colour (`#1f5ac8`).
    pub color: &'static str,
    /// Dashed (an allowable) or solid.
    pub dashed: bool,
    /// The points, in x order for a time history.
    pub points: Vec<(f64, f64)>,
}

/// A marker: a circle at `at`, with its legend name (or tooltip) and colour.
#[derive(Clone, Debug)]
pub struct Mark {
    /// Legend text (and the circle's tooltip).
    pub name: String,
    /// A CSS colour.
    pub color: &'static str,
    /// Where, in the chart's units.
    pub at: (f64, f64),
    /// Shown in the legend (false: the tooltip alone, for the many points of a sweep).
    pub legend: bool,
}

/// One figure.
#[derive(Clone, Debug, Default)]
pub struct Chart {
    /// The element's id (ASCII letters, digits and `-`: made by the page, never from a file).
    pub id: String,
    /// The caption above it.
    pub title: String,
    /// The x axis's label.
    pub x_label: String,
    /// The y axis's label.
    pub y_label: String,
    /// Its lines.
    pub lines: Vec<Line>,
    /// Its markers.
    pub marks: Vec<Mark>,
    /// x intervals shaded grey (the contact windows), with the shade's legend text.
    pub shaded: Vec<(f64, f64)>,
    /// The shade's legend text.
    pub shade_name: String,
    /// Zoomable along x by the page's script (the time histories).
    pub zoom: bool,
}

/// The tick step for `lo..hi`: 1, 2 or 5 times a power of ten, at most [`TICKS`] ticks.
pub fn tick_step(lo: f64, hi: f64) -> f64 {
    let span = hi - lo;
    if !(span > 0.0 && span.is_finite()) {
        return 1.0;
    }
    let raw = span / TICKS;
    let power = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * power).find(|s| *s >= raw).unwrap_or(10.0 * power)
}

/// The ticks of `lo..hi` with their labels (as many decimals as the step needs).
pub fn ticks(lo: f64, hi: f64) -> Vec<(f64, String)> {
    let step = tick_step(lo, hi);
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    if last < first || last - first > 100 {
        return Vec::new();
    }
    (first..=last)
        .map(|k| k as f64 * step)
        .map(|v| (v, format!("{:.*}", decimals, if v == 0.0 { 0.0 } else { v })))
        .collect()
}

/// The range of `values` padded by 5 % of its span (a single value: +-1 or +-5 % of it), and
/// (0, 1) when there is none.
fn padded(values: impl Iterator<Item = f64>, pad: bool) -> (f64, f64) {
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    // A forged log's 1e308 would make the span infinite: the figures' limit (a run's values are far within).
    let limit = crate::replay::figures::PLOTTABLE;
    let (lo, hi) = (lo.clamp(-limit, limit), hi.clamp(-limit, limit));
    if hi <= lo {
        let d = if lo == 0.0 { 1.0 } else { 0.05 * lo.abs() };
        return (lo - d, hi + d);
    }
    let d = if pad { 0.05 * (hi - lo) } else { 0.0 };
    (lo - d, hi + d)
}

/// A number for a path: two decimals of a pixel.
fn px(v: f64) -> String {
    // Pixels of values beyond the figures' limit, clamped to it, stay finite but may be huge.
    let r = ((v * 100.0).round() / 100.0).clamp(-1e9, 1e9);
    format!("{r}")
}

/// The chart as a `<figure>` with its SVG and its legend.
pub fn figure(chart: &Chart) -> String {
    let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let points = || {
        chart
            .lines
            .iter()
            .flat_map(|l| l.points.iter().copied().filter(finite))
            .chain(chart.marks.iter().map(|m| m.at).filter(finite))
    };
    let (x0, x1) = padded(points().map(|p| p.0), !chart.zoom);
    let (y0, y1) = padded(points().map(|p| p.1), true);
    let (w, h) = (WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM);
    let sx = |x: f64| LEFT + (x - x0) / (x1 - x0) * w;
    let sy = |y: f64| TOP + (y1 - y) / (y1 - y0) * h;
    let id = &chart.id;
    let mut s = String::new();
    let _ = write!(
        s,
        "<figure class=\"chart\" id=\"{id}\"><figcaption>{}</figcaption>\n<svg class=\"plot\" viewBox=\"0 0 {WIDTH} {HEIGHT}\" \
         role=\"img\" aria-label=\"{}\" data-x0=\"{x0}\" data-x1=\"{x1}\" data-view-x0=\"{x0}\" data-view-x1=\"{x1}\" \
         data-left=\"{LEFT}\" data-width=\"{w}\" data-top=\"{TOP}\" data-height=\"{h}\"{}>",
        escape(&chart.title),
        escape(&chart.title),
        if chart.zoom { " data-zoom=\"x\"" } else { "" }
    );
    let _ = write!(s, "<defs><clipPath id=\"{id}-clip\"><rect x=\"{LEFT}\" y=\"{TOP}\" width=\"{w}\" height=\"{h}\"/></clipPath></defs>");
    let _ = write!(s, "<rect class=\"area\" x=\"{LEFT}\" y=\"{TOP}\" width=\"{w}\" height=\"{h}\"/>");
    s.push_str("<g class=\"yticks\">");
    for (v, label) in ticks(y0, y1) {
        let y = px(sy(v));
        let _ = write!(s, "<line x1=\"{LEFT}\" x2=\"{}\" y1=\"{y}\" y2=\"{y}\"/><text x=\"{}\" y=\"{y}\" dy=\"4\" text-anchor=\"end\">{label}</text>", LEFT + w, LEFT - 6.0);
    }
    s.push_str("</g><g class=\"xticks\">");
    for (v, label) in ticks(x0, x1) {
        let x = px(sx(v));
        let _ = write!(s, "<line x1=\"{x}\" x2=\"{x}\" y1=\"{TOP}\" y2=\"{}\"/><text x=\"{x}\" y=\"{}\" text-anchor=\"middle\">{label}</text>", TOP + h, TOP + h + 16.0);
    }
    let _ = write!(s, "</g><g clip-path=\"url(#{id}-clip)\"><g class=\"data\">");
    for &(a, b) in &chart.shaded {
        if a.is_finite() && b.is_finite() {
            let (xa, xb) = (sx(a.max(x0)), sx(b.min(x1)));
            if xb >= xa {
                let _ = write!(
                    s,
                    "<rect class=\"shade\" x=\"{}\" y=\"{TOP}\" width=\"{}\" height=\"{h}\"/>",
                    px(xa),
                    px((xb - xa).max(0.5))
                );
            }
        }
    }
    for line in &chart.lines {
        let mut d = String::new();
        let mut pen = 'M';
        for p in &line.points {
            if finite(p) {
                let _ = write!(d, "{pen}{} {}", px(sx(p.0)), px(sy(p.1)));
                pen = 'L';
            } else {
                pen = 'M';
            }
        }
        let _ = write!(
            s,
            "<path d=\"{d}\" stroke=\"{}\"{}><title>{}</title></path>",
            line.color,
            if line.dashed { " stroke-dasharray=\"8 5\"" } else { "" },
            escape(&line.name)
        );
    }
    for m in chart.marks.iter().filter(|m| finite(&m.at)) {
        let _ = write!(
            s,
            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"{}\"><title>{}</title></circle>",
            px(sx(m.at.0)),
            px(sy(m.at.1)),
            if m.legend { 6 } else { 4 },
            m.color,
            escape(&m.name)
        );
    }
    s.push_str("</g></g>");
    let _ = writeln!(
        s,
        "<text class=\"label\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text><text class=\"label\" transform=\"translate(14 {}) rotate(-90)\" text-anchor=\"middle\">{}</text></svg>",
        LEFT + w / 2.0,
        HEIGHT - 6.0,
        escape(&chart.x_label),
        TOP + h / 2.0,
        escape(&chart.y_label)
    );
    s.push_str("<ul class=\"legend\">");
    for line in &chart.lines {
        let _ = write!(
            s,
            "<li><span class=\"swatch{}\" style=\"border-color:{}\"></span>{}</li>",
            if line.dashed { " dashed" } else { "" },
            line.color,
            escape(&line.name)
        );
    }
    for m in chart.marks.iter().filter(|m| m.legend) {
        let _ = write!(s, "<li><span class=\"dot\" style=\"background:{}\"></span>{}</li>", m.color, escape(&m.name));
    }
    if !chart.shaded.is_empty() {
        let _ = write!(s, "<li><span class=\"swatch shade\"></span>{}</li>", escape(&chart.shade_name));
    }
    s.push_str("</ul></figure>\n");
    s
}

/// The page's script: zoom (wheel) and pan (drag) of the charts marked `data-zoom` along x,
/// double-click to reset; it rebuilds the x ticks with [`ticks`]' rule. No request of any kind.
pub const ZOOM_SCRIPT: &str = r#"(function () {
  function ticks(a, b) {
    var raw = (b - a) / 8, p = Math.pow(10, Math.floor(Math.log10(raw))), step = 10 * p;
    [1, 2, 5, 10].some(function (m) { if (m * p >= raw) { step = m * p; return true; } return false; });
    var dec = Math.max(0, -Math.floor(Math.log10(step))), out = [];
    for (var k = Math.ceil(a / step); k <= Math.floor(b / step) && out.length < 101; k++) out.push([k * step, (k * step).toFixed(dec)]);
    return out;
  }
  document.querySelectorAll('svg[data-zoom]').forEach(function (svg) {
    var d = svg.dataset, x0 = +d.x0, x1 = +d.x1, L = +d.left, W = +d.width, T = +d.top, H = +d.height;
    var a = x0, b = x1, data = svg.querySelector('.data'), xt = svg.querySelector('.xticks'), drag = null;
    var NS = 'http://www.w3.org/2000/svg';
    function at(e) { var r = svg.getBoundingClientRect(); return (e.clientX - r.left) * svg.viewBox.baseVal.width / r.width; }
    function time(p) { return a + (p - L) / W * (b - a); }
    function draw() {
      var k = (x1 - x0) / (b - a);
      data.setAttribute('transform', 'matrix(' + k + ',0,0,1,' + (L - k * (L + (a - x0) / (x1 - x0) * W)) + ',0)');
      d.viewX0 = a; d.viewX1 = b;
      while (xt.firstChild) xt.removeChild(xt.firstChild);
      ticks(a, b).forEach(function (t) {
        var x = L + (t[0] - a) / (b - a) * W, line = document.createElementNS(NS, 'line'), text = document.createElementNS(NS, 'text');
        line.setAttribute('x1', x); line.setAttribute('x2', x); line.setAttribute('y1', T); line.setAttribute('y2', T + H);
        text.setAttribute('x', x); text.setAttribute('y', T + H + 16); text.setAttribute('text-anchor', 'middle');
        text.textContent = t[1]; xt.appendChild(line); xt.appendChild(text);
      });
    }
    function set(na, nb) {
      var span = Math.max(nb - na, (x1 - x0) * 1e-4);
      span = Math.min(span, x1 - x0);
      na = Math.min(Math.max(na, x0), x1 - span);
      a = na; b = na + span; draw();
    }
    svg.addEventListener('wheel', function (e) {
      e.preventDefault();
      var c = time(at(e)), f = e.deltaY > 0 ? 1.25 : 0.8;
      set(c - (c - a) * f, c + (b - c) * f);
    }, { passive: false });
    svg.addEventListener('mousedown', function (e) { drag = { p: at(e), a: a, b: b }; e.preventDefault(); });
    window.addEventListener('mousemove', function (e) {
      if (drag) { var dt = (at(e) - drag.p) / W * (drag.b - drag.a); set(drag.a - dt, drag.b - dt); }
    });
    window.addEventListener('mouseup', function () { drag = null; });
    svg.addEventListener('dblclick', function () { set(x0, x1); });
  });
})();"#;

#[cfg(test)]
mod tests {
    use super::*;

    /// plotters' rule: 0..1 in steps of 0.2 (0.1 would give 11 ticks, more than 8).
    #[test]
    fn ticks_are_one_two_or_five_times_a_power_of_ten() {
        assert_eq!(tick_step(0.0, 1.0), 0.2);
        assert_eq!(tick_step(0.0, 3.0), 0.5);
        assert_eq!(tick_step(-400.0, 500.0), 200.0);
        let labels: Vec<String> = ticks(0.0, 1.0).into_iter().map(|t| t.1).collect();
        assert_eq!(labels, ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
    }

    #[test]
    fn a_line_name_with_markup_stays_text() {
        let chart = Chart {
            id: "c".into(),
            title: "<b>t</b>".into(),
            lines: vec![Line {
                name: "<script>x</script>".into(),
                color: "#000",
                dashed: false,
                points: vec![(0.0, 1.0), (1.0, 2.0)],
            }],
            ..Chart::default()
        };
        let svg = figure(&chart);
        assert!(!svg.contains("<script>") && !svg.contains("<b>"));
        assert!(svg.contains("&lt;script&gt;x&lt;/script&gt;"));
    }
}
