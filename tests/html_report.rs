//! The report that opens in a browser (issue 44 item 4; `src/replay/html/`), without a browser
//! (tests/python/test_html_report.py opens it in Chromium): the page of the paper scenario is one
//! file under 5 MB with every section and figure, its only script the zoom script its CSP allows
//! by hash, no attribute that could fetch anything; every number of the run's document is on the
//! page with its JSON Pointer and its exact decimal; the blocks other parts add to the document
//! (load cases, DAF, fatigue) appear as tables from a hand-made document that has them; a
//! `<script>` in a load case's name, a file name or a title stays text; a sweep's page has a chart
//! per peak with its verdict colours. No tolerances: the page shows the document's own decimals.

use std::process::Command;
use std::sync::atomic::AtomicBool;

use beam_impact::answer::{Answer, Options};
use beam_impact::record::MemoryRecorder;
use beam_impact::replay::html::charts::ZOOM_SCRIPT;
use beam_impact::replay::html::escape::escape;
use beam_impact::replay::html::page::{base64, run_page, RunPage};
use beam_impact::replay::html::sweep_page::{sweep_page, SweepPage, FAIL, PASS, UNTRUSTED};
use beam_impact::results::StepResult;
use beam_impact::{one_run, Scenario};
use serde_json::{json, Value};
use sha2::{Digest, Sha256};

/// The paper scenario run in memory: its answer and every step.
fn paper_run() -> (Scenario, Answer, Vec<StepResult>) {
    let scenario = Scenario::paper();
    let mut recorder = MemoryRecorder::default();
    let answer = one_run::run(&scenario, &mut recorder, Options::default(), &AtomicBool::new(false)).unwrap();
    (scenario, answer, recorder.steps)
}

/// The page of `doc` for the paper run, titled `title`.
fn page_of(run: &(Scenario, Answer, Vec<StepResult>), doc: &Value, title: &str) -> String {
    let (scenario, answer, steps) = run;
    run_page(&RunPage {
        title: title.into(),
        source: vec![format!("the log {title}.mcap")],
        doc,
        scenario,
        summary: &answer.summary,
        steps,
        envelope_source: "of the run".into(),
        comparison: beam_impact::compare::comparison(&answer.summary, true),
    })
}

/// Every number of `v` not inside an array of scalars (shown as JSON text), with its pointer.
fn numbers(ptr: &str, v: &Value, out: &mut Vec<(String, String)>) {
    match v {
        Value::Object(map) => {
            for (k, c) in map {
                numbers(&beam_impact::replay::html::tables::pointer(ptr, k), c, out);
            }
        }
        Value::Array(items) if items.iter().any(|i| i.is_object() || i.is_array()) => {
            for (k, c) in items.iter().enumerate() {
                numbers(&format!("{ptr}/{k}"), c, out);
            }
        }
        Value::Number(n) => out.push((ptr.to_string(), n.to_string())),
        _ => {}
    }
}

/// The blocks issue 44's other items add to a run's document, made by hand.
fn hand_made_blocks(doc: &mut Value) {
    doc["load_cases"] = json!([
        {"name": "<script>alert(1)</script> in service (example factors)", "dynamic_factor": 1.0, "static_factor": 1.0,
         "allowable_factor": 1.0, "utilisation": {"lower.clamp_bending_stress": 0.8797, "upper.contact_bending_stress": 0.5925},
         "pass": true, "governing": "lower.clamp_bending_stress"},
        {"name": "emergency (example factors)", "dynamic_factor": 1.3, "static_factor": 1.1, "allowable_factor": 1.0,
         "utilisation": {"lower.clamp_bending_stress": 1.1437, "upper.contact_bending_stress": 0.7702},
         "pass": false, "governing": "lower.clamp_bending_stress"}
    ]);
    doc["governing"] = json!({"lower.clamp_bending_stress": "emergency (example factors)"});
    doc["dynamic_amplification"] = json!({
        "static": {"lower.clamp_bending_stress": 1.21e8, "lower.tip_deflection": 0.171},
        "daf": {"lower.clamp_bending_stress": 3.874, "lower.tip_deflection": 3.843},
        "energy_method": 3.67, "crane_psi": {"value": 2.31, "v": 2.589, "k": 756510.4, "m": 24124.0}
    });
    doc["fatigue"] = json!({
        "curve": "D (DNV-RP-C203 2016 Table 2-1, in air)",
        "hot_spots": [
            {"beam": "arrestor", "name": "clamp", "position": 0.0, "damage": 2.5e-6, "cycles": 41.5, "largest_range": 9.2e8},
            {"beam": "bridge", "name": "contact", "position": 13.0, "damage": 7.1e-7, "cycles": 63.0, "largest_range": 5.6e8}
        ],
        "worst": {"beam": "arrestor", "name": "clamp", "damage": 2.5e-6},
        "life_years": 1096.0
    });
}

#[test]
fn the_paper_page_is_one_file_under_5_mb_with_every_section_and_figure() {
    let run = paper_run();
    let doc = beam_impact::run_document::document(&run.0, &run.1, 0.1).unwrap();
    let page = page_of(&run, &doc, "run of the paper scenario");
    assert!(page.len() < 5_000_000, "{} bytes", page.len());
    for id in [
        "scenario",
        "table1",
        "verdicts",
        "load_cases",
        "dynamic_amplification",
        "fatigue",
        "envelope",
        "histories",
        "contact",
        "numbers",
    ] {
        assert!(page.contains(&format!("<section id=\"{id}\">")), "section {id}");
    }
    for id in ["envelope-arrestor", "envelope-bridge", "h-deflection", "h-force", "h-clamp", "h-bridge"] {
        assert!(page.contains(&format!("<figure class=\"chart\" id=\"{id}\">")), "figure {id}");
    }
    assert_eq!(page.matches("data-zoom=\"x\"").count(), 4, "the four time histories zoom");
    // One script, the zoom script, allowed by its hash; nothing that could fetch.
    assert_eq!(page.matches("<script").count(), 1);
    assert!(page.contains(&format!("<script>{ZOOM_SCRIPT}</script>")));
    let hash = base64(&Sha256::digest(ZOOM_SCRIPT.as_bytes()));
    assert!(page.contains(&format!("default-src 'none'; script-src 'sha256-{hash}'")));
    for fetching in [" src=", " href=", "@import", "url(http", "<link", "<iframe", "<img", "<object", "<embed"] {
        assert!(!page.contains(fetching), "the page holds {fetching}");
    }
    // Table 1 beside the paper: the paper's FEM column.
    assert!(page.contains("<td class=\"num\">492.000</td>"));
}

#[test]
fn every_number_of_the_run_document_is_on_the_page_with_its_pointer() {
    let run = paper_run();
    let doc = beam_impact::run_document::document(&run.0, &run.1, 0.1).unwrap();
    let page = page_of(&run, &doc, "run");
    let mut all = Vec::new();
    numbers("", &doc, &mut all);
    let all: Vec<_> =
        all.into_iter().filter(|(p, _)| !p.starts_with("/scenario_as_given") && !p.starts_with("/units")).collect();
    assert!(all.len() > 200, "{} numbers", all.len());
    for (ptr, value) in &all {
        assert!(page.contains(&format!("data-key=\"{}\" data-value=\"{value}\"", escape(ptr))), "{ptr} = {value}");
    }
}

#[test]
fn the_load_case_daf_and_fatigue_blocks_of_a_hand_made_document_appear_as_tables() {
    let run = paper_run();
    let mut doc = beam_impact::run_document::document(&run.0, &run.1, 0.1).unwrap();
    hand_made_blocks(&mut doc);
    let page = page_of(&run, &doc, "run");
    for (ptr, value) in [
        ("/load_cases/1/utilisation/lower.clamp_bending_stress", "1.1437"),
        ("/load_cases/0/dynamic_factor", "1.0"),
        ("/dynamic_amplification/daf/lower.tip_deflection", "3.843"),
        ("/dynamic_amplification/crane_psi/value", "2.31"),
        ("/fatigue/hot_spots/1/damage", "7.1e-7"),
        ("/fatigue/life_years", "1096.0"),
    ] {
        assert!(page.contains(&format!("data-key=\"{ptr}\" data-value=\"{value}\"")), "{ptr}");
    }
    assert!(page.contains("class=\"num fail\" data-key=\"/load_cases/1/utilisation/lower.clamp_bending_stress\""));
    assert!(page.contains("data-key=\"/load_cases/1/pass\" data-value=\"false\">FAIL"));
    assert!(page.contains("<td class=\"text\">emergency (example factors)</td>"), "the governing case by name");
    assert!(!page.contains("has no <code>load_cases</code> block"));
    // The name with a script tag stays text.
    assert!(page.contains("&lt;script&gt;alert(1)&lt;/script&gt; in service"));
    assert_eq!(page.matches("<script").count(), 1);
}

#[test]
fn a_title_or_file_name_with_a_script_tag_stays_text() {
    let run = paper_run();
    let doc = beam_impact::run_document::document(&run.0, &run.1, 0.1).unwrap();
    let page = page_of(&run, &doc, "<script>alert('x')</script>");
    assert!(page.contains("<title>beam-impact: &lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;</title>"));
    assert!(page.contains("the log &lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;.mcap"));
    assert_eq!(page.matches("<script").count(), 1);
}

#[test]
fn the_sweep_page_draws_a_chart_per_peak_with_its_verdict_colours() {
    let axes = beam_impact::studies::sweep::parse_axes(&["drop_height=0.5,1,2".to_string()]).unwrap();
    let columns = beam_impact::studies::sweep::column_units(&axes);
    let named = columns.len() - beam_impact::vocabulary::sweep_former_names().len();
    let row = |h: f64, stress: f64, trusted: bool, pass: bool| {
        json!({"drop_height": h, "peak.lower.clamp_bending_stress": stress, "utilisation.lower.bending_stress": stress / 5.33e8,
               "quality.trusted": trusted, "design.pass": pass, "error": ""})
    };
    let rows = json!([row(0.5, 3.1e8, true, true), row(1.0, 4.7e8, false, true), row(2.0, 6.2e8, true, false),
                      {"drop_height": 3.0, "quality.trusted": null, "error": "<script>alert(1)</script>"}]);
    let page = sweep_page(&SweepPage {
        title: "sweep of <b>x</b>.toml".into(),
        source: Vec::new(),
        axes: vec!["drop_height".into()],
        columns: columns.into_iter().take(named).collect(),
        rows: &rows,
    });
    assert_eq!(page.matches("<figure class=\"chart\"").count(), 2, "the two columns with numbers");
    for colour in [PASS, UNTRUSTED, FAIL] {
        assert!(page.contains(&format!("fill=\"{colour}\"")), "{colour}");
    }
    assert!(page.contains("data-key=\"/2/peak.lower.clamp_bending_stress\" data-value=\"620000000.0\""));
    assert!(
        page.contains("&lt;script&gt;alert(1)&lt;/script&gt;") && page.contains("sweep of &lt;b&gt;x&lt;/b&gt;.toml")
    );
    assert_eq!(page.matches("<script").count(), 1);
}

#[test]
fn run_html_without_a_log_is_refused_with_exit_code_2() {
    let out = Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .args(["run", "--no-mcap", "--html", "never.html"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(!std::path::Path::new("never.html").exists());
}

#[test]
fn report_html_of_a_file_that_is_not_a_log_is_one_line_and_writes_nothing() {
    let dir = std::env::temp_dir().join(format!("html-report-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let not_a_log = dir.join("not-a-log.mcap");
    std::fs::write(&not_a_log, b"hello").unwrap();
    let html = dir.join("page.html");
    let out = Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .args(["report", not_a_log.to_str().unwrap(), "--html", html.to_str().unwrap()])
        .output()
        .unwrap();
    assert_ne!(out.status.code(), Some(0));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr).trim().lines().count(),
        1,
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!html.exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// Nothing in a log is trusted (issue 9): the page of every log of the committed corpus, of the
/// crafted ones and of seeded mutations of a real log is made or refused with an error, never a
/// panic; a page made holds the one script and no number a browser cannot draw.
#[test]
fn the_page_of_a_hostile_log_is_made_or_refused_without_panic() {
    use crate::fuzz_support::{corpus_files, crafted_logs, iterations, mutate_log, real_log_bytes, Rng};
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("log.mcap");
    let real = real_log_bytes();
    let mut rng = Rng(44);
    let mutations: Vec<(String, Vec<u8>)> =
        (0..iterations(200)).map(|i| (format!("mutation {i}"), mutate_log(&real, &mut rng))).collect();
    let (mut made, mut refused) = (0, 0);
    for (name, bytes) in
        corpus_files("logs").into_iter().chain(crafted_logs()).chain([("real".into(), real.clone())]).chain(mutations)
    {
        std::fs::write(&path, &bytes).unwrap();
        let outcome = std::panic::catch_unwind(|| beam_impact::replay::html::log_page(&path));
        match outcome {
            Err(_) => panic!("{name}: the page panicked"),
            Ok(Ok(page)) => {
                made += 1;
                assert_eq!(page.matches("<script").count(), 1, "{name}");
                for svg in page.split("<svg").skip(1).map(|s| s.split("</svg>").next().unwrap_or("")) {
                    // The drawing without its tooltips (text, which may say "NaN").
                    let drawn: String =
                        svg.split("<title>").map(|part| part.split("</title>").last().unwrap_or("")).collect();
                    assert!(
                        !drawn.contains("NaN") && !drawn.contains("inf"),
                        "{name}: a number the browser cannot draw"
                    );
                }
            }
            Ok(Err(e)) => {
                refused += 1;
                assert_eq!(e.to_string().lines().count(), 1, "{name}: {e}");
            }
        }
    }
    assert!(made > 0 && refused > 0, "{made} made, {refused} refused");
}
