//! The first splitting step: inserting one intersection's curves into each of its surfaces;
//! every result is checked for conformity, topology, area, orientation and curve edges.

use crate::intersect_support;

use geom::TriMesh;
use intersect_support::{assert_sound, both, grid};
use model::intersect::split::{Side, split};

#[test]
fn a_horizon_and_a_fault_reaching_beyond_it_are_both_split_along_their_curve() {
    let a = grid(10, 10, |i, j| {
        [
            500_000.0 + 2.0 * i as f64,
            7_000_000.0 + 2.0 * j as f64,
            0.1 * (i as f64).sin(),
        ]
    });
    let b = grid(6, 4, |i, k| {
        let y = 7_000_000.0 - 1.0 + 4.0 * i as f64;
        [
            500_007.3 + 0.2 * (y - 7_000_000.0) + 0.3 * k as f64,
            y,
            -3.0 + 1.5 * k as f64,
        ]
    });
    let x = both("a", &a, "b", &b).expect("no coplanar contact");
    assert_eq!(x.curves.len(), 1);
    let sa = split(&a, &x, Side::A).expect("a splits");
    assert_sound(&a, &sa);
    let n = x.curves[0].points.len();
    assert_eq!(sa.curve_edges.len(), n - 1);
    // The fault reaches beyond the horizon, so on the fault the curve ends inside faces.
    let sb = split(&b, &x, Side::B).expect("dangling ends are joined");
    assert_sound(&b, &sb);
    assert_eq!(sb.curve_edges.len(), n - 1);
    assert!(sa.mesh.triangles.len() > a.triangles.len());
}

#[test]
fn a_bump_and_a_plane_are_split_along_their_closed_loop() {
    let bump = grid(16, 16, |i, j| {
        let (x, y) = (-3.0 + 0.375 * i as f64, -3.0 + 0.375 * j as f64);
        [x, y, 2.0 * (-(x * x + y * y)).exp() - 1.0 + 0.013]
    });
    let plane = grid(5, 5, |i, j| {
        [-5.0 + 2.0 * i as f64, -5.0 + 2.0 * j as f64, 0.0]
    });
    let x = both("bump", &bump, "plane", &plane).expect("no coplanar contact");
    assert!(x.curves.len() == 1 && x.curves[0].closed);
    let sa = split(&bump, &x, Side::A).expect("bump splits");
    let sb = split(&plane, &x, Side::B).expect("plane splits");
    assert_sound(&bump, &sa);
    assert_sound(&plane, &sb);
    assert_eq!(sb.curve_edges.len(), x.curves[0].points.len());
}

#[test]
fn a_curve_ending_inside_faces_is_joined_to_a_corner_and_stays_a_chain_of_edges() {
    let a = grid(4, 4, |i, j| [i as f64 * 2.0, j as f64 * 2.0, 0.0]);
    let b = TriMesh::new(
        vec![
            [2.5, 2.9, -1.0],
            [5.5, 3.1, -1.0],
            [5.5, 3.1, 1.0],
            [2.5, 2.9, 1.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let x = both("a", &a, "b", &b).expect("no coplanar contact");
    assert_eq!(x.curves.len(), 1);
    let sa = split(&a, &x, Side::A).expect("a splits");
    assert_sound(&a, &sa);
    assert_eq!(sa.curve_edges.len(), x.curves[0].segments_faces.len());
    assert_sound(
        &b,
        &split(&b, &x, Side::B).expect("b conforms: the curve runs across it"),
    );
}

#[test]
fn a_curve_lying_inside_a_single_face_is_inserted_as_a_chain_of_edges() {
    let a = grid(2, 2, |i, j| [i as f64 * 10.0, j as f64 * 10.0, 0.0]);
    let b = TriMesh::new(
        vec![
            [6.0, 2.0, -1.0],
            [7.0, 2.5, -1.0],
            [7.0, 2.5, 1.0],
            [6.0, 2.0, 1.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let x = both("a", &a, "b", &b).expect("no coplanar contact");
    assert_eq!(x.curves.len(), 1);
    let sa = split(&a, &x, Side::A)
        .unwrap_or_else(|e| panic!("the curve lies inside one face of a: {e}"));
    assert_sound(&a, &sa);
    assert_eq!(sa.curve_edges.len(), x.curves[0].segments_faces.len());
    let in_face_0 = sa.parent.iter().filter(|&&p| p == 0).count();
    assert_eq!(
        in_face_0, 7,
        "three curve points inside face 0 make seven triangles of it"
    );
}

/// A box side is two triangles; a horizon crossing it puts hundreds of curve points on them.
#[test]
fn a_box_side_crossed_by_a_long_horizon_curve_is_split_soundly() {
    use geom::BBox;
    use model::intersect::box_sides;
    let horizon = grid(300, 300, |i, j| {
        let (x, y) = (499_990.0 + 1.25 * i as f64, 6_999_990.0 + 1.25 * j as f64);
        [
            x,
            y,
            4.0 * ((x - 500_000.0) / 13.0).sin() * ((y - 7_000_000.0) / 29.0).cos(),
        ]
    });
    let b = BBox {
        min: [500_000.0, 7_000_000.0, -50.0],
        max: [500_300.0, 7_000_300.0, 50.0],
    };
    let (name, side) = box_sides(&b).swap_remove(2); // box.ymin
    assert_eq!(name, "box.ymin");
    let x = both("top", &horizon, &name, &side).expect("no coplanar contact");
    assert_eq!(x.curves.len(), 1);
    assert!(
        x.curves[0].points.len() > 200,
        "{}",
        x.curves[0].points.len()
    );
    let (s_box, s_top) = (
        split(&side, &x, Side::A).expect("box side splits"),
        split(&horizon, &x, Side::B).expect("top splits"),
    );
    assert_sound(&side, &s_box);
    assert_sound(&horizon, &s_top);
}
