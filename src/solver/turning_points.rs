//! Every stress station's turning points over a run (issue 44, fatigue): the peaks and valleys of
//! its signed stress history, all that rainflow counting (ASTM E1049-85, 2017, section 5.4.4)
//! needs of it, kept as the run steps so that no history is stored.
//!
//! A station's history is its value at every internal step's end; over the exact advance's
//! contact steps, which grow long (the contact bar's force a cubic over them), the history
//! between two ends is the cubic through the values and rates there (as
//! [`super::envelope::StationRows::observe_step`] takes each station's largest |value| from it),
//! and the cubic's stationary points inside the step are samples too, in time order: a crest
//! inside a step is a turning point of its own. Other steps (the paper method's short fixed steps,
//! the exact advance's free steps) are taken by their ends, as the envelope takes them.
//!
//! A step the simulation takes and then leaves untaken (a communication point inside it, the
//! state at a stop point) must not count: the latest step's samples can be undone, and are when
//! the next step starts before it ended (a retake) or the run ends before it
//! ([`TurningPoints::finish`]). The simulation retakes one step at most; the undo record is
//! written in the same pass as the samples (no copy of the state per step).
//!
//! Pure numbers: no I/O. A sample equal to the one before (a plateau) is no turning point; the
//! first and the last sample that moved the history always are (the residue's ends, as ASTM
//! E1049 counts them): the values [`crate::fatigue::ReversalTracker`] keeps of the same samples.
//! Only the stations asked for are followed (a run's bending stations: the S-N curves are of
//! direct stress ranges).

use std::ops::Range;

/// Each followed station's turning points so far, with the latest step's undo record.
#[derive(Clone, Debug, Default)]
pub struct TurningPoints {
    /// Each followed station's index into the values pushed.
    index: Vec<usize>,
    /// Per followed station, its confirmed turning points (the first sample first).
    points: Vec<Vec<f64>>,
    /// Per followed station, its latest sample that moved the history (the candidate turning
    /// point), and the direction of its current run: 1 rising, -1 falling, 0 none yet.
    last: Vec<f64>,
    direction: Vec<i8>,
    /// The state before the latest step's samples, per followed station.
    undo_last: Vec<f64>,
    undo_direction: Vec<i8>,
    undo_len: Vec<usize>,
    /// The latest step (start, end, ns), whether it pushed samples, and the step before it.
    step: Option<(u64, u64)>,
    pushed: bool,
    step_before: Option<(u64, u64)>,
    /// Retakes of a step older than the latest (not undone): the history is then not the run's
    /// own, and says so (none in the simulation's retakes).
    pub lost_steps: u64,
}

impl TurningPoints {
    /// Turning points of the stations `followed` (index ranges into the values pushed), none
    /// pushed yet.
    pub fn new(followed: Vec<Range<usize>>) -> TurningPoints {
        let index: Vec<usize> = followed.into_iter().flatten().collect();
        let n = index.len();
        TurningPoints {
            index,
            points: vec![Vec::new(); n],
            last: vec![0.0; n],
            direction: vec![0; n],
            undo_last: vec![0.0; n],
            undo_direction: vec![0; n],
            undo_len: vec![0; n],
            ..Default::default()
        }
    }

    /// Number of followed stations.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True without stations.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The index (into the values pushed) of each followed station, in order.
    pub fn stations(&self) -> &[usize] {
        &self.index
    }

    /// Starts a step from `start_ns` to `end_ns` (the initial state: 0, 0): a step that starts
    /// before the latest one ended retakes it, which is undone first.
    pub fn begin_step(&mut self, start_ns: u64, end_ns: u64) {
        if self.step.is_some_and(|(_, end)| start_ns < end) {
            self.undo_latest();
            if self.step.is_some_and(|(_, end)| start_ns < end) {
                self.lost_steps += 1;
            }
        }
        self.step_before = self.step;
        self.step = Some((start_ns, end_ns));
        self.pushed = false;
    }

    /// Undoes the latest step (once: the step before it stays).
    fn undo_latest(&mut self) {
        if self.pushed {
            self.last.copy_from_slice(&self.undo_last);
            self.direction.copy_from_slice(&self.undo_direction);
            for (points, &n) in self.points.iter_mut().zip(&self.undo_len) {
                points.truncate(n);
            }
        }
        self.pushed = false;
        self.step = self.step_before.take();
    }

    /// The run ended at `end_ns`: a latest step past it (taken to interpolate a point inside it)
    /// is undone.
    pub fn finish(&mut self, end_ns: u64) {
        if self.step.is_some_and(|(_, end)| end > end_ns) {
            self.undo_latest();
        }
    }

    /// One sample of every station (`values`, one per station of the run, in order) in the
    /// step begun.
    pub fn push(&mut self, values: &[f64]) {
        self.snapshot();
        let states = self.points.iter_mut().zip(self.last.iter_mut()).zip(self.direction.iter_mut());
        for (((points, last), direction), &k) in states.zip(&self.index) {
            if let Some(&x) = values.get(k) {
                join(points, last, direction, x);
            }
        }
        self.pushed = true;
    }

    /// The samples of a step of the cubic through each station's values `y0`, `y1` and rates
    /// `r0`, `r1` (per s) at its ends, `h` s apart: its stationary points inside the step in
    /// time order, then its end `y1`.
    pub fn push_cubic(&mut self, (y0, r0): (&[f64], &[f64]), (y1, r1): (&[f64], &[f64]), h: f64) {
        self.snapshot();
        let n = y0.len().min(r0.len()).min(y1.len()).min(r1.len());
        let states = self.points.iter_mut().zip(self.last.iter_mut()).zip(self.direction.iter_mut());
        for (((points, last), direction), &k) in states.zip(&self.index) {
            if k >= n {
                continue;
            }
            let (inside, count) = stationary_values(y0[k], y1[k], h * r0[k], h * r1[k]);
            for &v in &inside[..count] {
                join(points, last, direction, v);
            }
            join(points, last, direction, y1[k]);
        }
        self.pushed = true;
    }

    /// Writes the undo record of the step's samples about to be taken.
    fn snapshot(&mut self) {
        self.undo_last.copy_from_slice(&self.last);
        self.undo_direction.copy_from_slice(&self.direction);
        for (n, points) in self.undo_len.iter_mut().zip(&self.points) {
            *n = points.len();
        }
    }

    /// Followed station `i`'s turning points so far: its confirmed ones and its latest sample
    /// that moved the history; empty before any sample.
    pub fn of(&self, i: usize) -> Vec<f64> {
        let Some(points) = self.points.get(i) else { return Vec::new() };
        let mut out = points.clone();
        if self.direction[i] != 0 {
            out.push(self.last[i]);
        }
        out
    }

    /// Number of turning points held, over every followed station.
    pub fn total(&self) -> usize {
        self.points.iter().map(Vec::len).sum::<usize>() + self.direction.iter().filter(|d| **d != 0).count()
    }
}

/// Sample `x` joins a station's history: its confirmed turning `points`, its latest sample that
/// moved it `last` and the direction of its current run `direction`.
#[inline(always)]
fn join(points: &mut Vec<f64>, last: &mut f64, direction: &mut i8, x: f64) {
    if points.is_empty() {
        points.push(x);
        *last = x;
        return;
    }
    let now = if x > *last {
        1
    } else if x < *last {
        -1
    } else {
        // A plateau (its first sample stands for it), or NaN (the last finite sample stays).
        return;
    };
    if now != *direction && *direction != 0 {
        points.push(*last);
    }
    *direction = now;
    *last = x;
}

/// The values of the Hermite cubic p(s) on s in [0, 1] with p(0) = `p0`, p(1) = `p1`, p'(0) =
/// `d0`, p'(1) = `d1` (rates times the step) at its stationary points strictly inside (0, 1), in
/// order of s: at most two (p' is a quadratic; the roots by the numerically stable pair).
#[inline]
pub fn stationary_values(p0: f64, p1: f64, d0: f64, d1: f64) -> ([f64; 2], usize) {
    let (c2, c3) = super::step_extrema::cubic_coefficients(p0, p1, d0, d1);
    let value = |s: f64| p0 + s * (d0 + s * (c2 + s * c3));
    // p'(s) = d0 + 2 c2 s + 3 c3 s^2 = 0.
    let (a, b, c) = (3.0 * c3, 2.0 * c2, d0);
    // The common case first, without a root: p' of one sign at both ends has no root inside
    // unless its vertex lies inside with the other sign.
    if d0 * d1 > 0.0 {
        let vertex = -b / (2.0 * a);
        if !(vertex > 0.0 && vertex < 1.0) || (c - b * b / (4.0 * a)) * d0 >= 0.0 {
            return ([0.0; 2], 0);
        }
    }
    let mut roots = [f64::NAN; 2];
    if a.abs() <= 1e-14 * (b.abs() + c.abs()) {
        if b != 0.0 {
            roots[0] = -c / b;
        }
    } else {
        let discriminant = b * b - 4.0 * a * c;
        if discriminant > 0.0 {
            let q = -0.5 * (b + b.signum() * discriminant.sqrt());
            if q != 0.0 {
                roots = [q / a, c / q];
            }
        }
    }
    if roots[1] < roots[0] {
        roots.swap(0, 1);
    }
    let mut out = [0.0; 2];
    let mut count = 0;
    for s in roots {
        if s > 0.0 && s < 1.0 {
            out[count] = value(s);
            count += 1;
        }
    }
    (out, count)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first `n` stations, followed.
    fn first(n: usize) -> Vec<Range<usize>> {
        std::iter::once(0..n).collect()
    }

    /// A sine's turning points: sin(2 pi t) sampled at 1/8 s for 2 s has peaks +1 at t = 1/4,
    /// 5/4 and valleys -1 at 3/4, 7/4; with the first (0) and last (0) samples, six points.
    #[test]
    fn a_sampled_sine_turns_at_its_crests() {
        let mut t = TurningPoints::new(first(1));
        for i in 0..=16 {
            t.begin_step(i, i);
            t.push(&[(std::f64::consts::TAU * i as f64 / 8.0).sin()]);
        }
        t.finish(16);
        let p = t.of(0);
        assert_eq!(p.len(), 6, "{p:?}");
        // The samples at the crests are sin(pi/2) and sin(3 pi/2) to round-off (1e-15).
        for (got, want) in p.iter().zip([0.0, 1.0, -1.0, 1.0, -1.0, 0.0]) {
            assert!((got - want).abs() < 1e-12, "{p:?}");
        }
    }

    /// Plateaus and steps that only extend a run add no turning point.
    #[test]
    fn plateaus_and_monotone_runs_are_no_turning_points() {
        let mut t = TurningPoints::new(first(1));
        for (i, x) in [0.0, 1.0, 1.0, 2.0, 2.0, 2.0, 1.0, 1.0, 0.5, 3.0].iter().enumerate() {
            t.begin_step(i as u64, i as u64 + 1);
            t.push(&[*x]);
        }
        t.finish(10);
        assert_eq!(t.of(0), vec![0.0, 2.0, 0.5, 3.0]);
    }

    /// A step taken and then retaken (it starts before the latest ended) replaces it; a step past
    /// the run's end is undone: the turning points are those of the steps kept.
    #[test]
    fn a_retaken_step_and_a_step_past_the_end_are_undone() {
        let mut t = TurningPoints::new(first(2));
        t.begin_step(0, 0);
        t.push(&[0.0, 0.0]);
        t.begin_step(0, 10);
        t.push(&[5.0, -5.0]);
        // Retaken shorter, with other values.
        t.begin_step(10, 30);
        t.push(&[-7.0, 9.0]);
        t.begin_step(10, 20);
        t.push(&[1.0, -6.0]);
        t.begin_step(20, 30);
        t.push(&[-2.0, 4.0]);
        t.begin_step(30, 45);
        t.push(&[100.0, 100.0]);
        t.finish(30);
        // Station 0 kept 0, 5, 1, -2: 1 lies on the fall from 5 to -2.
        assert_eq!(t.of(0), vec![0.0, 5.0, -2.0]);
        assert_eq!(t.of(1), vec![0.0, -6.0, 4.0]);
        assert_eq!(t.lost_steps, 0);
    }

    /// The cubic's stationary points: p(s) = s (1 - s) (s - 1/2) scaled, i.e. with p0 = p1 = 0,
    /// d0 = -1/2, d1 = -1/2: p'(s) = -3 s^2 + 3 s - 1/2 = 0 at s = 1/2 -+ sqrt(3)/6, where
    /// p = -+ sqrt(3)/36 (closed form; round-off 1e-15).
    #[test]
    fn a_cubic_step_turns_at_its_stationary_points() {
        let (values, count) = stationary_values(0.0, 0.0, -0.5, -0.5);
        assert_eq!(count, 2);
        let want = 3f64.sqrt() / 36.0;
        assert!((values[0] + want).abs() < 1e-15 && (values[1] - want).abs() < 1e-15, "{values:?}");
        // Pushed as a step of h = 2 s (rates per s are d / h).
        let mut t = TurningPoints::new(first(1));
        t.begin_step(0, 0);
        t.push(&[0.0]);
        t.begin_step(0, 2);
        t.push_cubic((&[0.0], &[-0.25]), (&[0.0], &[-0.25]), 2.0);
        t.finish(2);
        let p = t.of(0);
        assert_eq!(p.len(), 4);
        assert!((p[1] + want).abs() < 1e-15 && (p[2] - want).abs() < 1e-15 && p[3] == 0.0, "{p:?}");
        // The shortcut for ends of one slope agrees with sampling the cubic finely: on random
        // cubics, a stationary point inside exactly when p' changes sign on a 1e5-point grid
        // (the grid can miss a pair of roots closer than 1e-5: such cubics are skipped).
        let mut seed = 7u64;
        let mut random = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut compared = 0;
        for _ in 0..2000 {
            let (p0, p1, d0, d1) = (random(), random(), random(), random());
            let (c2, c3) = crate::solver::step_extrema::cubic_coefficients(p0, p1, d0, d1);
            let slope = |s: f64| d0 + 2.0 * c2 * s + 3.0 * c3 * s * s;
            let changes = (0..100_000).filter(|&i| slope(i as f64 * 1e-5) * slope((i + 1) as f64 * 1e-5) < 0.0).count();
            let vertex = -c2 / (3.0 * c3);
            if (vertex - 0.5).abs() < 0.5 && slope(vertex).abs() < 1e-6 {
                continue;
            }
            assert_eq!(stationary_values(p0, p1, d0, d1).1, changes, "{p0} {p1} {d0} {d1}");
            compared += 1;
        }
        assert!(compared > 1900);
        // A monotone step (a straight line) has none.
        assert_eq!(stationary_values(0.0, 1.0, 1.0, 1.0).1, 0);
    }
}
