//! The FMU's resource location: FMI 2 gives a URI (`file:///a/b`, `file:///a/b/`, `file:/a/b`,
//! `file://localhost/a/b`, percent-encoded), FMI 3 a plain path with a trailing `/`.

use std::path::PathBuf;

/// Parses an FMI 2 `fmuResourceLocation` into a directory path. Returns `None` for schemes other
/// than `file` or a remote host (the FMU does not need its resources, so this is not an error).
pub fn parse_uri(uri: &str) -> Option<PathBuf> {
    let rest = uri.strip_prefix("file:").or_else(|| uri.strip_prefix("FILE:"))?;
    let path = if let Some(authority_and_path) = rest.strip_prefix("//") {
        // file://host/path: only an empty host or localhost is local.
        let slash = authority_and_path.find('/').unwrap_or(authority_and_path.len());
        let (host, path) = authority_and_path.split_at(slash);
        if !(host.is_empty() || host.eq_ignore_ascii_case("localhost")) {
            return None;
        }
        path
    } else {
        rest
    };
    if path.is_empty() {
        return None;
    }
    let decoded = percent_decode(path)?;
    Some(PathBuf::from(decoded.trim_end_matches('/').to_string()).join(""))
}

/// FMI 3's `resourcePath`: a plain path (normally with a trailing separator). Empty means none.
pub fn parse_path(path: &str) -> Option<PathBuf> {
    (!path.is_empty()).then(|| PathBuf::from(path.trim_end_matches('/')).join(""))
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
    fn fmi3_plain_path() {
        assert_eq!(parse_path("/tmp/x/resources/"), p("/tmp/x/resources/"));
        assert_eq!(parse_path("/tmp/x/resources"), p("/tmp/x/resources/"));
        assert_eq!(parse_path(""), None);
    }
}
