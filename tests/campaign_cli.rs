//! Issue 43: `beam-impact campaign`: events drawn across a sea state's records, one row each, the
//! same rows on any number of threads; statistics that agree with the rows they summarise; the
//! operability table over a grid, a breaking sea refused as a cell; bad input in one line; Ctrl-C
//! keeps the rows run so far.

use std::path::Path;
use std::process::Command;

use crate::sea_scenario::folder;

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

/// The fixture's sea (Hs 1 m, Tp 8 s, seed 7) with half-second runs: 10 ms or so an event.
fn scenario(extra: &str) -> String {
    format!(
        "duration = 0.5\n{extra}\n[sea]\nsignificant_wave_height = 1.0\npeak_period = 8.0\nseed = 7\n\
         raos = \"raos.csv\"\nhinge_point = [-10.0, 0.0, 8.0]\nclamp_point = [15.0, 0.0, 8.0]\n"
    )
}

fn campaign(dir: &Path, args: &[&str]) -> std::process::Output {
    beam_impact().arg("campaign").arg("s.toml").args(args).current_dir(dir).output().unwrap()
}

/// The CSV's rows as maps of column to text.
fn rows(path: &Path) -> Vec<std::collections::BTreeMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(str::to_string).collect();
    lines.map(|l| header.iter().cloned().zip(l.split(',').map(str::to_string)).collect()).collect()
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn a_campaign_writes_the_same_rows_on_one_thread_and_on_two() {
    let dir = folder(&scenario(""));
    let d = dir.path();
    for (jobs, out) in [("1", "one.csv"), ("2", "two.csv")] {
        let o = campaign(d, &["--events", "9", "--seeds", "3", "--record-length", "600", "--jobs", jobs, "--out", out]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let (one, two) = (rows(&d.join("one.csv")), rows(&d.join("two.csv")));
    assert_eq!(one.len(), 9);
    for (a, b) in one.iter().zip(&two) {
        let strip = |r: &std::collections::BTreeMap<String, String>| {
            r.iter().filter(|(k, _)| *k != "wall_time").map(|(k, v)| (k.clone(), v.clone())).collect::<Vec<_>>()
        };
        assert_eq!(strip(a), strip(b));
    }
    // Three records from the scenario's seed, three events each, inside [0, 600 - 0.5] s, sorted.
    let seeds: Vec<&str> = one.iter().map(|r| r["seed"].as_str()).collect();
    assert_eq!(seeds, ["7", "7", "7", "8", "8", "8", "9", "9", "9"]);
    let instants: Vec<f64> = one.iter().map(|r| r["instant"].parse().unwrap()).collect();
    assert!(instants.iter().all(|t| (0.0..=599.5).contains(t)), "{instants:?}");
    assert!(instants[..3].windows(2).all(|w| w[0] <= w[1]));
    // An event is the run of its seed and instant: `run` gives its peaks to the bit.
    let r = &one[4];
    let o = beam_impact()
        .args(["run", "s.toml", "--mcap", "event.mcap", "--json", "event.json"])
        .args(["--set", &format!("sea.seed={}", r["seed"]), "--set", &format!("sea.time_shift={}", r["instant"])])
        .current_dir(d)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let run = json(&d.join("event.json"));
    let converged = run["summary"]["converged_peaks"]["lower_clamp_bending_stress"].as_f64().unwrap();
    assert_eq!(r["peak.lower.clamp_bending_stress"].parse::<f64>().unwrap(), converged);
    // The supports' motion at the instant is the record's: the hinge moves.
    assert_ne!(r["upper.hinge_heave_velocity"].parse::<f64>().unwrap(), 0.0);
    // Its log replays in `report` (the record travels in it: no RAO file needed) with the row's
    // seed and instant and the run's peaks.
    let data = beam_impact::replay::report::read_log(&d.join("event.mcap")).unwrap();
    assert_eq!(data.metadata.get("sea.seed").map(String::as_str), Some(r["seed"].as_str()));
    std::fs::remove_file(d.join("raos.csv")).unwrap();
    let report = beam_impact().args(["report", "event.mcap", "--out", "figures"]).current_dir(d).output().unwrap();
    assert!(report.status.success(), "{}", String::from_utf8_lossy(&report.stderr));
    let text = String::from_utf8(report.stdout).unwrap();
    let deflection = run["summary"]["peaks"]["lower.tip_deflection"].as_f64().unwrap();
    assert!(text.contains(&format!("{deflection:.3}")), "{deflection}: {text}");
}

/// The statistics speak of the rows beside them: the exceedances are the rows' utilisations above
/// 1, the interval is Clopper-Pearson's for them, the most probable maximum follows from the fit.
#[test]
fn the_summary_counts_what_the_rows_hold() {
    // An allowable near the clamp's median peak (about 473 MPa here): some events exceed it.
    let dir = folder(&scenario("[lower]\nallowable_bending_stress = 4.73e8\n"));
    let d = dir.path();
    let o = campaign(
        d,
        &["--events", "20", "--seeds", "4", "--record-length", "900", "--out", "e.csv", "--json", "s.json"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows = rows(&d.join("e.csv"));
    let s = json(&d.join("s.json"));
    let cell = &s["cells"][0];
    let q = &cell["quantities"]["lower.clamp_bending_stress"];
    let beyond =
        rows.iter().filter(|r| r["utilisation.lower.clamp_bending_stress"].parse::<f64>().unwrap() > 1.0).count();
    assert!(beyond > 0 && beyond < 20, "the allowable should split the events: {beyond}");
    assert_eq!(q["exceedance"]["exceeding"], beyond);
    assert_eq!(q["exceedance"]["probability"].as_f64().unwrap(), beyond as f64 / 20.0);
    let overloads = rows.iter().filter(|r| r["design.pass"] == "false").count();
    assert_eq!(cell["overload"]["exceeding"], overloads);
    let max = rows.iter().map(|r| r["peak.lower.clamp_bending_stress"].parse::<f64>().unwrap()).fold(0.0, f64::max);
    assert_eq!(q["max"].as_f64().unwrap(), max);
    // MPM = location + scale ln(exposure / events per record), exposure 1 / target = 100.
    let (loc, scale) = (q["gumbel"]["location"].as_f64().unwrap(), q["gumbel"]["scale"].as_f64().unwrap());
    let mpm = q["most_probable_maximum"].as_f64().unwrap();
    assert!((mpm - (loc + scale * (100.0f64 / 5.0).ln())).abs() <= 1e-9 * mpm, "{mpm}");
    assert_eq!(s["campaign"]["interval"], "Clopper-Pearson (exact, two-sided)");
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains(&format!("overload (any utilisation > 1): {overloads} of 20")), "{text}");
}

#[test]
fn a_grid_prints_the_operability_table_and_refuses_a_breaking_sea() {
    let dir = folder(&scenario(""));
    let d = dir.path();
    // Hs 12 m at Tp 8 s is steeper than a sea can be (DNV-RP-C205 3.5.11): refused, not run.
    let o = beam_impact()
        .args(["campaign", "s.toml", "--events", "3", "--seeds", "1", "--record-length", "300"])
        .args(["--vary", "sea.significant_wave_height=0.5,1,12", "--vary", "sea.peak_period=8", "--on-estimate"])
        .args(["--out", "g.csv", "--json", "g.json", "--figures", "figs"])
        .current_dir(d)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains("Hs [m] \\ Tp [s]") && text.contains("breaking") && text.contains("limit Hs [m]"), "{text}");
    let stderr = String::from_utf8(o.stderr).unwrap();
    assert!(stderr.contains("Hs 12 m, Tp 8 s: refused") && stderr.contains("steeper than a sea can be"), "{stderr}");
    assert_eq!(rows(&d.join("g.csv")).len(), 6, "the breaking cell's events are not run");
    let s = json(&d.join("g.json"));
    assert!(s["cells"][2]["refused"].as_str().unwrap().contains("steeper"));
    // Nothing overloads at these heights: the limit is the largest sea the model takes.
    assert_eq!(s["operability"]["limits"][0]["significant_wave_height"], 1.0);
    for ext in ["svg", "png"] {
        assert!(std::fs::metadata(d.join(format!("figs/operability-heading-180.{ext}"))).unwrap().len() > 1000);
    }
}

#[test]
fn bad_campaigns_are_refused_in_one_line_naming_the_value() {
    let dir = folder(&scenario(""));
    let d = dir.path();
    std::fs::write(d.join("plain.toml"), "duration = 0.5\n").unwrap();
    let cases: [(&[&str], &str); 12] = [
        (
            &["--target", "0"],
            "--target must be a probability from 1e-15 to 1 (exclusive; 1 / target is the default --exposure), got 0",
        ),
        // A grid value its field's rule refuses is an error, not a refused cell that would end
        // its column of the operability table (and so lower the limit of the valid ones).
        (
            &["--vary", "sea.significant_wave_height=-1,1,2"],
            "campaign --vary: sea.significant_wave_height must be > 0 m, at most 20 m, got -1",
        ),
        (&["--vary", "sea.heading=90,450"], "campaign --vary: sea.heading must be between 0 and 360 deg, got 450"),
        (&["--json", "-"], "campaign --json -: standard output carries the campaign's statistics and table"),
        (&["--vary", "sea.significant_wave_height=1,2,1"], "campaign --vary sea.significant_wave_height: 1 is given twice"),
        (&["--vary", "sea.heading=0,180,360"], "campaign --vary sea.heading: 0 is given twice (0 and 360 deg are one heading)"),
        // Nothing to run: every cell breaks (Hs 12 and 13 m at Tp 8 s).
        (
            &["--vary", "sea.significant_wave_height=12,13"],
            "campaign: every cell of the grid is refused, nothing to run; the first: sea.significant_wave_height = 12 m",
        ),
        (&["--target", "1.5"], "got 1.5"),
        (&["--vary", "drop_height=0.5,1"], "campaign --vary drop_height: a campaign's grid is of sea states"),
        (&["--events", "50", "--max-events", "10"], "50 runs, more than --max-events 10"),
        (&["--record-length", "0.2"], "--record-length must be longer than the run's duration 0.5 s"),
        (&["--seeds", "5", "--events", "2"], "--seeds must be between 1 and --events = 2, got 5"),
    ];
    for (args, expected) in cases {
        let o = campaign(d, &[args, &["--out", "x.csv"][..]].concat());
        let stderr = String::from_utf8(o.stderr).unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
        assert!(!d.join("x.csv").exists(), "{args:?} wrote its output");
    }
    let o = beam_impact().args(["campaign", "plain.toml", "--out", "x.csv"]).current_dir(d).output().unwrap();
    let stderr = String::from_utf8(o.stderr).unwrap();
    assert!(stderr.contains("the scenario has no [sea] section"), "{stderr}");
}

/// Without `--seeds`, fewer events than the default 20 records take one record each (not an
/// error about an option never given); a `sea.time_shift`, which each event draws, is named as
/// not used.
#[test]
fn a_small_campaign_takes_a_record_an_event_and_names_the_time_shift_it_sets_aside() {
    let dir = folder(&scenario(""));
    let d = dir.path();
    let o = campaign(d, &["--events", "3", "--record-length", "300", "--set", "sea.time_shift=100", "--out", "s.csv"]);
    let stderr = String::from_utf8(o.stderr).unwrap();
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: sea.time_shift = 100 s is not used: each event's instant is drawn over its record"),
        "{stderr}"
    );
    let rows = rows(&d.join("s.csv"));
    let seeds: std::collections::BTreeSet<&str> = rows.iter().map(|r| r["seed"].as_str()).collect();
    assert_eq!((rows.len(), seeds.len()), (3, 3), "{seeds:?}");
}

/// A campaign of 5 000 half-second events in `d`, rows to `out` and statistics to `json`, sent
/// `signal` after 3 s (a few events' time: the modes and the first records come first); its
/// output once it stopped, and the number of rows its CSV holds.
fn interrupted_campaign(d: &Path, signal: i32, out: &str, json: &str) -> (std::process::Output, usize) {
    let mut child = beam_impact()
        .args(["campaign", "s.toml", "--events", "5000", "--seeds", "10", "--jobs", "1", "--out", out])
        .args(["--json", json])
        .current_dir(d)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_secs(3));
    // SAFETY: kill(2) with the child's own pid and a signal number.
    unsafe {
        libc::kill(child.id() as i32, signal);
    }
    let started = std::time::Instant::now();
    let o = loop {
        if let Some(_status) = child.try_wait().unwrap() {
            break child.wait_with_output().unwrap();
        }
        assert!(started.elapsed().as_secs() < 60, "the campaign did not stop");
        std::thread::sleep(std::time::Duration::from_millis(50));
    };
    let n = rows(&d.join(out)).len();
    (o, n)
}

/// Ctrl-C (SIGINT) stops the campaign between events: the rows run so far are written, the
/// statistics printed are of them, the message says so, exit code 130; the statistics document
/// says it is of a part.
#[test]
fn ctrl_c_keeps_the_rows_run_so_far() {
    let dir = folder(&scenario(""));
    let d = dir.path();
    let (o, n) = interrupted_campaign(d, libc::SIGINT, "k.csv", "k.json");
    let stderr = String::from_utf8(o.stderr).unwrap();
    assert_eq!(o.status.code(), Some(130), "{stderr}");
    assert!((1..5000).contains(&n), "{n} rows");
    assert!(stderr.contains(&format!("interrupted: {n} of 5000 events run and written to k.csv")), "{stderr}");
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains(&format!("{n} events on")), "{text}");
    let c = &json(&d.join("k.json"))["campaign"];
    assert_eq!(
        (c["interrupted"].as_bool(), c["events_run"].as_u64(), c["events_planned"].as_u64()),
        (Some(true), Some(n as u64), Some(5000))
    );
}

/// A scheduler's SIGTERM (or a closed session's SIGHUP) stops the campaign as Ctrl-C does: the
/// rows run so far are written to the CSV itself (not left in a partial file) and said so.
#[test]
fn sigterm_keeps_the_rows_run_so_far_as_ctrl_c_does() {
    let dir = folder(&scenario(""));
    let d = dir.path();
    let (o, n) = interrupted_campaign(d, libc::SIGTERM, "t.csv", "t.json");
    let stderr = String::from_utf8(o.stderr).unwrap();
    assert_eq!(o.status.code(), Some(130), "{stderr}");
    assert!((1..5000).contains(&n), "{n} rows");
    assert!(stderr.contains(&format!("interrupted: {n} of 5000 events run and written to t.csv")), "{stderr}");
    assert_eq!(json(&d.join("t.json"))["campaign"]["events_run"].as_u64(), Some(n as u64));
}

/// `bench`'s campaign line runs its events (all converged, none failed) and prints the projection
/// for 10 000 events beside the bar; its numbers are the machine's, not asserted.
#[test]
fn the_benchmarks_campaign_line_projects_ten_thousand_events() {
    let text = beam_impact::studies::bench::campaign_benchmark(1).unwrap();
    println!("{text}");
    assert!(text.contains("20 events on") && text.contains("10 000 events:") && text.contains("projected"), "{text}");
}
