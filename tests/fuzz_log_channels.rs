//! Issue 41 item 2: the `log.channels` list (`run --log-channels`, the FMU's `log.channels`,
//! Python's `log_channels=`) on any text: a set of topics, or one short line of error that names
//! the bad value (quoted, at most 40 characters, control characters escaped), never a panic;
//! what it accepts prints back to a list that parses to the same set.
//!
//! Goal: hostile literals (control characters, quotes, NULs, long and non-ASCII names, separators
//! of other languages) and seeded mutations of valid lists: items inserted, dropped, duplicated,
//! spaced, prefixed and cut, and byte-level edits. `BEAM_IMPACT_FUZZ_ITERATIONS` sets the number
//! of mutations.

use crate::fuzz_support;

use beam_impact::record::mcap::LogChannels;
use beam_impact::record::options::{CHANNEL_NAMES, MAX_CHANNELS_TEXT};
use fuzz_support::{iterations, Rng};

const LITERALS: &[&str] = &[
    "",
    " ",
    ",",
    ",,",
    "all",
    "ALL",
    "All",
    "/beam/all",
    "none",
    "step;modes",
    "step modes",
    "step\tmodes",
    "step,\nmodes",
    "\"step\"",
    "'modes'",
    "/beam/",
    "/beam//modes",
    "beam/modes",
    "/beam/modes/",
    "\0",
    "modes\0",
    "\u{1b}[2J",
    "\u{feff}step",
    "st\u{e9}p",
    "\u{661}",
    "模式",
    "modes\u{2c}scene",
    "modes\u{ff0c}scene",
    "${HOME}",
    "../../etc/passwd",
    "%s%n%x",
    "\\",
];

/// What any text must give: a set that prints back to itself, or one bounded line naming it.
fn check(text: &str) {
    match LogChannels::parse(text) {
        Ok(channels) => {
            let printed = channels.to_string();
            assert_eq!(LogChannels::parse(&printed), Ok(channels), "{text:?} printed {printed:?}");
            assert!(printed.split(',').all(|n| CHANNEL_NAMES.contains(&n)), "{printed}");
            assert!(text.len() <= MAX_CHANNELS_TEXT, "{} bytes accepted", text.len());
        }
        Err(e) => {
            assert!(e.starts_with("log.channels: "), "{text:?}: {e}");
            assert!(!e.chars().any(char::is_control), "{text:?}: a control character in {e:?}");
            // The known names (about 80 bytes), the quoted value (at most 40 characters, each
            // escaped to at most 10 bytes) and the words around them.
            assert!(e.len() <= 700, "{text:?}: {} bytes of error", e.len());
        }
    }
}

#[test]
fn hostile_literals_give_a_set_or_one_line_naming_the_value() {
    for text in LITERALS {
        check(text);
    }
    for name in CHANNEL_NAMES {
        check(name);
        check(&format!("/beam/{name}"));
        check(&format!(" {name} "));
    }
    check(&"modes,".repeat(43));
    check(&"modes,".repeat(42));
    check(&"\u{1b}".repeat(10_000));
    check(&"é".repeat(100));
    // Unknown names are quoted in the error, cut to 40 characters.
    let e = LogChannels::parse(&format!("step,{}", "x".repeat(100))).unwrap_err();
    assert!(e.contains(&format!("\"{}...\"", "x".repeat(40))), "{e}");
}

#[test]
fn mutated_lists_give_a_set_or_one_line_naming_the_value() {
    let mut rng = Rng(41);
    let pieces: Vec<String> = CHANNEL_NAMES
        .iter()
        .flat_map(|n| [n.to_string(), format!("/beam/{n}"), format!(" {n}")])
        .chain(LITERALS.iter().map(|s| s.to_string()))
        .collect();
    for _ in 0..iterations(5000) {
        let count = 1 + rng.below(8);
        let mut text = (0..count).map(|_| rng.pick(&pieces).clone()).collect::<Vec<_>>().join(",");
        // Byte-level edits where they leave UTF-8 (a `&str` cannot hold anything else).
        let mut bytes = text.clone().into_bytes();
        for _ in 0..rng.below(3) {
            if bytes.is_empty() {
                break;
            }
            let k = rng.below(bytes.len());
            match rng.below(3) {
                0 => bytes[k] = rng.below(128) as u8,
                1 => {
                    bytes.remove(k);
                }
                _ => bytes.insert(k, *rng.pick(b",/ \t\0ab")),
            }
        }
        if let Ok(edited) = String::from_utf8(bytes) {
            text = edited;
        }
        check(&text);
    }
}
