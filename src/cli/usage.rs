//! The command line's own mistakes (issue 41): a mistyped subcommand named as one, and clap's
//! usage errors printed as clap writes them (its lines, `tip:` and `Usage:`), bounded in size.
//! Errors of the input (a scenario, a log) stay one line each (`common::bounded_line`).

use std::ffi::OsString;
use std::path::Path;

use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::CommandFactory;

use super::args::Cli;

/// A word of a usage error longer than this (an argument of 120 KB echoed back) keeps its first
/// [`WORD_HEAD`] and last [`WORD_TAIL`] characters, the count cut between.
const LONG_WORD: usize = 200;
const WORD_HEAD: usize = 120;
const WORD_TAIL: usize = 40;
/// At most this many lines of a usage error (clap's are fewer than 20).
const MAX_LINES: usize = 60;

/// The error of a first argument that is neither a subcommand nor an existing file but close to a
/// subcommand's name (`beam-impact sweeep`): without it the bare `beam-impact FILE` took it for a
/// scenario file and said `cannot read scenario sweeep`. Closeness is clap's own (Jaro similarity
/// above 0.7). A word with a `.` or a `/` is a file name, as is any path that exists.
pub fn mistyped_subcommand(args: &[OsString]) -> Option<clap::Error> {
    let first = args.get(1)?.to_str()?;
    if first.is_empty() || first.starts_with('-') || first.contains(['.', '/']) || Path::new(first).exists() {
        return None;
    }
    let mut cmd = Cli::command();
    // clap's own `help` subcommand is added when the command is built: named here too.
    let names: Vec<String> =
        cmd.get_subcommands().map(|s| s.get_name().to_string()).chain(["help".to_string()]).collect();
    if names.iter().any(|n| n == first) {
        return None;
    }
    let mut close: Vec<(f64, String)> =
        names.into_iter().map(|n| (strsim::jaro(first, &n), n)).filter(|(confidence, _)| *confidence > 0.7).collect();
    // The closest first, as clap lists its suggestions.
    close.sort_by(|a, b| b.0.total_cmp(&a.0));
    if close.is_empty() {
        return None;
    }
    let usage = cmd.render_usage();
    let mut error = clap::Error::new(ErrorKind::InvalidSubcommand).with_cmd(&cmd);
    error.insert(ContextKind::InvalidSubcommand, ContextValue::String(first.to_string()));
    error.insert(ContextKind::SuggestedSubcommand, ContextValue::Strings(close.into_iter().map(|(_, n)| n).collect()));
    error.insert(ContextKind::Usage, ContextValue::StyledStr(usage));
    Some(error)
}

/// A clap usage error as clap prints it, line for line, with every over-long word cut in the
/// middle (the count cut said), control characters shown as U+FFFD, and at most [`MAX_LINES`]
/// lines.
pub fn bounded_usage(text: &str) -> String {
    let lines: Vec<&str> = text.trim_end().lines().collect();
    let mut out: Vec<String> = lines.iter().take(MAX_LINES).map(|line| bounded_words(line)).collect();
    if lines.len() > MAX_LINES {
        out.push(format!("[... {} lines cut ...]", lines.len() - MAX_LINES));
    }
    out.join("\n")
}

fn bounded_words(line: &str) -> String {
    line.split(' ')
        .map(|word| {
            let chars: Vec<char> = word.chars().map(|c| if c.is_control() { '\u{FFFD}' } else { c }).collect();
            if chars.len() <= LONG_WORD {
                return chars.into_iter().collect();
            }
            let head: String = chars[..WORD_HEAD].iter().collect();
            let tail: String = chars[chars.len() - WORD_TAIL..].iter().collect();
            format!("{head}[... {} characters cut ...]{tail}", chars.len() - WORD_HEAD - WORD_TAIL)
        })
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_word_is_cut_and_the_lines_kept() {
        let long = "x".repeat(120_000);
        let text = format!("error: unexpected argument '--{long}' found\n\nUsage: beam-impact run [OPTIONS]\n");
        let bounded = bounded_usage(&text);
        assert_eq!(bounded.lines().count(), 3, "{bounded}");
        assert!(bounded.len() < 400, "{bounded}");
        assert!(bounded.contains("characters cut") && bounded.ends_with("Usage: beam-impact run [OPTIONS]"));
    }
}
