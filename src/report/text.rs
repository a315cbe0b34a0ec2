//! Text helpers shared by the HTML and SVG writers: escaping (every name that reaches markup goes
//! through [`esc`]) and fixed-precision number formatting, so the same input always gives the same
//! bytes (no shortest-round-trip digits, no `-0`, NaN shown as a dash).

/// Escapes `&`, `<`, `>`, `"` and `'` for HTML/SVG text and attribute values.
pub fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
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

/// `v` with `digits` decimals; "-" for NaN, "inf"/"-inf" for infinities; never "-0.00".
pub fn num(v: f64, digits: usize) -> String {
    if v.is_nan() {
        return "-".to_string();
    }
    if v.is_infinite() {
        return if v > 0.0 { "inf" } else { "-inf" }.to_string();
    }
    let s = format!("{v:.digits$}");
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// An integer with thin thousands separators (`1 234 567`), as the seed's tables print counts.
pub fn count(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push('\u{202f}');
        }
        out.push(c);
    }
    out
}

/// A coordinate for SVG path data: one decimal, trailing ".0" dropped, never "-0".
pub fn coord(v: f64) -> String {
    let s = num(v, 1);
    match s.strip_suffix(".0") {
        Some(t) if t != "-" => t.to_string(),
        _ => s,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_characters_are_escaped() {
        assert_eq!(esc("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&#39;");
    }

    #[test]
    fn numbers_have_fixed_digits_and_no_negative_zero() {
        assert_eq!(num(1.0 / 3.0, 3), "0.333");
        assert_eq!(num(-0.0001, 2), "0.00");
        assert_eq!(num(-1.5, 1), "-1.5");
        assert_eq!(num(f64::NAN, 2), "-");
        assert_eq!(coord(12.04), "12");
        assert_eq!(coord(-0.04), "0");
        assert_eq!(coord(3.26), "3.3");
        assert_eq!(count(1234567), "1\u{202f}234\u{202f}567");
        assert_eq!(count(12), "12");
    }
}
