//! Property tests of `model::intersect` on random small meshes whose vertices sit on a coarse
//! integer lattice, so vertex-on-face, edge-in-face, shared vertices and coplanar pairs are
//! frequent. Checked: identical results in both argument orders, every curve point on both of
//! its triangles, the same contact set when the two meshes swap names (which swaps the roles of
//! `a` and `b` inside the algorithm), and no internal inconsistency ever.

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

/// The contact segments and touch points, with locations given as (on mesh 1, on mesh 2).
fn contact_set(
    x: &Intersection,
    mesh1_is_a: bool,
) -> (BTreeSet<Seg>, BTreeSet<(Location, Location)>) {
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

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

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
                prop_assert_eq!(contact_set(r, true), contact_set(s, false));
                prop_assert_eq!(r.curves.len(), s.curves.len());
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
