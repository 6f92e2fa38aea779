//! Issue 42: both RAO parsers (our CSV and VERES `.re1`) on any text: a table within the bounds
//! or one short line of error (no control character, nothing quoted of a first line that is not
//! a header), never a panic; an accepted table interpolates anywhere without a panic.
//!
//! Goal: seeded mutations of the fixture CSV and of a small `.re1` written here (cells replaced
//! by hostile literals, lines deleted, duplicated and swapped, byte-level mutations).
//! `BEAM_IMPACT_FUZZ_ITERATIONS` sets the number of mutations; `tests/corpus/raos/` (hostile files
//! and the seeds) is replayed.

use crate::fuzz_support;

use beam_impact::model::sea::raos::{RaoTable, MAX_FREQUENCY, MAX_ROTATION, MAX_TRANSLATION};
use fuzz_support::{corpus_dir, corpus_files, iterations, mutate, Rng};

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

#[test]
fn the_committed_corpus_replays() {
    let files = corpus_files("raos");
    assert!(files.len() >= 10);
    let mut accepted = 0;
    for (name, bytes) in files {
        if check(&name, &String::from_utf8_lossy(&bytes)) {
            accepted += 1;
        }
    }
    // The two seeds are accepted; every hostile file is refused.
    assert_eq!(accepted, 2);
}

/// Writes `tests/corpus/raos/` (the seeds and hostile files; a file of too many rows is
/// `sea_raos::a_million_rows_are_refused_at_the_limit_within_a_second`'s, made in memory):
/// `cargo test --release --test integration -- --ignored fuzz_sea_raos::write_corpus`.
#[test]
#[ignore]
fn write_corpus() {
    let dir = corpus_dir("raos");
    std::fs::create_dir_all(&dir).unwrap();
    let [csv, re1] = [seeds()[0].clone(), seeds()[1].clone()];
    let header = csv.lines().nth(1).unwrap().to_string();
    let row = |w: &str, h: &str| format!("{w},{h},0,0,0,0,1,0,0,0,0,0,0,0\n");
    let files: Vec<(&str, String)> = vec![
        ("seed.csv", csv.clone()),
        ("seed.re1", re1.clone()),
        ("shadow-first-line.csv", "root:$6$salt$hash:19000:0:99999:7:::\n".into()),
        ("nan-frequency.csv", format!("{header}\n{}{}", row("0.5", "180"), row("nan", "180"))),
        ("duplicate-row.csv", format!("{header}\n{}{}", row("0.5", "180"), row("0.5", "180"))),
        ("incomplete-grid.csv", format!("{header}\n{}{}{}", row("0.5", "180"), row("1", "180"), row("0.5", "195"))),
        ("escape-in-header.csv", "frequency,heading,\u{1b}]0;owned\u{7}\n".into()),
        ("re1-frequencies-decreasing.re1", re1.replacen("  0.8\n", "  0.1\n", 1)),
        ("re1-counts-huge.re1", re1.replacen("     1     2     3     6", "     1     2     3000000     6", 1)),
        ("re1-cut-short.re1", re1.lines().take(20).collect::<Vec<_>>().join("\n")),
        ("re1-dof-twice.re1", re1.replacen("  2 0.2E+00", "  1 0.2E+00", 1)),
        ("empty.csv", String::new()),
    ];
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
}
