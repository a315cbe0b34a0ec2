//! TOML syntax errors, turned into recipe diagnostics. The TOML parser's messages are terse
//! ("duplicate key"); this module names the key and the table, and points back at the first
//! definition, since a repeated key is how a duplicate surface or region name shows up.

use super::diagnostic::{Diagnostic, SourceText};

/// The diagnostics for the parser's errors, in source order.
pub(crate) fn diagnostics(src: &SourceText, errors: &[toml::de::Error]) -> Vec<Diagnostic> {
    let mut out: Vec<Diagnostic> = errors.iter().map(|e| one(src, e)).collect();
    out.sort_by_key(|d| (d.line, d.col));
    out.dedup();
    out
}

fn one(src: &SourceText, e: &toml::de::Error) -> Diagnostic {
    let range = e.span().unwrap_or(0..0);
    let span = src.span(range);
    let text = src.slice(span).to_string();
    let message = e.message().trim().to_string();
    if message.starts_with("duplicate key") && !text.is_empty() {
        let key = text.trim_matches(['"', '\'']).to_string();
        let header = enclosing_header(src, span.line);
        let is_header_dup = line_of(src, span.line).trim_start().starts_with('[');
        let what = match header.as_deref() {
            _ if is_header_dup => {
                format!("table `[{}]` is defined twice", header_text(src, span.line))
            }
            Some("surfaces") => format!("duplicate surface name `{key}`"),
            Some("regions") => format!("duplicate region name `{key}`"),
            Some(h) => format!("duplicate key `{key}` in `[{h}]`"),
            None => format!("duplicate key `{key}`"),
        };
        let first = if is_header_dup {
            find_header(src, span.line, &header_text(src, span.line))
        } else {
            find_first(src, span.line, &text)
        };
        let help = match first {
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

fn line_of(src: &SourceText, line: usize) -> &str {
    src.text.lines().nth(line.saturating_sub(1)).unwrap_or("")
}

/// The text between the brackets of the header on `line` (`[[trim]]` -> `trim`).
fn header_text(src: &SourceText, line: usize) -> String {
    let l = line_of(src, line).trim();
    let l = l.split('#').next().unwrap_or("").trim();
    l.trim_start_matches('[')
        .trim_end_matches(']')
        .trim()
        .to_string()
}

/// The name of the table whose header precedes `line` (a heuristic, for messages only).
fn enclosing_header(src: &SourceText, line: usize) -> Option<String> {
    (1..=line)
        .rev()
        .find(|&l| line_of(src, l).trim_start().starts_with('['))
        .map(|l| header_text(src, l))
}

/// The first line before `line` that defines the header `name`.
fn find_header(src: &SourceText, line: usize, name: &str) -> Option<usize> {
    (1..line)
        .find(|&l| line_of(src, l).trim_start().starts_with('[') && header_text(src, l) == name)
}

/// The first line, between the enclosing header and `line`, that starts with `key`.
fn find_first(src: &SourceText, line: usize, key: &str) -> Option<usize> {
    let start = (1..=line)
        .rev()
        .find(|&l| line_of(src, l).trim_start().starts_with('['))
        .unwrap_or(1);
    (start..line).find(|&l| {
        let t = line_of(src, l).trim_start();
        t.strip_prefix(key)
            .is_some_and(|rest| rest.trim_start().starts_with(['=', '.']))
            || t.contains(&format!("{{ {key} ="))
            || t.contains(&format!(", {key} ="))
    })
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
