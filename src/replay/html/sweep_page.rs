//! The sweep page: the response over the sweep's grid, a chart per peak column against the first
//! varied field (one line per combination of the other fields' values; each point coloured by its
//! verdict), and every row as a table whose numbers carry their place in the sweep's JSON rows.

use std::fmt::Write as _;

use serde_json::Value;

use super::charts::{figure, Chart, Line, Mark};
use super::escape::escape;
use super::page::shell;
use super::tables::{cell, pointer, shown_number};

/// The verdict colours of a point: trusted and passing the design check, not trusted, failing it.
pub const PASS: &str = "#2a9d3a";
/// A row whose numbers are not trusted (`quality.trusted` false).
pub const UNTRUSTED: &str = "#e08a00";
/// A row failing the design check (`design.pass` false).
pub const FAIL: &str = "#d7261e";

/// Line colours of the combinations of the other fields.
const LINES: [&str; 6] = ["#7a8ca8", "#a87a9a", "#8aa87a", "#a8987a", "#7aa8a4", "#9a9a9a"];

/// What a sweep's page is built from.
pub struct SweepPage<'a> {
    /// What the page is of, one line.
    pub title: String,
    /// Lines about the sweep (its base scenario, its files): shown as text.
    pub source: Vec<String>,
    /// The varied fields, in the order of the axes.
    pub axes: Vec<String>,
    /// The named columns with their units (`studies::sweep::column_units`, without former names).
    pub columns: Vec<(String, &'a str)>,
    /// The rows: the sweep's JSON array of row objects.
    pub rows: &'a Value,
}

/// A value as a number for a chart (a word, an enumerated field's value, has none).
fn number(v: Option<&Value>) -> Option<f64> {
    v.and_then(Value::as_f64)
}

/// Scale and unit shown for a column's unit: MPa for Pa, kN for N.
fn display_unit(unit: &str) -> (f64, String) {
    match unit {
        "Pa" => (1e-6, "MPa".into()),
        "N" => (1e-3, "kN".into()),
        other => (1.0, other.to_string()),
    }
}

/// The page of a sweep.
pub fn sweep_page(p: &SweepPage) -> String {
    let rows: &[Value] = p.rows.as_array().map_or(&[], Vec::as_slice);
    let mut body = format!("<h1>beam-impact: {}</h1>\n<ul>", escape(&p.title));
    for line in &p.source {
        let _ = write!(body, "<li>{}</li>", escape(line));
    }
    let verdict = |r: &Value| match (
        r.get("quality.trusted").and_then(Value::as_bool),
        r.get("design.pass").and_then(Value::as_bool),
    ) {
        (None, _) => None,
        (_, Some(false)) => Some(FAIL),
        (Some(false), _) => Some(UNTRUSTED),
        _ => Some(PASS),
    };
    let count = |c: &str| rows.iter().filter(|r| verdict(r) == Some(c)).count();
    let failed = rows.iter().filter(|r| verdict(r).is_none()).count();
    let _ = write!(
        body,
        "</ul>\n<p>{} scenarios: <span class=\"pass\">{} trusted and passing the design check</span>, <span class=\"fail\">{} failing the \
         design check</span>, <span style=\"background:#fbe3c0\">{} not trusted</span>, {failed} failed (no results). Varied: {}.</p>\n",
        rows.len(),
        count(PASS),
        count(FAIL),
        count(UNTRUSTED),
        escape(&p.axes.join(", "))
    );
    let Some(first) = p.axes.first() else {
        return shell(&p.title, &(body + "<p>No varied field.</p>"));
    };
    // x: the first axis's value, or the index of a word among the axis's distinct words.
    let mut words: Vec<String> = Vec::new();
    let mut x_of = |r: &Value| -> Option<f64> {
        match r.get(first.as_str()) {
            Some(Value::Number(n)) => n.as_f64(),
            Some(Value::String(w)) => Some(match words.iter().position(|x| x == w) {
                Some(k) => k as f64,
                None => {
                    words.push(w.clone());
                    (words.len() - 1) as f64
                }
            }),
            _ => None,
        }
    };
    let xs: Vec<Option<f64>> = rows.iter().map(&mut x_of).collect();
    let x_unit = p.columns.iter().find(|(n, _)| n == first).map_or("", |(_, u)| *u);
    let x_label = if words.is_empty() {
        format!("{first}, {x_unit}")
    } else {
        format!("{first} (0, 1, ...: {})", words.join(", "))
    };
    let group = |r: &Value| -> String {
        p.axes[1..]
            .iter()
            .map(|a| {
                format!(
                    "{a} = {}",
                    r.get(a.as_str()).map_or("-".into(), |v| v.to_string().trim_matches('"').to_string())
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut charts = format!(
        "<p class=\"note\">Each point a scenario of the grid: <span style=\"color:{PASS}\">&#9679;</span> trusted and passing the design check, \
         <span style=\"color:{UNTRUSTED}\">&#9679;</span> not trusted, <span style=\"color:{FAIL}\">&#9679;</span> failing the design check; \
         {}.</p>\n",
        if p.axes.len() > 1 { "one line per combination of the other varied fields" } else { "joined in grid order" }
    );
    let peaks = p.columns.iter().filter(|(n, _)| n.starts_with("peak.") || n.starts_with("utilisation."));
    for (k, (column, unit)) in peaks.enumerate() {
        let (scale, shown_unit) = display_unit(unit);
        let mut groups: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
        let mut marks = Vec::new();
        for (r, x) in rows.iter().zip(&xs) {
            let (Some(x), Some(y)) = (*x, number(r.get(column.as_str()))) else { continue };
            let g = group(r);
            match groups.iter_mut().find(|(name, _)| *name == g) {
                Some((_, points)) => points.push((x, y * scale)),
                None => groups.push((g.clone(), vec![(x, y * scale)])),
            }
            let color = verdict(r).unwrap_or("#999999");
            let name = format!(
                "{}{}{}: {} {shown_unit}",
                escape_free_value(r, first),
                if g.is_empty() { "" } else { ", " },
                g,
                shown_number(y * scale)
            );
            marks.push(Mark { name, color, at: (x, y * scale), legend: false });
        }
        if marks.is_empty() {
            continue;
        }
        let mut lines: Vec<Line> = groups
            .into_iter()
            .enumerate()
            .map(|(i, (name, points))| Line {
                name: if name.is_empty() { "the grid".into() } else { name },
                color: LINES[i % LINES.len()],
                dashed: false,
                points,
            })
            .collect();
        // A utilisation's allowable: 1.
        if column.starts_with("utilisation.") {
            let (lo, hi) =
                marks.iter().map(|m| m.at.0).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
            lines.push(Line {
                name: "allowable: utilisation 1".into(),
                color: FAIL,
                dashed: true,
                points: vec![(lo, 1.0), (hi, 1.0)],
            });
        }
        charts.push_str(&figure(&Chart {
            id: format!("sweep-{k}"),
            title: format!("{column} against {first}"),
            x_label: x_label.clone(),
            y_label: format!("{column}, {shown_unit}"),
            lines,
            marks,
            ..Chart::default()
        }));
    }
    let _ = write!(body, "<section id=\"response\"><h2>The response over the grid</h2>\n{charts}</section>\n");
    // Every row.
    let mut table = String::from("<table class=\"grid\" id=\"rows\"><thead><tr><th>row</th>");
    for (name, unit) in &p.columns {
        let _ = write!(table, "<th>{}<br><span class=\"note\">{}</span></th>", escape(name), escape(unit));
    }
    table.push_str("</tr></thead><tbody>");
    for (i, r) in rows.iter().enumerate() {
        let _ = write!(table, "<tr><th>{i}</th>");
        let row_ptr = pointer("", &i.to_string());
        for (name, _) in &p.columns {
            match r.get(name.as_str()) {
                Some(v) => table.push_str(&cell(&pointer(&row_ptr, name), v)),
                None => table.push_str("<td></td>"),
            }
        }
        table.push_str("</tr>");
    }
    table.push_str("</tbody></table>\n");
    let _ = write!(
        body,
        "<section id=\"rows-section\"><h2>Every row</h2>\n<div style=\"overflow-x:auto\">{table}</div></section>\n"
    );
    shell(&format!("beam-impact: {}", p.title), &body)
}

/// `field = value` of a row (the value as the JSON holds it: a word without its quotes).
fn escape_free_value(r: &Value, field: &str) -> String {
    let v = r.get(field).map_or("-".into(), |v| v.to_string());
    format!("{field} = {}", v.trim_matches('"'))
}
