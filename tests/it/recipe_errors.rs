//! Every error class of the recipe language names `file:line:col`, shows the offending text and,
//! where a likely intended name exists, suggests it.

use std::path::Path;

use georecipe::recipe::{Diagnostic, FileKind, Format, Recipe, check_files, parse};

const FILE: &str = "recipes/bad.toml";

/// A small valid recipe the tests extend or edit.
const BASE: &str = test_support::big_recipe::HEAD;

fn errors(text: &str) -> Vec<Diagnostic> {
    match parse(Path::new(FILE), text) {
        Ok(_) => panic!("expected errors, the recipe parsed:\n{text}"),
        Err(d) => d,
    }
}

fn ok(text: &str) -> Recipe {
    match parse(Path::new(FILE), text) {
        Ok(r) => r,
        Err(d) => panic!(
            "expected Ok, got:\n{}",
            d.iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join("\n")
        ),
    }
}

/// The 1-based line and column of the `nth` occurrence (0-based) of `needle` in `text`.
fn loc(text: &str, needle: &str, nth: usize) -> (usize, usize) {
    let at = text
        .match_indices(needle)
        .nth(nth)
        .map(|(i, _)| i)
        .expect("needle in text");
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().unwrap_or("").chars().count() + 1;
    (line, col)
}

/// The single error of `text`, checked to point at the `nth` occurrence of `needle`, to show it
/// in the rendered snippet, and to name `file:line:col`.
fn single_at(text: &str, needle: &str, nth: usize) -> (Diagnostic, String) {
    let d = errors(text);
    assert_eq!(
        d.len(),
        1,
        "expected one error, got:\n{}",
        d.iter()
            .map(|d| d.to_string())
            .collect::<Vec<_>>()
            .join("\n")
    );
    let d = d.into_iter().next().unwrap_or_else(|| unreachable!());
    let (line, col) = loc(text, needle, nth);
    let rendered = d.to_string();
    assert_eq!(
        (d.line, d.col),
        (line, col),
        "wrong position in:\n{rendered}"
    );
    assert!(
        rendered.contains(&format!("{FILE}:{line}:{col}")),
        "{rendered}"
    );
    assert!(
        d.snippet.contains(needle),
        "snippet {:?} lacks {needle:?}",
        d.snippet
    );
    (d, rendered)
}

#[test]
fn an_unknown_top_level_key_names_the_position_and_suggests_the_table() {
    let text = format!("{BASE}\n[outptu]\ndir = \"x\"\n");
    let (d, r) = single_at(&text, "outptu", 0);
    assert!(d.message.contains("unknown key `outptu`"), "{r}");
    assert_eq!(d.help.as_deref(), Some("did you mean `output`?"), "{r}");
}

#[test]
fn an_unknown_nested_key_is_underlined_and_gets_a_did_you_mean() {
    let text = format!("{BASE}[mesh.curves]\n\"top/f1\" = {{ szie = 25.0 }}\n");
    let (d, r) = single_at(&text, "szie", 0);
    assert!(
        d.message
            .contains("unknown key `szie` in `mesh.curves.\"top/f1\"`"),
        "{r}"
    );
    assert_eq!(d.help.as_deref(), Some("did you mean `size`?"));
    assert!(r.contains("^^^^\n"), "four carets under `szie`:\n{r}");
}

#[test]
fn the_rendering_is_rustc_style_with_gutter_snippet_caret_and_help() {
    let text = format!("{BASE}[mesh.curves]\n\"top/f1\" = {{ szie = 25.0 }}\n");
    let d = errors(&text);
    let expected = "error: unknown key `szie` in `mesh.curves.\"top/f1\"`\n  --> recipes/bad.toml:16:14\n   |\n16 | \"top/f1\" = { szie = 25.0 }\n   |              ^^^^\n   = help: did you mean `size`?";
    assert_eq!(d[0].to_string(), expected);
}

#[test]
fn a_misspelled_surface_option_suggests_the_option() {
    let text = BASE.replace("kind = \"fault\"", "knid = \"fault\"");
    let (d, _) = single_at(&text, "knid", 0);
    assert_eq!(d.help.as_deref(), Some("did you mean `kind`?"));
}

#[test]
fn a_wrong_type_names_the_expected_type_and_the_value() {
    let text = BASE.replace("size = 1.0", "size = \"1.0\"");
    let (d, r) = single_at(&text, "\"1.0\"", 0);
    assert!(
        d.message
            .contains("`mesh.size` must be a number, found a string `\"1.0\"`"),
        "{r}"
    );
    assert!(
        d.help
            .as_deref()
            .is_some_and(|h| h.contains("without quotes")),
        "{r}"
    );
}

#[test]
fn a_misspelled_kind_value_suggests_the_valid_word() {
    let text = BASE.replace("kind = \"fault\"", "kind = \"faut\"");
    let (d, r) = single_at(&text, "\"faut\"", 0);
    assert!(d.message.contains("`surfaces.f1.kind`"), "{r}");
    assert_eq!(d.help.as_deref(), Some("did you mean `fault`?"));
}

#[test]
fn a_duplicate_surface_name_points_at_the_second_and_names_the_first_line() {
    let text = BASE.replace("f1 = {", "top = { file = \"data/t2.ts\" }\nf1 = {");
    let (d, r) = single_at(&text, "top", 2);
    assert!(d.message.contains("duplicate surface name `top`"), "{r}");
    assert!(
        d.help.as_deref().is_some_and(|h| h.contains("line 5")),
        "{r}"
    );
}

#[test]
fn a_table_defined_twice_is_reported_with_its_first_line() {
    let text = format!("{BASE}\n[mesh]\ngrowth = 1.2\n");
    let d = errors(&text);
    assert_eq!(d.len(), 1);
    let r = d[0].to_string();
    assert!(r.contains("`[mesh]` is defined twice"), "{r}");
    assert!(r.contains("line 13"), "{r}");
}

#[test]
fn a_duplicate_curve_rule_written_in_the_other_order_is_an_error() {
    let text = format!(
        "{BASE}[mesh.curves]\n\"top/f1\" = {{ size = 2.0 }}\n\"f1/top\" = {{ count = 3 }}\n"
    );
    let (d, r) = single_at(&text, "\"f1/top\"", 0);
    assert!(d.message.contains("repeats `top/f1` (line 16)"), "{r}");
}

#[test]
fn a_selector_that_matches_no_surface_suggests_the_closest_name() {
    let text = format!("{BASE}[mesh.curves]\n\"topp/f1\" = {{ size = 2.0 }}\n");
    let (d, r) = single_at(&text, "topp", 0);
    assert!(
        d.message.contains("`topp`") && d.message.contains("matches no surface"),
        "{r}"
    );
    assert_eq!(d.help.as_deref(), Some("did you mean `top`?"));
}

#[test]
fn a_glob_over_box_sides_with_a_typo_suggests_the_box_glob() {
    let text = format!("{BASE}[mesh.curves]\n\"f1/bx.*\" = {{ count = 4 }}\n");
    let (d, r) = single_at(&text, "bx.*", 0);
    assert_eq!(d.help.as_deref(), Some("did you mean `box.*`?"), "{r}");
}

#[test]
fn a_surface_size_selector_that_matches_nothing_is_an_error() {
    let text = format!("{BASE}[mesh.surfaces]\n\"g*\" = {{ size = 2.0 }}\n");
    let (d, r) = single_at(&text, "\"g*\"", 0);
    assert!(d.message.contains("matches no surface"), "{r}");
}

#[test]
fn a_missing_file_names_the_recipe_position_and_the_resolved_path() {
    let r = ok(BASE);
    let d = check_files(&r, &|p: &Path| p != Path::new("recipes/data/f1.ts"));
    assert_eq!(d.len(), 1);
    let (line, col) = loc(BASE, "\"data/f1.ts\"", 0);
    let text = d[0].to_string();
    assert!(text.contains(&format!("{FILE}:{line}:{col}")), "{text}");
    assert!(
        text.contains("`data/f1.ts`") && text.contains("`recipes/data/f1.ts`"),
        "{text}"
    );
}

#[test]
fn a_missing_file_suggests_the_existing_file_in_another_case_or_directory() {
    let r = ok(&BASE.replace("data/f1.ts", "dat/F1.ts"));
    let exists = |p: &Path| p != Path::new("recipes/dat/F1.ts");
    let d = check_files(&r, &exists);
    assert_eq!(d.len(), 1);
    assert_eq!(d[0].help.as_deref(), Some("did you mean `data/F1.ts`?"));
    let d = check_files(&r, &|p: &Path| p == Path::new("recipes/dat/f1.ts"));
    let f1 = d
        .iter()
        .find(|d| d.message.contains("`f1`"))
        .expect("f1 reported");
    assert_eq!(f1.help.as_deref(), Some("did you mean `dat/f1.ts`?"));
}

#[test]
fn a_missing_file_suggests_the_closest_name_from_a_directory_listing() {
    let r = ok(&BASE.replace("data/f1.ts", "data/fault1.ts"));
    let list = |d: &Path| {
        if d == Path::new("recipes/data") {
            vec!["fault_1.ts".to_string(), "top.ts".to_string()]
        } else {
            vec![]
        }
    };
    let d = georecipe::recipe::check_files_with_listing(
        &r,
        &|p: &Path| {
            if p.ends_with("fault1.ts") {
                FileKind::Missing
            } else {
                FileKind::File
            }
        },
        &list,
    );
    assert_eq!(d.len(), 1);
    assert_eq!(
        d[0].help.as_deref(),
        Some("did you mean `data/fault_1.ts`?")
    );
}

#[test]
fn a_box_whose_min_is_not_below_max_names_the_axis() {
    let text = BASE.replace("max = [10.0, 10.0, 0.0]", "max = [10.0, 0.0, 0.0]");
    let (d, r) = single_at(&text, "0.0, 0.0]", 0);
    assert!(
        d.message
            .contains("`min` y = 0 is not less than `max` y = 0"),
        "{r}"
    );
}

#[test]
fn a_bad_output_format_suggests_the_closest_format() {
    let text = format!("{BASE}[output]\nformats = [\"msh\", \"vtk\"]\n");
    let (d, r) = single_at(&text, "\"vtk\"", 0);
    assert!(d.message.contains("`output.formats[1]`"), "{r}");
    assert_eq!(d.help.as_deref(), Some("did you mean `vtu`?"));
}

#[test]
fn nan_infinite_and_negative_sizes_are_each_reported_at_their_value() {
    let text = BASE.replace(
        "size = 1.0",
        "size = nan\nmin_size = inf\nmax_size = -3.0\ngrowth = 1.0",
    );
    let d = errors(&text);
    let r: Vec<String> = d.iter().map(|d| d.to_string()).collect();
    assert_eq!(d.len(), 4, "{r:#?}");
    assert!(
        d[0].message
            .contains("`mesh.size` = `nan` is not a finite number"),
        "{r:#?}"
    );
    assert!(
        d[1].message
            .contains("`mesh.min_size` = `inf` is not a finite number"),
        "{r:#?}"
    );
    assert!(
        d[2].message
            .contains("`mesh.max_size` = `-3.0` must be greater than 0"),
        "{r:#?}"
    );
    assert!(
        d[3].message
            .contains("`mesh.growth` = `1.0` must be greater than 1"),
        "{r:#?}"
    );
    assert_eq!((d[0].line, d[0].col), loc(&text, "nan", 0));
    assert_eq!((d[2].line, d[2].col), loc(&text, "-3.0", 0));
}

#[test]
fn an_overflowing_float_literal_is_not_finite() {
    let text = BASE.replace("size = 1.0", "size = 1e400");
    let (d, _) = single_at(&text, "1e400", 0);
    assert!(d.message.contains("not a finite number"));
}

#[test]
fn a_negative_retriangulation_size_is_rejected() {
    let text = BASE.replace("kind = \"fault\"", "kind = \"fault\", retriangulate = -5");
    let (d, _) = single_at(&text, "-5", 0);
    assert!(
        d.message
            .contains("`surfaces.f1.retriangulate` = `-5` must be greater than 0")
    );
}

#[test]
fn smoothing_levels_out_of_range_and_a_smooth_of_the_wrong_type_are_rejected_at_the_value() {
    let text = BASE.replace(
        "kind = \"fault\"",
        "kind = \"fault\", smooth = { levels = 9 }",
    );
    let (d, r) = single_at(&text, "9", 0);
    assert!(
        d.message
            .contains("`surfaces.f1.smooth.levels` = 9 is out of range"),
        "{r}"
    );
    assert!(
        d.help.as_deref().is_some_and(|h| h.contains("1 to 4")),
        "{r}"
    );
    let text = BASE.replace("kind = \"fault\"", "kind = \"fault\", smooth = \"yes\"");
    let (d, r) = single_at(&text, "\"yes\"", 0);
    assert!(d.message.contains("surfaces.f1.smooth"), "{r}");
    let text = BASE.replace(
        "kind = \"fault\"",
        "kind = \"fault\", smooth = { level = 2 }",
    );
    let (d, r) = single_at(&text, "level", 0);
    assert!(d.message.contains("level"), "{r}");
}

#[test]
fn smooth_true_takes_the_default_levels_and_passes_and_false_turns_it_off() {
    let on = ok(&BASE.replace("kind = \"fault\"", "kind = \"fault\", smooth = true"));
    assert_eq!(
        on.surfaces["f1"].smooth,
        Some(surface_mesh::SupportSmoothing::default())
    );
    let off = ok(&BASE.replace("kind = \"fault\"", "kind = \"fault\", smooth = false"));
    assert_eq!(off.surfaces["f1"].smooth, None);
    let some = ok(&BASE.replace(
        "kind = \"fault\"",
        "kind = \"fault\", smooth = { passes = 5 }",
    ));
    assert_eq!(
        some.surfaces["f1"].smooth,
        Some(surface_mesh::SupportSmoothing {
            levels: 2,
            passes: 5
        })
    );
}

#[test]
fn a_surface_named_like_a_box_side_is_reserved() {
    let text = BASE.replace("f1 = {", "\"box.x\" = {");
    let (d, r) = single_at(&text, "\"box.x\"", 0);
    assert!(
        d.message.contains("surface name `box.x` is reserved"),
        "{r}"
    );
    assert!(d.help.is_some());
}

#[test]
fn a_surface_name_with_a_slash_is_rejected_with_a_fixed_name() {
    let text = BASE.replace("f1 = {", "\"f/1\" = {");
    let (d, r) = single_at(&text, "\"f/1\"", 0);
    assert!(d.message.contains("contains `/`"), "{r}");
    assert!(
        d.help.as_deref().is_some_and(|h| h.contains("`f_1`")),
        "{r}"
    );
}

#[test]
fn an_intersect_pair_of_a_surface_with_itself_is_an_error() {
    let text = format!("{BASE}[intersect]\npairs = [[\"top\", \"f1\"], [\"f1\", \"f1\"]]\n");
    let (d, r) = single_at(&text, "[\"f1\", \"f1\"]", 0);
    assert!(d.message.contains("pairs `f1` with itself"), "{r}");
}

#[test]
fn an_intersect_pair_with_an_unknown_name_suggests_the_known_one() {
    let text = format!("{BASE}[intersect]\npairs = [[\"top\", \"fl\"]]\n");
    let (d, r) = single_at(&text, "\"fl\"", 0);
    assert!(d.message.contains("unknown surface `fl`"), "{r}");
    assert_eq!(d.help.as_deref(), Some("did you mean `f1`?"));
}

#[test]
fn a_surface_without_a_misspelled_file_key_gets_only_the_did_you_mean() {
    let text = BASE.replace("{ file = \"data/f1.ts\"", "{ fiel = \"data/f1.ts\"");
    let (d, _) = single_at(&text, "fiel", 0);
    assert_eq!(d.help.as_deref(), Some("did you mean `file`?"));
}

#[test]
fn the_design_sample_intersect_written_after_box_explains_the_toml_trap() {
    let text = BASE.replace(
        "max = [10.0, 10.0, 0.0]",
        "max = [10.0, 10.0, 0.0]\nintersect = [[\"top\", \"f1\"]]",
    );
    let (d, r) = single_at(&text, "intersect", 0);
    assert!(
        d.message.contains("unknown key `intersect` in `box`"),
        "{r}"
    );
    assert!(
        d.help
            .as_deref()
            .is_some_and(|h| h.contains("move it above `[box]`")),
        "{r}"
    );
}

#[test]
fn a_top_level_intersect_array_is_the_pairs_shorthand() {
    let text = format!("intersect = [[\"top\", \"f1\"], [\"f1\", \"box\"]]\n{BASE}");
    let r = ok(&text);
    assert_eq!(r.intersect.len(), 7);
    assert!(r.intersect.contains(&("f1".to_string(), "top".to_string())));
}

#[test]
fn a_trim_referring_to_an_unknown_surface_suggests_the_name() {
    let text = format!("{BASE}[[trim]]\nsurface = \"f1\"\nkeep = {{ below = \"tpo\" }}\n");
    let (d, r) = single_at(&text, "\"tpo\"", 0);
    assert!(d.message.contains("unknown surface `tpo`"), "{r}");
    assert_eq!(d.help.as_deref(), Some("did you mean `top`?"));
}

#[test]
fn a_trim_with_two_actions_is_an_error() {
    let text = format!(
        "{BASE}[[trim]]\nsurface = \"f1\"\nkeep = {{ below = \"top\" }}\ndiscard = {{ area_below = 3.0 }}\n"
    );
    let (d, _) = single_at(&text, "{ area_below = 3.0 }", 0);
    assert!(d.message.contains("both `keep` and `discard`"));
}

#[test]
fn a_region_size_for_an_unnamed_region_suggests_the_region() {
    let text = format!(
        "{BASE}[mesh.regions]\nreservior = {{ size = 0.5 }}\n[regions]\nreservoir = {{ point = [1.0, 1.0, -1.0] }}\n"
    );
    let (d, r) = single_at(&text, "reservior", 0);
    assert!(d.message.contains("unknown region `reservior`"), "{r}");
    assert_eq!(d.help.as_deref(), Some("did you mean `reservoir`?"));
}

#[test]
fn a_toml_syntax_error_names_the_line_and_column() {
    let text = BASE.replace("size = 1.0", "size = 1.0.0");
    let d = errors(&text);
    assert_eq!(d.len(), 1);
    let r = d[0].to_string();
    assert!(r.starts_with("error: TOML syntax error"), "{r}");
    assert_eq!(d[0].line, loc(&text, "size = 1.0.0", 0).0, "{r}");
    assert!(d[0].snippet.contains("1.0.0"), "{r}");
}

#[test]
fn several_errors_are_reported_at_once_in_source_order() {
    let text = BASE
        .replace("kind = \"fault\"", "kind = \"faultt\"")
        .replace("size = 1.0", "size = -1.0\nsizee = 2");
    let d = errors(&text);
    assert_eq!(d.len(), 3, "{d:#?}");
    assert!(
        d.windows(2)
            .all(|w| (w[0].line, w[0].col) <= (w[1].line, w[1].col))
    );
}

#[test]
fn a_missing_model_and_mesh_are_reported_at_the_start() {
    let d = errors("[surfaces]\n");
    let msgs: Vec<&str> = d.iter().map(|d| d.message.as_str()).collect();
    assert!(
        msgs.contains(&"missing key `model` in the recipe"),
        "{msgs:?}"
    );
    assert!(
        msgs.contains(&"missing key `mesh` in the recipe"),
        "{msgs:?}"
    );
    assert!(d.iter().all(|d| (d.line, d.col) == (1, 1)));
}

#[test]
fn a_curve_count_with_a_ratio_is_rejected() {
    let text = format!("{BASE}[mesh.curves]\n\"top\" = {{ count = 4, ratio = 1.2 }}\n");
    let (d, _) = single_at(&text, "1.2", 0);
    assert!(
        d.message
            .contains("`mesh.curves.top.ratio` applies to a sized subdivision"),
        "{}",
        d.message
    );
}

#[test]
fn a_zero_or_fractional_count_is_rejected() {
    let text =
        format!("{BASE}[mesh.curves]\n\"top\" = {{ count = 0 }}\n\"f1\" = {{ count = 2.5 }}\n");
    let d = errors(&text);
    assert_eq!(d.len(), 2);
    assert!(d[0].message.contains("must be between 1 and"));
    assert!(
        d[1].message
            .contains("must be an integer, found a float `2.5`")
    );
}

#[test]
fn a_trim_written_as_a_plain_table_asks_for_double_brackets() {
    let text = format!("{BASE}[trim]\nsurface = \"f1\"\n");
    let (d, r) = single_at(&text, "[trim]", 0);
    assert!(
        d.message
            .contains("`trim` must be an array of tables, written `[[trim]]`"),
        "{r}"
    );
}

#[test]
fn the_diagnostic_at_a_stored_span_points_back_at_the_recipe() {
    let text = format!("{BASE}[mesh.curves]\n\"top/f1\" = {{ size = 2.0 }}\n");
    let r = ok(&text);
    let rule = &r.mesh.curves[0];
    let d = r.diagnostic_at(
        rule.span,
        "curve selector `top/f1` matches no curve of the model",
        Some("the model has `top/f1#1`".into()),
    );
    assert_eq!((d.line, d.col), loc(&text, "\"top/f1\"", 0));
    assert!(d.to_string().contains("^^^^^^^^"), "{d}");
}

#[test]
fn a_model_name_that_cannot_be_a_file_name_is_rejected() {
    let text = BASE.replace("name = \"t\"", "name = \"../north field\"");
    let (d, r) = single_at(&text, "\"../north field\"", 0);
    assert!(
        d.message
            .contains("model name `../north field` contains `/`"),
        "{r}"
    );
    assert!(
        d.help
            .as_deref()
            .is_some_and(|h| h.contains("`.._north_field`")),
        "{r}"
    );
}

#[test]
fn a_tolerance_out_of_range_or_unknown_is_reported() {
    let text = format!("[tolerances]\nkink_angle_deg = 200\nmerge_dist = 1\n{BASE}");
    let d = errors(&text);
    assert_eq!(d.len(), 2, "{d:#?}");
    assert!(
        d[0].message
            .contains("`tolerances.kink_angle_deg` = `200` must be between 0 and 180"),
        "{}",
        d[0]
    );
    assert_eq!(d[1].help.as_deref(), Some("did you mean `merge_distance`?"));
}

#[test]
fn a_misspelled_trim_condition_gets_only_its_did_you_mean() {
    let text = format!(
        "{BASE}[[trim]]\nsurface = \"f1\"\nkeep = {{ bellow = \"top\" }}\n[[trim]]\nsurface = \"f*\"\ndiscard = {{ area = 10.0 }}\n"
    );
    let d = errors(&text);
    assert_eq!(d.len(), 2, "{d:#?}");
    assert_eq!((d[0].line, d[0].col), loc(&text, "bellow", 0));
    assert_eq!(d[0].help.as_deref(), Some("did you mean `below`?"));
    assert_eq!((d[1].line, d[1].col), loc(&text, "area", 0));
    assert_eq!(d[1].help.as_deref(), Some("did you mean `area_below`?"));
}

#[test]
fn a_trim_keeps_inside_or_outside_a_surface_or_discards_what_hugs_another_and_is_checked() {
    use georecipe::recipe::{Side, TrimAction};
    for (word, side) in [("inside", Side::Inside), ("outside", Side::Outside)] {
        let text = format!("{BASE}[[trim]]\nsurface = \"f1\"\nkeep = {{ {word} = \"top\" }}\n");
        let r = ok(&text);
        assert_eq!(
            r.trims[0].action,
            TrimAction::Keep {
                side,
                of: "top".into()
            }
        );
    }
    let text = format!("{BASE}[[trim]]\nsurface = \"f1\"\nkeep = {{ outide = \"top\" }}\n");
    let d = errors(&text);
    assert_eq!(
        d[0].help.as_deref(),
        Some("did you mean `outside`?"),
        "{d:#?}"
    );
    let text = format!("{BASE}[[trim]]\nsurface = \"f1\"\ndiscard = {{ within = 0.1 }}\n");
    assert_eq!(ok(&text).trims[0].action, TrimAction::DiscardWithin(0.1));
    let text = format!("{BASE}[[trim]]\nsurface = \"f1\"\ndiscard = {{ within = -1.0 }}\n");
    let d = errors(&text);
    assert!(d[0].message.contains("trim[0].discard.within"), "{d:#?}");
}

#[test]
fn a_surface_table_header_form_is_accepted_and_checked_like_the_inline_form() {
    let text = format!("{BASE}[surfaces.f2]\nfile = \"data/f2.ts\"\nkind = \"fualt\"\n");
    let (d, _) = single_at(&text, "\"fualt\"", 0);
    assert!(d.message.contains("`surfaces.f2.kind`"));
    let r = ok(&text.replace("fualt", "fault"));
    assert_eq!(r.surfaces["f2"].kind, georecipe::recipe::SurfaceKind::Fault);
}

#[test]
fn windows_line_endings_and_a_byte_order_mark_keep_positions_right() {
    let text = format!(
        "\u{feff}{}",
        BASE.replace("size = 1.0", "size = -1.0")
            .replace('\n', "\r\n")
    );
    let d = errors(&text);
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!((d[0].line, d[0].col), (14, 8));
    assert_eq!(d[0].snippet, "size = -1.0");
    assert!(d[0].to_string().contains("|        ^^^^"), "{}", d[0]);
}

#[test]
fn the_tet_method_defaults_to_delaunay_is_inherited_by_regions_and_a_wrong_one_is_named() {
    use georecipe::recipe::TetMethod;
    let regions =
        "[regions]\nres = { point = [1.0, 1.0, -1.0] }\nover = { point = [1.0, 1.0, -9.0] }\n";
    let r = ok(&format!("{BASE}{regions}"));
    assert_eq!(r.mesh.tet_method, TetMethod::Delaunay);
    let text = format!(
        "{}[mesh.regions]\nres = {{ size = 0.5, tet_method = \"delaunay\" }}\nover = {{ size = 0.5 }}\n{regions}",
        BASE.replace("size = 1.0", "size = 1.0\ntet_method = \"front\"")
    );
    let r = ok(&text);
    assert_eq!(r.mesh.tet_method, TetMethod::Front);
    assert_eq!(r.mesh.regions["res"].tet_method, TetMethod::Delaunay);
    assert_eq!(r.mesh.regions["over"].tet_method, TetMethod::Front);
    let text = BASE.replace("size = 1.0", "size = 1.0\ntet_method = \"frontal\"");
    let (d, rendered) = single_at(&text, "\"frontal\"", 0);
    assert!(d.message.contains("`mesh.tet_method`"), "{rendered}");
    assert!(rendered.contains("front"), "{rendered}");
}

#[test]
fn two_encodings_of_one_format_are_refused_because_they_write_the_same_file() {
    let text = format!("{BASE}[output]\nformats = [\"vtu\", \"msh\", \"msh-binary\"]\n");
    let (d, rendered) = single_at(&text, "\"msh-binary\"", 0);
    assert!(
        d.message.contains("`msh` and `msh-binary`") && d.message.contains("same file"),
        "{rendered}"
    );
    let r = ok(&format!(
        "{BASE}[output]\nformats = [\"vtu-binary\", \"inp\"]\n"
    ));
    assert_eq!(r.output.formats, [Format::VtuBinary, Format::Inp]);
}

#[test]
fn an_object_is_a_name_or_a_position_counted_from_one() {
    let with = |v: &str| {
        BASE.replace(
            "f1 = { file = \"data/f1.ts\", kind = \"fault\" }",
            &format!("f1 = {{ file = \"data/f1.ts\", kind = \"fault\", object = {v} }}"),
        )
    };
    let r = ok(&with("2"));
    assert_eq!(
        r.surfaces["f1"].object,
        Some(gocad::import::ObjectRef::Position(2))
    );
    let r = ok(&with("\"f1_a\""));
    assert_eq!(
        r.surfaces["f1"].object,
        Some(gocad::import::ObjectRef::Name("f1_a".into()))
    );
    let (d, r) = single_at(&with("0"), "0 }", 0);
    assert!(d.message.contains("not a position in the file"), "{r}");
    assert!(
        d.help.as_deref().is_some_and(|h| h.contains("from 1")),
        "{r}"
    );
    let (d, r) = single_at(&with("1.5"), "1.5", 0);
    assert!(
        d.message
            .contains("an object name (a string) or its position"),
        "{r}"
    );
}

#[test]
fn a_region_point_outside_the_box_names_the_coordinate_the_box_and_the_fix() {
    let text = format!(
        "{BASE}[regions]\nres = {{ point = [1.0, 1.0, -1.0] }}\nover = {{ point = [1.0, 12.5, -9.0] }}\n"
    );
    let (d, r) = single_at(&text, "12.5", 0);
    assert!(d.snippet.contains("over = "), "{r}");
    assert!(
        d.message.contains(
            "region `over`: the point [1, 12.5, -9] is outside the box [0, 0, -10]..[10, 10, 0]: y = 12.5 is above the box's `max` y = 10"
        ),
        "{r}"
    );
    let help = d.help.as_deref().unwrap_or_default();
    assert!(help.contains("`[box]` (line 9)"), "{r}");
    assert!(help.contains("y between 0 and 10"), "{r}");
    assert!(help.contains("move the point"), "{r}");
}

#[test]
fn a_region_point_on_a_side_of_the_box_is_in_no_region() {
    let text = format!("{BASE}[regions]\nres = {{ point = [1.0, 1.0, -10.0] }}\n");
    let (d, r) = single_at(&text, "-10.0]", 1);
    assert!(
        d.message.contains("z = -10 is on the box side `box.zmin`"),
        "{r}"
    );
}

#[test]
fn layers_are_read_per_region_and_globally_and_a_count_out_of_range_is_named() {
    let regions =
        "[regions]\nres = { point = [1.0, 1.0, -1.0] }\nover = { point = [1.0, 1.0, -9.0] }\n";
    let r = ok(&format!("{BASE}{regions}"));
    assert_eq!(r.mesh.min_layers, None);
    let text = format!(
        "{}[mesh.regions]\nres = {{ layers = 3 }}\n{regions}",
        BASE.replace("size = 1.0", "size = 1.0\nmin_layers = 2")
    );
    let r = ok(&text);
    assert_eq!(r.mesh.min_layers, Some(2));
    assert_eq!(r.mesh.regions["res"].layers, Some(3));
    assert!(
        !r.mesh.regions["res"].size_given,
        "layers alone writes no size"
    );
    let text = format!("{BASE}[mesh.regions]\nres = {{ layers = 0 }}\n{regions}");
    let (d, rendered) = single_at(&text, "0 }", 0);
    assert!(
        d.message.contains("`mesh.regions.res.layers` = 0"),
        "{rendered}"
    );
    let text = BASE.replace("size = 1.0", "size = 1.0\nmin_layers = 1000");
    let (d, rendered) = single_at(&text, "1000", 0);
    assert!(d.message.contains("between 1 and 100"), "{rendered}");
}

#[test]
fn close_curves_are_refined_where_a_mesh_fails_unless_the_recipe_says_otherwise() {
    let with = |v: &str| {
        let text = BASE.replace(
            "size = 1.0",
            &format!("size = 1.0\nrefine_close_curves = {v}"),
        );
        ok(&text).mesh.refine_close_curves
    };
    // Unwritten: no place from the start, the places where a mesh fails.
    let default = ok(BASE).mesh.refine_close_curves;
    assert!(!default.all && default.named.is_empty() && default.on_failure);
    assert!(!default.refines(["top/f1#1"].into_iter()));
    // `true`: every place; `false`: none, not even where a mesh fails.
    assert!(with("true").refines(["top/f1#1"].into_iter()));
    let off = with("false");
    assert!(!off.on_failure && !off.refines(["top/f1#1"].into_iter()));
    // A list: the places of the curves it selects, in either order of their surfaces.
    let listed = with("[\"f1/top#2\", \"base\"]");
    assert!(listed.on_failure && !listed.all);
    assert!(listed.refines(["top/f1#2"].into_iter()));
    assert!(listed.refines(["base/f1#7"].into_iter()));
    assert!(!listed.refines(["top/f1#1", "f1#3"].into_iter()));
    // Anything else is an error at its place, naming what it may be.
    let text = BASE.replace("size = 1.0", "size = 1.0\nrefine_close_curves = \"yes\"");
    let (d, rendered) = single_at(&text, "\"yes\"", 0);
    assert!(
        d.message.contains(
            "`mesh.refine_close_curves` must be `true`, `false` or a list of curve names"
        ),
        "{rendered}"
    );
    // A list naming a surface the recipe does not have.
    let text = BASE.replace(
        "size = 1.0",
        "size = 1.0\nrefine_close_curves = [\"top/f2\"]",
    );
    let (d, rendered) = single_at(&text, "f2\"]", 0);
    assert!(d.message.contains("f2"), "{rendered}");
}

#[test]
fn a_refinement_names_exactly_one_feature_and_grows_to_a_larger_size() {
    let r = ok(&format!(
        "{BASE}[[mesh.refine]]\nsurface = \"f1\"\nsize = 0.2\ndistance = 2.0\n"
    ));
    assert_eq!(r.mesh.refine.len(), 1);
    assert_eq!(r.mesh.refine[0].far, 1.0, "far defaults to the global size");
    let text = format!(
        "{BASE}[[mesh.refine]]\nsurface = \"f1\"\ncurve = \"f1/top\"\nsize = 0.2\ndistance = 2.0\n"
    );
    let d = errors(&text);
    assert!(d[0].message.contains("exactly one feature"), "{}", d[0]);
    let text = format!("{BASE}[[mesh.refine]]\nsurface = \"f2\"\nsize = 0.2\ndistance = 2.0\n");
    let d = errors(&text);
    assert!(
        d.iter().any(|d| d.to_string().contains("f1")),
        "suggests f1: {d:?}"
    );
    let text = format!(
        "{BASE}[[mesh.refine]]\npoint = [1.0, 1.0, -1.0]\nsize = 2.0\ndistance = 2.0\nfar = 1.5\n"
    );
    let (d, rendered) = single_at(&text, "1.5", 0);
    assert!(d.message.contains("not larger than"), "{rendered}");
}

#[test]
fn wells_are_read_with_their_options_and_bad_entries_point_at_the_value() {
    let named = format!(
        "{BASE}\n[regions]\nres = {{ point = [5.0, 5.0, -5.0] }}\n\n[wells]\nW1 = \"data/w1.wl\"\nW2 = {{ file = \"data/w2.pl\", size = 2.5, object = 2, regions = [\"res\"], area = 0.03 }}\n"
    );
    let r = ok(&named);
    let w2 = &r.wells["W2"];
    assert_eq!(
        (w2.size, w2.regions.clone(), w2.path.clone(), w2.area),
        (
            Some(2.5),
            Some(vec!["res".to_string()]),
            Path::new("recipes/data/w2.pl").to_path_buf(),
            Some(0.03)
        )
    );
    assert_eq!((r.wells["W1"].size, r.wells["W1"].area), (None, None));
    let (_, rendered) = single_at(&named.replace("0.03", "-1.0"), "-1.0", 0);
    assert!(rendered.contains("`wells.W2.area`"), "{rendered}");
    assert!(
        rendered.contains("cross-section area greater than 0"),
        "{rendered}"
    );
    let (_, rendered) = single_at(&named.replace("[\"res\"]", "[\"rez\"]"), "\"rez\"", 0);
    assert!(rendered.contains("unknown region `rez`"), "{rendered}");
    assert!(rendered.contains("did you mean `res`?"), "{rendered}");
    let (_, rendered) = single_at(&named.replace("w1.wl", "w1.ts"), "\"data/w1.ts\"", 0);
    assert!(rendered.contains("not a gOcad well or line"), "{rendered}");
    let (_, rendered) = single_at(&named.replace("W1 =", "top ="), "top =", 1);
    assert!(rendered.contains("also a surface name"), "{rendered}");
}

#[test]
fn an_error_that_starts_at_a_recipe_entry_reads_back_underlining_that_entry() {
    let text = format!(
        "{BASE}\n[[trim]]\nsurface = \"f1\"\ndiscard = {{ area_below = 1.0 }}\n\n[regions]\n\"upper.layer\" = {{ point = [5.0, 5.0, -1.0] }}\nlower = {{ point = [5.0, 5.0, -9.0] }}\n"
    );
    let r = ok(&text);
    let cases = [
        ("box", r.bbox.as_ref().expect("a box").span, "[box]"),
        ("trim", r.trims[0].span, "[[trim]]"),
        (
            "quoted region",
            r.regions["upper.layer"].span,
            "\"upper.layer\"",
        ),
        ("region", r.regions["lower"].span, "lower"),
    ];
    for (what, span, entry) in cases {
        let error = format!("{}: it is wrong; help: change it", r.place(span));
        let d = r
            .located(&error)
            .unwrap_or_else(|| panic!("{what}: not located"));
        assert_eq!((d.line, d.col), (span.line, span.col), "{what}");
        assert_eq!(d.message, "it is wrong", "{what}");
        assert_eq!(d.help.as_deref(), Some("change it"), "{what}");
        let shown = d.to_string();
        let underline = format!(
            "| {}{}\n",
            " ".repeat(d.col - 1),
            "^".repeat(entry.chars().count())
        );
        assert!(shown.contains(&format!("| {entry}")), "{what}: {shown}");
        assert!(shown.contains(&underline), "{what}: {shown}");
    }
}

#[test]
fn an_error_that_starts_elsewhere_is_not_read_as_a_recipe_location() {
    let r = ok(BASE);
    for error in [
        "data/top.ts:3:1: a bad vertex",
        "recipes/other.toml:1:1: another recipe",
        &format!("{FILE}:999:1: past the end of the recipe"),
        &format!("{FILE}:1:99: past the end of the line"),
        &format!("{FILE}: no line"),
        "the region `x` is strictly inside no region",
    ] {
        assert!(r.located(error).is_none(), "{error}");
    }
}

#[test]
fn an_output_dir_outside_the_recipes_folder_is_refused_unless_the_recipe_allows_it() {
    for dir in ["../../x", "/tmp/x", "out/../../x"] {
        let text = format!("{BASE}\n[output]\ndir = \"{dir}\"\n");
        let (d, _) = single_at(&text, &format!("\"{dir}\""), 0);
        assert!(
            d.message.contains("outside the recipe's folder"),
            "{dir}: {}",
            d.message
        );
        assert!(
            d.help
                .as_deref()
                .unwrap_or("")
                .contains("allow_outside = true"),
            "{dir}"
        );
        let allowed = format!("{BASE}\n[output]\ndir = \"{dir}\"\nallow_outside = true\n");
        assert_eq!(ok(&allowed).output.dir, Path::new(dir));
    }
    for dir in ["out", "results/run1", "a/../b", "."] {
        let text = format!("{BASE}\n[output]\ndir = \"{dir}\"\n");
        assert_eq!(ok(&text).output.dir, Path::new(dir), "{dir} stays inside");
    }
}

#[test]
fn a_model_name_that_would_make_hidden_files_is_refused_with_a_portable_one() {
    for (name, suggested) in [(".", "model"), ("..", "model"), (".hidden", "hidden")] {
        let text = BASE.replace("name = \"t\"", &format!("name = \"{name}\""));
        let (d, _) = single_at(&text, &format!("\"{name}\""), 0);
        assert!(
            d.message.contains("starts with `.`"),
            "{name}: {}",
            d.message
        );
        assert_eq!(
            d.help.as_deref(),
            Some(format!("e.g. `name = \"{suggested}\"`").as_str()),
            "{name}"
        );
    }
}

#[test]
fn an_import_that_is_a_directory_or_a_fifo_says_what_it_is_not_that_it_is_missing() {
    let r = ok(BASE);
    let kind = |p: &Path| {
        if p.ends_with("f1.ts") {
            FileKind::Other("a FIFO (a named pipe)")
        } else if p.ends_with("top.ts") {
            FileKind::Other("a directory")
        } else {
            FileKind::File
        }
    };
    let d = georecipe::recipe::check_files_with_listing(&r, &kind, &|_| Vec::new());
    let messages: Vec<&str> = d.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(
        messages,
        [
            "file `data/f1.ts` of surface `f1` is a FIFO (a named pipe), not a file",
            "file `data/top.ts` of surface `top` is a directory, not a file",
        ]
    );
}

#[test]
fn groups_take_a_selector_or_a_list_of_them_over_surfaces_patches_and_box_sides() {
    let text = format!("{BASE}[groups]\nseafloor = \"box.zmax\"\nfaults = [\"f*\", \"top#2\"]\n");
    let r = ok(&text);
    let texts: Vec<Vec<&str>> = (r.groups.values())
        .map(|g| g.selectors.iter().map(|s| s.text.as_str()).collect())
        .collect();
    assert_eq!(texts, [vec!["f*", "top#2"], vec!["box.zmax"]]);
    let faults = &r.groups["faults"].selectors;
    assert!(faults[1].matches("top#2") && !faults[1].matches("top#21"));
    assert!(faults[0].matches("f1#3") && !faults[0].matches("top#1"));
}

#[test]
fn a_group_named_like_a_surface_region_or_box_side_is_refused_at_its_name() {
    for (name, what) in [
        ("top", "surface"),
        ("box.zmin", "surface"),
        ("r0", "region"),
    ] {
        let text = format!(
            "{BASE}[regions]\nr0 = {{ point = [1.0, 1.0, -1.0] }}\n[groups]\n\"{name}\" = \"f1\"\n"
        );
        let (d, r) = single_at(&text, &format!("\"{name}\" = \"f1\""), 0);
        assert!(
            d.message
                .contains(&format!("group name `{name}` is also a {what} name")),
            "{r}"
        );
    }
}

#[test]
fn a_group_selector_with_an_unknown_surface_or_a_bad_patch_number_is_refused_where_written() {
    let text = format!("{BASE}[groups]\nbc = [\"f1\", \"topp#2\"]\n");
    let (d, r) = single_at(&text, "topp", 0);
    assert!(d.message.contains("matches no surface"), "{r}");
    assert_eq!(d.help.as_deref(), Some("did you mean `top`?"), "{r}");
    let text = format!("{BASE}[groups]\nbc = \"top#x\"\n");
    let (d, r) = single_at(&text, "\"top#x\"", 0);
    assert!(d.message.contains("bad group selector `top#x`"), "{r}");
    let text = format!("{BASE}[groups]\nbc = []\n");
    let (d, r) = single_at(&text, "[]", 0);
    assert!(d.message.contains("the group would hold no face"), "{r}");
}
