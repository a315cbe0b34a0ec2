//! Surfaces drawn onto each other vertex for vertex over part of their extent (a layer
//! collapsed to nothing where it pinches out): the common triangles are one interface, kept by
//! the surface whose name sorts first, and the curve runs where the two part.

use crate::intersect_support::{both, grid};
use geom::TriMesh;
use model::intersect::shared::unshare;
use model::intersect::{IntersectError, Location, PointKey, split};

/// A flat top on a 6 × 6 grid of unit cells.
fn top() -> TriMesh {
    grid(6, 6, |i, j| [i as f64, j as f64, 0.0])
}

/// A base drawn onto the top from column `from` on, and deepening by one per column west of it.
fn base(from: usize) -> TriMesh {
    grid(6, 6, |i, j| {
        [i as f64, j as f64, -(from.saturating_sub(i) as f64)]
    })
}

/// Every point of the curve is at column `i` (a vertex of both surfaces), in order along it.
fn runs_along_column(points: &[model::intersect::CurvePoint], i: f64) {
    let ys: Vec<f64> = points.iter().map(|p| p.xyz[1]).collect();
    assert!(points.iter().all(|p| p.xyz[0] == i && p.xyz[2] == 0.0));
    assert!(ys.windows(2).all(|w| (w[1] - w[0]).abs() == 1.0), "{ys:?}");
    assert!(
        points
            .iter()
            .all(|p| matches!(p.key, PointKey::VertexVertex { .. })
                && matches!((p.on_a, p.on_b), (Location::Vertex(_), Location::Vertex(_))))
    );
}

#[test]
fn two_surfaces_drawn_on_each_other_over_half_their_extent_meet_where_they_part() {
    let (t, b) = (top(), base(3));
    for (nt, nb) in [("top", "base"), ("a_top", "base")] {
        let x = both(nt, &t, nb, &b).expect("the common part is shared, not refused");
        assert_eq!(
            x.shared.len(),
            36,
            "three columns of two triangles, six rows"
        );
        let (first, second) = if nt < nb { (&t, &b) } else { (&b, &t) };
        for &(i, j) in &x.shared {
            let corners = |m: &TriMesh, k: u32| {
                let mut c = m.triangles[k as usize].map(|v| m.vertices[v as usize]);
                c.sort_by(|p, q| p.partial_cmp(q).unwrap());
                c
            };
            assert_eq!(corners(first, i), corners(second, j));
            assert!(corners(first, i).iter().all(|p| p[0] >= 3.0));
        }
        assert_eq!(x.curves.len(), 1, "one curve from border to border");
        let c = &x.curves[0];
        assert!(!c.closed);
        assert_eq!(c.points.len(), 7);
        runs_along_column(&c.points, 3.0);
    }
}

#[test]
fn a_surface_drops_what_it_shares_with_the_one_named_first_and_is_intersected_again() {
    let (t, b) = (top(), base(3));
    for (nt, nb) in [("top", "base"), ("a_top", "base")] {
        let x = both(nt, &t, nb, &b).unwrap();
        let surfaces = [(nt, &t), (nb, &b)];
        let u = unshare(&surfaces, std::slice::from_ref(&x))
            .unwrap()
            .expect("one surface drops the common part");
        let later = if nt < nb { 1 } else { 0 };
        assert!(u.meshes[1 - later].is_none(), "the first keeps its own");
        let (m, kept) = u.meshes[later].as_ref().unwrap();
        assert_eq!(m.triangles.len(), 36);
        assert!(kept.iter().all(|&k| !x.shared.iter().any(|s| s.1 == k)));
        let again = &u.intersections[0];
        assert!(again.shared.is_empty());
        assert_eq!(again.curves.len(), 1);
        assert_eq!(again.curves[0].points.len(), 7);
        runs_along_column(&again.curves[0].points, 3.0);
        let named: Vec<(&str, &TriMesh)> = vec![
            (nt, u.meshes[0].as_ref().map_or(&t, |(m, _)| m)),
            (nb, u.meshes[1].as_ref().map_or(&b, |(m, _)| m)),
        ];
        let s = split::split_model(&named, &u.intersections).expect("splits");
        assert_eq!(
            s[later].curve_edges.len(),
            6,
            "the kept part's border is the curve"
        );
    }
}

#[test]
fn three_surfaces_collapsed_onto_one_keep_the_common_part_once() {
    let (t, mid, low) = (top(), base(4), base(2));
    let x: Vec<_> = [
        ("a", &t, "b", &mid),
        ("a", &t, "c", &low),
        ("b", &mid, "c", &low),
    ]
    .into_iter()
    .map(|(na, a, nb, b)| both(na, a, nb, b).unwrap())
    .collect();
    let u = unshare(&[("a", &t), ("b", &mid), ("c", &low)], &x)
        .unwrap()
        .unwrap();
    assert!(u.meshes[0].is_none());
    let kept = |k: usize| u.meshes[k].as_ref().unwrap().0.triangles.len();
    assert_eq!(
        kept(1),
        72 - 2 * 2 * 6,
        "b keeps the four columns it does not share"
    );
    assert_eq!(
        kept(2),
        72 - 4 * 2 * 6,
        "c keeps the two columns west of its collapse"
    );
    assert!(u.intersections.iter().all(|x| x.shared.is_empty()));
}

#[test]
fn surfaces_with_nothing_in_common_are_left_as_they_are() {
    let t = top();
    let low = grid(6, 6, |i, j| [i as f64, j as f64, -1.0]);
    let x = both("a", &t, "b", &low).unwrap();
    assert!(x.shared.is_empty());
    assert!(unshare(&[("a", &t), ("b", &low)], &[x]).unwrap().is_none());
}

#[test]
fn surfaces_sharing_triangles_and_crossing_elsewhere_at_a_hairs_angle_are_refused() {
    // The base holds the top's triangles east of column 3; west of it, the same plane drawn
    // again with a millimetre of relief, crossing the top over and over.
    let t = top();
    let b = grid(6, 6, |i, j| {
        let bump = if (i + j) % 2 == 1 { 0.001 } else { -0.001 };
        [i as f64, j as f64, if i < 3 && i > 0 { bump } else { 0.0 }]
    });
    for (nt, nb) in [("top", "base"), ("a_top", "base")] {
        let e = both(nt, &t, nb, &b).expect_err("one part drawn twice");
        let IntersectError::Redrawn { shared, angle, .. } = &e else {
            panic!("{e}")
        };
        assert_eq!(*shared, 36);
        assert!(*angle < 1.0, "{angle}");
        assert!(
            e.to_string().contains("in common, and elsewhere cross"),
            "{e}"
        );
    }
}
