//! Splitting one surface along the curves of several intersections: curves crossing inside a
//! face meet at one new vertex, bit-identical on the three surfaces it belongs to; the patches
//! between the curves; and errors for intersections that do not involve the surface.

use crate::intersect_support;

use geom::TriMesh;
use intersect_support::{assert_sound, both, grid};
use model::intersect::Intersection;
use model::intersect::split::{Side, SplitError, split_all, split_all_with};
use model::patches::patches;

/// A gently tilted horizon and two vertical walls, one across x and one across y, placed so
/// that the walls' curves on the horizon cross inside a face (not on an edge).
fn three() -> (TriMesh, TriMesh, TriMesh) {
    let h = grid(8, 8, |i, j| {
        [
            500_000.0 + 10.0 * i as f64,
            7_000_000.0 + 10.0 * j as f64,
            -100.0 + 0.3 * i as f64 + 0.2 * j as f64,
        ]
    });
    let wx = grid(4, 2, |i, k| {
        let y = 6_999_990.0 + 25.0 * i as f64;
        [
            500_043.3 + 0.05 * (y - 7_000_000.0),
            y,
            -130.0 + 60.0 * k as f64,
        ]
    });
    let wy = grid(4, 2, |i, k| {
        let x = 499_990.0 + 25.0 * i as f64;
        [
            x,
            7_000_036.7 + 0.03 * (x - 500_000.0),
            -130.0 + 60.0 * k as f64,
        ]
    });
    (h, wx, wy)
}

fn sides<'a>(name: &str, xs: &'a [Intersection]) -> Vec<(&'a Intersection, Side)> {
    xs.iter()
        .filter_map(|x| match (x.a == name, x.b == name) {
            (true, _) => Some((x, Side::A)),
            (_, true) => Some((x, Side::B)),
            _ => None,
        })
        .collect()
}

#[test]
fn two_walls_crossing_on_a_horizon_meet_at_one_vertex_shared_by_all_three_surfaces() {
    let (h, wx, wy) = three();
    let xs = vec![
        both("h", &h, "wx", &wx).expect("meets"),
        both("h", &h, "wy", &wy).expect("meets"),
        both("wx", &wx, "wy", &wy).expect("meets"),
    ];
    assert!(xs.iter().all(|x| x.curves.len() == 1));
    let all = [("h", &h), ("wx", &wx), ("wy", &wy)];
    let others: Vec<(&str, &TriMesh)> = all.to_vec();
    let mut at = Vec::new();
    for (name, mesh) in all {
        let s = split_all_with(name, mesh, &sides(name, &xs), &others).expect("splits");
        assert_sound(mesh, &s);
        assert_eq!(s.crossings.len(), 1, "{name}: one crossing");
        let v = s.crossings[0];
        // The crossing splits both curves: four curve edges end at it.
        let n = s.curve_edges.iter().filter(|e| e.contains(&v)).count();
        assert_eq!(n, 4, "{name}: four curve pieces at the crossing");
        at.push(s.mesh.vertices[v as usize]);
        if name == "h" {
            let p = patches(name, &s);
            assert_eq!(p.len(), 4, "two crossing curves cut the horizon in four");
            let names: Vec<&str> = p.iter().map(|p| p.name.as_str()).collect();
            assert_eq!(names, ["h#1", "h#2", "h#3", "h#4"]);
            let total: usize = p.iter().map(|p| p.triangles.len()).sum();
            assert_eq!(total, s.mesh.triangles.len());
        }
    }
    let bits = |p: [f64; 3]| p.map(f64::to_bits);
    assert_eq!(
        bits(at[0]),
        bits(at[1]),
        "h and wx share the crossing bit for bit"
    );
    assert_eq!(
        bits(at[0]),
        bits(at[2]),
        "h and wy share the crossing bit for bit"
    );
}

#[test]
fn patch_order_does_not_depend_on_the_order_of_the_intersections() {
    let (h, wx, wy) = three();
    let xs = [
        both("h", &h, "wx", &wx).expect("meets"),
        both("h", &h, "wy", &wy).expect("meets"),
    ];
    let fwd = split_all("h", &h, &[(&xs[0], Side::A), (&xs[1], Side::A)]).expect("splits");
    let rev = split_all("h", &h, &[(&xs[1], Side::A), (&xs[0], Side::A)]).expect("splits");
    let key = |s| {
        patches("h", s)
            .into_iter()
            .map(|p| (p.name, p.mesh))
            .collect::<Vec<_>>()
    };
    assert_eq!(key(&fwd), key(&rev));
}

#[test]
fn an_intersection_of_other_surfaces_is_refused_by_name() {
    let (h, wx, wy) = three();
    let x = both("wx", &wx, "wy", &wy).expect("meets");
    let e = split_all("h", &h, &[(&x, Side::A)]).expect_err("h is not wx");
    assert!(matches!(e, SplitError::WrongSurface { .. }), "{e}");
    assert!(e.to_string().contains("`h`"), "{e}");
}

#[test]
fn a_curve_pointing_at_a_missing_triangle_is_an_error_not_a_panic() {
    let (h, wx, _) = three();
    let mut x = both("h", &h, "wx", &wx).expect("meets");
    for f in &mut x.curves[0].segments_faces {
        f.0 = 9999;
    }
    let e = split_all("h", &h, &[(&x, Side::A)]).expect_err("bad triangle");
    assert!(matches!(e, SplitError::BadIndex { index: 9999, .. }), "{e}");
}

#[test]
fn a_fault_ending_inside_a_face_after_crossing_another_curve_there_is_joined() {
    // One coarse horizon cell (two triangles of 100 m); a through-going wall near x = 40 and a
    // wall near y = 30 that stops at x = 70, inside the lower triangle, after crossing it.
    let h = grid(1, 1, |i, j| {
        [
            500_000.0 + 100.0 * i as f64,
            7_000_000.0 + 100.0 * j as f64,
            -50.0 + 3.0 * i as f64 + 2.0 * j as f64,
        ]
    });
    let wx = grid(1, 1, |i, k| {
        let y = 6_999_990.0 + 120.0 * i as f64;
        [
            500_040.3 + 0.01 * (y - 7_000_000.0),
            y,
            -90.0 + 80.0 * k as f64,
        ]
    });
    let wy = grid(1, 1, |i, k| {
        let x = 499_990.0 + 80.3 * i as f64;
        [
            x,
            7_000_030.7 + 0.02 * (x - 500_000.0),
            -90.0 + 80.0 * k as f64,
        ]
    });
    let xs = [
        both("h", &h, "wx", &wx).expect("meets"),
        both("h", &h, "wy", &wy).expect("meets"),
    ];
    let s = split_all("h", &h, &[(&xs[0], Side::A), (&xs[1], Side::A)]).expect("joined");
    assert_sound(&h, &s);
    assert_eq!(s.crossings.len(), 1);
    // West of the through wall, the other wall runs border to crossing and cuts that side in
    // two; east of it, the wall dangles and cuts nothing: three patches.
    assert_eq!(patches("h", &s).len(), 3);
}
