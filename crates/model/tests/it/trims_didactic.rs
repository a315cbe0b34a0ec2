//! Trims on the shipped didactic model, split as the `model` operation splits it: the horizons
//! H1 and H2 (35 m apart), the through-going fault F1 and the dangling fault F2, in the box.
//! Each test applies `[[trim]]` entries and checks which patches go.

use geom::{BBox, Tolerances, TriMesh};
use gocad::import::{ImportOptions, import_surface};
use model::intersect::split::split_model;
use model::intersect::{SurfaceRef, box_sides, intersect};
use model::patches::{Patch, inside_box, patches};
use model::trims::{Side, TrimAction, TrimSpec};
use model::trims::{TrimError, TrimOutcome, TrimPatch, apply_trims};
use std::sync::OnceLock;

const FILES: [(&str, &str); 4] = [
    ("H1", "H1_top_reservoir.ts"),
    ("H2", "H2_base_reservoir.ts"),
    ("F1", "F1_through.ts"),
    ("F2", "F2_dangling.ts"),
];

fn bbox() -> BBox {
    BBox {
        min: [500_000.0, 7_000_000.0, -2500.0],
        max: [505_000.0, 7_005_000.0, 0.0],
    }
}

/// The split model: split surfaces by name, and every patch (inside the box or not).
struct Model {
    split: Vec<(String, TriMesh)>,
    patches: Vec<(String, Patch)>,
}

/// The pairs `recipes/didactic.toml` intersects, minus those in `without`.
fn build(without: &[(&str, &str)]) -> Model {
    let dir = concat!(
        concat!(env!("CARGO_MANIFEST_DIR"), "/../.."),
        "/recipes/data/didactic/"
    );
    let mut surfaces: Vec<(String, TriMesh)> = FILES
        .iter()
        .map(|(name, file)| {
            let bytes = std::fs::read(format!("{dir}{file}")).expect("didactic data is shipped");
            let s = import_surface(&bytes, file, &ImportOptions::default()).expect("imports");
            (name.to_string(), s.mesh)
        })
        .collect();
    surfaces.extend(box_sides(&bbox()));
    let mut pairs = vec![
        ("H1", "H2"),
        ("H1", "F1"),
        ("H2", "F1"),
        ("F2", "H1"),
        ("F2", "H2"),
    ];
    let sides: Vec<String> = surfaces.iter().skip(4).map(|s| s.0.clone()).collect();
    for g in ["H1", "H2", "F1"] {
        for s in &sides {
            pairs.push((g, s.as_str()));
        }
    }
    pairs.retain(|p| !without.contains(p));
    let r = |n: &str| {
        let (name, mesh) = surfaces.iter().find(|s| s.0 == n).expect("known surface");
        SurfaceRef { name, mesh }
    };
    let xs: Vec<_> = pairs
        .iter()
        .map(|(a, b)| intersect(r(a), r(b)).expect("no coplanar contact"))
        .collect();
    let named: Vec<(&str, &TriMesh)> = surfaces.iter().map(|(n, m)| (n.as_str(), m)).collect();
    let split = split_model(&named, &xs).unwrap_or_else(|e| panic!("splits: {e}"));
    let mut all = Vec::new();
    for ((name, _), s) in surfaces.iter().zip(&split) {
        all.extend(patches(name, s).into_iter().map(|p| (name.clone(), p)));
    }
    Model {
        split: surfaces
            .iter()
            .map(|s| s.0.clone())
            .zip(split.into_iter().map(|s| s.mesh))
            .collect(),
        patches: all,
    }
}

fn model() -> &'static Model {
    static M: OnceLock<Model> = OnceLock::new();
    M.get_or_init(|| build(&[]))
}

/// A trim of the surfaces `selector` names: a name, or a prefix followed by `*` (resolved
/// against the model's surfaces by `run`, as the plan resolves a recipe's globs).
fn trim(selector: &str, action: TrimAction) -> TrimSpec {
    TrimSpec {
        selector: selector.into(),
        surfaces: Vec::new(),
        action,
    }
}

fn keep(surface: &str, side: Side, of: &str) -> TrimSpec {
    trim(
        surface,
        TrimAction::Keep {
            side,
            of: of.into(),
        },
    )
}

fn run(m: &Model, trims: &[TrimSpec]) -> Result<TrimOutcome, TrimError> {
    let selects = |pattern: &str, name: &str| match pattern.strip_suffix('*') {
        Some(prefix) => name.starts_with(prefix),
        None => name == pattern,
    };
    let trims: Vec<TrimSpec> = trims
        .iter()
        .map(|t| TrimSpec {
            surfaces: m
                .split
                .iter()
                .map(|(n, _)| n.clone())
                .filter(|n| selects(&t.selector, n))
                .collect(),
            ..t.clone()
        })
        .collect();
    let ps: Vec<TrimPatch> = m
        .patches
        .iter()
        .map(|(s, p)| TrimPatch {
            name: &p.name,
            surface: s,
            mesh: &p.mesh,
        })
        .collect();
    let split: Vec<(&str, &TriMesh)> = m.split.iter().map(|(n, s)| (n.as_str(), s)).collect();
    apply_trims(&ps, &split, &trims, &bbox(), &Tolerances::default())
}

/// The patches a given trim (by index) discarded.
fn discarded_by<'m>(m: &'m Model, out: &TrimOutcome, k: usize) -> Vec<&'m Patch> {
    out.discarded
        .iter()
        .filter(|d| d.trim == Some(k))
        .map(|d| &m.patches[d.patch].1)
        .collect()
}

fn z_range(p: &Patch) -> (f64, f64) {
    let zs = p.mesh.vertices.iter().map(|v| v[2]);
    (
        zs.clone().fold(f64::INFINITY, f64::min),
        zs.fold(f64::NEG_INFINITY, f64::max),
    )
}

fn kept_of<'m>(m: &'m Model, out: &TrimOutcome, surface: &str) -> Vec<&'m Patch> {
    m.patches
        .iter()
        .zip(&out.keep)
        .filter(|((s, _), k)| s == surface && **k)
        .map(|((_, p), _)| p)
        .collect()
}

#[test]
fn without_trims_only_the_patches_outside_the_box_go_and_the_dangling_fault_stays() {
    let m = model();
    let out = run(m, &[]).expect("no trims");
    for (i, (_, p)) in m.patches.iter().enumerate() {
        assert_eq!(out.keep[i], inside_box(p, &bbox()), "{}", p.name);
    }
    assert!(out.discarded.iter().all(|d| d.trim.is_none()));
    assert!(out.discarded.iter().all(|d| d.reason == "outside the box"));
    assert_eq!(
        kept_of(m, &out, "F1").len(),
        3,
        "above, in and below the reservoir"
    );
    assert_eq!(
        kept_of(m, &out, "F2").len(),
        3,
        "F2's free borders do not trim it"
    );
}

#[test]
fn keeping_f1_below_h1_discards_exactly_the_f1_patch_above_h1() {
    let m = model();
    let out = run(m, &[keep("F1", Side::Below, "H1")]).expect("trims");
    let gone = discarded_by(m, &out, 0);
    assert_eq!(gone.len(), 1);
    let (lo, hi) = z_range(gone[0]);
    assert_eq!(hi, 0.0, "it reaches the top of the box");
    assert!(lo > -1300.0, "it ends at H1, near z = -1200: {lo}");
    assert!(
        out.discarded
            .iter()
            .any(|d| d.reason.ends_with(": above H1"))
    );
    assert_eq!(kept_of(m, &out, "F1").len(), 2);
}

#[test]
fn keeping_f1_above_h2_discards_exactly_the_f1_patch_below_h2() {
    let m = model();
    let out = run(m, &[keep("F1", Side::Above, "H2")]).expect("trims");
    let gone = discarded_by(m, &out, 0);
    assert_eq!(gone.len(), 1);
    let (lo, hi) = z_range(gone[0]);
    assert_eq!(lo, -2500.0, "it reaches the bottom of the box");
    assert!(hi < -1100.0, "it ends at H2: {hi}");
}

#[test]
fn two_keeps_leave_only_the_reservoir_parts_of_both_faults() {
    let m = model();
    let out = run(
        m,
        &[keep("F*", Side::Below, "H1"), keep("F*", Side::Above, "H2")],
    )
    .expect("trims");
    assert_eq!(discarded_by(m, &out, 0).len(), 2, "F1 and F2 above H1");
    assert_eq!(discarded_by(m, &out, 1).len(), 2, "F1 and F2 below H2");
    for f in ["F1", "F2"] {
        let left = kept_of(m, &out, f);
        assert_eq!(left.len(), 1, "{f}");
        let (lo, hi) = z_range(left[0]);
        assert!(
            hi - lo < 200.0,
            "{f}: the 35 m reservoir strip, seen along dip: {lo}..{hi}"
        );
    }
}

#[test]
fn a_keep_with_a_glob_never_judges_the_surface_it_keeps_against() {
    // H1 judged against itself would be "every vertex is on H1"; H2 lies wholly below H1, so
    // the trim keeps everything and says so.
    let m = model();
    let e = run(m, &[keep("H*", Side::Below, "H1")]).unwrap_err();
    assert!(
        e.message
            .contains("patches it selects are already below `H1`"),
        "{}",
        e.message
    );
}

#[test]
fn a_point_on_h1_west_of_f1_discards_that_patch_and_only_it() {
    let m = model();
    let h1 = &m.split.iter().find(|s| s.0 == "H1").expect("H1").1;
    // An original vertex of H1 inside the box, west of F1 (x < 1000 m local).
    let p = *h1
        .vertices
        .iter()
        .find(|v| v[0] > 500_300.0 && v[0] < 501_000.0 && v[1] > 7_001_000.0)
        .expect("a vertex");
    for q in [p, [p[0], p[1], p[2] + 1e-3]] {
        let out = run(m, &[trim("H1", TrimAction::DiscardContaining(q))]).expect("trims");
        let gone = discarded_by(m, &out, 0);
        assert_eq!(gone.len(), 1, "exactly one patch holds {q:?}");
        assert!(
            gone[0].mesh.vertices.iter().all(|v| v[0] < 502_000.0),
            "the west one"
        );
    }
    let off = [p[0], p[1], p[2] + 1.0];
    let e = run(m, &[trim("H1", TrimAction::DiscardContaining(off))]).unwrap_err();
    assert_eq!(e.trim, Some(0));
    assert!(e.message.contains("[[trim]] #1"), "{}", e.message);
    assert!(e.message.contains("is on no patch"), "{}", e.message);
    assert!(e.message.contains("the nearest is `H1#"), "{}", e.message);
}

#[test]
fn a_point_on_the_curve_between_two_patches_is_ambiguous_and_names_both() {
    let m = model();
    let out = run(m, &[]).expect("no trims");
    let h1 = kept_of(m, &out, "H1");
    assert_eq!(h1.len(), 2, "F1 cuts H1 in two");
    let shared = h1[0]
        .mesh
        .vertices
        .iter()
        .find(|v| h1[1].mesh.vertices.contains(v))
        .copied()
        .expect("a vertex on H1/F1");
    let e = run(m, &[trim("H1", TrimAction::DiscardContaining(shared))]).unwrap_err();
    assert!(e.message.contains("is on 2 patches"), "{}", e.message);
    assert!(e.message.contains(&h1[0].name) && e.message.contains(&h1[1].name));
}

#[test]
fn the_nearest_patch_to_a_point_in_the_west_overburden_is_the_west_part_of_h1() {
    let m = model();
    let p = [500_500.0, 7_001_000.0, -600.0];
    let out = run(m, &[trim("H1", TrimAction::DiscardNearest(p))]).expect("trims");
    let gone = discarded_by(m, &out, 0);
    assert_eq!(gone.len(), 1);
    assert!(gone[0].mesh.vertices.iter().all(|v| v[0] < 502_000.0));
    // Symmetric: the east one from the east.
    let q = [504_000.0, 7_001_000.0, -2000.0];
    let out = run(m, &[trim("H1", TrimAction::DiscardNearest(q))]).expect("trims");
    let gone = discarded_by(m, &out, 0);
    assert!(gone[0].mesh.vertices.iter().all(|v| v[0] > 500_900.0));
}

#[test]
fn a_later_trim_only_sees_the_patches_earlier_trims_kept() {
    let m = model();
    let top = [501_000.0, 7_002_500.0, 0.0];
    let out = run(
        m,
        &[
            keep("F1", Side::Below, "H1"),
            trim("F1", TrimAction::DiscardNearest(top)),
        ],
    )
    .expect("trims");
    let second = discarded_by(m, &out, 1);
    assert_eq!(second.len(), 1);
    let (_, hi) = z_range(second[0]);
    assert!(
        hi < -1100.0,
        "the reservoir strip, the nearest one left: {hi}"
    );
}

#[test]
fn area_below_discards_the_thin_reservoir_strips_of_the_box_sides() {
    let m = model();
    let out = run(m, &[trim("box.*", TrimAction::DiscardAreaBelow(200_000.0))]).expect("trims");
    let gone = discarded_by(m, &out, 0);
    // box.xmin, box.xmax: one strip each; box.ymin, box.ymax: F1 cuts theirs in two.
    assert_eq!(gone.len(), 6);
    for p in gone {
        let (lo, hi) = z_range(p);
        assert!(hi - lo < 200.0, "{}: {lo}..{hi}", p.name);
        assert!(p.mesh.area() < 200_000.0);
    }
    let bigger = run(m, &[trim("box.*", TrimAction::DiscardAreaBelow(1.0))]).unwrap_err();
    assert!(
        bigger.message.contains("no patch has an area below 1"),
        "{}",
        bigger.message
    );
    assert!(
        bigger.message.contains("the smallest is `box."),
        "{}",
        bigger.message
    );
}

#[test]
fn a_trim_that_changes_nothing_is_an_error_naming_it() {
    let m = model();
    let e = run(
        m,
        &[
            keep("F1", Side::Below, "H1"),
            keep("F2", Side::Above, "box.zmin"),
        ],
    )
    .unwrap_err();
    assert_eq!(e.trim, Some(1));
    assert!(
        e.message
            .starts_with("[[trim]] #2 (surface = \"F2\", keep = { above = \"box.zmin\" })"),
        "{}",
        e.message
    );
    assert!(e.message.contains("discards nothing"), "{}", e.message);
    let e = run(m, &[trim("G*", TrimAction::DiscardAreaBelow(1.0))]).unwrap_err();
    assert!(
        e.message.contains("no patch of a surface matching `G*`"),
        "{}",
        e.message
    );
    let e = run(m, &[keep("F1", Side::Below, "H9")]).unwrap_err();
    assert!(e.message.contains("no surface `H9`"), "{}", e.message);
}

#[test]
fn a_fault_not_intersected_with_the_horizon_lies_on_both_sides_of_it_and_says_so() {
    let m = build(&[("H1", "F1")]);
    let e = run(&m, &[keep("F1", Side::Below, "H1")]).unwrap_err();
    assert!(
        e.message.contains("lies on both sides of `H1`"),
        "{}",
        e.message
    );
    assert!(
        e.message.contains("intersect `F1` with `H1`"),
        "{}",
        e.message
    );
    assert!(e.patch.as_deref().is_some_and(|p| p.starts_with("F1#")));
    assert!(e.at.is_some());
}

#[test]
fn a_vertical_wall_cannot_be_kept_above_and_the_error_names_the_patch_and_point() {
    let m = model();
    let e = run(m, &[keep("H1", Side::Above, "box.xmin")]).unwrap_err();
    assert!(e.message.contains("does not extend over"), "{}", e.message);
    assert!(e.patch.as_deref().is_some_and(|p| p.starts_with("H1#")));
}

#[test]
fn the_split_model_is_the_same_on_one_thread_and_on_four() {
    // `split_model` splits surfaces in parallel; the trims read its meshes bit for bit.
    let build_on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool")
            .install(|| build(&[]))
    };
    let (one, four) = (build_on(1), build_on(4));
    assert_eq!(one.split, four.split);
    assert_eq!(one.patches, four.patches);
}
