//! Issue 44's leftovers in `beam-impact sweep`: `--fatigue` adds each row's fatigue (the worst
//! station's damage of one impact, the life, where it is), the same numbers as `run --json`'s
//! `fatigue` block of the row's scenario; without it the columns stay as they were; and a
//! scenario with `[[load_cases]]` prints per design quantity the governing case and row.

use std::path::Path;
use std::process::Command;

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

fn example(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name).to_string_lossy().into_owned()
}

fn run_ok(command: &mut Command) -> String {
    let out = command.output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// `run --json`'s document of the load-cases example at `drop_height`, with 100 impacts a year.
fn run_document(dir: &Path, drop_height: &str) -> serde_json::Value {
    let path = dir.join(format!("run-{drop_height}.json"));
    run_ok(beam_impact().args(["run", &example("load-cases.toml"), "--no-mcap", "--json"]).arg(&path).args([
        "--set",
        &format!("drop_height={drop_height}"),
        "--set",
        "fatigue.events_per_year=100",
    ]));
    json(&path)
}

/// Each row's fatigue columns are the `fatigue` block of `run --json` for the row's scenario, to
/// the bit (a row is the run's printed rung with its stations' turning points kept: the same
/// histories, the same rainflow count, the same sum); the life is 1 / (damage x 100).
#[test]
fn a_fatigue_sweeps_rows_equal_the_runs_fatigue_to_the_bit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let heights = ["0.3", "0.6"];
    run_ok(
        beam_impact()
            .args(["sweep", &example("load-cases.toml"), "--fatigue", "--vary"])
            .arg(format!("drop_height={}", heights.join(",")))
            .args(["--set", "fatigue.events_per_year=100", "--out"])
            .arg(d.join("rows.csv"))
            .arg("--json")
            .arg(d.join("rows.json")),
    );
    let rows = json(&d.join("rows.json"));
    for (row, h) in rows.as_array().unwrap().iter().zip(heights) {
        let doc = run_document(d, h);
        let worst = ["lower", "upper"]
            .iter()
            .map(|b| &doc["fatigue"]["worst"][b])
            .max_by(|a, b| a["damage"].as_f64().unwrap().total_cmp(&b["damage"].as_f64().unwrap()))
            .unwrap();
        assert_eq!(row["fatigue.damage"].as_f64(), worst["damage"].as_f64(), "drop {h}");
        assert_eq!(row["fatigue.beam"], worst["beam"], "drop {h}");
        assert_eq!(row["fatigue.position"].as_f64(), worst["position"].as_f64(), "drop {h}");
        assert_eq!(row["fatigue.life"].as_f64(), doc["fatigue"]["life_years"].as_f64(), "drop {h}");
        let damage = row["fatigue.damage"].as_f64().unwrap();
        // 1 / (d x 100): one division and one product, to round-off.
        assert!((row["fatigue.life"].as_f64().unwrap() * damage * 100.0 - 1.0).abs() < 1e-12);
    }
    // The CSV has the same columns as the JSON, the fatigue ones after load_cases.utilisation.
    let csv = std::fs::read_to_string(d.join("rows.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let at = header.iter().position(|c| *c == "load_cases.utilisation").unwrap();
    assert_eq!(header[at + 1..at + 5], ["fatigue.damage", "fatigue.life", "fatigue.beam", "fatigue.position"]);
    assert_eq!(header[at + 5], "quality.trusted");
    // The units sidecar names them.
    let units = json(&d.join("rows.units.json")).to_string();
    assert!(units.contains("\"fatigue.life\"") && units.contains("\"years\""), "{units}");
}

/// Without `--fatigue` a sweep of one varied field has its 63 columns, none of them fatigue's.
#[test]
fn without_fatigue_the_columns_stay_as_they_were() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rows.csv");
    run_ok(beam_impact().args(["sweep", "--vary", "drop_height=0.3", "--set", "duration=0.05", "--out"]).arg(&out));
    let csv = std::fs::read_to_string(&out).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert_eq!(header.len(), 63);
    assert!(!header.iter().any(|c| c.starts_with("fatigue.")));
}

/// A row that fails has empty fatigue cells (JSON nulls) and its error, every CSV row has the
/// header's cells (the error quoted where it holds a comma, RFC 4180), and the sweep goes on.
#[test]
fn a_failed_rows_fatigue_cells_are_empty() {
    let dir = tempfile::tempdir().unwrap();
    let (out, json_out) = (dir.path().join("rows.csv"), dir.path().join("rows.json"));
    run_ok(
        beam_impact()
            .args(["sweep", "--fatigue", "--vary", "drop_height=-1,0.3", "--set", "duration=0.05", "--out"])
            .arg(&out)
            .arg("--json")
            .arg(&json_out),
    );
    // Cells split at commas outside quotes.
    let split = |line: &str| -> Vec<String> {
        let (mut cells, mut cell, mut quoted) = (Vec::new(), String::new(), false);
        for ch in line.chars() {
            match ch {
                '"' => quoted = !quoted,
                ',' if !quoted => cells.push(std::mem::take(&mut cell)),
                c => cell.push(c),
            }
        }
        cells.push(cell);
        cells
    };
    let csv = std::fs::read_to_string(&out).unwrap();
    let mut lines = csv.lines();
    let header = split(lines.next().unwrap());
    let cells: Vec<Vec<String>> = lines.map(split).collect();
    assert!(cells.iter().all(|c| c.len() == header.len()), "every row has the header's cells");
    let damage = header.iter().position(|c| c == "fatigue.damage").unwrap();
    assert_eq!(cells[0][damage], "", "the refused row");
    assert!(cells[1][damage].parse::<f64>().unwrap() > 0.0, "{:?}", cells[1]);
    let rows = json(&json_out);
    assert!(rows[0]["fatigue.damage"].is_null() && rows[0]["fatigue.beam"].is_null());
    assert!(rows[0]["error"].as_str().unwrap().contains("drop_height"), "{}", rows[0]["error"]);
    assert!(rows[1]["fatigue.damage"].as_f64().unwrap() > 0.0);
}

/// The printed governing case per quantity is, for each quantity, the case and row of the
/// largest governing utilisation among the rows' own `run --json` documents (their
/// `load_cases.governing`), the first row on a tie; printed to three decimals.
#[test]
fn the_sweep_prints_each_quantitys_governing_case_and_row() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let heights = ["0.3", "0.6"];
    let text = run_ok(
        beam_impact()
            .args(["sweep", &example("load-cases.toml"), "--vary"])
            .arg(format!("drop_height={}", heights.join(",")))
            .arg("--out")
            .arg(d.join("rows.csv"))
            .arg("--html")
            .arg(d.join("rows.html")),
    );
    // The page shows the same lines, as text.
    let page = std::fs::read_to_string(d.join("rows.html")).unwrap();
    assert!(page.contains("governing load case per quantity (the largest factored utilisation over 2 rows)"));
    let docs: Vec<serde_json::Value> = heights.iter().map(|h| run_document(d, h)).collect();
    let governing = text.split("governing load case per quantity").nth(1).expect(&text);
    let quantities: Vec<&String> = docs[0]["load_cases"]["governing"].as_object().unwrap().keys().collect();
    assert!(quantities.len() >= 3, "{quantities:?}");
    for q in quantities {
        let mut best: Option<(usize, &str, f64)> = None;
        for (k, doc) in docs.iter().enumerate() {
            let g = &doc["load_cases"]["governing"][q.as_str()];
            let u = g["utilisation"].as_f64().unwrap();
            if best.is_none_or(|b| u > b.2) {
                best = Some((k + 1, g["case"].as_str().unwrap(), u));
            }
        }
        let (row, case, u) = best.unwrap();
        let verdict = if u <= 1.0 { "PASS" } else { "FAIL" };
        let line = governing
            .lines()
            .find(|l| l.trim_start().starts_with(&format!("{q} ")))
            .unwrap_or_else(|| panic!("no line for {q}: {text}"));
        let expected = format!("\"{case}\" at row {row} (drop_height={}): {u:.3} {verdict}", heights[row - 1]);
        assert!(line.ends_with(&expected), "{line} vs {expected}");
    }
}

/// A scenario without load cases and a sweep without `--fatigue` print no such lines.
#[test]
fn no_cases_and_no_fatigue_print_nothing_more() {
    let dir = tempfile::tempdir().unwrap();
    let text = run_ok(
        beam_impact()
            .args(["sweep", "--vary", "drop_height=0.3", "--set", "duration=0.05", "--out"])
            .arg(dir.path().join("rows.csv")),
    );
    assert!(!text.contains("governing") && !text.contains("fatigue"), "{text}");
}
