//! The FMU's variable table: the one source of both modelDescription.xml files and of the
//! value references the getters and setters dispatch on. The parameter part comes from
//! [`PARAMETERS`]; the value reference of a variable is its index in [`table`].

use crate::model::parameters::{Kind, Parameter, PARAMETERS};
use crate::results::StepResult;
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

/// Where a variable's value comes from.
#[derive(Clone, Copy, Debug)]
pub enum Source {
    /// Simulated time, s.
    Time,
    /// A scenario parameter.
    Parameter(&'static Parameter),
    /// The MCAP log path.
    LogPath,
    /// An input tip force.
    Input(Tip),
    /// A real output of the latest step.
    Output(fn(&StepResult) -> f64),
    /// Whether the latest step was in contact.
    ContactActive,
    /// The `k`-th natural frequency (0-based) of a column of Table 2.
    Mode(Column, usize),
    /// A result of the energy approach of Section 3.
    EnergyMethod(fn(&EnergyMethod) -> f64),
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
    /// SI unit, if any.
    pub unit: Option<&'static str>,
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
        (self.unit == Some("Pa")).then_some("MPa")
    }
}

/// Formats a real start value so that it parses back to the same number.
pub fn format_real(value: f64) -> String {
    format!("{value:?}")
}

type Out = fn(&StepResult) -> f64;

/// The real outputs: name, unit, description, accessor.
const OUTPUTS: &[(&str, &str, &str, Out)] = &[
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
    ("energy.external_work", "J", "Work done by the two input tip forces since t = 0", |r| r.energy.external_work),
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
const APPENDED_OUTPUTS: &[(&str, &str, &str, Out)] = &[
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

/// Whether a scenario parameter is an FMU parameter: all but `duration`, the CLI's run length (an
/// FMU runs until its importer's stop time).
pub fn is_fmu_parameter(p: &Parameter) -> bool {
    p.name != "duration"
}

/// Whether a parameter came after the first release: its value reference follows every older
/// variable's (the end of [`table`]), so that the older value references stay as they were.
pub fn is_appended_parameter(p: &Parameter) -> bool {
    matches!(p.name, "energy_tolerance" | "stress_recovery")
}

/// Every variable of the FMU, in value-reference order.
pub fn table() -> Vec<Variable> {
    let defaults = Scenario::default();
    let mut v: Vec<Variable> = Vec::new();
    let mut push = |name: String,
                    ty: Type,
                    causality: Causality,
                    variability: Variability,
                    exact: Option<bool>,
                    unit: Option<&'static str>,
                    description: String,
                    start: Option<String>,
                    source: Source| {
        let vr = v.len() as u32;
        v.push(Variable { name, vr, ty, causality, variability, exact, unit, description, start, source });
    };
    push(
        "time".into(),
        Type::Real,
        Causality::Independent,
        Variability::Continuous,
        None,
        Some("s"),
        "Simulated time since the impact starts".into(),
        None,
        Source::Time,
    );
    let parameter = |p: &'static Parameter| {
        let value = (p.get)(&defaults);
        let (ty, start) = match p.kind {
            Kind::Real => (Type::Real, format_real(value)),
            Kind::Integer => (Type::Integer, format!("{}", value as i64)),
        };
        let unit = (!p.unit.is_empty()).then_some(p.unit);
        (p.name.to_string(), ty, unit, p.description.to_string(), start)
    };
    for p in PARAMETERS.iter().filter(|p| is_fmu_parameter(p) && !is_appended_parameter(p)) {
        let (name, ty, unit, description, start) = parameter(p);
        push(
            name,
            ty,
            Causality::Parameter,
            Variability::Fixed,
            Some(true),
            unit,
            description,
            Some(start),
            Source::Parameter(p),
        );
    }
    push(
        "log.path".into(),
        Type::String,
        Causality::Parameter,
        Variability::Fixed,
        Some(true),
        None,
        "MCAP log of every internal step, relative to the working directory; empty: no log".into(),
        Some("BeamImpact.mcap".into()),
        Source::LogPath,
    );
    for (name, tip, what) in
        [("upper.tip_force", Tip::Upper, "bridge's free end"), ("lower.tip_force", Tip::Lower, "arrestor's free end")]
    {
        push(
            name.into(),
            Type::Real,
            Causality::Input,
            Variability::Continuous,
            Some(true),
            Some("N"),
            format!("Vertical external force at the {what}, up positive, held over each step"),
            Some("0.0".into()),
            Source::Input(tip),
        );
    }
    for &(name, unit, description, get) in OUTPUTS {
        push(
            name.into(),
            Type::Real,
            Causality::Output,
            Variability::Continuous,
            Some(false),
            Some(unit),
            description.into(),
            None,
            Source::Output(get),
        );
    }
    push(
        "contact.active".into(),
        Type::Boolean,
        Causality::Output,
        Variability::Discrete,
        Some(false),
        None,
        "Whether the latest internal step was taken in contact (Eq. 6)".into(),
        None,
        Source::ContactActive,
    );
    for (column, key, what) in [
        (Column::Lower, "lower", "the arrestor alone"),
        (Column::Upper, "upper", "the bridge alone"),
        (Column::Coupled, "coupled", "the coupled system (bar always active)"),
    ] {
        for k in 0..MODES {
            push(
                format!("modes.{key}.omega[{}]", k + 1),
                Type::Real,
                Causality::CalculatedParameter,
                Variability::Fixed,
                Some(false),
                Some("rad/s"),
                format!("Natural frequency {} of {what} (Table 2)", k + 1),
                None,
                Source::Mode(column, k),
            );
        }
    }
    for &(name, unit, description, get) in ENERGY_METHOD {
        push(
            format!("energy_method.{name}"),
            Type::Real,
            Causality::CalculatedParameter,
            Variability::Fixed,
            Some(false),
            Some(unit),
            description.into(),
            None,
            Source::EnergyMethod(get),
        );
    }
    for &(name, unit, description, get) in APPENDED_OUTPUTS {
        push(
            name.into(),
            Type::Real,
            Causality::Output,
            Variability::Continuous,
            Some(false),
            Some(unit),
            description.into(),
            None,
            Source::Output(get),
        );
    }
    for p in PARAMETERS.iter().filter(|p| is_fmu_parameter(p) && is_appended_parameter(p)) {
        let (name, ty, unit, description, start) = parameter(p);
        push(
            name,
            ty,
            Causality::Parameter,
            Variability::Fixed,
            Some(true),
            unit,
            description,
            Some(start),
            Source::Parameter(p),
        );
    }
    v
}

/// Base-unit exponents (kg, m, s, rad) of every unit the table uses.
pub fn base_units(unit: &str) -> Option<[i32; 4]> {
    Some(match unit {
        "1" => [0, 0, 0, 0],
        "s" => [0, 0, 1, 0],
        "1/s" => [0, 0, -1, 0],
        "m" => [0, 1, 0, 0],
        "m2" => [0, 2, 0, 0],
        "m3" => [0, 3, 0, 0],
        "m4" => [0, 4, 0, 0],
        "m/s2" => [0, 1, -2, 0],
        "m/s" => [0, 1, -1, 0],
        "N.m" => [1, 2, -2, 0],
        "kg" => [1, 0, 0, 0],
        "N" => [1, 1, -2, 0],
        "Pa" => [1, -1, -2, 0],
        "J" => [1, 2, -2, 0],
        "rad/s" => [0, 0, -1, 1],
        _ => return None,
    })
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
            }
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
