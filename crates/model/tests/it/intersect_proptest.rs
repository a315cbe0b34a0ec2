//! Property tests of `model::intersect` on random small meshes whose vertices sit on a coarse
//! integer lattice, so vertex-on-face, edge-in-face, shared vertices and coplanar pairs are
//! frequent. Checked: identical results in both argument orders, every curve point on both of
//! its triangles, the same contact set when the two meshes swap names (which swaps the roles of
//! `a` and `b` inside the algorithm), and no internal inconsistency ever.
//!
//! A triangle both meshes hold is kept by the mesh whose name sorts first, so where the common
//! part reaches the border of one mesh, a curve along that border exists only when that mesh
//! keeps the triangle: segments along the edges of common triangles are compared apart.
//!
//! The seed is fixed (`test_support::proptest_config`), so every run tries the same cases.

use crate::intersect_support;

use geom::TriMesh;
use intersect_support::{assert_sound, both, grid};
use model::intersect::split::{Side, split};
use model::intersect::{IntersectError, Intersection, Location, SurfaceRef, intersect};
use proptest::prelude::*;
use std::collections::BTreeSet;

fn horizon(z: &[i8]) -> TriMesh {
    grid(3, 3, |i, j| {
        [i as f64, j as f64, f64::from(z[j * 4 + i]) * 0.5]
    })
}

fn fault(x: &[i8], dy: i8) -> TriMesh {
    grid(3, 3, |i, k| {
        [
            f64::from(x[k * 4 + i]) * 0.5,
            i as f64 + f64::from(dy) * 0.5,
            k as f64 - 1.5,
        ]
    })
}

type Seg = BTreeSet<(Location, Location)>;
type Contacts = (BTreeSet<Seg>, BTreeSet<(Location, Location)>);

/// The contact segments and touch points, with locations given as (on mesh 1, on mesh 2).
fn contact_set(x: &Intersection, mesh1_is_a: bool) -> Contacts {
    let orient = |a: Location, b: Location| if mesh1_is_a { (a, b) } else { (b, a) };
    let mut segs = BTreeSet::new();
    for c in &x.curves {
        let n = c.points.len();
        for s in 0..c.segments_faces.len() {
            let (p, q) = (&c.points[s], &c.points[(s + 1) % n]);
            segs.insert(
                [orient(p.on_a, p.on_b), orient(q.on_a, q.on_b)]
                    .into_iter()
                    .collect(),
            );
        }
    }
    let touches = x.touches.iter().map(|p| orient(p.on_a, p.on_b)).collect();
    (segs, touches)
}

/// The pairs of common triangles as (triangle of mesh 1, triangle of mesh 2), sorted.
fn shared_pairs(x: &Intersection, mesh1_is_a: bool) -> Vec<(u32, u32)> {
    let mut s: Vec<(u32, u32)> = (x.shared.iter())
        .map(|&(i, j)| if mesh1_is_a { (i, j) } else { (j, i) })
        .collect();
    s.sort_unstable();
    s
}

/// Whether both ends of `seg` are corners of one common triangle of mesh 1 (`shared` as
/// [`shared_pairs`] gives it): the segment runs along that triangle's edge.
fn along_shared(seg: &Seg, m1: &TriMesh, shared: &[(u32, u32)]) -> bool {
    shared.iter().any(|&(t, _)| {
        let corners = m1.triangles[t as usize];
        seg.iter()
            .all(|(l, _)| matches!(l, Location::Vertex(v) if corners.contains(v)))
    })
}

/// `r` (mesh 1 named first) and `s` (mesh 2 named first) agree: the same common triangles, the
/// same touches, and the same segments apart from those along common triangles' edges.
fn agree_when_names_swap(m1: &TriMesh, r: &Intersection, s: &Intersection) -> Result<(), String> {
    let shared = shared_pairs(r, true);
    if shared != shared_pairs(s, false) {
        return Err(format!(
            "common triangles differ: {shared:?} / {:?}",
            shared_pairs(s, false)
        ));
    }
    let away = |c: Contacts| -> Contacts {
        let segs =
            c.0.into_iter()
                .filter(|g| !along_shared(g, m1, &shared))
                .collect();
        (segs, c.1)
    };
    let (cr, cs) = (away(contact_set(r, true)), away(contact_set(s, false)));
    if cr != cs {
        return Err(format!("contacts differ:\n{cr:?}\n{cs:?}"));
    }
    if shared.is_empty() && r.curves.len() != s.curves.len() {
        return Err(format!("{} curves / {}", r.curves.len(), s.curves.len()));
    }
    Ok(())
}

proptest! {
    #![proptest_config(test_support::proptest_config(300))]

    #[test]
    fn random_lattice_meshes_intersect_consistently_whatever_the_order_and_the_names(
        z in proptest::collection::vec(-2i8..=2, 16),
        x in proptest::collection::vec(0i8..=6, 16),
        dy in -2i8..=2,
    ) {
        let m1 = horizon(&z);
        let m2 = fault(&x, dy);
        let r = both("m1", &m1, "m2", &m2);
        let swapped = intersect(SurfaceRef { name: "m1", mesh: &m2 }, SurfaceRef { name: "m2", mesh: &m1 });
        match (&r, &swapped) {
            (Ok(r), Ok(s)) => {
                if let Err(e) = agree_when_names_swap(&m1, r, s) {
                    prop_assert!(false, "{}", e);
                }
                // Whenever splitting succeeds, the result is sound.
                if let Ok(sa) = split(&m1, r, Side::A) {
                    assert_sound(&m1, &sa);
                }
                if let Ok(sb) = split(&m2, r, Side::B) {
                    assert_sound(&m2, &sb);
                }
            }
            (Err(IntersectError::Coplanar { contacts: c1, .. }), Err(IntersectError::Coplanar { contacts: c2, .. })) => {
                let p1: BTreeSet<(u32, u32)> = c1.iter().map(|c| (c.tri_a, c.tri_b)).collect();
                let p2: BTreeSet<(u32, u32)> = c2.iter().map(|c| (c.tri_b, c.tri_a)).collect();
                prop_assert_eq!(p1, p2);
            }
            (a, b) => prop_assert!(false, "outcomes differ or failed: {:?} / {:?}", a.as_ref().err(), b.as_ref().err()),
        }
    }
}

/// A triangle both meshes hold, one of its edges on mesh 2's border: mesh 2 stops there while
/// mesh 1 goes on, a curve only when mesh 2 keeps the triangle (named first).
#[test]
fn a_triangle_both_meshes_hold_parts_them_alike_whichever_name_sorts_first() {
    let z = [0, 0, 0, 0, -1, 0, 0, 0, 1, -1, 0, 0, 0, 0, 0, 0];
    let x = [0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0];
    let (m1, m2) = (horizon(&z), fault(&x, -2));
    let r = both("m1", &m1, "m2", &m2).expect("mesh 1 named first");
    let s = both("m2", &m1, "m1", &m2).expect("mesh 2 named first");
    assert_eq!(shared_pairs(&r, true), vec![(7, 10)]);
    agree_when_names_swap(&m1, &r, &s).unwrap();
    let border: Seg = [
        (Location::Vertex(8), Location::Vertex(11)),
        (Location::Vertex(9), Location::Vertex(7)),
    ]
    .into_iter()
    .collect();
    assert!(!contact_set(&r, true).0.contains(&border));
    assert!(contact_set(&s, false).0.contains(&border));
}
