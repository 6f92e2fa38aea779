//! Long sub-impact lists (issue 45): a contact that chatters opens hundreds of windows (the lab
//! sphere bouncing on its bar for 0.5 s without damping, gravity raised tenfold so that its flights
//! are short: 139 windows). `run --json` and the log's `answer.json` keep the first 100 (and the
//! largest-force window if later, with its `number`) beside `sub_impacts_total` and
//! `sub_impacts_truncated`; `run`'s text and `report LOG` print the same table ending
//! "... N more".

use std::process::Command;

fn beam_impact_cli() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

/// The lab sphere made to chatter: no damping, 0.5 s, gravity 98.1 m/s^2.
fn chattering_scenario(dir: &std::path::Path) -> std::path::PathBuf {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/lab-sphere.toml")).unwrap();
    let text = text
        .replace("duration = 0.02", "duration = 0.5")
        .replace("damping_ratio = 0.005", "damping_ratio = 0.0")
        .replace("gravity = 9.81", "gravity = 98.1");
    let path = dir.join("chatter.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_chattering_sphere_keeps_the_first_hundred_sub_impacts_and_counts_them_all() {
    let dir = std::env::temp_dir().join(format!("beam-impact-chatter-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scenario = chattering_scenario(&dir);
    let log = dir.join("chatter.mcap");
    let run =
        beam_impact_cli().arg("run").arg(&scenario).arg("--mcap").arg(&log).args(["--json", "-"]).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let doc: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let total = doc["sub_impacts_total"].as_u64().unwrap() as usize;
    assert!(total > 100, "the variant chatters: {total} windows");
    assert_eq!(doc["sub_impacts_truncated"], true);
    let list = doc["sub_impacts"].as_array().unwrap();
    // The first 100, then the largest-force window if it is later (its number beyond 100).
    assert!(list.len() == 100 || (list.len() == 101 && list[100]["number"].as_u64().unwrap() > 100), "{}", list.len());
    let starts: Vec<f64> = list.iter().take(100).map(|w| w["start"].as_f64().unwrap()).collect();
    assert!(starts.windows(2).all(|w| w[0] < w[1]), "the first windows in order");
    // The largest force of all is listed (the document's own peak contact force).
    let listed_largest = list.iter().map(|w| w["peak_force"].as_f64().unwrap()).fold(0.0, f64::max);
    let peak = doc["summary"]["peaks"]["contact_force"].as_f64().unwrap();
    assert!((listed_largest - peak).abs() <= 1e-9 * peak, "{listed_largest} vs the run's peak {peak}");
    // The text: the table's rows, then "... N more".
    let text_run = beam_impact_cli().arg("run").arg(&scenario).arg("--no-mcap").output().unwrap();
    let text = String::from_utf8_lossy(&text_run.stdout).to_string();
    let shown = beam_impact::sub_impacts::SHOWN;
    // The largest-force window is printed after the first rows when it is not among them.
    let largest_apart = usize::from(text.contains("... the largest contact force is window"));
    let more = format!("... {} more", total - shown - largest_apart);
    assert!(text.contains(&format!("sub-impacts: {total} contact windows")) && text.contains(&more), "{text}");
    // `report` replays the same table from the log's answer.json.
    let report = beam_impact_cli().arg("report").arg(&log).arg("--out").arg(dir.join("figures")).output().unwrap();
    assert!(report.status.success(), "{}", String::from_utf8_lossy(&report.stderr));
    let replayed = String::from_utf8_lossy(&report.stdout).to_string();
    let table = |t: &str| -> String {
        t.lines().skip_while(|l| !l.starts_with("sub-impacts:")).take_while(|l| !l.is_empty()).take(shown + 6).collect()
    };
    let (a, b) = (table(&text), table(&replayed));
    assert!(!a.is_empty() && a.contains(&more), "{a}");
    assert!(b.starts_with(&a[..a.find("... ").unwrap()]), "report's table is run's:\n{b}\n---\n{a}");
    assert!(b.contains(&more), "{b}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A logged run and an unlogged one list the same sub-impacts: the log's dense output retakes the
/// step the stop time breaks and leaves it untaken, sub-impacts included (found on
/// examples/vessel-sea.toml, whose last window is open at the stop: it ended 0.304327874 s long
/// unlogged and 0.305083106 s logged, past the stop time).
#[test]
fn a_logged_run_lists_the_same_sub_impacts_as_an_unlogged_one() {
    let dir = std::env::temp_dir().join(format!("beam-impact-subimpact-log-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/vessel-sea.toml");
    let json = |log: Option<&std::path::Path>| -> serde_json::Value {
        let mut cmd = beam_impact_cli();
        cmd.arg("run").arg(example).args(["--json", "-"]);
        match log {
            Some(path) => cmd.arg("--mcap").arg(path),
            None => cmd.arg("--no-mcap"),
        };
        let out = cmd.output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let (logged, unlogged) = (json(Some(&dir.join("sea.mcap"))), json(None));
    let list = |doc: &serde_json::Value| doc["sub_impacts"].as_array().unwrap().clone();
    assert_eq!(list(&logged), list(&unlogged));
    let duration = 3.0;
    for w in list(&logged) {
        let end = w["start"].as_f64().unwrap() + w["duration"].as_f64().unwrap();
        // The stop time to within the rounding of start + duration (a few ulps of 3 s).
        assert!(end <= duration + 1e-12, "a sub-impact ends at {end} s, past the stop time {duration} s");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
