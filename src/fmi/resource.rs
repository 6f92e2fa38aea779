//! The FMU's resource location: FMI 2 gives a URI (`file:///a/b`, `file:///a/b/`, `file:/a/b`,
//! `file://localhost/a/b`, percent-encoded), FMI 3 a plain path with a trailing `/`.
//!
//! On Windows the URI's path is a drive path (`file:///C:/a/b`, `file:/C:/a/b`, `file:///C|/a/b`,
//! `file://localhost/C:/a/b`: the slash before the drive letter is dropped) or a share
//! (`file://server/share/a`: `\\server\share\a`), and FMI 3's path may end in `\`. The
//! parsing is plain string logic, tested for both platforms on either ([`parse_uri_for`]).
//!
//! The one resource the FMU reads is its starting scenario, `scenario.toml` ([`read_scenario`],
//! issue 30): what `beam-impact pack --scenario FILE.toml` packs, so that beams of sections (which
//! no scalar parameter can state, FMI 2 having no arrays) reach the FMU. Without it the FMU
//! starts from the paper scenario, as every FMU before it.

use std::path::{Path, PathBuf};

use crate::error::{bounded_line, Error};
use crate::Scenario;

pub use super::description::SCENARIO_RESOURCE;

/// Largest `resources/scenario.toml` the FMU reads, bytes, checked from the file's size before
/// it is read and again while reading: `pack` writes a few kB (32 sections on each beam, the
/// most a scenario has, take about 20 kB); a file of 1 MiB is no scenario of this model.
pub const MAX_SCENARIO_RESOURCE_BYTES: u64 = 1 << 20;

/// The FMU's starting scenario from the bytes of `resources/scenario.toml`: at most
/// [`MAX_SCENARIO_RESOURCE_BYTES`], UTF-8, a scenario file that validates, and nothing an FMU
/// takes otherwise (the supports' motion is its inputs, not a file). An error is one line of
/// bounded length, starting with `resources/scenario.toml:`.
pub fn scenario_from_bytes(bytes: &[u8]) -> Result<Scenario, String> {
    let fail = |detail: String| bounded_line(&format!("resources/{SCENARIO_RESOURCE}: {detail}"));
    if bytes.len() as u64 > MAX_SCENARIO_RESOURCE_BYTES {
        return Err(fail(format!(
            "{} bytes, larger than {MAX_SCENARIO_RESOURCE_BYTES} bytes (the limit; beam-impact pack --scenario \
             writes a few kB)",
            bytes.len()
        )));
    }
    let text = std::str::from_utf8(bytes).map_err(|e| fail(format!("not UTF-8 text ({e})")))?;
    let scenario = Scenario::from_toml(text, &format!("resources/{SCENARIO_RESOURCE}")).map_err(|e| match e {
        // The parser's errors name the file already; validation's name the field.
        Error::Scenario { .. } => bounded_line(&e.to_string()),
        e => fail(e.to_string()),
    })?;
    if !scenario.motion.is_unset() {
        return Err(fail(
            "[motion] is not for an FMU: the supports' motion is its inputs (upper.hinge_heave, \
             lower.clamp_heave, lower.clamp_rotation and their rates), set by the importer"
                .to_string(),
        ));
    }
    if scenario.sea.is_some() {
        return Err(fail(
            "[sea] is not for an FMU: the supports' motion is its inputs (upper.hinge_heave, lower.clamp_heave, \
             lower.clamp_rotation and their rates), set by the importer"
                .to_string(),
        ));
    }
    Ok(scenario)
}

/// The FMU's starting scenario from its resource directory `dir`: `None` when the directory holds
/// no `scenario.toml` (the paper scenario, as every FMU without one); the scenario of
/// [`scenario_from_bytes`] otherwise. The file must be a regular one (not a link, a FIFO or a
/// device) of at most [`MAX_SCENARIO_RESOURCE_BYTES`], refused from its size before it is read
/// and bounded while read. An error is one line of bounded length.
pub fn read_scenario(dir: &Path) -> Result<Option<Scenario>, String> {
    use std::io::Read;
    let path = dir.join(SCENARIO_RESOURCE);
    let file = match crate::record::output::open_regular_input(&path, "cannot read the FMU's starting scenario") {
        Ok(file) => file,
        // No such file, or a resource location that is no folder: no starting scenario, as before.
        Err(Error::Io { source, .. })
            if matches!(source.kind(), std::io::ErrorKind::NotFound | std::io::ErrorKind::NotADirectory) =>
        {
            return Ok(None)
        }
        Err(e) => return Err(bounded_line(&e.to_string())),
    };
    let fail =
        |e: std::io::Error| bounded_line(&format!("cannot read the FMU's starting scenario {}: {e}", path.display()));
    let size = file.metadata().map_err(fail)?.len();
    let mut bytes = Vec::with_capacity(usize::try_from(size.min(MAX_SCENARIO_RESOURCE_BYTES)).unwrap_or(0));
    // One byte more than the limit: a file that grew since its size was read is refused too.
    let limit = if size > MAX_SCENARIO_RESOURCE_BYTES { 0 } else { MAX_SCENARIO_RESOURCE_BYTES + 1 };
    file.take(limit).read_to_end(&mut bytes).map_err(fail)?;
    if size > MAX_SCENARIO_RESOURCE_BYTES || bytes.len() as u64 > MAX_SCENARIO_RESOURCE_BYTES {
        return Err(bounded_line(&format!(
            "resources/{SCENARIO_RESOURCE}: {} bytes, larger than {MAX_SCENARIO_RESOURCE_BYTES} bytes (the limit; \
             beam-impact pack --scenario writes a few kB)",
            size.max(bytes.len() as u64)
        )));
    }
    scenario_from_bytes(&bytes).map(Some)
}

/// Parses an FMI 2 `fmuResourceLocation` into a directory path. Returns `None` for schemes other
/// than `file` or a remote host (the FMU does not need its resources, so this is not an error).
pub fn parse_uri(uri: &str) -> Option<PathBuf> {
    parse_uri_for(uri, cfg!(windows)).map(PathBuf::from)
}

/// [`parse_uri`] as a string, for Windows (`windows`) or Unix: the directory with a trailing
/// separator.
pub fn parse_uri_for(uri: &str, windows: bool) -> Option<String> {
    let rest = uri.strip_prefix("file:").or_else(|| uri.strip_prefix("FILE:"))?;
    let path = if let Some(authority_and_path) = rest.strip_prefix("//") {
        // file://host/path: only an empty host or localhost is local.
        let slash = authority_and_path.find('/').unwrap_or(authority_and_path.len());
        let (host, path) = authority_and_path.split_at(slash);
        if !(host.is_empty() || host.eq_ignore_ascii_case("localhost")) {
            // A share on another machine: a path Windows opens (`\\host\share\...`), none on Unix.
            if !windows || path.len() <= 1 {
                return None;
            }
            let decoded = percent_decode(path)?;
            return Some(format!("\\\\{host}{}\\", decoded.trim_end_matches('/').replace('/', "\\")));
        }
        path
    } else {
        rest
    };
    if path.is_empty() {
        return None;
    }
    let decoded = percent_decode(path)?;
    if windows {
        // `/C:/a`, `/C|/a` (the old form) -> `C:\a`.
        let drive = decoded.strip_prefix('/').unwrap_or(&decoded);
        let b = drive.as_bytes();
        if b.len() >= 2 && b[0].is_ascii_alphabetic() && (b[1] == b':' || b[1] == b'|') {
            // `C:` alone would be the drive's current folder: `C:\\` is its root.
            let path = format!("{}:{}", &drive[..1], &drive[2..]).replace('/', "\\");
            return Some(format!("{}\\", path.trim_end_matches('\\')));
        }
        return Some(format!("{}\\", decoded.trim_end_matches('/').replace('/', "\\")));
    }
    // As `PathBuf::from(trimmed).join("")`: a trailing `/` unless the path is empty.
    let trimmed = decoded.trim_end_matches('/');
    Some(if trimmed.is_empty() { String::new() } else { format!("{trimmed}/") })
}

/// FMI 3's `resourcePath`: a plain path (normally with a trailing separator; `\` too on Windows).
/// Empty means none.
pub fn parse_path(path: &str) -> Option<PathBuf> {
    let separators: &[char] = if cfg!(windows) { &['/', '\\'] } else { &['/'] };
    (!path.is_empty()).then(|| PathBuf::from(path.trim_end_matches(separators)).join(""))
}

/// Checks the token an importer gives (`what`: `fmuGUID` or `instantiationToken`) against the one
/// of this binary with the starting scenario `packed` ([`super::description::token_for`]); the
/// error says which of the two does not fit.
pub fn check_token(what: &str, given: &str, packed: Option<&Scenario>) -> Result<(), String> {
    let expected = super::description::token_for(packed);
    if given == expected {
        return Ok(());
    }
    let given = bounded_line(given);
    Err(match packed {
        None => format!(
            "{what} \"{given}\" does not match this binary's \"{expected}\" (modelDescription.xml from another build, \
             or of an FMU packed with a scenario whose resources/{SCENARIO_RESOURCE} is missing?)"
        ),
        Some(_) => format!(
            "{what} \"{given}\" does not match \"{expected}\", this binary's with the starting scenario of \
             resources/{SCENARIO_RESOURCE} (modelDescription.xml from another build, or a {SCENARIO_RESOURCE} \
             changed or added by hand? `beam-impact pack --scenario FILE.toml` writes both)"
        ),
    })
}

/// Decodes `%XX` escapes; `None` on a malformed escape or invalid UTF-8.
pub fn percent_decode(text: &str) -> Option<String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = text.get(i + 1..i + 3)?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Option<PathBuf> {
        Some(PathBuf::from(s))
    }

    #[test]
    fn every_form_of_file_uri() {
        // The forms importers send (see FMI-AND-MCAP-NOTES.md): fmpy, others, the short form.
        assert_eq!(parse_uri("file:///tmp/x/resources"), p("/tmp/x/resources/"));
        assert_eq!(parse_uri("file:///tmp/x/resources/"), p("/tmp/x/resources/"));
        assert_eq!(parse_uri("file:/tmp/x/resources"), p("/tmp/x/resources/"));
        assert_eq!(parse_uri("file://localhost/tmp/x"), p("/tmp/x/"));
        assert_eq!(parse_uri("file:///tmp/my%20dir/r%C3%A9s"), p("/tmp/my dir/rés/"));
    }

    #[test]
    fn non_local_or_malformed_uris_give_none() {
        assert_eq!(parse_uri("http://example.com/x"), None);
        assert_eq!(parse_uri("file://server/share"), None);
        assert_eq!(parse_uri("file:///tmp/bad%2"), None);
        assert_eq!(parse_uri("file:///tmp/bad%zz"), None);
        assert_eq!(parse_uri(""), None);
    }

    #[test]
    fn windows_file_uris() {
        let w = |uri| parse_uri_for(uri, true);
        let s = |text: &str| Some(text.to_string());
        assert_eq!(w("file:///C:/Users/me/fmu/resources"), s("C:\\Users\\me\\fmu\\resources\\"));
        assert_eq!(w("file:///C:/Users/me/fmu/resources/"), s("C:\\Users\\me\\fmu\\resources\\"));
        assert_eq!(w("file:/C:/tmp/x"), s("C:\\tmp\\x\\"));
        assert_eq!(w("file:///c|/tmp/x"), s("c:\\tmp\\x\\"));
        assert_eq!(w("file://localhost/D:/my%20dir/r%C3%A9s"), s("D:\\my dir\\rés\\"));
        assert_eq!(w("file:///C:/"), s("C:\\"));
        assert_eq!(w("file:///Z:/tmp/x"), s("Z:\\tmp\\x\\"));
        assert_eq!(w("file://server/share/fmu/resources"), s("\\\\server\\share\\fmu\\resources\\"));
        assert_eq!(w("file://server"), None);
        assert_eq!(w("http://example.com/x"), None);
        assert_eq!(w("file:///C:/bad%2"), None);
        // The Unix forms stay as they were.
        assert_eq!(parse_uri_for("file:///C:/x", false), s("/C:/x/"));
        assert_eq!(parse_uri_for("file:///tmp/x", false), s("/tmp/x/"));
    }

    #[test]
    fn fmi3_plain_path() {
        assert_eq!(parse_path("/tmp/x/resources/"), p("/tmp/x/resources/"));
        assert_eq!(parse_path("/tmp/x/resources"), p("/tmp/x/resources/"));
        assert_eq!(parse_path(""), None);
    }
}
