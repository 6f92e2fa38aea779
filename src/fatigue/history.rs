//! A stress history a user brings (`beam-impact fatigue HISTORY.csv`): CSV text with a `time`
//! column (s, finite, strictly increasing) and one or more stress columns (Pa). Parsed from text
//! (the CLI reads the file, bounded): no I/O here. Each stress column is followed through a
//! [`ReversalTracker`], so only its turning points are kept.
//!
//! The format is the motion file's (`run --motion`): comma separated, the first line that is not
//! blank or a `#` comment is the header, names and cells trimmed of spaces and double quotes. An
//! error is one line naming the row, its line and the column, the cell quoted and cut
//! ([`quote_cell`]).

use super::rainflow::ReversalTracker;
use crate::model::motion_table::quote_cell;

/// Largest history file the CLI reads, bytes (as a motion file: 256 MiB).
pub const MAX_HISTORY_BYTES: u64 = 256 << 20;

/// Largest number of data rows (10^7: three hours at 1 ms).
pub const MAX_ROWS: usize = 10_000_000;

/// Largest number of stress columns.
pub const MAX_COLUMNS: usize = 1000;

/// Largest magnitude of a stress, Pa: 1e12 Pa (1 TPa) is three orders above any steel's
/// strength, and keeps every range and mean finite (a range of two 1e308 stresses is infinite).
pub const MAX_STRESS_PA: f64 = 1e12;

/// The name of the time column.
pub const TIME: &str = "time";

/// A parsed, checked stress history: per stress column its turning points.
#[derive(Clone, Debug)]
pub struct StressHistory {
    /// The stress columns' names, in the file's order (the time column left out).
    pub names: Vec<String>,
    /// Data rows read.
    pub rows: usize,
    /// First and last time, s.
    pub time_span: (f64, f64),
    /// Each stress column's reversals, in the order of `names`.
    pub columns: Vec<ReversalTracker>,
}

/// A header or data line's cells, trimmed of spaces and double quotes.
pub fn cells(line: &str) -> impl Iterator<Item = &str> {
    line.split(',').map(|c| c.trim().trim_matches('"').trim())
}

/// A CSV text's lines that hold cells, numbered from 1 and trimmed: a leading byte-order mark
/// dropped, blank lines and `#` comments skipped (the stress histories' and the campaign's
/// occurrence tables' one reading).
pub fn data_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    text.lines().enumerate().map(|(i, l)| (i + 1, l.trim())).filter(|(_, l)| !l.is_empty() && !l.starts_with('#'))
}

impl StressHistory {
    /// Parses CSV text; the error is one line naming the row, the line and the column.
    pub fn parse(text: &str) -> Result<StressHistory, String> {
        let mut lines = data_lines(text);
        let (header_line, header) = lines.next().ok_or("no header line (a `time` column and stress columns in Pa)")?;
        let names: Vec<&str> = cells(header).collect();
        let time_at = names.iter().position(|n| *n == TIME).ok_or_else(|| {
            format!(
                "line {header_line} is not a stress-history header: it has no `{TIME}` column \
                 (expected `{TIME}` and one or more stress columns, Pa)"
            )
        })?;
        for (i, name) in names.iter().enumerate() {
            if name.is_empty() {
                return Err(format!("line {header_line}: column {} of the header has no name", i + 1));
            }
            if let Some(j) = names[..i].iter().position(|n| n == name) {
                return Err(format!(
                    "line {header_line}: column `{}` appears twice (columns {} and {})",
                    quote_cell(name),
                    j + 1,
                    i + 1
                ));
            }
        }
        if names.len() < 2 {
            return Err(format!("line {header_line}: no stress column beside `{TIME}` (stress columns in Pa)"));
        }
        if names.len() - 1 > MAX_COLUMNS {
            return Err(format!(
                "line {header_line}: {} stress columns, more than {MAX_COLUMNS} (the limit)",
                names.len() - 1
            ));
        }
        let stress_names: Vec<String> =
            names.iter().enumerate().filter(|(i, _)| *i != time_at).map(|(_, n)| n.to_string()).collect();
        let mut columns = vec![ReversalTracker::new(); stress_names.len()];
        let mut rows = 0usize;
        let mut span = (f64::NAN, f64::NAN);
        let mut values = Vec::with_capacity(names.len());
        for (line, text) in lines {
            rows += 1;
            let row = rows;
            if row > MAX_ROWS {
                return Err(format!("more than {MAX_ROWS} data rows (the limit), at line {line}"));
            }
            values.clear();
            for (i, cell) in cells(text).enumerate() {
                if i >= names.len() {
                    break;
                }
                let name = names[i];
                let value: f64 = cell.parse().map_err(|_| {
                    format!(
                        "row {row} (line {line}), column `{}`: `{}` is not a number",
                        quote_cell(name),
                        quote_cell(cell)
                    )
                })?;
                if !value.is_finite() {
                    return Err(format!(
                        "row {row} (line {line}), column `{}`: {value} is not a finite number",
                        quote_cell(name)
                    ));
                }
                if i != time_at && value.abs() > MAX_STRESS_PA {
                    return Err(format!(
                        "row {row} (line {line}), column `{}`: {value} Pa is beyond +-{MAX_STRESS_PA:e} Pa \
                         (stresses are in Pa)",
                        quote_cell(name)
                    ));
                }
                values.push(value);
            }
            let found = cells(text).count();
            if found != names.len() {
                return Err(format!("row {row} (line {line}) has {found} cells, the header {}", names.len()));
            }
            let t = values[time_at];
            if row == 1 {
                span.0 = t;
            } else if t <= span.1 {
                return Err(format!(
                    "row {row} (line {line}): time {t} s is not after the row before's {} s (time must increase)",
                    span.1
                ));
            }
            span.1 = t;
            let stresses = values.iter().enumerate().filter(|(i, _)| *i != time_at).map(|(_, v)| *v);
            for (tracker, v) in columns.iter_mut().zip(stresses) {
                // Finite: checked above.
                let _ = tracker.push(v);
            }
        }
        if rows == 0 {
            return Err(format!("no data rows after the header (line {header_line})"));
        }
        Ok(StressHistory { names: stress_names, rows, time_span: span, columns })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_history_keeps_each_column_s_reversals() {
        let h = StressHistory::parse("# a comment\ntime, a ,\"b\"\n0,0,5\n1,2,5\n\n2,1,6\n3,3,4\n").unwrap();
        assert_eq!(h.names, ["a", "b"]);
        assert_eq!((h.rows, h.time_span), (4, (0.0, 3.0)));
        assert_eq!(h.columns[0].reversals(), [0.0, 2.0, 1.0, 3.0]);
        assert_eq!(h.columns[1].reversals(), [5.0, 6.0, 4.0]);
    }

    #[test]
    fn bad_input_is_one_line_naming_row_line_and_column() {
        let e = |text: &str| StressHistory::parse(text).unwrap_err();
        assert!(e("").starts_with("no header line"));
        assert!(e("t,s\n0,1\n").starts_with("line 1 is not a stress-history header"));
        assert_eq!(e("time\n0\n"), "line 1: no stress column beside `time` (stress columns in Pa)");
        assert_eq!(e("time,s,s\n"), "line 1: column `s` appears twice (columns 2 and 3)");
        assert_eq!(e("time,s\n0,1\n1,x\n"), "row 2 (line 3), column `s`: `x` is not a number");
        assert_eq!(e("time,s\n0,NaN\n"), "row 1 (line 2), column `s`: NaN is not a finite number");
        assert_eq!(e("time,s\n0,1,2\n"), "row 1 (line 2) has 3 cells, the header 2");
        assert_eq!(
            e("time,s\n0,1\n0,2\n"),
            "row 2 (line 3): time 0 s is not after the row before's 0 s (time must increase)"
        );
        assert_eq!(e("time,s\n"), "no data rows after the header (line 1)");
        assert!(e("time,s\n0,1e300\n").contains("beyond +-1e12 Pa"));
        let wide = format!("time{}\n", (0..=MAX_COLUMNS).map(|i| format!(",s{i}")).collect::<String>());
        assert_eq!(e(&wide), "line 1: 1001 stress columns, more than 1000 (the limit)");
    }
}
