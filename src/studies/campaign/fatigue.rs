//! A campaign's fatigue (issue 44 with issue 43): each event's Miner sum at its worst bending
//! station ([`crate::run_fatigue`], the sweep's `fatigue.damage`), its mean per cell (the damage
//! of one impact in that sea state), and with the sea states' occurrence the damage of a year
//! and the fatigue life.
//!
//! The year: `fatigue.events_per_year` impacts N, spread over the occurrence table's cells in
//! proportion to their probabilities p_c (normalised by their sum S: the impacts of a year happen
//! in the tabulated sea states, where the gangway is used); the damage of a year is
//! D = N sum_c (p_c / S) d_c with d_c the cell's mean damage per impact, and the life 1 / D
//! (Palmgren-Miner over the long-term distribution as a sum over sea states, DNV-RP-C203 (2016)
//! Sec. 2.3 and 5.1: D = sum n_i / N_i). Each event's damage is its worst station's; the worst
//! station may differ from event to event, so the sum is an upper bound on any one station's
//! damage (conservative).
//!
//! The occurrence table is CSV text a user brings: the columns `significant_wave_height` (m),
//! `peak_period` (s), optionally `heading` (deg), and one of `probability` (each in [0, 1], the sum
//! at most 1) or `hours` (a year's, each in [0, 8766], the sum at most 8766 = 365.25 x 24). Every
//! row must be a cell of the campaign's grid (its values equal to a relative 1e-9: a grid value
//! is written to 15 significant digits); a cell the table does not list has no weight. Parsed
//! from text, bounded ([`MAX_TABLE_BYTES`], [`MAX_TABLE_ROWS`]); every error one line naming the
//! line and column.

use crate::run_fatigue::years;
use serde::Serialize;

use crate::error::{Error, Result};
use crate::model::motion_table::quote_cell;

/// Largest occurrence table the CLI reads, bytes (a scatter diagram of 100 x 100 x 36 cells is
/// under 10 MB; 16 MiB leaves room for comments).
pub const MAX_TABLE_BYTES: u64 = 16 << 20;

/// Most rows of an occurrence table (no campaign's grid has more cells than runs:
/// [`super::DEFAULT_MAX_EVENTS`] runs of one event each at most, raised by `--max-events`).
pub const MAX_TABLE_ROWS: usize = 1_000_000;

/// Hours of a year: 365.25 x 24 (a Julian year, as the RP's design lives count years).
pub const HOURS_PER_YEAR: f64 = 8766.0;

/// The tolerance on a probability sum, and on matching a row's values to the grid's (relative).
pub const TOLERANCE: f64 = 1e-9;

/// How the table gives its weights.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Weight {
    /// A probability per sea state.
    Probability,
    /// Hours a year per sea state.
    Hours,
}

/// One row of the table.
#[derive(Clone, Debug, PartialEq)]
pub struct OccurrenceRow {
    /// Its line in the text (1-based).
    pub line: usize,
    /// Hs, m.
    pub significant_wave_height: f64,
    /// Tp, s.
    pub peak_period: f64,
    /// The heading, deg (None: the table has no heading column).
    pub heading: Option<f64>,
    /// Its probability: as given, or hours / [`HOURS_PER_YEAR`].
    pub probability: f64,
}

/// A parsed, checked occurrence table.
#[derive(Clone, Debug, PartialEq)]
pub struct Occurrence {
    /// How the weights were given.
    pub weight: Weight,
    /// Whether the table has a heading column.
    pub has_heading: bool,
    /// The rows in the text's order.
    pub rows: Vec<OccurrenceRow>,
}

const HS: &str = "significant_wave_height";
const TP: &str = "peak_period";
const HEADING: &str = "heading";
const PROBABILITY: &str = "probability";
const HOURS: &str = "hours";

fn table_error(text: String) -> Error {
    Error::Other(format!("occurrence table: {text}"))
}

impl Occurrence {
    /// Parses the table's text: a header naming the columns (any order; `#` comments and blank
    /// lines skipped), then one row per sea state.
    pub fn parse(text: &str) -> Result<Occurrence> {
        let mut lines = crate::fatigue::history::data_lines(text);
        let cells = |line: &str| -> Vec<String> { crate::fatigue::history::cells(line).map(String::from).collect() };
        let (header_line, header) = lines.next().ok_or_else(|| {
            table_error(format!("no header line (the columns {HS}, {TP}, [{HEADING},] {PROBABILITY} or {HOURS})"))
        })?;
        let names = cells(header);
        for (i, name) in names.iter().enumerate() {
            if ![HS, TP, HEADING, PROBABILITY, HOURS].contains(&name.as_str()) {
                return Err(table_error(format!(
                    "line {header_line}: unknown column `{}` (the columns are {HS}, {TP}, [{HEADING},] {PROBABILITY} \
                     or {HOURS})",
                    quote_cell(name)
                )));
            }
            if names[..i].contains(name) {
                return Err(table_error(format!("line {header_line}: column `{name}` appears twice")));
            }
        }
        let at = |n: &str| names.iter().position(|c| c == n);
        let (Some(hs), Some(tp)) = (at(HS), at(TP)) else {
            return Err(table_error(format!("line {header_line}: the header needs the columns {HS} and {TP}")));
        };
        let heading = at(HEADING);
        let (weight, w) = match (at(PROBABILITY), at(HOURS)) {
            (Some(p), None) => (Weight::Probability, p),
            (None, Some(h)) => (Weight::Hours, h),
            _ => {
                return Err(table_error(format!(
                    "line {header_line}: the header needs one of the columns {PROBABILITY} and {HOURS}"
                )))
            }
        };
        let mut rows = Vec::new();
        for (line, text) in lines {
            if rows.len() == MAX_TABLE_ROWS {
                return Err(table_error(format!("more than {MAX_TABLE_ROWS} rows")));
            }
            let row = cells(text);
            if row.len() != names.len() {
                return Err(table_error(format!(
                    "line {line}: {} cells, the header has {} columns",
                    row.len(),
                    names.len()
                )));
            }
            let number = |k: usize| -> Result<f64> {
                row[k].parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| {
                    table_error(format!(
                        "line {line}: {} must be a finite number, got `{}`",
                        names[k],
                        quote_cell(&row[k])
                    ))
                })
            };
            let (h, t) = (number(hs)?, number(tp)?);
            for (k, v) in [(hs, h), (tp, t)] {
                if v <= 0.0 {
                    return Err(table_error(format!("line {line}: {} must be > 0, got {v}", names[k])));
                }
            }
            let heading = heading.map(number).transpose()?;
            let given = number(w)?;
            let probability = match weight {
                Weight::Probability if (0.0..=1.0).contains(&given) => given,
                Weight::Hours if (0.0..=HOURS_PER_YEAR).contains(&given) => given / HOURS_PER_YEAR,
                Weight::Probability => {
                    return Err(table_error(format!("line {line}: probability must be in [0, 1], got {given}")))
                }
                Weight::Hours => {
                    return Err(table_error(format!(
                        "line {line}: hours must be in [0, {HOURS_PER_YEAR}] (a year's), got {given}"
                    )))
                }
            };
            rows.push(OccurrenceRow { line, significant_wave_height: h, peak_period: t, heading, probability });
        }
        if rows.is_empty() {
            return Err(table_error("no row after the header".into()));
        }
        let sum: f64 = rows.iter().map(|r| r.probability).sum();
        if sum > 1.0 + TOLERANCE {
            return Err(table_error(match weight {
                Weight::Probability => format!("the probabilities sum to {sum}, more than 1"),
                Weight::Hours => {
                    format!("the hours sum to {}, more than a year's {HOURS_PER_YEAR}", sum * HOURS_PER_YEAR)
                }
            }));
        }
        if sum <= 0.0 {
            return Err(table_error("every weight is 0: no sea state to spread the impacts over".into()));
        }
        Ok(Occurrence { weight, has_heading: heading.is_some(), rows })
    }

    /// Each cell's probability (in the order of `cells`, each `[Hs, Tp, heading]`): the table's
    /// row of that cell, 0 where it has none. `varies_heading`: the grid varies the heading (the
    /// table then needs a heading column). Errors: a row that is no cell, two rows of one cell.
    pub fn weights(&self, cells: &[[f64; 3]], varies_heading: bool) -> Result<Vec<f64>> {
        if varies_heading && !self.has_heading {
            return Err(table_error("the campaign's grid varies sea.heading: the table needs a heading column".into()));
        }
        if self.rows.len() > cells.len() {
            return Err(table_error(format!(
                "{} rows for the campaign's {} cells: each row is one cell of the grid",
                self.rows.len(),
                cells.len()
            )));
        }
        let same = |a: f64, b: f64| (a - b).abs() <= TOLERANCE * a.abs().max(b.abs()).max(1.0);
        let matches = |c: &[f64; 3], row: &OccurrenceRow| {
            same(c[0], row.significant_wave_height)
                && same(c[1], row.peak_period)
                && row.heading.is_none_or(|h| same(c[2], h))
        };
        // The cells by their exact (Hs, Tp): a row written as the grid's values finds its cell
        // at once; one within the tolerance but not equal is looked for among all the cells.
        let bits = |x: f64| (x + 0.0).to_bits();
        let mut exact: std::collections::HashMap<(u64, u64), Vec<usize>> = std::collections::HashMap::new();
        for (k, c) in cells.iter().enumerate() {
            exact.entry((bits(c[0]), bits(c[1]))).or_default().push(k);
        }
        let mut weights = vec![0.0; cells.len()];
        let mut row_of: Vec<Option<usize>> = vec![None; cells.len()];
        for row in &self.rows {
            let found = exact
                .get(&(bits(row.significant_wave_height), bits(row.peak_period)))
                .and_then(|ks| ks.iter().copied().find(|&k| matches(&cells[k], row)))
                .or_else(|| cells.iter().position(|c| matches(c, row)));
            let Some(c) = found else {
                let heading = row.heading.map_or_else(String::new, |h| format!(", heading {h} deg"));
                return Err(table_error(format!(
                    "line {}: Hs {} m, Tp {} s{heading} is not a cell of the campaign's grid",
                    row.line, row.significant_wave_height, row.peak_period
                )));
            };
            if let Some(first) = row_of[c] {
                return Err(table_error(format!("lines {first} and {}: the same cell twice", row.line)));
            }
            row_of[c] = Some(row.line);
            weights[c] = row.probability;
        }
        Ok(weights)
    }
}

/// One cell's fatigue.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CellFatigue {
    /// Hs, m.
    pub significant_wave_height: f64,
    /// Tp, s.
    pub peak_period: f64,
    /// The heading, deg.
    pub heading: f64,
    /// Events with a damage (their runs ran).
    pub events: usize,
    /// Events whose runs failed (no damage).
    pub failed: usize,
    /// The mean damage per event (None: no event ran: refused, or interrupted before).
    pub mean_damage: Option<f64>,
    /// The largest damage of one event.
    pub largest_damage: Option<f64>,
    /// The cell's probability in the occurrence table (None: no table).
    pub probability: Option<f64>,
}

/// A campaign's fatigue: per cell, and weighted over the sea states.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CampaignFatigue {
    /// The S-N curve and factors, as `[fatigue]` gives them.
    pub curve: String,
    /// The stress concentration factor.
    pub scf: f64,
    /// The design fatigue factor.
    pub design_fatigue_factor: f64,
    /// The detail's thickness, m (None: no correction).
    pub thickness: Option<f64>,
    /// What an event's damage is.
    pub damage: &'static str,
    /// Each cell, in the grid's order.
    pub cells: Vec<CellFatigue>,
    /// The occurrence table's weights: `probability` or `hours` (None: no table).
    pub occurrence: Option<Weight>,
    /// The table's probabilities' sum S (hours / 8766).
    pub probability_sum: Option<f64>,
    /// The probability of the cells the table weights but that have no damage (refused, or no
    /// event ran): the weighted damage leaves them out.
    pub probability_without_damage: Option<f64>,
    /// sum_c (p_c / S) d_c: the damage of one impact, weighted over the sea states.
    pub damage_per_event: Option<f64>,
    /// Impacts a year (`fatigue.events_per_year`).
    pub events_per_year: Option<f64>,
    /// N x damage_per_event.
    pub damage_per_year: Option<f64>,
    /// 1 / damage_per_year, years.
    pub life_years: Option<f64>,
}

/// What an event's damage is, as the JSON states it.
pub const DAMAGE_MEANING: &str = "Miner's sum of one event at its worst bending station (the worst station may differ \
                                  between events: an upper bound on any one station's)";

/// The campaign's fatigue from each cell's sea state (`[Hs, Tp, heading]`), its events' damages
/// (`damages[c]`: one per event that ran) and failed events, the scenario's `[fatigue]` settings
/// and, if given, the occurrence table (`varies_heading`: the grid varies the heading).
pub fn assess(
    cells: &[[f64; 3]],
    damages: &[Vec<f64>],
    failed: &[usize],
    settings: &crate::model::fatigue_settings::FatigueSettings,
    occurrence: Option<&Occurrence>,
    varies_heading: bool,
) -> Result<CampaignFatigue> {
    let weights = occurrence.map(|o| o.weights(cells, varies_heading)).transpose()?;
    let cell_fatigue: Vec<CellFatigue> = cells
        .iter()
        .enumerate()
        .map(|(c, sea)| {
            let d = damages.get(c).map_or(&[][..], Vec::as_slice);
            CellFatigue {
                significant_wave_height: sea[0],
                peak_period: sea[1],
                heading: sea[2],
                events: d.len(),
                failed: failed.get(c).copied().unwrap_or(0),
                mean_damage: (!d.is_empty()).then(|| d.iter().sum::<f64>() / d.len() as f64),
                largest_damage: d.iter().copied().reduce(f64::max),
                probability: weights.as_ref().map(|w| w[c]),
            }
        })
        .collect();
    let (mut sum, mut without, mut weighted) = (None, None, None);
    if let Some(w) = &weights {
        let s: f64 = w.iter().sum();
        // `+ 0.0`: an empty sum is -0.0.
        let missing: f64 =
            cell_fatigue.iter().zip(w).filter(|(c, _)| c.mean_damage.is_none()).map(|(_, p)| p).sum::<f64>() + 0.0;
        let d: f64 = cell_fatigue.iter().zip(w).filter_map(|(c, p)| c.mean_damage.map(|d| p / s * d)).sum();
        (sum, without, weighted) = (Some(s), Some(missing), (s > 0.0).then_some(d));
    }
    let per_year = weighted.zip(settings.events_per_year).map(|(d, n)| d * n);
    Ok(CampaignFatigue {
        curve: settings.curve.clone(),
        scf: settings.scf,
        design_fatigue_factor: settings.design_fatigue_factor,
        thickness: settings.thickness,
        damage: DAMAGE_MEANING,
        cells: cell_fatigue,
        occurrence: occurrence.map(|o| o.weight),
        probability_sum: sum,
        probability_without_damage: without,
        damage_per_event: weighted,
        events_per_year: settings.events_per_year,
        damage_per_year: per_year,
        life_years: per_year.filter(|d| *d > 0.0).map(|d| 1.0 / d).filter(|l| l.is_finite()),
    })
}

impl CampaignFatigue {
    /// The lines the campaign prints: per cell its mean and largest damage (and probability),
    /// then the weighted damage, the year's and the life.
    pub fn text(&self, names: &[String]) -> String {
        let mut out = format!(
            "fatigue ({}, SCF {}, DFF {}{}; each event's worst station):\n",
            self.curve,
            self.scf,
            self.design_fatigue_factor,
            self.thickness.map_or_else(String::new, |t| format!(", t {t} m"))
        );
        for (cell, name) in self.cells.iter().zip(names) {
            let damage = match (cell.mean_damage, cell.largest_damage) {
                (Some(m), Some(l)) => {
                    format!("mean damage {m:.4e} per event, largest {l:.4e} ({} events)", cell.events)
                }
                _ => "no event ran".to_string(),
            };
            let failed = if cell.failed > 0 { format!(", {} failed", cell.failed) } else { String::new() };
            let p = cell.probability.map_or_else(String::new, |p| format!("; probability {p:.6}"));
            out += &format!("  {name}: {damage}{failed}{p}\n");
        }
        if let (Some(d), Some(s)) = (self.damage_per_event, self.probability_sum) {
            out += &format!(
                "  weighted over the occurrence table (its {} sum to {:.6}; weights p / sum): damage {d:.4e} per \
                 event\n",
                if self.occurrence == Some(Weight::Hours) { "hours / 8766" } else { "probabilities" },
                s
            );
            if let Some(m) = self.probability_without_damage.filter(|m| *m > 0.0) {
                out +=
                    &format!("  warning: cells of probability {m:.6} have no damage (refused or not run): left out\n");
            }
            out += &match (self.damage_per_year, self.life_years, self.events_per_year) {
                (Some(y), Some(l), Some(n)) => {
                    format!("  at {n} impacts a year: damage {y:.4e} a year, fatigue life {} years\n", years(l))
                }
                (Some(_), None, Some(n)) => format!("  at {n} impacts a year: no damage, life unbounded\n"),
                _ => "  fatigue life: give fatigue.events_per_year (--set fatigue.events_per_year=N)\n".to_string(),
            };
        } else {
            out += "  damage a year: give the sea states' occurrence (--occurrence FILE.csv)\n";
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two cells of damages 1e-6 and 3e-6 weighted 0.2 and 0.6 (sum 0.8): the damage per event is
    /// (0.2 x 1e-6 + 0.6 x 3e-6) / 0.8 = 2.5e-6, a year at 1000 impacts 2.5e-3, the life 400
    /// years. Relative 1e-12: a few sums and products.
    #[test]
    fn weighted_damage_is_the_normalised_sum_over_the_cells() {
        let table = Occurrence::parse("significant_wave_height,peak_period,probability\n1,6,0.2\n2,8,0.6\n").unwrap();
        let cells = [[1.0, 6.0, 0.0], [2.0, 8.0, 0.0], [3.0, 8.0, 0.0]];
        let settings =
            crate::model::fatigue_settings::FatigueSettings { events_per_year: Some(1000.0), ..Default::default() };
        let damages = vec![vec![0.5e-6, 1.5e-6], vec![3e-6], vec![9.0]];
        let f = assess(&cells, &damages, &[0, 0, 1], &settings, Some(&table), false).unwrap();
        let close = |a: Option<f64>, b: f64| (a.unwrap() / b - 1.0).abs() < 1e-12;
        assert!(close(f.damage_per_event, 2.5e-6), "{:?}", f.damage_per_event);
        assert!(close(f.damage_per_year, 2.5e-3));
        assert!(close(f.life_years, 400.0));
        assert_eq!(f.cells[2].probability, Some(0.0));
        assert_eq!(f.cells[2].failed, 1);
        // Hours: the same shares.
        let hours = Occurrence::parse("peak_period,significant_wave_height,hours\n6,1,1753.2\n8,2,5259.6\n").unwrap();
        let g = assess(&cells, &damages, &[0, 0, 0], &settings, Some(&hours), false).unwrap();
        assert!(close(g.damage_per_event, 2.5e-6), "{:?}", g.damage_per_event);
    }

    /// Bad tables: one line each, naming the line or the column.
    #[test]
    fn bad_tables_are_one_line_errors() {
        let cells = [[1.0, 6.0, 0.0], [1.0, 6.0, 30.0]];
        for (text, needle) in [
            ("", "no header line"),
            ("significant_wave_height,peak_period\n", "one of the columns probability and hours"),
            ("significant_wave_height,peak_period,probability,hours\n1,6,1,1\n", "one of the columns"),
            ("significant_wave_height,peak_period,probability,wind\n", "unknown column `wind`"),
            ("significant_wave_height,peak_period,probability\n1,6,1.5\n", "line 2: probability must be in [0, 1]"),
            ("significant_wave_height,peak_period,probability\n1,6,NaN\n", "must be a finite number"),
            ("significant_wave_height,peak_period,probability\n1,6,0.6\n1,8,0.6\n", "sum to 1.2"),
            ("significant_wave_height,peak_period,hours\n1,6,9000\n", "hours must be in [0, 8766]"),
            ("significant_wave_height,peak_period,probability\n1,6\n", "line 2: 2 cells"),
            ("significant_wave_height,peak_period,probability\n1,6,0\n", "every weight is 0"),
            ("significant_wave_height,peak_period,probability\n-1,6,0.1\n", "must be > 0"),
        ] {
            let e = Occurrence::parse(text).unwrap_err().to_string();
            assert!(e.contains(needle), "{text:?}: {e}");
            assert_eq!(e.lines().count(), 1, "{e}");
        }
        let no_heading = Occurrence::parse("significant_wave_height,peak_period,probability\n1,6,0.5\n").unwrap();
        let e = no_heading.weights(&cells, true).unwrap_err().to_string();
        assert!(e.contains("needs a heading column"), "{e}");
        let off = Occurrence::parse("significant_wave_height,peak_period,probability\n1.5,6,0.5\n").unwrap();
        let e = off.weights(&cells[..1], false).unwrap_err().to_string();
        assert!(e.contains("line 2: Hs 1.5 m, Tp 6 s is not a cell"), "{e}");
        let twice =
            Occurrence::parse("significant_wave_height,peak_period,probability\n1,6,0.2\n1.0000000000001,6,0.2\n")
                .unwrap();
        let e = twice.weights(&cells, false).unwrap_err().to_string();
        assert!(e.contains("lines 2 and 3: the same cell twice"), "{e}");
        let e = twice.weights(&cells[..1], false).unwrap_err().to_string();
        assert!(e.contains("2 rows for the campaign's 1 cells"), "{e}");
    }
}
