//! The page builder: one self-contained HTML file (inline CSS, inline SVG, one short inline
//! script; a Content-Security-Policy that forbids every request) with a run's scenario, Table 1
//! beside the paper, every number of its JSON document with its verdict, the design check per load
//! case, the dynamic amplification and fatigue blocks when the document has them, the stress envelope
//! along each beam, the time histories (zoomable) and the contact windows.

use std::fmt::Write as _;

use serde_json::Value;
use sha2::{Digest, Sha256};

use super::charts::{figure, Chart, Line, Mark, ZOOM_SCRIPT};
use super::escape::escape;
use super::tables::{cell, render, shown_number};
use crate::model::Scenario;
use crate::results::{StationEnvelope, StepResult, Summary};
use crate::wording::Wording;

/// Points kept per time history: the minimum and maximum of each of this many equal time slices
/// ([`crate::replay::figures::min_max_decimate`]), so every peak stays visible at any zoom down to
/// one slice per pixel of a 900 px chart zoomed 4x.
pub const SLICES: usize = 3600;

/// The blocks other parts of the program add to a run's document, shown under their own headings
/// (issue 44): the key, the heading, and what the page says when the document has none.
pub const BLOCKS: [(&str, &str); 4] = [
    ("load_cases", "Design check per load case"),
    ("governing", "Governing load case per quantity"),
    ("dynamic_amplification", "Dynamic amplification (DAF)"),
    ("fatigue", "Fatigue"),
];

/// Keys of the document not shown in its "every number" section (shown elsewhere, or text).
const SHOWN_ELSEWHERE: [&str; 6] =
    ["scenario", "scenario_as_given", "units", "merged_contact_windows", "quality", "design"];

/// What a run's page is built from.
pub struct RunPage<'a> {
    /// What the page is of, one line ("run of paper.toml", "log paper.mcap").
    pub title: String,
    /// Lines about where the numbers come from (the log, its status, notes): shown as text.
    pub source: Vec<String>,
    /// The run's JSON document (`run --json`'s, or the same keys rebuilt from a log).
    pub doc: &'a Value,
    /// The scenario the run was made of.
    pub scenario: &'a Scenario,
    /// The run's summary (Table 1, the envelope, the contact windows).
    pub summary: &'a Summary,
    /// The recorded steps (the time histories).
    pub steps: &'a [StepResult],
    /// Where the envelope comes from, one line.
    pub envelope_source: String,
    /// Table 1's comparison as `run` prints it (`compare::comparison`).
    pub comparison: String,
}

/// The stylesheet.
const STYLE: &str = "body{font:14px/1.45 system-ui,sans-serif;margin:0 auto;max-width:1000px;padding:0 16px 40px;color:#222}\
h1{font-size:22px}h2{font-size:18px;border-bottom:1px solid #bbb;margin-top:28px}h3{font-size:15px}h4{font-size:13px;margin:10px 0 4px}\
table{border-collapse:collapse;margin:6px 0;font-size:12px}td,th{border:1px solid #ccc;padding:2px 6px;text-align:left;vertical-align:top}\
td.num{text-align:right;font-variant-numeric:tabular-nums}.pass{background:#dff3df}.fail{background:#f8d4d4}.verdict{font-weight:bold}\
.none{color:#999}.note{color:#555;font-size:12px}pre{background:#f6f6f6;padding:8px;overflow-x:auto;font-size:12px}\
figure{margin:12px 0}figcaption{font-weight:bold;margin-bottom:4px}svg.plot{width:100%;height:auto;background:#fff;user-select:none}\
svg .area{fill:none;stroke:#888}svg .yticks line,svg .xticks line{stroke:#e4e4e4}svg text{font:11px sans-serif;fill:#333}\
svg .label{font-size:12px}svg path{fill:none;stroke-width:1.6;vector-effect:non-scaling-stroke}svg .shade{fill:#e2e2e2}\
svg[data-zoom]{cursor:grab}ul.legend{list-style:none;padding:0;margin:2px 0;font-size:12px}ul.legend li{display:inline-block;margin-right:14px}\
.swatch{display:inline-block;width:22px;border-top:3px solid;margin-right:5px;vertical-align:middle}.swatch.dashed{border-top-style:dashed}\
.swatch.shade{border:0;height:10px;background:#e2e2e2}.dot{display:inline-block;width:10px;height:10px;border-radius:5px;margin-right:5px}\
.banner td{font-size:14px}details{margin:4px 0}summary{cursor:pointer;font-weight:bold}";

/// Standard base64 (RFC 4648 section 4, with padding) of `bytes`: the CSP's script hash.
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// The page around `body`: its title, the CSP (no request of any kind: `default-src 'none'`; the
/// one script allowed by its SHA-256, inline styles, images only as `data:`), the stylesheet and
/// the zoom script.
pub fn shell(title: &str, body: &str) -> String {
    let hash = base64(&Sha256::digest(ZOOM_SCRIPT.as_bytes()));
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<meta http-equiv=\"Content-Security-Policy\" \
         content=\"default-src 'none'; script-src 'sha256-{hash}'; style-src 'unsafe-inline'; img-src data:; \
         base-uri 'none'; form-action 'none'\">\n<meta name=\"viewport\" content=\"width=device-width\">\n\
         <title>{}</title>\n<style>{STYLE}</style></head>\n<body>\n{body}\n<script>{ZOOM_SCRIPT}</script>\n</body></html>\n",
        escape(title)
    )
}

/// The cell of the document's value at `ptr`, or an empty one.
fn doc_cell(doc: &Value, ptr: &str) -> String {
    doc.pointer(ptr).map_or_else(|| "<td class=\"none\">-</td>".into(), |v| cell(ptr, v))
}

/// A number of the document shown scaled (`scale`, `decimals`), with its exact value in
/// `data-value`: Table 1's MPa of a document's Pa.
fn scaled_cell(doc: &Value, ptr: &str, scale: f64, decimals: usize) -> String {
    match doc.pointer(ptr) {
        Some(Value::Number(n)) => {
            let x = n.as_f64().unwrap_or(f64::NAN) * scale;
            format!("<td class=\"num\" data-key=\"{}\" data-value=\"{n}\">{x:.decimals$}</td>", escape(ptr))
        }
        Some(other) => cell(ptr, other),
        None => "<td class=\"none\">-</td>".into(),
    }
}

/// Table 1: FEM peaks (the printed run and the converged answer) and the energy approach, with the
/// paper's values and ratios for the paper's scenario (as `compare::table1`).
/// In the words of `w` (issue 45): w_din,a at the contact point on two supports or struck inside
/// the span, a pin's stresses, and no sigma_din,b row for a rigid impactor.
fn table1(doc: &Value, paper: bool, w: &Wording) -> String {
    let deflection = format!("w_din,a arrestor {} [m]", w.deflection());
    let bending = format!("sigma_din,a {} bending stress [MPa]", w.first_support);
    let shear = format!("tau_din,a {} shear stress [MPa]", w.first_support);
    let all_rows = [
        (deflection.as_str(), "lower_tip_deflection", "tip_deflection", 1.0),
        (bending.as_str(), "lower_clamp_bending_stress", "clamp_bending_stress", 1e-6),
        (shear.as_str(), "lower_clamp_shear_stress", "clamp_shear_stress", 1e-6),
        ("sigma_din,b bridge bending at contact [MPa]", "upper_contact_bending_stress", "bridge_bending_stress", 1e-6),
    ];
    let rows = &all_rows[..if w.rigid_impactor { 3 } else { 4 }];
    let mut s = String::from("<table class=\"grid\" id=\"table1\"><thead><tr><th></th><th>FEM (printed run)</th>");
    if paper {
        s.push_str("<th>paper</th><th>ratio</th>");
    }
    s.push_str("<th>energy approach</th>");
    if paper {
        s.push_str("<th>paper</th><th>ratio</th>");
    }
    s.push_str("<th>converged answer</th></tr></thead><tbody>");
    let ratio = |v: Option<f64>, r: f64| match v {
        Some(v) if r != 0.0 && v.is_finite() => format!("<td class=\"num\">{:.3}</td>", v / r),
        _ => "<td>-</td>".into(),
    };
    for (k, (name, peak, energy, scale)) in rows.iter().enumerate() {
        let fem_ptr = format!("/summary/peaks/{peak}");
        let energy_ptr = format!("/summary/energy_method/{energy}");
        let _ = write!(s, "<tr><th>{}</th>{}", escape(name), scaled_cell(doc, &fem_ptr, *scale, 3));
        let number = |ptr: &str| doc.pointer(ptr).and_then(Value::as_f64);
        if paper {
            let (pf, pe) = (crate::paper::TABLE1_FEM[k], crate::paper::TABLE1_ENERGY[k]);
            let _ = write!(s, "<td class=\"num\">{:.3}</td>{}", pf * scale, ratio(number(&fem_ptr), pf));
            s.push_str(&scaled_cell(doc, &energy_ptr, *scale, 3));
            let _ = write!(s, "<td class=\"num\">{:.3}</td>{}", pe * scale, ratio(number(&energy_ptr), pe));
        } else {
            s.push_str(&scaled_cell(doc, &energy_ptr, *scale, 3));
        }
        s.push_str(&scaled_cell(doc, &format!("/summary/converged_peaks/{peak}"), *scale, 3));
        s.push_str("</tr>");
    }
    s.push_str("</tbody></table>\n");
    s
}

/// The (time, value * scale) points of `value` over `steps`, decimated to [`SLICES`] min/max pairs.
fn history(steps: &[StepResult], value: fn(&StepResult) -> f64, scale: f64) -> Vec<(f64, f64)> {
    let points: Vec<(f64, f64)> = steps.iter().map(|r| (r.time, value(r) * scale)).collect();
    crate::replay::figures::min_max_decimate(&points, SLICES)
}

/// A history's curve: its name, colour, value of a step and the scale it is shown at.
type Curve = (&'static str, &'static str, fn(&StepResult) -> f64, f64);

/// The time histories the reader can zoom: deflections, contact force, the first support's
/// stresses, the bridge's stress at the contact point (none for a rigid impactor); contact
/// windows shaded; in the words of `w` (issue 45).
fn histories(steps: &[StepResult], shaded: &[(f64, f64)], w: &Wording) -> Vec<Chart> {
    let arrestor: &'static str = if w.at_contact {
        "arrestor deflection at the contact w_a (lower_tip_deflection)"
    } else {
        "arrestor end deflection w_a (lower_tip_deflection)"
    };
    let striker: &'static str =
        if w.rigid_impactor { "impactor displacement" } else { "bridge deflection at the contact point" };
    let (support_title, support_bending, support_shear): (&'static str, &'static str, &'static str) =
        if w.first_support == "pin" {
            (
                "Stresses of the arrestor at its first support (a pin)",
                "bending stress at the pin sigma_a",
                "shear stress at the pin tau_a",
            )
        } else {
            ("Clamp stresses of the arrestor", "bending stress at the clamp sigma_a", "shear stress at the clamp tau_a")
        };
    let mut specs: Vec<(&str, &str, &str, Vec<Curve>)> = vec![
        (
            "h-deflection",
            if w.at_contact { "Deflection at the contact" } else { "Tip deflection" },
            "deflection, m",
            vec![
                (arrestor, "#d7261e", |r| r.lower_tip_deflection, 1.0),
                (striker, "#1f5ac8", |r| r.upper_contact_deflection, 1.0),
            ],
        ),
        (
            "h-force",
            "Contact force",
            "force, kN",
            vec![("contact bar force F_c", "#288c3c", |r| r.contact_force, 1e-3)],
        ),
        (
            "h-clamp",
            support_title,
            "stress, MPa",
            vec![
                (support_bending, "#d7261e", |r| r.lower_clamp_bending_stress, 1e-6),
                (support_shear, "#963caf", |r| r.lower_clamp_shear_stress, 1e-6),
            ],
        ),
        (
            "h-bridge",
            "Bridge stress at the contact point",
            "stress, MPa",
            vec![(
                "bending stress of the bridge at contact sigma_b",
                "#1f5ac8",
                |r| r.upper_contact_bending_stress,
                1e-6,
            )],
        ),
    ];
    if w.rigid_impactor {
        specs.retain(|spec| spec.0 != "h-bridge");
    }
    specs
        .into_iter()
        .map(|(id, title, y_label, series)| Chart {
            id: id.into(),
            title: title.into(),
            x_label: "time since impact, s".into(),
            y_label: y_label.into(),
            lines: series
                .into_iter()
                .map(|(name, color, pick, scale)| Line {
                    name: name.into(),
                    color,
                    dashed: false,
                    points: history(steps, pick, scale),
                })
                .collect(),
            marks: Vec::new(),
            shaded: shaded.to_vec(),
            shade_name: format!("in contact (bounces under {} ms apart merged)", crate::results::BOUNCE_GAP * 1e3),
            zoom: true,
        })
        .collect()
}

/// The envelope chart of one beam: its bending and shear envelopes and allowables (MPa), and the
/// paper's points on it as markers (as `envelope_figure` draws them).
fn envelope_chart(id: &str, title: &str, x_label: &str, beam: [&StationEnvelope; 2], marks: Vec<Mark>) -> Chart {
    let mut lines = Vec::new();
    let names = [("largest |bending stress| |M| / W", "#1f5ac8"), ("largest |shear stress| |Q| / A_s", "#288c3c")];
    for (e, (name, color)) in beam.iter().zip(names) {
        if !e.max.is_empty() {
            let points = e.positions.iter().zip(&e.max).map(|(&x, &v)| (x, v * 1e-6)).collect();
            lines.push(Line { name: name.into(), color, dashed: false, points });
        }
    }
    for (e, (name, color)) in
        beam.iter().zip([("allowable bending stress", "#1f5ac8"), ("allowable shear stress", "#288c3c")])
    {
        let points: Vec<(f64, f64)> =
            e.positions.iter().zip(&e.allowable).filter(|(_, &a)| a > 0.0).map(|(&x, &a)| (x, a * 1e-6)).collect();
        if !points.is_empty() {
            lines.push(Line { name: name.into(), color, dashed: true, points });
        }
    }
    Chart {
        id: id.into(),
        title: title.into(),
        x_label: x_label.into(),
        y_label: "stress, MPa".into(),
        lines,
        marks,
        ..Chart::default()
    }
}

/// A section with its heading.
fn section(s: &mut String, id: &str, heading: &str, body: &str) {
    let _ = write!(s, "<section id=\"{id}\"><h2>{}</h2>\n{body}</section>\n", escape(heading));
}

/// The page of one run.
pub fn run_page(p: &RunPage) -> String {
    let doc = p.doc;
    let paper = p.scenario.is_paper();
    let mut body = format!("<h1>beam-impact: {}</h1>\n", escape(&p.title));
    let _ = write!(
        body,
        "<p class=\"note\">beam-impact {}; every number below is the run's JSON document's (its key in the \
         element's data-key, a JSON Pointer); figures drawn from the run's recorded steps.</p>\n<ul>",
        env!("CARGO_PKG_VERSION")
    );
    for line in &p.source {
        let _ = write!(body, "<li>{}</li>", escape(line));
    }
    body.push_str("</ul>\n<table class=\"banner\"><tr><th>numbers trusted (every check that ran passed)</th>");
    body.push_str(&doc_cell(doc, "/quality/trusted"));
    body.push_str(if has_load_cases(doc) {
        "<th>design check (every load case's verdict)</th>"
    } else {
        "<th>design check</th>"
    });
    body.push_str(&doc_cell(doc, "/design/pass"));
    body.push_str("</tr></table>\n");
    if let Some(reasons) = doc.pointer("/quality/reasons").and_then(Value::as_array).filter(|r| !r.is_empty()) {
        body.push_str("<p>Not trusted because:</p><ul>");
        for r in reasons {
            let _ = write!(body, "<li>{}</li>", escape(r.as_str().unwrap_or("")));
        }
        body.push_str("</ul>\n");
    }

    // The scenario, every field.
    let mut scenario = String::new();
    match doc.get("scenario") {
        Some(v) => scenario.push_str(&render("/scenario", v, 0)),
        None => scenario.push_str("<p class=\"note\">(not in the document)</p>"),
    }
    let _ =
        writeln!(scenario, "<details><summary>as TOML</summary><pre>{}</pre></details>", escape(&p.scenario.to_toml()));
    section(
        &mut body,
        "scenario",
        if paper { "Scenario: the paper's (Catipovic, Vladimir, Reljic 2008)" } else { "Scenario" },
        &scenario,
    );

    let words = Wording::of(p.scenario);
    let mut t1 = table1(doc, paper, &words);
    let _ =
        writeln!(t1, "<details><summary>as `run` prints it</summary><pre>{}</pre></details>", escape(&p.comparison));
    section(&mut body, "table1", if paper { "Table 1 beside the paper" } else { "Table 1" }, &t1);

    // Verdicts: the quality checks and the design check per quantity.
    let mut checks = String::new();
    let design_heading = design_heading(doc);
    for (key, heading) in [("quality", "Quality: the checks behind the verdict"), ("design", design_heading.as_str())] {
        if let Some(v) = doc.get(key) {
            let _ = write!(checks, "<h3>{}</h3>\n{}", escape(heading), render(&format!("/{key}"), v, 0));
        }
    }
    section(&mut body, "verdicts", "Verdicts", &checks);

    for (key, heading) in BLOCKS {
        let text = match doc.get(key) {
            Some(v) => render(&format!("/{key}"), v, 0),
            None => format!("<p class=\"note\">This run's document has no <code>{key}</code> block.</p>\n"),
        };
        section(&mut body, key, heading, &text);
    }

    // The envelope along each beam.
    let e = &p.summary.envelope;
    let peaks = &p.summary.peaks;
    let mut env = format!("<p class=\"note\">Envelope {}.</p>\n", escape(&p.envelope_source));
    // The marks are the paper's quantities on its scenario, the run's own peaks on any other.
    let owner = if paper { "paper's " } else { "" };
    let arrestor_marks = vec![
        Mark {
            name: format!(
                "{}sigma_din,a at the {}: {:.1} MPa",
                owner,
                words.first_support,
                peaks.lower_clamp_bending_stress * 1e-6
            ),
            color: "#d7231e",
            at: (0.0, peaks.lower_clamp_bending_stress * 1e-6),
            legend: true,
        },
        Mark {
            name: format!(
                "{}tau_din,a at the {}: {:.1} MPa",
                owner,
                words.first_support,
                peaks.lower_clamp_shear_stress * 1e-6
            ),
            color: "#963caf",
            at: (0.0, peaks.lower_clamp_shear_stress * 1e-6),
            legend: true,
        },
    ];
    let bridge_marks = vec![Mark {
        name: format!(
            "{}sigma_din,b at the contact point ({} m): {:.1} MPa",
            owner,
            shown_number(p.scenario.contact_position),
            peaks.upper_contact_bending_stress * 1e-6
        ),
        color: "#d7231e",
        at: (p.scenario.contact_position, peaks.upper_contact_bending_stress * 1e-6),
        legend: true,
    }];
    if e.lower.bending.max.is_empty() && e.upper.bending.max.is_empty() {
        env.push_str("<p>No envelope to draw.</p>");
    } else {
        let (title, x_label) = if words.first_support == "pin" {
            ("Arrestor: stress envelope from its first support (a pin)", "x from the first support, m")
        } else {
            ("Arrestor: stress envelope from the clamp", "x from the clamp, m")
        };
        env.push_str(&figure(&envelope_chart(
            "envelope-arrestor",
            title,
            x_label,
            [&e.lower.bending, &e.lower.shear],
            arrestor_marks,
        )));
        // A rigid impactor has no stress along it.
        if !words.rigid_impactor {
            env.push_str(&figure(&envelope_chart(
                "envelope-bridge",
                "Bridge: stress envelope from the hinge",
                "x from the hinge, m",
                [&e.upper.bending, &e.upper.shear],
                bridge_marks,
            )));
        }
    }
    section(&mut body, "envelope", "Stress envelope along each beam", &env);

    // Time histories.
    let shaded = crate::replay::figures::shaded_windows(p.summary);
    let mut hist = format!(
        "<p class=\"note\">{} recorded steps; each curve shown as the minimum and maximum of each of {SLICES} equal time \
         slices (so every peak stays visible). Zoom with the mouse wheel, pan by dragging, double-click to reset.</p>\n",
        p.steps.len()
    );
    if p.steps.is_empty() {
        hist.push_str("<p>No recorded steps.</p>");
    } else {
        for chart in histories(p.steps, &shaded, &words) {
            hist.push_str(&figure(&chart));
        }
    }
    section(&mut body, "histories", "Time histories", &hist);

    // Contact windows.
    let mut windows = format!(
        "<p>{} contact windows; merged where the beams separate for less than {} ms (the shading above):</p>\n",
        p.summary.contact_windows.len(),
        crate::results::BOUNCE_GAP * 1e3
    );
    match doc.get("merged_contact_windows") {
        Some(v) => windows.push_str(&render("/merged_contact_windows", v, 0)),
        None => windows.push_str("<p class=\"note\">(not in the document)</p>"),
    }
    section(&mut body, "contact", "Contact windows", &windows);

    // Every other number of the document.
    let mut rest = String::new();
    if let Value::Object(map) = doc {
        for (key, v) in map {
            if SHOWN_ELSEWHERE.contains(&key.as_str()) || BLOCKS.iter().any(|(k, _)| k == key) {
                continue;
            }
            let _ = write!(
                rest,
                "<details><summary>{}</summary>\n{}</details>\n",
                escape(key),
                render(&super::tables::pointer("", key), v, 0)
            );
        }
    }
    if let Some(units) = doc.get("units") {
        let _ = write!(rest, "<details><summary>units</summary>\n{}</details>\n", render("/units", units, 0));
    }
    section(&mut body, "numbers", "Every number of the run's document", &rest);
    shell(&format!("beam-impact: {}", p.title), &body)
}

#[cfg(test)]
mod tests {
    use super::{base64, history, SLICES};
    use crate::results::StepResult;

    /// A history of 100 001 steps with one spike of one step: the decimated history keeps at most
    /// two points per slice, and the spike's value exactly (the min/max of its slice).
    #[test]
    fn a_decimated_history_keeps_its_spike() {
        let steps: Vec<StepResult> = (0..=100_000)
            .map(|k| StepResult {
                time: k as f64 * 1e-5,
                contact_force: if k == 61_234 { -9.7e6 } else { (k as f64 * 1e-3).sin() * 1e5 },
                ..StepResult::default()
            })
            .collect();
        let points = history(&steps, |r| r.contact_force, 1e-3);
        assert!(points.len() <= 2 * SLICES + 2, "{} points", points.len());
        let lowest = points.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        assert_eq!(lowest, -9.7e3);
        assert!(points.iter().any(|p| p.0 == 0.61234));
    }

    /// RFC 4648 section 10's test vectors.
    #[test]
    fn base64_gives_the_rfc_4648_vectors() {
        for (input, output) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(input.as_bytes()), output);
        }
    }
}

/// Whether the document judged load cases (its `load_cases` block is there and not null).
fn has_load_cases(doc: &Value) -> bool {
    doc.get("load_cases").is_some_and(|v| !v.is_null())
}

/// The design check's heading, saying what its `pass` judges (issue 44): with load cases,
/// `design.pass` is every case's verdict, which can fail beside utilisations all <= 1; the
/// heading then gives the plain check's verdict (every utilisation of the block <= 1) and names
/// the cases' as the one `pass` shows.
fn design_heading(doc: &Value) -> String {
    let plain = "Design check per quantity (utilisation = converged peak / allowable)";
    if !has_load_cases(doc) {
        return plain.to_string();
    }
    let mut utilisations = Vec::new();
    if let Some(u) = doc.pointer("/design/utilisation") {
        collect_numbers(u, &mut utilisations);
    }
    let verdict = |pass: bool| if pass { "PASS" } else { "FAIL" };
    let own = verdict(utilisations.iter().all(|u| *u <= 1.0));
    let cases = doc.pointer("/design/pass").and_then(Value::as_bool).map_or("-", verdict);
    format!(
        "{plain}: the plain check (every utilisation <= 1) {own}; its pass is every load case's verdict, {cases} \
         (Design check per load case)"
    )
}

/// Every finite number in `v`, depth first.
fn collect_numbers(v: &Value, out: &mut Vec<f64>) {
    match v {
        Value::Number(n) => out.extend(n.as_f64().filter(|x| x.is_finite())),
        Value::Array(items) => items.iter().for_each(|c| collect_numbers(c, out)),
        Value::Object(map) => map.values().for_each(|c| collect_numbers(c, out)),
        _ => {}
    }
}

#[cfg(test)]
mod design_heading_tests {
    use super::*;

    /// With load cases, a failing case beside green utilisations: the heading gives the plain
    /// check's PASS and names `pass` as every case's FAIL; without cases, the plain heading.
    #[test]
    fn the_design_heading_says_which_verdict_pass_is() {
        let utilisation = serde_json::json!({"lower_clamp_bending_stress": 0.88, "upper_contact_bending_stress": 0.59,
                                             "upper_shear_stress": null});
        let mut doc =
            serde_json::json!({"design": {"pass": false, "utilisation": utilisation}, "load_cases": {"pass": false}});
        let heading = design_heading(&doc);
        assert!(heading.contains("the plain check (every utilisation <= 1) PASS"), "{heading}");
        assert!(heading.contains("its pass is every load case's verdict, FAIL"), "{heading}");
        doc["design"]["utilisation"]["upper_contact_bending_stress"] = serde_json::json!(1.2);
        assert!(design_heading(&doc).contains("(every utilisation <= 1) FAIL"));
        doc["load_cases"] = Value::Null;
        assert_eq!(design_heading(&doc), "Design check per quantity (utilisation = converged peak / allowable)");
    }
}
