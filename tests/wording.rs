//! Issue 45's labels: a run of the lab sphere (a rigid impactor on a pinned-pinned bar, struck at
//! midspan) and of the deck beam (the bridge on a pinned-pinned beam) says what was measured, in
//! every door: the text of `run`, `report`'s text, the HTML page; `run --json` keeps its field
//! names (only words change). The paper's words ("end deflection", "clamp", "bridge ... hinge")
//! are false there: w_din,a is the contact point's, the first support is a pin, and a rigid
//! impactor is no bridge.

use std::path::PathBuf;
use std::process::Command;

fn beam_impact_cli() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

fn example(name: &str) -> String {
    format!("{}/examples/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("beam-impact-wording-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The words a reader reads in `line`: without names (`lower.clamp_shear_stress`,
/// `lower_clamp_shear_stress`, `--set upper.elements_to_contact=112`) and paths, which keep
/// their spelling whatever the scenario.
fn prose(line: &str) -> String {
    line.split_whitespace().filter(|t| !t.contains(['_', '/', '='])).collect::<Vec<_>>().join(" ")
}

/// Lines of `text` whose prose holds any of `words` (case-sensitive), for the failure message.
fn offending<'a>(text: &'a str, words: &[&str]) -> Vec<&'a str> {
    text.lines().filter(|l| words.iter().any(|w| prose(l).contains(w))).collect()
}

/// The paper's words that are false on a pinned-pinned beam struck at midspan.
const FALSE_ON_TWO_PINS: [&str; 4] = ["clamp", "end deflection", "free end", "Tip deflection"];

/// The words that are false for a rigid impactor (no bridge, no hinge).
const FALSE_FOR_A_MASS: [&str; 2] = ["bridge", "hinge"];

#[test]
fn run_text_of_the_lab_sphere_and_the_deck_beam_has_no_false_wording() {
    let out = beam_impact_cli().args(["run", &example("lab-sphere"), "--no-mcap"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    let words: Vec<&str> = FALSE_ON_TWO_PINS.iter().chain(FALSE_FOR_A_MASS.iter()).copied().collect();
    assert!(offending(&text, &words).is_empty(), "{:#?}", offending(&text, &words));
    assert!(text.contains("w_din,a arrestor at contact") && text.contains("tau_din,a pin shear"), "{text}");
    assert!(text.contains("impactor resting on the arrestor"), "{text}");
    // The deck beam is struck by the bridge: "bridge" and its hinge are true there, the clamp is not.
    let out = beam_impact_cli().args(["run", &example("deck-beam-supports"), "--no-mcap"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(offending(&text, &FALSE_ON_TWO_PINS).is_empty(), "{:#?}", offending(&text, &FALSE_ON_TWO_PINS));
    assert!(text.contains("sigma_din,b bridge bending, contact"), "the bridge's row stays: {text}");
}

#[test]
fn run_json_of_the_lab_sphere_keeps_its_field_names_and_changes_only_words() {
    let out = beam_impact_cli().args(["run", &example("lab-sphere"), "--no-mcap", "--json", "-"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in ["lower_tip_deflection", "lower_clamp_bending_stress", "upper_contact_bending_stress"] {
        assert!(doc["summary"]["peaks"].get(key).is_some(), "summary.peaks.{key} stays");
    }
    assert!(doc["summary"]["energy_method"].get("bridge_bending_stress").is_some());
    let note = doc["dynamic_amplification"]["note"].as_str().unwrap();
    assert!(note.contains("impactor resting on the arrestor") && !note.contains("bridge"), "{note}");
    for reason in doc["quality"]["reasons"].as_array().unwrap() {
        let r = reason.as_str().unwrap();
        assert!(offending(r, &["clamp", "bridge", "hinge"]).is_empty(), "{r}");
    }
}

#[test]
fn report_and_html_of_the_lab_sphere_have_no_false_wording() {
    let dir = scratch("html");
    let (log, html) = (dir.join("sphere.mcap"), dir.join("sphere.html"));
    let run = beam_impact_cli()
        .args(["run", &example("lab-sphere"), "--mcap"])
        .arg(&log)
        .arg("--html")
        .arg(&html)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let page = std::fs::read_to_string(&html).unwrap();
    // The page renders the JSON document, whose keys keep their names (lower_clamp_...): the
    // labels a reader sees are checked, not the keys.
    for false_label in [
        "arrestor end deflection",
        "Tip deflection",
        "Clamp stresses",
        "at the clamp",
        "from the clamp",
        "sigma_din,b bridge bending",
        "Bridge: stress envelope",
        "bridge deflection at the contact",
        "Bridge stress at the contact",
        "paper&#39;s",
        "paper's",
    ] {
        assert!(!page.contains(false_label), "the page says {false_label:?}");
    }
    assert!(page.contains("arrestor deflection at the contact"), "the page names the measured point");
    assert!(page.contains("tau_din,a pin shear stress"), "the page names the pin");
    let report = beam_impact_cli().arg("report").arg(&log).arg("--out").arg(dir.join("figures")).output().unwrap();
    assert!(report.status.success(), "{}", String::from_utf8_lossy(&report.stderr));
    let text = String::from_utf8_lossy(&report.stdout);
    let words: Vec<&str> = FALSE_ON_TWO_PINS.iter().chain(FALSE_FOR_A_MASS.iter()).copied().collect();
    assert!(offending(&text, &words).is_empty(), "{:#?}", offending(&text, &words));
    assert!(text.contains("contact-point deflection w_din,a") && text.contains("pin shear stress"), "{text}");
    std::fs::remove_dir_all(&dir).ok();
}
