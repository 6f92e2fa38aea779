//! The stress stations as a recorder sees them (issue 30): where they sit along each beam with
//! their allowables ([`StationLayout`], written once in the model message), how a step's stresses
//! follow from its modal coordinates ([`StationProbe::rows`], evaluated on the writer thread for
//! the steps the log keeps), and the [`StationFeed`] through which the simulation hands over what
//! a step's result and modal coordinates do not say: the discarded modes' load coefficients of
//! the step (a truncated basis' static correction) and, at the end of each advance, the run's
//! envelope (`envelope.json`, attached when the log is finished).
//!
//! The feed travels in [`super::RunInfo`], so it reaches the log through any recorder that passes
//! the run's description on (the CLI's progress bar, the FMU's tap) without a call of its own. The
//! simulation writes to it only while a recorder holds it (a recorder that keeps nothing drops it
//! at `start`).

use std::sync::{Arc, Mutex, PoisonError};

use serde::{Deserialize, Serialize};

use crate::model::stations::{Station, Stations};
use crate::results::StressEnvelope;
use crate::solver::envelope::StationRows;
use crate::solver::static_correction::LOADS;

/// One stress's stations along one beam.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StationGroup {
    /// Positions, m from the beam's support (the clamp, the hinge), in order.
    pub positions: Vec<f64>,
    /// The allowable stress of the section at each station, Pa (0: none given).
    pub allowable: Vec<f64>,
    /// The node each station sits at (0 at the support). Two stations at one node (a section
    /// change, a point load's shear jump) are its two sides: the first the element before it,
    /// the second the element after.
    pub nodes: Vec<u32>,
}

impl StationGroup {
    fn of(stations: &[Station]) -> StationGroup {
        StationGroup {
            positions: stations.iter().map(|s| s.x).collect(),
            allowable: stations.iter().map(|s| s.allowable).collect(),
            nodes: stations.iter().map(|s| s.node as u32).collect(),
        }
    }

    /// Number of stations.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// True without stations.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Whether the three lists have one entry per station, every position and allowable finite.
    pub fn is_consistent(&self) -> bool {
        self.allowable.len() == self.len()
            && self.nodes.len() == self.len()
            && self.positions.iter().chain(&self.allowable).all(|v| v.is_finite())
    }

    /// For each element of a beam of `elements` elements, the stations that bound it (their
    /// indices in this group): a node's one station serves both elements beside it, the two
    /// sides of a node each their own element.
    pub fn stations_of_elements(&self, elements: usize) -> Vec<Vec<usize>> {
        let mut out = vec![Vec::new(); elements];
        let mut k = 0;
        while k < self.nodes.len() {
            let node = self.nodes[k] as usize;
            let two = self.nodes.get(k + 1) == Some(&self.nodes[k]);
            let (left, right) = if two { (k, k + 1) } else { (k, k) };
            if node > 0 && node <= elements {
                out[node - 1].push(left);
            }
            if node < elements {
                out[node].push(right);
            }
            k += if two { 2 } else { 1 };
        }
        out
    }
}

/// Every station of a run, in the order of [`Stations::all`]: the arrestor's bending, its shear,
/// the bridge's bending, its shear.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StationLayout {
    /// The arrestor's bending stations, from the clamp.
    pub lower_bending: StationGroup,
    /// The arrestor's shear stations.
    pub lower_shear: StationGroup,
    /// The bridge's bending stations, from the hinge.
    pub upper_bending: StationGroup,
    /// The bridge's shear stations (none without a shear area).
    pub upper_shear: StationGroup,
    /// The steps at which the stations are evaluated: every `sampled_every`-th (see
    /// [`crate::solver::envelope::ENVELOPE_BUDGET`]); the log's per-step stresses follow it.
    pub sampled_every: u64,
}

impl StationLayout {
    /// The layout of a model's `stations`, evaluated every `sampled_every` steps.
    pub fn of(stations: &Stations, sampled_every: u64) -> StationLayout {
        StationLayout {
            lower_bending: StationGroup::of(&stations.lower.bending),
            lower_shear: StationGroup::of(&stations.lower.shear),
            upper_bending: StationGroup::of(&stations.upper.bending),
            upper_shear: StationGroup::of(&stations.upper.shear),
            sampled_every: sampled_every.max(1),
        }
    }

    /// The four groups in order.
    pub fn groups(&self) -> [&StationGroup; 4] {
        [&self.lower_bending, &self.lower_shear, &self.upper_bending, &self.upper_shear]
    }

    /// Number of stations.
    pub fn len(&self) -> usize {
        self.groups().iter().map(|g| g.len()).sum()
    }

    /// True without stations.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// What the simulation tells a recorder about the current step and the run so far.
#[derive(Debug, Default)]
struct FeedState {
    /// The static correction's load coefficients of the step about to be recorded (None: a
    /// full basis, where the kept modes say everything).
    loads: Option<[f64; LOADS]>,
    /// The run's stress envelope as of the end of the latest advance.
    envelope: Option<StressEnvelope>,
    /// The envelope's largest |stress| at every station as of the step about to be recorded, Pa,
    /// in the layout's order, then when each was reached, s (empty: not given).
    maxima: Vec<f64>,
}

/// The simulation's side of the stations' feed (see the module's documentation).
#[derive(Debug, Default)]
pub struct StationFeed {
    state: Mutex<FeedState>,
}

impl StationFeed {
    fn with<T>(&self, f: impl FnOnce(&mut FeedState) -> T) -> T {
        // A panic elsewhere while the lock was held leaves plain numbers: still usable.
        f(&mut self.state.lock().unwrap_or_else(PoisonError::into_inner))
    }

    /// The load coefficients of the step about to be recorded.
    pub fn set_loads(&self, loads: Option<[f64; LOADS]>) {
        self.with(|s| s.loads = loads);
    }

    /// The load coefficients of the latest step.
    pub fn loads(&self) -> Option<[f64; LOADS]> {
        self.with(|s| s.loads)
    }

    /// The run's envelope so far.
    pub fn set_envelope(&self, envelope: StressEnvelope) {
        self.with(|s| s.envelope = Some(envelope));
    }

    /// The latest envelope given, if any.
    pub fn envelope(&self) -> Option<StressEnvelope> {
        self.with(|s| s.envelope.clone())
    }

    /// The envelope's largest |stress| at every station as of the step about to be recorded
    /// (the simulation's running maxima, Pa, in the layout's order) and when each was reached, s.
    pub fn set_maxima(&self, maxima: &[f64], times: &[f64]) {
        self.set_maxima_with(maxima, times, |_, _| {});
    }

    /// [`Self::set_maxima`], then `adjust` applied to the copies (maxima, times).
    pub fn set_maxima_with(&self, maxima: &[f64], times: &[f64], adjust: impl FnOnce(&mut [f64], &mut [f64])) {
        self.with(|s| {
            s.maxima.clear();
            if maxima.len() == times.len() {
                s.maxima.extend_from_slice(maxima);
                s.maxima.extend_from_slice(times);
                let (max, times) = s.maxima.split_at_mut(maxima.len());
                adjust(max, times);
            }
        });
    }

    /// Appends the latest running maxima given, then their times, to `out` (nothing if none were).
    pub fn append_maxima(&self, out: &mut Vec<f64>) {
        self.with(|s| out.extend_from_slice(&s.maxima));
    }
}

/// The simulation's end of a [`StationFeed`]: written to only while a recorder holds the other
/// end. A clone (a simulation cloned) gets a feed of its own, which nobody holds, so that two
/// simulations never write into one log's feed.
#[derive(Debug, Default)]
pub struct FeedEnd(Arc<StationFeed>);

impl Clone for FeedEnd {
    fn clone(&self) -> Self {
        FeedEnd::default()
    }
}

impl FeedEnd {
    /// The feed, if a recorder holds it.
    pub fn listened(&self) -> Option<&StationFeed> {
        (Arc::strong_count(&self.0) > 1).then_some(&*self.0)
    }

    /// The recorder's end.
    pub fn share(&self) -> Arc<StationFeed> {
        Arc::clone(&self.0)
    }
}

/// The stations of a run, handed to a recorder at `start` (in [`super::RunInfo::stations`]).
#[derive(Clone, Debug)]
pub struct StationProbe {
    /// Where the stations are.
    pub layout: StationLayout,
    /// Their rows in modal coordinates: a step's stresses from its coordinates and loads.
    pub rows: Arc<StationRows>,
    /// The simulation's per-step loads and the run's envelope.
    pub feed: Arc<StationFeed>,
}

/// Splits the stresses of every station (in the order of [`StationLayout::groups`]) into the
/// four groups; None when `values` does not hold one per station.
pub fn split<'a, T>(layout: &StationLayout, values: &'a [T]) -> Option<[&'a [T]; 4]> {
    if values.len() != layout.len() {
        return None;
    }
    let counts = layout.groups().map(|g| g.len());
    let (a, rest) = values.split_at(counts[0]);
    let (b, rest) = rest.split_at(counts[1]);
    let (c, d) = rest.split_at(counts[2]);
    Some([a, b, c, d])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A node's one station bounds both elements beside it; the two sides of a section change
    /// each bound their own element.
    #[test]
    fn elements_take_the_stations_at_their_ends_on_their_side() {
        let group = StationGroup {
            positions: vec![0.0, 1.0, 2.0, 2.0, 3.0],
            allowable: vec![1.0; 5],
            nodes: vec![0, 1, 2, 2, 3],
        };
        assert_eq!(group.stations_of_elements(3), vec![vec![0, 1], vec![1, 2], vec![3, 4]]);
        assert!(group.is_consistent());
        let layout = StationLayout { lower_bending: group.clone(), upper_shear: group, ..Default::default() };
        let values: Vec<u32> = (0..10).collect();
        let [a, b, c, d] = split(&layout, &values).unwrap();
        assert_eq!((a.len(), b.len(), c.len(), d.len()), (5, 0, 0, 5));
        assert!(split(&layout, &values[1..]).is_none());
    }
}
