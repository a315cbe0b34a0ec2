//! Generated recipes with tens of thousands of entries: the checker's answers (what is accepted,
//! which line a repeat names) stay right at that size. The time is measured in
//! `benches/recipe_check.rs`, not here; only how it grows with the entries is tested.

use std::path::Path;

use georecipe::recipe::{Diagnostic, Recipe, parse};
use test_support::big_recipe::{self, FIRST_ENTRY_LINE};

const FILE: &str = "recipes/big.toml";
const N: usize = 20_000;

fn parsed(text: &str) -> Result<Recipe, Vec<Diagnostic>> {
    parse(Path::new(FILE), text)
}

#[test]
fn twenty_thousand_regions_at_distinct_points_are_all_accepted() {
    let r = parsed(&big_recipe::regions(N)).expect("valid");
    assert_eq!(r.regions.len(), N);
}

#[test]
fn a_region_repeating_a_point_far_up_is_refused_naming_that_regions_line() {
    let (x, y) = big_recipe::region_xy(7);
    let text = format!(
        "{}late = {{ point = [{x}, {y}, -5.0] }}\n",
        big_recipe::regions(N)
    );
    let d = parsed(&text).expect_err("a shared point");
    assert_eq!(d.len(), 1, "{d:?}");
    let want = format!("same point as region `r7` (line {})", FIRST_ENTRY_LINE + 7);
    assert!(d[0].message.contains(&want), "{}", d[0]);
    assert_eq!(d[0].line, FIRST_ENTRY_LINE + N);
}

#[test]
fn a_point_written_as_minus_zero_is_the_same_point_as_zero() {
    let text = big_recipe::regions(0)
        .replace("min = [0.0, 0.0, -10.0]", "min = [-1.0, -1.0, -10.0]")
        + "a = { point = [0.0, 1.0, -5.0] }\nb = { point = [-0.0, 1.0, -5.0] }\n";
    let d = parsed(&text).expect_err("one point");
    assert_eq!(d.len(), 1, "{d:?}");
    assert!(
        d[0].message.contains("same point as region `a`"),
        "{}",
        d[0]
    );
}

#[test]
fn twenty_thousand_curve_rules_are_all_accepted() {
    let r = parsed(&big_recipe::curve_rules(N)).expect("valid");
    assert_eq!(r.mesh.curves.len(), N);
}

#[test]
fn a_curve_rule_repeated_in_the_other_order_far_down_names_the_first_rules_line() {
    let text = format!(
        "{}\"f1/top#3\" = {{ count = 4 }}\n",
        big_recipe::curve_rules(N)
    );
    let d = parsed(&text).expect_err("a repeat");
    assert_eq!(d.len(), 1, "{d:?}");
    let want = format!("repeats `top/f1#3` (line {})", FIRST_ENTRY_LINE + 3);
    assert!(d[0].message.contains(&want), "{}", d[0]);
}

#[test]
fn every_one_of_thousands_of_repeated_names_is_reported_at_its_repeat_naming_its_first_line() {
    let n = 5_000;
    let d = parsed(&big_recipe::repeated_region_names(n)).expect_err("repeats");
    assert_eq!(d.len(), n);
    for (i, e) in d.iter().enumerate() {
        let first = FIRST_ENTRY_LINE + 2 * i;
        assert_eq!(e.line, first + 1, "{e}");
        assert!(e.message.contains(&format!("`r{i}`")), "{e}");
        let help = e.help.as_deref().unwrap_or("");
        assert!(help.contains(&format!("line {first}:")), "{e}");
    }
}

#[test]
fn property_names_over_the_budget_are_refused_once_at_the_first_name_too_many() {
    use georecipe::recipe::MAX_PROPERTY_NAMES;
    let mut text = big_recipe::regions(0);
    for r in 0..3 {
        let props: Vec<String> = (0..MAX_PROPERTY_NAMES)
            .map(|k| format!("p{} = 1.0", r * 100 + k))
            .collect();
        text.push_str(&format!(
            "r{r} = {{ point = [1.{r}, 1.0, -5.0], properties = {{ {} }} }}\n",
            props.join(", ")
        ));
    }
    let d = parsed(&text).expect_err("too many property names");
    assert_eq!(d.len(), 1, "{d:?}");
    assert!(
        d[0].message.contains("one name more than the 1024"),
        "{}",
        d[0]
    );
    assert_eq!(d[0].line, FIRST_ENTRY_LINE + 1, "{}", d[0]);
    // Exactly the budget, shared by several regions, is accepted.
    let mut text = big_recipe::regions(0);
    for r in 0..3 {
        let props: Vec<String> = (0..MAX_PROPERTY_NAMES)
            .map(|k| format!("p{k} = 1.0"))
            .collect();
        text.push_str(&format!(
            "r{r} = {{ point = [1.{r}, 1.0, -5.0], properties = {{ {} }} }}\n",
            props.join(", ")
        ));
    }
    assert_eq!(parsed(&text).expect("at the budget").regions.len(), 3);
}

#[test]
fn an_error_far_along_a_very_long_line_quotes_a_window_around_it() {
    let props: Vec<String> = (0..1000)
        .map(|k| format!("a_rather_long_property_name_{k:05} = 1.0"))
        .collect();
    let mut props = props.join(", ");
    props.push_str(", bad = \"x\"");
    let text = format!(
        "{}r = {{ point = [1.0, 1.0, -5.0], properties = {{ {props} }} }}\n",
        big_recipe::regions(0)
    );
    let d = parsed(&text).expect_err("a property that is not a number");
    let e = &d[0];
    assert!(e.col > 30_000, "{}", e.col);
    assert!(e.snippet.chars().count() <= 162, "{}", e.snippet.len());
    assert!(e.snippet.starts_with('…'), "{}", e.snippet);
    let shown = e.to_string();
    let caret_line = shown.lines().find(|l| l.contains('^')).expect("a caret");
    let quoted = shown
        .lines()
        .find(|l| l.contains("bad = "))
        .expect("the line quoted");
    // The caret stands under the quoted value.
    let caret = caret_line.find('^').unwrap();
    assert_eq!(
        quoted.chars().nth(caret_line[..caret].chars().count()),
        Some('"'),
        "{shown}"
    );
}

/// The fastest of three parses of `text`.
fn fastest_parse(text: &str) -> std::time::Duration {
    (0..3)
        .map(|_| {
            let t = std::time::Instant::now();
            let _ = parsed(text);
            t.elapsed()
        })
        .min()
        .expect("three runs")
}

/// Eight times the entries take about eight times as long: a check whose work grows with the
/// square of the entries (each compared with every other, as it once was: 100,000 regions took
/// 81 s) takes 64 times as long. The bound, 24, leaves room for a busy machine's noise
/// between the two sizes. A ratio of two times is compared, never a time against a target.
#[test]
fn checking_eight_times_the_regions_or_curve_rules_takes_far_less_than_sixty_four_times_as_long() {
    let (few, many) = (5_000, 40_000);
    for (what, make) in [
        ("regions", big_recipe::regions as fn(usize) -> String),
        ("curve rules", big_recipe::curve_rules),
    ] {
        let (small, big) = (make(few), make(many));
        let ratio = fastest_parse(&big).as_secs_f64() / fastest_parse(&small).as_secs_f64();
        assert!(
            ratio < 24.0,
            "{what}: {many} entries took {ratio:.1} times as long as {few}"
        );
    }
}
