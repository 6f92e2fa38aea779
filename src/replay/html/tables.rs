//! Any block of a run's JSON as HTML tables, built from its keys and numbers alone, so that a block
//! the page does not know by name (`load_cases`, `dynamic_amplification`, `fatigue`, ...) appears
//! without further work. Every number's cell carries its place in the document as a JSON Pointer
//! (RFC 6901; the keys hold dots, `lower.clamp_bending_stress`) in `data-key` and the document's own
//! decimal in `data-value` (serde_json's shortest round trip), so a reader (the browser test) can
//! compare the page with the run's `--json` document number for number. Verdicts are coloured:
//! a `pass` or `trusted` that is false, a utilisation above 1.

use std::fmt::Write as _;

use serde_json::Value;

use super::escape::escape;

/// Deepest nesting rendered; below it a block is shown as its JSON text.
const DEPTH: usize = 8;

/// `base` with `key` appended as a JSON Pointer reference token (`~` as `~0`, `/` as `~1`).
pub fn pointer(base: &str, key: &str) -> String {
    format!("{base}/{}", key.replace('~', "~0").replace('/', "~1"))
}

/// A number as the page shows it: five significant digits, in scientific form outside 1e-3..1e5.
pub fn shown_number(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if !v.is_finite() {
        return format!("{v}");
    }
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        return format!("{v:.4e}");
    }
    let decimals = (4 - a.log10().floor() as i32).clamp(0, 8) as usize;
    format!("{v:.decimals$}")
}

/// Whether `ptr` names a verdict (its last key `pass` or `trusted`).
fn is_verdict(ptr: &str) -> bool {
    matches!(ptr.rsplit('/').next(), Some("pass" | "trusted"))
}

/// One value's cell, with its `data-key` and `data-value` (text as escaped text).
pub fn cell(ptr: &str, v: &Value) -> String {
    let key = escape(ptr);
    match v {
        Value::Number(n) => {
            let x = n.as_f64().unwrap_or(f64::NAN);
            let class = if ptr.contains("utilisation") && x > 1.0 {
                "num fail"
            } else if ptr.contains("utilisation") {
                "num pass"
            } else {
                "num"
            };
            format!("<td class=\"{class}\" data-key=\"{key}\" data-value=\"{n}\">{}</td>", shown_number(x))
        }
        Value::Bool(b) => {
            let (class, text) = match (is_verdict(ptr), b) {
                (true, true) => ("verdict pass", "PASS"),
                (true, false) => ("verdict fail", "FAIL"),
                (false, b) => ("", if *b { "true" } else { "false" }),
            };
            let text = if ptr.ends_with("/trusted") {
                if *b {
                    "TRUSTED"
                } else {
                    "NOT TRUSTED"
                }
            } else {
                text
            };
            format!("<td class=\"{class}\" data-key=\"{key}\" data-value=\"{b}\">{text}</td>")
        }
        Value::Null => format!("<td class=\"none\" data-key=\"{key}\" data-value=\"null\">-</td>"),
        Value::String(t) => format!("<td class=\"text\">{}</td>", escape(t)),
        other => format!("<td class=\"text\"><code>{}</code></td>", escape(&other.to_string())),
    }
}

fn is_scalar(v: &Value) -> bool {
    !matches!(v, Value::Object(_) | Value::Array(_))
}

/// The scalars under `v`, flattened: (dotted display name, pointer, value); arrays of scalars kept
/// whole (one cell of JSON text).
fn flatten(ptr: &str, name: &str, v: &Value, depth: usize, out: &mut Vec<(String, String, Value)>) {
    let join = |k: &str| if name.is_empty() { k.to_string() } else { format!("{name}.{k}") };
    match v {
        Value::Object(map) if depth < DEPTH => {
            for (k, child) in map {
                flatten(&pointer(ptr, k), &join(k), child, depth + 1, out);
            }
        }
        Value::Array(items) if depth < DEPTH && items.iter().any(|i| !is_scalar(i)) => {
            for (k, child) in items.iter().enumerate() {
                flatten(&pointer(ptr, &k.to_string()), &join(&k.to_string()), child, depth + 1, out);
            }
        }
        other => out.push((name.to_string(), ptr.to_string(), other.clone())),
    }
}

/// A table of rows: `rows` each (name, pointer, value) pairs; columns the union of the names in
/// first-seen order, the row's label in the first column.
fn grid(labels: &[String], rows: &[Vec<(String, String, Value)>]) -> String {
    let mut columns: Vec<&str> = Vec::new();
    for row in rows {
        for (name, _, _) in row {
            if !columns.contains(&name.as_str()) {
                columns.push(name);
            }
        }
    }
    let mut s = String::from("<table class=\"grid\"><thead><tr><th></th>");
    for c in &columns {
        let _ = write!(s, "<th>{}</th>", escape(c));
    }
    s.push_str("</tr></thead><tbody>");
    for (label, row) in labels.iter().zip(rows) {
        let _ = write!(s, "<tr><th>{}</th>", escape(label));
        for c in &columns {
            match row.iter().find(|(n, _, _)| n == c) {
                Some((_, ptr, v)) => s.push_str(&cell(ptr, v)),
                None => s.push_str("<td></td>"),
            }
        }
        s.push_str("</tr>");
    }
    s.push_str("</tbody></table>\n");
    s
}

/// `v` (at `ptr`) as tables: an object's scalars as one name/value table, an object or array of
/// objects as a grid (a row each, columns their flattened keys), other children under their own
/// heading.
pub fn render(ptr: &str, v: &Value, depth: usize) -> String {
    let mut s = String::new();
    let children: Vec<(String, &Value)> = match v {
        Value::Object(map) => map.iter().map(|(k, c)| (k.clone(), c)).collect(),
        Value::Array(items) => items.iter().enumerate().map(|(k, c)| (k.to_string(), c)).collect(),
        scalar => return format!("<table class=\"pairs\"><tr>{}</tr></table>\n", cell(ptr, scalar)),
    };
    if children.is_empty() {
        return "<p class=\"note\">(empty)</p>\n".into();
    }
    if depth >= DEPTH {
        return format!("<pre>{}</pre>\n", escape(&v.to_string()));
    }
    // Every child an object (or array) of scalars, or all objects: one grid.
    let objects = children.iter().filter(|(_, c)| matches!(c, Value::Object(_))).count();
    let all_objects = children.iter().all(|(_, c)| matches!(c, Value::Object(_) | Value::Null));
    if all_objects && objects > 1 {
        let labels: Vec<String> = children.iter().map(|(k, _)| k.clone()).collect();
        let rows: Vec<Vec<(String, String, Value)>> = children
            .iter()
            .map(|(k, c)| {
                let mut row = Vec::new();
                flatten(&pointer(ptr, k), "", c, depth + 1, &mut row);
                row
            })
            .collect();
        if rows.iter().map(Vec::len).sum::<usize>() <= 400 * rows.len().max(1) {
            return grid(&labels, &rows);
        }
    }
    let scalars: Vec<&(String, &Value)> = children
        .iter()
        .filter(|(_, c)| is_scalar(c) || matches!(c, Value::Array(a) if a.iter().all(is_scalar)))
        .collect();
    if !scalars.is_empty() {
        s.push_str("<table class=\"pairs\"><tbody>");
        for (k, c) in &scalars {
            let _ = write!(s, "<tr><th>{}</th>{}</tr>", escape(k), cell(&pointer(ptr, k), c));
        }
        s.push_str("</tbody></table>\n");
    }
    for (k, c) in
        children.iter().filter(|(_, c)| !(is_scalar(c) || matches!(c, Value::Array(a) if a.iter().all(is_scalar))))
    {
        let _ = write!(
            s,
            "<div class=\"block\"><h4>{}</h4>\n{}</div>\n",
            escape(k),
            render(&pointer(ptr, k), c, depth + 1)
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pointer_escapes_tilde_and_slash_and_keeps_dots() {
        assert_eq!(pointer("/design", "lower.clamp_bending_stress"), "/design/lower.clamp_bending_stress");
        assert_eq!(pointer("", "a/b~c"), "/a~1b~0c");
    }

    #[test]
    fn every_number_carries_its_pointer_and_its_exact_decimal() {
        let doc = serde_json::json!({"utilisation": {"a": 0.8797438844527831, "b": 1.5}, "pass": false});
        let html = render("", &doc, 0);
        assert!(html.contains("data-key=\"/utilisation/a\" data-value=\"0.8797438844527831\""), "{html}");
        assert!(html.contains("class=\"num fail\" data-key=\"/utilisation/b\""), "{html}");
        assert!(html.contains("data-key=\"/pass\" data-value=\"false\">FAIL"), "{html}");
    }

    #[test]
    fn an_array_of_objects_is_one_grid_with_the_union_of_their_keys() {
        let doc = serde_json::json!([{"name": "<script>", "u": {"x": 1.0}}, {"name": "b", "v": 2.0}]);
        let html = render("/cases", &doc, 0);
        assert!(html.contains("<th>u.x</th>") && html.contains("<th>v</th>"), "{html}");
        assert!(html.contains("data-key=\"/cases/1/v\""));
        assert!(html.contains("&lt;script&gt;") && !html.contains("<script>"));
    }

    #[test]
    fn numbers_show_five_significant_digits() {
        assert_eq!(shown_number(0.8797438844527831), "0.87974");
        assert_eq!(shown_number(468754498.2144521), "4.6875e8");
        assert_eq!(shown_number(12.5), "12.500");
    }
}
