//! The fatigue of a stress history, column by column (`beam-impact fatigue`): each column's
//! rainflow cycles and its design damage on one S-N curve with the designer's factors, as a
//! short table and as the `--json` document.

use serde::Serialize;

use super::history::StressHistory;
use super::miner::{damage, SnOptions};
use super::rainflow::count;
use super::sn_curve::SnCurve;

/// How the cycles are counted, as the document says.
pub const COUNTING: &str = "rainflow, ASTM E1049-85 (2017) Sec. 5.4.4: three-point rule with the starting point, \
                            the residue counted as half cycles";

/// How the damage is formed, as the document says.
pub const DAMAGE_RULE: &str = "Palmgren-Miner: DFF x sum count / N(range x SCF x (t/t_ref)^k), no cut-off";

/// One counted cycle as the document lists it (Pa).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CycleRow {
    /// Range, Pa.
    pub range: f64,
    /// Mean, Pa.
    pub mean: f64,
    /// 1 or 0.5.
    pub count: f64,
}

/// One stress column's fatigue.
#[derive(Clone, Debug, Serialize)]
pub struct ColumnFatigue {
    /// The column's name.
    pub name: String,
    /// Its number of reversals.
    pub reversals: usize,
    /// Its cycles, in the order counted (full cycles as they close, then the residue's halves).
    pub cycles: Vec<CycleRow>,
    /// Its design damage (with DFF).
    pub damage: f64,
}

/// The document of `beam-impact fatigue --json`.
#[derive(Clone, Debug, Serialize)]
pub struct HistoryFatigue {
    /// How the cycles are counted.
    pub counting: &'static str,
    /// How the damage is formed.
    pub damage_rule: &'static str,
    /// Data rows of the history.
    pub rows: usize,
    /// The S-N curve and its parameters.
    pub curve: SnCurve,
    /// The factors.
    pub options: SnOptions,
    /// Per stress column.
    pub columns: Vec<ColumnFatigue>,
}

impl HistoryFatigue {
    /// Counts and sums every column of `history` on `curve` with `options` (validated before).
    pub fn new(history: &StressHistory, curve: &SnCurve, options: &SnOptions) -> HistoryFatigue {
        let columns = history
            .names
            .iter()
            .zip(&history.columns)
            .map(|(name, tracker)| {
                let reversals = tracker.reversals();
                let cycles = count(&reversals);
                ColumnFatigue {
                    name: name.clone(),
                    reversals: reversals.len(),
                    damage: damage(&cycles, curve, options),
                    cycles: cycles.iter().map(|c| CycleRow { range: c.range, mean: c.mean, count: c.count }).collect(),
                }
            })
            .collect();
        HistoryFatigue {
            counting: COUNTING,
            damage_rule: DAMAGE_RULE,
            rows: history.rows,
            curve: curve.clone(),
            options: *options,
            columns,
        }
    }

    /// The printed table: the curve and the factors, then per column its cycles in MPa (at most
    /// `max_cycles`, the largest ranges first when cut) and its damage.
    pub fn table(&self, max_cycles: usize) -> String {
        let c = &self.curve;
        let mut text = format!("S-N curve {} ({}): m1 {}, log a1 {}", c.name, c.source, c.m1, c.log_a1);
        if let (Some(m2), Some(log_a2), Some(n)) = (c.m2, c.log_a2, c.n_switch) {
            text += &format!(", m2 {m2}, log a2 {log_a2}, slope change at {n:e} cycles");
        }
        text += &format!(", k {}, t_ref {} mm\n", c.thickness_exponent, c.reference_thickness_m * 1e3);
        let o = &self.options;
        let thickness = o.thickness_m.map_or_else(|| "none".to_string(), |t| format!("{} mm", t * 1e3));
        text += &format!(
            "SCF {}, thickness {thickness} (factor {:.4}), DFF {}; {DAMAGE_RULE}\ncounting: {COUNTING}\n",
            o.scf,
            c.thickness_factor(o.thickness_m),
            o.design_fatigue_factor
        );
        for column in &self.columns {
            let full = column.cycles.iter().filter(|c| c.count == 1.0).count();
            let half = column.cycles.len() - full;
            text += &format!(
                "\ncolumn {}: {} reversals, {full} full and {half} half cycles, damage {:.6e}\n",
                crate::model::motion_table::quote_cell(&column.name),
                column.reversals,
                column.damage
            );
            let mut shown: Vec<&CycleRow> = column.cycles.iter().collect();
            if shown.len() > max_cycles {
                shown.sort_by(|a, b| b.range.total_cmp(&a.range));
                shown.truncate(max_cycles);
                text +=
                    &format!("  the {max_cycles} largest ranges of {} cycles (all in --json):\n", column.cycles.len());
            }
            if !shown.is_empty() {
                text += &format!("  {:>14} {:>14} {:>5}\n", "range (MPa)", "mean (MPa)", "count");
            }
            for row in shown {
                text += &format!("  {:>14} {:>14} {:>5}\n", row.range / 1e6, row.mean / 1e6, row.count);
            }
        }
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_column_is_counted_and_summed_on_its_own() {
        let history = StressHistory::parse("time,a,b\n0,-2e6,0\n1,1e6,0\n2,-3e6,0\n3,5e6,0\n").unwrap();
        let d = SnCurve::by_name("D").unwrap();
        let doc = HistoryFatigue::new(&history, &d, &SnOptions::default());
        assert_eq!(doc.columns[0].reversals, 4);
        assert_eq!(doc.columns[1].reversals, 1);
        assert!(doc.columns[1].cycles.is_empty());
        assert_eq!(doc.columns[1].damage, 0.0);
        let expected: f64 = doc.columns[0].cycles.iter().map(|c| c.count / d.cycles_to_failure(c.range)).sum();
        assert_eq!(doc.columns[0].damage, expected);
    }
}
