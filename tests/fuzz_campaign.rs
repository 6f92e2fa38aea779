//! Issue 43: a campaign's inputs from strangers (the counts, lengths, probabilities and grid axes
//! of `beam-impact campaign` and `beam_impact.campaign`) and its statistics on any sample: a
//! campaign made or one line of error naming the input, never a panic; statistics finite where
//! their sample is, an error or an empty field where it cannot give one.
//!
//! Goal: seeded random choices among hostile literals (NaN, infinities, zero, negatives, huge,
//! the bounds and one past them) for every option; samples with NaN, infinities, repeats and
//! single values. `BEAM_IMPACT_FUZZ_ITERATIONS` sets the number of cases.

use crate::fuzz_support::{iterations, Rng};
use crate::sea_scenario::{folder, sea_toml};

use beam_impact::scenario_file::read_file;
use beam_impact::studies::campaign::summary::{summarise, EventOutcome, EventResults};
use beam_impact::studies::campaign::{Campaign, Options};
use beam_impact::studies::sweep::parse_axes;

const REALS: &[f64] = &[
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    -1.0,
    5e-324,
    1e-9,
    0.5,
    1.0,
    1.0 + 1e-12,
    2.0,
    1e6,
    1e6 + 1.0,
    1e15,
    1e300,
];
const COUNTS: &[u64] = &[0, 1, 2, 3, 7, 1_000_000, 1_000_001, u64::MAX];
const AXES: &[&str] = &[
    "sea.significant_wave_height=0.5,1",
    "sea.significant_wave_height=nan",
    "sea.significant_wave_height=-1,25",
    "sea.peak_period=1:40:3",
    "sea.heading=0:360:2",
    "sea.heading=400",
    "sea.seed=1,2",
    "sea.time_shift=5",
    "drop_height=1",
    "sea.significant_wave_height=0.1:1:1000000",
    "",
    "=",
    "sea.peak_period=8,8",
];

#[test]
fn campaign_inputs_give_a_campaign_or_one_line_naming_them() {
    let dir = folder(&sea_toml(""));
    let base = read_file(&dir.path().join("s.toml"), &mut Vec::new()).unwrap();
    let mut rng = Rng(43);
    let mut made = 0;
    for case in 0..iterations(300) {
        // Half the cases change one field of a valid campaign, the others draw every field.
        let mut options =
            Options { events: 2, seeds: 1, record_length: 100.0, exposure: Some(10.0), ..Options::default() };
        let all = rng.below(2) == 0;
        let field = rng.below(6);
        if all || field == 0 {
            options.events = *rng.pick(COUNTS);
        }
        if all || field == 1 {
            options.seeds = *rng.pick(COUNTS);
        }
        if all || field == 2 {
            options.record_length = *rng.pick(REALS);
        }
        if all || field == 3 {
            options.target = *rng.pick(REALS);
        }
        if all || field == 4 {
            options.confidence = *rng.pick(REALS);
        }
        if all || field == 5 {
            options.exposure = if rng.below(2) == 0 { None } else { Some(*rng.pick(REALS)) };
        }
        let axes: Vec<String> = (0..rng.below(3)).map(|_| rng.pick(AXES).to_string()).collect();
        // A campaign's cells are checked against their records: keep the grids small.
        let max_events = if rng.below(2) == 0 { 1_000_000 } else { *rng.pick(COUNTS) };
        let outcome = std::panic::catch_unwind(|| {
            let axes = parse_axes(&axes)?;
            Campaign::new(base.clone(), axes, options.clone(), max_events, 1_000_000)
        });
        match outcome {
            Err(_) => panic!("case {case}: a panic for {options:?}, {axes:?}, max {max_events}"),
            Ok(Ok(c)) => {
                made += 1;
                assert!(c.len() as u64 <= max_events, "case {case}");
                assert!(options.target > 0.0 && options.target < 1.0, "case {case}: target {}", options.target);
            }
            Ok(Err(e)) => {
                let text = e.to_string();
                assert!(!text.contains('\n') && !text.is_empty() && text.len() < 600, "case {case}: {text:?}");
            }
        }
    }
    assert!(made > 0, "no case made a campaign: the fuzz only tried refusals");
}

#[test]
fn statistics_on_any_sample_are_finite_or_absent() {
    let mut rng = Rng(4343);
    let values = [f64::NAN, f64::INFINITY, 0.0, 1.0, 1.0, 2.5, 1e300, -1e300, 5e-324];
    for case in 0..iterations(300) {
        let n = rng.below(12);
        let outcomes: Vec<EventOutcome> = (0..n)
            .map(|_| EventOutcome {
                seed: rng.below(4) as u64,
                results: (rng.below(5) != 0).then(|| EventResults {
                    peaks: std::array::from_fn(|_| (rng.below(4) != 0).then(|| *rng.pick(&values))),
                    utilisation: std::array::from_fn(|_| (rng.below(3) != 0).then(|| *rng.pick(&values))),
                    design_pass: rng.below(2) == 0,
                    trusted: rng.below(2) == 0,
                }),
            })
            .collect();
        let summary = std::panic::catch_unwind(|| summarise(&outcomes, &Options::default()))
            .unwrap_or_else(|_| panic!("case {case}: a panic on {outcomes:?}"));
        let i = summary.overload.interval;
        if summary.overload.events == 0 {
            // No event to count: no estimate (null in the JSON), the whole of [0, 1] possible.
            assert!(i.probability.is_nan() && i.low == 0.0 && i.high == 1.0 && !summary.operable, "case {case}: {i:?}");
        } else {
            assert!(
                i.low >= 0.0 && i.low <= i.probability && i.probability <= i.high && i.high <= 1.0,
                "case {case}: {i:?}"
            );
        }
        for q in &summary.quantities {
            if let Ok(g) = &q.gumbel {
                assert!(g.location.is_finite() && g.scale.is_finite() && g.scale > 0.0, "case {case}: {g:?}");
                assert!(q.most_probable_maximum.is_some_and(f64::is_finite), "case {case}");
            }
        }
        let text = beam_impact::studies::campaign::summary::text("fuzz", &summary, &Options::default());
        assert!(!text.contains("NaN") || q_has_nan(&outcomes), "case {case}: {text}");
    }
}

/// Whether a sample holds a NaN (its mean may then print as NaN; nothing else may).
fn q_has_nan(outcomes: &[EventOutcome]) -> bool {
    outcomes.iter().filter_map(|o| o.results).any(|r| r.peaks.iter().flatten().any(|v| v.is_nan()))
}
