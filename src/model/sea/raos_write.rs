//! A vessel's RAO table written as our CSV (the format [`super::raos`] reads; docs/sea-states.md):
//! `pack --ssp` gives the vessel FMU, which reads our CSV only, the table of a `[sea]` whose file
//! is VERES `.re1`. Every heading of the table is written (those completed by symmetry too: a file
//! with headings on both sides is read back without mirroring), amplitudes as |H| (m/m, deg/m) and
//! phases as arg H (deg), in Rust's shortest round-trip form: reading the text back gives each
//! complex RAO to a few ulp (amplitude times the cosine and sine of the phase).

use super::raos::{RaoTable, CSV_COLUMNS};

/// The table as our CSV: `comment` lines (each prefixed `# `), the header, one row per frequency
/// and heading.
pub fn write_csv(table: &RaoTable, comment: &str) -> String {
    let mut text = String::new();
    for line in comment.lines() {
        text.push_str("# ");
        text.push_str(line);
        text.push('\n');
    }
    text.push_str(&CSV_COLUMNS.join(","));
    text.push('\n');
    let nf = table.frequencies.len();
    for (h, heading) in table.headings.iter().enumerate() {
        for (f, frequency) in table.frequencies.iter().enumerate() {
            text.push_str(&format!("{frequency:?},{heading:?}"));
            for (dof, value) in table.values[h * nf + f].iter().enumerate() {
                let scale = if dof >= 3 { 180.0 / std::f64::consts::PI } else { 1.0 };
                text.push_str(&format!(",{:?},{:?}", value.norm() * scale, value.arg().to_degrees()));
            }
            text.push('\n');
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A one-sided table (mirrored when read) written and read back: the same grid, every complex
    /// RAO within 4 ulp of its magnitude (|H| cos(arg H) against re: two roundings each way).
    #[test]
    fn a_table_written_reads_back_to_round_off() {
        let header = CSV_COLUMNS.join(",");
        let mut text = format!("{header}\n");
        for heading in [150.0, 165.0, 180.0] {
            for w in [0.3, 0.7, 1.9] {
                text += &format!("{w},{heading},0.3,80,0.2,-10,0.9,-20,1.5,35,2.5,-118,0.4,170\n");
            }
        }
        let table = RaoTable::parse_csv(&text).unwrap();
        let back = RaoTable::parse_csv(&write_csv(&table, "a test\nof two lines")).unwrap();
        assert_eq!((&back.frequencies, &back.headings), (&table.frequencies, &table.headings));
        for (a, b) in table.values.iter().zip(&back.values) {
            for j in 0..6 {
                assert!((a[j] - b[j]).norm() <= 4.0 * f64::EPSILON * a[j].norm(), "{j}: {} {}", a[j], b[j]);
            }
        }
    }
}
