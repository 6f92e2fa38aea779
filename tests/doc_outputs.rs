//! The outputs the README and the pages of `docs/` show are today's (issue 41, item 3): a snapshot
//! test in the style of `trycmd`/`snapbox`, over the pages' own Markdown.
//!
//! An output block (```` ```text ````, ```` ```json ````, ```` ```csv ````) carries a marker on the
//! line before its fence (tests/docs.rs refuses one with none, outside the pages it still lists as
//! `PAGES_NOT_YET_UNDER_OUTPUT_MARKERS`):
//!
//! - `<!-- output: the block above -->`: this test runs the page's fenced block just above it (a
//!   ```` ```sh ```` block) and compares what it prints with the block (a command block no other
//!   test runs says so with `<!-- run by tests/doc_outputs.rs: ... -->` before its fence);
//! - ``<!-- output: `COMMAND` -->``: this test runs COMMAND (for an output whose command the page
//!   gives in prose, or the README's results);
//! - `<!-- illustrative: why -->`: shown, not compared, and the reason says why (an abbreviated
//!   Python output, a measurement on a named machine and date, a file tree).
//!
//! Each page's checked commands run in order, in one temporary folder holding a copy of
//! `examples/` (so a later block reads the files an earlier one wrote), through
//! `bash -eo pipefail`, with the release `beam-impact` first on PATH and `LC_ALL=C`, standard
//! error merged into standard output (as a terminal shows them). The pages run in parallel.
//!
//! A block matches its output line for line, trailing blanks dropped, a run of spaces matching any
//! run of spaces (columns may widen). The volatile parts are masked in the block:
//!
//! - `...` alone on a line: any number of lines (none included);
//! - `[..]`: any text within a line;
//! - `[TIME]`: a duration or a wall time (`833.5 ms`, `4.86 s`, `0.50`);
//! - `[COUNT]`: a whole number that depends on the machine (threads, cores);
//! - `[DATE]`: a date (`2026-11-29`, with an optional time);
//! - `[PATH]`: a path (no spaces); `[HASH]`: a hexadecimal hash.
//!
//! A mask is one of these names exactly: `[m]`, `[N]`, `[MPa]` are units, compared as written.
//!
//! Everything else is compared as written: a number that moves fails the test, with the page, the
//! line and the two texts. **Bless** when the change is meant: `BEAM_IMPACT_BLESS=1 cargo test
//! --release --test integration doc_outputs` rewrites every checked block from today's output, keeping
//! its masks and `...` where the output still fits around them (a line whose text changed keeps
//! its masks, its numbers taken from today; a block whose lines no longer align is written out in
//! full, to be abridged again by hand). Then read `git diff` on the pages: the prose around a
//! blessed block may quote its numbers.
//!
//! A new checked block: write its marker and an empty ```` ```text ```` block, bless, then abridge
//! the output with `...` and mask what varies from run to run or machine to machine.
//!
//! Why a harness of our own and not `trycmd` or `snapbox` as a dependency: trycmd reads
//! ```` ```console ```` blocks holding `$ command` and its output together and runs argv without a
//! shell, while these pages keep a command (```` ```sh ````, which tests/python/test_tutorial.py
//! and tests/examples.rs run as written) and its output in separate blocks, with pipes (`| grep`)
//! and files written by earlier blocks; snapbox's matcher would fit (this test takes its `[..]`
//! and `...` syntax and named masks), but its bless rewrites a Rust source or a whole file, not
//! one block of a Markdown page. The harness is this file, with `regex` (already in the lock
//! file) as its one new dev-dependency.

use std::path::Path;
use std::process::Command;

use regex::Regex;

use crate::docs::{blocks, pages, root, Block};

/// The environment variable that rewrites the pages' checked blocks from today's outputs.
pub(crate) const BLESS: &str = "BEAM_IMPACT_BLESS";

/// The masks a checked block may hold within a line, with the regular expression each stands for.
pub(crate) const MASKS: &[(&str, &str)] = &[
    ("[..]", r".*?"),
    ("[TIME]", r"[0-9]+(?:\.[0-9]+)?(?:e-?[0-9]+)?(?: ?(?:ns|us|µs|ms|s|min|h))?"),
    ("[COUNT]", r"[0-9]+"),
    ("[DATE]", r"[0-9]{4}-[0-9]{2}-[0-9]{2}(?:[T ][0-9:.]+Z?)?"),
    ("[PATH]", r"\S+"),
    ("[HASH]", r"[0-9a-f]{6,}"),
];

/// The marker of a block whose output this test produces from the block above it.
pub(crate) const OUTPUT_OF_BLOCK_ABOVE: &str = "output: the block above";

/// What a checked block's marker asks to run: the block above, or a command of its own.
pub(crate) fn checked_command(marker: &str) -> Option<Option<String>> {
    let rest = marker.strip_prefix("output:")?.trim();
    if rest == "the block above" {
        return Some(None);
    }
    let command = rest.strip_prefix('`')?.strip_suffix('`')?;
    (!command.is_empty()).then(|| Some(command.to_string()))
}

/// One token of a line of a block.
#[derive(Debug, Clone, PartialEq)]
enum Token {
    Literal(String),
    Space,
    Number(String),
    Mask(&'static str),
}

fn tokens(line: &str) -> Vec<Token> {
    let number = Regex::new(r"^[0-9]+(?:\.[0-9]+)?(?:[eE][-+]?[0-9]+)?").unwrap();
    let mut out = Vec::new();
    let mut rest = line;
    'scan: while let Some(c) = rest.chars().next() {
        for (mask, _) in MASKS {
            if rest.starts_with(mask) {
                out.push(Token::Mask(mask));
                rest = &rest[mask.len()..];
                continue 'scan;
            }
        }
        if c.is_whitespace() {
            let end = rest.find(|c: char| !c.is_whitespace()).unwrap_or(rest.len());
            out.push(Token::Space);
            rest = &rest[end..];
        } else if let Some(m) = number.find(rest) {
            out.push(Token::Number(m.as_str().to_string()));
            rest = &rest[m.end()..];
        } else {
            match out.last_mut() {
                Some(Token::Literal(s)) => s.push(c),
                _ => out.push(Token::Literal(c.to_string())),
            }
            rest = &rest[c.len_utf8()..];
        }
    }
    out
}

/// A line of a block as a pattern: `strict` matches today's line only where the block holds (its
/// numbers as written), `relaxed` matches a line of the same words whatever its numbers (to align
/// a changed output with the block, and bless it).
#[derive(Debug)]
struct LinePattern {
    text: String,
    tokens: Vec<Token>,
    strict: Regex,
    relaxed: Regex,
}

impl LinePattern {
    fn new(text: &str) -> Self {
        let tokens = tokens(text.trim_end());
        let (mut strict, mut relaxed) = (String::from("^"), String::from("^"));
        for token in &tokens {
            match token {
                Token::Literal(s) => {
                    strict.push_str(&regex::escape(s));
                    relaxed.push_str(&regex::escape(s));
                }
                Token::Space => {
                    strict.push_str(r"\s+");
                    relaxed.push_str(r"(\s+)");
                }
                Token::Number(n) => {
                    strict.push_str(&regex::escape(n));
                    relaxed.push_str(r"([-+]?[0-9][0-9.]*(?:[eE][-+]?[0-9]+)?|-)");
                }
                Token::Mask(m) => {
                    let re = MASKS.iter().find(|(name, _)| name == m).unwrap().1;
                    strict.push_str(&format!("(?:{re})"));
                    relaxed.push_str(&format!("({re})"));
                }
            }
        }
        strict.push('$');
        relaxed.push('$');
        LinePattern {
            text: text.trim_end().to_string(),
            tokens,
            strict: Regex::new(&strict).unwrap(),
            relaxed: Regex::new(&relaxed).unwrap(),
        }
    }

    /// Today's line in this line's shape: its masks kept, its spaces and numbers today's.
    fn bless(&self, actual: &str) -> String {
        if self.strict.is_match(actual) {
            return self.text.clone();
        }
        let Some(caps) = self.relaxed.captures(actual) else { return actual.to_string() };
        let mut out = String::new();
        let mut group = 1;
        for token in &self.tokens {
            match token {
                Token::Literal(s) => out.push_str(s),
                Token::Space | Token::Number(_) => {
                    out.push_str(caps.get(group).map_or("", |m| m.as_str()));
                    group += 1;
                }
                Token::Mask(m) => {
                    out.push_str(m);
                    group += 1;
                }
            }
        }
        out
    }
}

#[derive(Debug)]
enum Pattern {
    /// `...` (its text, indented or not): any number of lines.
    AnyLines(String),
    Line(LinePattern),
}

fn patterns(block: &str) -> Vec<Pattern> {
    block
        .lines()
        .map(|l| if l.trim() == "..." { Pattern::AnyLines(l.to_string()) } else { Pattern::Line(LinePattern::new(l)) })
        .collect()
}

/// Today's output as the lines a block is compared with: trailing blanks and blank lines dropped.
fn output_lines(output: &str) -> Vec<String> {
    let mut lines: Vec<String> = output.lines().map(|l| l.trim_end().to_string()).collect();
    while lines.last().is_some_and(|l| l.is_empty()) {
        lines.pop();
    }
    lines
}

/// For each pattern, the index of the line it matches (`...`: where its lines start), or None
/// when the block does not match. `...` takes as few lines as it can.
fn align(patterns: &[Pattern], lines: &[String], relaxed: bool) -> Option<Vec<usize>> {
    fn go(
        p: usize,
        i: usize,
        patterns: &[Pattern],
        lines: &[String],
        relaxed: bool,
        failed: &mut std::collections::HashSet<(usize, usize)>,
        out: &mut Vec<usize>,
    ) -> bool {
        if p == patterns.len() {
            return i == lines.len();
        }
        if failed.contains(&(p, i)) {
            return false;
        }
        let ok = match &patterns[p] {
            Pattern::AnyLines(_) => (i..=lines.len()).any(|j| {
                out.push(i);
                let ok = go(p + 1, j, patterns, lines, relaxed, failed, out);
                if !ok {
                    out.pop();
                }
                ok
            }),
            Pattern::Line(line) => {
                let re = if relaxed { &line.relaxed } else { &line.strict };
                i < lines.len() && re.is_match(&lines[i]) && {
                    out.push(i);
                    let ok = go(p + 1, i + 1, patterns, lines, relaxed, failed, out);
                    if !ok {
                        out.pop();
                    }
                    ok
                }
            }
        };
        if !ok {
            failed.insert((p, i));
        }
        ok
    }
    let mut out = Vec::new();
    let mut failed = std::collections::HashSet::new();
    go(0, 0, patterns, lines, relaxed, &mut failed, &mut out).then_some(out)
}

/// Whether a block shows an output, its masks and `...` allowed for.
pub(crate) fn matches(block: &str, output: &str) -> bool {
    align(&patterns(block), &output_lines(output), false).is_some()
}

/// Where a block and an output differ, line by line, for a failure message (empty when they match);
/// `first` is the page's line number of the block's first line.
pub(crate) fn differences(block: &str, output: &str, first: usize) -> String {
    let patterns = patterns(block);
    let lines = output_lines(output);
    if align(&patterns, &lines, false).is_some() {
        return String::new();
    }
    if let Some(at) = align(&patterns, &lines, true) {
        let mut out = String::new();
        for (n, (pattern, &i)) in patterns.iter().zip(&at).enumerate() {
            if let Pattern::Line(line) = pattern {
                if !line.strict.is_match(&lines[i]) {
                    out.push_str(&format!(
                        "  line {}:\n    shown: {}\n    today: {}\n",
                        first + n,
                        line.text,
                        lines[i]
                    ));
                }
            }
        }
        return out;
    }
    format!(
        "  the lines no longer align (a line added, removed or reworded):\n--- shown:\n{}\n--- today:\n{}\n",
        block.trim_end(),
        lines.join("\n")
    )
}

/// The block rewritten from today's output: unchanged when it matches; else its lines with today's
/// numbers, masks and `...` kept; else (the lines no longer align) today's output in full.
pub(crate) fn bless(block: &str, output: &str) -> String {
    let patterns = patterns(block);
    let lines = output_lines(output);
    if align(&patterns, &lines, false).is_some() {
        return block.trim_end().to_string();
    }
    match align(&patterns, &lines, true) {
        Some(at) => patterns
            .iter()
            .zip(&at)
            .map(|(pattern, &i)| match pattern {
                Pattern::AnyLines(text) => text.clone(),
                Pattern::Line(line) => line.bless(&lines[i]),
            })
            .collect::<Vec<_>>()
            .join("\n"),
        None => lines.join("\n"),
    }
}

/// A checked block of a page and the command that produces its output.
struct Checked {
    block: Block,
    command: String,
}

/// The checked blocks of a page, in order, each with its command.
fn checked_blocks(text: &str) -> Result<Vec<Checked>, String> {
    let all = blocks(text);
    let mut out = Vec::new();
    for (n, block) in all.iter().enumerate() {
        let Some(command) = block.marker.as_deref().and_then(checked_command) else { continue };
        let command = match command {
            Some(c) => c,
            None => {
                let above = n.checked_sub(1).map(|k| &all[k]);
                match above {
                    Some(b) if matches!(b.language.as_str(), "sh" | "bash") => b.body.clone(),
                    _ => {
                        return Err(format!("line {}: `{OUTPUT_OF_BLOCK_ABOVE}` with no ```sh block above", block.line))
                    }
                }
            }
        };
        out.push(Checked { block: block.clone(), command });
    }
    Ok(out)
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}

/// Runs a page's checked commands in order in one fresh folder: each one's output, or why it failed.
fn run_page(checked: &[Checked]) -> Vec<Result<String, String>> {
    let folder = tempfile::tempdir().unwrap();
    copy_dir(&root().join("examples"), &folder.path().join("examples"));
    let binary = Path::new(env!("CARGO_BIN_EXE_beam-impact"));
    let path = std::env::join_paths(
        std::iter::once(binary.parent().unwrap().to_path_buf())
            .chain(std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default())),
    )
    .unwrap();
    checked
        .iter()
        .map(|c| {
            let out = Command::new("bash")
                .args(["-eo", "pipefail", "-c", &format!("exec 2>&1\n{}", c.command)])
                .current_dir(folder.path())
                .env("PATH", &path)
                .env("LC_ALL", "C") // the C locale's numbers (awk, sort) and messages
                .env_remove(BLESS)
                .output()
                .map_err(|e| format!("bash: {e}"))?;
            let text = String::from_utf8_lossy(&out.stdout).to_string();
            if out.status.success() {
                Ok(text)
            } else {
                Err(format!("exit status {}; its output:\n{text}", out.status))
            }
        })
        .collect()
}

/// Replaces the body of the block whose fence opens at 1-based `line`, keeping its indentation.
fn replace_body(text: &str, line: usize, body: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let fence = lines[line - 1];
    let indent = &fence[..fence.len() - fence.trim_start().len()];
    let close = (line..lines.len()).find(|&i| lines[i].trim_start().starts_with("```")).unwrap();
    let mut out: Vec<String> = lines[..line].iter().map(|l| l.to_string()).collect();
    out.extend(body.lines().map(|l| if l.is_empty() { String::new() } else { format!("{indent}{l}") }));
    out.extend(lines[close..].iter().map(|l| l.to_string()));
    let mut joined = out.join("\n");
    if text.ends_with('\n') {
        joined.push('\n');
    }
    joined
}

/// Issue 41: "Every output a page shows is produced by the tests and compared, or marked as
/// illustrative." Every checked block is its command's output today (or, under
/// `BEAM_IMPACT_BLESS=1`, is rewritten to be).
#[test]
fn every_checked_output_block_shows_todays_output() {
    let blessing = std::env::var_os(BLESS).is_some_and(|v| v != "0" && !v.is_empty());
    let mut work = Vec::new();
    let mut problems = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(root().join(&page)).unwrap();
        match checked_blocks(&text) {
            Ok(c) if c.is_empty() => {}
            Ok(c) => work.push((page, text, c)),
            Err(e) => problems.push(format!("{page}: {e}")),
        }
    }
    let checked: usize = work.iter().map(|w| w.2.len()).sum();
    let results: Vec<Vec<Result<String, String>>> = std::thread::scope(|s| {
        let handles: Vec<_> = work.iter().map(|(_, _, c)| s.spawn(|| run_page(c))).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let mut blessed = Vec::new();
    for ((page, text, checked), outputs) in work.iter().zip(results) {
        let mut new_text = text.clone();
        // Bottom up, so that the lines of the blocks above stay where they are.
        for (c, output) in checked.iter().zip(outputs).rev() {
            let at = format!("{page}:{} (```{})", c.block.line, c.block.language);
            let output = match output {
                Ok(o) => o,
                Err(e) => {
                    problems.push(format!("{at}: its command failed:\n{}\n--- {e}", c.command));
                    continue;
                }
            };
            let diff = differences(&c.block.body, &output, c.block.line + 1);
            if diff.is_empty() {
                continue;
            }
            if blessing {
                new_text = replace_body(&new_text, c.block.line, &bless(&c.block.body, &output));
                blessed.push(at);
            } else {
                problems.push(format!("{at}: the block is not today's output of\n    {}\n{diff}", c.command.trim()));
            }
        }
        if blessing && &new_text != text {
            std::fs::write(root().join(page), new_text).unwrap();
        }
    }
    if !blessed.is_empty() {
        eprintln!("{BLESS}: rewrote {} blocks from today's outputs:\n{}", blessed.len(), blessed.join("\n"));
    }
    assert!(
        problems.is_empty(),
        "{} of {checked} checked output blocks:\n{}\n\nIf the change is meant, bless it: {BLESS}=1 cargo test --release \
         --test integration doc_outputs (rewrites the blocks from today's outputs; then read `git diff` on the pages)",
        problems.len(),
        problems.join("\n\n")
    );
    assert!(checked >= 10, "only {checked} checked output blocks found");
}

/// The comparator fails on one changed digit, and says where.
#[test]
fn doc_outputs_a_changed_digit_fails_the_comparison() {
    let output = "steps: 4506 to t = 3.0000 s\nF_c contact force [kN]               10635.9720\nwall time: 67.6 ms\n";
    let shown = "steps: 4506 to t = 3.0000 s\nF_c contact force [kN]               10635.9720\nwall time: [TIME]\n";
    assert!(matches(shown, output));
    let doctored = shown.replace("10635.9720", "10635.9721");
    assert!(!matches(&doctored, output));
    let diff = differences(&doctored, output, 41);
    assert!(diff.contains("line 42:") && diff.contains("10635.9721") && diff.contains("10635.9720"), "{diff}");
    // One digit of an integer, and a digit gone.
    assert!(!matches(&shown.replace("4506", "4507"), output));
    assert!(!matches(&shown.replace("3.0000", "3.000"), output));
}

/// The masks hide what they name and nothing else; `...` stands for any lines, none included.
#[test]
fn doc_outputs_masks_and_elisions_hide_only_what_they_name() {
    let output = "sweep: 5 scenarios on 2 threads in 0.13 s (51.4 ms of a thread each): 5 ran\nrows written\n";
    assert!(matches(
        "sweep: 5 scenarios on [COUNT] threads in [TIME] ([TIME] of a thread each): 5 ran\nrows written",
        output
    ));
    assert!(matches("sweep: [..]: 5 ran\n...", output));
    assert!(matches("...\nrows written", output));
    assert!(matches(
        "sweep: 5 scenarios on 2 threads in 0.13 s (51.4 ms of a thread each): 5 ran\n...\nrows written",
        output
    ));
    // Columns may widen: a run of spaces matches any run.
    assert!(matches(
        "sweep:  5 scenarios on 2 threads in 0.13 s (51.4 ms of a thread each): 5   ran\nrows written",
        output
    ));
    // Units in brackets are text, not masks.
    assert!(matches("F_c [N] 12 [MPa] 3", "F_c [N] 12 [MPa] 3"));
    assert!(!matches("F_c [N] 12", "F_c 7 12"));
    // A mask does not hide a number outside it, nor text.
    assert!(!matches(
        "sweep: 6 scenarios on [COUNT] threads in [TIME] ([TIME] of a thread each): 5 ran\nrows written",
        output
    ));
    assert!(!matches("sweep: 5 scenarios on [COUNT] threads in [TIME] ([TIME] of a thread each): 5 ran", output));
    assert!(!matches(
        "sweep: 5 scenarios on [COUNT] threads in [COUNT] s (51.4 ms of a thread each): 5 ran\nrows written",
        output
    ));
    assert!(!matches(
        "sweep: 5 scenarios on [TIME] cores in [TIME] ([TIME] of a thread each): 5 ran\nrows written",
        output
    ));
}

/// Bless rewrites a block's numbers from today's output and keeps its masks and elisions.
#[test]
fn doc_outputs_bless_keeps_masks_and_elisions() {
    let output = "head\nsteps: 4506 to t = 3.0000 s\nmiddle\nwall time: 67.6 ms (assembly)\nmore\ntail\n";
    let shown = "...\nsteps: 8873 to t = 3.0000 s\n  ...\nwall time: [TIME] (assembly)\n...";
    assert!(!matches(shown, output));
    let blessed = bless(shown, output);
    assert_eq!(blessed, "...\nsteps: 4506 to t = 3.0000 s\n  ...\nwall time: [TIME] (assembly)\n...");
    assert!(matches(&blessed, output));
    // A masked line whose other numbers moved keeps its mask.
    let blessed = bless("sweep: 4 ran in [TIME], 1 failed", "sweep: 5 ran in 2.1 s, 0 failed");
    assert_eq!(blessed, "sweep: 5 ran in [TIME], 0 failed");
    // Lines that no longer align: today's output in full.
    assert_eq!(bless("a 1\nb 2", "a 1\nc 2\nd 3"), "a 1\nc 2\nd 3");
    // A matching block is left as it is.
    assert_eq!(bless(shown.replace("8873", "4506").as_str(), output), shown.replace("8873", "4506"));
}

/// The markers this test reads, and the block it rewrites in place.
#[test]
fn doc_outputs_markers_and_rewriting() {
    assert_eq!(checked_command("output: the block above"), Some(None));
    assert_eq!(checked_command("output: `beam-impact --no-mcap`"), Some(Some("beam-impact --no-mcap".into())));
    assert_eq!(checked_command("output: beam-impact"), None);
    assert_eq!(checked_command("illustrative: a Python output"), None);
    let page = "# t\n\n```sh\nx\n```\n\n  ```text\n  old 1\n  old 2\n  ```\nafter\n";
    assert_eq!(
        replace_body(page, 7, "new 1\n\nnew 3"),
        "# t\n\n```sh\nx\n```\n\n  ```text\n  new 1\n\n  new 3\n  ```\nafter\n"
    );
}
