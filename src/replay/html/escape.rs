//! The one escape function every text that reaches the HTML report goes through: the scenario's
//! strings, file names, notes, keys and values of the run's JSON. It replaces the five characters
//! HTML gives a meaning to (`&`, `<`, `>`, `"`, `'`: the HTML Living Standard's "escaping a
//! string" set, with `'` added so that single-quoted attributes are safe too), so that a scenario or
//! a file named `<script>` stays text, in an element's content or in an attribute's value alike.

/// `text` with `& < > " '` replaced by their character references.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::escape;

    #[test]
    fn a_script_tag_and_both_quotes_become_text() {
        assert_eq!(
            escape("<script>alert('x' & \"y\")</script>"),
            "&lt;script&gt;alert(&#39;x&#39; &amp; &quot;y&quot;)&lt;/script&gt;"
        );
    }

    #[test]
    fn other_text_is_kept_as_it_is() {
        assert_eq!(escape("σ_din,a = 492 MPa; x/y"), "σ_din,a = 492 MPa; x/y");
    }
}
