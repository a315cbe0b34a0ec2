//! The recipe loader never panics: arbitrary text, TOML-like token soup, and valid recipes
//! mutated byte- and line-wise all give `Ok` or a list of positioned diagnostics, and every
//! diagnostic renders and points inside the text.

use std::path::Path;

use georecipe::recipe::{Diagnostic, check_files, parse};
use proptest::prelude::*;

const REFERENCE: &str = include_str!("../data/recipes/reference.toml");
const DIDACTIC: &str = include_str!("../data/recipes/didactic.toml");

/// Parses, and checks what every outcome must satisfy.
fn parse_never_panics(text: &str) {
    match parse(Path::new("fuzz/r.toml"), text) {
        Ok(r) => {
            let _ = check_files(&r, &|_| false);
            for c in &r.mesh.curves {
                let _ = r.diagnostic_at(c.span, "x", None).to_string();
            }
        }
        Err(diags) => {
            assert!(!diags.is_empty(), "Err must carry at least one diagnostic");
            let lines = text.split('\n').count().max(1);
            for d in &diags {
                check_diag(d, lines);
            }
        }
    }
}

fn check_diag(d: &Diagnostic, lines: usize) {
    assert!(
        d.line >= 1 && d.line <= lines,
        "line {} of {lines}: {d:?}",
        d.line
    );
    assert!(d.col >= 1);
    let r = d.to_string();
    assert!(r.contains(&format!("fuzz/r.toml:{}:{}", d.line, d.col)));
}

fn mutate(base: &str, ops: &[(u8, usize, char)]) -> String {
    let mut chars: Vec<char> = base.chars().collect();
    for &(op, pos, c) in ops {
        if chars.is_empty() {
            chars.push(c);
            continue;
        }
        let i = pos % chars.len();
        match op % 5 {
            0 => chars[i] = c,
            1 => chars.insert(i, c),
            2 => {
                chars.remove(i);
            }
            3 => chars.truncate(i),
            _ => {
                // Duplicate the line containing i (duplicate keys and tables).
                let s: String = chars.iter().collect();
                let start = s[..s.char_indices().nth(i).map_or(s.len(), |(b, _)| b)]
                    .rfind('\n')
                    .map_or(0, |p| p + 1);
                let end = s[start..].find('\n').map_or(s.len(), |p| start + p + 1);
                let line = s[start..end].to_string();
                let mut out = s.clone();
                out.insert_str(end, &line);
                if !line.ends_with('\n') {
                    out.insert(end, '\n');
                }
                chars = out.chars().collect();
            }
        }
    }
    chars.into_iter().collect()
}

fn toml_char() -> impl Strategy<Value = char> {
    prop_oneof![
        prop::sample::select(vec![
            '[', ']', '{', '}', '=', ',', '"', '\'', '.', '\n', ' ', '#', '-', '+', '*', '/', '0',
            '1', '9', 'e', '_'
        ]),
        any::<char>(),
    ]
}

fn token() -> impl Strategy<Value = String> {
    prop::sample::select(vec![
        "[model]",
        "[surfaces]",
        "[box]",
        "[mesh]",
        "[mesh.curves]",
        "[mesh.surfaces]",
        "[mesh.regions]",
        "[regions]",
        "[output]",
        "[[trim]]",
        "[intersect]",
        "[tolerances]",
        "name",
        "size",
        "min",
        "max",
        "file",
        "kind",
        "point",
        "surface",
        "keep",
        "discard",
        "pairs",
        "all",
        "count",
        "ratio",
        "grading",
        "formats",
        "around",
        "margin",
        "=",
        "\"top\"",
        "\"box\"",
        "\"f1/box.*\"",
        "\"a.ts\"",
        "\"x.ml\"",
        "nan",
        "inf",
        "-1",
        "0",
        "1e400",
        "2.5",
        "[",
        "]",
        "{",
        "}",
        ",",
        "\n",
        "true",
        "\"horizon\"",
        "\"msh\"",
        "[0, 0, 0]",
        "[1, 1, 1]",
        "{ size = 1 }",
        "top",
        "f1",
        "\"top/f1#2\"",
        "\"#\"",
        "\"\"",
        "'",
        "below",
        "above",
        "containing",
        "area_below",
        "material",
        "properties",
    ])
    .prop_map(str::to_string)
}

proptest! {
    // FUZZ_CASES sets the count (`.ci/run` runs a longer, bounded hunt).
    #![proptest_config(test_support::proptest_config(test_support::fuzz_cases(512)))]

    #[test]
    fn arbitrary_strings_never_panic(text in ".{0,400}") {
        parse_never_panics(&text);
    }

    #[test]
    fn toml_like_character_soup_never_panics(chars in prop::collection::vec(toml_char(), 0..300)) {
        parse_never_panics(&chars.into_iter().collect::<String>());
    }

    #[test]
    fn recipe_token_soup_never_panics(tokens in prop::collection::vec(token(), 0..120), seps in prop::collection::vec(prop::sample::select(vec![" ", "\n", ""]), 120)) {
        let text: String = tokens.iter().zip(seps.iter().cycle()).map(|(t, s)| format!("{t}{s}")).collect();
        parse_never_panics(&text);
    }

    #[test]
    fn mutated_reference_recipes_never_panic(ops in prop::collection::vec((any::<u8>(), any::<usize>(), toml_char()), 1..8)) {
        parse_never_panics(&mutate(REFERENCE, &ops));
    }

    #[test]
    fn mutated_didactic_recipes_never_panic(ops in prop::collection::vec((any::<u8>(), any::<usize>(), toml_char()), 1..8)) {
        parse_never_panics(&mutate(DIDACTIC, &ops));
    }
}

#[test]
fn deeply_nested_input_is_an_error_not_a_stack_overflow() {
    let text = format!(
        "[model]\nname = {}{}\n",
        "[".repeat(100_000),
        "]".repeat(100_000)
    );
    let d = parse(Path::new("fuzz/r.toml"), &text).unwrap_err();
    assert_eq!(d[0].line, 2);
}

#[test]
fn an_empty_recipe_reports_the_missing_tables() {
    let d = parse(Path::new("fuzz/r.toml"), "").unwrap_err();
    assert_eq!(d.len(), 2);
    assert!(d.iter().all(|d| d.line == 1 && d.col == 1));
}
