//! Selector semantics the planner relies on: the glob matcher agrees with a straightforward
//! reference definition, curve selectors are symmetric in their two sides, and one-sided
//! selectors select exactly the curves that involve the surface.

use georecipe::recipe::{CurveSelector, SurfaceSelector, glob_match};
use proptest::prelude::*;

/// Reference glob semantics by dynamic programming over (pattern prefix, text prefix).
fn reference_glob(p: &[char], t: &[char]) -> bool {
    let mut m = vec![vec![false; t.len() + 1]; p.len() + 1];
    m[0][0] = true;
    for i in 1..=p.len() {
        m[i][0] = m[i - 1][0] && p[i - 1] == '*';
        for j in 1..=t.len() {
            m[i][j] = match p[i - 1] {
                '*' => m[i - 1][j] || m[i][j - 1],
                '?' => m[i - 1][j - 1],
                c => m[i - 1][j - 1] && c == t[j - 1],
            };
        }
    }
    m[p.len()][t.len()]
}

fn name() -> impl Strategy<Value = String> {
    "[abx.1]{1,5}"
}

fn pattern() -> impl Strategy<Value = String> {
    "[abx.1*?]{1,5}"
}

proptest! {
    #![proptest_config(test_support::proptest_config(2000))]

    #[test]
    fn the_glob_matcher_agrees_with_the_reference_definition(p in "[ab*?]{0,7}", t in "[ab]{0,9}") {
        let pc: Vec<char> = p.chars().collect();
        let tc: Vec<char> = t.chars().collect();
        prop_assert_eq!(glob_match(&p, &t), reference_glob(&pc, &tc));
    }

    #[test]
    fn a_two_sided_selector_does_not_depend_on_side_order(a in pattern(), b in pattern(), x in name(), y in name(), k in prop::option::of(0u32..3)) {
        let suffix = k.map(|k| format!("#{k}")).unwrap_or_default();
        let ab = CurveSelector::parse(&format!("{a}/{b}{suffix}"));
        let ba = CurveSelector::parse(&format!("{b}/{a}{suffix}"));
        prop_assert!(ab.is_ok() && ba.is_ok());
        let (ab, ba) = (ab.unwrap_or_else(|_| unreachable!()), ba.unwrap_or_else(|_| unreachable!()));
        prop_assert_eq!(&ab.sides, &ba.sides);
        for curve in [format!("{x}/{y}"), format!("{y}/{x}#1"), format!("{x}#2"), format!("{x}/{y}#0")] {
            prop_assert_eq!(ab.matches(&curve), ba.matches(&curve), "{}", curve);
        }
    }

    #[test]
    fn a_one_sided_selector_selects_the_curves_that_involve_a_matching_surface(a in pattern(), x in name(), y in name()) {
        let s = CurveSelector::parse(&a).unwrap_or_else(|_| unreachable!());
        let surf = SurfaceSelector::new(&a);
        let expected = surf.matches(&x) || surf.matches(&y);
        prop_assert_eq!(s.matches(&format!("{x}/{y}")), expected);
        prop_assert_eq!(s.matches(&format!("{x}#4")), surf.matches(&x));
    }
}

#[test]
fn a_glob_with_many_stars_is_matched_in_linear_memory_without_recursion() {
    let p = "*a".repeat(2000);
    let t = "a".repeat(5000);
    assert!(glob_match(&p, &t));
    assert!(!glob_match(&format!("{p}b"), &t));
}
