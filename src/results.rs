//! What a run produces: one [`StepResult`] per internal step, contact events, and the summary.

use serde::{Deserialize, Serialize};

/// Seconds from the integer nanoseconds every time in the crate is counted in: the one
/// conversion, so that step results, logs and FMU outputs carry the same f64 for a time.
pub fn seconds(ns: u64) -> f64 {
    ns as f64 / 1e9
}

/// The energy account of Section 2 at one instant, J. The residual is what the discrete
/// balance misses: kinetic + strain + gravity + dissipated - external work - initial total.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EnergyAccount {
    /// 1/2 v^T M v of both beams.
    pub kinetic: f64,
    /// Strain energy of both beams and of the bar while in contact.
    pub strain: f64,
    /// -F_g^T delta, from the undeformed horizontal position.
    pub gravity_potential: f64,
    /// Work done by the two external tip forces since t = 0.
    pub external_work: f64,
    /// Energy dissipated by damping since t = 0 (trapezoidal integral of v^T C v).
    pub damping_dissipation: f64,
    /// Balance residual.
    pub residual: f64,
}

/// Running peaks max |.| since t = 0 of the Table 1 quantities (and the contact force).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Peaks {
    /// Arrestor end deflection w_din,a, m.
    pub lower_tip_deflection: f64,
    /// Bending stress at the clamp sigma_din,a, Pa.
    pub lower_clamp_bending_stress: f64,
    /// Shear stress at the clamp tau_din,a, Pa.
    pub lower_clamp_shear_stress: f64,
    /// Bending stress at the bridge's contact node sigma_din,b, Pa.
    pub upper_contact_bending_stress: f64,
    /// Contact bar force, N.
    pub contact_force: f64,
}

impl Peaks {
    /// The five peak quantities in a fixed order (for loops over them).
    pub fn as_array(&self) -> [f64; 5] {
        [
            self.lower_tip_deflection,
            self.lower_clamp_bending_stress,
            self.lower_clamp_shear_stress,
            self.upper_contact_bending_stress,
            self.contact_force,
        ]
    }

    /// The peaks from five values in the order of [`Peaks::as_array`].
    pub fn from_array(v: [f64; 5]) -> Peaks {
        Peaks {
            lower_tip_deflection: v[0],
            lower_clamp_bending_stress: v[1],
            lower_clamp_shear_stress: v[2],
            upper_contact_bending_stress: v[3],
            contact_force: v[4],
        }
    }

    /// Raises each peak to |value| where that is larger (values in the order of [`Peaks::as_array`]).
    pub fn raise(&mut self, values: &[f64; 5]) {
        let mut peaks = self.as_array();
        for (peak, value) in peaks.iter_mut().zip(values) {
            *peak = peak.max(value.abs());
        }
        *self = Peaks::from_array(peaks);
    }

    /// Mutable access in the order of [`Peaks::as_array`].
    pub fn as_mut_array(&mut self) -> [&mut f64; 5] {
        [
            &mut self.lower_tip_deflection,
            &mut self.lower_clamp_bending_stress,
            &mut self.lower_clamp_shear_stress,
            &mut self.upper_contact_bending_stress,
            &mut self.contact_force,
        ]
    }
}

/// Results at the end of one internal step (y up: deflections are negative downward).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StepResult {
    /// Steps taken since t = 0 (0 is the initial state).
    pub step: u64,
    /// Simulated time since impact, ns (integer: the time base of the logs).
    pub time_ns: u64,
    /// Simulated time since impact, s.
    pub time: f64,
    /// Size of the step that ended here, s (0 for the initial state).
    pub step_size: f64,
    /// Whether that step was taken in contact (Eq. 6 at its start).
    pub contact: bool,
    /// Deflection of the arrestor's end (node 8), m.
    pub lower_tip_deflection: f64,
    /// Deflection of the bridge's contact node (node 16), m.
    pub upper_contact_deflection: f64,
    /// Deflection of the bridge's free end, m.
    pub upper_tip_deflection: f64,
    /// Bending stress M/W at the clamp (node 1), Pa, sagging positive.
    pub lower_clamp_bending_stress: f64,
    /// Shear stress Q/A_s at the clamp, Pa.
    pub lower_clamp_shear_stress: f64,
    /// Bending stress M/W at the bridge's contact node, Pa, sagging positive.
    pub upper_contact_bending_stress: f64,
    /// Contact bar force F_c (Eq. 5), N: negative in compression, 0 when apart.
    pub contact_force: f64,
    /// Contact bar stress F_c / A_c, Pa.
    pub contact_stress: f64,
    /// Vertical force of the clamp on the arrestor, N, up positive (the dynamic reaction: the
    /// clamp's row of stiffness, damping, consistent mass and loads).
    pub lower_clamp_reaction_force: f64,
    /// Moment of the clamp on the arrestor, N m, counter-clockwise positive (x from the clamp).
    pub lower_clamp_reaction_moment: f64,
    /// Vertical force of the hinge on the bridge, N, up positive.
    pub upper_hinge_reaction_force: f64,
    /// Vertical velocity of the arrestor's end, m/s, up positive.
    pub lower_tip_velocity: f64,
    /// Vertical velocity of the bridge's free end, m/s, up positive.
    pub upper_tip_velocity: f64,
    /// The hinge's heave at this instant, m, up positive (issue 17; 0 for fixed supports): the
    /// bridge's free end is at `upper_tip_deflection` plus it ([`StepResult::upper_tip_position`]).
    #[serde(default)]
    pub upper_support_displacement: f64,
    /// The clamp's heave plus its rotation times the arrestor's length at this instant, m (0 for
    /// fixed supports): the rigid rise of the arrestor's end ([`StepResult::lower_tip_position`]).
    #[serde(default)]
    pub lower_support_displacement: f64,
    /// Vertical force of the struck beam's far support on it, N, up positive (issue 45: a beam
    /// on two supports; 0 for the paper's free end).
    #[serde(default)]
    pub lower_far_reaction_force: f64,
    /// Moment of the far support on the struck beam, N m, counter-clockwise positive (a clamped
    /// far end; 0 at a pin or a free end).
    #[serde(default)]
    pub lower_far_reaction_moment: f64,
    /// Energy account.
    pub energy: EnergyAccount,
    /// Running peaks.
    pub peaks: Peaks,
}

impl StepResult {
    /// The |value| of each peak output, in the order of [`Peaks::as_array`]: what the running
    /// peaks are the largest of.
    pub fn peak_magnitudes(&self) -> [f64; 5] {
        [
            self.lower_tip_deflection.abs(),
            self.lower_clamp_bending_stress.abs(),
            self.lower_clamp_shear_stress.abs(),
            self.upper_contact_bending_stress.abs(),
            self.contact_force.abs(),
        ]
    }

    /// Absolute vertical position of the bridge's free end, m, up positive: its deflection plus
    /// the hinge's heave (0 at the undeformed horizontal with the supports at rest).
    pub fn upper_tip_position(&self) -> f64 {
        self.upper_support_displacement + self.upper_tip_deflection
    }

    /// Absolute vertical position of the arrestor's end, m: its deflection plus the clamp's heave
    /// and rotation's rise there.
    pub fn lower_tip_position(&self) -> f64 {
        self.lower_support_displacement + self.lower_tip_deflection
    }
}

/// The start or the end of a contact stage.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ContactEvent {
    /// True when contact starts, false when the beams separate.
    pub start: bool,
    /// Time at which Eq. (6) changed, ns (start of the first step in the new stage).
    pub time_ns: u64,
    /// Index of the first step in the new stage.
    pub step: u64,
    /// Relative velocity of the contact points d(y_k,u - y_k,l)/dt, m/s (negative approaching).
    pub relative_velocity: f64,
}

/// One interval of contact, s.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ContactWindow {
    /// Start, s.
    pub start: f64,
    /// End, s (the run's end if still in contact).
    pub end: f64,
}

/// Natural frequencies of Table 2, rad/s, the first five (or fewer) of each column.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ModeTable {
    /// Arrestor alone.
    pub lower: Vec<f64>,
    /// Bridge alone.
    pub upper: Vec<f64>,
    /// Coupled through an always-active bar.
    pub coupled: Vec<f64>,
}

/// Whether a run's numbers can be trusted, by its own energy balance.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Quality {
    /// Largest |energy residual| as a fraction of the energy that flows in the run: the larger of
    /// m_u g h + |external work| and the largest strain energy reached.
    pub energy_residual_fraction: f64,
    /// The scenario's tolerance on that fraction.
    pub energy_tolerance: f64,
    /// True when the fraction is finite and within the tolerance.
    pub trusted: bool,
    /// Why the run is not trusted (empty when it is).
    pub reasons: Vec<String>,
    /// Warnings that do not decide trust: fixed time steps above the energy-safe limit.
    pub advisories: Vec<String>,
}

impl Quality {
    /// The verdict from a run's energy account: `max_residual` against the energy that flows,
    /// the larger of `impact_energy` (m_u g h) + `max_external_work` and `max_strain_energy`, J.
    pub fn assess(
        max_residual: f64,
        impact_energy: f64,
        max_external_work: f64,
        max_strain_energy: f64,
        energy_tolerance: f64,
        advisories: Vec<String>,
    ) -> Quality {
        let flow = (impact_energy + max_external_work.abs()).max(max_strain_energy);
        let fraction = if flow > 0.0 { max_residual / flow } else { 0.0 };
        let trusted = fraction.is_finite() && fraction <= energy_tolerance;
        let reasons = if trusted {
            Vec::new()
        } else {
            vec![format!(
                "energy residual {max_residual:.4e} J is {} % of the {flow:.4e} J that flow in the run, above \
                 energy_tolerance = {} %",
                percent(fraction),
                percent(energy_tolerance)
            )]
        };
        Quality { energy_residual_fraction: fraction, energy_tolerance, trusted, reasons, advisories }
    }
}

/// A fraction as a percentage people read: 1 %, 0.036 %, 1e-7 %.
fn percent(fraction: f64) -> String {
    let p = fraction * 100.0;
    if p != 0.0 && p.abs() < 1e-3 {
        format!("{p:.1e}")
    } else {
        format!("{}", (p * 1e3).round() / 1e3)
    }
}

/// Contact windows closer than this are one window (the bounces of one contact), s.
pub const BOUNCE_GAP: f64 = 0.01;

/// A contact window (bounces merged) at least this long is sustained, s.
pub const SUSTAINED_CONTACT: f64 = 0.1;

/// The peaks of the first sustained contact: from t = 0 until the end of the first contact window
/// (bounces closer than [`BOUNCE_GAP`] merged) that lasts at least [`SUSTAINED_CONTACT`]: 0.75 s
/// on the paper scenario, where the impact's first bounces (separations of 14-15 ms) precede it.
/// A separation as long as a sustained contact ([`SUSTAINED_CONTACT`]) before it ends it too, at
/// its last step in contact: the bodies flew apart and the next touch is another impact (issue 40's
/// re-test: an undamped bridge without gravity bounced off the arrestor's free end four times in
/// 0.5 s, none of its windows sustained, and its fourth impact's peak passed as a first-contact
/// one, beyond the lightly damped run's late-peak rule). The steps of a separation count once
/// contact resumes, so they are held apart until then.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FirstContact {
    /// Peaks max |.| from t = 0 to the end of the first sustained contact (so far, while it lasts).
    pub peaks: Peaks,
    /// Peaks since the latest step in contact.
    pending: Peaks,
    /// Start of the current contact window (bounces merged), s.
    window_start: Option<f64>,
    /// Time of the latest step taken in contact, s.
    last_contact: Option<f64>,
    /// True once the first sustained contact has ended.
    pub ended: bool,
}

impl FirstContact {
    /// Takes one step's results into account, in time order.
    pub fn observe(&mut self, result: &StepResult) {
        let values = [
            result.lower_tip_deflection,
            result.lower_clamp_bending_stress,
            result.lower_clamp_shear_stress,
            result.upper_contact_bending_stress,
            result.contact_force,
        ];
        self.observe_values(result, &values);
    }

    /// [`FirstContact::observe`] with the step's peak values given (the largest |value| of each
    /// output over the step, in the order of [`Peaks::as_array`]).
    pub fn observe_values(&mut self, result: &StepResult, values: &[f64; 5]) {
        if self.ended {
            return;
        }
        let values = *values;
        if result.contact || self.last_contact.is_none() {
            // A step in contact, or before the first one (the impact instant itself).
            let pending = std::mem::take(&mut self.pending).as_array();
            self.peaks.raise(&pending);
            self.peaks.raise(&values);
            if result.contact {
                self.window_start.get_or_insert(result.time);
                self.last_contact = Some(result.time);
            }
            return;
        }
        self.pending.raise(&values);
        if let Some(end) = self.last_contact {
            let apart = result.time - end;
            match self.window_start {
                Some(start) if apart >= BOUNCE_GAP && end - start >= SUSTAINED_CONTACT => self.ended = true,
                Some(_) if apart >= BOUNCE_GAP => self.window_start = None,
                _ => {}
            }
            if apart >= SUSTAINED_CONTACT {
                self.ended = true;
            }
        }
    }

    /// When the first sustained contact ended (its last step in contact), s; `None` while it lasts.
    pub fn end(&self) -> Option<f64> {
        if self.ended {
            self.last_contact
        } else {
            None
        }
    }
}

/// The time steps a run used, s (automatic ones resolved).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TimeSteps {
    /// Out of contact, s.
    pub free: f64,
    /// In contact, s.
    pub contact: f64,
}

/// The impact as the run starts it (issue 28): printed by every run, `--json`'s `impact`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Impact {
    /// The bridge's angular velocity about its hinge at first contact, rad/s, free end moving
    /// down: stated, or from the drop height (Eqs. 20-22).
    pub angular_velocity: f64,
    /// The speed at which the contact point closes the gap at t = 0, m/s: omega_0 d plus the
    /// supports' closing speed.
    pub closing_speed: f64,
}

/// The whole run's summary: what the CLI prints and `--json` writes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Internal steps taken.
    pub steps: u64,
    /// Simulated time reached, s.
    pub time: f64,
    /// Running peaks at the end.
    pub peaks: Peaks,
    /// Times at which each peak was reached, s (same order as the peaks).
    pub peak_times: Peaks,
    /// Bridge strain energy at the instant of the largest arrestor deflection, J (E_def,b, Eq. 36).
    pub upper_strain_at_peak_deflection: f64,
    /// Contact intervals.
    pub contact_windows: Vec<ContactWindow>,
    /// Energy balance residual at the end, J.
    pub final_energy_residual: f64,
    /// Largest |residual| during the run, J.
    pub max_energy_residual: f64,
    /// Energy approach of Section 3.
    pub energy_method: crate::solver::EnergyMethod,
    /// Natural frequencies (Table 2).
    pub modes: ModeTable,
    /// The energy verdict.
    pub quality: Quality,
    /// Peaks from t = 0 to the end of the first sustained contact (see [`FirstContact`]).
    pub first_contact_peaks: Peaks,
    /// End of the first sustained contact, s (null if it lasts to the end of the run).
    pub first_contact_end: Option<f64>,
    /// The time steps used.
    pub time_steps: TimeSteps,
    /// The impact's angular velocity and closing speed.
    #[serde(default)]
    pub impact: Impact,
    /// The stress envelope along each beam (issue 30).
    #[serde(default)]
    pub envelope: StressEnvelope,
    /// The linear model's range over every node of both beams (issue 40); a summary rebuilt
    /// from a log leaves it at its default (the stored answer's verdict carries its check).
    #[serde(default)]
    pub model_range: crate::solver::model_range::RangeCheck,
    /// Each contact window as an impact (issue 45): start, duration, peak force and the apparent
    /// restitution; a summary rebuilt from a log leaves it empty (the log's `answer.json` has it).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sub_impacts: Vec<SubImpact>,
}

/// One contact window seen as an impact (issue 45): the first strike, the rebound's later
/// sub-impacts, or one bounce of a chattering contact (no merging: see `merged_contact_windows`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SubImpact {
    /// When the contact starts, s.
    pub start: f64,
    /// How long it lasts, s (to the run's end if still in contact).
    pub duration: f64,
    /// The largest contact force in it, N.
    pub peak_force: f64,
    /// When that force is reached, s.
    pub peak_time: f64,
    /// The speed at which the striking point closes on the struck point at the start, m/s (>= 0:
    /// minus the gap's rate, Eq. 6's y_k,u - y_k,l).
    pub approach_speed: f64,
    /// The speed at which they part at the end, m/s (the gap's rate; null while still in contact).
    pub separation_speed: Option<f64>,
    /// The apparent coefficient of restitution, separation speed / approach speed (null while
    /// still in contact, or with no approach speed): 1 for an elastic contact on a rigid
    /// support, below 1 where the struck beam keeps vibrating (its energy not given back at
    /// separation) or the contact damps.
    pub restitution: Option<f64>,
}

impl SubImpact {
    /// A window opening at `time` (s) with the gap's rate `gap_rate` (m/s, negative approaching).
    pub fn starting(time: f64, gap_rate: f64) -> SubImpact {
        SubImpact {
            start: time,
            duration: 0.0,
            peak_force: 0.0,
            peak_time: time,
            approach_speed: (-gap_rate).max(0.0),
            separation_speed: None,
            restitution: None,
        }
    }

    /// A contact step ending at `time` (s) whose largest force was `force` (N at s).
    pub fn observe(&mut self, time: f64, (force, at): (f64, f64)) {
        self.duration = time - self.start;
        if force > self.peak_force {
            self.peak_force = force;
            self.peak_time = at;
        }
    }

    /// The window closes at `time` (s) with the gap opening at `gap_rate` (m/s).
    pub fn separate(&mut self, time: f64, gap_rate: f64) {
        self.duration = time - self.start;
        self.separation_speed = Some(gap_rate);
        self.restitution = (self.approach_speed > 0.0).then(|| gap_rate / self.approach_speed);
    }
}

/// One stress's envelope along a beam: at each station (a node; two at a section change or a
/// point load's shear jump) its largest |stress| over the run and when.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StationEnvelope {
    /// Stations' positions, m from the beam's support (the clamp, the hinge).
    pub positions: Vec<f64>,
    /// Largest |stress| at each station, Pa.
    pub max: Vec<f64>,
    /// When each was reached, s.
    pub times: Vec<f64>,
    /// The allowable stress of the section at each station, Pa (0: none given).
    pub allowable: Vec<f64>,
}

/// The peak of an envelope: the largest stress with where and when, and the worst utilisation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EnvelopePeak {
    /// Largest |stress| along the beam, Pa.
    pub value: f64,
    /// Its position, m from the support.
    pub position: f64,
    /// When, s.
    pub time: f64,
    /// The largest stress / allowable along the beam (null: no allowable given).
    pub utilisation: Option<f64>,
    /// Where that utilisation is, m (null: no allowable given).
    pub utilisation_position: Option<f64>,
}

impl StationEnvelope {
    /// The envelope's peak and its worst utilisation; None without stations (the bridge
    /// without a shear area, a rigid support).
    pub fn peak(&self) -> Option<EnvelopePeak> {
        let mut peak: Option<EnvelopePeak> = None;
        for k in 0..self.max.len() {
            let p = peak.get_or_insert(EnvelopePeak {
                value: self.max[k],
                position: self.positions[k],
                time: self.times[k],
                utilisation: None,
                utilisation_position: None,
            });
            if self.max[k] > p.value {
                (p.value, p.position, p.time) = (self.max[k], self.positions[k], self.times[k]);
            }
            if self.allowable[k] > 0.0 {
                let u = self.max[k] / self.allowable[k];
                if p.utilisation.is_none_or(|w| u > w) {
                    (p.utilisation, p.utilisation_position) = (Some(u), Some(self.positions[k]));
                }
            }
        }
        peak
    }
}

/// Bending and shear envelopes of one beam.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BeamEnvelope {
    /// |M| / W at each bending station.
    pub bending: StationEnvelope,
    /// |Q| / A_s at each shear station (empty for a beam without a shear area).
    pub shear: StationEnvelope,
}

/// The stress envelope of both beams.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StressEnvelope {
    /// The arrestor's, from the clamp.
    pub lower: BeamEnvelope,
    /// The bridge's, from the hinge.
    pub upper: BeamEnvelope,
    /// The steps the stations were evaluated at: every `sampled_every`-th (1: every step; more
    /// on a full basis of hundreds of elements, see [`crate::solver::envelope::ENVELOPE_BUDGET`]).
    #[serde(default = "one")]
    pub sampled_every: u64,
}

fn one() -> u64 {
    1
}

/// The envelope peaks' names (`summary.peaks`' keys, the FMU's `peak.` outputs), in the order of
/// [`StressEnvelope::peaks`].
pub const ENVELOPE_PEAK_NAMES: [&str; 4] =
    ["upper.bending_stress", "upper.shear_stress", "lower.bending_stress", "lower.shear_stress"];

impl StressEnvelope {
    /// Each beam's worst bending and shear stress, in the order of [`ENVELOPE_PEAK_NAMES`].
    pub fn peaks(&self) -> [Option<EnvelopePeak>; 4] {
        [self.upper.bending.peak(), self.upper.shear.peak(), self.lower.bending.peak(), self.lower.shear.peak()]
    }

    /// The peaks' values only, in the same order.
    pub fn peak_values(&self) -> [Option<f64>; 4] {
        self.peaks().map(|p| p.map(|p| p.value))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Steps every millisecond from 0 to `end` s: in contact within `windows`, the contact force
    /// `force(t)` (the other peaks 0).
    fn observed(windows: &[(f64, f64)], end: f64, force: impl Fn(f64) -> f64) -> FirstContact {
        let mut first = FirstContact::default();
        for i in 0..=(end * 1e3).round() as usize {
            let time = i as f64 * 1e-3;
            let contact = windows.iter().any(|&(a, b)| (a..=b).contains(&time));
            first.observe(&StepResult { time, contact, contact_force: force(time), ..Default::default() });
        }
        first
    }

    /// The paper's pattern: bounces 15 ms apart, then a window of 0.3 s: the first contact holds
    /// the bounces and the sustained window, and ends with it.
    #[test]
    fn the_first_contact_spans_short_bounces_and_ends_with_the_sustained_window() {
        let windows = [(0.0, 0.02), (0.035, 0.05), (0.065, 0.365), (0.6, 0.7)];
        let first = observed(&windows, 1.0, |t| if t > 0.6 { 9.0 } else { 1.0 + t });
        assert!(first.ended);
        assert_eq!(first.end(), Some(0.365));
        assert_eq!(first.peaks.contact_force, 1.365, "the sustained window's largest, not the later impact's 9");
    }

    /// Issue 40's re-test: windows of 25 ms with a 121 ms flight between (no window sustained): the
    /// flight ends the first contact at its last step in contact, so a later impact's peak is not a
    /// first-contact one; separations shorter than 0.1 s do not.
    #[test]
    fn a_flight_as_long_as_a_sustained_contact_ends_the_first_contact() {
        let windows = [(0.0, 0.025), (0.044, 0.061), (0.182, 0.21), (0.237, 0.248)];
        let first = observed(&windows, 0.5, |t| if t > 0.1 { 5.0 } else { t });
        assert_eq!(first.end(), Some(0.061));
        assert_eq!(first.peaks.contact_force, 0.061);
        // Flights of 99 ms between short windows: one first contact, over the whole run.
        let windows = [(0.0, 0.02), (0.119, 0.14), (0.239, 0.26)];
        let first = observed(&windows, 0.3, |t| t);
        assert_eq!(first.end(), None);
        assert_eq!(first.peaks.contact_force, 0.26);
    }
}
