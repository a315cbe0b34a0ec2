//! Byte-level lexing of gOcad ASCII text: lines (LF, CRLF or lone CR), whitespace-separated
//! tokens (spaces, tabs, runs of either), double-quoted names, and numbers.
//!
//! gOcad files are nominally ASCII but real ones carry Latin-1 names and stray bytes, so the lexer
//! works on `&[u8]` and never assumes UTF-8; only tokens that must be numbers are converted. Numbers
//! are parsed with the standard library's correctly rounded parser, so the coordinates are exactly
//! the binary64 values the text denotes.
//!
//! A line can be any length (a damaged file may hold one of a gigabyte), so nothing here copies a
//! line whole: a name or other text kept from a line is at most [`MAX_TEXT`] bytes (longer text
//! is cut and says how long it was), and a list of tokens stops at the count its caller can use.
//! Memory then stays about the size of the file, whatever its lines.

/// One line of the input: its 1-based number and its bytes without the line terminator.
#[derive(Clone, Copy, Debug)]
pub struct Line<'a> {
    pub number: usize,
    pub text: &'a [u8],
}

/// Iterates over the lines of a byte buffer; `\n`, `\r\n` and a lone `\r` all end a line.
pub struct Lines<'a> {
    bytes: &'a [u8],
    pos: usize,
    number: usize,
}

impl<'a> Lines<'a> {
    pub fn new(bytes: &'a [u8]) -> Self {
        Lines {
            bytes,
            pos: 0,
            number: 0,
        }
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = Line<'a>;
    #[inline]
    fn next(&mut self) -> Option<Line<'a>> {
        let rest = self.bytes.get(self.pos..)?;
        if rest.is_empty() {
            return None;
        }
        self.number += 1;
        let end = rest
            .iter()
            .position(|&b| b == b'\n' || b == b'\r')
            .unwrap_or(rest.len());
        let text = &rest[..end];
        let mut skip = end;
        if let Some(&b) = rest.get(end) {
            skip += 1;
            if b == b'\r' && rest.get(end + 1) == Some(&b'\n') {
                skip += 1;
            }
        }
        self.pos += skip;
        Some(Line {
            number: self.number,
            text,
        })
    }
}

#[inline]
pub fn is_space(b: u8) -> bool {
    b == b' ' || b == b'\t' || b == b'\r' || b == 0x0c || b == 0x0b
}

/// Strips leading and trailing blanks.
pub fn trim(mut s: &[u8]) -> &[u8] {
    while let [first, rest @ ..] = s {
        if is_space(*first) {
            s = rest;
        } else {
            break;
        }
    }
    while let [rest @ .., last] = s {
        if is_space(*last) {
            s = rest;
        } else {
            break;
        }
    }
    s
}

/// Whitespace-separated tokens of a line (no quote handling: the fast path for records).
pub struct Tokens<'a> {
    s: &'a [u8],
    pos: usize,
}

impl<'a> Tokens<'a> {
    #[inline]
    pub fn new(s: &'a [u8]) -> Self {
        Tokens { s, pos: 0 }
    }
    /// The unread remainder of the line, trimmed.
    pub fn rest(&self) -> &'a [u8] {
        trim(self.s.get(self.pos..).unwrap_or(&[]))
    }
}

impl<'a> Iterator for Tokens<'a> {
    type Item = &'a [u8];
    #[inline]
    fn next(&mut self) -> Option<&'a [u8]> {
        let s = self.s;
        let mut i = self.pos;
        while i < s.len() && is_space(s[i]) {
            i += 1;
        }
        if i >= s.len() {
            self.pos = i;
            return None;
        }
        let start = i;
        while i < s.len() && !is_space(s[i]) {
            i += 1;
        }
        self.pos = i;
        Some(&s[start..i])
    }
}

/// The longest text kept from a line, in bytes: names, units, values in messages.
pub const MAX_TEXT: usize = 4096;

/// Tokens of a line where a double-quoted run (which may hold blanks) is one token, quotes removed.
/// An unterminated quote runs to the end of the line. At most `limit` tokens are returned, so a
/// caller that can use `n` asks for `n + 1` to tell a line that holds more.
pub fn quoted_tokens(s: &[u8], limit: usize) -> Vec<String> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < s.len() && out.len() < limit {
        if is_space(s[i]) {
            i += 1;
            continue;
        }
        if s[i] == b'"' {
            let start = i + 1;
            let mut j = start;
            while j < s.len() && s[j] != b'"' {
                j += 1;
            }
            out.push(text(&s[start.min(s.len())..j]));
            i = j + 1;
        } else {
            let start = i;
            while i < s.len() && !is_space(s[i]) {
                i += 1;
            }
            out.push(text(&s[start..i]));
        }
    }
    out
}

/// Bytes as text, replacing invalid UTF-8 (names in messages and outputs); text longer than
/// [`MAX_TEXT`] bytes is cut there and ends with how long it was.
pub fn text(s: &[u8]) -> String {
    if s.len() <= MAX_TEXT {
        return String::from_utf8_lossy(s).into_owned();
    }
    let mut cut = String::from_utf8_lossy(&s[..MAX_TEXT]).into_owned();
    // A character split at the cut reads as a replacement character: drop it.
    cut = cut.trim_end_matches('\u{fffd}').to_string();
    cut.push_str(&format!("… ({} bytes in all)", s.len()));
    cut
}

/// Why a token is not a usable number.
#[derive(Debug, Clone, PartialEq)]
pub enum NumberError {
    /// Not a number at all (`blah`).
    NotNumeric,
    /// `inf`, `nan`, `1.#INF`, `-1.#IND`... or a literal that overflows binary64.
    NotFinite,
}

/// Exact powers of ten representable in binary64.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Clinger's fast path for plain decimals (`-123.4500`): when the digits form an integer
/// m ≤ 2^53 and there are at most 22 fraction digits, m and 10^k are exact binary64 values and one
/// IEEE division is correctly rounded, so the result equals the standard parser's. Anything else
/// (exponents, long mantissas, words) returns `None` for the general parser.
#[inline]
fn fast_f64(tok: &[u8]) -> Option<f64> {
    let (neg, s) = match tok.first()? {
        b'-' => (true, &tok[1..]),
        b'+' => (false, &tok[1..]),
        _ => (false, tok),
    };
    let mut m: u64 = 0;
    let mut digits = 0u32;
    let mut frac = 0usize;
    let mut seen_dot = false;
    for &b in s {
        if b.is_ascii_digit() {
            digits += 1;
            if digits > 19 {
                return None;
            }
            m = m * 10 + u64::from(b - b'0');
            if seen_dot {
                frac += 1;
            }
        } else if b == b'.' && !seen_dot {
            seen_dot = true;
        } else {
            return None;
        }
    }
    if digits == 0 || m > (1u64 << 53) || frac >= POW10.len() {
        return None;
    }
    let v = m as f64 / POW10[frac];
    Some(if neg { -v } else { v })
}

/// Parses a finite binary64 value (correctly rounded).
#[inline]
pub fn parse_f64(tok: &[u8]) -> Result<f64, NumberError> {
    if let Some(v) = fast_f64(tok) {
        return Ok(v);
    }
    let s = std::str::from_utf8(tok).map_err(|_| NumberError::NotNumeric)?;
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(NumberError::NotFinite),
        Err(_) => {
            let up = s.to_ascii_uppercase();
            if up.contains("#INF")
                || up.contains("#IND")
                || up.contains("#QNAN")
                || up.contains("#SNAN")
            {
                Err(NumberError::NotFinite)
            } else {
                Err(NumberError::NotNumeric)
            }
        }
    }
}

/// Parses a non-negative integer identifier (at most 19 digits, so it fits a u64).
#[inline]
pub fn parse_id(tok: &[u8]) -> Option<u64> {
    let tok = tok.strip_prefix(b"+").unwrap_or(tok);
    if tok.is_empty() || tok.len() > 19 {
        return None;
    }
    let mut v: u64 = 0;
    for &b in tok {
        if !b.is_ascii_digit() {
            return None;
        }
        v = v * 10 + u64::from(b - b'0');
    }
    Some(v)
}

/// Parses a signed integer (REGION side lists use `+3` / `-3`).
pub fn parse_signed(tok: &[u8]) -> Option<i64> {
    let (neg, digits) = match tok.first() {
        Some(b'-') => (true, &tok[1..]),
        Some(b'+') => (false, &tok[1..]),
        _ => (false, tok),
    };
    let v = i64::try_from(parse_id(digits)?).ok()?;
    Some(if neg { -v } else { v })
}

/// ASCII case-insensitive comparison of a token with a keyword.
#[inline]
pub fn eq_ci(tok: &[u8], kw: &str) -> bool {
    tok.eq_ignore_ascii_case(kw.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crlf_lone_cr_and_a_missing_final_newline_all_end_lines() {
        let v: Vec<_> = Lines::new(b"a\r\nb\rc\nd")
            .map(|l| (l.number, l.text.to_vec()))
            .collect();
        assert_eq!(
            v,
            vec![
                (1, b"a".to_vec()),
                (2, b"b".to_vec()),
                (3, b"c".to_vec()),
                (4, b"d".to_vec())
            ]
        );
    }

    #[test]
    fn tabs_and_runs_of_spaces_separate_tokens() {
        let t: Vec<_> = Tokens::new(b"PVRTX\t0  1.5\t\t2 ").collect();
        assert_eq!(t, vec![&b"PVRTX"[..], b"0", b"1.5", b"2"]);
    }

    #[test]
    fn a_quoted_name_with_spaces_is_one_token() {
        assert_eq!(
            quoted_tokens(br#"PROPERTIES " default property"  def-prop"#, 10),
            vec!["PROPERTIES", " default property", "def-prop"]
        );
    }

    #[test]
    fn windows_infinity_spellings_are_not_finite_and_words_are_not_numeric() {
        assert_eq!(parse_f64(b"1.#INF"), Err(NumberError::NotFinite));
        assert_eq!(parse_f64(b"-inf"), Err(NumberError::NotFinite));
        assert_eq!(parse_f64(b"nan"), Err(NumberError::NotFinite));
        assert_eq!(parse_f64(b"1e999"), Err(NumberError::NotFinite));
        assert_eq!(parse_f64(b"blah"), Err(NumberError::NotNumeric));
        assert_eq!(parse_f64(b"868.21875"), Ok(868.21875));
    }

    #[test]
    fn the_fast_decimal_path_agrees_with_the_standard_parser_bit_for_bit() {
        let samples = [
            "0",
            "-0",
            "1.",
            "868.21875",
            "-354.825653076171",
            "512345.125000",
            "7012345.5",
            "0.1",
            "0.3",
            "9007199254740993",
            "123456789012.345678",
            "0.0000000000000000000001",
            "-1234.25",
            "+5.5",
            "99999999.99999999",
        ];
        for s in samples {
            let want: f64 = s.parse().unwrap();
            let got = parse_f64(s.as_bytes()).unwrap();
            assert_eq!(got.to_bits(), want.to_bits(), "{s}");
        }
        // A pseudo-random sweep of short decimals.
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let int = x % 10_000_000;
            let frac = (x >> 24) % 1_000_000;
            let s = format!("{}{int}.{frac:06}", if x & 1 == 1 { "-" } else { "" });
            let want: f64 = s.parse().unwrap();
            assert_eq!(
                parse_f64(s.as_bytes()).unwrap().to_bits(),
                want.to_bits(),
                "{s}"
            );
        }
    }

    #[test]
    fn identifiers_reject_signs_overflow_and_letters() {
        assert_eq!(parse_id(b"17"), Some(17));
        assert_eq!(parse_id(b"-1"), None);
        assert_eq!(parse_id(b"99999999999999999999"), None);
        assert_eq!(parse_id(b"1a"), None);
        assert_eq!(parse_signed(b"-18"), Some(-18));
        assert_eq!(parse_signed(b"+3"), Some(3));
    }

    #[test]
    fn a_list_of_tokens_stops_at_its_limit() {
        assert_eq!(quoted_tokens(b"a b \"c d\" e", 2), vec!["a", "b"]);
        assert_eq!(
            quoted_tokens(b"a b \"c d\" e", 9),
            vec!["a", "b", "c d", "e"]
        );
    }

    #[test]
    fn text_longer_than_its_bound_is_cut_and_says_how_long_it_was() {
        let long = vec![b'x'; MAX_TEXT * 3];
        let t = text(&long);
        assert!(t.starts_with(&"x".repeat(MAX_TEXT)), "{}", &t[..20]);
        assert!(
            t.ends_with(&format!("… ({} bytes in all)", MAX_TEXT * 3)),
            "{t}"
        );
        assert!(t.len() < MAX_TEXT + 40);
        // A two-byte character across the cut is not half kept.
        let mut accented = vec![b'a'; MAX_TEXT - 1];
        accented.extend("é".repeat(10).as_bytes());
        let t = text(&accented);
        assert!(!t.contains('\u{fffd}'), "{}", &t[MAX_TEXT - 4..]);
        assert_eq!(text("é".as_bytes()), "é");
    }
}
