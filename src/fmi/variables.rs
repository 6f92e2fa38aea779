//! The FMU's variable table: the one source of both modelDescription.xml files and of the
//! value references the getters and setters dispatch on. The parameter part comes from
//! [`PARAMETERS`]; the value reference of a variable is its index in [`table`].

use crate::model::parameters::{Kind, Parameter, PARAMETERS};
use crate::model::support_motion::{MOTION_LIMITS, MOTION_NAMES, MOTION_UNITS};
use crate::results::{Impact, StepResult, ENVELOPE_PEAK_NAMES};
use crate::solver::EnergyMethod;
use crate::Scenario;

/// How many natural frequencies of each column of Table 2 are exposed.
pub const MODES: usize = 5;

/// The FMI base type of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Type {
    /// `Real` (FMI 2) / `Float64` (FMI 3).
    Real,
    /// `Integer` (FMI 2) / `Int32` (FMI 3).
    Integer,
    /// `Boolean`.
    Boolean,
    /// `String`.
    String,
}

impl Type {
    /// The type's name in messages and the FMI 2 description.
    pub fn fmi2_name(self) -> &'static str {
        match self {
            Type::Real => "Real",
            Type::Integer => "Integer",
            Type::Boolean => "Boolean",
            Type::String => "String",
        }
    }

    /// The element name in the FMI 3 description.
    pub fn fmi3_name(self) -> &'static str {
        match self {
            Type::Real => "Float64",
            Type::Integer => "Int32",
            Type::Boolean => "Boolean",
            Type::String => "String",
        }
    }
}

/// FMI causality.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    /// The independent variable, time.
    Independent,
    /// Set before initialization.
    Parameter,
    /// Computed from the parameters at initialization.
    CalculatedParameter,
    /// Set by the importer before each step.
    Input,
    /// Computed by the FMU.
    Output,
}

impl Causality {
    /// The attribute value.
    pub fn name(self) -> &'static str {
        match self {
            Causality::Independent => "independent",
            Causality::Parameter => "parameter",
            Causality::CalculatedParameter => "calculatedParameter",
            Causality::Input => "input",
            Causality::Output => "output",
        }
    }
}

/// FMI variability.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variability {
    /// Fixed after initialization.
    Fixed,
    /// Changes only at events (Boolean outputs).
    Discrete,
    /// Changes continuously.
    Continuous,
}

impl Variability {
    /// The attribute value.
    pub fn name(self) -> &'static str {
        match self {
            Variability::Fixed => "fixed",
            Variability::Discrete => "discrete",
            Variability::Continuous => "continuous",
        }
    }
}

/// Which end of which beam an input force acts on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tip {
    /// The bridge's free end.
    Upper,
    /// The arrestor's free end.
    Lower,
}

/// A column of Table 2.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Column {
    /// The arrestor alone.
    Lower,
    /// The bridge alone.
    Upper,
    /// The coupled system.
    Coupled,
}

/// `log.channels`' start value: every topic.
pub const DEFAULT_LOG_CHANNELS: &str = "all";

/// Where a variable's value comes from.
#[derive(Clone, Copy, Debug)]
pub enum Source {
    /// Simulated time, s.
    Time,
    /// A scenario parameter.
    Parameter(&'static Parameter),
    /// The MCAP log path.
    LogPath,
    /// The MCAP log's topics (`log.channels`).
    LogChannels,
    /// The MCAP log's dense output, s (`log.sample_interval`, issue 41).
    LogSampleInterval,
    /// The most internal steps a run may take (`solver.max_steps`, issue 40), enforced at every
    /// step of doStep.
    MaxSteps,
    /// An input tip force.
    Input(Tip),
    /// A support-motion input: its index in [`crate::model::support_motion::MOTION_NAMES`].
    Motion(usize),
    /// A real output of the latest step.
    Output(fn(&StepResult) -> f64),
    /// Whether the latest step was in contact.
    ContactActive,
    /// The `k`-th natural frequency (0-based) of a column of Table 2.
    Mode(Column, usize),
    /// A result of the energy approach of Section 3.
    EnergyMethod(fn(&EnergyMethod) -> f64),
    /// A stress peak's utilisation (running peak / allowable), in the order of
    /// [`crate::answer::DesignUtilisation::as_array`].
    Utilisation(usize),
    /// Whether every utilisation is <= 1.
    DesignPass,
    /// Whether every check that runs in the FMU passes (energy, discretisation, yield).
    Trusted,
    /// Whether the FMU runs the reproducibility twin (`check_sensitivity`, an FMU-only parameter).
    CheckSensitivity,
    /// The largest discretisation figure of the running peaks so far (-1: not checked).
    DiscretisationError,
    /// The largest spread against the twin run (-1: not checked; the FMU runs no twin).
    SensitivitySpread,
    /// The impact as the run starts it ([`crate::Simulation::impact`], issue 28).
    Impact(fn(&Impact) -> f64),
    /// A beam's worst stress along it so far (issue 30), in the order of
    /// [`crate::results::ENVELOPE_PEAK_NAMES`]: its value, Pa (0 where the beam has none).
    EnvelopePeak(usize),
    /// ... its position, m from the beam's support (0 where the beam has none).
    EnvelopePosition(usize),
    /// ... and the beam's worst utilisation along it, each station against its section's
    /// allowable (0 where the beam has no such stress or no allowable).
    EnvelopeUtilisation(usize),
}

/// One model variable.
#[derive(Clone, Debug)]
pub struct Variable {
    /// Name (structured naming convention: `upper.length`, `modes.lower.omega[1]`).
    pub name: String,
    /// Value reference (= index in the table).
    pub vr: u32,
    /// Base type.
    pub ty: Type,
    /// Causality.
    pub causality: Causality,
    /// Variability.
    pub variability: Variability,
    /// `initial`: `Some(true)` for exact (with a start value), `Some(false)` for calculated,
    /// `None` for the independent variable.
    pub exact: Option<bool>,
    /// SI unit, if any; the descriptions declare it through the unit's type definition
    /// ([`declared_type`]), not on the variable.
    pub unit: Option<&'static str>,
    /// Declared `min` (parameters the physics bounds, see [`declared_range`]; the support-motion
    /// inputs' range, [`MOTION_LIMITS`]).
    pub min: Option<f64>,
    /// Declared `max`.
    pub max: Option<f64>,
    /// What it is.
    pub description: String,
    /// Start value as written in the description.
    pub start: Option<String>,
    /// Where the value comes from.
    pub source: Source,
}

impl Variable {
    /// The display unit (MPa for stresses and moduli).
    pub fn display_unit(&self) -> Option<&'static str> {
        self.unit.and_then(display_unit)
    }

    /// The name of the type definition that declares the variable's unit.
    pub fn declared_type(&self) -> Option<&'static str> {
        self.unit.and_then(declared_type).map(|(name, _)| name)
    }
}

/// The display unit of a unit, if it has one (MPa for Pa).
pub fn display_unit(unit: &str) -> Option<&'static str> {
    (unit == "Pa").then_some("MPa")
}

pub use crate::model::parameters::SMALLEST_POSITIVE;

/// The declared (`min`, `max`) of a parameter (`None`: not declared): the scenario's ranges,
/// [`crate::model::parameters::RANGES`].
pub fn declared_range(p: &Parameter) -> (Option<f64>, Option<f64>) {
    crate::model::parameters::range(p.name)
}

/// Formats a real start value so that it parses back to the same number.
pub fn format_real(value: f64) -> String {
    format!("{value:?}")
}

type Out = fn(&StepResult) -> f64;

/// The real outputs: name, unit, description, accessor.
const OUTPUTS: &[OutputRow] = &[
    ("lower.tip_deflection", "m", "Deflection of the arrestor's free end (y up: negative downward)", |r| {
        r.lower_tip_deflection
    }),
    ("upper.contact_deflection", "m", "Deflection of the bridge's contact node (y up: negative downward)", |r| {
        r.upper_contact_deflection
    }),
    ("upper.tip_deflection", "m", "Deflection of the bridge's free end (y up: negative downward)", |r| {
        r.upper_tip_deflection
    }),
    ("lower.clamp_bending_stress", "Pa", "Bending stress M/W at the arrestor's clamp, sagging positive", |r| {
        r.lower_clamp_bending_stress
    }),
    ("lower.clamp_shear_stress", "Pa", "Shear stress Q/A_s at the arrestor's clamp", |r| r.lower_clamp_shear_stress),
    ("upper.contact_bending_stress", "Pa", "Bending stress M/W at the bridge's contact node, sagging positive", |r| {
        r.upper_contact_bending_stress
    }),
    ("contact.stress", "Pa", "Contact bar stress F_c/A_c (negative in compression, 0 when apart)", |r| {
        r.contact_stress
    }),
    ("contact.force", "N", "Contact bar force F_c (Eq. 5): negative in compression, 0 when apart", |r| r.contact_force),
    ("energy.kinetic", "J", "Kinetic energy of both beams", |r| r.energy.kinetic),
    ("energy.strain", "J", "Strain energy of both beams and of the contact bar", |r| r.energy.strain),
    ("energy.gravity_potential", "J", "Potential energy of gravity from the undeformed position", |r| {
        r.energy.gravity_potential
    }),
    (
        "energy.external_work",
        "J",
        "Work done on the beams since t = 0 by the two input tip forces and by the supports when they move: the \
         inertia loads of their accelerations, and the contact bar's force through the change of the gap their \
         displacements make (the energies are those of the motion relative to the supports)",
        |r| r.energy.external_work,
    ),
    ("energy.damping_dissipation", "J", "Energy dissipated by damping since t = 0", |r| r.energy.damping_dissipation),
    (
        "energy.residual",
        "J",
        "Energy balance residual: kinetic + strain + gravity + dissipated - external work - initial total",
        |r| r.energy.residual,
    ),
    ("peak.lower.tip_deflection", "m", "Running peak max |lower.tip_deflection| since t = 0", |r| {
        r.peaks.lower_tip_deflection
    }),
    ("peak.lower.clamp_bending_stress", "Pa", "Running peak max |lower.clamp_bending_stress| since t = 0", |r| {
        r.peaks.lower_clamp_bending_stress
    }),
    ("peak.lower.clamp_shear_stress", "Pa", "Running peak max |lower.clamp_shear_stress| since t = 0", |r| {
        r.peaks.lower_clamp_shear_stress
    }),
    ("peak.upper.contact_bending_stress", "Pa", "Running peak max |upper.contact_bending_stress| since t = 0", |r| {
        r.peaks.upper_contact_bending_stress
    }),
    ("peak.contact.force", "N", "Running peak max |contact.force| since t = 0", |r| r.peaks.contact_force),
];

/// Real outputs added after the first release (issue 8: what a system engineer couples the
/// platforms and tip springs to), appended at the end of [`table`] so that older value
/// references stay as they were.
const APPENDED_OUTPUTS: &[OutputRow] = &[
    (
        "lower.clamp_reaction_force",
        "N",
        "Vertical force of the clamp on the arrestor, up positive (dynamic: stiffness, damping, consistent mass, loads)",
        |r| r.lower_clamp_reaction_force,
    ),
    (
        "upper.hinge_reaction_force",
        "N",
        "Vertical force of the hinge on the bridge, up positive (dynamic: stiffness, damping, consistent mass, loads)",
        |r| r.upper_hinge_reaction_force,
    ),
    (
        "lower.clamp_reaction_moment",
        "N.m",
        "Moment of the clamp on the arrestor, counter-clockwise positive (x from the clamp towards the free end)",
        |r| r.lower_clamp_reaction_moment,
    ),
    ("lower.tip_velocity", "m/s", "Vertical velocity of the arrestor's free end, up positive", |r| {
        r.lower_tip_velocity
    }),
    ("upper.tip_velocity", "m/s", "Vertical velocity of the bridge's free end, up positive", |r| r.upper_tip_velocity),
];

type Method = fn(&EnergyMethod) -> f64;

/// The energy approach's results: name suffix, unit, description, accessor.
const ENERGY_METHOD: &[(&str, &str, &str, Method)] = &[
    ("tip_deflection", "m", "Energy method (Eq. 33): dynamic deflection of the arrestor's end", |e| e.tip_deflection),
    ("force", "N", "Energy method (Eq. 29): dynamic contact force", |e| e.force),
    ("clamp_bending_stress", "Pa", "Energy method: bending stress at the arrestor's clamp", |e| e.clamp_bending_stress),
    ("clamp_shear_stress", "Pa", "Energy method: shear stress at the arrestor's clamp", |e| e.clamp_shear_stress),
    ("strain_energy", "J", "Energy method (Eq. 35): strain energy of the arrestor", |e| e.strain_energy),
];

/// The energy approach's FMU outputs, `energy_method.<name>`, by name suffix (the Python
/// package's native sweep gives the FMU route's columns).
pub fn energy_method_names() -> Vec<&'static str> {
    ENERGY_METHOD.iter().map(|(name, ..)| *name).collect()
}

/// Whether a scenario parameter is an FMU parameter: all but `duration`, the CLI's run length (an
/// FMU runs until its importer's stop time).
pub fn is_fmu_parameter(p: &Parameter) -> bool {
    p.name != "duration"
}

/// Whether the values the FMU computes (outputs, calculated parameters) depend on a parameter:
/// all but `energy_tolerance`, which only decides whether a run is trusted (a warning).
pub fn affects_values(p: &Parameter) -> bool {
    p.name != "energy_tolerance"
}

/// Whether a parameter came after the first release: its value reference follows every older
/// variable's (the end of [`table`]), so that the older value references stay as they were.
/// These are every parameter from `energy_tolerance` on in [`PARAMETERS`] (issue 7: the energy
/// tolerance, the stress recovery; issue 15: the method, the modal cut-off, the discretisation
/// tolerance, the allowables and the yield stresses), in that order.
pub fn is_appended_parameter(p: &Parameter) -> bool {
    let index = |name: &str| PARAMETERS.iter().position(|q| q.name == name);
    matches!((index(p.name), index("energy_tolerance")), (Some(i), Some(first)) if i >= first)
        && !is_issue_28_parameter(p)
        && !is_issue_30_parameter(p)
        && !is_issue_45_parameter(p)
}

/// Whether a parameter came with issue 28 (every parameter from `impact_angular_velocity` on in
/// [`PARAMETERS`]): its value reference follows the tip positions, the end of the table before it.
pub fn is_issue_28_parameter(p: &Parameter) -> bool {
    let index = |name: &str| PARAMETERS.iter().position(|q| q.name == name);
    matches!((index(p.name), index("impact_angular_velocity")), (Some(i), Some(first)) if i >= first)
        && !is_issue_30_parameter(p)
        && !is_issue_45_parameter(p)
}

/// Whether a parameter came with issue 30 (every parameter from `upper.shear_area` on in
/// [`PARAMETERS`]): its value reference follows the impact's outputs, the end of the table before it.
pub fn is_issue_30_parameter(p: &Parameter) -> bool {
    let index = |name: &str| PARAMETERS.iter().position(|q| q.name == name);
    matches!((index(p.name), index("upper.shear_area")), (Some(i), Some(first)) if i >= first)
        && !is_issue_45_parameter(p)
}

/// Whether a parameter came with issue 45 (every parameter from `lower.supports` on in
/// [`PARAMETERS`]: the struck beam's supports, then the rigid impactor and the Hertz law's inputs): its value reference follows `solver.max_steps`, the end of the table before it.
pub fn is_issue_45_parameter(p: &Parameter) -> bool {
    let index = |name: &str| PARAMETERS.iter().position(|q| q.name == name);
    matches!((index(p.name), index("lower.supports")), (Some(i), Some(first)) if i >= first)
}

/// A variable as [`table`] lists it, before its value reference and declared range: name,
/// type, causality, variability, initial (see [`Variable::exact`]), unit, description, start
/// value, source.
type Row = (String, Type, Causality, Variability, Option<bool>, Option<&'static str>, String, Option<String>, Source);

/// An entry of [`OUTPUTS`] and [`APPENDED_OUTPUTS`]: name, unit, description, accessor.
type OutputRow = (&'static str, &'static str, &'static str, Out);

/// Every variable of the FMU, in value-reference order, with the paper scenario's start values.
pub fn table() -> Vec<Variable> {
    table_for(&Scenario::default())
}

/// Every variable of the FMU, in value-reference order, with the start values of `defaults`: the
/// scenario an instance starts from (the paper's, or the one packed into the FMU's resources,
/// issue 30). Names, value references, types and ranges are the same for every scenario.
pub fn table_for(defaults: &Scenario) -> Vec<Variable> {
    let mut v: Vec<Variable> = Vec::new();
    let mut push = |(name, ty, causality, variability, exact, unit, description, start, source): Row| {
        let vr = v.len() as u32;
        let (min, max) = match source {
            Source::Parameter(p) => declared_range(p),
            Source::Motion(k) => (Some(-MOTION_LIMITS[k]), Some(MOTION_LIMITS[k])),
            // 0 (every internal step) or 1e-6 to 1 s: the declared range is the span.
            Source::LogSampleInterval => {
                (Some(0.0), Some(crate::record::options::SAMPLE_INTERVAL_BOUNDS_NS.1 as f64 * 1e-9))
            }
            Source::MaxSteps => (Some(1.0), Some(f64::from(i32::MAX))),
            _ => (None, None),
        };
        v.push(Variable { name, vr, ty, causality, variability, exact, unit, min, max, description, start, source });
    };
    push((
        "time".into(),
        Type::Real,
        Causality::Independent,
        Variability::Continuous,
        None,
        Some("s"),
        "Simulated time since the impact starts".into(),
        None,
        Source::Time,
    ));
    // The two parameter blocks (first release, appended) and the two output blocks (first
    // release, appended) differ only in which entries they take.
    let parameter = |p: &'static Parameter| -> Row {
        let value = (p.get)(defaults);
        let (ty, start) = match p.kind {
            Kind::Real => (Type::Real, format_real(value)),
            Kind::Integer => (Type::Integer, format!("{}", value as i64)),
        };
        let unit = (!p.unit.is_empty()).then_some(p.unit);
        (
            p.name.to_string(),
            ty,
            Causality::Parameter,
            Variability::Fixed,
            Some(true),
            unit,
            format!("{}{}", p.description, crate::model::parameters::range_note(p.name).unwrap_or_default()),
            Some(start),
            Source::Parameter(p),
        )
    };
    let real_output = |name: &str, unit: &'static str, description: &str, source: Source| -> Row {
        (
            name.into(),
            Type::Real,
            Causality::Output,
            Variability::Continuous,
            Some(false),
            Some(unit),
            description.into(),
            None,
            source,
        )
    };
    let output = |&(name, unit, description, get): &OutputRow| -> Row {
        real_output(name, unit, description, Source::Output(get))
    };
    let later = |p: &Parameter| {
        is_appended_parameter(p) || is_issue_28_parameter(p) || is_issue_30_parameter(p) || is_issue_45_parameter(p)
    };
    for p in PARAMETERS.iter().filter(|p| is_fmu_parameter(p) && !later(p)) {
        push(parameter(p));
    }
    push((
        "log.path".into(),
        Type::String,
        Causality::Parameter,
        Variability::Fixed,
        Some(true),
        None,
        "MCAP log of the run (the exact state every log.sample_interval and at every peak; zstd chunks). The default BeamImpact.mcap stands for a new file per \
         instance and run in the user's log folder, not the working directory (an SSP tool's run would litter it): \
         $XDG_STATE_HOME/beam-impact/logs, else ~/.local/state/beam-impact/logs (Windows: \
         %LOCALAPPDATA%\\beam-impact\\logs), named BeamImpact-<instance>-<UTC date-time>-<n>.mcap after the instance \
         name (its last component if it is a path), never overwriting one (the FMU's log says the full path); any \
         other path: that file, relative to the working directory; empty: no log"
            .into(),
        Some("BeamImpact.mcap".into()),
        Source::LogPath,
    ));
    for (name, tip, what, start) in [
        ("upper.tip_force", Tip::Upper, "bridge's free end", defaults.upper.tip_force),
        ("lower.tip_force", Tip::Lower, "arrestor's free end", defaults.lower.tip_force),
    ] {
        push((
            name.into(),
            Type::Real,
            Causality::Input,
            Variability::Continuous,
            Some(true),
            Some("N"),
            format!("Vertical external force at the {what}, up positive, held over each step"),
            Some(format_real(start)),
            Source::Input(tip),
        ));
    }
    for row in OUTPUTS {
        push(output(row));
    }
    push((
        "contact.active".into(),
        Type::Boolean,
        Causality::Output,
        Variability::Discrete,
        Some(false),
        None,
        "Whether the latest internal step was taken in contact (Eq. 6)".into(),
        None,
        Source::ContactActive,
    ));
    for (column, key, what) in [
        (Column::Lower, "lower", "the arrestor alone"),
        (Column::Upper, "upper", "the bridge alone"),
        (Column::Coupled, "coupled", "the coupled system (bar always active)"),
    ] {
        for k in 0..MODES {
            push((
                format!("modes.{key}.omega[{}]", k + 1),
                Type::Real,
                Causality::CalculatedParameter,
                Variability::Fixed,
                Some(false),
                Some("rad/s"),
                format!("Natural frequency {} of {what} (Table 2)", k + 1),
                None,
                Source::Mode(column, k),
            ));
        }
    }
    for &(name, unit, description, get) in ENERGY_METHOD {
        push((
            format!("energy_method.{name}"),
            Type::Real,
            Causality::CalculatedParameter,
            Variability::Fixed,
            Some(false),
            Some(unit),
            description.into(),
            None,
            Source::EnergyMethod(get),
        ));
    }
    for row in APPENDED_OUTPUTS {
        push(output(row));
    }
    for (k, name) in ["lower.clamp_bending_stress", "lower.clamp_shear_stress", "upper.contact_bending_stress"]
        .into_iter()
        .enumerate()
    {
        push((
            format!("utilisation.{name}"),
            Type::Real,
            Causality::Output,
            Variability::Continuous,
            Some(false),
            Some("1"),
            format!("Design check: running peak of {name} over its allowable stress (fails above 1)"),
            None,
            Source::Utilisation(k),
        ));
    }
    push((
        "design.pass".into(),
        Type::Boolean,
        Causality::Output,
        Variability::Discrete,
        Some(false),
        None,
        "Design check: every utilisation.* <= 1".into(),
        None,
        Source::DesignPass,
    ));
    push((
        "quality.trusted".into(),
        Type::Boolean,
        Causality::Output,
        Variability::Discrete,
        Some(false),
        None,
        "Every check the FMU runs passes so far: energy balance, discretisation (the coarser rungs run in \
         lockstep), the twin's spread, yield, and the model's range (every node's deflection and rotation, each \
         beam's strain)"
            .into(),
        None,
        Source::Trusted,
    ));
    push((
        "quality.discretisation_error".into(),
        Type::Real,
        Causality::Output,
        Variability::Continuous,
        Some(false),
        Some("1"),
        "Largest discretisation figure of the running peaks against the coarser rungs (paper method: against the \
         converged answer); -1: not checked (after SetFMUState)"
            .into(),
        None,
        Source::DiscretisationError,
    ));
    push((
        "quality.sensitivity_spread".into(),
        Type::Real,
        Causality::Output,
        Variability::Continuous,
        Some(false),
        Some("1"),
        "Largest spread of the running peaks against a twin run with the drop height changed by 1e-9 (relative), \
         stepped in lockstep when check_sensitivity is true; -1: not checked (check_sensitivity false, the \
         default, or after SetFMUState of a state without the twin)"
            .into(),
        None,
        Source::SensitivitySpread,
    ));
    for p in PARAMETERS.iter().filter(|p| is_fmu_parameter(p) && is_appended_parameter(p)) {
        push(parameter(p));
    }
    push((
        "check_sensitivity".into(),
        Type::Boolean,
        Causality::Parameter,
        Variability::Fixed,
        None,
        None,
        "Run the reproducibility twin (drop height changed by 1e-9, relative) in lockstep and report \
         quality.sensitivity_spread; it doubles the cost of a converged run's stepping (the CLI always runs it)"
            .into(),
        Some("false".into()),
        Source::CheckSensitivity,
    ));
    // Issue 17: the supports' motion, as a vessel-motion model hands it over (appended).
    let motion_descriptions = [
        "Vertical displacement of the bridge's hinge, up positive (its support moves with it)",
        "Vertical velocity of the bridge's hinge",
        "Vertical acceleration of the bridge's hinge (loads the bridge with its inertia)",
        "Vertical displacement of the arrestor's clamp, up positive",
        "Vertical velocity of the arrestor's clamp",
        "Vertical acceleration of the arrestor's clamp (loads the arrestor with its inertia)",
        "Rotation of the arrestor's clamp, the sign of the arrestor's slope dw/dx (positive raises its end by \
         lower.length times it); small angles (the model linearises the rotation)",
        "Angular velocity of the arrestor's clamp",
        "Angular acceleration of the arrestor's clamp",
    ];
    for (k, (name, unit)) in MOTION_NAMES.iter().zip(MOTION_UNITS).enumerate() {
        push((
            (*name).into(),
            Type::Real,
            Causality::Input,
            Variability::Continuous,
            Some(true),
            Some(unit),
            format!(
                "{}. Range |value| <= {} {unit} (min and max; a value beyond is refused with an error). Between \
                 communication points the support moves as z + v tau + a tau^2/2 from the values set at the point: \
                 displacement, velocity and acceleration must agree (a warning names a mismatch)",
                motion_descriptions[k], MOTION_LIMITS[k]
            ),
            Some("0.0".into()),
            Source::Motion(k),
        ));
    }
    for row in POSITION_OUTPUTS {
        push(output(row));
    }
    // Issue 28: the impact's speed, the rigid support, the contact's rate and clearance (appended).
    for p in PARAMETERS.iter().filter(|p| is_fmu_parameter(p) && is_issue_28_parameter(p)) {
        push(parameter(p));
    }
    // Issue 28: the impact the run starts with (appended after its parameters).
    for &(name, unit, description, get) in IMPACT_OUTPUTS {
        push(real_output(name, unit, description, Source::Impact(get)));
    }
    // Issue 30: the bridge's shear area and allowable shear stress (appended), then each beam's
    // worst stress along it, its position and its utilisation.
    for p in PARAMETERS.iter().filter(|p| is_fmu_parameter(p) && is_issue_30_parameter(p)) {
        push(parameter(p));
    }
    for (k, name) in ENVELOPE_PEAK_NAMES.iter().enumerate() {
        let description = format!("{}{}", envelope_description(k, EnvelopeField::Peak), missing_envelope(k));
        push(real_output(&format!("peak.{name}"), "Pa", &description, Source::EnvelopePeak(k)));
    }
    for (k, name) in ENVELOPE_PEAK_NAMES.iter().enumerate() {
        let description = format!("{}{}", envelope_description(k, EnvelopeField::Position), missing_envelope(k));
        push(real_output(&format!("peak_position.{name}"), "m", &description, Source::EnvelopePosition(k)));
    }
    for (k, name) in ENVELOPE_PEAK_NAMES.iter().enumerate() {
        let description = format!("{}{}", envelope_description(k, EnvelopeField::Utilisation), missing_utilisation(k));
        push(real_output(&format!("utilisation.{name}"), "1", &description, Source::EnvelopeUtilisation(k)));
    }
    push((
        "log.channels".into(),
        Type::String,
        Causality::Parameter,
        Variability::Fixed,
        Some(true),
        None,
        "The MCAP log's topics, a comma list: model, step, contact and log (always written), modes (/beam/modes, the \
         modal coordinates: the deflected shapes), scene (/beam/scene, Foxglove's 3D panel) and stations \
         (/beam/stations, the stress at every station: a killed run's log rebuilds its envelope from them), or all; \
         \"step\" writes the smallest log that replays. An unknown name is an error naming it"
            .into(),
        Some(DEFAULT_LOG_CHANNELS.into()),
        Source::LogChannels,
    ));
    push((
        "log.sample_interval".into(),
        Type::Real,
        Causality::Parameter,
        Variability::Fixed,
        Some(true),
        Some("s"),
        "The MCAP log's dense output: the exact state every this much simulated time and at every instant a \
         running peak is reached (the converged method; the paper method's log keeps one of its own steps at least \
         this often), so that the log's largest values are the peak outputs; 0: every internal step; else 1e-6 to 1 s"
            .into(),
        Some(format!("{}", crate::record::options::DEFAULT_SAMPLE_INTERVAL_NS as f64 * 1e-9)),
        Source::LogSampleInterval,
    ));
    push((
        "solver.max_steps".into(),
        Type::Integer,
        Causality::Parameter,
        Variability::Fixed,
        Some(true),
        None,
        format!(
            "The most internal steps the run may take, enforced at every step of doStep (and of the check runs): a \
             run whose steps shrink far below its plan's (a very stiff contact chattering) stops with an error \
             naming the time reached, instead of running on; 1 to {} (the CLI's --max-steps, Python's max_steps=)",
            i32::MAX
        ),
        Some(format!("{}", crate::model::scenario::MAX_STEPS)),
        Source::MaxSteps,
    ));
    // Issue 45: the struck beam's supports and contact position, the rigid impactor and the
    // Hertz law's inputs, and the far support's reactions (appended).
    for p in PARAMETERS.iter().filter(|p| is_fmu_parameter(p) && is_issue_45_parameter(p)) {
        push(parameter(p));
    }
    for row in FAR_SUPPORT_OUTPUTS {
        push(output(row));
    }
    v
}

/// Issue 45: the struck beam's far support's reactions (0 for the paper's free far end).
const FAR_SUPPORT_OUTPUTS: &[OutputRow] = &[
    (
        "lower.far_reaction_force",
        "N",
        "Vertical force of the struck beam's far support (x = lower.length) on it, up positive, on a beam on two \
         supports (lower.supports); 0 at a free end (dynamic: stiffness, damping, consistent mass, loads)",
        |r| r.lower_far_reaction_force,
    ),
    (
        "lower.far_reaction_moment",
        "N.m",
        "Moment of the struck beam's far support on it, counter-clockwise positive, at a clamped far end; 0 at a pin \
         or a free end",
        |r| r.lower_far_reaction_moment,
    ),
];

/// Which output of an envelope peak a description is for.
#[derive(Clone, Copy)]
enum EnvelopeField {
    Peak,
    Position,
    Utilisation,
}

/// The beam and stress of envelope peak `k` ([`ENVELOPE_PEAK_NAMES`]' order): (beam, its
/// support, stress, formula).
fn envelope_quantity(k: usize) -> (&'static str, &'static str, &'static str, &'static str) {
    let (beam, support) = if k < 2 { ("bridge", "hinge") } else { ("arrestor", "clamp") };
    let (stress, formula) = if k.is_multiple_of(2) { ("bending", "|M|/W") } else { ("shear", "|Q|/A_s") };
    (beam, support, stress, formula)
}

/// The description of one of the envelope outputs (issue 30).
fn envelope_description(k: usize, field: EnvelopeField) -> String {
    let (beam, support, stress, formula) = envelope_quantity(k);
    let name = ENVELOPE_PEAK_NAMES[k];
    match field {
        EnvelopeField::Peak => format!(
            "Running peak of the {beam}'s {stress} stress {formula} along its whole length: the largest over every \
             station (each node; both sides of a section change or a point load) since t = 0, the stress envelope's \
             peak (the CLI's summary.peaks.{name})"
        ),
        EnvelopeField::Position => format!(
            "Where peak.{name} is along the {beam}, m from its {support} (the CLI's summary.peak_positions.{name})"
        ),
        EnvelopeField::Utilisation => format!(
            "Design check: the {beam}'s worst {stress} utilisation along it so far, each station's running peak over \
             the allowable {stress} stress of its own section (fails above 1; design.pass counts it)"
        ),
    }
}

/// What an envelope output gives where the beam has no such stress (the bridge always has its
/// bending stress).
fn missing_envelope(k: usize) -> &'static str {
    match k {
        0 => "",
        1 => "; 0 when the bridge has no shear area (upper.shear_area = 0, the default: no shear stress computed)",
        _ => "; 0 with a rigid support (lower.kind = 1: no arrestor beam)",
    }
}

/// What a utilisation output gives where it is not checked (the bridge's bending stress always is).
fn missing_utilisation(k: usize) -> &'static str {
    match k {
        0 => "",
        1 => {
            "; 0 when not checked: the bridge has no shear area (upper.shear_area = 0) or no allowable shear stress \
             (upper.allowable_shear_stress = 0 and no section gives its own)"
        }
        _ => "; 0 with a rigid support (lower.kind = 1: no arrestor beam)",
    }
}

/// An entry of [`IMPACT_OUTPUTS`]: name, unit, description, accessor.
type ImpactRow = (&'static str, &'static str, &'static str, fn(&Impact) -> f64);

/// The impact as the run starts it (issue 28), appended after issue 28's parameters: name, unit,
/// description, accessor of [`crate::Simulation::impact`]. Both are fixed by the parameters and
/// the support-motion inputs at the end of initialization (constant over the run).
const IMPACT_OUTPUTS: &[ImpactRow] = &[
    (
        "impact.angular_velocity",
        "rad/s",
        "The bridge's angular velocity omega_0 about its hinge at first contact (t = 0), free end moving down: \
         impact_angular_velocity when given (> 0), else from drop_height h after Eqs. 20-22, omega_0 = sqrt(3 g \
         alpha_0 / l_u) with alpha_0 = atan(2 h / l_u), l_u = upper.length and g = gravity plus \
         upper.hinge_heave_acceleration at t = 0 (the paper's 0.567 m drop of its 29 m bridge: 0.1992 rad/s). Constant over the run",
        |i| i.angular_velocity,
    ),
    (
        "impact.closing_speed",
        "m/s",
        "The speed at which the contact point closes the gap at t = 0, positive closing: omega_0 d \
         (impact.angular_velocity times contact_position) plus the supports' closing speed \
         (lower.clamp_heave_velocity + lower.clamp_rotation_velocity lower.length - upper.hinge_heave_velocity at \
         t = 0; 0 with the supports at rest). Constant over the run",
        |i| i.closing_speed,
    ),
];

/// The tips' absolute positions (issue 17), appended after the support-motion inputs.
const POSITION_OUTPUTS: &[OutputRow] = &[
    (
        "upper.tip_position",
        "m",
        "Absolute vertical position of the bridge's free end: upper.tip_deflection plus the hinge's heave (0 at the \
         undeformed horizontal with the supports at rest)",
        |r| r.upper_tip_position(),
    ),
    (
        "lower.tip_position",
        "m",
        "Absolute vertical position of the arrestor's free end: lower.tip_deflection plus the clamp's heave plus its \
         rotation times lower.length",
        |r| r.lower_tip_position(),
    ),
];

/// Every unit the table uses: its base-unit exponents (kg, m, s, rad) and the type definition
/// that declares it (name, quantity), as the Reference-FMUs declare units: through
/// `<TypeDefinitions>` and `declaredType`, never on the variable (some importers, such as
/// rust-fmi, refuse `unit` on an FMI 3 `Float64`).
const UNITS: &[(&str, [i32; 4], &str, &str)] = &[
    ("1", [0, 0, 0, 0], "Ratio", "Ratio"),
    ("s", [0, 0, 1, 0], "Time", "Time"),
    ("1/s", [0, 0, -1, 0], "InverseTime", "InverseTime"),
    ("m", [0, 1, 0, 0], "Length", "Length"),
    ("m2", [0, 2, 0, 0], "Area", "Area"),
    ("m3", [0, 3, 0, 0], "SectionModulus", "SectionModulus"),
    ("m4", [0, 4, 0, 0], "SecondMomentOfArea", "SecondMomentOfArea"),
    ("m/s2", [0, 1, -2, 0], "Acceleration", "Acceleration"),
    ("m/s", [0, 1, -1, 0], "Velocity", "Velocity"),
    ("N.m", [1, 2, -2, 0], "Moment", "MomentOfForce"),
    ("N/m", [1, 0, -2, 0], "Stiffness", "TranslationalStiffness"),
    ("s/m", [0, -1, 1, 0], "InverseVelocity", "InverseVelocity"),
    ("kg", [1, 0, 0, 0], "Mass", "Mass"),
    ("N", [1, 1, -2, 0], "Force", "Force"),
    ("Pa", [1, -1, -2, 0], "Stress", "Stress"),
    ("J", [1, 2, -2, 0], "Energy", "Energy"),
    ("rad/s", [0, 0, -1, 1], "AngularVelocity", "AngularVelocity"),
    ("rad", [0, 0, 0, 1], "Angle", "Angle"),
    ("rad/s2", [0, 0, -2, 1], "AngularAcceleration", "AngularAcceleration"),
];

/// Base-unit exponents (kg, m, s, rad) of every unit the table uses.
pub fn base_units(unit: &str) -> Option<[i32; 4]> {
    UNITS.iter().find(|u| u.0 == unit).map(|u| u.1)
}

/// The type definition that declares a unit: (type name, quantity).
pub fn declared_type(unit: &str) -> Option<(&'static str, &'static str)> {
    UNITS.iter().find(|u| u.0 == unit).map(|u| (u.2, u.3))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_value_references_are_indices() {
        let t = table();
        let mut names: Vec<&str> = t.iter().map(|v| v.name.as_str()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), t.len());
        assert!(t.iter().enumerate().all(|(i, v)| v.vr as usize == i));
    }

    #[test]
    fn every_unit_has_base_units_and_every_variable_a_description() {
        for v in table() {
            assert!(!v.description.is_empty(), "{}", v.name);
            if let Some(u) = v.unit {
                assert!(base_units(u).is_some(), "{} has unit {u} without base units", v.name);
                assert!(declared_type(u).is_some(), "{} has unit {u} without a type definition", v.name);
            }
        }
    }

    #[test]
    fn type_names_are_unique() {
        let mut names: Vec<&str> = UNITS.iter().map(|u| u.2).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), UNITS.len());
    }

    #[test]
    fn every_range_names_an_fmu_parameter_and_holds_its_start_value() {
        for &(name, min, max) in crate::model::parameters::RANGES {
            let v = table().into_iter().find(|v| v.name == name).unwrap_or_else(|| panic!("{name}: no such variable"));
            let start: f64 = v.start.as_deref().unwrap_or_default().parse().unwrap();
            assert!(min.is_none_or(|m| m <= start) && max.is_none_or(|m| start <= m), "{name}: start {start}");
        }
    }

    #[test]
    fn start_values_parse_back_to_the_paper_scenario() {
        let defaults = Scenario::default();
        for v in table() {
            if let (Source::Parameter(p), Some(start)) = (v.source, &v.start) {
                assert_eq!(start.parse::<f64>().unwrap(), (p.get)(&defaults), "{}", v.name);
            }
        }
    }
}
