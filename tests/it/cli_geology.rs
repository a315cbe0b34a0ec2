//! The corpus of geological situations (`test_support::geology`) built through a recipe: each
//! case meshes into its regions, every region's worst tet is within the quality bars (normalised
//! mean ratio at least 0.2, dihedral angles at least the case's bar, 8°, or 7° for the lens,
//! whose rim's needle triangles bound it, and 6° for the Tejon Pass faults at 2 km; where the
//! region's surfaces meet at a sharper angle, three quarters of that angle), and, when the
//! independent checker is available, the msh passes `check_mesh.py` with that region count.
//! Cases over the SCEC fault model in `../shared` skip when it is absent.

use crate::common_cli;
use geom::mesh::read::read_volume_msh;
use std::collections::BTreeSet;
use std::process::Command;
use test_support::geology::{
    Case, cases, collapsed_layer, horizon_with_a_hole, known_gaps, scec_big_bend, scec_cases,
};
use test_support::paths;

/// Builds `case` in a scratch folder (kept for the caller's checks); asserts the build
/// succeeded and returns the folder and the build's JSON report.
fn build(case: &Case) -> (tempfile::TempDir, serde_json::Value) {
    let dir = tempfile::tempdir().expect("a scratch folder");
    let recipe = case.write(dir.path());
    let out = Command::new(env!("CARGO_BIN_EXE_recipe"))
        .current_dir(dir.path())
        .args(["build", "--json", "--quiet"])
        .arg(&recipe)
        .output()
        .expect("the recipe binary runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "{}: {err}\n{}",
        case.name,
        case.recipe
    );
    let report = serde_json::from_slice(&out.stdout).expect("JSON");
    (dir, report)
}

/// Runs `recipe build recipe` in `dir`, saying what it does.
fn build_saying(dir: &std::path::Path, recipe: &std::path::Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_recipe"))
        .current_dir(dir)
        .arg("build")
        .arg(recipe)
        .output()
        .expect("the recipe binary runs")
}

/// Runs `recipe build --quiet recipe` in `dir`.
fn build_quietly(dir: &std::path::Path, recipe: &std::path::Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_recipe"))
        .current_dir(dir)
        .args(["build", "--quiet"])
        .arg(recipe)
        .output()
        .expect("the recipe binary runs")
}

/// Builds `case` in a scratch folder and checks its model, mesh and quality.
fn builds_and_meshes(case: &Case) -> tempfile::TempDir {
    builds_and_meshes_reporting(case).0
}

/// As [`builds_and_meshes`], also returning the build's JSON report.
fn builds_and_meshes_reporting(case: &Case) -> (tempfile::TempDir, serde_json::Value) {
    let (dir, report) = build(case);
    let model = report["nodes"]
        .as_array()
        .and_then(|n| n.iter().find(|n| n["name"] == "model"))
        .expect("a model node");
    assert_eq!(
        model["counts"]["regions"].as_u64(),
        Some(case.regions as u64),
        "{}: {model}",
        case.name
    );
    let below = below_the_bars(dir.path(), case);
    assert!(below.is_empty(), "{}: {}", case.name, below.join("\n"));
    passes_the_checker(dir.path(), case);
    (dir, report)
}

/// The quality table rows of the regions of `case`, built in `dir`, under the corpus's bars: a
/// minimum mean ratio of 0.2, and the case's minimum dihedral angle wherever the region's
/// boundary allows it, else [`BOUND_SHARE`] of the sharpest angle its surfaces leave it (no tet
/// can beat that bound: every region's smallest angle is checked to be under it).
fn below_the_bars(dir: &std::path::Path, case: &Case) -> Vec<String> {
    (regions(dir, case).into_iter())
        .filter(|r| below_the_bars_row(r, case))
        .map(|r| r.to_string())
        .collect()
}

/// Whether the Table 2 row `r` of `case` is under the corpus's bars (see [`below_the_bars`]).
fn below_the_bars_row(r: &serde_json::Value, case: &Case) -> bool {
    let (mr, dihedral) = (
        r["min"].as_f64().unwrap(),
        r["min_dihedral_deg"].as_f64().unwrap(),
    );
    let bound = r["min_dihedral_bound_deg"].as_f64().unwrap_or(180.0);
    assert!(
        dihedral <= bound + 1e-9,
        "{}: over its bound: {r}",
        case.name
    );
    mr < 0.2 || dihedral < case.min_dihedral.min(BOUND_SHARE * bound)
}

/// The rows of Table 2 of `case`, built in `dir`.
fn regions(dir: &std::path::Path, case: &Case) -> Vec<serde_json::Value> {
    let quality = dir.join(format!("out/{}.quality.json", case.name));
    let mut q: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&quality).expect("the quality tables")).unwrap();
    match q["table2"].take() {
        serde_json::Value::Array(rows) => rows,
        other => panic!("table 2: {other}"),
    }
}

/// A region whose surfaces meet at an angle under the dihedral bar must reach this share of it.
/// The wedges of the corpus reach 0.89 (the splay at 1°), 0.93 (the erosional unconformity, 6.7°
/// of 7.2°) and 1.0 (the onlap under a degree at 0.13°); the closed channel, whose rim's facets
/// meet at 3.8°, 0.56.
const BOUND_SHARE: f64 = 0.75;

/// The share of that angle a known gap must reach. The onlap's wedge, 36 m thick at most and one
/// element across at 250 (warned), reaches 0.47 of its 0.96°; refined as its warnings say
/// (`refine_close_curves`, or `min_layers = 3`), 0.99 and 1.0.
const KNOWN_GAP_SHARE: f64 = 0.45;

/// The rows of the regions of `case`, built in `dir`, whose surfaces meet at an angle under the
/// case's dihedral bar, and whose smallest dihedral angle is under `share` of that angle.
fn far_under_their_bound(dir: &std::path::Path, case: &Case, share: f64) -> Vec<String> {
    (regions(dir, case).into_iter())
        .filter(|r| {
            let dihedral = r["min_dihedral_deg"].as_f64().unwrap();
            let bound = r["min_dihedral_bound_deg"].as_f64().unwrap_or(180.0);
            bound < case.min_dihedral && dihedral < share * bound
        })
        .map(|r| r.to_string())
        .collect()
}

/// Builds `case` quietly in a scratch folder (returned), asserting that it succeeds and that its
/// mesh passes the checker, whatever its quality.
fn meshes_validly(case: &Case) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("a scratch folder");
    let out = build_quietly(dir.path(), &case.write(dir.path()));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{}: {err}", case.name);
    passes_the_checker(dir.path(), case);
    dir
}

/// Asserts that `check_mesh.py` passes the mesh of `case`, built in `dir` (skipped, with a
/// note, where the checker is absent).
fn passes_the_checker(dir: &std::path::Path, case: &Case) {
    let msh = dir.join(format!("out/{}.msh", case.name));
    common_cli::passes_check_mesh(&msh, case.regions, case.name);
}

fn case(name: &str) -> Case {
    cases()
        .into_iter()
        .find(|c| c.name == name)
        .unwrap_or_else(|| panic!("no case `{name}`"))
}

/// The known gap named `name`.
fn known_gap(name: &str) -> Case {
    known_gaps()
        .into_iter()
        .find(|c| c.name == name)
        .unwrap_or_else(|| panic!("no known gap `{name}`"))
}

#[test]
fn a_normal_fault_with_throw_and_trimmed_horizons_meshes_into_six_regions() {
    builds_and_meshes(&case("normal_fault"));
}

#[test]
fn a_reverse_fault_with_throw_and_trimmed_horizons_meshes_into_six_regions() {
    builds_and_meshes(&case("reverse_fault"));
}

#[test]
fn a_fault_dying_out_inside_a_layer_is_embedded_in_its_region() {
    builds_and_meshes(&case("fault_stops_in_a_layer"));
}

#[test]
fn an_erosional_unconformity_truncating_a_horizon_meshes_into_four_regions() {
    builds_and_meshes(&case("erosional_unconformity"));
}

#[test]
fn two_faults_crossing_in_an_x_cut_a_horizon_into_eight_regions() {
    builds_and_meshes(&case("x_fault_junction"));
}

#[test]
fn a_fault_ending_on_another_in_a_y_meshes_into_six_regions() {
    builds_and_meshes(&case("y_fault_junction"));
}

#[test]
fn a_splay_branching_from_a_fault_at_eight_degrees_meshes_into_six_regions() {
    builds_and_meshes(&case("fault_splay"));
}

#[test]
fn a_recumbent_fold_with_an_overturned_limb_cuts_the_box_into_two_regions() {
    builds_and_meshes(&case("recumbent_fold"));
}

#[test]
fn every_case_of_the_corpus_has_a_test() {
    let tested = [
        "normal_fault",
        "reverse_fault",
        "small_throw_fault",
        "fault_stops_in_a_layer",
        "erosional_unconformity",
        "x_fault_junction",
        "y_fault_junction",
        "recumbent_fold",
        "vertical_tube",
        "salt_stock",
        "closed_salt_diapir",
        "closed_salt_diapir_with_well",
        "salt_dome_cut_by_the_box",
        "lens",
        "fault_patches_at_corners",
        "dense_fault_patches_at_corners",
        "dangling_faults_crossing",
        "horizons_touching_at_a_point",
        "horizons_touching_along_a_line",
        "raft_in_salt",
        "chevron_fold",
        "intrusion_cutting_a_body",
        "fault_splay",
        "fault_with_a_hole",
        "graben",
        "horst",
        "tilted_layers",
        "fault_under_an_unconformity",
        "relay_ramp",
        "listric_fault",
        "fault_through_salt",
        "horizon_with_standing_caps",
        "caps_cut_by_curves",
        "salt_overhang",
    ];
    let names: Vec<&str> = cases().iter().map(|c| c.name).collect();
    assert_eq!(names, tested);
}

#[test]
fn a_salt_dome_cut_by_the_box_meshes_with_no_wedge_of_a_chart_on_the_cut() {
    // The side clips a chart of the dome near its tip: a wedge one support triangle wide met the
    // cut along 6 m between seams 95 m long, and the tets there reached 7.5°. Given to the chart
    // beside it, it leaves no piece of the cut that short.
    let dir = builds_and_meshes(&case("salt_dome_cut_by_the_box"));
    let cut = curves_named(dir.path(), "SALT/box.xmax#", "length");
    assert!(cut.len() > 4, "{cut:?}");
    assert!(cut.iter().all(|(_, length)| *length > 10.0), "{cut:?}");
}

/// The curves of the build in `dir` whose names start with `prefix`, each with its figure
/// `field` (`length`, `nodes`) from the report.
fn curves_named(dir: &std::path::Path, prefix: &str, field: &str) -> Vec<(String, f64)> {
    let report = std::fs::read(dir.join("out/report.json")).expect("the report");
    let report: serde_json::Value = serde_json::from_slice(&report).expect("JSON");
    (report["curves"].as_array().expect("curves").iter())
        .filter_map(|c| Some((c["name"].as_str()?.to_string(), c[field].as_f64()?)))
        .filter(|(name, _)| name.starts_with(prefix))
        .collect()
}

#[test]
fn a_fault_with_a_five_metre_throw_meshes_with_its_strips_as_fine_as_they_are_wide() {
    // At a size of 250 m, each horizon's two cutoffs bound a strip of the fault 5.8 m wide
    // between two thick blocks: cut at the cutoffs' nodes 77 m apart, its triangles were
    // needles and the tets beside them reached 2.2°.
    let dir = builds_and_meshes(&case("small_throw_fault"));
    let cutoffs = curves_named(dir.path(), "F/H", "nodes");
    assert_eq!(cutoffs.len(), 4, "{cutoffs:?}");
    // 4 km each, their nodes now about the strip's width apart (77 m before).
    assert!(
        cutoffs.iter().all(|(_, nodes)| *nodes > 300.0),
        "{cutoffs:?}"
    );
}

#[test]
fn a_salt_overhang_meets_the_bars_with_no_strip_of_a_chart_along_its_contact_with_a_horizon() {
    // The overhang's underside faces between two axes, so its charts' seams fall where its
    // facets happen to turn past the diagonal. H1 cut one chart into a strip 330 m long and 2 to
    // 12 m wide along their contact: its triangles were needles, and the tets on them reached
    // 5.4° (0.9° before the charts' curves were made as fine as their patches are wide). The
    // strip now joins the chart beside it.
    let dir = builds_and_meshes(&case("salt_overhang"));
    // Its curves come close at several places: each warning gives the line that refines there,
    // and what to do about them all is said once.
    let text = std::fs::read(dir.path().join("out/report.json")).expect("the report");
    let report: serde_json::Value = serde_json::from_slice(&text).expect("JSON");
    let warnings: Vec<&str> = (report["warnings"].as_array().expect("warnings").iter())
        .filter_map(|w| w.as_str())
        .collect();
    let close: Vec<&&str> = warnings
        .iter()
        .filter(|w| w.contains("come within"))
        .collect();
    assert!(close.len() > 1, "{warnings:?}");
    for w in &close {
        assert!(
            w.contains("`refine_close_curves = [\"") && w.contains("refines there"),
            "{w}"
        );
        assert!(!w.contains("mend the surfaces"), "{w}");
    }
    let advice: Vec<&&str> = (warnings.iter())
        .filter(|w| w.starts_with("where curves come that close"))
        .collect();
    assert_eq!(advice.len(), 1, "{warnings:?}");
    assert!(
        advice[0].contains("`refine_close_curves = true`"),
        "{}",
        advice[0]
    );
}

#[test]
fn a_lens_rim_meshed_without_creases_has_its_folds_repaired_and_meshes() {
    // The two lenses' rims are crumpled into facets that turn by up to 115° between
    // neighbours; with creases turned off (`crease_angle_deg = 179`) surface elements span such
    // turns and fold, until the repair judges folds as the verification does and unfolds them.
    let case = known_gap("two_lenses");
    let case = Case {
        recipe: format!("{}\n[tolerances]\ncrease_angle_deg = 179\n", case.recipe),
        ..case
    };
    meshes_validly(&case);
}

#[test]
fn a_closed_salt_diapir_and_a_lens_retriangulated_piece_by_piece_mesh_into_their_regions() {
    // Re-triangulated as one piece, a body closed on itself had no border loop to flatten ("the
    // patch has no boundary loop"); cut as the model cuts it (`model::remesh`), it
    // re-triangulates, and the model meshes on the new support.
    for name in ["closed_salt_diapir", "lens"] {
        let case = case(name);
        let recipe = (case.recipe).replace(
            "kind = \"other\" }",
            "kind = \"other\", retriangulate = 60.0 }",
        );
        assert!(recipe.contains("retriangulate"), "{name}: {recipe}");
        meshes_validly(&Case { recipe, ..case });
    }
}

/// Builds `case` with its recipe's trims replaced by `trims`; returns the scratch folder and the
/// build's JSON report, after checking the mesh with `regions` regions.
fn build_with_trims(case: &Case, trims: &str, regions: usize) -> serde_json::Value {
    let at = case.recipe.find("[[trim]]").expect("the case trims");
    let end = case.recipe[at..]
        .find("\n\n")
        .map_or(case.recipe.len(), |e| at + e + 2);
    let case = Case {
        name: case.name,
        recipe: format!("{}{trims}{}", &case.recipe[..at], &case.recipe[end..]),
        files: case.files.clone(),
        regions,
        min_dihedral: case.min_dihedral,
    };
    let (dir, report) = build(&case);
    passes_the_checker(dir.path(), &case);
    report
}

/// The names of the regions the model found, from a build's JSON report.
fn region_names(report: &serde_json::Value) -> Vec<String> {
    let regions = report["model"]["regions"].as_array().expect("regions");
    let mut names: Vec<String> = (regions.iter())
        .map(|r| r["name"].as_str().expect("a name").to_string())
        .collect();
    names.sort();
    names
}

#[test]
fn an_intrusion_keeps_the_overlap_of_two_bodies_whichever_is_kept_outside_the_other() {
    let case = case("intrusion_cutting_a_body");
    // The regions the bodies bound (the other two are the layers above and below H).
    let bodies = |report: serde_json::Value| -> Vec<String> {
        let names = region_names(&report);
        names.into_iter().filter(|n| !n.starts_with("H+")).collect()
    };
    let outside = |a: &str, b: &str| {
        format!("[[trim]]\nsurface = \"{a}\"\nkeep = {{ outside = \"{b}\" }}\n\n")
    };
    // As written, A outside B: the overlap is B's, and what is left of A is bounded by both.
    let a_cut = build_with_trims(&case, &outside("A", "B"), 4);
    assert_eq!(bodies(a_cut), ["A+B", "B"]);
    // Both ways: B outside A leaves A whole.
    let b_cut = build_with_trims(&case, &outside("B", "A"), 4);
    assert_eq!(bodies(b_cut), ["A", "A+B"]);
    // Untrimmed, the overlap is a third region between the two.
    let both = build_with_trims(&case, "", 5);
    assert_eq!(bodies(both), ["A+B#1", "A+B#2", "A+B#3"]);
}

#[test]
fn a_horizon_trimmed_where_it_laps_onto_another_leaves_no_trace_on_the_box_walls() {
    // H1 meets U at a small angle and is kept on one side of it. Its discarded part drew curves
    // on three box sides, and these ran into U's a fraction of a metre apart where H1 meets U:
    // the strips between were meshed flat, and the region beyond U had tets of 4°.
    for name in ["onlap", "downlap"] {
        let case = (known_gaps().into_iter())
            .find(|c| c.name == name)
            .expect("a known gap");
        let (dir, report) = build(&case);
        let model = (report["nodes"].as_array())
            .and_then(|n| n.iter().find(|n| n["name"] == "model"))
            .expect("a model node");
        assert_eq!(
            model["counts"]["rejoined_patches"].as_u64(),
            Some(3),
            "{name}"
        );
        let written: serde_json::Value = serde_json::from_slice(
            &std::fs::read(dir.path().join("out/report.json")).expect("the report"),
        )
        .expect("JSON");
        let traces: Vec<&serde_json::Value> = (written["curves"].as_array().expect("curves"))
            .iter()
            .filter(|c| c["surfaces"].as_array().is_some_and(|s| s.len() == 1))
            .collect();
        assert!(traces.is_empty(), "{name}: {traces:?}");
        // Only the wedge between H1 and U is left under the bars, as its surfaces' angle is.
        let below: Vec<String> = (regions(dir.path(), &case).into_iter())
            .filter(|r| r["name"] != "all" && below_the_bars_row(r, &case))
            .map(|r| r["name"].as_str().unwrap_or_default().to_string())
            .collect();
        assert_eq!(below, ["H1+U+box.xmax+box.ymax+box.ymin"], "{name}");
    }
}

#[test]
fn every_known_gap_misses_the_bars_with_a_valid_mesh_or_fails_naming_its_place() {
    // These mesh now, below the bars: the lenses since no chart's border overlaps itself in map
    // view, the smoothed channel since projections that turn a few triangles over are mended.
    let meshing = [
        "two_lenses",
        "onlap",
        "onlap_under_a_degree",
        "downlap",
        "detachment",
        "fault_splay_at_one_degree",
        "zero_thickness_layer",
        "channel",
        "smoothed_channel",
        "lens_cut_by_a_fault",
    ];
    for case in known_gaps() {
        let dir = tempfile::tempdir().expect("a scratch folder");
        let recipe = case.write(dir.path());
        let out = build_quietly(dir.path(), &recipe);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            out.status.success() || !meshing.contains(&case.name),
            "{} meshed before: {err}",
            case.name
        );
        if out.status.success() {
            passes_the_checker(dir.path(), &case);
            assert!(
                !below_the_bars(dir.path(), &case).is_empty(),
                "{} meshes within the bars now: move it into `cases`",
                case.name
            );
            // Where its surfaces meet at a sharp angle, it reaches a share of it.
            let far = far_under_their_bound(dir.path(), &case, KNOWN_GAP_SHARE);
            assert!(far.is_empty(), "{}: {}", case.name, far.join("\n"));
            continue;
        }
        assert_eq!(out.status.code(), Some(1), "{}: {err}", case.name);
        let failed = (err.lines())
            .find(|l| l.contains("error `"))
            .unwrap_or_else(|| panic!("{}: no failing node:\n{err}", case.name));
        assert!(
            failed.contains(" at ("),
            "{}: no place: {failed}",
            case.name
        );
        assert!(
            err.contains("note the nearest input triangle is data/"),
            "{}: no input line:\n{err}",
            case.name
        );
        // A front that could not close says whether a pinch is to blame.
        if failed.contains("the front") {
            assert!(failed.contains("pinched"), "{}: {failed}", case.name);
        }
    }
}

#[test]
fn a_detachments_worst_tet_is_put_down_to_the_slab_under_its_flat_with_what_to_write() {
    // The thrust's flat runs 10 m above the horizon, meshed at 250: the slab between is a
    // fraction of an element across, though its surfaces never meet at a sharp angle (Table 2's
    // bound is 60°), and the region is thick by its median, so no other warning says why.
    let case = known_gap("detachment");
    let dir = tempfile::tempdir().expect("a scratch folder");
    let recipe = case.write(dir.path());
    let out = build_saying(dir.path(), &recipe);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let warning = (err.lines())
        .find(|l| l.contains("worst tet (") && l.contains("is where the region is only"))
        .unwrap_or_else(|| panic!("no warning about the thin slab:\n{err}"));
    let thickness: f64 = (warning.split("is only ").nth(1))
        .and_then(|rest| rest.split(' ').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no thickness: {warning}"));
    // The flat's slab is 10 m thick where the horizon is flat, thinner where it rises.
    assert!(thickness > 0.0 && thickness <= 10.5, "{warning}");
    assert!(
        warning.contains("meshed at 250") && warning.contains("layers = 3"),
        "{warning}"
    );
    // The report keeps it with the build's other warnings.
    let report = std::fs::read(dir.path().join("out/report.json")).expect("the report");
    let report: serde_json::Value = serde_json::from_slice(&report).expect("JSON");
    let kept = (report["warnings"].as_array().expect("warnings").iter())
        .filter_map(|w| w.as_str())
        .any(|w| w.contains("is where the region is only"));
    assert!(kept, "{}", report["warnings"]);
    // A region thin all over is told once, by the thin-region warning: the shipped example's
    // reservoir, where its worst tet is.
    let example = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("recipes/didactic.toml");
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let out = Command::new(env!("CARGO_BIN_EXE_recipe"))
        .current_dir(scratch.path())
        .args(["build", "--cache-dir", "cache"])
        .arg(&example)
        .output()
        .expect("the recipe binary runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("region `reservoir_E` is about 35.0 thick"),
        "{err}"
    );
    assert!(!err.contains("is where the region is only"), "{err}");
}

#[test]
fn a_downlap_has_no_needle_where_its_two_surfaces_leave_the_box_side_together() {
    // The box side's two curves leave the tip at 2°, one with a node 6 m on, the other's first
    // 250 m on: without grading both from that node, the triangle between is a needle and its
    // tets reach 0.11°.
    let case = known_gap("downlap");
    let dir = meshes_validly(&case);
    let quality = dir.path().join("out/downlap.quality.json");
    let q: serde_json::Value = serde_json::from_slice(&std::fs::read(quality).unwrap()).unwrap();
    let all = (q["table2"].as_array().unwrap().iter())
        .find(|r| r["name"] == "all")
        .expect("the whole mesh's row");
    let worst = all["min_dihedral_deg"].as_f64().unwrap();
    assert!(worst > 1.0, "{all}");
}

#[test]
fn a_graben_between_a_master_fault_and_an_antithetic_one_ending_on_it_meshes_into_six_regions() {
    builds_and_meshes(&case("graben"));
}

#[test]
fn layers_tilted_to_35_degrees_outcrop_at_the_top_and_mesh_into_four_regions() {
    let (_dir, report) = builds_and_meshes_reporting(&case("tilted_layers"));
    let names = region_names(&report);
    // The layers between horizons run from the box's top to its base; the side regions each
    // end at one of them.
    for layer in ["H1+H2+", "H2+H3+"] {
        let n = (names.iter().find(|n| n.starts_with(layer)))
            .unwrap_or_else(|| panic!("no layer {layer}: {names:?}"));
        assert!(n.contains("box.zmax") && n.contains("box.zmin"), "{n}");
    }
    // West of H1 the top and no base; east of H3 the base and no top.
    for (side, has, lacks) in [("H1+box", "zmax", "zmin"), ("H3+box", "zmin", "zmax")] {
        let n = (names.iter().find(|n| n.starts_with(side))).expect(side);
        let (has, lacks) = (format!("box.{has}"), format!("box.{lacks}"));
        assert!(n.contains(&has) && !n.contains(&lacks), "{n}");
    }
}

#[test]
fn a_horst_between_two_faults_dipping_away_from_each_other_meshes_into_six_regions() {
    let (_dir, report) = builds_and_meshes_reporting(&case("horst"));
    let names = region_names(&report);
    // The raised block, above and below its own horizon, lies between both faults; each outer
    // block, above and below the regional horizon, against one.
    let between = |n: &&String| n.starts_with("F1+F2+H_h+");
    assert_eq!(names.iter().filter(between).count(), 2, "{names:?}");
    for fault in ["F1+H+", "F2+H+"] {
        let outer = names.iter().filter(|n| n.starts_with(fault)).count();
        assert_eq!(outer, 2, "{fault}: {names:?}");
    }
}

#[test]
fn a_fault_ending_upwards_on_an_unconformity_meshes_into_five_regions() {
    builds_and_meshes(&case("fault_under_an_unconformity"));
}

#[test]
fn a_relay_ramp_between_two_faults_dying_out_side_by_side_meshes_into_two_regions() {
    builds_and_meshes(&case("relay_ramp"));
}

#[test]
fn a_listric_fault_flattening_with_depth_over_a_rollover_meshes_into_six_regions() {
    builds_and_meshes(&case("listric_fault"));
}

#[test]
fn a_fault_with_a_hole_in_it_is_embedded_in_its_layer_with_the_holes_border_as_a_curve() {
    builds_and_meshes(&case("fault_with_a_hole"));
}

#[test]
fn a_horizon_with_a_hole_nothing_fills_fails_naming_the_hole_and_what_to_change() {
    let case = horizon_with_a_hole();
    let dir = tempfile::tempdir().expect("a scratch folder");
    let out = build_quietly(dir.path(), &case.write(dir.path()));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    for said in [
        "surface `H2` stops short: a free border loop through (",
        "a hole in the surface",
        "close the hole in the data",
        "`kind = \"fault\"`",
    ] {
        assert!(err.contains(said), "{said}: {err}");
    }
}

#[test]
fn a_layer_collapsed_onto_its_top_ends_where_the_two_surfaces_part_whichever_is_named_first() {
    // The surface named first keeps the triangles the two have in common, the other ends at
    // their border: the same three regions either way.
    for (top, base, first) in [("H1", "H2", "H1"), ("T", "B", "B")] {
        let case = collapsed_layer("collapsed_layer", top, base, -1060.0, 0.045);
        let dir = tempfile::tempdir().expect("a scratch folder");
        let out = build_saying(dir.path(), &case.write(dir.path()));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{top}/{base}: {err}");
        let other = if first == top { base } else { top };
        let said = format!(
            "`{other}` is one with `{first}` over 209 triangle(s) (the same points): kept as \
             `{first}`'s, and `{other}` ends where they part"
        );
        assert!(err.contains(&said), "{top}/{base}: {err}");
        passes_the_checker(dir.path(), &case);
    }
}

#[test]
fn an_onlap_under_a_degree_meshes_at_the_first_build_without_a_round_of_refinement() {
    // While `H1/U` was cut at every jog sharper than the kink angle, however short, the meshes
    // of U and H1 crossed near the tip, and the build refined along it to 25 m and built again.
    // Cut only at corners that turn over the longer edge's reach, they do not cross.
    let case = known_gap("onlap_under_a_degree");
    let dir = tempfile::tempdir().expect("a scratch folder");
    let recipe = case.write(dir.path());
    let out = build_saying(dir.path(), &recipe);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(!err.contains("Refining"), "{err}");
    passes_the_checker(dir.path(), &case);
}

#[test]
fn a_vertical_tube_through_a_horizon_meshes_into_four_regions() {
    builds_and_meshes(&case("vertical_tube"));
}

#[test]
fn a_salt_stock_piercing_two_horizons_meshes_into_four_regions() {
    builds_and_meshes(&case("salt_stock"));
}

#[test]
fn a_fault_through_a_closed_salt_diapir_meshes_with_no_crease_at_the_walls_standing_caps() {
    // The salt wall's caps stood at 89-118° to the wall round them: their edges were creases,
    // a sliver patch between them held a needle of 1.2 m by 12 m, and tets on it reached 5.7°.
    builds_and_meshes(&case("fault_through_salt"));
}

#[test]
fn a_horizon_with_caps_standing_off_it_meshes_as_if_it_had_none() {
    // Each cap stood at 71-80° to the horizon round it: its edges were creases, and it a
    // patch of its own, a needle half a metre wide and some 230 m long.
    let (_, report) = builds_and_meshes_reporting(&case("horizon_with_standing_caps"));
    let h1 = (report["model"]["patches"].as_array().unwrap().iter())
        .filter(|p| p["name"].as_str().unwrap().starts_with("H1#"))
        .count();
    assert_eq!(h1, 2, "H1 cut by the fault, and nothing else");
}

#[test]
fn a_horizon_whose_caps_the_curves_cut_meshes_as_if_it_had_none() {
    // Where the fault or a box side cut a cap, the curve climbed its wall and came down within
    // 0.1 m: cut at each turn, curves of 5 cm; and the cap's pieces stood up as the cap did, a
    // bend the surface meshes refined at to 5 m beside curve segments of 250 m. Tets reached
    // 0.10°, at 206,000 against some 16,000.
    let (dir, report) = builds_and_meshes_reporting(&case("caps_cut_by_curves"));
    let plain = test_support::geology::standing_caps("no_caps", |_| false);
    let (_, plain_report) = builds_and_meshes_reporting(&plain);
    let counts = |r: &serde_json::Value| {
        let names = |k: &str| -> Vec<String> {
            (r["model"][k].as_array().unwrap().iter())
                .map(|x| x["name"].as_str().unwrap().to_string())
                .collect()
        };
        (names("patches"), names("curves"))
    };
    assert_eq!(
        counts(&report),
        counts(&plain_report),
        "the same patches and curves"
    );
    let shortest = (curves_named(dir.path(), "", "length").into_iter())
        .map(|(_, l)| l)
        .fold(f64::INFINITY, f64::min);
    assert!(shortest > 100.0, "{shortest}");
    let tets = |r: &serde_json::Value| {
        (r["nodes"].as_array().unwrap().iter())
            .find(|n| n["name"] == "mesh")
            .and_then(|n| n["counts"]["tets"].as_f64())
            .expect("a mesh node counting tets")
    };
    assert!(
        tets(&report) < 1.1 * tets(&plain_report),
        "{} against {}",
        tets(&report),
        tets(&plain_report)
    );
}

#[test]
fn a_closed_salt_diapir_inside_the_box_meshes_into_four_regions() {
    builds_and_meshes(&case("closed_salt_diapir"));
}

#[test]
fn a_smoothed_salt_diapir_meshes_with_its_contact_curves_as_fine_as_the_salt_bends() {
    // Smoothed, the salt's surface mesh refines to its curvature, some 25 m: at the recipe's
    // 250 m its contacts with the horizons would leave thin boundary triangles the tet mesher
    // could not recover (it gave up on the salt after minutes). A chart seam passing 8 cm from
    // the salt's contact with H1 cut off a lobe whose surface mesh held a needle, and tets of
    // 0.55° on both sides of it: the quality bars hold now.
    let mut case = case("closed_salt_diapir");
    case.recipe = case.recipe.replace("\" }", "\", smooth = true }");
    assert_eq!(
        case.recipe.matches("smooth = true").count(),
        3,
        "{}",
        case.recipe
    );
    let (dir, _) = builds_and_meshes_reporting(&case);
    let report: serde_json::Value = serde_json::from_slice(
        &std::fs::read(dir.path().join("out/report.json")).expect("the report"),
    )
    .expect("JSON");
    let curves = report["curves"].as_array().expect("curves");
    let contacts: Vec<&serde_json::Value> = (curves.iter())
        .filter(|c| c["name"].as_str().is_some_and(|n| n.contains("/SALT")))
        .collect();
    assert!(contacts.len() >= 2, "{curves:?}");
    for c in contacts {
        let (length, nodes) = (c["length"].as_f64().unwrap(), c["nodes"].as_f64().unwrap());
        let segment = length / (nodes - 1.0);
        assert!(segment < 100.0, "{c}: segments of {segment:.0} m");
    }
}

#[test]
fn a_smoothed_lens_meshes_its_rim_with_the_curves_of_its_narrow_rim_patches_graded_alike() {
    // Smoothed, the lens's rim bends tightly and is split into narrow strips along it. Each
    // strip's borders lie along patches that bend very differently (one at 4 m, the other at
    // 30 m, 10 m apart): without grading the curvature sizes across curves the strips' meshes
    // were needles and the tet mesher stalled for minutes in the rim.
    let mut case = case("lens");
    case.recipe = case.recipe.replace("\" }", "\", smooth = true }");
    assert_eq!(
        case.recipe.matches("smooth = true").count(),
        3,
        "{}",
        case.recipe
    );
    assert!(!case.recipe.contains("min_size"), "{}", case.recipe);
    builds_and_meshes(&case);
}

#[test]
fn smoothed_horizons_touching_along_a_line_are_refused_naming_the_patches_that_lie_on_each_other() {
    // Smoothing the ridge that touches H1 along its crest bulges it through H1 between the
    // file's crest vertices: thin regions whose two sides are one and the same triangles.
    let mut case = case("horizons_touching_along_a_line");
    case.recipe = case.recipe.replace("\" }", "\", smooth = true }");
    assert!(case.recipe.contains("smooth = true"), "{}", case.recipe);
    let dir = tempfile::tempdir().expect("a scratch folder");
    let recipe = case.write(dir.path());
    let out = build_quietly(dir.path(), &recipe);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{err}");
    let line = (err.lines())
        .find(|l| l.contains("lie on each other"))
        .unwrap_or_else(|| panic!("no face-to-face error:\n{err}"));
    assert!(
        line.contains("`H1#") && line.contains("`H2#") && line.contains("`smooth`"),
        "{line}"
    );
}

#[test]
fn a_closed_salt_diapir_with_a_well_into_its_flank_meshes_with_the_well_embedded() {
    let case = case("closed_salt_diapir_with_well");
    let dir = builds_and_meshes(&case);
    // The well is a line group of the mesh, so its salt region was meshed by the Delaunay path
    // (the front embeds no segments).
    let msh = std::fs::read_to_string(dir.path().join(format!("out/{}.msh", case.name)))
        .expect("the mesh");
    let names = msh
        .split("$PhysicalNames")
        .nth(1)
        .and_then(|s| s.split("$EndPhysicalNames").next())
        .expect("physical names");
    assert!(
        names
            .lines()
            .any(|l| l.starts_with("1 ") && l.contains("\"W\"")),
        "{names}"
    );
}

#[test]
fn an_intrusion_cutting_an_older_body_meshes_into_four_regions() {
    // The seams cutting the younger body into charts run 0.16 m beside the curve where the
    // bodies meet: the curves are as fine as the charts are wide there.
    builds_and_meshes(&case("intrusion_cutting_a_body"));
}

#[test]
fn a_closed_lens_inside_a_layer_meshes_as_its_own_region_inside_its_host() {
    builds_and_meshes(&case("lens"));
}

#[test]
fn a_raft_inside_a_closed_salt_body_meshes_as_a_region_inside_the_salt() {
    let case = case("raft_in_salt");
    let dir = builds_and_meshes(&case);
    let file = dir.path().join(format!("out/{}.msh", case.name));
    let mesh = read_volume_msh(&std::fs::read(&file).expect("the msh"), "msh").expect("reads");
    // The raft's triangles bound the raft on one side and the salt on the other.
    let region = |name: &str| mesh.regions.iter().position(|r| r.name == name);
    let (raft, salt) = (
        region("RAFT").expect("a raft"),
        region("SALT").expect("a salt"),
    );
    let on_raft: BTreeSet<u32> = (mesh.triangles.iter().zip(&mesh.triangle_group))
        .filter(|(_, g)| mesh.surface_groups[**g as usize].name == "RAFT")
        .flat_map(|(t, _)| *t)
        .collect();
    let touching = |r: usize| {
        (mesh.tets.iter().zip(&mesh.tet_region))
            .filter(|(t, g)| {
                **g as usize == r && t.iter().filter(|v| on_raft.contains(v)).count() == 3
            })
            .count()
    };
    assert!(
        touching(raft) > 0 && touching(salt) > 0,
        "the raft lies in the salt"
    );
    for (k, r) in mesh.regions.iter().enumerate() {
        if k != raft && k != salt {
            assert_eq!(touching(k), 0, "{} touches the raft", r.name);
        }
    }
}

#[test]
fn a_chevron_fold_keeps_its_hinge_as_curves_of_each_horizon() {
    let (_dir, report) = builds_and_meshes_reporting(&case("chevron_fold"));
    // The hinge's creases are curves of each horizon's own (not where a box side cuts it).
    for h in ["H1", "H2"] {
        let own = count_named(&report, &format!("discretize:{h}#"));
        assert!(own >= 2, "{h}: {own} crease curves");
    }
}

#[test]
fn a_fault_of_patches_touching_only_at_corners_embeds_every_patch_with_its_own_curves() {
    let (_dir, report) = builds_and_meshes_reporting(&case("fault_patches_at_corners"));
    let named = |prefix: &str| count_named(&report, prefix);
    // 144 triangles, none sharing an edge: each is a patch of its own, bounded by its own
    // curves (split where it touches its neighbours).
    assert_eq!(named("surface_mesh:F#"), 144, "{}", named("patch:F"));
    assert!(named("curve:F#") >= 144, "{}", named("curve:F#"));
}

#[test]
fn a_dense_fault_of_patches_touching_only_at_corners_meshes_and_passes_the_checker() {
    // 3,600 triangles on a cocircular grid: a third of the layer's triangles are no Delaunay
    // faces at first, each crossed in its plane by the other diagonal of its cell, through the
    // gap beside it. Recovered by flipping that diagonal; left to the front, the layer failed.
    let (_dir, report) = builds_and_meshes_reporting(&case("dense_fault_patches_at_corners"));
    assert_eq!(count_named(&report, "surface_mesh:F#"), 3600);
}

/// How many nodes of `report` have a name starting with `prefix`.
fn count_named(report: &serde_json::Value, prefix: &str) -> usize {
    report["nodes"]
        .as_array()
        .expect("nodes")
        .iter()
        .filter(|n| n["name"].as_str().is_some_and(|s| s.starts_with(prefix)))
        .count()
}

#[test]
fn two_dangling_faults_crossing_inside_a_layer_are_both_embedded_in_its_region() {
    let (_dir, report) = builds_and_meshes_reporting(&case("dangling_faults_crossing"));
    // F1 runs across F2 from its upper tip line to its lower one: F2 is cut in two patches,
    // F1 keeps one with the curve inside it.
    assert_eq!(count_named(&report, "surface_mesh:F2#"), 2);
    assert_eq!(count_named(&report, "surface_mesh:F1#"), 1);
    assert_eq!(count_named(&report, "discretize:F1/F2"), 1);
}

#[test]
fn a_horizon_touching_another_at_one_point_leaves_one_layer_pinched_at_a_node_of_both() {
    let case = case("horizons_touching_at_a_point");
    let dir = builds_and_meshes(&case);
    let file = dir.path().join(format!("out/{}.msh", case.name));
    let mesh = read_volume_msh(&std::fs::read(&file).expect("the msh"), "msh").expect("reads");
    let nodes_of = |surface: &str| -> BTreeSet<u32> {
        (mesh.triangles.iter().zip(&mesh.triangle_group))
            .filter(|(_, g)| mesh.surface_groups[**g as usize].name == surface)
            .flat_map(|(t, _)| *t)
            .collect()
    };
    let shared: Vec<u32> = nodes_of("H1")
        .intersection(&nodes_of("H2"))
        .copied()
        .collect();
    assert_eq!(shared.len(), 1, "H1 and H2 share the touch point only");
    assert_eq!(mesh.nodes[shared[0] as usize][2], -600.0, "on the flat H1");
}

#[test]
fn a_horizon_touching_another_along_a_line_cuts_the_layer_between_in_two_regions() {
    let (_dir, report) = builds_and_meshes_reporting(&case("horizons_touching_along_a_line"));
    // The crest runs along H2's edges on H1: one curve across the box, found exactly.
    assert_eq!(count_named(&report, "discretize:H1/H2"), 1);
}

/// The SCEC CFM case `name`, or `None` (after a note) when `../shared` is absent.
fn scec_case(name: &str) -> Option<Case> {
    let cfm = paths::shared("data/gocad/SCECcode__CFM")?;
    scec_cases(&cfm).into_iter().find(|c| c.name == name)
}

#[test]
fn the_western_transverse_ranges_faults_of_the_scec_cfm_intersected_in_a_box_mesh() {
    let Some(case) = scec_case("scec_western_transverse_ranges") else {
        return;
    };
    let (_dir, report) = builds_and_meshes_reporting(&case);
    // Big Pine meets Pine Mountain and the box top where their curves cross: the crossing
    // rounds onto the curve point of Big Pine's edge on the box top, and is that point.
    assert_eq!(count_named(&report, "discretize:bigpine/pinemtn"), 1);
    assert!(count_named(&report, "surface_mesh:bigpine#") >= 1);
}

#[test]
fn the_tejon_pass_faults_of_the_scec_cfm_with_white_wolfs_crossing_strands_mesh() {
    let Some(case) = scec_case("scec_tejon_pass") else {
        return;
    };
    let (_dir, report) = builds_and_meshes_reporting(&case);
    // White Wolf's strands cross along non-manifold edges inside the box: more than one patch.
    assert!(count_named(&report, "surface_mesh:whitewolf#") >= 3);
}

#[test]
fn the_tejon_pass_faults_at_two_kilometres_mesh_with_a_white_wolf_fin_in_a_recovery_hole() {
    let Some(case) = scec_case("scec_tejon_pass_coarse") else {
        return;
    };
    let (_dir, report) = builds_and_meshes_reporting(&case);
    assert!(count_named(&report, "surface_mesh:whitewolf#") >= 3);
}

#[test]
fn the_big_bend_faults_build_and_the_report_names_the_slit_between_two_san_andreas_strands() {
    let Some(cfm) = paths::shared("data/gocad/SCECcode__CFM") else {
        return;
    };
    let case = scec_big_bend(&cfm);
    let (dir, _) = build(&case);
    let report: serde_json::Value = serde_json::from_slice(
        &std::fs::read(dir.path().join("out/report.json")).expect("report.json"),
    )
    .expect("json");
    let warnings: Vec<&str> = (report["warnings"].as_array().expect("warnings").iter())
        .filter_map(|w| w.as_str())
        .filter(|w| w.contains("come within"))
        .collect();
    // The strands' free edges, 2 m apart at x = 362.4 km; Lockwood Valley's end 11 m from the
    // San Andreas at the box floor; both told, closest first.
    let slit = warnings
        .first()
        .unwrap_or_else(|| panic!("no close curves in {report}"));
    for needle in [
        "`saf#3`",
        "`saf#4`",
        "(362412.4, 3840390.6",
        "(316474.3, 3854918.9",
    ] {
        assert!(slit.contains(needle), "`{needle}` not in {slit}");
    }
}

#[test]
fn a_thin_region_the_recipe_does_not_name_is_warned_about_with_a_point_to_name_it_by() {
    // Without `min_layers`, the lens (about 230 m thick at 250 m) is one element across; the
    // recipe cannot give it `layers` until it names it, so the warning says how, with a point.
    let mut lens = case("lens");
    lens.recipe = lens.recipe.replace("min_layers = 2\n", "");
    let dir = tempfile::tempdir().expect("a scratch folder");
    let recipe = lens.write(dir.path());
    let out = build_saying(dir.path(), &recipe);
    let err = String::from_utf8_lossy(&out.stderr);
    let warning = err
        .lines()
        .find(|l| l.contains("region `L` is about"))
        .unwrap_or_else(|| panic!("no warning about the lens:\n{err}"));
    assert!(
        warning.contains("name it in `[regions]` (for example `L = { point = ["),
        "{warning}"
    );
    // The point it gives names the lens: a recipe that takes the advice builds with layers.
    let point = warning
        .split("point = [")
        .nth(1)
        .and_then(|s| s.split(']').next())
        .expect("a point");
    let named = format!(
        "{}\n[regions]\nL = {{ point = [{point}] }}\n\n[mesh.regions]\nL = {{ layers = 2 }}\n",
        std::fs::read_to_string(&recipe).unwrap()
    );
    std::fs::write(&recipe, named).unwrap();
    let out = build_quietly(dir.path(), &recipe);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(!err.contains("region `L` is about"), "{err}");
}
