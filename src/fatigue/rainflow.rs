//! Rainflow counting of a stress history, ASTM E1049-85 (reapproved 2017), "Standard Practices
//! for Cycle Counting in Fatigue Analysis", Sec. 5.4.4 "Rainflow Counting".
//!
//! The variant is the standard's own: the three-point rule with the starting point, and the
//! residue counted as half cycles. With X the range of the two newest unused reversals and Y the
//! range of the two before it:
//! - X < Y: read the next reversal;
//! - X >= Y and Y holds the history's starting point S: count Y as one-half cycle, discard the
//!   first point of Y and move S to its second point (Sec. 5.4.4 step 5);
//! - X >= Y otherwise: count Y as one cycle and discard both its points (step 4).
//!
//! At the end every range still unused, between neighbouring reversals of the residue, counts as
//! one-half cycle (step 6). The residue is not closed on itself (no "repeating history"
//! concatenation): a history of one event is counted as given. Against the four-point method
//! (its closed cycles, and its residue's neighbouring ranges as half cycles) the count per range
//! and mean is the same; where two neighbouring ranges tie (a, b, a) step 5 counts two half
//! cycles a-b, b-a where the four-point method closes one full cycle: the same range, mean and
//! damage (`tests/python/test_fatigue.py` checks both against PyPI `rainflow` and `fatpack`).
//!
//! Reversals are the first sample, every sample where the direction changes and the last sample
//! (Sec. 3.2.11 peak and valley); a plateau (equal neighbours) is one point, at its first sample.
//! A non-finite sample is an error ([`NonFiniteSample`]), never a silent NaN range.

/// A sample that is not a finite number (NaN or infinite): the history cannot be counted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NonFiniteSample {
    /// Index of the sample in the history (0 = the first).
    pub index: usize,
    /// The sample.
    pub value: f64,
}

impl std::fmt::Display for NonFiniteSample {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "stress sample {} is {}: a stress history must be finite", self.index, self.value)
    }
}

impl std::error::Error for NonFiniteSample {}

/// One counted cycle (ASTM E1049-85 Sec. 5.4.4).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Cycle {
    /// The range, |peak - valley|, in the history's unit (Pa for a stress).
    pub range: f64,
    /// The mean, (peak + valley) / 2.
    pub mean: f64,
    /// 1.0 for a full cycle, 0.5 for a half cycle.
    pub count: f64,
    /// Index of the cycle's first point: in the reversals for [`count`], in the history for
    /// [`count_history`].
    pub start: usize,
    /// Index of the cycle's second point, as `start`.
    pub end: usize,
}

/// Follows a history one sample at a time and keeps only its turning points (with their sample
/// indices): the memory a station of a run needs is its number of reversals, not of steps.
/// [`ReversalTracker::turning_points`] equals [`turning_points`] of the same samples.
#[derive(Clone, Debug, Default)]
pub struct ReversalTracker {
    /// The turning points known for certain: the first sample and every change of direction.
    points: Vec<(usize, f64)>,
    /// The newest sample that moved the history, after the last of `points` (the candidate
    /// turning point, or the last sample at the end).
    tail: Option<(usize, f64)>,
    /// The direction from the last of `points` to `tail`: +1 up, -1 down, 0 before any move.
    direction: i8,
    /// Samples seen.
    samples: usize,
}

impl ReversalTracker {
    /// An empty tracker.
    pub fn new() -> Self {
        Self::default()
    }

    /// Takes the next sample. A non-finite sample is refused (the tracker is unchanged).
    pub fn push(&mut self, value: f64) -> Result<(), NonFiniteSample> {
        let index = self.samples;
        if !value.is_finite() {
            return Err(NonFiniteSample { index, value });
        }
        self.samples += 1;
        let Some(&(_, first)) = self.points.last() else {
            self.points.push((index, value));
            return Ok(());
        };
        let reference = self.tail.map_or(first, |(_, v)| v);
        if value == reference {
            return Ok(()); // a plateau: its first sample stands for it
        }
        let direction: i8 = if value > reference { 1 } else { -1 };
        if let Some(tail) = self.tail {
            if direction != self.direction {
                self.points.push(tail);
            }
        }
        self.direction = direction;
        self.tail = Some((index, value));
        Ok(())
    }

    /// The number of samples taken.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// The turning points so far (sample index, value), the newest sample that moved the history
    /// last: what [`turning_points`] gives for the samples taken.
    pub fn turning_points(&self) -> Vec<(usize, f64)> {
        let mut points = self.points.clone();
        points.extend(self.tail);
        points
    }

    /// The reversals' values so far (see [`ReversalTracker::turning_points`]).
    pub fn reversals(&self) -> Vec<f64> {
        self.turning_points().into_iter().map(|(_, v)| v).collect()
    }
}

/// The turning points of `history` with their sample indices: the first sample, each sample where
/// the direction changes (a plateau at its first sample) and the last sample that moved the
/// history. A constant history has one point.
pub fn turning_points(history: &[f64]) -> Result<Vec<(usize, f64)>, NonFiniteSample> {
    let mut tracker = ReversalTracker::new();
    for &x in history {
        tracker.push(x)?;
    }
    Ok(tracker.turning_points())
}

/// The reversals (peaks and valleys) of `history`, see [`turning_points`].
pub fn reversals(history: &[f64]) -> Result<Vec<f64>, NonFiniteSample> {
    Ok(turning_points(history)?.into_iter().map(|(_, v)| v).collect())
}

/// The cycles of a sequence of reversals by ASTM E1049-85 Sec. 5.4.4 (see the module's doc):
/// full cycles in the order they close, then the residue's half cycles from the oldest. `start`
/// and `end` index `reversals`. The input should alternate (as [`reversals`] gives); equal
/// neighbours give a zero range, not an error.
pub fn count(reversals: &[f64]) -> Vec<Cycle> {
    let indexed: Vec<(usize, f64)> = reversals.iter().copied().enumerate().collect();
    count_indexed(&indexed)
}

/// [`count`] of [`turning_points`]`(history)`, with `start` and `end` indexing the history.
pub fn count_history(history: &[f64]) -> Result<Vec<Cycle>, NonFiniteSample> {
    Ok(count_indexed(&turning_points(history)?))
}

/// The cycle between two points, `count` 1.0 or 0.5.
fn cycle(a: (usize, f64), b: (usize, f64), count: f64) -> Cycle {
    Cycle { range: (b.1 - a.1).abs(), mean: 0.5 * (a.1 + b.1), count, start: a.0, end: b.0 }
}

/// ASTM E1049-85 Sec. 5.4.4 steps 1-6 on indexed reversals.
fn count_indexed(points: &[(usize, f64)]) -> Vec<Cycle> {
    let mut cycles = Vec::new();
    // The unused reversals; `stack[0]` is the starting point S.
    let mut stack: Vec<(usize, f64)> = Vec::new();
    for &point in points {
        absorb(&mut stack, &mut cycles, point);
    }
    residue(&stack, &mut cycles);
    cycles
}

/// Steps 1-5 for one more reversal: pushes it on the unused reversals and counts what it closes.
fn absorb(stack: &mut Vec<(usize, f64)>, cycles: &mut Vec<Cycle>, point: (usize, f64)) {
    stack.push(point);
    while stack.len() >= 3 {
        let n = stack.len();
        let x = (stack[n - 1].1 - stack[n - 2].1).abs();
        let y = (stack[n - 2].1 - stack[n - 3].1).abs();
        if x < y {
            break;
        }
        if n == 3 {
            // Step 5: Y holds S: a half cycle, S moves to Y's second point.
            cycles.push(cycle(stack[0], stack[1], 0.5));
            stack.remove(0);
        } else {
            // Step 4: a full cycle; Y's two points are discarded.
            cycles.push(cycle(stack[n - 3], stack[n - 2], 1.0));
            stack.drain(n - 3..n - 1);
        }
    }
}

/// Step 6: the residue's ranges, each one-half cycle.
fn residue(stack: &[(usize, f64)], cycles: &mut Vec<Cycle>) {
    cycles.extend(stack.windows(2).map(|w| cycle(w[0], w[1], 0.5)));
}

/// [`count_history`] one sample at a time, keeping only the unused reversals (the residue, a
/// few points for a decaying impact) and the cycles counted: for a run's stations, step by step.
/// [`RainflowCounter::cycles`] equals [`count_history`] of the samples taken, in the same order;
/// [`RainflowCounter::take_closed`] hands over the cycles closed so far (for a running damage).
#[derive(Clone, Debug, Default)]
pub struct RainflowCounter {
    /// The reversals: what is not yet a certain turning point stays in its `tail`.
    tracker: ReversalTracker,
    /// Whether the tracker's one kept turning point is counted already.
    counted_last: bool,
    /// The unused reversals; `stack[0]` is the starting point.
    stack: Vec<(usize, f64)>,
    /// Cycles closed (steps 4 and 5) and not yet taken.
    closed: Vec<Cycle>,
}

impl RainflowCounter {
    /// An empty counter.
    pub fn new() -> Self {
        Self::default()
    }

    /// Takes the next sample; a non-finite sample is refused (the counter is unchanged).
    pub fn push(&mut self, value: f64) -> Result<(), NonFiniteSample> {
        self.tracker.push(value)?;
        // The certain turning points not yet counted move on to the count; the tracker keeps only
        // the newest (its reference for the direction while it has no tail).
        let points = &mut self.tracker.points;
        let fresh = usize::from(self.counted_last).min(points.len());
        for &point in &points[fresh..] {
            absorb(&mut self.stack, &mut self.closed, point);
        }
        if points.len() > 1 {
            points.drain(..points.len() - 1);
        }
        self.counted_last = !points.is_empty();
        Ok(())
    }

    /// The samples taken.
    pub fn samples(&self) -> usize {
        self.tracker.samples()
    }

    /// Hands over the cycles closed so far (full cycles and start half cycles); later calls give
    /// only newer ones.
    pub fn take_closed(&mut self) -> Vec<Cycle> {
        std::mem::take(&mut self.closed)
    }

    /// The cycles of the samples taken if the history ended here: the closed cycles not taken,
    /// then those the last sample closes and the residue's half cycles (the counter goes on).
    pub fn cycles(&self) -> Vec<Cycle> {
        let mut cycles = self.closed.clone();
        let mut stack = self.stack.clone();
        if let Some(tail) = self.tracker.tail {
            absorb(&mut stack, &mut cycles, tail);
        }
        residue(&stack, &mut cycles);
        cycles
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ASTM E1049-85 Fig. 6 (the rainflow example): -2 1 -3 5 -1 3 -4 4 -2 gives, as the
    /// standard's table beside it: range 3 x 0.5, 4 x 1.5, 6 x 0.5, 8 x 1.0, 9 x 0.5. Exact: the
    /// ranges are differences of small integers.
    #[test]
    fn astm_e1049_fig6_counts_as_the_standard() {
        let history = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0];
        let cycles = count_history(&history).unwrap();
        let total = |range: f64| cycles.iter().filter(|c| c.range == range).map(|c| c.count).sum::<f64>();
        assert_eq!([total(3.0), total(4.0), total(6.0), total(8.0), total(9.0)], [0.5, 1.5, 0.5, 1.0, 0.5]);
        assert_eq!(cycles.iter().map(|c| c.count).sum::<f64>(), 4.0);
        // The one full cycle is -1 -> 3 (samples 4 and 5), mean 1.
        let full: Vec<_> = cycles.iter().filter(|c| c.count == 1.0).collect();
        assert_eq!(full.len(), 1);
        assert_eq!((full[0].range, full[0].mean, full[0].start, full[0].end), (4.0, 1.0, 4, 5));
    }

    #[test]
    fn plateaus_and_monotone_runs_are_one_reversal() {
        let history = [0.0, 1.0, 2.0, 2.0, 2.0, 1.0, 1.0, -1.0, -1.0];
        assert_eq!(turning_points(&history).unwrap(), vec![(0, 0.0), (2, 2.0), (7, -1.0)]);
        assert_eq!(reversals(&[3.0, 3.0, 3.0]).unwrap(), vec![3.0]);
        assert!(count_history(&[3.0, 3.0]).unwrap().is_empty());
        assert!(reversals(&[]).unwrap().is_empty());
    }

    #[test]
    fn a_nan_or_an_infinity_is_an_error_naming_its_index() {
        let e = reversals(&[0.0, 1.0, f64::NAN]).unwrap_err();
        assert_eq!(e.index, 2);
        assert_eq!(e.to_string(), "stress sample 2 is NaN: a stress history must be finite");
        assert_eq!(reversals(&[f64::NEG_INFINITY]).unwrap_err().index, 0);
    }

    /// Each neighbouring pair of n reversals is used once: a full cycle (count 1) turns three
    /// neighbouring ranges into one, a start half cycle (0.5) drops one range, and k residue
    /// points give k - 1 half cycles; so the sum of 2 x count is n - 1, exactly.
    #[test]
    fn half_cycles_total_the_reversal_pairs() {
        let history: Vec<f64> = (0..200).map(|i| ((i * 7919) % 101) as f64 - 50.0).collect();
        let n = reversals(&history).unwrap().len();
        let cycles = count_history(&history).unwrap();
        let halves: f64 = cycles.iter().map(|c| 2.0 * c.count).sum();
        assert_eq!(halves, (n - 1) as f64);
    }

    /// The streaming counter gives the batch count, in the same order, at every length of a
    /// history with plateaus and ties (small integers: exact).
    #[test]
    fn the_streaming_counter_equals_the_batch_count_at_every_sample() {
        let history: Vec<f64> = (0..300).map(|i| (((i * 7919) % 13) as f64 - 6.0).abs().min(4.0)).collect();
        let mut counter = RainflowCounter::new();
        let mut taken = Vec::new();
        for (n, &x) in history.iter().enumerate() {
            counter.push(x).unwrap();
            if n % 17 == 0 {
                taken.extend(counter.take_closed());
            }
            let mut all = taken.clone();
            all.extend(counter.cycles());
            assert_eq!(all, count_history(&history[..=n]).unwrap(), "after sample {n}");
        }
        assert_eq!(counter.samples(), history.len());
        let mut astm = RainflowCounter::new();
        [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0].iter().for_each(|&x| astm.push(x).unwrap());
        assert_eq!(astm.cycles(), count_history(&[-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]).unwrap());
        assert!(astm.push(f64::INFINITY).is_err());
    }
}
