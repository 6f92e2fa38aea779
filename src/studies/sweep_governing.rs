//! What `beam-impact sweep` prints beside its rows (issue 44): for a scenario with
//! `[[load_cases]]`, per design quantity the load case and the row with the largest factored
//! utilisation over the whole grid (each row's governing case is the largest over its cases,
//! [`crate::load_cases::judge`]; over the grid the largest of those, the first row on a tie); with
//! `--fatigue`, the row of the largest damage per impact.
//!
//! Pure numbers and text: the rows come from [`crate::studies::sweep::Sweep::write_observed`] in
//! grid order, so a row's number is its line in the CSV after the header (1 = the first row).

use crate::model::Scenario;
use crate::run_fatigue::years;
use crate::studies::sweep::{format_value, Axis, Row, RowFatigue, GOVERNING_QUANTITIES};

/// The row where a quantity's largest factored utilisation over the grid sits.
#[derive(Clone, Debug, PartialEq)]
pub struct GoverningRow {
    /// The design quantity ([`GOVERNING_QUANTITIES`]).
    pub quantity: &'static str,
    /// The governing case's name.
    pub case: String,
    /// Its factored utilisation there.
    pub utilisation: f64,
    /// The row: 1 for the CSV's first row, in grid order.
    pub row: usize,
    /// The row's varied values, in the axes' order (parameter form).
    pub values: Vec<f64>,
}

/// The row of the largest fatigue damage per impact.
#[derive(Clone, Debug, PartialEq)]
pub struct FatigueRow {
    /// The row, 1 for the CSV's first.
    pub row: usize,
    /// Its varied values.
    pub values: Vec<f64>,
    /// Its fatigue.
    pub fatigue: RowFatigue,
}

/// The rows seen so far and what they govern.
#[derive(Clone, Debug, Default)]
pub struct SweepSummary {
    /// The scenario's load cases' names, in its order (the rows hold their indices).
    cases: Vec<String>,
    /// Per quantity of [`GOVERNING_QUANTITIES`], the governing row so far.
    governing: Vec<Option<GoverningRow>>,
    /// The worst fatigue row so far.
    fatigue: Option<FatigueRow>,
    /// Rows seen.
    rows: usize,
}

impl SweepSummary {
    /// An empty summary for a sweep of `base` (its load cases name the rows' governing cases).
    pub fn new(base: &Scenario) -> SweepSummary {
        SweepSummary {
            cases: base.load_cases.iter().map(|c| c.name.clone()).collect(),
            governing: vec![None; GOVERNING_QUANTITIES.len()],
            fatigue: None,
            rows: 0,
        }
    }

    /// Takes the next row in grid order (a failed row counts as a row, with nothing to govern).
    pub fn observe(&mut self, row: &Row) {
        self.rows += 1;
        let Ok(results) = &row.outcome else { return };
        for (k, g) in results.governing.iter().enumerate() {
            let Some((case, utilisation)) = *g else { continue };
            let Some(name) = self.cases.get(case) else { continue };
            // Strictly larger replaces: the first row keeps a tie; a NaN never governs.
            let larger = match &self.governing[k] {
                None => !utilisation.is_nan(),
                Some(best) => utilisation > best.utilisation,
            };
            if larger {
                self.governing[k] = Some(GoverningRow {
                    quantity: GOVERNING_QUANTITIES[k],
                    case: name.clone(),
                    utilisation,
                    row: self.rows,
                    values: row.values.clone(),
                });
            }
        }
        if let Some(f) = results.fatigue {
            let larger = self.fatigue.as_ref().map_or(!f.damage.is_nan(), |w| f.damage > w.fatigue.damage);
            if larger {
                self.fatigue = Some(FatigueRow { row: self.rows, values: row.values.clone(), fatigue: f });
            }
        }
    }

    /// Each quantity's governing row over the rows seen (those with an allowable and a case).
    pub fn governing(&self) -> Vec<&GoverningRow> {
        self.governing.iter().flatten().collect()
    }

    /// The row of the largest damage per impact, if the rows have fatigue.
    pub fn fatigue(&self) -> Option<&FatigueRow> {
        self.fatigue.as_ref()
    }

    /// The printed lines (empty without load cases and fatigue): per quantity its governing case,
    /// row (with the varied values) and factored utilisation with its verdict; the worst fatigue
    /// row.
    pub fn text(&self, axes: &[Axis]) -> String {
        let at = |row: usize, values: &[f64]| {
            let named: Vec<String> = axes
                .iter()
                .zip(values)
                .map(|(a, &v)| format!("{}={}", a.field.name, format_value(a.field, v)))
                .collect();
            if named.is_empty() {
                format!("row {row}")
            } else {
                format!("row {row} ({})", named.join(", "))
            }
        };
        let mut out = String::new();
        let governing = self.governing();
        if !governing.is_empty() {
            out += &format!(
                "governing load case per quantity (the largest factored utilisation over {} rows):\n",
                self.rows
            );
            let width = governing.iter().map(|g| g.quantity.len()).max().unwrap_or(0);
            for g in governing {
                out += &format!(
                    "  {:<width$}  \"{}\" at {}: {:.3} {}\n",
                    g.quantity,
                    printable(&g.case),
                    at(g.row, &g.values),
                    g.utilisation,
                    if g.utilisation <= 1.0 { "PASS" } else { "FAIL" }
                );
            }
        }
        if let Some(w) = &self.fatigue {
            let f = &w.fatigue;
            let beam = if f.beam == "upper" { "bridge" } else { "arrestor" };
            let life = f.life.map_or_else(
                || "no life (give fatigue.events_per_year)".to_string(),
                |l| format!("life {} years at fatigue.events_per_year", years(l)),
            );
            out += &format!(
                "fatigue: the largest damage per impact {:.4e} at {}, the {beam}'s station at {} m; {life}\n",
                f.damage,
                at(w.row, &w.values),
                f.position
            );
        }
        out
    }
}

/// A case's name as printed: control characters escaped, cut as the load cases' own lines
/// ([`crate::model::load_case::MAX_NAME_CHARS`]).
fn printable(name: &str) -> String {
    let cut: String = name.chars().take(crate::model::load_case::MAX_NAME_CHARS).collect();
    cut.chars().flat_map(|c| if c.is_control() { c.escape_default().collect::<Vec<_>>() } else { vec![c] }).collect()
}
