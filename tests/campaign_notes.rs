//! Issue 43, the tester's defects in the campaign's printed notes (D3, D4, D7) and the bench's
//! bar: end to end on `examples/vessel-sea.toml`, asserting what the notes say rather than the
//! sea's numbers (the unit tests in src/studies/campaign/summary.rs hold those).

use std::process::{Command, Output};

/// `beam-impact campaign examples/vessel-sea.toml ARGS --out DIR/e.csv` from the crate's root.
fn campaign(args: &[&str]) -> (Output, String) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("e.csv");
    let o = Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .args(["campaign", "examples/vessel-sea.toml"])
        .args(args)
        .arg("--out")
        .arg(&out)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let text = String::from_utf8(o.stdout.clone()).unwrap();
    (o, text)
}

/// The tester's Hs 5 m, Tp 9 s cell: overloads and failed events, judged well above the target.
/// The note speaks of the judged events and says more events will not help (not "N events cannot
/// show ... at least 368 ... are needed"); each "no event beyond the allowable" note names its
/// quantities, and those are the table's rows with no exceedance.
#[test]
fn an_overloaded_sea_is_told_more_events_will_not_help_and_its_notes_name_their_quantities() {
    let (o, text) = campaign(&[
        "--events",
        "150",
        "--seeds",
        "10",
        "--set",
        "sea.significant_wave_height=5",
        "--set",
        "sea.peak_period=9",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(text.contains("events judged are overloads, an estimate of") && text.contains("will not show"), "{text}");
    assert!(!text.contains("cannot show") && !text.contains("at least"), "{text}");
    let beyond: Vec<&str> = text.lines().filter(|l| l.contains("no event beyond the allowable")).collect();
    assert!(!beyond.is_empty(), "{text}");
    for line in beyond {
        let names = line.strip_prefix("note (").and_then(|l| l.split_once("): ")).map(|(n, _)| n).expect(line);
        for name in names.split(", ") {
            let row = text.lines().find(|l| l.starts_with(&format!("{name} ["))).expect(name);
            assert!(row.contains(" 0 (< "), "{name} has exceedances: {row}\n{text}");
        }
    }
}

/// A target below 1e-15 is refused in one line naming the bound (1 / target is the default
/// exposure, at most 1e15); at 1e-15 the target and the exposure print as 1e-15 and 1e15, no
/// line runs to hundreds of digits, and the most probable maximum says it extrapolates.
#[test]
fn a_tiny_target_is_refused_below_1e_15_and_printed_short_at_it() {
    let (o, _) = campaign(&["--events", "5", "--seeds", "5", "--target", "1e-300"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{stderr}");
    assert!(
        stderr.contains("--target must be a probability from 1e-15 to 1") && stderr.contains("got 1e-300"),
        "{stderr}"
    );
    let (o, text) = campaign(&["--events", "5", "--seeds", "5", "--target", "1e-15"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(text.contains("target 1e-15") && text.contains("MPM 1e15"), "{text}");
    assert!(text.contains("extrapolates the fit 2e14 times beyond the 5 events"), "{text}");
    assert!(!text.contains("0000000000") && !text.contains(&u64::MAX.to_string()), "{text}");
}

/// `bench`'s campaign line gives its verdict beside the bar.
#[test]
fn the_benchmarks_campaign_line_says_whether_the_bar_is_met() {
    let text = beam_impact::studies::bench::campaign_benchmark(1).unwrap();
    assert!(
        text.contains("(bar: 60 s on two cores: met") || text.contains("(bar: 60 s on two cores: not met"),
        "{text}"
    );
    assert!(text.contains("median of 1 run)"), "{text}");
}
