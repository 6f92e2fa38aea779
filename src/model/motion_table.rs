//! A support-motion time series (`run --motion FILE.csv`, the scenario's `[motion]`): rows of
//! `time` and any of the nine support-motion names, each support's three given together. Between
//! rows each support moves as z_n + v_n tau + a_n tau^2 / 2 from the row before, as an FMU's inputs
//! do between communication points. Parsed from text (the CLI reads the file): no I/O here. A
//! `wave_elevation` column (`beam-impact sea`'s files, issue 42) is read as a number and left out.

use super::support_motion::{check_motion_value, MotionMismatch, SupportMotion, MOTION_NAMES};

/// Largest number of rows a motion file may hold (10^7 rows: 3 hours at 1 ms).
pub const MAX_ROWS: usize = 10_000_000;

/// Most characters of a cell an error quotes (issue 27: an error quotes the offending cell, cut,
/// never a line of a file that is not a motion CSV).
pub const MAX_QUOTED: usize = 200;

/// `cell` as an error quotes it: at most [`MAX_QUOTED`] characters as shown, control characters
/// escaped (`\u{1b}`, counted as shown), with the count of the cell's characters cut.
pub fn quote_cell(cell: &str) -> String {
    let mut out = String::new();
    let (mut shown, mut taken) = (0, 0);
    for c in cell.chars() {
        let piece: String = if c.is_control() { c.escape_default().collect() } else { c.to_string() };
        let width = piece.chars().count();
        if shown + width > MAX_QUOTED {
            break;
        }
        out.push_str(&piece);
        shown += width;
        taken += 1;
    }
    let total = cell.chars().count();
    if taken < total {
        out.push_str(&format!("... ({} characters cut)", total - taken));
    }
    out
}

/// A column a motion file may carry beside the support motion and that the run does not use: the
/// wave elevation at the vessel's motion reference point, m, as `beam-impact sea` writes it.
pub const WAVE_ELEVATION: &str = "wave_elevation";

/// A parsed, checked support-motion time series.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionTable {
    /// The support-motion columns present, in the file's order (names of [`MOTION_NAMES`]).
    pub columns: Vec<&'static str>,
    /// Row times, s, strictly increasing.
    pub times: Vec<f64>,
    /// The motion of each row (absent columns zero).
    pub motions: Vec<SupportMotion>,
}

/// A row that disagrees with the motion of the row before it.
#[derive(Clone, Debug, PartialEq)]
pub struct RowMismatch {
    /// Row number (1 = the first data row; the header is line 1, so the row is on line row + 1).
    pub row: usize,
    /// What disagrees.
    pub mismatch: MotionMismatch,
}

/// The error of a first line that is not a motion header (nothing of it quoted).
fn not_a_header(line: usize) -> String {
    format!(
        "line {line} is not a motion-file header: it has no `time` column (expected `time` and any of {})",
        MOTION_NAMES.join(", ")
    )
}

impl MotionTable {
    /// Parses CSV text (comma separated, a header line, `#` comment lines and blank lines
    /// ignored). The error is one line naming the row, the line and the column.
    pub fn parse(text: &str) -> Result<MotionTable, String> {
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let (header_line, header) = lines.next().ok_or("no header line (time and support-motion columns)")?;
        let names: Vec<&str> = header.split(',').map(|c| c.trim().trim_matches('"')).collect();
        let mut time_column = None;
        let mut slots: Vec<Option<usize>> = Vec::with_capacity(names.len());
        let mut columns = Vec::new();
        let mut elevation_column = None;
        for (c, name) in names.iter().enumerate() {
            if *name == WAVE_ELEVATION {
                // `beam-impact sea`'s record of the waves (issue 42): read as a number, not used.
                if elevation_column.replace(c).is_some() {
                    return Err(format!("line {header_line}: column `{WAVE_ELEVATION}` appears twice"));
                }
                slots.push(None);
                continue;
            }
            if *name == "time" {
                if time_column.replace(c).is_some() {
                    return Err(format!("line {header_line}: column `time` appears twice"));
                }
                slots.push(None);
                continue;
            }
            let Some(k) = MOTION_NAMES.iter().position(|n| n == name) else {
                // A first line without a `time` column is not a motion header: nothing of it is
                // quoted (the file may be any file a scenario named).
                if !names.contains(&"time") {
                    return Err(not_a_header(header_line));
                }
                return Err(format!(
                    "line {header_line}: unknown column `{}` (expected `time` and any of {})",
                    quote_cell(name),
                    MOTION_NAMES.join(", ")
                ));
            };
            if columns.contains(&MOTION_NAMES[k]) {
                return Err(format!("line {header_line}: column `{name}` appears twice"));
            }
            columns.push(MOTION_NAMES[k]);
            slots.push(Some(k));
        }

        let time_column = time_column.ok_or_else(|| not_a_header(header_line))?;
        if columns.is_empty() {
            return Err(format!("line {header_line}: no support-motion column (any of {})", MOTION_NAMES.join(", ")));
        }
        // A moving support needs its displacement (the gap), velocity and acceleration (the load).
        for group in MOTION_NAMES.chunks(3) {
            let present: Vec<&&str> = group.iter().filter(|n| columns.contains(n)).collect();
            if !present.is_empty() && present.len() < 3 {
                let missing: Vec<&str> = group.iter().filter(|n| !columns.contains(n)).copied().collect();
                return Err(format!(
                    "line {header_line}: `{}` needs {} too (displacement, velocity and acceleration of a moving support)",
                    present[0],
                    missing.join(" and ")
                ));
            }
        }
        let mut times = Vec::new();
        let mut motions = Vec::new();
        for (line, text) in lines {
            let row = times.len() + 1;
            if row > MAX_ROWS {
                return Err(format!("more than {MAX_ROWS} rows (line {line})"));
            }
            let fields: Vec<&str> = text.split(',').map(str::trim).collect();
            if fields.len() != names.len() {
                return Err(format!(
                    "row {row} (line {line}): {} fields, the header has {} columns",
                    fields.len(),
                    names.len()
                ));
            }
            let mut values = [0.0; 9];
            let mut time = 0.0;
            for (c, field) in fields.iter().enumerate() {
                let value: f64 = field.parse().map_err(|_| {
                    format!("row {row} (line {line}): `{}` = `{}` is not a number", names[c], quote_cell(field))
                })?;
                if !value.is_finite() {
                    return Err(format!("row {row} (line {line}): `{}` = {value} is not finite", names[c]));
                }
                match slots[c] {
                    None if Some(c) == elevation_column => {}
                    Some(k) => {
                        check_motion_value(k, value).map_err(|e| format!("row {row} (line {line}): {e}"))?;
                        values[k] = value;
                    }
                    None if value.abs() > 1e9 => {
                        return Err(format!("row {row} (line {line}): time = {value:e} s is beyond +-1e9 s"));
                    }
                    None => time = value,
                }
            }
            debug_assert!(time_column < fields.len());
            if let Some(&previous) = times.last() {
                if time <= previous {
                    return Err(format!(
                        "row {row} (line {line}): time {time} s is not after the previous row's {previous} s \
                         (times must increase strictly)"
                    ));
                }
            }
            times.push(time);
            motions.push(SupportMotion::from_values(values));
        }
        if times.is_empty() {
            return Err(format!("no data rows after the header (line {header_line})"));
        }
        Ok(MotionTable { columns, times, motions })
    }

    /// The table as CSV that [`MotionTable::parse`] reads back to an equal table: a header of
    /// `time` and the columns given, then one line per row, every value in Rust's shortest
    /// round-trip form (the log's `motion.csv` attachment).
    pub fn to_csv(&self) -> String {
        let slots: Vec<usize> =
            self.columns.iter().map(|c| MOTION_NAMES.iter().position(|n| n == c).unwrap_or(0)).collect();
        let mut out = String::with_capacity(24 * (1 + slots.len()) * (1 + self.times.len()));
        out.push_str("time");
        for c in &self.columns {
            out.push(',');
            out.push_str(c);
        }
        out.push('\n');
        for (time, motion) in self.times.iter().zip(&self.motions) {
            let values = motion.values();
            out.push_str(&format!("{time:?}"));
            for &k in &slots {
                out.push_str(&format!(",{:?}", values[k]));
            }
            out.push('\n');
        }
        out
    }

    /// Checks that the rows cover the run from `start` to `end` s (file time); the error names
    /// what is missing.
    pub fn check_covers(&self, start: f64, end: f64) -> Result<(), String> {
        let (first, last) = (self.times[0], self.times[self.times.len() - 1]);
        if first > start {
            return Err(format!(
                "starts at {first} s, after the run's start at {start} s (time_shift): add rows from {start} s"
            ));
        }
        if last < end {
            return Err(format!(
                "ends at {last} s, before the run's end at {end} s (time_shift + duration): add rows up to {end} s"
            ));
        }
        Ok(())
    }

    /// The motion at file time `t` (at or after the first row): the row at or before it,
    /// continued with its constant accelerations.
    pub fn motion_at(&self, t: f64) -> SupportMotion {
        let n = self.times.partition_point(|&x| x <= t).max(1) - 1;
        self.motions[n].after(t - self.times[n])
    }

    /// The rows whose times fall strictly inside the run (file time `shift` to `shift` +
    /// `duration_ns`), as run times in ns with their motions.
    pub fn changes(&self, shift: f64, duration_ns: u64) -> Vec<(u64, SupportMotion)> {
        self.times
            .iter()
            .zip(&self.motions)
            .filter_map(|(&t, m)| {
                let ns = ((t - shift) * 1e9).round();
                (ns > 0.0 && ns < duration_ns as f64).then_some((ns as u64, *m))
            })
            .collect()
    }

    /// Every row that disagrees with the motion the row before it leads to.
    pub fn mismatches(&self) -> Vec<RowMismatch> {
        let mut out = Vec::new();
        for n in 1..self.times.len() {
            let interval = self.times[n] - self.times[n - 1];
            if let Some(mismatch) = self.motions[n - 1].mismatch(&self.motions[n], interval) {
                out.push(RowMismatch { row: n + 1, mismatch });
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAVE: &str = "time,upper.hinge_heave,upper.hinge_heave_velocity,upper.hinge_heave_acceleration\n";

    #[test]
    fn a_constant_acceleration_file_is_read_and_continued_exactly() {
        let text = format!("{HEAVE}0,0,0,2\n0.5,0.25,1,2\n1,1,2,2\n");
        let table = MotionTable::parse(&text).unwrap();
        assert_eq!(table.columns.len(), 3);
        assert!(table.mismatches().is_empty());
        // z = t^2 at t = 0.75: 0.5625, from the row at 0.5.
        assert_eq!(table.motion_at(0.75).hinge_heave.displacement, 0.5625);
        assert_eq!(table.changes(0.25, 500_000_000).iter().map(|c| c.0).collect::<Vec<_>>(), vec![250_000_000]);
        assert!(table.check_covers(0.0, 1.0).is_ok());
        assert!(table.check_covers(0.0, 1.5).unwrap_err().contains("ends at 1 s"));
    }

    #[test]
    fn the_csv_written_to_the_log_reads_back_to_the_same_table() {
        let text = format!(
            "# a comment\n{}\n0,0.1,1e-300,-3.25,0.01,0.02,0.03\n0.1,0.0900000000000001,1e-7,-3.25,0.011,0.02,0.03\n",
            "time,lower.clamp_rotation,lower.clamp_rotation_velocity,lower.clamp_rotation_acceleration,\
             lower.clamp_heave,lower.clamp_heave_velocity,lower.clamp_heave_acceleration"
        );
        let table = MotionTable::parse(&text).unwrap();
        let csv = table.to_csv();
        assert!(csv.starts_with("time,lower.clamp_rotation,"), "{csv}");
        assert_eq!(MotionTable::parse(&csv).unwrap(), table);
        let example = include_str!("../../examples/vessel-motion.csv");
        let table = MotionTable::parse(example).unwrap();
        assert_eq!(MotionTable::parse(&table.to_csv()).unwrap(), table);
    }

    #[test]
    fn errors_quote_at_most_the_offending_cell_and_nothing_of_a_file_that_is_not_a_motion_csv() {
        // /etc/shadow's or /proc/self/environ's first line: no `time` column, nothing quoted.
        for secret in ["root:$6$secret:19000:0:99999:7:::", "PATH=/bin\0SECRET=hunter2", "a,b,SECRET=x"] {
            let e = MotionTable::parse(secret).unwrap_err();
            assert!(!e.contains("secret") && !e.contains("SECRET") && !e.contains("PATH"), "{e}");
            assert!(e.contains("not a motion-file header"), "{e}");
        }
        // A cell of a million NUL bytes: cut to 200 characters, each escaped.
        let cell = "\0".repeat(1_000_000);
        let e = MotionTable::parse(&format!("{HEAVE}0,0,0,{cell}\n")).unwrap_err();
        assert!(e.len() < 2000 && e.contains("\\u{0}") && e.contains("999960 characters cut"), "{}", &e[..200]);
        assert!(!e.contains('\0'));
        // An escape sequence in a cell reaches no terminal.
        let e = MotionTable::parse(&format!("{HEAVE}0,0,0,\u{1b}[31mred\n")).unwrap_err();
        assert!(!e.contains('\u{1b}') && e.contains("\\u{1b}[31mred"), "{e}");
    }

    #[test]
    fn motion_beyond_the_models_range_is_refused_naming_row_and_input() {
        let rotation = "time,lower.clamp_rotation,lower.clamp_rotation_velocity,lower.clamp_rotation_acceleration\n";
        let e = MotionTable::parse(&format!("{rotation}0,0,0,0\n1,1.5,0,0\n")).unwrap_err();
        assert!(e.starts_with("row 2 (line 3): lower.clamp_rotation must be finite with |value| <= 0.1 rad"), "{e}");
        let e = MotionTable::parse(&format!("{HEAVE}0,0,0,1e5\n")).unwrap_err();
        assert!(e.contains("upper.hinge_heave_acceleration") && e.contains("100 m/s2"), "{e}");
        assert!(MotionTable::parse(&format!("{HEAVE}2e9,0,0,0\n")).unwrap_err().contains("beyond +-1e9 s"));
    }

    #[test]
    fn bad_files_are_one_line_errors_naming_the_row() {
        let cases = [
            ("", "no header"),
            ("time,upper.hinge_heave\n0,0\n", "needs upper.hinge_heave_velocity and upper.hinge_heave_acceleration"),
            ("time,lower.clamp_hieve\n", "unknown column `lower.clamp_hieve`"),
            ("upper.hinge_heave,upper.hinge_heave_velocity,upper.hinge_heave_acceleration\n", "no `time` column"),
            ("time,lower.clamp_hieve\u{1b}[2J\n", "unknown column `lower.clamp_hieve\\u{1b}[2J`"),
            (&format!("{HEAVE}0,0,0,0\n0,0,0,0\n"), "row 2 (line 3): time 0 s is not after"),
            (&format!("{HEAVE}0,0,0,0\n1,nan,0,0\n"), "row 2 (line 3): `upper.hinge_heave` = NaN is not finite"),
            (&format!("{HEAVE}0,0,0,x\n"), "row 1 (line 2): `upper.hinge_heave_acceleration` = `x` is not a number"),
            (&format!("{HEAVE}0,0,0\n"), "row 1 (line 2): 3 fields, the header has 4"),
            (HEAVE, "no data rows"),
        ];
        for (text, expected) in cases {
            let e = MotionTable::parse(text).unwrap_err();
            assert!(e.contains(expected), "{text:?}: {e}");
            assert!(!e.contains('\n'), "{e}");
        }
    }

    #[test]
    fn a_row_that_jumps_is_named() {
        // Position jumps by 0.1 m with zero velocity and acceleration.
        let text = format!("{HEAVE}0,0,0,0\n1,0,0,0\n2,0.1,0,0\n");
        let m = MotionTable::parse(&text).unwrap().mismatches();
        assert_eq!(m.len(), 1);
        assert_eq!((m[0].row, m[0].mismatch.name), (3, "upper.hinge_heave"));
    }
}
