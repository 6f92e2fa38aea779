//! `beam-impact report --csv`: the step channel of a log as CSV, one row per step message kept by
//! the reader ([`super::report::LogData::steps`]: after rollbacks, in step order).
//!
//! The header row names each quantity as the FMU does ([`crate::vocabulary`]:
//! `lower.clamp_bending_stress`, `peak.contact.force`, `energy.kinetic`), then repeats the renamed
//! ones under their former names, the field paths of `beam_impact.Step`
//! (`lower_clamp_bending_stress`, `peaks.contact_force`), in the column order of the Python
//! reader's `load_log(...).dataframe()`, so `pandas.read_csv` gives the same columns. No comment
//! lines: the units are in [`COLUMNS`] and in the sidecar `FILE.units.json` that `report --csv
//! FILE` writes. The modal coordinates (field 16,
//! repeated; from log format 2 on a topic of their own) are not a column.
//!
//! Numbers round-trip: every f64 is written with the fewest digits that read back to the same
//! bits (Rust's shortest representation, in exponent form outside 1e-4 <= |x| < 1e15); integers
//! as integers; `contact` as `true` / `false` (pandas reads a bool column).

use std::io::Write;

use crate::results::StepResult;
use crate::vocabulary::STEP_RENAMES;

/// One column: its field path in `beam_impact.Step`, its SI unit, and how to read it off a step.
pub type Column = (&'static str, &'static str, Getter);

/// Reads one cell off a step.
pub type Getter = fn(&StepResult) -> Value;

/// The columns, in order.
pub const COLUMNS: [Column; 31] = [
    ("step", "1 (count)", |r| Value::Int(r.step)),
    ("time_ns", "ns", |r| Value::Int(r.time_ns)),
    ("time", "s", |r| Value::Float(r.time)),
    ("step_size", "s", |r| Value::Float(r.step_size)),
    ("contact", "true/false", |r| Value::Bool(r.contact)),
    ("lower_tip_deflection", "m", |r| Value::Float(r.lower_tip_deflection)),
    ("upper_contact_deflection", "m", |r| Value::Float(r.upper_contact_deflection)),
    ("upper_tip_deflection", "m", |r| Value::Float(r.upper_tip_deflection)),
    ("lower_clamp_bending_stress", "Pa", |r| Value::Float(r.lower_clamp_bending_stress)),
    ("lower_clamp_shear_stress", "Pa", |r| Value::Float(r.lower_clamp_shear_stress)),
    ("upper_contact_bending_stress", "Pa", |r| Value::Float(r.upper_contact_bending_stress)),
    ("contact_force", "N", |r| Value::Float(r.contact_force)),
    ("contact_stress", "Pa", |r| Value::Float(r.contact_stress)),
    ("lower_clamp_reaction_force", "N", |r| Value::Float(r.lower_clamp_reaction_force)),
    ("lower_clamp_reaction_moment", "N m", |r| Value::Float(r.lower_clamp_reaction_moment)),
    ("upper_hinge_reaction_force", "N", |r| Value::Float(r.upper_hinge_reaction_force)),
    ("lower_tip_velocity", "m/s", |r| Value::Float(r.lower_tip_velocity)),
    ("upper_tip_velocity", "m/s", |r| Value::Float(r.upper_tip_velocity)),
    ("lower_far_reaction_force", "N", |r| Value::Float(r.lower_far_reaction_force)),
    ("lower_far_reaction_moment", "N m", |r| Value::Float(r.lower_far_reaction_moment)),
    ("energy.kinetic", "J", |r| Value::Float(r.energy.kinetic)),
    ("energy.strain", "J", |r| Value::Float(r.energy.strain)),
    ("energy.gravity_potential", "J", |r| Value::Float(r.energy.gravity_potential)),
    ("energy.external_work", "J", |r| Value::Float(r.energy.external_work)),
    ("energy.damping_dissipation", "J", |r| Value::Float(r.energy.damping_dissipation)),
    ("energy.residual", "J", |r| Value::Float(r.energy.residual)),
    ("peaks.lower_tip_deflection", "m", |r| Value::Float(r.peaks.lower_tip_deflection)),
    ("peaks.lower_clamp_bending_stress", "Pa", |r| Value::Float(r.peaks.lower_clamp_bending_stress)),
    ("peaks.lower_clamp_shear_stress", "Pa", |r| Value::Float(r.peaks.lower_clamp_shear_stress)),
    ("peaks.upper_contact_bending_stress", "Pa", |r| Value::Float(r.peaks.upper_contact_bending_stress)),
    ("peaks.contact_force", "N", |r| Value::Float(r.peaks.contact_force)),
];

/// One cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// An unsigned integer field.
    Int(u64),
    /// A double field.
    Float(f64),
    /// A bool field.
    Bool(bool),
}

impl std::fmt::Display for Value {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Value::Int(n) => write!(f, "{n}"),
            Value::Bool(b) => f.write_str(if b { "true" } else { "false" }),
            Value::Float(x) => write_f64(f, x),
        }
    }
}

/// Writes `x` with the fewest digits that parse back to the same f64 (`NaN`, `inf`, `-inf` as
/// such): plain decimals for 1e-4 <= |x| < 1e15 and zero, exponent form (`1.5e-7`) otherwise,
/// so that tiny residuals do not take hundreds of zeros.
fn write_f64(f: &mut dyn std::fmt::Write, x: f64) -> std::fmt::Result {
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&x.abs()) {
        write!(f, "{x}")
    } else {
        write!(f, "{x:e}")
    }
}

/// The column names, in order: the quantities' names (the FMU's, [`crate::vocabulary`]: a
/// [`COLUMNS`] field path renamed by [`STEP_RENAMES`] or kept), then the former field-path names
/// of the renamed ones, as duplicates, until [`crate::vocabulary::FORMER_NAMES_REMOVED_IN`].
pub fn names() -> Vec<&'static str> {
    let renamed = |path: &'static str| STEP_RENAMES.iter().find(|(f, _)| *f == path).map_or(path, |(_, n)| *n);
    let mut names: Vec<&'static str> = COLUMNS.iter().map(|(path, _, _)| renamed(path)).collect();
    names.extend(STEP_RENAMES.iter().map(|(former, _)| *former));
    names
}

/// Each column of [`names`] with its unit.
pub fn column_units() -> Vec<(String, &'static str)> {
    let unit = |path: &str| COLUMNS.iter().find(|(p, _, _)| *p == path).map_or("", |(_, u, _)| *u);
    let mut columns: Vec<(String, &'static str)> = COLUMNS.iter().map(|(p, u, _)| (p.to_string(), *u)).collect();
    for (path, name) in STEP_RENAMES {
        if let Some(c) = columns.iter_mut().find(|(p, _)| p == path) {
            c.0 = name.to_string();
        }
    }
    columns.extend(STEP_RENAMES.iter().map(|(former, _)| (former.to_string(), unit(former))));
    columns
}

/// The former names with the names they duplicate (for the units sidecar).
pub fn former_names() -> Vec<(String, String)> {
    STEP_RENAMES.iter().map(|(f, n)| (f.to_string(), n.to_string())).collect()
}

/// The header row, without the line end.
pub fn header() -> String {
    names().join(",")
}

/// The getters in the order of [`names`].
fn getters() -> Vec<Getter> {
    let mut getters: Vec<Getter> = COLUMNS.iter().map(|(_, _, get)| *get).collect();
    for (former, _) in STEP_RENAMES {
        if let Some((_, _, get)) = COLUMNS.iter().find(|(p, _, _)| *p == former) {
            getters.push(*get);
        }
    }
    getters
}

/// Writes the header row and one row per step to `out` (buffer it: one `write` per cell).
pub fn write_steps(steps: &[StepResult], out: &mut dyn Write) -> std::io::Result<()> {
    writeln!(out, "{}", header())?;
    let getters = getters();
    for r in steps {
        for (k, get) in getters.iter().enumerate() {
            if k > 0 {
                out.write_all(b",")?;
            }
            write!(out, "{}", get(r))?;
        }
        out.write_all(b"\n")?;
    }
    out.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(x: f64) -> String {
        Value::Float(x).to_string()
    }

    #[test]
    fn floats_round_trip_and_stay_short() {
        for x in [
            0.0,
            -0.0,
            1.0,
            -0.657_123_456_789_012_3,
            4.688e8,
            1e-17,
            -3.3e-300,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            1e15,
            0.1 + 0.2,
            2.5e-5,
            1.0 / 3.0,
        ] {
            let s = text(x);
            let back: f64 = s.parse().unwrap();
            assert_eq!(back.to_bits(), x.to_bits(), "{x:e} written as {s}");
            assert!(s.len() <= 24, "{s}");
            assert!(!s.contains(','), "{s}");
        }
        assert_eq!(text(0.25), "0.25");
        assert_eq!(text(1e-17), "1e-17");
        assert_eq!(text(f64::NAN), "NaN");
        assert_eq!(text(f64::NEG_INFINITY), "-inf");
        assert_eq!(Value::Bool(true).to_string(), "true");
        assert_eq!(Value::Int(u64::MAX).to_string(), u64::MAX.to_string());
    }

    #[test]
    fn one_row_per_step_with_every_column() {
        let mut steps = vec![StepResult::default(); 3];
        steps[1].step = 1;
        steps[1].contact = true;
        steps[1].energy.residual = -1.25e-9;
        steps[2].step = 2;
        steps[2].peaks.contact_force = 123_456.5;
        let mut out = Vec::new();
        write_steps(&steps, &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 4);
        assert_eq!(lines[0], header());
        // Every field once by its name, the renamed ones again by their former names.
        assert!(lines.iter().all(|l| l.split(',').count() == COLUMNS.len() + STEP_RENAMES.len()));
        let row: Vec<&str> = lines[2].split(',').collect();
        let names = names();
        let at = |name: &str| names.iter().position(|c| *c == name).unwrap();
        assert_eq!(row[at("contact.active")], "true");
        assert_eq!(row[at("contact")], "true");
        assert_eq!(row[at("energy.residual")], "-1.25e-9");
        assert_eq!(lines[3].split(',').nth(at("peak.contact.force")).unwrap(), "123456.5");
        assert_eq!(lines[3].split(',').nth(at("peaks.contact_force")).unwrap(), "123456.5");
        let units = column_units();
        assert_eq!(units.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(), names);
        assert_eq!(units[at("peaks.contact_force")].1, "N");
    }
}
