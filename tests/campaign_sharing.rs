//! Issue 43 item 4: what a campaign's events share (one geometry: the assembled models, the modes,
//! the initial state's factors, the model-range and station rows, the reference mesh's
//! frequencies, one sea record per seed) keeps every answer to the bit.
//!
//! Goal: an event run inside a campaign, after other events filled every cache, gives the row it
//! gives run alone from a freshly read scenario (nothing shared with any other event); a run set up
//! from a cache warmed by an event at another instant is the run set up with no cache at all, its
//! initial state and its whole summary to the bit. Equal `Debug` text is equal bits (every f64
//! as its shortest round-trip decimal), so the comparisons are exact, not within a tolerance.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use beam_impact::record::NullRecorder;
use beam_impact::scenario_file::read_file;
use beam_impact::solver::ModalCache;
use beam_impact::studies::campaign::{Campaign, Options};
use beam_impact::{Scenario, Simulation};

/// The example vessel in its sea (examples/vessel-sea.toml with its RAO file), read afresh: its
/// sea's record caches are its own.
fn vessel_sea() -> Scenario {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/vessel-sea.toml");
    read_file(&path, &mut Vec::new()).unwrap()
}

/// A campaign of `events` events on two records of the example vessel's sea, from a fresh read.
fn campaign(events: u64) -> Campaign {
    let options = Options { events, seeds: 2, ..Options::default() };
    Campaign::new(vessel_sea(), Vec::new(), options, 1_000, beam_impact::model::scenario::MAX_STEPS).unwrap()
}

/// A row's CSV line without its `wall_time` cell (the one column that is not an answer).
fn without_wall_time(campaign: &Campaign, line: &str) -> String {
    let header = campaign.csv_header();
    let column = header.split(',').position(|name| name == "wall_time").expect("a wall_time column");
    line.split(',').enumerate().filter(|(k, _)| *k != column).map(|(_, cell)| cell).collect::<Vec<_>>().join(",")
}

#[test]
fn a_campaigns_events_are_the_same_events_run_alone_to_the_bit() {
    let events = 5;
    let together = campaign(events);
    let mut lines = Vec::new();
    together
        .run(1, &AtomicBool::new(false), &mut |_| {}, &mut |row| {
            lines.push(without_wall_time(&together, &together.csv_line(row)));
            Ok(())
        })
        .unwrap();
    assert_eq!(lines.len(), together.len());
    for (index, line) in lines.iter().enumerate() {
        // Alone: a fresh scenario (its own sea records and tables) and a fresh campaign (its own
        // modal cache): nothing this event computes was made for another event.
        let alone = campaign(events);
        let row = alone.run_event(index).unwrap();
        assert!(row.row.outcome.is_ok(), "event {index}: {:?}", row.row.outcome.as_ref().err());
        assert_eq!(*line, without_wall_time(&alone, &alone.csv_line(&row)), "event {index}");
    }
}

#[test]
fn a_run_set_up_from_a_warm_cache_is_the_uncached_run_to_the_bit() {
    let at = |time_shift: f64| {
        let mut s = vessel_sea();
        s.sea.as_mut().unwrap().time_shift = time_shift;
        s
    };
    let cache = ModalCache::default();
    // Another instant fills the cache (models, modes, factors, rows, reference frequencies).
    Simulation::new_cached(&at(137.25), &cache).unwrap();
    let event = at(2_048.125);
    let mut cached = Simulation::new_cached(&event, &cache).unwrap();
    let mut fresh = Simulation::new(&event).unwrap();
    assert_eq!(format!("{:?}", cached.state()), format!("{:?}", fresh.state()), "the initial state");
    assert_eq!(format!("{:?}", cached.impact()), format!("{:?}", fresh.impact()));
    let (a, b) = (cached.run(&mut NullRecorder).unwrap(), fresh.run(&mut NullRecorder).unwrap());
    assert_eq!(format!("{a:?}"), format!("{b:?}"), "the whole run's summary");
    assert_eq!(format!("{:?}", cached.model_range()), format!("{:?}", fresh.model_range()));
}
