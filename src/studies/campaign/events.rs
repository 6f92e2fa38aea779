//! A campaign's events (issue 43): which sea-state records (seeds) and which instants of them the
//! gangway's support is lost at. The plan is fixed before any event runs, from integers alone, so
//! the same command gives the same events, in the same order, on any number of workers.
//!
//! Seeds: `first_seed`, `first_seed + 1`, ... (`seeds` of them, the scenario's `sea.seed` first);
//! the events shared out as evenly as can be, the first `events % seeds` records one more. Each
//! record's instants are uniform over `[0, record_length - duration]` (the run after the instant
//! stays inside the record), drawn by splitmix64 ([`SplitMix64`], the generator of the wave
//! components) from a state of its own, `seed` times the golden ratio's 64-bit constant xor
//! [`INSTANT_STREAM`], so that they are independent of the record's phases and frequencies drawn
//! from `seed`; sorted in time within the record.

use crate::error::{Error, Result};
use crate::model::sea::components::SplitMix64;
use crate::model::sea::settings::{MAX_RECORD_TIME, MAX_SEED};

/// The instants' own stream: mixed into the seed so that the instants do not reuse the random
/// numbers of the record's components (an arbitrary odd constant, the digits of pi's fraction).
pub const INSTANT_STREAM: u64 = 0x243F_6A88_85A3_08D3;

/// Most events of a campaign (a million converged runs: days of CPU; `--max-events` lowers it).
pub const MAX_EVENTS: u64 = 1_000_000;

/// One loss of the support: the record (seed) and its instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    /// The sea state's seed (`sea.seed`).
    pub seed: u64,
    /// The record's time at which the support is lost (`sea.time_shift`), s.
    pub instant: f64,
}

/// The events of a campaign of `events` support losses spread over `seeds` records of
/// `record_length` s, starting at `first_seed`, each run lasting `duration` s.
pub fn plan(events: u64, seeds: u64, first_seed: u64, record_length: f64, duration: f64) -> Result<Vec<Event>> {
    if !(1..=MAX_EVENTS).contains(&events) {
        return Err(Error::invalid("--events", format!("between 1 and {MAX_EVENTS}"), events.to_string()));
    }
    if !(1..=events).contains(&seeds) {
        return Err(Error::invalid("--seeds", format!("between 1 and --events = {events}"), seeds.to_string()));
    }
    if first_seed.checked_add(seeds - 1).is_none_or(|last| last > MAX_SEED) {
        return Err(Error::Other(format!(
            "sea.seed = {first_seed} with --seeds {seeds} goes beyond the largest seed 2^53 = {MAX_SEED}"
        )));
    }
    if !(record_length.is_finite() && record_length > duration && record_length <= MAX_RECORD_TIME) {
        return Err(Error::invalid(
            "--record-length",
            format!("longer than the run's duration {duration} s, at most {MAX_RECORD_TIME:e} s"),
            format!("{record_length} s"),
        ));
    }
    let span = record_length - duration;
    let mut out = Vec::with_capacity(events as usize);
    for s in 0..seeds {
        let seed = first_seed + s;
        let count = events / seeds + u64::from(s < events % seeds);
        let mut rng = SplitMix64::new(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ INSTANT_STREAM);
        let mut instants: Vec<f64> = (0..count).map(|_| rng.next_f64() * span).collect();
        instants.sort_by(f64::total_cmp);
        out.extend(instants.into_iter().map(|instant| Event { seed, instant }));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn events_are_shared_over_the_seeds_and_stay_inside_the_record() {
        let events = plan(10, 3, 7, 100.0, 3.0).unwrap();
        let per_seed: Vec<usize> = (7..10).map(|s| events.iter().filter(|e| e.seed == s).count()).collect();
        assert_eq!(per_seed, vec![4, 3, 3]);
        assert!(events.iter().all(|e| (0.0..=97.0).contains(&e.instant)));
        // Sorted in time within each record.
        assert!(events.windows(2).all(|w| w[0].seed != w[1].seed || w[0].instant <= w[1].instant));
    }

    #[test]
    fn a_plan_is_the_same_every_time_and_another_seed_gives_other_instants() {
        assert_eq!(plan(50, 5, 1, 10800.0, 3.0).unwrap(), plan(50, 5, 1, 10800.0, 3.0).unwrap());
        let a = plan(5, 1, 1, 10800.0, 3.0).unwrap();
        let b = plan(5, 1, 2, 10800.0, 3.0).unwrap();
        assert_ne!(a[0].instant, b[0].instant);
    }

    /// The instants are uniform over the window: 20 000 of them put 10 % +- 0.6 % (three standard
    /// deviations of a binomial share, sqrt(0.1 * 0.9 / 20000) = 0.21 %) in each tenth.
    #[test]
    fn instants_are_uniform_over_the_window() {
        let events = plan(20_000, 4, 1, 1000.0, 0.0 + 1e-9).unwrap();
        for tenth in 0..10 {
            let lo = tenth as f64 * 100.0;
            let share = events.iter().filter(|e| (lo..lo + 100.0).contains(&e.instant)).count() as f64 / 20_000.0;
            assert!((share - 0.1).abs() < 0.0064, "tenth {tenth}: {share}");
        }
    }

    #[test]
    fn bad_counts_and_lengths_are_refused_with_their_values() {
        let e = plan(0, 1, 1, 100.0, 3.0).unwrap_err().to_string();
        assert!(e.contains("--events") && e.contains("got 0"), "{e}");
        let e = plan(5, 6, 1, 100.0, 3.0).unwrap_err().to_string();
        assert!(e.contains("--seeds") && e.contains('6'), "{e}");
        let e = plan(5, 1, 1, 2.0, 3.0).unwrap_err().to_string();
        assert!(e.contains("--record-length") && e.contains("2 s"), "{e}");
        let e = plan(5, 2, MAX_SEED, 100.0, 3.0).unwrap_err().to_string();
        assert!(e.contains("2^53"), "{e}");
    }
}
