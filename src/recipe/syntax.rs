//! TOML syntax errors, turned into recipe diagnostics. The TOML parser's messages are terse
//! ("duplicate key"); this module names the key and the table, and points back at the first
//! definition, since a repeated key is how a duplicate surface or region name shows up.

use super::diagnostic::{Diagnostic, SourceText};
use std::collections::BTreeMap;

/// The diagnostics for the parser's errors, in source order.
pub(crate) fn diagnostics(src: &SourceText, errors: &[toml::de::Error]) -> Vec<Diagnostic> {
    let layout = Layout::of(src);
    let mut out: Vec<Diagnostic> = errors.iter().map(|e| one(src, &layout, e)).collect();
    out.sort_by_key(|d| (d.line, d.col));
    out.dedup();
    out
}

/// Where the text's tables and keys are first written, found in one pass so that each of any
/// number of errors is placed in constant time (a recipe may repeat thousands of names).
struct Layout {
    /// Per line (1-based; index 0 unused): the line of the table header at or above it, 0 when
    /// there is none.
    header_of: Vec<usize>,
    /// Each table header's name -> its first line.
    first_header: BTreeMap<String, usize>,
    /// (the line of a table's header, or 1 above every header; a key as written) -> the first
    /// line that writes that key in that table: at the line's start (`key =`, `key.sub =`) or
    /// in an inline table (`{ key =`, `, key =`).
    first_key: BTreeMap<(usize, String), usize>,
}

impl Layout {
    fn of(src: &SourceText) -> Layout {
        let mut l = Layout {
            header_of: vec![0],
            first_header: BTreeMap::new(),
            first_key: BTreeMap::new(),
        };
        let mut header = 0;
        for line in 1..=src.line_count() {
            let t = src.line_text(line).trim_start();
            if t.starts_with('[') {
                header = line;
                l.first_header.entry(header_text(t)).or_insert(line);
            } else {
                for key in keys_written(t) {
                    l.first_key
                        .entry((header.max(1), key.to_string()))
                        .or_insert(line);
                }
            }
            l.header_of.push(header);
        }
        l
    }

    /// The header line of the table `line` is in (0: above every header).
    fn header_of(&self, line: usize) -> usize {
        self.header_of.get(line).copied().unwrap_or(0)
    }
}

fn one(src: &SourceText, layout: &Layout, e: &toml::de::Error) -> Diagnostic {
    let range = e.span().unwrap_or(0..0);
    let span = src.span(range);
    let text = src.slice(span).to_string();
    let message = e.message().trim().to_string();
    if message.starts_with("duplicate key") && !text.is_empty() {
        let key = text.trim_matches(['"', '\'']).to_string();
        let header = match layout.header_of(span.line) {
            0 => None,
            h => Some(header_text(src.line_text(h))),
        };
        let is_header_dup = src.line_text(span.line).trim_start().starts_with('[');
        let what = match header.as_deref() {
            _ if is_header_dup => {
                let name = header_text(src.line_text(span.line));
                format!("table `[{name}]` is defined twice")
            }
            Some("surfaces") => format!("duplicate surface name `{key}`"),
            Some("regions") => format!("duplicate region name `{key}`"),
            Some(h) => format!("duplicate key `{key}` in `[{h}]`"),
            None => format!("duplicate key `{key}`"),
        };
        let first = if is_header_dup {
            let name = header_text(src.line_text(span.line));
            layout.first_header.get(&name).copied()
        } else {
            let table = layout.header_of(span.line).max(1);
            layout.first_key.get(&(table, text.clone())).copied()
        };
        let help = match first.filter(|&l| l < span.line) {
            Some(l) if is_header_dup => format!("first defined on line {l}: merge the two tables"),
            Some(l) => format!(
                "`{key}` is first defined on line {l}: each name may appear once; rename or remove one"
            ),
            None => "each key may appear once in a table; rename or remove one".to_string(),
        };
        return src.diagnostic(span, what, Some(help));
    }
    if let Some(d) = unterminated_string(src, range_of(e), &message) {
        return d;
    }
    let message = if text.trim().is_empty() {
        format!("TOML syntax error: {message}")
    } else {
        format!(
            "TOML syntax error: {message}, at `{}`",
            text.lines().next().unwrap_or("")
        )
    };
    src.diagnostic(
        span,
        message,
        Some("see https://toml.io for the syntax".into()),
    )
}

/// The text between the brackets of a header line (`[[trim]]  # x` -> `trim`).
fn header_text(line: &str) -> String {
    let l = line.trim();
    let l = l.split('#').next().unwrap_or("").trim();
    l.trim_start_matches('[')
        .trim_end_matches(']')
        .trim()
        .to_string()
}

/// The keys a (non-header) line writes, as written: the one it starts with when `=` or `.`
/// follows, and each one opening or continuing an inline table (`{ key =`, `, key =`).
fn keys_written(t: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let lead = key_token(t);
    if !lead.is_empty() && t[lead.len()..].trim_start().starts_with(['=', '.']) {
        out.push(lead);
    }
    for (at, _) in t.match_indices(['{', ',']) {
        let Some(after) = t[at + 1..].strip_prefix(' ') else {
            continue;
        };
        let k = key_token(after);
        if !k.is_empty() && after[k.len()..].starts_with(" =") {
            out.push(k);
        }
    }
    out
}

/// The key at the start of `t`: a quoted string with its quotes, or a bare key.
fn key_token(t: &str) -> &str {
    match t.chars().next() {
        Some(q @ ('"' | '\'')) => t[1..].find(q).map_or("", |end| &t[..end + 2]),
        _ => {
            let end = t
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '-'))
                .unwrap_or(t.len());
            &t[..end]
        }
    }
}

fn range_of(e: &toml::de::Error) -> std::ops::Range<usize> {
    e.span().unwrap_or(0..0)
}

/// An unterminated string is reported by the parser at the end of the line; point at its
/// opening quote instead, where the user has to look.
fn unterminated_string(
    src: &SourceText,
    range: std::ops::Range<usize>,
    message: &str,
) -> Option<Diagnostic> {
    let quote = if message.starts_with("invalid basic string") {
        '"'
    } else if message.starts_with("invalid literal string") {
        '\''
    } else {
        return None;
    };
    let at = src.span(range.clone());
    let line_start = src.text.get(..at.start)?.rfind('\n').map_or(0, |p| p + 1);
    let before = src.text.get(line_start..at.start)?;
    let rel = before.rfind(quote)?;
    let open = src.span(line_start + rel..at.start);
    Some(src.diagnostic(
        open,
        format!(
            "TOML syntax error: unterminated string `{}`",
            before.get(rel..).unwrap_or("").trim_end()
        ),
        Some(format!(
            "close the string with `{quote}` on the same line (use triple quotes for several lines)"
        )),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_writes_its_leading_key_and_the_keys_of_its_inline_table() {
        assert_eq!(
            keys_written(r#"r1 = { point = [1, 2, 3], material = 2 }"#),
            ["r1", "point", "material"]
        );
        assert_eq!(
            keys_written(r#""top/f1#2" = { size = 2.0 }"#),
            [r#""top/f1#2""#, "size"]
        );
        assert_eq!(keys_written("a.b = 1"), ["a"]);
        assert_eq!(keys_written("'lit' = 1"), ["'lit'"]);
    }

    #[test]
    fn a_line_that_writes_no_key_gives_none() {
        for t in ["", "# a comment", "  1.0, 2.0,", "\"open = 1", "x_y"] {
            assert!(keys_written(t).is_empty(), "{t}");
        }
    }
}
