//! Text in Exodus: names, QA and info records are rows of a `char` variable, each row as wide
//! as its dimension (`len_name`, `len_string`, `len_line`) and NUL-terminated, so a text keeps at
//! most `width - 1` bytes. Longer text is cut at a character boundary rather than refused: a
//! name is a label, and the ids (which are never cut) identify blocks and sets.

use crate::netcdf::Values;

/// `texts` as rows of `width` bytes (cut to `width - 1` bytes, zero-padded).
pub(super) fn rows<'a>(texts: impl IntoIterator<Item = &'a str>, width: usize) -> Values {
    let mut out = Vec::new();
    for t in texts {
        let cut = cut(t, width.saturating_sub(1));
        out.extend_from_slice(cut.as_bytes());
        out.resize(out.len() + width - cut.len(), 0);
    }
    Values::Char(out)
}

/// The longest prefix of `s` of at most `max` bytes that ends on a character boundary.
pub(super) fn cut(s: &str, max: usize) -> &str {
    let mut end = s.len().min(max);
    while !s.is_char_boundary(end) {
        end -= 1;
    }
    &s[..end]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_nul_padded_to_the_width_and_cut_on_a_character_boundary() {
        assert_eq!(
            rows(["ab", ""], 4),
            Values::Char(b"ab\0\0\0\0\0\0".to_vec())
        );
        // "é" is two bytes: cutting "aé" to 2 bytes keeps only "a".
        assert_eq!(rows(["aé"], 3), Values::Char(b"a\0\0".to_vec()));
        assert_eq!(cut("abcdef", 3), "abc");
    }
}
