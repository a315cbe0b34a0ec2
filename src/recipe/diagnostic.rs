//! Diagnostics: where in the recipe something is wrong, and how to say it.
//!
//! Every error the recipe language reports names `file:line:col`, quotes the offending source
//! line with a caret under the offending text, and, where a likely intended spelling exists, a
//! "did you mean" help line. Positions are computed here once from byte offsets (columns count
//! characters, 1-based, like rustc), so later stages that only hold a [`Span`] can still report
//! errors at the recipe location through `Recipe::diagnostic_at`.

use std::fmt;
use std::ops::Range;

/// A location in the recipe text: a byte range plus its 1-based line and column (in characters).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Span {
    /// Byte offset of the first byte.
    pub start: usize,
    /// Byte offset one past the last byte.
    pub end: usize,
    /// 1-based line of `start`.
    pub line: usize,
    /// 1-based column of `start`, counted in characters.
    pub col: usize,
}

/// One error, rendered rustc-style by `Display`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}", self.rendered())]
pub struct Diagnostic {
    /// The recipe file as the user named it.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, in characters.
    pub col: usize,
    /// What is wrong, quoting the offending text in backticks.
    pub message: String,
    /// The source line the error points into (without its line break); a line longer than
    /// `SNIPPET_WIDTH` (160) characters is cut to a window around the column, marked with `…`.
    pub snippet: String,
    /// The 1-based column of `col` within `snippet`.
    pub snippet_col: usize,
    /// A suggestion, e.g. "did you mean `size`?".
    pub help: Option<String>,
    /// How many characters to underline from `col` (at least 1 when rendered).
    pub len: usize,
}

impl Diagnostic {
    /// The message, the location and the quoted line with its caret, and the help.
    fn rendered(&self) -> String {
        let mut f = String::new();
        self.render(&mut f).expect("writing to a String");
        f
    }

    fn render(&self, f: &mut impl fmt::Write) -> fmt::Result {
        let gutter = self.line.to_string().len();
        let pad = " ".repeat(gutter);
        writeln!(f, "error: {}", self.message)?;
        writeln!(f, "{pad}--> {}:{}:{}", self.file, self.line, self.col)?;
        writeln!(f, "{pad} |")?;
        writeln!(f, "{} | {}", self.line, self.snippet)?;
        // Keep tabs as tabs so the caret lines up under the text whatever the tab width.
        let lead: String = self
            .snippet
            .chars()
            .take(self.snippet_col.saturating_sub(1))
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        let avail = self
            .snippet
            .chars()
            .count()
            .saturating_sub(self.snippet_col.saturating_sub(1));
        let width = self.len.min(avail).max(1);
        write!(f, "{pad} | {lead}{}", "^".repeat(width))?;
        if let Some(help) = &self.help {
            write!(f, "\n{pad} = help: {help}")?;
        }
        Ok(())
    }
}

/// The recipe text with its label and line starts, for turning byte offsets into positions.
#[derive(Clone, Debug)]
pub(crate) struct SourceText {
    pub label: String,
    pub text: String,
    line_starts: Vec<usize>,
}

impl SourceText {
    pub fn new(label: String, text: &str) -> SourceText {
        let mut line_starts = vec![0];
        for (i, b) in text.bytes().enumerate() {
            if b == b'\n' {
                line_starts.push(i + 1);
            }
        }
        SourceText {
            label,
            text: text.to_string(),
            line_starts,
        }
    }

    /// The largest char boundary not after `i` (input-derived offsets never split a character).
    fn floor(&self, i: usize) -> usize {
        let mut i = i.min(self.text.len());
        while i > 0 && !self.text.is_char_boundary(i) {
            i -= 1;
        }
        i
    }

    /// The span of a byte range, with its line and column.
    pub fn span(&self, range: Range<usize>) -> Span {
        let start = self.floor(range.start);
        let end = self.floor(range.end.max(start));
        let line_idx = self
            .line_starts
            .partition_point(|&s| s <= start)
            .saturating_sub(1);
        let line_start = self.line_starts.get(line_idx).copied().unwrap_or(0);
        let col = self
            .text
            .get(line_start..start)
            .map_or(0, |s| s.chars().count())
            + 1;
        Span {
            start,
            end,
            line: line_idx + 1,
            col,
        }
    }

    /// The span of the TOML token that starts at a 1-based `line` and `col` (a `[table]` or
    /// `[[array]]` header, a quoted string or a bare key), for errors that hold only a position.
    /// `None` when the text has no such place.
    pub fn token_at(&self, line: usize, col: usize) -> Option<Span> {
        let start_of_line = *self.line_starts.get(line.checked_sub(1)?)?;
        let text = self.line_text(line);
        let (offset, rest) = text
            .char_indices()
            .nth(col.checked_sub(1)?)
            .map(|(i, _)| (i, &text[i..]))?;
        let len = token_len(rest);
        let start = start_of_line + offset;
        Some(self.span(start..start + len))
    }

    /// How many lines the text has (a last line without a line break counts).
    pub(crate) fn line_count(&self) -> usize {
        self.line_starts.len()
    }

    /// The text of a line (1-based), without `\r\n` / `\n`.
    pub(crate) fn line_text(&self, line: usize) -> &str {
        let Some(&start) = self.line_starts.get(line.saturating_sub(1)) else {
            return "";
        };
        let end = self
            .line_starts
            .get(line)
            .copied()
            .unwrap_or(self.text.len());
        let s = self.text.get(start..end).unwrap_or("");
        s.trim_end_matches(['\n', '\r'])
    }

    /// The source text of a span (empty if the span is not in this text).
    pub fn slice(&self, span: Span) -> &str {
        self.text.get(span.start..span.end).unwrap_or("")
    }

    /// A diagnostic pointing at `span`; the underline stops at the end of the span's first line.
    pub fn diagnostic(&self, span: Span, message: String, help: Option<String>) -> Diagnostic {
        let (snippet, snippet_col) = window(self.line_text(span.line), span.col);
        let spanned = self.slice(span);
        let first_line = spanned.split('\n').next().unwrap_or("");
        let len = first_line.trim_end_matches('\r').chars().count().max(1);
        Diagnostic {
            file: self.label.clone(),
            line: span.line,
            col: span.col,
            message,
            snippet,
            snippet_col,
            help,
            len,
        }
    }
}

/// The most characters of a source line a diagnostic quotes: a generated recipe may hold a
/// table of millions of entries on one line, which would be quoted (and kept) whole.
pub const SNIPPET_WIDTH: usize = 160;

/// `line` cut to at most [`SNIPPET_WIDTH`] characters around the 1-based column `col`, with `…`
/// where it was cut; and `col`'s column in the result.
fn window(line: &str, col: usize) -> (String, usize) {
    let count = line.chars().count();
    if count <= SNIPPET_WIDTH {
        return (line.to_string(), col);
    }
    let at = col.saturating_sub(1).min(count);
    let from = at
        .saturating_sub(SNIPPET_WIDTH / 3)
        .min(count - SNIPPET_WIDTH);
    let to = from + SNIPPET_WIDTH;
    let mut out: String = if from > 0 {
        "…".into()
    } else {
        String::new()
    };
    out.extend(line.chars().skip(from).take(SNIPPET_WIDTH));
    if to < count {
        out.push('…');
    }
    (out, at - from + 1 + usize::from(from > 0))
}

/// The byte length of the TOML token at the start of `s`: a header through its closing `]`s, a
/// quoted string up to its closing quote, or a bare key; at least one character.
fn token_len(s: &str) -> usize {
    let first = s.chars().next().map_or(0, char::len_utf8);
    let end = match s.chars().next() {
        Some('[') => s
            .find(']')
            .map(|i| i + s[i..].chars().take_while(|&c| c == ']').count()),
        Some(q @ ('"' | '\'')) => s[1..].find(q).map(|i| i + 2),
        _ => s
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '-'))
            .or(Some(s.len())),
    };
    end.filter(|&e| e > 0).unwrap_or(first)
}

/// The closest candidate to `word`, if it is close enough to be a plausible typo.
///
/// Closeness is the normalised Damerau-Levenshtein similarity (>= 0.6), or a single edit on a
/// name of two or more characters (`fl` for `f1`), or a case-insensitive match, or one being a prefix of the other (`reservoir` for `reserv`); ties go to the first
/// candidate in the order given, so the answer is deterministic.
pub fn did_you_mean<'a, I>(word: &str, candidates: I) -> Option<String>
where
    I: IntoIterator<Item = &'a str>,
{
    let lower = word.to_lowercase();
    let mut best: Option<(f64, &str)> = None;
    for cand in candidates {
        if cand == word {
            continue;
        }
        let cl = cand.to_lowercase();
        let mut score = strsim::normalized_damerau_levenshtein(&lower, &cl);
        if cl == lower {
            score = 1.0;
        } else if lower.chars().count() >= 2 && strsim::damerau_levenshtein(&lower, &cl) == 1 {
            score = score.max(0.6);
        } else if lower.len() >= 3 && (cl.starts_with(&lower) || lower.starts_with(&cl)) {
            score = score.max(0.75);
        }
        if score >= 0.6 && best.is_none_or(|(b, _)| score > b) {
            best = Some((score, cand));
        }
    }
    best.map(|(_, c)| c.to_string())
}

/// "did you mean `x`?" for the closest candidate, else a list of the valid choices.
pub fn suggest(word: &str, candidates: &[&str], what: &str) -> Option<String> {
    if let Some(c) = did_you_mean(word, candidates.iter().copied()) {
        return Some(format!("did you mean `{c}`?"));
    }
    if candidates.is_empty() {
        return None;
    }
    let list: Vec<String> = candidates.iter().map(|c| format!("`{c}`")).collect();
    Some(format!("{what}: {}", list.join(", ")))
}
