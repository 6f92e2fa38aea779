//! The README and the pages of `docs/` (issue 31, item 5; issue 41, item 3): every command a page
//! shows is run by a test or marked as not run here, with why; every output a page shows is
//! today's, compared by tests/doc_outputs.rs, or marked illustrative; every relative link and
//! `#anchor` resolves; the README stays a five-minute read that starts with the project's two
//! set-up commands.
//!
//! A fenced block of commands (`sh`, `python`, `js`, ...) carries a marker on the line before it:
//!
//! - `<!-- run by PATH: how -->`: the test file PATH runs it. PATH must exist and name the page,
//!   or the marker itself: the runners of `tests/examples.rs` and `tests/python/test_doc_snippets.py`
//!   find their blocks by this very marker, so a block they are named for is a block they run;
//! - `<!-- not run here: why -->`: shown, not run, and the reason says why;
//!
//! or its page says `<!-- page run by PATH -->` (a page whose every block a test executes in
//! order, as `tests/python/test_tutorial.py` does `docs/tutorial.md`'s).
//!
//! A block of output (`text`, `json`, `csv`) carries one of these (tests/doc_outputs.rs has the
//! details: how the commands run, the masks `[..]`, `[TIME]`, `[COUNT]`, `[DATE]`, `[PATH]`, `[HASH]`
//! and `...` for the volatile parts):
//!
//! - `<!-- output: the block above -->`: tests/doc_outputs.rs runs the ```sh block just above and
//!   compares its output with the block;
//! - ``<!-- output: `COMMAND` -->``: the same with COMMAND;
//! - `<!-- illustrative: why -->`: not compared, and the reason says why.
//!
//! The pages of `PAGES_NOT_YET_UNDER_OUTPUT_MARKERS` are not yet held to this. Blocks of input data
//! (`toml`, `xml`) need no marker; a scenario shown (```toml) must be one the program reads. Prose
//! that quotes a run's numbers quotes a checked block, or says where and when it was measured
//! (times: `beam-impact bench` on a named machine, dated) after an `<!-- illustrative: why -->`.
//!
//! **When a number moves** (a change to the physics, the log, the output's wording), the output
//! test fails naming the page, the line and both texts; if the change is meant, bless it:
//!
//! ```sh
//! BEAM_IMPACT_BLESS=1 cargo test --release --test integration doc_outputs
//! git diff README.md docs/      # read what moved, and the prose around it
//! ```

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The info strings of blocks that hold commands or code a reader would run.
const COMMAND_LANGUAGES: &[&str] = &["sh", "bash", "shell", "console", "python", "py", "js", "javascript", "ps1"];
/// The info strings of blocks that show data or output: nothing to run.
const DATA_LANGUAGES: &[&str] = &["text", "toml", "json", "csv", "xml"];
/// The info strings of blocks that show a program's output: compared by tests/doc_outputs.rs, or
/// marked illustrative.
const OUTPUT_LANGUAGES: &[&str] = &["text", "json", "csv"];

/// Pages whose output blocks need no marker yet (issue 41, item 3): other branches edit them while
/// the output markers come in. Bring a page under the rule by marking its output blocks and
/// removing it from here; a listed page whose output blocks are all marked (one at least) is a test
/// failure (its entry is stale).
pub(crate) const PAGES_NOT_YET_UNDER_OUTPUT_MARKERS: &[&str] =
    &["docs/logs.md", "docs/python.md", "docs/python-reference.md", "docs/wheels.md"];

/// Pages other branches write, linked from the README before they are merged (issue 31). A page
/// listed here that exists is a test failure: its entry is then stale and must go.
const PENDING_PAGES: &[&str] = &[];

/// The README at most this long (issue 31: "a README of at most about 250 lines").
const README_MAX_LINES: usize = 250;

pub(crate) fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every `docs/*.md`, as paths relative to the repository root, sorted.
pub(crate) fn pages() -> Vec<String> {
    let mut pages = vec!["README.md".to_string()];
    let mut docs: Vec<String> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .map(|p| format!("docs/{}", p.file_name().unwrap().to_string_lossy()))
        .collect();
    docs.sort();
    pages.extend(docs);
    pages
}

/// One fenced block of a page.
#[derive(Debug, Clone)]
pub(crate) struct Block {
    /// 1-based line of the opening fence.
    pub line: usize,
    /// The info string's first word (`sh` of "```sh setup").
    pub language: String,
    /// The marker comment on the nearest non-blank line before the fence, without `<!--` `-->`.
    pub marker: Option<String>,
    pub body: String,
}

/// The fenced blocks of a Markdown text (``` fences, indented or not), in order.
pub(crate) fn blocks(text: &str) -> Vec<Block> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let trimmed = lines[i].trim_start();
        if let Some(info) = trimmed.strip_prefix("```") {
            let indent = lines[i].len() - trimmed.len();
            let start = i;
            let mut body = Vec::new();
            i += 1;
            while i < lines.len() && !lines[i].trim_start().starts_with("```") {
                body.push(lines[i].get(indent..).unwrap_or(lines[i].trim_start()));
                i += 1;
            }
            let marker = lines[..start]
                .iter()
                .rev()
                .find(|l| !l.trim().is_empty())
                .and_then(|l| l.trim().strip_prefix("<!--"))
                .and_then(|l| l.strip_suffix("-->"))
                .map(|m| m.trim().to_string());
            out.push(Block {
                line: start + 1,
                language: info.split_whitespace().next().unwrap_or("").to_string(),
                marker,
                body: body.join("\n"),
            });
        }
        i += 1;
    }
    out
}

/// The test file a block's own marker names (`run by PATH...`).
fn run_by(marker: &str) -> Option<&str> {
    let rest = marker.strip_prefix("run by ")?;
    Some(rest.split([':', ' ']).next().unwrap_or(rest))
}

/// The blocks of every page whose marker says `run by <runner>`: (page, block).
pub(crate) fn blocks_run_by(runner: &str) -> Vec<(String, Block)> {
    let mut out = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(root().join(&page)).unwrap();
        for block in blocks(&text) {
            if block.marker.as_deref().and_then(run_by) == Some(runner) {
                out.push((page.clone(), block));
            }
        }
    }
    out
}

/// `<!-- page run by PATH -->` anywhere in a page.
fn page_runner(text: &str) -> Option<&str> {
    text.lines().find_map(|l| l.trim().strip_prefix("<!-- page run by ")?.strip_suffix("-->").map(str::trim))
}

/// Why a command block is accounted for, or what is wrong with it.
fn account(page: &str, page_text: &str, block: &Block) -> Result<(), String> {
    let at = format!("{page}:{} (```{})", block.line, block.language);
    let runner = match block.marker.as_deref() {
        Some(m) if m.starts_with("not run here:") => {
            let why = m["not run here:".len()..].trim();
            // A reason, not a token: a few words at least.
            return if why.split_whitespace().count() >= 3 {
                Ok(())
            } else {
                Err(format!("{at}: `not run here:` needs a reason, got {why:?}"))
            };
        }
        Some(m) if run_by(m).is_some() => run_by(m).unwrap(),
        _ => match page_runner(page_text) {
            Some(runner) => runner,
            None => {
                return Err(format!(
                    "{at}: a command block with no marker: put `<!-- run by tests/FILE: how -->` (a test that \
                     runs it) or `<!-- not run here: why -->` on the line before its fence"
                ))
            }
        },
    };
    let path = root().join(runner);
    let runner_text =
        std::fs::read_to_string(&path).map_err(|e| format!("{at}: its runner {runner} cannot be read: {e}"))?;
    // The runner names the page it runs (a path, or the README by name), or finds its blocks by
    // this marker (it then names the marker: `run by PATH`).
    let name = if page == "README.md" { "README" } else { page };
    if !runner_text.contains(name) && !runner_text.contains(&format!("run by {runner}")) {
        return Err(format!(
            "{at}: its runner {runner} names neither {name} nor the marker `run by {runner}`, so it cannot be \
             running it"
        ));
    }
    Ok(())
}

/// Issue 31: "Every command a page shows is run by the tests (as the tutorial's are) or marked as
/// not run here, with why."
#[test]
fn every_command_a_page_shows_is_run_by_a_test_or_marked_not_run_here() {
    let mut problems = Vec::new();
    let mut commands = 0;
    for page in pages() {
        let text = std::fs::read_to_string(root().join(&page)).unwrap();
        for block in blocks(&text) {
            if DATA_LANGUAGES.contains(&block.language.as_str()) {
                continue;
            }
            if !COMMAND_LANGUAGES.contains(&block.language.as_str()) {
                problems.push(format!(
                    "{page}:{}: a block of language {:?}: name it (one of {COMMAND_LANGUAGES:?} for commands, \
                     {DATA_LANGUAGES:?} for data)",
                    block.line, block.language
                ));
                continue;
            }
            commands += 1;
            if let Err(e) = account(&page, &text, &block) {
                problems.push(e);
            }
        }
    }
    assert!(problems.is_empty(), "{} of {commands} command blocks:\n{}", problems.len(), problems.join("\n"));
    // The README and the tutorial show commands: the scan sees them.
    assert!(commands >= 15, "only {commands} command blocks found");
}

/// Why an output block is accounted for, or what is wrong with it.
fn account_output(page: &str, all: &[Block], n: usize) -> Result<(), String> {
    let block = &all[n];
    let at = format!("{page}:{} (```{})", block.line, block.language);
    match block.marker.as_deref() {
        Some(m) if m.starts_with("illustrative:") => {
            let why = m["illustrative:".len()..].trim();
            if why.split_whitespace().count() >= 3 {
                Ok(())
            } else {
                Err(format!("{at}: `illustrative:` needs a reason, got {why:?}"))
            }
        }
        Some(m) => match crate::doc_outputs::checked_command(m) {
            Some(None) if n > 0 && matches!(all[n - 1].language.as_str(), "sh" | "bash") => Ok(()),
            Some(None) => Err(format!("{at}: `output: the block above` with no ```sh block just above")),
            Some(Some(_)) => Ok(()),
            None => Err(format!("{at}: the marker `{m}` is neither `output: ...` nor `illustrative: why`")),
        },
        None => Err(format!(
            "{at}: an output block with no marker: put `<!-- output: the block above -->` (tests/doc_outputs.rs runs \
             the ```sh block above and compares), ``<!-- output: `COMMAND` -->`` or `<!-- illustrative: why -->` on \
             the line before its fence"
        )),
    }
}

/// Issue 41: "Every output a page shows is produced by the tests and compared, or marked as
/// illustrative": every output block of the README and the docs (but the pages still to be brought
/// under the rule) carries `output: ...` (tests/doc_outputs.rs compares it) or `illustrative: why`.
#[test]
fn every_output_a_page_shows_is_checked_or_marked_illustrative() {
    let mut problems = Vec::new();
    let (mut outputs, mut checked) = (0, 0);
    for page in pages() {
        let text = std::fs::read_to_string(root().join(&page)).unwrap();
        let all = blocks(&text);
        let pending = PAGES_NOT_YET_UNDER_OUTPUT_MARKERS.contains(&page.as_str());
        let (mut marked, mut unmarked) = (0, 0);
        for n in 0..all.len() {
            if !OUTPUT_LANGUAGES.contains(&all[n].language.as_str()) {
                continue;
            }
            outputs += 1;
            if all[n].marker.as_deref().and_then(crate::doc_outputs::checked_command).is_some() {
                checked += 1;
            }
            if let Err(e) = account_output(&page, &all, n) {
                unmarked += 1;
                if !pending {
                    problems.push(e);
                }
            } else {
                marked += 1;
            }
        }
        if pending && marked > 0 && unmarked == 0 {
            problems.push(format!(
                "{page}: every output block is marked now: remove it from PAGES_NOT_YET_UNDER_OUTPUT_MARKERS in \
                 tests/docs.rs"
            ));
        }
    }
    for page in PAGES_NOT_YET_UNDER_OUTPUT_MARKERS {
        assert!(root().join(page).exists(), "{page} is gone: remove it from PAGES_NOT_YET_UNDER_OUTPUT_MARKERS");
    }
    assert!(problems.is_empty(), "{} of {outputs} output blocks:\n{}", problems.len(), problems.join("\n"));
    assert!(checked >= 10, "only {checked} of {outputs} output blocks are checked");
}

/// The markers themselves: a block with a stray or misspelt marker would otherwise count as
/// unmarked only by luck. A command block's marker is `run by` or `not run here`; an output
/// block's `output:` or `illustrative:`.
#[test]
fn a_marker_is_one_of_the_forms_its_block_takes() {
    for page in pages() {
        let text = std::fs::read_to_string(root().join(&page)).unwrap();
        for block in blocks(&text) {
            if let Some(m) = &block.marker {
                let command_marker = m.starts_with("not run here:") || run_by(m).is_some();
                let output_marker = m.starts_with("illustrative:") || crate::doc_outputs::checked_command(m).is_some();
                let output_block = OUTPUT_LANGUAGES.contains(&block.language.as_str());
                assert!(
                    if output_block { output_marker } else { command_marker },
                    "{page}:{} (```{}): the comment before the block is `{m}`: a marker is `run by PATH: how` or \
                     `not run here: why` before commands, `output: the block above`, ``output: `COMMAND` `` or \
                     `illustrative: why` before an output",
                    block.line,
                    block.language
                );
            }
        }
    }
}

/// GitHub's anchor of a heading: lower case, punctuation other than `-` and `_` dropped, spaces
/// to `-` (a repeated heading gets `-1`, `-2`, ...).
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | ' '))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of a Markdown page: its headings' slugs (outside code blocks).
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut out = BTreeSet::new();
    let mut in_code = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if in_code {
            continue;
        }
        if let Some(h) = line.strip_prefix('#') {
            let h = h.trim_start_matches('#');
            if h.starts_with(' ') {
                let base = slug(h);
                let mut anchor = base.clone();
                let mut n = 0;
                while !seen.insert(anchor.clone()) {
                    n += 1;
                    anchor = format!("{base}-{n}");
                }
                out.insert(anchor);
            }
        }
    }
    out
}

/// The targets of a page's Markdown links and images, outside code (fenced blocks and `spans`).
fn link_targets(text: &str) -> Vec<String> {
    let mut prose = String::new();
    let mut in_code = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if !in_code {
            // Inline code spans dropped: `a](b)` inside backticks is not a link.
            let mut in_span = false;
            for c in line.chars() {
                if c == '`' {
                    in_span = !in_span;
                } else if !in_span {
                    prose.push(c);
                }
            }
            prose.push('\n');
        }
    }
    // A link's text may span lines; its target may not.
    let mut out = Vec::new();
    let mut rest = prose.as_str();
    while let Some(i) = rest.find("](") {
        let after = &rest[i + 2..];
        match after.find(')') {
            Some(j) if !after[..j].contains('\n') => out.push(after[..j].trim().to_string()),
            _ => {}
        }
        rest = after;
    }
    out
}

/// Issue 31: "Check rendered Markdown links resolve": every relative link of the README and the
/// docs names an existing file, and its `#anchor` an existing heading.
#[test]
fn every_relative_link_and_anchor_resolves() {
    let mut problems = Vec::new();
    let mut checked = 0;
    for page in pages() {
        let text = std::fs::read_to_string(root().join(&page)).unwrap();
        let dir = Path::new(&page).parent().unwrap().to_path_buf();
        for target in link_targets(&text) {
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            checked += 1;
            let (file, anchor) = match target.split_once('#') {
                Some((f, a)) => (f, Some(a)),
                None => (target.as_str(), None),
            };
            let rel: PathBuf = if file.is_empty() { PathBuf::from(&page) } else { normalise(&dir.join(file)) };
            let rel_str = rel.to_string_lossy().to_string();
            let path = root().join(&rel);
            if !path.exists() {
                if PENDING_PAGES.contains(&rel_str.as_str()) {
                    continue;
                }
                problems.push(format!("{page}: ({target}): {rel_str} does not exist"));
                continue;
            }
            if let Some(anchor) = anchor {
                if rel_str.ends_with(".md") {
                    let anchors = anchors(&std::fs::read_to_string(&path).unwrap());
                    if !anchors.contains(anchor) {
                        problems.push(format!("{page}: ({target}): {rel_str} has no heading #{anchor}"));
                    }
                }
            }
        }
    }
    for pending in PENDING_PAGES {
        assert!(
            !root().join(pending).exists(),
            "{pending} exists now: remove it from PENDING_PAGES in tests/docs.rs so its links are checked"
        );
    }
    assert!(problems.is_empty(), "{} broken links:\n{}", problems.len(), problems.join("\n"));
    assert!(checked >= 30, "only {checked} relative links found");
}

/// `a/b/../c` -> `a/c` (no file system access: the target may not exist).
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// The project's rules for its front page: at most about 250 lines, and at its top exactly two
/// set-up commands, one running the main job and one running every test (the one `.ci/run` calls).
#[test]
fn the_readme_is_short_and_opens_with_the_two_set_up_commands() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let lines = readme.lines().count();
    assert!(lines <= README_MAX_LINES, "README.md has {lines} lines, at most {README_MAX_LINES}");
    let first = &blocks(&readme)[0];
    // Before it only the title and the block's marker.
    let before: Vec<&str> = readme.lines().take(first.line - 1).filter(|l| !l.trim().is_empty()).collect();
    assert!(before.len() <= 2 && before[0].starts_with("# "), "the README opens with its commands: {before:?}");
    let commands: Vec<&str> =
        first.body.lines().map(|l| l.split('#').next().unwrap().trim()).filter(|l| !l.is_empty()).collect();
    assert_eq!(commands, ["cargo run --release", "tests/run_all.sh"], "the two set-up commands");
    let ci = std::fs::read_to_string(root().join(".ci/run")).unwrap();
    assert!(ci.lines().any(|l| l.trim() == "tests/run_all.sh"), ".ci/run calls the README's test command");
}

/// The slug and the link scanner on the forms the pages use.
#[test]
fn slugs_and_links_follow_githubs_rules() {
    assert_eq!(
        slug(" Results against the paper (paper scenario, `cargo run --release`)"),
        "results-against-the-paper-paper-scenario-cargo-run---release"
    );
    assert_eq!(
        slug(" Answers an engineer can sign: converged, checked"),
        "answers-an-engineer-can-sign-converged-checked"
    );
    let a = anchors("# T\n## A b\n```sh\n# not a heading\n```\n## A b\n");
    assert_eq!(a, ["a-b", "a-b-1", "t"].iter().map(|s| s.to_string()).collect());
    let links = link_targets("see [x](a.md#b) and `[y](not/a/link)`, ![i](p.png)\n```\n[z](code)\n```\n[w\nv](c.md)");
    assert_eq!(links, ["a.md#b", "p.png", "c.md"]);
}

/// A scenario a page shows is one the program reads: every ```toml block of the README and the
/// docs parses as a scenario (unknown fields are refused), and one without a `[motion]` file (which
/// the page's own folder does not hold) validates as well, its `[sea] raos` read from `examples/`
/// (where the example vessel's RAO file is).
#[test]
fn every_scenario_a_page_shows_is_read_by_the_program() {
    let mut shown = 0;
    for page in pages() {
        let text = std::fs::read_to_string(root().join(&page)).unwrap();
        for block in blocks(&text).into_iter().filter(|b| b.language == "toml") {
            let at = format!("{page}:{}", block.line);
            let scenario = beam_impact::Scenario::from_toml(&block.body, &at).unwrap_or_else(|e| panic!("{e}"));
            if scenario.motion.file.is_empty() {
                let examples = root().join("examples");
                let scenario = match scenario.sea {
                    Some(_) => beam_impact::scenario_file::from_text(&block.body, &at, &examples, &mut Vec::new())
                        .unwrap_or_else(|e| panic!("{at}: {e}")),
                    None => scenario,
                };
                scenario.validate().unwrap_or_else(|e| panic!("{at}: {e}"));
            }
            shown += 1;
        }
    }
    assert!(shown >= 2, "{shown} scenarios shown");
}

/// Issue 41: docs/cli.md lists every subcommand `beam-impact --help` lists (`completions` was
/// missing from it), each as `beam-impact NAME` in its table of commands.
#[test]
fn the_cli_page_lists_every_subcommand() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact")).arg("--help").output().unwrap();
    assert!(out.status.success());
    let help = String::from_utf8(out.stdout).unwrap();
    let commands = help.split("Commands:\n").nth(1).unwrap().split("\n\n").next().unwrap();
    let names: Vec<&str> =
        commands.lines().filter_map(|l| l.split_whitespace().next()).filter(|n| *n != "help").collect();
    assert!(names.contains(&"sweep") && names.contains(&"completions"), "{names:?}");
    let page = std::fs::read_to_string(root().join("docs/cli.md")).unwrap();
    for name in names {
        let listed =
            page.lines().any(|l| l.starts_with("| `beam-impact") && l.contains(&format!("`beam-impact {name}")));
        assert!(listed, "docs/cli.md's table of commands does not list `beam-impact {name}`");
    }
}
