//! Selectors: how a recipe names surfaces and curves before the model exists.
//!
//! A surface selector is a name or a glob (`*` = any run of characters, `?` = one character)
//! over surface names and the box sides `box.xmin` .. `box.zmax`. A curve selector is one or two
//! surface selectors joined by `/`, in either order, with an optional `#k` component suffix.
//! Curve names produced by the model look like `top/f1` (the surfaces that meet there, sorted),
//! `top/f1#2` (component 2 of several), `box.xmin/top`, or `top#3` (a free boundary curve of
//! one surface). The recipe validates that every side matches some known surface; the planner
//! then uses [`CurveSelector::matches`] against the curve names of the built model.

use std::fmt;

/// Matches `text` against a glob with `*` and `?` (no character classes, no escapes), iteratively
/// (the classic two-pointer backtracking over the last `*`, linear memory, no recursion).
pub fn glob_match(pattern: &str, text: &str) -> bool {
    let p: Vec<char> = pattern.chars().collect();
    let t: Vec<char> = text.chars().collect();
    let (mut pi, mut ti) = (0usize, 0usize);
    let mut star: Option<(usize, usize)> = None;
    while ti < t.len() {
        match p.get(pi) {
            Some('*') => {
                star = Some((pi, ti));
                pi += 1;
            }
            Some(&c) if c == '?' || c == t[ti] => {
                pi += 1;
                ti += 1;
            }
            _ => match star {
                Some((sp, st)) => {
                    pi = sp + 1;
                    ti = st + 1;
                    star = Some((sp, st + 1));
                }
                None => return false,
            },
        }
    }
    p[pi.min(p.len())..].iter().all(|&c| c == '*')
}

/// True when `s` contains a glob wildcard.
pub fn is_glob(s: &str) -> bool {
    s.contains(['*', '?'])
}

/// A surface name or glob, e.g. `f2`, `f*`, `box.*`.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub struct SurfaceSelector {
    /// The pattern as written.
    pub pattern: String,
}

impl SurfaceSelector {
    pub fn new(pattern: &str) -> SurfaceSelector {
        SurfaceSelector {
            pattern: pattern.to_string(),
        }
    }

    /// Whether the surface (or box side) `name` is selected.
    pub fn matches(&self, name: &str) -> bool {
        glob_match(&self.pattern, name)
    }

    /// True when the pattern has no wildcard (it names exactly one surface).
    pub fn is_exact(&self) -> bool {
        !is_glob(&self.pattern)
    }

    /// Number of non-wildcard characters: more means more specific.
    pub fn literal_len(&self) -> usize {
        self.pattern
            .chars()
            .filter(|c| *c != '*' && *c != '?')
            .count()
    }
}

impl fmt::Display for SurfaceSelector {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.pattern)
    }
}

/// A curve selector: `a/b`, `a`, `a/*`, with globs on either side and an optional `#k`.
///
/// Matching rules (documented in the README's recipe reference):
/// * `a/b` matches a curve whose name lists (at least) two different surfaces, one matched by `a`
///   and another by `b`, in either order;
/// * `a` (same as `a/*` or `*/a`) matches every curve that has a surface matched by `a`,
///   including the free boundary curves `a#k` of that surface;
/// * `#k` restricts to the curve whose name ends in `#k`; without it all components match.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub struct CurveSelector {
    /// The selector as written.
    pub text: String,
    /// One or two side patterns; a lone side means "any curve of this surface". Two sides are
    /// stored sorted, so `f1/top` and `top/f1` compare equal.
    pub sides: Vec<SurfaceSelector>,
    /// The `#k` component, if given.
    pub component: Option<u32>,
}

/// Why a curve selector's text is malformed (worded for users).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SelectorError {
    #[error("the component after `#` must be a whole number, found `{0}`")]
    Component(String),
    #[error("a curve selector has at most one `#k` suffix")]
    TwoComponents,
    #[error("a curve selector has one or two sides separated by one `/`, e.g. `top/f1`")]
    TooManySides,
    #[error("empty side in curve selector: write `top/f1`, `top` or `f1/box.*`")]
    EmptySide,
    #[error(
        "character `{0}` is not allowed in a selector (names use letters, digits, `_ . -`; globs `* ?`)"
    )]
    Character(char),
}

impl CurveSelector {
    /// Parses `a/b#k`. Errors are worded for users; the caller adds the recipe location.
    pub fn parse(text: &str) -> Result<CurveSelector, SelectorError> {
        let (body, component) = match text.rsplit_once('#') {
            Some((b, k)) => {
                let k: u32 = k
                    .parse()
                    .map_err(|_| SelectorError::Component(k.to_string()))?;
                (b, Some(k))
            }
            None => (text, None),
        };
        if body.contains('#') {
            return Err(SelectorError::TwoComponents);
        }
        let parts: Vec<&str> = body.split('/').collect();
        if parts.len() > 2 {
            return Err(SelectorError::TooManySides);
        }
        for p in &parts {
            if p.is_empty() {
                return Err(SelectorError::EmptySide);
            }
            if let Some(c) = p.chars().find(|c| !valid_pattern_char(*c)) {
                return Err(SelectorError::Character(c));
            }
        }
        let mut sides: Vec<SurfaceSelector> = parts
            .iter()
            .filter(|p| parts.len() == 1 || **p != "*")
            .map(|p| SurfaceSelector::new(p))
            .collect();
        if sides.is_empty() {
            // `*/*`: every curve.
            sides.push(SurfaceSelector::new("*"));
        }
        sides.sort();
        Ok(CurveSelector {
            text: text.to_string(),
            sides,
            component,
        })
    }

    /// Whether the curve named `curve_name` (as produced by the model) is selected.
    pub fn matches(&self, curve_name: &str) -> bool {
        let (body, comp) = split_component(curve_name);
        if let Some(k) = self.component
            && comp != Some(k)
        {
            return false;
        }
        let names: Vec<&str> = body.split('/').collect();
        match self.sides.as_slice() {
            [a] => names.iter().any(|n| a.matches(n)),
            [a, b] => names.iter().enumerate().any(|(i, x)| {
                names
                    .iter()
                    .enumerate()
                    .any(|(j, y)| i != j && a.matches(x) && b.matches(y))
            }),
            _ => false,
        }
    }

    /// Specificity for precedence among rules matching the same curve: a `#k` component first,
    /// then the number of sides, then how many sides are exact names, then literal characters.
    pub fn specificity(&self) -> (bool, usize, usize, usize) {
        (
            self.component.is_some(),
            self.sides.len(),
            self.sides.iter().filter(|s| s.is_exact()).count(),
            self.sides.iter().map(SurfaceSelector::literal_len).sum(),
        )
    }

    /// A canonical text (`a/b#k`, sides sorted) to detect two rules that say the same thing.
    pub fn canonical(&self) -> String {
        let sides: Vec<&str> = self.sides.iter().map(|s| s.pattern.as_str()).collect();
        match self.component {
            Some(k) => format!("{}#{k}", sides.join("/")),
            None => sides.join("/"),
        }
    }
}

impl fmt::Display for CurveSelector {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

/// Splits `top/f1#2` into (`top/f1`, Some(2)); a suffix that is not a number stays in the body.
fn split_component(name: &str) -> (&str, Option<u32>) {
    match name.rsplit_once('#') {
        Some((b, k)) => match k.parse::<u32>() {
            Ok(k) => (b, Some(k)),
            Err(_) => (name, None),
        },
        None => (name, None),
    }
}

/// Characters allowed in a surface name.
pub fn valid_name_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '-')
}

fn valid_pattern_char(c: char) -> bool {
    valid_name_char(c) || matches!(c, '*' | '?')
}

/// A patch selector: a surface name or glob, with an optional `#k` for patch `k` of each
/// surface it matches (the model's patch names are `surface#k`). `H1` selects every patch of
/// `H1`, `H1#2` one of them, `box.*` every box side.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub struct PatchSelector {
    /// The selector as written.
    pub text: String,
    pub surface: SurfaceSelector,
    /// The `#k` patch number, if given.
    pub patch: Option<u32>,
}

impl PatchSelector {
    /// Parses `surface#k`. Errors are worded for users; the caller adds the recipe location.
    pub fn parse(text: &str) -> Result<PatchSelector, SelectorError> {
        let (surface, patch) = split_component(text);
        if text.matches('#').count() > 1 {
            return Err(SelectorError::TwoComponents);
        }
        if let Some((_, k)) = text.split_once('#')
            && patch.is_none()
        {
            return Err(SelectorError::Component(k.to_string()));
        }
        if surface.is_empty() {
            return Err(SelectorError::EmptySide);
        }
        if let Some(c) = surface.chars().find(|c| !valid_pattern_char(*c)) {
            return Err(SelectorError::Character(c));
        }
        Ok(PatchSelector {
            text: text.to_string(),
            surface: SurfaceSelector::new(surface),
            patch,
        })
    }

    /// Whether the patch named `patch_name` (`surface#k`, as the model names patches) is
    /// selected.
    pub fn matches(&self, patch_name: &str) -> bool {
        let (surface, k) = split_component(patch_name);
        self.surface.matches(surface) && self.patch.is_none_or(|p| k == Some(p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_star_matches_any_run_and_a_question_mark_one_character() {
        assert!(glob_match("box.*", "box.xmin"));
        assert!(glob_match("f?", "f1"));
        assert!(!glob_match("f?", "f12"));
        assert!(glob_match("*", ""));
        assert!(glob_match("a*b*c", "aXXbYYc"));
        assert!(!glob_match("a*b*c", "aXXbYY"));
        assert!(!glob_match("top", "top2"));
    }

    #[test]
    fn a_two_sided_selector_matches_in_either_order_and_respects_the_component() {
        let s = CurveSelector::parse("f1/top").unwrap();
        assert!(s.matches("top/f1"));
        assert!(s.matches("f1/top#2"));
        assert!(!s.matches("top#3"));
        let s = CurveSelector::parse("top/f1#2").unwrap();
        assert!(s.matches("f1/top#2"));
        assert!(!s.matches("f1/top#1"));
        assert!(!s.matches("f1/top"));
    }

    #[test]
    fn a_one_sided_selector_matches_every_curve_of_the_surface_including_free_boundaries() {
        for text in ["top", "top/*", "*/top"] {
            let s = CurveSelector::parse(text).unwrap();
            assert!(s.matches("top/f1"), "{text}");
            assert!(s.matches("box.xmin/top"), "{text}");
            assert!(s.matches("top#3"), "{text}");
            assert!(!s.matches("base/f1"), "{text}");
        }
    }

    #[test]
    fn the_same_surface_cannot_fill_both_sides_of_a_two_sided_selector() {
        let s = CurveSelector::parse("f*/f*").unwrap();
        assert!(s.matches("f1/f2"));
        assert!(!s.matches("f1#1"));
        assert!(!s.matches("f1/top"));
    }

    #[test]
    fn malformed_selectors_are_rejected_with_a_reason() {
        assert!(CurveSelector::parse("a/b/c").is_err());
        assert!(CurveSelector::parse("a/").is_err());
        assert!(CurveSelector::parse("a#x").is_err());
        assert!(CurveSelector::parse("a b").is_err());
    }

    #[test]
    fn a_patch_selector_takes_every_patch_of_its_surfaces_or_only_the_numbered_one() {
        let all = PatchSelector::parse("box.x*").unwrap();
        assert!(all.matches("box.xmin#1") && all.matches("box.xmax#3"));
        assert!(!all.matches("box.ymin#1"));
        let one = PatchSelector::parse("H1#2").unwrap();
        assert!(one.matches("H1#2") && !one.matches("H1#12") && !one.matches("H10#2"));
        for bad in ["H1#x", "H1#2#3", "#2", "H1/F1", "H 1"] {
            assert!(PatchSelector::parse(bad).is_err(), "{bad}");
        }
    }
}
