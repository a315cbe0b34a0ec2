//! The build says where the model's curves come closer than their mesh can resolve: two
//! dangling faults a few metres apart in the shipped example are named with the place and the
//! fix, and the example itself, whose closest curves are the reservoir's 35 m apart at 100 m
//! curves, gets no such warning.

use crate::common_cli;
use common_cli::*;

/// Adds `F3`, the dangling fault `F2` moved `dy` metres north, intersected with both horizons.
fn with_f3(s: &Scratch, dy: f64) {
    let f2 = std::fs::read_to_string(s.path("data/didactic/F2_dangling.ts")).expect("F2");
    let moved = |line: &str| -> String {
        let mut f: Vec<String> = line.split_whitespace().map(str::to_string).collect();
        if f.first().is_some_and(|k| k == "VRTX") {
            f[3] = format!("{:.3}", f[3].parse::<f64>().expect("y") + dy);
        }
        f.join(" ")
    };
    let f3 = (f2.lines().map(moved).collect::<Vec<_>>().join("\n"))
        .replace("name:F2_dangling", "name:F3_dangling");
    std::fs::write(s.path("data/didactic/F3_dangling.ts"), f3).expect("written");
    s.edit(
        "F2 = { file",
        "F3 = { file = \"data/didactic/F3_dangling.ts\", kind = \"fault\" }\nF2 = { file",
    );
    s.edit(
        "pairs = [[\"F2\", \"H1\"], [\"F2\", \"H2\"]]",
        "pairs = [[\"F2\", \"H1\"], [\"F2\", \"H2\"], [\"F3\", \"H1\"], [\"F3\", \"H2\"]]",
    );
}

#[test]
fn two_dangling_faults_five_metres_apart_are_named_with_the_place_and_the_fix() {
    let s = Scratch::didactic();
    with_f3(&s, 5.0);
    let (_, _, err) = s.build(&[]);
    let warning = (err.lines())
        .find(|l| l.contains("Warning curves") && l.contains("come within"))
        .unwrap_or_else(|| panic!("no warning about close curves in:\n{err}"));
    for needle in ["`F2#", "`F3#", "of each other", "mesh size 100"] {
        assert!(warning.contains(needle), "`{needle}` not in: {warning}");
    }
    assert!(
        warning.contains("`refine_close_curves = [\"F") && warning.contains("(elements of 8.00"),
        "{warning}"
    );
    assert!(
        warning.contains("`refine_close_curves = true` for every such place"),
        "{warning}"
    );
}

/// The smallest dihedral angle of the didactic build's tets.
fn min_dihedral(s: &Scratch) -> f64 {
    worst_dihedral(&s.path("out/didactic/didactic.quality.json"))
}

#[test]
fn refining_close_curves_lifts_the_tets_between_two_faults_and_reruns_only_what_lies_near() {
    let s = Scratch::didactic();
    with_f3(&s, 8.0);
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    let flat = min_dihedral(&s);
    assert!(flat < 4.0, "{flat}");
    s.edit("[mesh]\n", "[mesh]\nrefine_close_curves = true\n");
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    // 6.9 m apart at curves of 100 m: refined to 8 m between them, as the report says (the
    // console warns only when the model is built, and it was not).
    let text = std::fs::read(s.path("out/didactic/report.json")).expect("the report");
    let report: serde_json::Value = serde_json::from_slice(&text).expect("JSON");
    let warnings = report["warnings"].as_array().expect("warnings");
    let warning = (warnings.iter().filter_map(|w| w.as_str()))
        .find(|l| l.contains("come within"))
        .unwrap_or_else(|| panic!("no warning about close curves in: {warnings:?}"));
    assert!(warning.contains("refined there to 8.00"), "{warning}");
    let lifted = min_dihedral(&s);
    assert!(lifted > 8.0, "{flat}° became {lifted}°");
    let ran = nodes_in_state(&r, "ran");
    assert!(
        ran.iter().any(|n| n.starts_with("close_curves:")),
        "{ran:?}"
    );
    assert!(ran.contains(&"surface_mesh:F3#1".to_string()), "{ran:?}");
    // The model is as it was, and the box's far sides are beyond the refinements' reach.
    for n in all_nodes(&r).iter().filter(|n| {
        n.starts_with("import:")
            || n.starts_with("intersect:")
            || n.as_str() == "model"
            || n.starts_with("surface_mesh:box.xmin#")
            || n.starts_with("surface_mesh:box.ymax#")
    }) {
        assert!(!ran.contains(n), "`{n}` re-ran");
    }
}

#[test]
fn refining_the_places_of_listed_curves_refines_those_and_warns_about_the_rest() {
    // F3 8 m north of F2: the model's one place where curves come close. Listing one curve of
    // it, as the warning advises, refines the place as `true` does.
    let s = Scratch::didactic();
    with_f3(&s, 8.0);
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    let warning = (err.lines())
        .find(|l| l.contains("Warning curves") && l.contains("come within"))
        .unwrap_or_else(|| panic!("no warning about close curves in:\n{err}"));
    // The advice names a curve of the place to list.
    let listed = (warning.split("`refine_close_curves = [\"").nth(1))
        .and_then(|t| t.split('"').next())
        .unwrap_or_else(|| panic!("no curve to list in: {warning}"))
        .to_string();
    s.edit(
        "[mesh]\n",
        &format!("[mesh]\nrefine_close_curves = [\"{listed}\"]\n"),
    );
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    let ran = nodes_in_state(&r, "ran");
    assert!(
        ran.iter().any(|n| n.starts_with("close_curves:")),
        "{ran:?}"
    );
    let lifted = min_dihedral(&s);
    assert!(lifted > 8.0, "{lifted}°");
    // The same mesh as `true` gives: the model has no other place.
    let listed_mesh = std::fs::read(s.path("out/didactic/didactic.msh")).expect("the mesh");
    s.edit(
        &format!("refine_close_curves = [\"{listed}\"]"),
        "refine_close_curves = true",
    );
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    let all_mesh = std::fs::read(s.path("out/didactic/didactic.msh")).expect("the mesh");
    assert!(
        listed_mesh == all_mesh,
        "listing the place's curve differs from `true`"
    );
}

#[test]
fn the_shipped_example_and_faults_apart_by_a_few_elements_get_no_such_warning() {
    let s = Scratch::didactic();
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert!(!err.contains("come within"), "{err}");
    let s = Scratch::didactic();
    with_f3(&s, 300.0);
    let (_, _, err) = s.build(&[]);
    assert!(!err.contains("come within"), "{err}");
}
