//! Issue 42: both RAO parsers (our CSV and VERES `.re1`) on any text: a table within the bounds
//! or one short line of error (no control character, nothing quoted of a first line that is not
//! a header), never a panic; an accepted table interpolates anywhere without a panic.
//!
//! Goal: seeded mutations of the fixture CSV and of a small `.re1` written here (cells replaced
//! by hostile literals, lines deleted, duplicated and swapped, byte-level mutations).
//! `BEAM_IMPACT_FUZZ_ITERATIONS` sets the number of mutations.

use crate::fuzz_support;

use beam_impact::model::sea::raos::{RaoTable, MAX_FREQUENCY, MAX_ROTATION, MAX_TRANSLATION};
use fuzz_support::{iterations, mutate, Rng};

const LITERALS: &[&str] = &[
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "0",
    "-0.0",
    "5e-324",
    "0.5",
    "1",
    "180",
    "360",
    "-360",
    "720",
    "1e9",
    "",
    " ",
    "\"1\"",
    "\u{661}",
    "0x10",
    "\u{1b}[2J",
    "\0\0",
    "1,2",
    "#",
    "frequency",
    "6",
    "7",
    "2000000",
];

/// A small `.re1`: two headings, three frequencies, one speed.
fn re1() -> String {
    let mut text = String::from(" MOTION TRANSFER FUNCTIONS  - VERES\n Run name:\n Ship name: Test\n x\n\n x\n");
    text += "  1025 9.81\n  80 20 6\n  5 7\n     1     2     3     6\n  0 0 0 5 6\n";
    for heading in ["0.00", "90.00"] {
        text += &format!("       {heading}\n");
        for w in ["0.2", "0.8", "1.5"] {
            text += &format!("  {w}\n");
            for dof in 1..=6 {
                text += &format!("  {dof} 0.{dof}E+00 -0.{dof}E-01\n");
            }
        }
    }
    text
}

fn seeds() -> Vec<String> {
    // The fixture's first two lines and its rows at 4 frequencies and 3 headings (a full grid).
    let csv: Vec<&str> = include_str!("fixtures/sea-raos.csv")
        .lines()
        .enumerate()
        .filter(|(k, l)| {
            let cells: Vec<&str> = l.split(',').collect();
            *k < 2
                || (["0.100000", "0.200000", "0.300000", "0.400000"].contains(&cells[0])
                    && ["180", "195", "210"].contains(&cells[1]))
        })
        .map(|(_, l)| l)
        .collect();
    vec![csv.join("\n"), re1()]
}

fn mutate_lines(text: &str, rng: &mut Rng) -> String {
    let sep = if text.contains(',') { ',' } else { ' ' };
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for _ in 0..1 + rng.below(3) {
        if lines.is_empty() {
            lines.push(String::new());
        }
        let i = rng.below(lines.len());
        match rng.below(6) {
            0..=2 => {
                let mut cells: Vec<String> = lines[i].split(sep).map(str::to_string).collect();
                let c = rng.below(cells.len());
                cells[c] = rng.pick(LITERALS).to_string();
                lines[i] = cells.join(&sep.to_string());
            }
            3 => {
                lines.remove(i);
            }
            4 => {
                let line = lines[i].clone();
                lines.insert(rng.below(lines.len() + 1), line);
            }
            _ => {
                let j = rng.below(lines.len());
                lines.swap(i, j);
            }
        }
    }
    lines.join("\n")
}

/// Parses `text` and checks what it gives; returns whether it was accepted.
fn check(name: &str, text: &str) -> bool {
    match RaoTable::parse(text) {
        Err(e) => {
            assert!(!e.chars().any(char::is_control), "{name}: a control character in {e:?}");
            assert!(e.chars().count() <= 1500, "{name}: {} characters of error", e.len());
            false
        }
        Ok(t) => {
            assert!(t.frequencies.windows(2).all(|w| w[0] < w[1]), "{name}: frequencies");
            assert!(t.frequencies.iter().all(|f| *f > 0.0 && *f <= MAX_FREQUENCY), "{name}");
            assert!(t.headings.windows(2).all(|w| w[0] < w[1]), "{name}: headings");
            assert!(t.headings.iter().all(|h| (0.0..360.0).contains(h)), "{name}: {:?}", t.headings);
            assert_eq!(t.values.len(), t.headings.len() * t.frequencies.len(), "{name}");
            for v in &t.values {
                for (dof, c) in v.iter().enumerate() {
                    let limit = if dof >= 3 { MAX_ROTATION } else { MAX_TRANSLATION };
                    assert!(c.norm() <= limit * (1.0 + 1e-12), "{name}: {c}");
                }
            }
            let (lo, hi) = t.frequency_range();
            for beta in [0.0, 45.0, 90.0, 179.9, 180.0, 270.0, 359.99] {
                match t.at_heading(beta) {
                    Ok(column) => {
                        for w in [lo, 0.5 * (lo + hi), hi] {
                            let h = t.at_frequency(&column, w).unwrap();
                            assert!(h.iter().all(|c| c.re.is_finite() && c.im.is_finite()), "{name}");
                        }
                    }
                    Err(e) => assert!(!e.contains('\n'), "{name}: {e}"),
                }
            }
            true
        }
    }
}

#[test]
fn the_seeds_are_accepted() {
    for (k, seed) in seeds().iter().enumerate() {
        assert!(check(&format!("seed {k}"), seed), "seed {k}");
    }
}

#[test]
fn seeded_mutations_of_rao_files_never_panic_and_stay_within_bounds() {
    let seeds = seeds();
    let mut rng = Rng(0x5EA_5EA);
    let (mut accepted, mut refused) = ([0; 2], [0; 2]);
    for i in 0..iterations(4000) {
        let which = rng.below(seeds.len());
        let seed = &seeds[which];
        let text = if i % 4 == 3 {
            String::from_utf8_lossy(&mutate(seed.as_bytes(), &mut rng)).into_owned()
        } else {
            mutate_lines(seed, &mut rng)
        };
        if check(&format!("mutation {i}"), &text) {
            accepted[which] += 1;
        } else {
            refused[which] += 1;
        }
    }
    // Both sides reached for both formats: the mutator is neither only harmless nor only fatal.
    println!("accepted {accepted:?}, refused {refused:?}");
    assert!(
        accepted.iter().all(|a| *a > 0) && refused.iter().all(|r| *r > 0),
        "accepted {accepted:?}, refused {refused:?}"
    );
}
