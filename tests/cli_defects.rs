//! Regression tests of small CLI defects of issue 11 that had none (the others are in
//! `tests/cli.rs` and `tests/fmi_pack.rs`). Each fails on the behaviour it guards against.

use std::process::Command;

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

/// A scenario file with three bad fields names all three in its one-line error (it named only
/// the first: fixing a file took one run per field).
#[test]
fn three_bad_fields_are_all_named() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("three.toml");
    std::fs::write(&file, "damping_ratio = 1.5\n[upper]\nlength = -3.0\n[lower]\ntip_mass = -1.0\n").unwrap();
    let out = beam_impact().args(["run", "--no-mcap"]).arg(&file).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    for field in ["damping_ratio must be", "upper.length must be", "lower.tip_mass must be"] {
        assert!(stderr.contains(field), "{field:?} missing from: {stderr}");
    }
    assert!(out.stdout.is_empty());
}

/// `bench` says what it is doing on stderr while it runs (it was silent for tens of seconds) and
/// judges nothing against targets (it ended with "target: ... MISSED" on a slower machine).
#[test]
fn bench_prints_progress_and_no_targets() {
    let out = beam_impact().args(["bench", "--runs", "1"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stderr = String::from_utf8(out.stderr).unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    let progress: Vec<&str> = stderr.lines().filter(|l| l.starts_with("beam-impact bench: ")).collect();
    assert_eq!(progress.len(), 2, "{stderr}");
    assert!(progress[0].contains("1/2") && progress[1].contains("2/2"), "{stderr}");
    for text in [&stdout, &stderr] {
        let lower = text.to_lowercase();
        assert!(!lower.contains("target") && !lower.contains("missed"), "{text}");
    }
    assert!(stdout.contains("ns/step") && stdout.contains("unrecorded"), "the measurements are printed:\n{stdout}");
}

/// `--json`: the raw contact windows stay under `summary.contact_windows` (old key), the bounces
/// closer than 10 ms are merged under `merged_contact_windows` (they were not: 81 raw windows on
/// the paper run for Figure 6's few), and a `units` object gives the SI unit of the fields
/// (there were none).
#[test]
fn json_has_merged_windows_old_keys_and_units() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("paper.json");
    let out = beam_impact().args(["run", "--no-mcap", "--json"]).arg(&json).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    for key in ["scenario", "summary", "quality", "wall_time_s"] {
        assert!(doc.get(key).is_some(), "old key {key} kept");
    }
    let window = |w: &serde_json::Value| (w["start"].as_f64().unwrap(), w["end"].as_f64().unwrap());
    let raw: Vec<(f64, f64)> = doc["summary"]["contact_windows"].as_array().unwrap().iter().map(window).collect();
    let merged: Vec<(f64, f64)> =
        doc["merged_contact_windows"].as_array().expect("merged_contact_windows").iter().map(window).collect();
    assert!(!merged.is_empty() && merged.len() < raw.len(), "{} merged of {} raw", merged.len(), raw.len());
    // Merged windows are ordered, apart by at least the bounce gap, and cover every raw window;
    // each starts and ends where a raw one does.
    let gap = beam_impact::results::BOUNCE_GAP;
    assert!(merged.windows(2).all(|w| w[1].0 - w[0].1 >= gap), "{merged:?}");
    for &(start, end) in &raw {
        assert!(merged.iter().any(|&(s, e)| s <= start && end <= e), "raw window {start}..{end} not covered");
    }
    for &(s, e) in &merged {
        assert!(raw.iter().any(|r| r.0 == s) && raw.iter().any(|r| r.1 == e), "{s}..{e}");
    }
    let units = doc["units"].as_object().expect("a units object");
    let unit_of = |field: &str| {
        units
            .iter()
            .find(|(k, _)| k.split(',').any(|part| part.split_whitespace().next() == Some(field)))
            .map(|(_, v)| v.as_str().unwrap().to_string())
            .unwrap_or_else(|| panic!("no unit for {field} in {units:?}"))
    };
    assert_eq!(unit_of("lower_tip_deflection"), "m");
    assert_eq!(unit_of("contact_force"), "N");
    assert_eq!(unit_of("time"), "s");
    assert_eq!(unit_of("modes"), "rad/s");
    assert_eq!(unit_of("wall_time_s"), "s");
    assert!(units.iter().any(|(k, v)| k.contains("_stress") && v == "Pa"), "{units:?}");
}

/// A scenario file that is not `.toml` keeps its name in its log's (`s.mcap` logs to
/// `s.mcap.mcap`): the default log used to replace the extension, so `run s.mcap` overwrote the
/// scenario with its own log. An explicit `--mcap` naming the scenario is refused.
#[test]
fn a_scenario_file_is_never_overwritten_by_its_log() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = "duration = 0.01\n";
    let file = dir.path().join("s.mcap");
    std::fs::write(&file, scenario).unwrap();
    let out = beam_impact().current_dir(dir.path()).args(["run", "s.mcap"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), scenario);
    assert!(dir.path().join("s.mcap.mcap").is_file());

    let other = dir.path().join("t.txt");
    std::fs::write(&other, scenario).unwrap();
    let out = beam_impact().arg("run").arg(&other).arg("--mcap").arg(&other).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.contains("the scenario file and --mcap name the same file"), "{stderr}");
    assert_eq!(std::fs::read_to_string(&other).unwrap(), scenario);
}

/// Issue 40 (part 5) item 2: the impact line printed "closing at -0.000000 m/s" for a drop of 0
/// (a negative zero), and "0.000000 rad/s" for a stated speed of 1e-9 rad/s (a speed that is not
/// 0 printed as 0). Now a zero is "0.000000" and a speed too small for six decimals is printed in
/// scientific form.
#[test]
fn the_impact_speeds_are_printed_truthfully() {
    let impact_line = |settings: &[&str]| {
        let mut command = beam_impact();
        command.args(["run", "--no-mcap", "--set", "duration=0.002"]);
        for setting in settings {
            command.args(["--set", setting]);
        }
        let out = command.output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let stdout = String::from_utf8(out.stdout).unwrap();
        stdout.lines().find(|l| l.starts_with("impact: ")).unwrap_or_else(|| panic!("{stdout}")).to_string()
    };
    let line = impact_line(&["drop_height=0"]);
    assert!(!line.contains("-0.000000"), "{line}");
    assert!(line.contains("turns at 0.000000 rad/s") && line.contains("closing at 0.000000 m/s"), "{line}");
    let line = impact_line(&["impact_angular_velocity=1e-9"]);
    assert!(line.contains("turns at 1.000e-9 rad/s") && line.contains("closing at 1.300e-8 m/s"), "{line}");
}

/// Issue 40 (part 5) item 4: `modes --set contact_position=29` (then the paper's scenario, whose
/// bridge has 7 elements beyond the contact) blamed upper.elements_beyond_contact, a field the user
/// never set. Now the message names the field set, contact_position, with the user's value, and
/// says what else to set. (`modes --set` without a file now starts from the default scenario, as
/// `run --set` does, whose automatic mesh takes contact_position=29: the paper's file here.)
#[test]
fn a_setting_at_odds_with_the_scenario_is_the_one_named() {
    let dir = tempfile::tempdir().unwrap();
    let paper = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/paper.toml");
    let out = beam_impact()
        .args(["modes", paper, "--set", "contact_position=29", "--out"])
        .arg(dir.path().join("modes"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("beam-impact: contact_position must be"), "{stderr}");
    assert!(stderr.contains("got 29") && stderr.contains("upper.elements_beyond_contact=auto"), "{stderr}");
    assert!(!dir.path().join("modes").exists());
    // Set with the count it needs, it is accepted.
    let out = beam_impact()
        .args(["modes", paper, "--set", "contact_position=29", "--set", "upper.elements_beyond_contact=auto", "--out"])
        .arg(dir.path().join("modes"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// Issue 40: a run whose plan is large says so before it starts, and where no terminal shows the
/// progress bar (a pipe, as here) a run still going after two seconds says how far it is. The
/// paper method at 5e-7 s steps for 3 s: 6 million steps, about 4 s of stepping on this machine
/// (0.7 us a step), so the progress line is due whatever the machine's speed within 2x.
#[test]
fn a_long_run_says_its_size_before_and_its_progress_after_two_seconds() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .args(["run", "--no-mcap", "--set", "method=paper", "--set", "step_free=5e-7", "--set", "step_contact=5e-7"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("note: this run may take up to 6000000 internal steps (3 s"), "{stderr}");
    let progress =
        stderr.lines().find(|l| l.contains(" of 3.0000 s simulated (")).unwrap_or_else(|| panic!("{stderr}"));
    assert!(progress.ends_with(" s elapsed"), "{progress}");
}

/// Issue 40: a run in which the bodies never touch says so (it printed "Contact: 0 windows" beside
/// "first sustained contact (t = 0 .. end of run)" and a design PASS).
#[test]
fn a_run_without_contact_says_the_beams_never_touch() {
    let out = beam_impact()
        .args(["run", "--no-mcap", "--set", "contact.clearance=0.5", "--set", "duration=0.05"])
        .output()
        .unwrap();
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{stderr}");
    assert!(stdout.contains("Contact: none (the beams never touch in the run)"), "{stdout}");
    assert!(!stdout.contains("first sustained contact (t = 0 .. end of run)"), "{stdout}");
    assert!(stderr.contains("no contact: the beams never touch in the run (t = 0 .. 0.0500 s)"), "{stderr}");
}

/// Issue 40: a yield stress so small that every utilisation overflows ("over 1e308 %" on the
/// yield line) is refused by name; 1 kPa, below any solid's, is the smallest taken.
#[test]
fn a_yield_stress_below_any_solid_s_is_refused() {
    let out = beam_impact().args(["run", "--no-mcap", "--set", "lower.yield_stress=1e-300"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("lower.yield_stress must be between 1000 and 1e12 Pa (0: none), got 1e-300"), "{stderr}");
}

/// Issue 41: a mistyped subcommand is named as one, with clap's suggestion, exit code 2 (the bare
/// `beam-impact FILE` took `sweeep` for a scenario file: "cannot read scenario sweeep"). A file of
/// that name that exists is still the scenario, and a word far from every subcommand still a
/// missing file.
#[test]
fn a_mistyped_subcommand_is_named_with_its_suggestion() {
    let dir = tempfile::tempdir().unwrap();
    for (args, typed, suggested) in [
        (vec!["sweeep"], "sweeep", "sweep"),
        (vec!["verfy", "--set", "drop_height=1"], "verfy", "verify"),
        (vec!["sweep_", "--vary", "drop_height=1,2", "--out", "x.csv"], "sweep_", "sweep"),
    ] {
        let out = beam_impact().args(&args).current_dir(dir.path()).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert!(stderr.starts_with(&format!("error: unrecognized subcommand '{typed}'\n")), "{stderr}");
        assert!(stderr.contains(&format!("tip: a similar subcommand exists: '{suggested}'")), "{stderr}");
        assert!(stderr.contains("Usage: beam-impact"), "{stderr}");
        assert!(out.stdout.is_empty());
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written");
    let far = beam_impact().arg("zzqq").current_dir(dir.path()).output().unwrap();
    assert_eq!(far.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&far.stderr).contains("cannot read scenario zzqq"));
    std::fs::write(dir.path().join("sweeep"), "duration = 0.005\n").unwrap();
    let file = beam_impact().args(["sweeep", "--no-mcap"]).current_dir(dir.path()).output().unwrap();
    assert!(file.status.success(), "an existing file is the scenario: {}", String::from_utf8_lossy(&file.stderr));
}

/// Issue 41: a usage error is clap's message as clap prints it, several lines with its `tip:` and
/// `Usage:` (main.rs joined them into one line), and bounded: a 120 KB argument, echoed three
/// times, is cut inside each line (before the bound was one line). Help still prints in full.
#[test]
fn usage_errors_keep_clap_lines_and_stay_bounded() {
    let out = beam_impact().args(["run", "--strct"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let text = String::from_utf8(out.stderr).unwrap();
    assert!(text.lines().count() >= 5, "{text}");
    assert!(text.starts_with("error: unexpected argument '--strct' found\n"), "{text}");
    assert!(text.contains("tip: a similar argument exists: '--strict'"), "{text}");
    assert!(text.lines().any(|l| l.starts_with("Usage: beam-impact run")), "{text}");
    let long = format!("--{}", "x".repeat(120_000));
    for args in [vec!["run", long.as_str()], vec!["sweep", "--vary", "drop_height=1"], vec!["sweep", long.as_str()]] {
        let out = beam_impact().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2));
        let text = String::from_utf8(out.stderr).unwrap();
        assert!(text.lines().count() >= 3, "{text}");
        assert!(text.lines().any(|l| l.starts_with("Usage: beam-impact")), "{text}");
        assert!(text.len() < 2000, "{} bytes", text.len());
    }
    let help = beam_impact().args(["run", "--help"]).output().unwrap();
    assert!(help.status.success() && String::from_utf8_lossy(&help.stdout).lines().count() > 5);
}

/// Issue 41: `completions SHELL` prints the shell's completion script, naming every subcommand,
/// for each shell clap_complete knows; an unknown shell is a usage error.
#[test]
fn completions_print_a_script_naming_the_subcommands() {
    let out = beam_impact().args(["completions", "bash"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let script = String::from_utf8(out.stdout).unwrap();
    assert!(script.contains("complete -F") && script.contains("beam-impact"), "{script}");
    for name in ["run", "scenario", "damping", "modes", "pack", "report", "bench", "verify", "sweep", "completions"] {
        assert!(script.contains(&format!("beam__impact,{name})")), "{name} missing from the bash script");
    }
    for option in ["--strict", "--json", "--vary", "--set"] {
        assert!(script.contains(option), "{option} missing from the bash script");
    }
    for shell in ["zsh", "fish", "elvish", "powershell"] {
        let out = beam_impact().args(["completions", shell]).output().unwrap();
        assert!(out.status.success() && String::from_utf8_lossy(&out.stdout).contains("sweep"), "{shell}");
    }
    let bad = beam_impact().args(["completions", "tcsh"]).output().unwrap();
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("possible values: bash"));
}

/// Issue 41: `run --help` says what `--strict` checks (it named the energy balance alone; it
/// exits 3 whenever the run is not trusted) and that `--json -` is standard output.
#[test]
fn run_help_says_what_strict_checks_and_json_to_standard_output() {
    let out = beam_impact().args(["run", "--help"]).output().unwrap();
    assert!(out.status.success());
    let help = String::from_utf8(out.stdout).unwrap();
    let strict = help.split("--strict").nth(1).unwrap().split("\n      --").next().unwrap();
    for check in ["energy_tolerance", "discretisation_tolerance", "twin run", "yield_stress", "model's range"] {
        assert!(strict.contains(check), "--strict's help does not name {check:?}: {strict}");
    }
    let json = help.split("--json <FILE>").nth(1).unwrap().split("\n      --").next().unwrap();
    assert!(json.contains("`-`: to standard output"), "{json}");
}
