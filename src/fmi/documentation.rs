//! The packed FMU's `documentation/`: `index.html` from the hand-written page in
//! `fmu/documentation/index.html`, with the parts that must match the build generated into it
//! (the binaries it carries, the variables with their units, Table 1 against the reference run),
//! and the result figures drawn from the reference run ([`super::reference`]), as the Reference
//! FMUs carry a `result.svg`.

use std::fmt::Write;

use super::packed_scenario::PackedScenario;
use super::reference::{ReferenceRun, REFERENCE_CSV, REFERENCE_STEP};
use super::resource::SCENARIO_RESOURCE;
use super::variables::{format_real, table, table_for, Type, Variable, SMALLEST_POSITIVE};
use crate::paper::TABLE1_FEM;
use crate::replay::figures::{figure_svg, Figure, Pen, Series, ARRESTOR, BRIDGE};
use crate::results::ENVELOPE_PEAK_NAMES;
use crate::vocabulary::{PEAK_QUANTITIES, PEAK_UNITS};
use crate::Scenario;

/// The markers of the hand-written page that [`index_html`] replaces, in order of appearance.
pub const MARKERS: [&str; 5] = [
    "<!-- generated: binaries -->",
    "<!-- generated: scenario -->",
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
/// converged method) and `paper` (`method` = 1: the paper's mesh and steps), under its heading.
fn table1(default: &ReferenceRun, paper: &ReferenceRun) -> Result<String, String> {
    let mut out = String::from(
        "<h2>The paper's run</h2>\n<p>With the defaults (0 to 3 s), the running peaks <code>peak.*</code> at the \
         stop time against Table 1 (FEM) of the paper. <code>method</code> = 1 runs the paper's 7 + 7/7 mesh and \
         time steps, which Table 1 is bound to; the default converged method differs from it where the paper's \
         mesh is coarse (the shear stress at the clamp, the bridge's stress; the repository's docs/trust.md, \
         \"Answers an engineer can sign\"). These numbers were computed when this FMU was packed, by its own \
         model:</p>\n",
    );
    out.push_str(
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

/// The running peaks at 3 s of `default`, the reference run of an FMU packed with a scenario of
/// its own (issue 30): the paper's five and each beam's worst stress along it with its position
/// (Table 1 is the paper scenario's, not this one's).
fn packed_peaks(default: &ReferenceRun) -> Result<String, String> {
    let mut out = String::from(
        "<h2>This FMU's reference run</h2>\n<p>With the defaults (its packed scenario, 0 to 3 s), the running peaks \
         at the stop time, computed when this FMU was packed, by its own model (Table 1 of the paper is the paper \
         scenario's: an FMU packed without <code>--scenario</code> compares with it):</p>\n<table>\n<tr><th>output \
         at 3 s</th><th>value</th><th>where</th></tr>\n",
    );
    let value = |name: &str| default.last(name).ok_or(format!("the reference run has no output `{name}`"));
    for (name, unit) in PEAK_QUANTITIES.iter().zip(PEAK_UNITS) {
        let name = format!("peak.{name}");
        let shown = match unit {
            "Pa" => format!("{:.1} MPa", value(&name)? * 1e-6),
            "m" => format!("{:.4} m", value(&name)?),
            _ => format!("{:.4e} {unit}", value(&name)?),
        };
        let _ = writeln!(out, "<tr><td><code>{name}</code></td><td>{shown}</td><td></td></tr>");
    }
    for name in ENVELOPE_PEAK_NAMES {
        let (peak, position) = (value(&format!("peak.{name}"))?, value(&format!("peak_position.{name}"))?);
        // 0 at 0 m: the beam has no such stress (the bridge without a shear area).
        let (shown, at) = if peak == 0.0 {
            ("none".to_string(), String::new())
        } else {
            (format!("{:.1} MPa", peak * 1e-6), format!("{position} m (<code>peak_position.{name}</code>)"))
        };
        let _ = writeln!(out, "<tr><td><code>peak.{name}</code></td><td>{shown}</td><td>{at}</td></tr>");
    }
    out.push_str("</table>\n");
    Ok(out)
}

/// Where the FMU's scenario comes from and how beams of sections reach it (issue 30): the packed
/// scenario with its sections, or how to pack one.
fn starting_scenario(packed: Option<&PackedScenario>) -> String {
    let rules = "Parameters set by the importer override its uniform fields; one that contradicts the sections \
                 (<code>lower.length</code> other than their sum, <code>lower.mass</code> other than their mass, \
                 <code>lower.second_moment</code>, <code>lower.section_modulus</code> or <code>lower.shear_area</code> \
                 other than the first section's, and the same for <code>upper.*</code>) makes \
                 <code>ExitInitializationMode</code> return an error, the reason in the log. A \
                 <code>scenario.toml</code> that cannot be the FMU's (larger than 1 MiB, not a valid scenario, a \
                 <code>[motion]</code> table: the supports' motion is the FMU's inputs) or that does not belong to \
                 <code>modelDescription.xml</code> (its token) fails the instantiation with one line in the log.";
    let Some(packed) = packed else {
        return format!(
            "<p>This FMU starts from the paper's scenario, its beams uniform (one second moment, section modulus, \
             shear area and mass per metre along each). Beams whose section changes along them \
             (<code>[[lower.sections]]</code>, <code>[[upper.sections]]</code> in a scenario file) cannot be stated \
             by scalar parameters (FMI 2.0 has no arrays): <code>beam-impact pack --scenario FILE.toml</code> packs a \
             scenario, sections included, as <code>resources/{SCENARIO_RESOURCE}</code>, which the FMU reads at \
             instantiation as its starting scenario; the start values in <code>modelDescription.xml</code> are then \
             that scenario's. {rules}</p>\n"
        );
    };
    let s = &packed.scenario;
    let mut out = format!(
        "<p>This FMU starts from its own scenario, packed from <code>{}</code> as \
         <code>resources/{SCENARIO_RESOURCE}</code> and read at instantiation: the start values in \
         <code>modelDescription.xml</code> are that scenario's. {rules}</p>\n",
        esc(&packed.source)
    );
    for (beam, from, sections) in [("bridge", "hinge", &s.upper.sections), ("arrestor", "clamp", &s.lower.sections)] {
        if sections.is_empty() {
            let _ = writeln!(out, "<p>The {beam}: uniform.</p>");
            continue;
        }
        let _ = writeln!(
            out,
            "<p>The {beam}'s sections from its {from}:</p>\n<table>\n<tr><th>section</th><th>from, m</th><th>to, \
             m</th><th>I, m4</th><th>W, m3</th><th>A_s, m2</th><th>mass, kg/m</th></tr>"
        );
        let mut start = 0.0;
        for (k, g) in sections.iter().enumerate() {
            let w = match g.section_modulus_bottom {
                Some(bottom) => format!("{} (bottom {})", format_real(g.section_modulus), format_real(bottom)),
                None => format_real(g.section_modulus),
            };
            let _ = writeln!(
                out,
                "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{w}</td><td>{}</td><td>{}</td></tr>",
                k + 1,
                format_real(start),
                format_real(start + g.length),
                format_real(g.second_moment),
                format_real(g.shear_area),
                format_real(g.mass_per_length)
            );
            start += g.length;
        }
        out.push_str("</table>\n");
    }
    out
}

/// Every variable: name, causality, variability, type, unit, declared range, start value (the
/// starting scenario's: `packed`, or the paper's), description (which lists an Integer's choices).
fn variables(packed: Option<&Scenario>) -> String {
    let mut out = String::from(
        "<table>\n<tr><th>name</th><th>causality</th><th>variability</th><th>type</th><th>unit</th><th>range</th>\
         <th>start</th><th>description</th></tr>\n",
    );
    for v in packed.map_or_else(table, table_for) {
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
/// binaries the FMU carries (`platforms`: FMI platform directory and what it is), the starting
/// scenario (`packed`, issue 30, or the paper's, and how sections are packed), Table 1 against
/// `default` and `paper` (the reference runs with the defaults and with `method` = 1; a packed
/// FMU has no `paper` run and lists its own peaks instead), the result figures and the variable
/// table. A template without a marker is an error naming it.
pub fn index_html(
    template: &str,
    platforms: &[(String, String)],
    generation_tool: &str,
    default: &ReferenceRun,
    paper: Option<&ReferenceRun>,
    packed: Option<&PackedScenario>,
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
    let peaks = match paper {
        Some(paper) => table1(default, paper)?,
        None => packed_peaks(default)?,
    };
    let scenario = packed.map(|p| &p.scenario);
    let parts = [binaries, starting_scenario(packed), peaks, figures, variables(scenario)];
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
        let table = variables(None);
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
