//! Black-list findings on small hand-built surfaces (detection and repair of each kind) and on
//! the real quirky CFM files.

use geom::{Tolerances, TriMesh};
use gocad::import::{ImportOptions, ImportedSurface, PartInfo, SourceMap, import_surface};
use gocad::validate::{FindingKind, repair, repair_summary, repaired_counts, validate};
use test_support::paths;

fn surface(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> ImportedSurface {
    let nt = triangles.len();
    let nv = vertices.len();
    ImportedSurface {
        name: "s".into(),
        mesh: TriMesh::new(vertices, triangles),
        triangle_part: vec![0; nt],
        parts: vec![PartInfo {
            name: "TFACE 1".into(),
            line: 1,
            object: "s".into(),
            model_tface: None,
            triangle_count: nt,
        }],
        bstones: vec![],
        borders: vec![],
        property_names: vec![],
        properties: vec![],
        source: SourceMap {
            file: "s.ts".into(),
            vertex_ids: (1..=nv as u64).collect(),
            vertex_lines: (0..nv as u32).map(|i| i + 10).collect(),
            triangle_lines: (0..nt as u32).map(|i| i + 100).collect(),
        },
    }
}

/// UTM-sized origin so that nothing passes by luck of small coordinates.
const X0: f64 = 512_345.125;
const Y0: f64 = 7_012_345.5;

fn p(x: f64, y: f64, z: f64) -> [f64; 3] {
    [X0 + x, Y0 + y, z - 1234.25]
}

/// A 2x2 cell grid, consistently oriented: 9 vertices, 8 triangles.
fn grid() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut v = Vec::new();
    for j in 0..3 {
        for i in 0..3 {
            v.push(p(i as f64 * 10.0, j as f64 * 10.0, 0.0));
        }
    }
    let mut t = Vec::new();
    for j in 0..2u32 {
        for i in 0..2u32 {
            let a = j * 3 + i;
            t.push([a, a + 1, a + 4]);
            t.push([a, a + 4, a + 3]);
        }
    }
    (v, t)
}

fn count(s: &ImportedSurface, kind: FindingKind) -> usize {
    validate(s, &Tolerances::default()).of_kind(kind).count()
}

#[test]
fn a_clean_grid_has_no_findings_and_repair_changes_nothing() {
    let (v, t) = grid();
    let s = surface(v, t);
    let r = validate(&s, &Tolerances::default());
    assert!(r.is_clean(), "{}", r.render_text());
    let (fixed, log) = repair(&s, &r, &Tolerances::default());
    assert_eq!(fixed.mesh, s.mesh);
    assert!(log.flipped.is_empty() && log.dropped_degenerate.is_empty());
}

#[test]
fn an_unreferenced_vertex_is_reported_with_its_id_line_and_coordinates_and_removed_by_repair() {
    let (mut v, t) = grid();
    v.push(p(99.0, 99.0, 0.0));
    let s = surface(v, t);
    let r = validate(&s, &Tolerances::default());
    let f: Vec<_> = r.of_kind(FindingKind::UnreferencedVertex).collect();
    assert_eq!(f.len(), 1);
    assert_eq!(
        (
            f[0].vertices.clone(),
            f[0].vertex_ids.clone(),
            f[0].lines.clone()
        ),
        (vec![9], vec![10], vec![19])
    );
    assert_eq!(f[0].points, vec![p(99.0, 99.0, 0.0)]);
    let (fixed, log) = repair(&s, &r, &Tolerances::default());
    assert_eq!(fixed.mesh.vertices.len(), 9);
    assert_eq!(log.removed_vertices, 1);
    assert!(validate(&fixed, &Tolerances::default()).is_clean());
}

#[test]
fn coincident_vertices_are_one_finding_and_repair_merges_them_onto_the_lowest_index() {
    let (mut v, mut t) = grid();
    // Re-create vertex 4 (the centre) as vertex 9 and use it in two triangles.
    v.push(v[4]);
    t[2] = [1, 2, 9];
    t[3] = [1, 9, 4];
    let s = surface(v, t);
    let r = validate(&s, &Tolerances::default());
    let f: Vec<_> = r.of_kind(FindingKind::DuplicateVertex).collect();
    assert_eq!(f.len(), 1);
    assert_eq!(f[0].vertices, vec![4, 9]);
    let (fixed, log) = repair(&s, &r, &Tolerances::default());
    assert_eq!(log.merged_vertices, 1);
    assert_eq!(fixed.mesh.vertices.len(), 9);
    assert!(fixed.mesh.triangles.iter().flatten().all(|&i| i < 9));
}

#[test]
fn a_merge_distance_makes_near_vertices_duplicates() {
    let (mut v, t) = grid();
    let mut q = v[8];
    q[0] += 0.001;
    v.push(q);
    let s = surface(v, t);
    assert_eq!(count(&s, FindingKind::DuplicateVertex), 0);
    let tol = Tolerances {
        merge_distance: 0.01,
        ..Tolerances::default()
    };
    assert_eq!(
        validate(&s, &tol)
            .of_kind(FindingKind::DuplicateVertex)
            .count(),
        1
    );
}

#[test]
fn exactly_collinear_corners_at_utm_magnitudes_are_degenerate_and_dropped() {
    let (mut v, mut t) = grid();
    // The midpoint of two UTM-sized points is exact in binary64, so the corners are collinear.
    let (a, b) = (p(31.0, 3.0, 2.0), p(41.0, 13.0, 9.0));
    v.push(a);
    v.push([
        (a[0] + b[0]) / 2.0,
        (a[1] + b[1]) / 2.0,
        (a[2] + b[2]) / 2.0,
    ]);
    v.push(b);
    t.push([9, 10, 11]);
    let s = surface(v, t);
    let r = validate(&s, &Tolerances::default());
    let deg: Vec<_> = r
        .of_kind(FindingKind::DegenerateTriangle)
        .map(|f| f.triangles.clone())
        .collect();
    assert_eq!(deg, vec![vec![8]], "{}", r.render_text());
    let (fixed, log) = repair(&s, &r, &Tolerances::default());
    assert_eq!(log.dropped_degenerate, vec![8]);
    assert!(
        validate(&fixed, &Tolerances::default())
            .of_kind(FindingKind::DegenerateTriangle)
            .next()
            .is_none()
    );
}

#[test]
fn a_nearly_collinear_triangle_is_not_degenerate() {
    let v = vec![p(0.0, 0.0, 0.0), p(10.0, 0.0, 0.0), p(20.0, 1e-9, 0.0)];
    let s = surface(v, vec![[0, 1, 2]]);
    assert_eq!(count(&s, FindingKind::DegenerateTriangle), 0);
}

#[test]
fn a_repeated_triangle_in_any_corner_order_is_a_duplicate_and_dropped() {
    let (v, mut t) = grid();
    t.push([4, 0, 1]);
    let s = surface(v, t);
    let r = validate(&s, &Tolerances::default());
    let f: Vec<_> = r.of_kind(FindingKind::DuplicateTriangle).collect();
    assert_eq!(f.len(), 1);
    assert_eq!(f[0].triangles, vec![0, 8]);
    assert_eq!(f[0].lines, vec![100, 108]);
    let (fixed, log) = repair(&s, &r, &Tolerances::default());
    assert_eq!(log.dropped_duplicate, vec![8]);
    assert!(validate(&fixed, &Tolerances::default()).is_clean());
}

#[test]
fn a_flipped_neighbour_is_inconsistent_and_repair_flips_it_back() {
    let (v, mut t) = grid();
    t[3].swap(1, 2);
    let s = surface(v, t);
    let r = validate(&s, &Tolerances::default());
    let f: Vec<_> = r.of_kind(FindingKind::InconsistentOrientation).collect();
    assert_eq!(f.len(), 3, "{}", r.render_text());
    assert!(f.iter().all(|f| f.triangles.contains(&3)));
    let (fixed, log) = repair(&s, &r, &Tolerances::default());
    assert_eq!(log.flipped, vec![3]);
    assert_eq!(log.orientation_conflicts, 0);
    assert!(validate(&fixed, &Tolerances::default()).is_clean());
}

#[test]
fn three_triangles_on_one_edge_make_a_non_manifold_edge_that_repair_leaves() {
    let v = vec![
        p(0.0, 0.0, 0.0),
        p(10.0, 0.0, 0.0),
        p(5.0, 8.0, 0.0),
        p(5.0, -8.0, 0.0),
        p(5.0, 0.0, 8.0),
    ];
    let s = surface(v, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    let r = validate(&s, &Tolerances::default());
    let f: Vec<_> = r.of_kind(FindingKind::NonManifoldEdge).collect();
    assert_eq!(f.len(), 1);
    assert_eq!(f[0].vertices, vec![0, 1]);
    assert_eq!(f[0].triangles, vec![0, 1, 2]);
    let (_, log) = repair(&s, &r, &Tolerances::default());
    assert_eq!(log.not_repaired.get("non_manifold_edge"), Some(&1));
}

#[test]
fn overlapping_coplanar_triangles_are_found_exactly() {
    let v = vec![
        p(0.0, 0.0, 0.0),
        p(10.0, 0.0, 0.0),
        p(0.0, 10.0, 0.0),
        p(2.0, 2.0, 0.0),
        p(12.0, 2.0, 0.0),
        p(2.0, 12.0, 0.0),
    ];
    let s = surface(v, vec![[0, 1, 2], [3, 4, 5]]);
    let r = validate(&s, &Tolerances::default());
    assert_eq!(
        r.of_kind(FindingKind::CoplanarOverlap).count(),
        1,
        "{}",
        r.render_text()
    );
    assert_eq!(r.of_kind(FindingKind::SelfIntersection).count(), 0);
}

#[test]
fn a_fold_over_a_shared_edge_is_a_coplanar_overlap() {
    let v = vec![
        p(0.0, 0.0, 0.0),
        p(10.0, 0.0, 0.0),
        p(0.0, 10.0, 0.0),
        p(5.0, 10.0, 0.0),
    ];
    let s = surface(v, vec![[0, 1, 2], [1, 0, 3]]);
    assert_eq!(count(&s, FindingKind::CoplanarOverlap), 1);
}

#[test]
fn crossing_triangles_are_a_self_intersection_and_a_lift_of_one_micron_clears_it() {
    let mk = |dz: f64| {
        let v = vec![
            p(0.0, 0.0, 0.0),
            p(10.0, 0.0, 0.0),
            p(0.0, 10.0, 0.0),
            p(2.0, 2.0, -5.0 + dz),
            p(3.0, 3.0, 5.0 + dz),
            p(2.0, 4.0, 5.0 + dz),
        ];
        surface(v, vec![[0, 1, 2], [3, 4, 5]])
    };
    let r = validate(&mk(0.0), &Tolerances::default());
    let f: Vec<_> = r.of_kind(FindingKind::SelfIntersection).collect();
    assert_eq!(f.len(), 1);
    assert_eq!(f[0].triangles, vec![0, 1]);
    assert_eq!(f[0].points.len(), 6);
    assert_eq!(count(&mk(5.000001), FindingKind::SelfIntersection), 0);
}

#[test]
fn what_repair_leaves_is_found_again_on_the_repaired_surface_and_said_in_one_line() {
    // Triangle 0 and triangle 2 share an edge through a duplicate of vertex 1 (6); triangle 1
    // crosses triangle 0.
    let v = vec![
        p(0.0, 0.0, 0.0),
        p(10.0, 0.0, 0.0),
        p(0.0, 10.0, 0.0),
        p(2.0, 2.0, -5.0),
        p(3.0, 3.0, 5.0),
        p(2.0, 4.0, 5.0),
        p(10.0, 0.0, 0.0),
        p(10.0, 10.0, 0.0),
    ];
    let s = surface(v, vec![[0, 1, 2], [3, 4, 5], [2, 6, 7]]);
    let tol = Tolerances::default();
    let found = validate(&s, &tol);
    let (fixed, _) = repair(&s, &found, &tol);
    let left = validate(&fixed, &tol);
    assert_eq!(left.findings.len(), 1, "{}", left.render_text());
    assert_eq!(left.findings[0].kind, FindingKind::SelfIntersection);
    assert_eq!(
        left.findings[0].lines,
        vec![100, 101],
        "the source lines are kept"
    );
    let repaired = repaired_counts(&found.counts(), &left.counts());
    assert_eq!(repaired["duplicate_vertex"], 1);
    assert_eq!(repaired.values().sum::<u64>(), 1);
    assert_eq!(
        repair_summary(&found.counts(), &left.counts()),
        "2 validation findings: 1 repaired (1 duplicate vertex), 1 remains (1 self-intersection)"
    );
    let none = std::collections::BTreeMap::new();
    assert_eq!(repair_summary(&none, &none), "clean");
    let mut only_fixed = found.counts();
    only_fixed.insert("self_intersection".into(), 0);
    assert_eq!(
        repair_summary(&only_fixed, &none),
        "1 validation finding: 1 repaired (1 duplicate vertex), none remain"
    );
    assert_eq!(
        repair_summary(&left.counts(), &left.counts()),
        "1 validation finding: none repaired, 1 remains (1 self-intersection)"
    );
}

#[test]
fn the_report_renders_text_counts_and_json_with_every_kind() {
    let (mut v, t) = grid();
    v.push(p(50.0, 50.0, 0.0));
    let r = validate(&surface(v, t), &Tolerances::default());
    let text = r.render_text();
    assert!(text.contains("unreferenced vertex x1"), "{text}");
    let c = r.counts();
    assert_eq!(c.len(), 8);
    assert_eq!(c["unreferenced_vertex"], 1);
    let j = r.to_json();
    assert_eq!(j["counts"]["unreferenced_vertex"], 1);
    assert_eq!(j["findings"][0]["kind"], "unreferenced_vertex");
    assert_eq!(j["clean"], false);
}

fn real(path: &str) -> Option<ImportedSurface> {
    let file = paths::shared(&format!("data/gocad/{path}"))?;
    let bytes = std::fs::read(file).expect("read");
    Some(import_surface(&bytes, path, &ImportOptions::default()).expect("imports"))
}

macro_rules! real_or_skip {
    ($p:expr) => {
        match real($p) {
            Some(s) => s,
            None => return,
        }
    };
}

#[test]
fn big_bear_has_two_zero_area_triangles_and_coincident_vertices() {
    let s = real_or_skip!(
        "SCECcode__CFM/CFM5_release_2017/obj/CFM5_all/ETRA-BBFS-1992-Big_Bear_rupture_fault-nw.ts"
    );
    let r = validate(&s, &Tolerances::default());
    let c = r.counts();
    assert_eq!(c["degenerate_triangle"], 2, "{}", r.render_text());
    assert!(c["duplicate_vertex"] >= 1, "{}", r.render_text());
    let (fixed, log) = repair(&s, &r, &Tolerances::default());
    assert_eq!(log.dropped_degenerate.len(), 2);
    let after = validate(&fixed, &Tolerances::default());
    assert_eq!(after.counts()["degenerate_triangle"], 0);
    assert_eq!(after.counts()["duplicate_vertex"], 0);
}

#[test]
fn potatochip_has_eleven_unused_vertices() {
    let s = real_or_skip!(
        "SCECcode__CFM/CFM5_release_2017/obj/CFM5_all/SAFS-SGPR-MTSJ-Potatochip1_blind_fault-CRNA-CFM5.ts"
    );
    let r = validate(&s, &Tolerances::default());
    assert_eq!(r.counts()["unreferenced_vertex"], 11, "{}", r.render_text());
    let (fixed, _) = repair(&s, &r, &Tolerances::default());
    assert_eq!(
        validate(&fixed, &Tolerances::default()).counts()["unreferenced_vertex"],
        0
    );
    assert_eq!(fixed.properties[0].len(), fixed.mesh.vertices.len());
}

#[test]
fn white_wolf_1000m_has_coincident_duplicate_vertices_that_repair_merges() {
    let s = real_or_skip!(
        "SCECcode__CFM/CFM5.3_4/ts/1000m/GVFA-WWFZ-MULT-White_Wolf_fault-CFM5_1000m.ts"
    );
    let r = validate(&s, &Tolerances::default());
    let dups: usize = r
        .of_kind(FindingKind::DuplicateVertex)
        .map(|f| f.vertices.len() - 1)
        .sum();
    assert_eq!(dups, 43, "{}", r.render_text());
    let (fixed, log) = repair(&s, &r, &Tolerances::default());
    assert_eq!(log.merged_vertices, 43);
    assert_eq!(fixed.mesh.vertices.len(), s.mesh.vertices.len() - 43);
}

#[test]
fn the_closed_kimberlite_pipe_is_clean() {
    let s = real_or_skip!("simpeg-research__Astic-2020-JointInversion/Geology_Surfaces/PK2.ts");
    let r = validate(&s, &Tolerances::default());
    assert!(r.is_clean(), "{}", r.render_text());
}

/// Duplicate-vertex findings of TSurf `object` of RINGMesh's `file`, each with its two file
/// lines, or `None` without `../shared`.
fn ringmesh_duplicates(file: &str, object: &str) -> Option<Vec<Vec<usize>>> {
    let path = paths::shared(&format!("data/gocad/ringmesh__RINGMesh/tests/data/{file}"))?;
    let bytes = std::fs::read(path).expect("read");
    let opts = ImportOptions {
        object: Some(gocad::import::ObjectRef::Name(object.into())),
        skip_other_types: true,
        ..ImportOptions::default()
    };
    let s = import_surface(&bytes, file, &opts).expect("imports");
    let r = validate(&s, &Tolerances::default());
    Some(
        (r.findings.iter())
            .filter(|f| f.kind == FindingKind::DuplicateVertex)
            .map(|f| f.lines.clone())
            .collect(),
    )
}

#[test]
fn cloudspins_non_conformal_cracks_are_found_with_their_file_lines_and_the_fixed_file_has_none() {
    // CloudSpin.ml's KOBE horizon is cracked along a line: its triangles on either side do
    // not share the vertices there (14 pairs at one place each). The fixed file has none.
    let Some(cracked) = ringmesh_duplicates("CloudSpin.ml", "KOBE") else {
        return;
    };
    assert_eq!(cracked.len(), 14);
    assert!(
        cracked
            .iter()
            .all(|lines| lines.len() == 2 && lines[0] < lines[1])
    );
    assert_eq!(cracked[0], [30731, 31010]);
    let fixed = ringmesh_duplicates("CloudSpin_fixed.ml", "KOBE").expect("beside it");
    assert!(fixed.is_empty(), "{fixed:?}");
}
