//! The packed FMU's `documentation/`: `index.html` from the hand-written page in
//! `fmu/documentation/index.html`, with the parts that must match the build generated into it
//! (the binaries it carries, the variables with their units, Table 1 against the reference run),
//! and the result figures drawn from the reference run ([`super::reference`]), as the Reference
//! FMUs carry a `result.svg`.

use std::fmt::Write;

use super::reference::{ReferenceRun, REFERENCE_CSV, REFERENCE_STEP};
use super::variables::{format_real, table, Type, Variable, SMALLEST_POSITIVE};
use crate::paper::TABLE1_FEM;
use crate::replay::figures::{figure_svg, Figure, Pen, Series, ARRESTOR, BRIDGE};

/// The markers of the hand-written page that [`index_html`] replaces, in order of appearance.
pub const MARKERS: [&str; 4] = [
    "<!-- generated: binaries -->",
    "<!-- generated: table1 -->",
    "<!-- generated: figures -->",
    "<!-- generated: variables -->",
];

/// The figures: (file name inside `documentation/`, caption).
pub const FIGURES: [(&str, &str); 2] = [
    ("result.svg", "Figure 6: deflection of the arrestor's end and of the bridge at the contact point"),
    ("result-stress.svg", "Figure 7: bending stress at the arrestor's clamp and in the bridge at the contact point"),
];

/// Escapes text for HTML.
fn esc(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// Table 1's four quantities: symbol, the FMU's running-peak output, scale to the shown unit, unit,
/// decimals shown (one more than the paper prints).
const TABLE1_ROWS: [(&str, &str, f64, &str, usize); 4] = [
    ("w<sub>din,a</sub>, arrestor end deflection", "peak.lower.tip_deflection", 1.0, "m", 4),
    ("&sigma;<sub>din,a</sub>, bending stress at the clamp", "peak.lower.clamp_bending_stress", 1e-6, "MPa", 1),
    ("&tau;<sub>din,a</sub>, shear stress at the clamp", "peak.lower.clamp_shear_stress", 1e-6, "MPa", 1),
    ("&sigma;<sub>din,b</sub>, bridge bending stress at contact", "peak.upper.contact_bending_stress", 1e-6, "MPa", 1),
];

/// Table 1 (FEM column) beside the running peaks at 3 s of `default` (the FMU's defaults: the
/// converged method) and `paper` (`method` = 1: the paper's mesh and steps).
fn table1(default: &ReferenceRun, paper: &ReferenceRun) -> Result<String, String> {
    let mut out = String::from(
        "<table>\n<tr><th>Table 1 (FEM)</th><th>output at 3 s</th><th>paper</th><th>this FMU, <code>method</code> = 1 \
         (paper's mesh)</th><th>ratio</th><th>this FMU, defaults (converged)</th><th>ratio</th></tr>\n",
    );
    for ((symbol, output, scale, unit, decimals), printed) in TABLE1_ROWS.iter().zip(TABLE1_FEM) {
        let value = |run: &ReferenceRun| run.last(output).ok_or(format!("the reference run has no output `{output}`"));
        let (p, d) = (value(paper)?, value(default)?);
        let _ = writeln!(
            out,
            "<tr><td>{symbol}</td><td><code>{output}</code></td><td>{:.paper$} {unit}</td><td>{:.decimals$} {unit}</td>\
             <td>{:.3}</td><td>{:.decimals$} {unit}</td><td>{:.3}</td></tr>",
            printed * scale,
            p * scale,
            p / printed,
            d * scale,
            d / printed,
            paper = decimals - 1,
        );
    }
    out.push_str("</table>\n");
    Ok(out)
}

/// A variable's accepted range as the page shows it: its declared `min` and `max` ("0 to 1",
/// "> 0" for the smallest positive bound), empty where none is declared.
fn range(v: &Variable) -> String {
    let bound = |x: f64| if v.ty == Type::Integer { format!("{}", x as i64) } else { format_real(x) };
    match (v.min, v.max) {
        (Some(min), Some(max)) if min == SMALLEST_POSITIVE => format!("> 0, <= {}", bound(max)),
        (Some(min), Some(max)) => format!("{} to {}", bound(min), bound(max)),
        (Some(min), None) if min == SMALLEST_POSITIVE => "> 0".into(),
        (Some(min), None) => format!(">= {}", bound(min)),
        (None, Some(max)) => format!("<= {}", bound(max)),
        (None, None) => String::new(),
    }
}

/// Every variable: name, causality, variability, type, unit, declared range, start value,
/// description (which lists an Integer's choices).
fn variables() -> String {
    let mut out = String::from(
        "<table>\n<tr><th>name</th><th>causality</th><th>variability</th><th>type</th><th>unit</th><th>range</th>\
         <th>start</th><th>description</th></tr>\n",
    );
    for v in table() {
        let unit = match (v.unit, v.display_unit()) {
            (Some(unit), Some(display)) => format!("{unit} (shown in {display})"),
            (Some(unit), None) => unit.to_string(),
            (None, _) if v.ty == Type::Real => "-".into(),
            (None, _) => String::new(),
        };
        let _ = writeln!(
            out,
            "<tr><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>\
             <td>{}</td></tr>",
            esc(&v.name),
            v.causality.name(),
            v.variability.name(),
            v.ty.fmi2_name(),
            esc(&unit),
            esc(&range(&v)),
            esc(v.start.as_deref().unwrap_or("")),
            esc(&v.description),
        );
    }
    out.push_str("</table>\n");
    out
}

/// The contact windows of a run sampled every millisecond (`contact.active`), bounces closer
/// than [`crate::results::BOUNCE_GAP`] merged as the report's figures merge them.
fn contact_windows(run: &ReferenceRun) -> Vec<(f64, f64)> {
    let mut windows: Vec<(f64, f64)> = Vec::new();
    let Some(active) = run.series("contact.active") else { return windows };
    let mut start = None;
    for (i, &(t, a)) in active.iter().enumerate() {
        match (start, a > 0.5) {
            (None, true) => start = Some(if i == 0 { t } else { active[i - 1].0 }),
            (Some(s), false) => {
                match windows.last_mut() {
                    Some(last) if s - last.1 < crate::results::BOUNCE_GAP => last.1 = t,
                    _ => windows.push((s, t)),
                }
                start = None;
            }
            _ => {}
        }
    }
    if let (Some(s), Some(&(end, _))) = (start, active.last()) {
        windows.push((s, end));
    }
    windows
}

/// The result figures (Figures 6 and 7 of the paper from the reference run's outputs) as
/// (file name, SVG).
pub fn figures(run: &ReferenceRun) -> Result<Vec<(String, String)>, String> {
    let series = |name: &str, output: &str, scale: f64, color, pen| -> Result<Series, String> {
        let points = run.series(output).ok_or(format!("the reference run has no output `{output}`"))?;
        Ok(Series::new(name, color, pen, points.into_iter().map(|(t, v)| (t, v * scale)).collect()))
    };
    let shaded = contact_windows(run);
    let subtitle = vec![format!(
        "The FMU's reference run: every parameter at its start value, 0 to 3 s, outputs every {} ms ({REFERENCE_CSV})",
        REFERENCE_STEP * 1e3
    )];
    let figure = |stem: &str, caption: &str, y_label: &str, series: Vec<Series>| Figure {
        stem: stem.into(),
        caption: caption.into(),
        subtitle: subtitle.clone(),
        y_label: y_label.into(),
        series,
        shaded: shaded.clone(),
    };
    let figures = [
        figure(
            "result",
            FIGURES[0].1,
            "deflection, m (up positive)",
            vec![
                series("arrestor end (lower.tip_deflection)", "lower.tip_deflection", 1.0, ARRESTOR, Pen::Wide)?,
                series(
                    "bridge at contact (upper.contact_deflection)",
                    "upper.contact_deflection",
                    1.0,
                    BRIDGE,
                    Pen::Thin,
                )?,
            ],
        ),
        figure(
            "result-stress",
            FIGURES[1].1,
            "bending stress, MPa",
            vec![
                series(
                    "arrestor clamp (lower.clamp_bending_stress)",
                    "lower.clamp_bending_stress",
                    1e-6,
                    ARRESTOR,
                    Pen::Wide,
                )?,
                series(
                    "bridge at contact (upper.contact_bending_stress)",
                    "upper.contact_bending_stress",
                    1e-6,
                    BRIDGE,
                    Pen::Thin,
                )?,
            ],
        ),
    ];
    figures
        .iter()
        .zip(FIGURES)
        .map(|(f, (file, _))| figure_svg(f).map(|svg| (file.to_string(), svg)).map_err(|e| e.to_string()))
        .collect()
}

/// `index.html`: `template` (the hand-written page) with each of [`MARKERS`] replaced: the
/// binaries the FMU carries (`platforms`: FMI platform directory and what it is), Table 1 against
/// `default` and `paper` (the reference runs with the defaults and with `method` = 1), the result
/// figures and the variable table. A template without a marker is an error naming it.
pub fn index_html(
    template: &str,
    platforms: &[(String, String)],
    generation_tool: &str,
    default: &ReferenceRun,
    paper: &ReferenceRun,
) -> Result<String, String> {
    let mut binaries =
        format!("<p>Generated by {}. Binaries in this FMU (<code>binaries/</code>):</p>\n<ul>\n", esc(generation_tool));
    for (dir, what) in platforms {
        let _ = writeln!(binaries, "<li><code>{}</code>: {}</li>", esc(dir), esc(what));
    }
    binaries.push_str("</ul>\n");
    let mut figures = String::new();
    for (file, caption) in FIGURES {
        let _ = writeln!(
            figures,
            "<figure><img src=\"{file}\" alt=\"{caption}\" width=\"100%\"><figcaption>{caption}</figcaption></figure>"
        );
    }
    let _ = writeln!(
        figures,
        "<p>The outputs of this run at every millisecond are in <code>{REFERENCE_CSV}</code> (a header of the \
         variables' names, SI units, Booleans as 0 and 1): an importer running the FMU with its defaults and 1 ms \
         communication steps should reproduce them to round-off.</p>"
    );
    let parts = [binaries, table1(default, paper)?, figures, variables()];
    let mut page = template.to_string();
    for (marker, part) in MARKERS.iter().zip(parts) {
        if !page.contains(marker) {
            return Err(format!("the documentation page has no `{marker}` (fmu/documentation/index.html)"));
        }
        page = page.replacen(marker, &part, 1);
    }
    Ok(page)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The row of variable `name` in the page's variable table.
    fn row(name: &str) -> String {
        let table = variables();
        let start = table.find(&format!("<tr><td><code>{name}</code></td>")).unwrap_or_else(|| panic!("{name}"));
        table[start..].lines().next().unwrap().to_string()
    }

    /// Issue 28's parameters are listed with their type, unit, range and choices, and the impact's
    /// outputs with their units and formulas.
    #[test]
    fn the_variable_table_lists_issue_28s_parameters_with_units_ranges_and_choices() {
        let kind = row("lower.kind");
        assert!(kind.contains("<td>Integer</td><td></td><td>0 to 1</td><td>0</td>"), "{kind}");
        assert!(kind.contains("0 the arrestor beam, 1 a rigid point"), "{kind}");
        let stiffness = row("contact.stiffness");
        assert!(stiffness.contains("<td>Real</td><td>N/m</td><td>0.0 to 10000000000000.0</td>"), "{stiffness}");
        assert!(stiffness.contains("0: the bar's E A_c / l_c"), "{stiffness}");
        assert!(row("contact.clearance").contains("<td>m</td><td>0.0 to 10.0</td>"));
        assert!(row("impact_angular_velocity").contains("<td>rad/s</td><td>0.0 to 50.0</td>"));
        assert!(row("gravity").contains("<td>m/s2</td><td>0.0 to 100.0</td>"));
        assert!(row("contact_position").contains("<td>&gt; 0</td>"));
        let omega = row("impact.angular_velocity");
        assert!(omega.contains("<td>output</td>") && omega.contains("<td>rad/s</td>"), "{omega}");
        assert!(omega.contains("sqrt(3 g alpha_0 / l_u) with alpha_0 = atan(2 h / l_u)"), "{omega}");
        let closing = row("impact.closing_speed");
        assert!(closing.contains("<td>m/s</td>") && closing.contains("omega_0 d"), "{closing}");
    }
}
