//! Every input of a run in one serde struct, with the paper scenario as [`Default`]
//! (see `docs/scenario.md` for where each number comes from).

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::contact_law::{ContactLaw, LawKind, EXPONENT_RANGE};
use super::discretisation::{auto_count, auto_real, Method, PAPER_ELEMENTS};
use super::load_case::{self, LoadCase};
use super::motion_table::MotionTable;
use super::sea::SeaSettings;
use super::section::{self, SectionSpec};
use super::stress_recovery::StressRecovery;
use super::support_motion::SupportMotion;
use super::supports::Supports;
use super::time_step::TimeStep;
use crate::error::{Error, Result};

/// The bridge (upper beam): hinged at x = 0 (rotation free), free at x = `length`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct UpperBeam {
    /// Length l_u, m. Paper: 29 m.
    pub length: f64,
    /// Total mass m_u, kg, uniformly distributed (Eq. 12). Paper: 12 t.
    pub mass: f64,
    /// Young's modulus E_b, Pa. Paper: 2.1e5 MPa.
    pub elastic_modulus: f64,
    /// Second moment of area I_b, m^4. Paper: 0.01831 m^4.
    pub second_moment: f64,
    /// Section modulus W_b, m^3, for the bending stress M/W. Paper: 0.009978 m^3.
    pub section_modulus: f64,
    /// Equal elements from the hinge to the contact node, or `"auto"` (the default; 0 in the FMU):
    /// the method's mesh (see [`Method`]). Paper (Fig. 5): 7.
    #[serde(with = "auto_count")]
    pub elements_to_contact: u32,
    /// Equal elements from the contact node to the free end, or `"auto"`. Paper (Fig. 5): 7.
    #[serde(with = "auto_count")]
    pub elements_beyond_contact: u32,
    /// Allowable bending stress of the bridge, Pa. Paper: 533 MPa.
    pub allowable_bending_stress: f64,
    /// Yield stress of the bridge, Pa, or 0 (the default): none given. Above it the elastic
    /// model is out of its range and the run is not trusted.
    pub yield_stress: f64,
    /// Constant vertical force at the free end, N, up positive (the FMU overrides it as an input).
    pub tip_force: f64,
    /// Shear area A_s,b, m^2, for the bridge's shear stress Q/A_s, or 0 (the default; the paper
    /// gives none): no shear stress for the bridge.
    #[serde(skip_serializing_if = "is_zero")]
    pub shear_area: f64,
    /// Allowable shear stress of the bridge, Pa, or 0 (the default): none checked.
    #[serde(skip_serializing_if = "is_zero")]
    pub allowable_shear_stress: f64,
    /// The bridge's sections from the hinge (`[[upper.sections]]`, issue 30); none: the uniform
    /// beam of the fields above. With sections, `length` and `mass` follow from them and
    /// `second_moment`, `section_modulus` and `shear_area` are the first section's.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub sections: Vec<SectionSpec>,
    /// `"beam"` (the default: the bridge) or `"mass"` (issue 45: a rigid body of `mass` kg moving
    /// vertically, one translational DOF, dropped from `drop_height` or striking at
    /// `impact_speed`; the bridge's beam fields do not apply).
    #[serde(skip_serializing_if = "ImpactorKind::is_beam")]
    pub kind: ImpactorKind,
    /// The striking body's radius of curvature at the contact, m, for `contact.law = "hertz"`
    /// (a sphere on a flat face); 0 (the default): not given.
    #[serde(skip_serializing_if = "is_zero")]
    pub radius: f64,
    /// Poisson's ratio of the striking body, for `contact.law = "hertz"`. Default 0.3 (steel).
    #[serde(skip_serializing_if = "is_default_poisson")]
    pub poisson_ratio: f64,
}

/// The Poisson's ratio of steel, the default of both bodies' `poisson_ratio` (Hertz's law).
pub const STEEL_POISSON_RATIO: f64 = 0.3;

fn is_default_poisson(x: &f64) -> bool {
    *x == STEEL_POISSON_RATIO
}

/// What strikes (issue 45): the paper's hinged bridge, or a rigid body (a dropped object, a sphere).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ImpactorKind {
    /// The paper's bridge: a hinged-free beam (the default).
    #[default]
    Beam,
    /// A rigid body of `upper.mass` moving vertically (one translational DOF, no rotation).
    Mass,
}

impl ImpactorKind {
    /// The FMU's Integer parameter: 0 beam, 1 mass.
    pub fn index(self) -> u32 {
        match self {
            ImpactorKind::Beam => 0,
            ImpactorKind::Mass => 1,
        }
    }

    /// From the FMU's Integer parameter; `None` outside 0..=1.
    pub fn from_index(value: f64) -> Option<ImpactorKind> {
        match value {
            0.0 => Some(ImpactorKind::Beam),
            1.0 => Some(ImpactorKind::Mass),
            _ => None,
        }
    }

    fn is_beam(&self) -> bool {
        *self == ImpactorKind::Beam
    }
}

impl Default for UpperBeam {
    fn default() -> Self {
        UpperBeam {
            length: 29.0,
            mass: 12_000.0,
            elastic_modulus: 2.1e11,
            second_moment: 0.01831,
            section_modulus: 0.009978,
            elements_to_contact: 0,
            elements_beyond_contact: 0,
            allowable_bending_stress: PAPER_ALLOWABLE_BENDING,
            yield_stress: 0.0,
            tip_force: 0.0,
            shear_area: 0.0,
            allowable_shear_stress: 0.0,
            sections: Vec::new(),
            kind: ImpactorKind::Beam,
            radius: 0.0,
            poisson_ratio: STEEL_POISSON_RATIO,
        }
    }
}

/// What the bridge strikes (issue 28): the arrestor beam, or a rigid point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SupportKind {
    /// The paper's arrestor: a cantilever with a tip mass (the default).
    #[default]
    Beam,
    /// A fixed point under the contact: the contact element alone is the support's spring
    /// (its stiffness `contact.stiffness`, or the bar's E A / l). The arrestor's fields do not
    /// apply; its outputs (deflection, clamp stresses) are 0.
    Rigid,
}

impl SupportKind {
    /// The FMU's Integer parameter: 0 beam, 1 rigid.
    pub fn index(self) -> u32 {
        match self {
            SupportKind::Beam => 0,
            SupportKind::Rigid => 1,
        }
    }

    /// From the FMU's Integer parameter; `None` outside 0..=1.
    pub fn from_index(value: f64) -> Option<SupportKind> {
        match value {
            0.0 => Some(SupportKind::Beam),
            1.0 => Some(SupportKind::Rigid),
            _ => None,
        }
    }

    fn is_beam(&self) -> bool {
        *self == SupportKind::Beam
    }
}

/// The arrestor (lower beam): clamped at x = 0, free at x = `length` with a lumped tip mass.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LowerBeam {
    /// `"beam"` (the default: the arrestor) or `"rigid"` (a fixed point under the contact; the
    /// other fields of `[lower]` do not apply).
    #[serde(skip_serializing_if = "SupportKind::is_beam")]
    pub kind: SupportKind,
    /// Length l_l, m. Paper: 12 m.
    pub length: f64,
    /// Mass of the uniform beam m_l, kg (Eq. 13): the two longitudinal I-beams, 2 x 0.05374 m^2 x 12 m x 7850 kg/m^3.
    pub mass: f64,
    /// Lumped mass at the free end, kg: the transverse beam, so that the total is the paper's 11.7 t.
    pub tip_mass: f64,
    /// Young's modulus E_a, Pa. Paper: 2.1e5 N/mm^2.
    pub elastic_modulus: f64,
    /// Second moment of area I_a, m^4. Paper: 0.002075 m^4.
    pub second_moment: f64,
    /// Section modulus W_a, m^3. Paper: 0.01384 m^3.
    pub section_modulus: f64,
    /// Shear area A_s,a, m^2, for the shear stress Q/A_s. Paper: 0.012 m^2.
    pub shear_area: f64,
    /// Equal elements from the clamp to the free end, or `"auto"` (the default; 0 in the FMU).
    /// Paper (Fig. 5): 7.
    #[serde(with = "auto_count")]
    pub elements: u32,
    /// Allowable bending stress of the arrestor, Pa. Paper: 533 MPa.
    pub allowable_bending_stress: f64,
    /// Allowable shear stress of the arrestor, Pa. Paper: 355 MPa.
    pub allowable_shear_stress: f64,
    /// Yield stress of the arrestor, Pa, or 0 (the default): none given. The clamp's equivalent
    /// stress max(sigma, sqrt(3) tau) above it puts the run out of the elastic model's range.
    pub yield_stress: f64,
    /// Constant vertical force at the free end, N, up positive (the FMU overrides it as an input).
    pub tip_force: f64,
    /// The arrestor's sections from the clamp (`[[lower.sections]]`, issue 30); none: the uniform
    /// beam of the fields above. With sections, `length` and `mass` follow from them and
    /// `second_moment`, `section_modulus` and `shear_area` are the first section's (at the clamp).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub sections: Vec<SectionSpec>,
    /// How the beam is held at its two ends (issue 45): `"clamped-free"` (the default, the
    /// paper's cantilever), `"pinned-pinned"`, `"clamped-clamped"` or `"clamped-pinned"` (the
    /// first named end at x = 0).
    #[serde(skip_serializing_if = "Supports::is_clamped_free")]
    pub supports: Supports,
    /// Where the bridge strikes it, m from its first support (issue 45); 0 (the default): not
    /// given, the free end of a clamped-free beam, the midspan of a beam on two supports.
    #[serde(skip_serializing_if = "is_zero")]
    pub contact_position: f64,
    /// Poisson's ratio of the struck beam, for `contact.law = "hertz"` (issue 45). Default 0.3 (steel).
    #[serde(skip_serializing_if = "is_default_poisson")]
    pub poisson_ratio: f64,
}

impl Default for LowerBeam {
    fn default() -> Self {
        LowerBeam {
            kind: SupportKind::Beam,
            length: 12.0,
            mass: 10_124.0,
            tip_mass: 1_576.0,
            elastic_modulus: 2.1e11,
            second_moment: 0.002075,
            section_modulus: 0.01384,
            shear_area: 0.012,
            elements: 0,
            allowable_bending_stress: PAPER_ALLOWABLE_BENDING,
            allowable_shear_stress: PAPER_ALLOWABLE_SHEAR,
            yield_stress: 0.0,
            tip_force: 0.0,
            sections: Vec::new(),
            supports: Supports::ClampedFree,
            contact_position: 0.0,
            poisson_ratio: STEEL_POISSON_RATIO,
        }
    }
}

/// The contact bar (Eq. 3) between the arrestor's end and the bridge's contact node.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ContactBar {
    /// Cross-section area A_c, m^2. Paper: 0.04 m^2.
    pub area: f64,
    /// Length l_c, m. Paper: 0.3 m.
    pub length: f64,
    /// Young's modulus, Pa. Paper: 2.1e11 Pa (stiffness E A_c / l_c = 2.8e10 N/m).
    pub elastic_modulus: f64,
    /// The contact's rate k, N/m, given directly (issue 28) instead of the bar's E A_c / l_c
    /// (give one of the two). Absent: the bar's.
    #[serde(default, skip_serializing_if = "Option::is_none", rename = "stiffness")]
    pub given_stiffness: Option<f64>,
    /// A gap the bodies close before the contact acts, m (default 0): the beams start touching
    /// geometrically and the contact force begins once they have closed another `clearance`.
    #[serde(skip_serializing_if = "is_zero")]
    pub clearance: f64,
    /// `"linear"` (the default: F = k delta, the paper's bar) or `"power"` (F = k delta^n with
    /// n = `exponent`; `stiffness` then in N/m^n and required).
    #[serde(skip_serializing_if = "LawKind::is_linear")]
    pub law: LawKind,
    /// The power law's exponent n, 1 to 3; 0 (the default): not given, the power law's
    /// [`HERTZ_EXPONENT`]. With the linear law only 0 or its own 1 (F = k delta^1): any other
    /// would be ignored, so it is refused.
    #[serde(skip_serializing_if = "is_zero")]
    pub exponent: f64,
    /// Hunt and Crossley's damping c, s/m (default 0): F = k delta^n (1 + c delta'), for either law.
    #[serde(skip_serializing_if = "is_zero")]
    pub damping: f64,
}

/// The power law's exponent when none is given: Hertz's 1.5 (Goldsmith, Impact, Eq. 4.7).
pub const HERTZ_EXPONENT: f64 = 1.5;

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl Default for ContactBar {
    fn default() -> Self {
        ContactBar {
            area: 0.04,
            length: 0.3,
            elastic_modulus: 2.1e11,
            given_stiffness: None,
            clearance: 0.0,
            law: LawKind::Linear,
            exponent: 0.0,
            damping: 0.0,
        }
    }
}

impl ContactBar {
    /// Axial stiffness k, N/m: as given, or the bar's E A_c / l_c (Eq. 3).
    pub fn stiffness(&self) -> f64 {
        self.given_stiffness.unwrap_or(self.elastic_modulus * self.area / self.length)
    }

    /// The law the stepper solves as a scalar equation, or `None` for the paper's linear bar
    /// without damping (solved in closed form, Sherman-Morrison).
    pub fn nonlinear_law(&self) -> Option<ContactLaw> {
        let exponent = match self.law {
            LawKind::Power | LawKind::Hertz if self.exponent == 0.0 => HERTZ_EXPONENT,
            LawKind::Hertz => HERTZ_EXPONENT,
            LawKind::Power => self.exponent,
            LawKind::Linear => 1.0,
        };
        // Hertz's constant needs both bodies: `Scenario::contact_law` puts it in (here 0).
        let hertz = self.law == LawKind::Hertz;
        (self.law == LawKind::Power || hertz || self.damping > 0.0).then(|| ContactLaw {
            stiffness: if hertz { 0.0 } else { self.stiffness() },
            exponent,
            damping: self.damping,
        })
    }
}

impl Scenario {
    /// The contact law the stepper solves each step (see [`ContactBar::nonlinear_law`]), with
    /// Hertz's constant from both bodies for `contact.law = "hertz"` (issue 45), or `None` for
    /// the paper's linear bar without damping.
    pub fn contact_law(&self) -> Option<ContactLaw> {
        let mut law = self.contact.nonlinear_law()?;
        if self.contact.law == LawKind::Hertz {
            law.stiffness = self.hertz_constant();
        }
        Some(law)
    }

    /// The contact's rate or constant, N/m (N/m^n): Hertz's for `contact.law = "hertz"`, else
    /// [`ContactBar::stiffness`].
    pub fn contact_stiffness(&self) -> f64 {
        if self.contact.law == LawKind::Hertz {
            self.hertz_constant()
        } else {
            self.contact.stiffness()
        }
    }

    /// Hertz's constant k = 4/3 E* sqrt(R), N/m^1.5, of the sphere (`upper.radius`,
    /// `upper.elastic_modulus`, `upper.poisson_ratio`) on the struck beam's face
    /// (`lower.elastic_modulus`, `lower.poisson_ratio`; a rigid support's term left out).
    pub fn hertz_constant(&self) -> f64 {
        let striker = (self.upper.elastic_modulus, self.upper.poisson_ratio);
        let struck =
            (self.lower.kind != SupportKind::Rigid).then_some((self.lower.elastic_modulus, self.lower.poisson_ratio));
        super::contact_law::hertz_stiffness(self.upper.radius, striker, struck)
    }
}

/// The supports' prescribed motion (issue 17): a time series of the hinge's heave and the
/// clamp's heave and rotation (see [`MotionTable`] for the file), read by the CLI. Without a file
/// the supports are fixed (the paper).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MotionSettings {
    /// CSV file of the supports' motion, relative to the scenario file (or as given to `--motion`);
    /// "" (the default): fixed supports.
    pub file: String,
    /// The file's time at the run's t = 0 (the impact), s. Default 0. Over one wave period it
    /// sweeps the wave's phase at impact.
    pub time_shift: f64,
    /// The file's rows, loaded by the CLI (not part of the TOML).
    #[serde(skip)]
    pub table: Option<Arc<MotionTable>>,
}

impl MotionSettings {
    /// True for fixed supports with the default shift (nothing to write in a scenario file).
    pub fn is_unset(&self) -> bool {
        self.file.is_empty() && self.time_shift == 0.0 && self.table.is_none()
    }

    /// The supports' motion at the run's t = 0 (rest without a table).
    pub fn at_start(&self) -> SupportMotion {
        self.table.as_ref().map(|t| t.motion_at(self.time_shift)).unwrap_or_default()
    }

    /// The table's rows inside a run of `duration_ns` as (run time in ns, motion), in order.
    pub fn changes(&self, duration_ns: u64) -> Vec<(u64, SupportMotion)> {
        self.table.as_ref().map(|t| t.changes(self.time_shift, duration_ns)).unwrap_or_default()
    }
}

/// A whole run: the two beams, the contact bar, the drop, damping and time stepping.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Scenario {
    /// Drop height h of the bridge's centre of gravity before impact, m (Eq. 20).
    /// 0.567 m reproduces the whole energy column of Table 1.
    pub drop_height: f64,
    /// The bridge's angular velocity about its hinge at first contact, rad/s, positive with the
    /// free end moving down (toward the support): the impact stated by its speed instead of a
    /// drop height (give one; with it `drop_height` is 0). The bridge then starts in the state of
    /// Eqs. 14-26 for that speed: rotating rigidly, in quasi-static balance under gravity (with
    /// gravity 0: undeformed). Absent (the default): from `drop_height` by Eqs. 20-22,
    /// omega_0 = sqrt(3 g alpha_0 / l_u) with alpha_0 = atan(2 h / l_u).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impact_angular_velocity: Option<f64>,
    /// Distance d from the hinge to the contact point on the bridge, m. 13 m reproduces Table 2's coupled column.
    pub contact_position: f64,
    /// Modal damping ratio gamma on every mode of each beam's own modes (Eq. 34). Paper: 0.03.
    pub damping_ratio: f64,
    /// Rayleigh mass coefficient alpha, 1/s, added to the modal damping (C += alpha M per beam). Default 0.
    pub rayleigh_alpha: f64,
    /// Rayleigh stiffness coefficient beta, s, added to the modal damping (C += beta K per beam). Default 0.
    pub rayleigh_beta: f64,
    /// Time step out of contact, s, or `"auto"` (the default): the largest whole-nanosecond step
    /// with omega_max dt <= 1, at most the paper's 5e-5 s. The paper's 5e-5 s is above that
    /// energy-safe limit on its own mesh (omega_max dt = 2.19) and pumps energy into undamped runs.
    pub step_free: TimeStep,
    /// Time step in contact, s, or `"auto"` (the default): as `step_free`, at most the paper's 2.5e-5 s.
    pub step_contact: TimeStep,
    /// Simulated time from the impact, s. Paper: 3 s.
    pub duration: f64,
    /// Acceleration of gravity g, m/s^2.
    pub gravity: f64,
    /// Largest energy balance residual a trusted run may have, as a fraction of the energy that
    /// flows in the run (the larger of m_u g h + |external work| and the largest strain energy).
    /// Default 0.01.
    pub energy_tolerance: f64,
    /// The solution method: `"converged"` (the default) or `"paper"` (see [`Method`]).
    pub method: Method,
    /// Modal cut-off of the converged method, rad/s, or `"auto"` (the default; 0 in the FMU): the
    /// ladder's. Each beam's modes above it are replaced by their static response; a cut-off
    /// above every frequency keeps the full basis. Ignored by `method = "paper"`.
    #[serde(with = "auto_real")]
    pub modal_cutoff: f64,
    /// Largest relative change of a peak against the next coarser discretisation, and largest
    /// spread between the run and its twin (drop height changed by 1e-9), for the peak to be
    /// vouched for. Default 0.01.
    pub discretisation_tolerance: f64,
    /// Which element(s) give the bridge's bending moment at the contact node: `"mean"` (default),
    /// `"left"` (hinge side) or `"right"`.
    pub stress_recovery: StressRecovery,
    /// The bridge.
    pub upper: UpperBeam,
    /// The arrestor.
    pub lower: LowerBeam,
    /// The contact bar.
    pub contact: ContactBar,
    /// The supports' prescribed motion (none by default: fixed supports).
    #[serde(skip_serializing_if = "MotionSettings::is_unset")]
    pub motion: MotionSettings,
    /// The supports on a vessel in a sea state (issue 42: `[sea]`), instead of a motion file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sea: Option<SeaSettings>,
    /// The load cases checked beside the plain design check (issue 44: `[[load_cases]]`; none by
    /// default): each case's factors and the fields it changes ([`LoadCase`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub load_cases: Vec<LoadCase>,
    /// The S-N curve and factors of a run's fatigue (issue 44: `[fatigue]`); absent: the
    /// defaults ([`super::fatigue_settings::FatigueSettings`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fatigue: Option<super::fatigue_settings::FatigueSettings>,
    /// The rigid impactor's downward speed at first contact, m/s (issue 45, `upper.kind =
    /// "mass"`), instead of a drop height (give one: with it `drop_height` is 0); 0 (the
    /// default): not given, v = sqrt(2 g h) from `drop_height`.
    #[serde(skip_serializing_if = "is_zero")]
    pub impact_speed: f64,
}

impl Default for Scenario {
    fn default() -> Self {
        Scenario {
            drop_height: 0.567,
            impact_angular_velocity: None,
            contact_position: 13.0,
            damping_ratio: 0.03,
            rayleigh_alpha: 0.0,
            rayleigh_beta: 0.0,
            step_free: TimeStep::Auto,
            step_contact: TimeStep::Auto,
            duration: 3.0,
            gravity: 9.81,
            energy_tolerance: 0.01,
            method: Method::Converged,
            modal_cutoff: 0.0,
            discretisation_tolerance: 0.01,
            stress_recovery: StressRecovery::Mean,
            upper: UpperBeam::default(),
            lower: LowerBeam::default(),
            contact: ContactBar::default(),
            motion: MotionSettings::default(),
            sea: None,
            load_cases: Vec::new(),
            fatigue: None,
            impact_speed: 0.0,
        }
    }
}

/// The paper's allowable bending stress of both beams, Pa (533 MPa).
pub const PAPER_ALLOWABLE_BENDING: f64 = 533e6;

/// The paper's allowable shear stress of the arrestor, Pa (355 MPa).
pub const PAPER_ALLOWABLE_SHEAR: f64 = 355e6;

/// The paper's time step out of contact, s: the upper bound of the automatic step.
pub const PAPER_STEP_FREE: f64 = 5e-5;

/// The paper's time step in contact, s: the upper bound of the automatic step.
pub const PAPER_STEP_CONTACT: f64 = 2.5e-5;

/// Largest element count accepted per beam segment: 32x the paper's 7 (224) fits, and the
/// dense eigen solutions of the beams (O(n^3)) stay within seconds.
pub const MAX_ELEMENTS: u32 = 256;

/// Largest number of internal steps a run may need (duration over the smaller time step),
/// unless the CLI's `--max-steps` raises it: 1e8 steps take minutes on the paper mesh and
/// hours on fine ones; a scenario asking for more is refused before it starts.
pub const MAX_STEPS: u64 = 100_000_000;

/// Smallest time step: the stepper counts time in integer nanoseconds.
pub const MIN_STEP: f64 = 1e-9;

/// The smallest allowable stress, Pa (any field of an allowable): 1 mPa.
pub const SMALLEST_STRESS: f64 = 1e-3;

/// The smallest yield stress given, Pa: 1 kPa, below any solid's (the softest elastomers yield
/// above 1 MPa; a smaller one makes every utilisation overflow).
pub const SMALLEST_YIELD_STRESS: f64 = 1e3;

/// The softest contact given, N/m (N/m^n).
pub const SMALLEST_CONTACT_STIFFNESS: f64 = 1e-3;

pub(super) fn positive(name: &'static str, unit: &str, value: f64) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(name, format!("> 0 {unit}").trim_end().to_string(), bound(value)))
    }
}

/// A number as people write it: 0.999, 1000, 1e-12, 1e9 (and -3, NaN, inf as they are).
pub(super) fn bound(x: f64) -> String {
    if x.is_finite() && x != 0.0 && !(1e-3..1e4).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// Whether a contact exponent is in its range (else its range's error names it).
fn within_exponent(exponent: f64) -> bool {
    (EXPONENT_RANGE.0..=EXPONENT_RANGE.1).contains(&exponent)
}

/// `min <= value <= max`, finite.
pub(super) fn within(name: &'static str, unit: &str, value: f64, min: f64, max: f64) -> Result<()> {
    if value.is_finite() && (min..=max).contains(&value) {
        Ok(())
    } else if value.is_finite() && value < min && min == 0.0 {
        Err(Error::invalid(name, format!(">= 0 {unit}").trim_end().to_string(), bound(value)))
    } else {
        Err(Error::invalid(
            name,
            format!("between {} and {} {unit}", bound(min), bound(max)).trim_end().to_string(),
            bound(value),
        ))
    }
}

/// A physical size: > 0 (the message every user knows), then within its sane range.
pub(super) fn size(name: &'static str, unit: &str, value: f64, min: f64, max: f64) -> Result<()> {
    positive(name, unit, value)?;
    within(name, unit, value, min, max)
}

fn time_step(name: &'static str, value: TimeStep) -> Result<()> {
    let TimeStep::Fixed(step) = value else { return Ok(()) };
    if !(step.is_finite() && (MIN_STEP..=1.0).contains(&step)) {
        return Err(Error::invalid(
            name,
            format!("between {MIN_STEP:e} s (time is counted in ns) and 1 s, or \"auto\" (0 in the FMU)"),
            step,
        ));
    }
    Ok(())
}

/// Largest impact angular velocity accepted, rad/s: the paper's bridge turns at 0.199 rad/s
/// (its contact point at 13 m closing at 2.59 m/s); 50 rad/s is 1450 m/s at a 29 m bridge's
/// end, far beyond elastic impact.
pub const MAX_IMPACT_ANGULAR_VELOCITY: f64 = 50.0;

/// Largest tip force accepted, N: a thousand times the paper's 475 kN impact force is far
/// beyond any load the beams could carry, and keeps every state finite.
pub const MAX_TIP_FORCE: f64 = 1e9;

fn tip_force(name: &'static str, value: f64) -> Result<()> {
    if value.is_finite() && value.abs() <= MAX_TIP_FORCE {
        Ok(())
    } else {
        Err(Error::invalid(name, format!("finite with |F| <= {MAX_TIP_FORCE:e} N"), value))
    }
}

fn elements(name: &'static str, value: u32) -> Result<()> {
    if (0..=MAX_ELEMENTS).contains(&value) {
        Ok(())
    } else {
        Err(Error::invalid(name, format!("between 1 and {MAX_ELEMENTS}, or \"auto\" (0 in the FMU)"), value))
    }
}

/// A stress limit: > 0, at most 1e12 Pa.
fn stress(name: &'static str, value: f64) -> Result<()> {
    size(name, "Pa", value, SMALLEST_STRESS, 1e12)
}

/// The stiffest linear contact, N/m: 1.43 times the paper's steel bar (E A / l = 2.8e10 N/m), so
/// a bar of the paper's section and steel from 0.21 m long. Stiffer, a run's cost is erratic: the
/// bar rings at each separation, and the contact can chatter (each change of contact located by
/// retaking its step with new exact coefficients for every kept mode), in the printed rung or in
/// one of its checks. Measured (issue 40 item 3; the whole answer, CPU time, against the default's
/// at the same point) on a grid of the default scenario, 3 s: drop heights 0.1, 0.5, 1 and 2 m,
/// contact positions 4, 8, 13, 20 and 29 m, damping ratios 0, 0.02 and 0.05: at 4e10 N/m all 60
/// runs within 1.4x the default's; at 5e10 one 3.7x (drop 0.1 m at 8 m, damping 0.05); at that
/// point 8e10 took 30x (3 414 contact windows), 1e11 18x, 2e11 140x (42 261 windows, 12.4 s);
/// 1e12 on the default at drop 0.5 m 3.3 s against 0.09 s. (Until issue 40 item 3 the bound
/// was 1e12, and 1e13 did not pass t = 0.75 s in 400 s.)
///
/// Every law's rate is held to it ([`super::contact_range`]): a power law of exponent 1 is the
/// same bar in its own unit, and chattered above it as the bar did (drop 0.5 m: 1e12 N/m^1 2 166
/// contact windows, 3.6 s and not trusted against 0.13 s at 4e10; 1e13 2 482 windows). Measured
/// at the top rate (the whole answer's CPU time against the default bar's at the same point; drop
/// heights 0.1, 0.5, 1 and 2 m, contact positions 4, 13 and 29 m, damping ratios 0 and 0.03,
/// exponents 1, 1.3 and 1.5, k set so that the rate is 4e10 N/m): every run within 1.8x (exponent
/// 1 at 29 m with damping 0.03: 0.21 s against 0.11 s; exponent 1.3 at most 1.6x, 1.5 at most
/// 1.2x; at 4 m undamped the default bar itself takes 18-25 s, 884-1 836 windows, and the power
/// laws 0.2-1.6 times that).
pub const MAX_CONTACT_STIFFNESS: f64 = 4e10;

/// The stiffest power-law contact in its own unit, N/m^n: it keeps the numbers finite (a Hertz
/// law carrying the paper's 475 kN at the bar's 17 um compression is 6.8e12 N/m^1.5); the law's
/// rate is held to [`MAX_CONTACT_STIFFNESS`] besides ([`super::contact_range`]).
pub const MAX_POWER_LAW_STIFFNESS: f64 = 1e13;

/// A yield stress: 0 (none given), or from 1 kPa (below any solid's: the softest elastomers yield
/// above 1 MPa; a smaller one makes every utilisation overflow) to 1e12 Pa.
fn optional_stress(name: &'static str, value: f64) -> Result<()> {
    if value == 0.0 {
        Ok(())
    } else {
        within(name, "Pa (0: none)", value, SMALLEST_YIELD_STRESS, 1e12)
    }
}

impl Scenario {
    /// Parses a scenario from TOML text; missing fields take their defaults. Every invalid field
    /// is reported at once (a syntax or type error stops first).
    pub fn from_toml(text: &str, path: &str) -> Result<Self> {
        let mut scenario: Scenario = toml::from_str(text)
            .map_err(|e| Error::Scenario { path: path.to_string(), message: one_line(&e.to_string()) })?;
        // A speed stated without a drop height: the drop height is not the default's but 0.
        if (scenario.impact_angular_velocity.is_some() || scenario.impact_speed != 0.0)
            && !has_key(text, &["drop_height"])
        {
            scenario.drop_height = 0.0;
        }
        if scenario.upper.kind == ImpactorKind::Mass {
            Scenario::refuse_mass_beam_fields(text)?;
        }
        // A beam of sections: what its uniform fields say follows from them unless given (then
        // they must agree, which validation checks).
        for beam in ["upper", "lower"] {
            let given = |key: &str| has_key(text, &[beam, key]);
            let (length, mass, first) = match beam {
                "upper" if !scenario.upper.sections.is_empty() => {
                    let (l, m) = section::totals(&scenario.upper.sections);
                    (l, m, scenario.upper.sections[0].clone())
                }
                "lower" if !scenario.lower.sections.is_empty() => {
                    let (l, m) = section::totals(&scenario.lower.sections);
                    (l, m, scenario.lower.sections[0].clone())
                }
                _ => continue,
            };
            let fields: [(&str, f64); 5] = [
                ("length", length),
                ("mass", mass),
                ("second_moment", first.second_moment),
                ("section_modulus", first.section_modulus),
                ("shear_area", first.shear_area),
            ];
            for (key, value) in fields {
                if given(key) {
                    continue;
                }
                let target = match (beam, key) {
                    ("upper", "length") => &mut scenario.upper.length,
                    ("upper", "mass") => &mut scenario.upper.mass,
                    ("upper", "second_moment") => &mut scenario.upper.second_moment,
                    ("upper", "section_modulus") => &mut scenario.upper.section_modulus,
                    ("upper", _) => &mut scenario.upper.shear_area,
                    (_, "length") => &mut scenario.lower.length,
                    (_, "mass") => &mut scenario.lower.mass,
                    (_, "second_moment") => &mut scenario.lower.second_moment,
                    (_, "section_modulus") => &mut scenario.lower.section_modulus,
                    _ => &mut scenario.lower.shear_area,
                };
                *target = value;
            }
        }
        // What one field states, another may not state too.
        let bar = ["area", "length", "elastic_modulus"].map(|k| format!("contact.{k}"));
        let given_bar: Vec<&str> = bar.iter().map(String::as_str).filter(|k| has_key(text, &split(k))).collect();
        if scenario.contact.given_stiffness.is_some() && !given_bar.is_empty() {
            return Err(Error::Other(format!(
                "contact.stiffness and {} are both given: the contact's rate is one or the bar's E A / l, not both",
                given_bar.join(", ")
            )));
        }
        if scenario.lower.kind == SupportKind::Rigid {
            if let Ok(table) = text.parse::<toml::Table>() {
                let beam_fields: Vec<String> = table
                    .get("lower")
                    .and_then(|l| l.as_table())
                    .map(|l| l.keys().filter(|k| *k != "kind").map(|k| format!("lower.{k}")).collect())
                    .unwrap_or_default();
                if !beam_fields.is_empty() {
                    return Err(Error::Other(format!(
                        "lower.kind = \"rigid\" has no arrestor beam, but {} {} given: leave them out",
                        beam_fields.join(", "),
                        if beam_fields.len() == 1 { "is" } else { "are" }
                    )));
                }
            }
        }
        let mut errors = scenario.validation_errors();
        match errors.len() {
            0 => Ok(scenario),
            1 => Err(errors.remove(0)),
            _ => Err(Error::Invalid(errors)),
        }
    }

    /// The scenario as TOML, with every field.
    pub fn to_toml(&self) -> String {
        let text = toml::to_string(self).unwrap_or_else(|e| format!("# cannot serialize scenario: {e}\n"));
        let rigid = self.lower.kind == SupportKind::Rigid;
        let mass = self.upper.kind == ImpactorKind::Mass;
        if !rigid && !mass && self.contact.given_stiffness.is_none() {
            return text;
        }
        // Fields that do not apply are left out, so that the text reads back (a rigid support
        // has no beam fields; a given contact rate no bar).
        let Ok(mut table) = text.parse::<toml::Table>() else { return text };
        if let (true, Some(toml::Value::Table(lower))) = (rigid, table.get_mut("lower")) {
            lower.retain(|k, _| k == "kind");
        }
        if mass {
            Scenario::retain_mass_fields(&mut table);
        }
        if let (true, Some(toml::Value::Table(contact))) =
            (self.contact.given_stiffness.is_some(), table.get_mut("contact"))
        {
            contact.retain(|k, _| k != "area" && k != "length" && k != "elastic_modulus");
        }
        toml::to_string(&table).unwrap_or(text)
    }

    /// The paper's scenario and method: the defaults with the paper's mesh (7 + 7/7 elements, the
    /// full modal basis) and its own step pair (5e-5 s out of contact, 2.5e-5 s in contact), what
    /// a bare `beam-impact` runs.
    pub fn paper() -> Scenario {
        let mut s = Scenario {
            method: Method::Paper,
            step_free: TimeStep::Fixed(PAPER_STEP_FREE),
            step_contact: TimeStep::Fixed(PAPER_STEP_CONTACT),
            ..Scenario::default()
        };
        s.lower.elements = PAPER_ELEMENTS;
        s.upper.elements_to_contact = PAPER_ELEMENTS;
        s.upper.elements_beyond_contact = PAPER_ELEMENTS;
        s
    }

    /// The paper's method and mesh (7 + 7/7 elements, full modal basis) with the default automatic
    /// steps: the paper mesh as tests of it and `verify`'s base run use it.
    pub fn paper_mesh() -> Scenario {
        Scenario { step_free: TimeStep::Auto, step_contact: TimeStep::Auto, ..Scenario::paper() }
    }

    /// True when the contact sits at the bridge's free end (`contact_position = upper.length`):
    /// the bridge has no elements beyond it.
    pub fn contact_at_free_end(&self) -> bool {
        self.contact_position == self.upper.length
    }

    /// True when an element count or the modal cut-off is still `"auto"`.
    pub fn has_auto_discretisation(&self) -> bool {
        self.lower.elements == 0
            || self.upper.elements_to_contact == 0
            || (self.upper.elements_beyond_contact == 0 && !self.contact_at_free_end())
            || (self.method == Method::Converged && self.modal_cutoff == 0.0)
    }

    /// True when this is the paper's scenario (the comparison with the paper applies).
    pub fn is_paper(&self) -> bool {
        *self == Scenario::paper()
    }

    /// Checks every field that can be checked without assembling the model. The stability of
    /// the time steps needs the natural frequencies and is checked by [`crate::solver::ModalSystem::new`].
    pub fn validate(&self) -> Result<()> {
        if let Some(e) = self.validation_errors().into_iter().next() {
            return Err(e);
        }
        // A scenario file's `[motion] file` is read by the CLI after the TOML is parsed.
        if self.motion.table.is_none() && !self.motion.file.is_empty() {
            return Err(Error::invalid(
                "motion.file",
                "a CSV file the CLI reads (`run --motion FILE.csv` or `[motion] file` in a scenario file)",
                format!("'{}', not loaded", self.motion.file),
            ));
        }
        // A sea's RAO file is read by the CLI too (a log's replay carries the record instead).
        if let Some(sea) = &self.sea {
            match &sea.rao_table {
                Some(raos) => sea.check_against(raos)?,
                None if sea.recorded.is_some() => {}
                None => {
                    sea.motion_table(self.duration)?;
                }
            }
        }
        Ok(())
    }

    /// Every field that breaks its rule, each as its own error naming the field, its rule (with
    /// the unit) and the value. The bounds keep every accepted scenario finite and answerable:
    /// beyond them the model's numbers overflow, underflow or stop meaning anything physical.
    pub fn validation_errors(&self) -> Vec<Error> {
        let mut errors = self.rigid_impactor_errors();
        let u = &self.upper;
        let mut check = |result: Result<()>| {
            if let Err(e) = result {
                errors.push(e);
            }
        };
        let l = &self.lower;
        let c = &self.contact;
        // A zero drop height is legal: the bridge touches the arrestor at rest. The centre of
        // gravity cannot drop more than half the bridge's length (45 degrees with Eq. 20's tan).
        let bridge_ok = size("upper.length", "m", u.length, 0.01, 1e3).is_ok();
        if u.kind == ImpactorKind::Beam {
            check(within("drop_height", "m", self.drop_height, 0.0, if bridge_ok { 0.5 * u.length } else { 500.0 }));
        }
        let mut check = |result: Result<()>| {
            if let Err(e) = result {
                errors.push(e);
            }
        };
        if let Some(omega) = self.impact_angular_velocity {
            check(within("impact_angular_velocity", "rad/s", omega, 0.0, MAX_IMPACT_ANGULAR_VELOCITY));
            if self.drop_height != 0.0 {
                check(Err(Error::Other(format!(
                    "drop_height = {} m and impact_angular_velocity = {} rad/s are both given: give one (the impact's \
                     speed, or the drop height it comes from; with impact_angular_velocity, drop_height is 0)",
                    bound(self.drop_height),
                    bound(omega)
                ))));
            }
        } else if self.gravity == 0.0 && u.kind == ImpactorKind::Beam {
            check(Err(Error::Other(
                "gravity = 0 needs impact_angular_velocity: nothing makes the bridge fall, so state the impact by its \
                 speed (and drop_height = 0)"
                    .into(),
            )));
        }
        check(positive("contact_position", "m", self.contact_position));
        if bridge_ok && self.contact_position.is_finite() && self.contact_position > u.length {
            check(Err(Error::invalid(
                "contact_position",
                format!("on the upper beam, 0 < d <= upper.length = {} m", u.length),
                self.contact_position,
            )));
        }
        if self.contact_at_free_end() && u.elements_beyond_contact != 0 && u.kind == ImpactorKind::Beam {
            check(Err(Error::invalid(
                "upper.elements_beyond_contact",
                format!(
                    "\"auto\" (0: none) with the contact at the bridge's free end (contact_position = upper.length = {} m)",
                    u.length
                ),
                u.elements_beyond_contact,
            )));
        }
        check(within("damping_ratio", "", self.damping_ratio, 0.0, 0.999));
        check(within("rayleigh_alpha", "1/s", self.rayleigh_alpha, 0.0, 1e4));
        check(within("rayleigh_beta", "s", self.rayleigh_beta, 0.0, 1.0));
        check(time_step("step_free", self.step_free));
        check(time_step("step_contact", self.step_contact));
        check(positive("duration", "s", self.duration).and_then(|()| within("duration", "s", self.duration, 0.0, 1e6)));
        check(within("gravity", "m/s^2", self.gravity, 0.0, 100.0));
        check(
            positive("energy_tolerance", "", self.energy_tolerance)
                .and_then(|()| within("energy_tolerance", "(a fraction)", self.energy_tolerance, 0.0, 1.0)),
        );

        check(size("upper.length", "m", u.length, 0.01, 1e3));
        check(size("upper.mass", "kg", u.mass, 1e-3, 1e9));
        check(size("upper.elastic_modulus", "Pa", u.elastic_modulus, 1e6, 1e13));
        check(size("upper.second_moment", "m^4", u.second_moment, 1e-12, 1e3));
        check(size("upper.section_modulus", "m^3", u.section_modulus, 1e-12, 1e3));
        check(elements("upper.elements_to_contact", u.elements_to_contact));
        check(elements("upper.elements_beyond_contact", u.elements_beyond_contact));
        check(stress("upper.allowable_bending_stress", u.allowable_bending_stress));
        check(optional_stress("upper.yield_stress", u.yield_stress));
        check(tip_force("upper.tip_force", u.tip_force));

        if u.shear_area != 0.0 {
            check(size("upper.shear_area", "m^2 (0: none)", u.shear_area, 1e-12, 1e3));
        }
        if u.allowable_shear_stress != 0.0 {
            check(stress("upper.allowable_shear_stress", u.allowable_shear_stress));
        }
        for (beam, elastic_modulus, sections, fields) in [
            (
                "upper",
                u.elastic_modulus,
                &u.sections,
                [u.length, u.mass, u.second_moment, u.section_modulus, u.shear_area],
            ),
            (
                "lower",
                l.elastic_modulus,
                &l.sections,
                [l.length, l.mass, l.second_moment, l.section_modulus, l.shear_area],
            ),
        ] {
            let errors_before = errors.len();
            errors.extend(section::validation_errors(beam, elastic_modulus, sections));
            if sections.is_empty() || errors.len() > errors_before {
                continue;
            }
            let (length, mass) = section::totals(sections);
            let first = &sections[0];
            let implied = [length, mass, first.second_moment, first.section_modulus, first.shear_area];
            let names = ["length", "mass", "second_moment", "section_modulus", "shear_area"];
            let units = ["m", "kg", "m^4", "m^3", "m^2"];
            for k in 0..5 {
                let name = format!("{beam}.{}", names[k]);
                if let Err(e) = section::agrees(name, units[k], fields[k], implied[k]) {
                    errors.push(e);
                }
            }
        }
        let mut check = |result: Result<()>| {
            if let Err(e) = result {
                errors.push(e);
            }
        };
        check(size("lower.length", "m", l.length, 0.01, 1e3));
        check(size("lower.mass", "kg", l.mass, 1e-3, 1e9));
        check(within("lower.tip_mass", "kg", l.tip_mass, 0.0, 1e9));
        check(size("lower.elastic_modulus", "Pa", l.elastic_modulus, 1e6, 1e13));
        check(size("lower.second_moment", "m^4", l.second_moment, 1e-12, 1e3));
        check(size("lower.section_modulus", "m^3", l.section_modulus, 1e-12, 1e3));
        check(size("lower.shear_area", "m^2", l.shear_area, 1e-12, 1e3));
        check(elements("lower.elements", l.elements));
        check(stress("lower.allowable_bending_stress", l.allowable_bending_stress));
        check(stress("lower.allowable_shear_stress", l.allowable_shear_stress));
        check(optional_stress("lower.yield_stress", l.yield_stress));
        check(within("modal_cutoff", "rad/s (0: auto)", self.modal_cutoff, 0.0, 1e12));
        check(positive("discretisation_tolerance", "", self.discretisation_tolerance).and_then(|()| {
            within("discretisation_tolerance", "(a fraction)", self.discretisation_tolerance, 0.0, 1.0)
        }));
        check(tip_force("lower.tip_force", l.tip_force));
        errors.extend(self.supports_errors());
        let mut check = |result: Result<()>| {
            if let Err(e) = result {
                errors.push(e);
            }
        };

        if let Some(k) = c.given_stiffness {
            let max = if c.law == LawKind::Linear { MAX_CONTACT_STIFFNESS } else { MAX_POWER_LAW_STIFFNESS };
            // The limit's reason only where it is the limit that refuses (not for -1 or NaN).
            let unit = match c.law {
                LawKind::Linear if k > max => "N/m (the linear law's limit)",
                LawKind::Linear => "N/m",
                _ => "N/m^n",
            };
            check(size("contact.stiffness", unit, k, SMALLEST_CONTACT_STIFFNESS, max));
        } else if c.law == LawKind::Linear
            && size("contact.area", "m^2", c.area, 1e-12, 1e3).is_ok()
            && size("contact.length", "m", c.length, 1e-6, 1e3).is_ok()
            && size("contact.elastic_modulus", "Pa", c.elastic_modulus, 1e6, 1e13).is_ok()
        {
            // The bar's fields each within their own ranges, their stiffness within the law's.
            let k = c.stiffness();
            if k.is_nan() || k > MAX_CONTACT_STIFFNESS {
                check(Err(Error::invalid(
                    "contact.elastic_modulus * contact.area / contact.length",
                    format!(
                        "<= {MAX_CONTACT_STIFFNESS:e} N/m (the bar's stiffness; {} Pa * {} m^2 / {} m)",
                        bound(c.elastic_modulus),
                        bound(c.area),
                        bound(c.length)
                    ),
                    bound(k),
                )));
            }
        }
        check(within("contact.clearance", "m", c.clearance, 0.0, 10.0));
        if c.exponent != 0.0 {
            check(within("contact.exponent", "(0: not given)", c.exponent, EXPONENT_RANGE.0, EXPONENT_RANGE.1));
        }
        // The exponent is the power law's: given with the linear law it would be ignored. Its
        // default 0 (the FMU's start value) is no setting, and 1 is the linear law's own
        // (F = k delta^1); any other is refused, Hertz's 1.5 too (issue 40).
        let linear_exponent = c.exponent == 0.0 || c.exponent == 1.0;
        if c.law == LawKind::Linear && !linear_exponent && within_exponent(c.exponent) {
            check(Err(Error::invalid(
                "contact.exponent",
                "0 (not given) or 1 with contact.law = \"linear\" (F = k delta: the exponent is the power law's; set \
                 contact.law = \"power\" for F = k delta^n)",
                bound(c.exponent),
            )));
        }
        check(within("contact.damping", "s/m", c.damping, 0.0, 1e3));
        if c.law == LawKind::Hertz {
            errors.extend(self.hertz_errors());
        }
        let mut check = |result: Result<()>| {
            if let Err(e) = result {
                errors.push(e);
            }
        };
        if c.law == LawKind::Power && c.given_stiffness.is_none() {
            check(Err(Error::invalid(
                "contact.stiffness",
                "given with contact.law = \"power\" (k in N/m^n: the bar's E A / l is a linear rate)",
                "absent",
            )));
        }
        check(size("contact.area", "m^2", c.area, 1e-12, 1e3));
        check(size("contact.length", "m", c.length, 1e-6, 1e3));
        check(size("contact.elastic_modulus", "Pa", c.elastic_modulus, 1e6, 1e13));

        let m = &self.motion;
        check(within("motion.time_shift", "s", m.time_shift, -1e9, 1e9));
        if m.time_shift != 0.0 && m.file.is_empty() && m.table.is_none() {
            check(Err(Error::invalid(
                "motion.time_shift",
                "0 s without a motion file (it shifts the file's time; give one with `[motion] file` or --motion)",
                bound(m.time_shift),
            )));
        }
        if let Some(sea) = &self.sea {
            if !m.is_unset() {
                check(Err(Error::Other(
                    "[sea] and [motion] are both given: the supports follow one (the sea state through the vessel's \
                     RAOs, or a motion file); leave one out"
                        .into(),
                )));
            }
            errors.extend(sea.validation_errors(self.duration));
        }
        if let Some(fatigue) = &self.fatigue {
            errors.extend(fatigue.validation_errors());
        }
        let mut check = |result: Result<()>| {
            if let Err(e) = result {
                errors.push(e);
            }
        };
        match &m.table {
            Some(table) if m.time_shift.is_finite() && self.duration.is_finite() => {
                check(table.check_covers(m.time_shift, m.time_shift + self.duration).map_err(|e| {
                    Error::invalid(
                        "motion.file",
                        format!(
                            "rows from time_shift to time_shift + duration ({} to {} s)",
                            m.time_shift,
                            m.time_shift + self.duration
                        ),
                        format!("'{}', which {e}", m.file),
                    )
                }))
            }
            _ => {}
        }
        errors.extend(load_case::validation_errors(&self.load_cases));
        // The contact's rate (issue 40 item 3) from several fields: judged when each is in range.
        if errors.is_empty() {
            errors.extend(self.contact_rate_error());
        }
        errors
    }

    /// The supports' motion table the run follows, with the table's time at the run's t = 0: the
    /// motion file's (`[motion]`, `--motion`), the sea's record (`[sea]`), or none (fixed supports).
    pub fn motion_source(&self) -> Result<Option<(Arc<MotionTable>, f64)>> {
        if let Some(sea) = &self.sea {
            return Ok(Some((sea.motion_table(self.duration)?, sea.time_shift)));
        }
        Ok(self.motion.table.as_ref().map(|t| (Arc::clone(t), self.motion.time_shift)))
    }

    /// The supports' motion at the run's t = 0 (rest without a motion source).
    pub fn motion_at_start(&self) -> Result<SupportMotion> {
        Ok(self.motion_source()?.map(|(t, shift)| t.motion_at(shift)).unwrap_or_default())
    }

    /// The motion source's rows inside a run of `duration_ns` as (run time in ns, motion), in order.
    pub fn motion_changes(&self, duration_ns: u64) -> Result<Vec<(u64, SupportMotion)>> {
        Ok(self.motion_source()?.map(|(t, shift)| t.changes(shift, duration_ns)).unwrap_or_default())
    }

    /// The energy the impact brings, J: m_u g h for a drop (the paper's energy balance), or the
    /// bridge's kinetic energy about its hinge, m_u l_u^2 omega_0^2 / 6, for a stated speed.
    pub fn impact_energy(&self) -> f64 {
        if self.upper.kind == ImpactorKind::Mass {
            let v = self.mass_impact_speed();
            return 0.5 * self.upper.mass * v * v;
        }
        if !self.upper.sections.is_empty() {
            // J omega^2 / 2 about the hinge, J = int mu x^2 dx.
            let (_, _, second) = section::mass_moments(&self.upper_segments());
            return match self.impact_angular_velocity {
                Some(omega) => 0.5 * second * omega * omega,
                None => self.upper.mass * self.gravity * self.drop_height,
            };
        }
        match self.impact_angular_velocity {
            Some(omega) => self.upper.mass * self.upper.length * self.upper.length * omega * omega / 6.0,
            None => self.upper.mass * self.gravity * self.drop_height,
        }
    }

    /// The bridge's segments from the hinge: its sections, or one of its uniform fields.
    pub fn upper_segments(&self) -> Vec<section::Segment> {
        let u = &self.upper;
        section::segments(
            &section::Uniform {
                length: u.length,
                mass: u.mass,
                elastic_modulus: u.elastic_modulus,
                second_moment: u.second_moment,
                section_modulus: u.section_modulus,
                shear_area: u.shear_area,
                allowable_bending_stress: u.allowable_bending_stress,
                allowable_shear_stress: u.allowable_shear_stress,
            },
            &u.sections,
        )
    }

    /// The arrestor's segments from the clamp: its sections, or one of its uniform fields.
    pub fn lower_segments(&self) -> Vec<section::Segment> {
        let l = &self.lower;
        section::segments(
            &section::Uniform {
                length: l.length,
                mass: l.mass,
                elastic_modulus: l.elastic_modulus,
                second_moment: l.second_moment,
                section_modulus: l.section_modulus,
                shear_area: l.shear_area,
                allowable_bending_stress: l.allowable_bending_stress,
                allowable_shear_stress: l.allowable_shear_stress,
            },
            &l.sections,
        )
    }

    /// The allowables the paper's three stresses are checked against, Pa: sigma_a and tau_a
    /// by the arrestor's first section (the clamp's), sigma_b by the bridge's section at the
    /// contact point ([`section::bending_check_at`]); a uniform beam's own allowables.
    pub fn paper_allowables(&self) -> [f64; 3] {
        let lower = self.lower_segments();
        let (_, contact) = section::bending_check_at(&self.upper_segments(), self.contact_position);
        let clamp = lower.first();
        [
            clamp.map_or(self.lower.allowable_bending_stress, |g| g.allowable_bending_stress),
            clamp.map_or(self.lower.allowable_shear_stress, |g| g.allowable_shear_stress),
            contact,
        ]
    }

    /// Where the bridge strikes the arrestor, m from its first support (issue 45): the given
    /// `lower.contact_position`, else the free end of a clamped-free beam and the midspan of a
    /// beam on two supports.
    pub fn lower_contact_position(&self) -> f64 {
        let l = &self.lower;
        match (l.contact_position, l.supports.has_far_support()) {
            (x, _) if x > 0.0 => x,
            (_, true) => 0.5 * l.length,
            (_, false) => l.length,
        }
    }

    /// The rules of `lower.supports` and `lower.contact_position` (issue 45): the contact on the
    /// beam (0 < x <= length; strictly inside between two supports, where the far end cannot
    /// deflect), and a beam on two supports with fixed supports (the supports' prescribed motion
    /// is the clamp's heave and rotation of a cantilever).
    fn supports_errors(&self) -> Vec<Error> {
        let l = &self.lower;
        let mut errors = Vec::new();
        let two = l.supports.has_far_support();
        let x = l.contact_position;
        if x != 0.0 {
            let length_ok = l.length.is_finite() && l.length > 0.0;
            let bad = !x.is_finite() || x < 0.0 || (length_ok && (x > l.length || (two && x >= l.length)));
            if bad {
                let rule = if two {
                    format!(
                        "0 (not given: midspan) or 0 < x < lower.length = {} m with lower.supports = \"{}\" (the far \
                         end is a support)",
                        bound(l.length),
                        l.supports.name()
                    )
                } else {
                    format!("0 (not given: the free end) or 0 < x <= lower.length = {} m", bound(l.length))
                };
                errors.push(Error::invalid("lower.contact_position", rule, bound(x)));
            }
        }
        // Both supports of a deck beam move with the deck (heave h + rotation theta x along it),
        // which the moving-base loads -M r a already describe; what is missing is the far
        // support's share of that rigid motion's inertia in its reaction (the stepper's far
        // support rows, `solver/far_support.rs`, see none of the supports' accelerations), so the
        // motion is refused rather than reported with a wrong far reaction.
        if two && (!self.motion.is_unset() || self.sea.is_some()) {
            errors.push(Error::Other(format!(
                "lower.supports = \"{}\" with {}: moving supports are a cantilever's clamp only; on two supports \
                 the far support's reaction would miss the deck motion's inertia, so a beam on two supports takes \
                 fixed supports (leave the motion out and fold a steady deck heave acceleration a into gravity, \
                 gravity = 9.81 + a, which loads the beam as the moving deck does; or use lower.supports = \
                 \"clamped-free\")",
                l.supports.name(),
                if self.sea.is_some() { "[sea]" } else { "[motion]" }
            )));
        }
        errors
    }

    /// Duration in integer nanoseconds.
    pub fn duration_ns(&self) -> u64 {
        (self.duration * 1e9).round() as u64
    }
}

/// Whether the TOML `text` (already parsed once) sets the key at `path` (`["contact", "area"]`).
fn has_key(text: &str, path: &[&str]) -> bool {
    let Ok(table) = text.parse::<toml::Table>() else { return false };
    let mut value = &toml::Value::Table(table);
    for key in path {
        match value.as_table().and_then(|t| t.get(*key)) {
            Some(v) => value = v,
            None => return false,
        }
    }
    true
}

/// A dotted name's parts.
fn split(name: &str) -> Vec<&str> {
    name.split('.').collect()
}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}
