//! No circles between the source files (issue 19): if a.rs uses something from b.rs, b.rs uses
//! nothing from a.rs, directly or through other files. A newcomer can then read the files bottom
//! up, and a change to a file affects only the files above it.
//!
//! The graph is read from the text, not from the compiler: every `crate::`, `super::` and `self::`
//! path outside comments and string literals is resolved to the longest existing file:
//! `crate::a::b::Item` is `src/a/b.rs` or `src/a/b/mod.rs` if there is one, else `src/a.rs` or
//! `src/a/mod.rs`, else the crate's root. A `mod.rs` is a file of its own. The binary's files
//! (`main.rs` and the modules it declares) are a crate of their own: their `crate::` is
//! `main.rs`'s, and their `beam_impact::` paths go into the library. `use` groups (`crate::a::{b::X, Y}`) count each
//! of their paths; inline modules (`mod tests { use super::*; }`) move `super::` one level down,
//! so a file's own test module makes no edge (test modules are scanned like any other code). A
//! file's edges to itself are ignored. Doc links are comments and not counted (documentation may
//! point anywhere, up or down). The relative `pub use child::Item` of a `mod.rs` is not a
//! `crate::`/`super::` path and is not counted either.

use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::path::Path;

/// One edge: `from` uses `to` at `line` through `path`.
#[derive(Clone, Debug)]
struct Use {
    to: String,
    line: usize,
    path: String,
}

/// The file graph: for each file (relative to `src/`, with `/`), the files it uses.
type Graph = BTreeMap<String, BTreeMap<String, Use>>;

/// Every `.rs` file under `dir`, relative to `root`, with its text.
fn read_tree(root: &Path, dir: &Path, files: &mut BTreeMap<String, String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            read_tree(root, &path, files);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let name = path.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/");
            files.insert(name, std::fs::read_to_string(&path).unwrap());
        }
    }
}

/// The text with comments, string literals and character literals blanked (newlines kept, so
/// that line numbers stay).
fn code_only(text: &str) -> Vec<char> {
    let c: Vec<char> = text.chars().collect();
    let mut out = c.clone();
    let blank = |out: &mut Vec<char>, from: usize, to: usize| {
        for ch in &mut out[from..to.min(c.len())] {
            if *ch != '\n' {
                *ch = ' ';
            }
        }
    };
    let ident = |ch: char| ch.is_alphanumeric() || ch == '_';
    let mut i = 0;
    while i < c.len() {
        let at = |k: usize| c.get(k).copied().unwrap_or('\0');
        if c[i] == '/' && at(i + 1) == '/' {
            let end = (i..c.len()).find(|&k| c[k] == '\n').unwrap_or(c.len());
            blank(&mut out, i, end);
            i = end;
        } else if c[i] == '/' && at(i + 1) == '*' {
            // Block comments nest.
            let (mut k, mut depth) = (i + 2, 1);
            while k < c.len() && depth > 0 {
                if c[k] == '/' && at(k + 1) == '*' {
                    depth += 1;
                    k += 2;
                } else if c[k] == '*' && at(k + 1) == '/' {
                    depth -= 1;
                    k += 2;
                } else {
                    k += 1;
                }
            }
            blank(&mut out, i, k);
            i = k;
        } else if (c[i] == 'r' || (c[i] == 'b' && at(i + 1) == 'r'))
            && (i == 0 || !ident(c[i - 1]))
            && matches!(at(i + 1 + usize::from(c[i] == 'b')), '"' | '#')
        {
            // A raw string r"..", r#".."#, br#".."# (or an identifier starting with r).
            let mut k = i + 1 + usize::from(c[i] == 'b');
            let hashes = (k..c.len()).take_while(|&j| c[j] == '#').count();
            k += hashes;
            if at(k) != '"' {
                i += 1;
                continue;
            }
            k += 1;
            loop {
                if k >= c.len() {
                    break;
                }
                if c[k] == '"' && (1..=hashes).all(|h| at(k + h) == '#') {
                    k += 1 + hashes;
                    break;
                }
                k += 1;
            }
            blank(&mut out, i, k);
            i = k;
        } else if c[i] == '"' {
            let mut k = i + 1;
            while k < c.len() && c[k] != '"' {
                k += if c[k] == '\\' { 2 } else { 1 };
            }
            blank(&mut out, i, k + 1);
            i = k + 1;
        } else if c[i] == '\'' {
            // A character literal ('x', '\n', '\u{..}'); otherwise a lifetime or a label.
            if at(i + 1) == '\\' {
                let end = (i + 3..c.len()).find(|&k| c[k] == '\'').unwrap_or(c.len());
                blank(&mut out, i, end + 1);
                i = end + 1;
            } else if at(i + 2) == '\'' {
                blank(&mut out, i, i + 3);
                i += 3;
            } else {
                i += 1;
            }
        } else if ident(c[i]) {
            // Skip a whole identifier (so that `br` or `r` inside one is not a raw string).
            while i < c.len() && ident(c[i]) {
                i += 1;
            }
        } else {
            i += 1;
        }
    }
    out
}

/// The module path of a file: `record/mcap.rs` is `[record, mcap]`, `record/mod.rs` is
/// `[record]`, `lib.rs` and `main.rs` are the root.
fn module_of(file: &str) -> Vec<String> {
    let mut parts: Vec<String> = file.trim_end_matches(".rs").split('/').map(String::from).collect();
    if parts.last().is_some_and(|p| p == "mod") || file == "lib.rs" || file == "main.rs" {
        parts.pop();
    }
    parts
}

/// The top-level modules `main.rs` declares (`mod cli;`): the binary's own files.
fn binary_modules(files: &BTreeMap<String, String>) -> BTreeSet<String> {
    let Some(main) = files.get("main.rs") else { return BTreeSet::new() };
    let code = code_only(main);
    let mut cursor = Cursor { c: &code, i: 0 };
    let mut modules = BTreeSet::new();
    while cursor.i < code.len() {
        match cursor.ident() {
            Some(word) if word == "mod" => {
                cursor.skip_space();
                if let Some(name) = cursor.ident() {
                    cursor.skip_space();
                    if cursor.peek() == ';' {
                        modules.insert(name);
                    }
                }
            }
            Some(_) => {}
            None => cursor.i += 1,
        }
    }
    modules
}

/// Whether a file belongs to the binary crate rather than to the library.
fn in_binary(file: &str, binary: &BTreeSet<String>) -> bool {
    let top = file.split('/').next().unwrap_or(file).trim_end_matches(".rs");
    file == "main.rs" || binary.contains(top)
}

/// The file a path from a crate's root lands in (the binary's when `binary`): the longest
/// prefix that is a file of that crate, else the crate's root.
fn resolve(files: &BTreeMap<String, String>, modules: &BTreeSet<String>, binary: bool, segments: &[String]) -> String {
    for n in (1..=segments.len()).rev() {
        let stem = segments[..n].join("/");
        for candidate in [format!("{stem}.rs"), format!("{stem}/mod.rs")] {
            if files.contains_key(&candidate) && in_binary(&candidate, modules) == binary {
                return candidate;
            }
        }
    }
    if binary { "main.rs" } else { "lib.rs" }.into()
}

/// A cursor over blanked source text.
struct Cursor<'a> {
    c: &'a [char],
    i: usize,
}

impl Cursor<'_> {
    fn skip_space(&mut self) {
        while self.i < self.c.len() && self.c[self.i].is_whitespace() {
            self.i += 1;
        }
    }
    fn peek(&self) -> char {
        self.c.get(self.i).copied().unwrap_or('\0')
    }
    fn ident(&mut self) -> Option<String> {
        let start = self.i;
        while self.i < self.c.len() && (self.c[self.i].is_alphanumeric() || self.c[self.i] == '_') {
            self.i += 1;
        }
        (self.i > start).then(|| self.c[start..self.i].iter().collect())
    }
    /// Consumes `::` (with spaces around it) if it comes next.
    fn colons(&mut self) -> bool {
        let save = self.i;
        self.skip_space();
        if self.peek() == ':' && self.c.get(self.i + 1) == Some(&':') {
            self.i += 2;
            self.skip_space();
            true
        } else {
            self.i = save;
            false
        }
    }
    /// The paths of a path tree after `prefix::`: `a::b`, `a::{b, c::d}`, `*`.
    fn tree(&mut self, prefix: &[String], out: &mut Vec<Vec<String>>) {
        self.skip_space();
        if self.peek() == '{' {
            self.i += 1;
            loop {
                self.skip_space();
                match self.peek() {
                    '}' => {
                        self.i += 1;
                        break;
                    }
                    ',' => self.i += 1,
                    '\0' => break,
                    _ => {
                        let before = self.i;
                        self.tree(prefix, out);
                        // `as` aliases and anything unexpected: skip to the next item.
                        while !matches!(self.peek(), ',' | '}' | '\0') {
                            self.i += 1;
                        }
                        if self.i == before {
                            self.i += 1;
                        }
                    }
                }
            }
            return;
        }
        match self.ident() {
            Some(segment) => {
                let mut path = prefix.to_vec();
                path.push(segment);
                if self.colons() {
                    self.tree(&path, out);
                } else {
                    out.push(path);
                }
            }
            // `*`, `<T>` or the end of the path.
            None => out.push(prefix.to_vec()),
        }
    }
}

/// The files `file` uses, with where.
fn uses_of(files: &BTreeMap<String, String>, modules: &BTreeSet<String>, file: &str) -> Vec<Use> {
    let code = code_only(&files[file]);
    let home = module_of(file);
    let binary = in_binary(file, modules);
    let mut uses = Vec::new();
    // Inline modules open at a depth of braces: (name, depth inside it).
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut pending_mod: Option<String> = None;
    let mut depth = 0usize;
    let mut cursor = Cursor { c: &code, i: 0 };
    let mut previous_ident = String::new();
    while cursor.i < code.len() {
        let ch = cursor.peek();
        if ch == '{' {
            depth += 1;
            if let Some(name) = pending_mod.take() {
                inline.push((name, depth));
            }
            cursor.i += 1;
            continue;
        }
        if ch == '}' {
            if inline.last().is_some_and(|(_, d)| *d == depth) {
                inline.pop();
            }
            depth = depth.saturating_sub(1);
            cursor.i += 1;
            continue;
        }
        if ch == ';' {
            pending_mod = None;
        }
        let start = cursor.i;
        let after_colons = start >= 2 && code[start - 1] == ':' && code[start - 2] == ':';
        let Some(word) = cursor.ident() else {
            cursor.i += 1;
            continue;
        };
        if previous_ident == "mod" {
            pending_mod = Some(word.clone());
        }
        previous_ident.clone_from(&word);
        // `beam_impact::` is the library seen from the binary.
        let library = binary && word == "beam_impact";
        let root = word == "crate" || library;
        if after_colons || !(root || word == "super" || word == "self") {
            continue;
        }
        let mut module = home.clone();
        module.extend(inline.iter().map(|(name, _)| name.clone()));
        let mut base = if root { Vec::new() } else { module };
        if word == "super" {
            base.pop();
        }
        if !cursor.colons() {
            continue;
        }
        // Further `super::` go up again.
        loop {
            let save = cursor.i;
            if cursor.ident().as_deref() == Some("super") && cursor.colons() {
                base.pop();
            } else {
                cursor.i = save;
                break;
            }
        }
        let mut paths = Vec::new();
        cursor.tree(&base, &mut paths);
        let line = code[..start].iter().filter(|&&c| c == '\n').count() + 1;
        let text: String = code[start..cursor.i].iter().collect();
        for path in paths {
            let to = resolve(files, modules, binary && !library, &path);
            if to != file {
                uses.push(Use { to, line, path: text.split_whitespace().collect::<Vec<_>>().join(" ") });
            }
        }
    }
    uses
}

/// The graph of every file in `files`.
fn graph(files: &BTreeMap<String, String>) -> Graph {
    let modules = binary_modules(files);
    files
        .keys()
        .map(|file| {
            let mut edges = BTreeMap::new();
            for u in uses_of(files, &modules, file) {
                edges.entry(u.to.clone()).or_insert(u);
            }
            (file.clone(), edges)
        })
        .collect()
}

/// One group of files that reach each other (a strongly connected component of more than one
/// file) and its shortest circle through its first file.
#[derive(Debug)]
struct Circle {
    group: Vec<String>,
    files: Vec<String>,
}

/// Every group of files that reach each other, with a circle through it.
fn circles(graph: &Graph) -> Vec<Circle> {
    let reach = |from: &str| {
        let mut seen = BTreeSet::new();
        let mut queue = VecDeque::from([from.to_string()]);
        while let Some(f) = queue.pop_front() {
            for to in graph.get(&f).into_iter().flat_map(|e| e.keys()) {
                if seen.insert(to.clone()) {
                    queue.push_back(to.clone());
                }
            }
        }
        seen
    };
    let reachable: BTreeMap<&String, BTreeSet<String>> = graph.keys().map(|f| (f, reach(f))).collect();
    let mut done = BTreeSet::new();
    let mut found = Vec::new();
    for file in graph.keys() {
        if done.contains(file) || !reachable[file].contains(file) {
            continue;
        }
        let group: BTreeSet<String> =
            graph.keys().filter(|g| reachable[file].contains(*g) && reachable[*g].contains(file)).cloned().collect();
        done.extend(group.iter().cloned());
        // The shortest way back to `file` inside the group.
        let mut back: BTreeMap<String, String> = BTreeMap::new();
        let mut queue = VecDeque::from([file.clone()]);
        'search: while let Some(f) = queue.pop_front() {
            for to in graph[&f].keys().filter(|t| group.contains(*t)) {
                if to == file {
                    back.insert(file.clone(), f.clone());
                    break 'search;
                }
                if !back.contains_key(to) {
                    back.insert(to.clone(), f.clone());
                    queue.push_back(to.clone());
                }
            }
        }
        let mut circle = vec![file.clone()];
        let mut at = back[file].clone();
        while at != *file {
            circle.push(at.clone());
            at = back[&at].clone();
        }
        circle.push(file.clone());
        circle.reverse();
        found.push(Circle { group: group.into_iter().collect(), files: circle });
    }
    found
}

/// The circles as text: each edge with the line and path that makes it.
fn describe(graph: &Graph, circles: &[Circle]) -> String {
    let mut text = String::new();
    for circle in circles {
        text.push_str(&format!("circle: {}\n", circle.files.join(" -> ")));
        if circle.group.len() + 1 > circle.files.len() {
            text.push_str(&format!("  (the files that reach each other: {})\n", circle.group.join(", ")));
        }
        for pair in circle.files.windows(2) {
            let u = &graph[&pair[0]][&pair[1]];
            text.push_str(&format!("  src/{}:{} uses src/{} through `{}`\n", pair[0], u.line, u.to, u.path));
        }
    }
    text
}

#[test]
fn the_source_files_use_each_other_without_circles() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = BTreeMap::new();
    read_tree(&src, &src, &mut files);
    let graph = graph(&files);
    // The scan sees the uses (a scanner that found none would find no circle either).
    let edges: usize = graph.values().map(|e| e.len()).sum();
    assert!(files.len() > 50 && edges > 2 * files.len(), "{} files, {edges} uses: the scan is broken", files.len());
    assert!(graph["fmi/instance.rs"].contains_key("simulation.rs"));
    let found = circles(&graph);
    assert!(found.is_empty(), "the source files use each other in circles:\n{}", describe(&graph, &found));
}

#[test]
fn the_scan_finds_a_circle_and_not_what_is_not_code() {
    let files: BTreeMap<String, String> = [
        ("lib.rs", "pub mod a;\npub mod b;\npub mod c;\n"),
        ("a/mod.rs", "pub mod x;\npub mod y;\n"),
        // x -> y through a `use` group; the test module's `super::*` is x itself.
        ("a/x.rs", "use super::{y::Y, Z};\npub struct X;\n#[cfg(test)]\nmod tests {\n    use super::*;\n}\n"),
        // y -> c through a call; the comment and the strings name b and are not code.
        (
            "a/y.rs",
            "// crate::b::B\n/// [`crate::b`]\npub struct Y;\nfn f() -> u32 { let _ = \"crate::b\"; let _ = r#\"super::super::b\"#; \
             let _ = 'c'; crate::c::g() }\n",
        ),
        // c -> x: the circle x -> y -> c -> x.
        ("c.rs", "pub fn g() -> u32 { let _: &'static str = \"\"; let _ = crate::a::x::X; 1 }\n"),
        ("b.rs", "use super::a::y::Y;\n"),
        // The binary: its `crate::` is main.rs's, `beam_impact::` is the library.
        ("main.rs", "mod cli;\nuse cli::run;\nfn main() { beam_impact::b::go() }\n"),
        ("cli/mod.rs", "pub mod run;\npub struct Thing;\n"),
        ("cli/run.rs", "use beam_impact::a::x::X;\nuse crate::cli::Thing;\nfn f() { crate::c::g() }\n"),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v.to_string()))
    .collect();
    let graph = graph(&files);
    let targets = |f: &str| graph[f].keys().cloned().collect::<Vec<_>>();
    assert_eq!(targets("a/x.rs"), ["a/mod.rs", "a/y.rs"]);
    assert_eq!(targets("a/y.rs"), ["c.rs"]);
    assert_eq!(targets("c.rs"), ["a/x.rs"]);
    assert_eq!(targets("b.rs"), ["a/y.rs"]);
    assert!(targets("lib.rs").is_empty() && targets("a/mod.rs").is_empty());
    assert_eq!(targets("main.rs"), ["b.rs"]);
    // `crate::c` is not the library's c.rs from the binary: no such file there, its root.
    assert_eq!(targets("cli/run.rs"), ["a/x.rs", "cli/mod.rs", "main.rs"]);
    let found = circles(&graph);
    assert_eq!(found.len(), 1, "{}", describe(&graph, &found));
    assert_eq!(found[0].files, ["a/x.rs", "a/y.rs", "c.rs", "a/x.rs"]);
    assert!(describe(&graph, &found).contains("src/a/y.rs:4 uses src/c.rs through `crate::c::g`"));
}
