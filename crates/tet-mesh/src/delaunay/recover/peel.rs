//! A recovery hole with embedded triangles inside it, filled by peeling them off first. Neither
//! a cone (no point sees both sides of an embedded triangle) nor, often, the hole's own Delaunay
//! mesh can take such a hole: a fault triangle hinged on the hole's wall along two edges, its
//! third edge free inside the hole, is a fin no tetrahedralization of the hole's vertices need
//! have as a face. Peeling makes the fin part of the wall: a tet on one side of it, from its
//! corners to a vertex of the hole, is cut off, and what is left of the hole has the fin as a
//! face of its closed surface, which the Delaunay mesh or the cone then fills.
//!
//! Decisions and why:
//! - The tet must be positive (exact `orient3d`) and what is left must be a valid hole
//!   (`check_input`: closed, consistently oriented, no two triangles crossing, every embedded
//!   triangle left inside, all exact): then the tet lies inside the hole, since a tet poking out
//!   would cross the wall it pokes through.
//! - Apexes are tried best shape first (ties by index), embedded triangles in their order: the
//!   same mesh on every machine. At most `MAX_PEELED` triangles, each trying its `MAX_APEXES`
//!   best-shaped apexes.

use super::super::super::RegionInput;
use super::super::super::check::check_input;
use super::super::super::exact::orient3d;
use super::super::super::quality::mean_ratio;
use super::holes::Filled;
use super::{same_turn, sorted};
use geom::predicates::Orientation;

/// More embedded triangles than this in one hole are left to the other fillers.
const MAX_PEELED: usize = 8;
/// Apexes tried per triangle, best shape first: each costs a check of the whole hole, and a
/// widened hole has hundreds of vertices.
const MAX_APEXES: usize = 16;

/// The tets of `hole` (a recovery hole with embedded triangles): each embedded triangle cut off
/// with a tet of its own, then the rest filled by `fill` (no embedded triangle left in it).
pub(super) fn peel(
    hole: &RegionInput,
    fill: &dyn Fn(&RegionInput) -> Option<Filled>,
) -> Option<Filled> {
    if hole.embedded.is_empty() || hole.embedded.len() > MAX_PEELED {
        return None;
    }
    let mut rest = hole.clone();
    let mut tets = Vec::new();
    while !rest.embedded.is_empty() {
        let (tet, next) = (0..rest.embedded.len()).find_map(|k| peel_one(&rest, k))?;
        tets.push(tet);
        rest = next;
    }
    let (nodes, more) = fill(&rest)?;
    tets.extend(more);
    Some((nodes, tets))
}

/// Embedded triangle `k` of `hole` cut off by the best-shaped valid tet on either side: the tet
/// and the hole left.
fn peel_one(hole: &RegionInput, k: usize) -> Option<([u32; 4], RegionInput)> {
    let [a, b, c] = hole.embedded[k];
    let pts = &hole.vertices;
    let at = |v: u32| &pts[v as usize];
    // Each apex off the triangle's plane with the positive tet it makes.
    let mut apexes: Vec<(f64, [u32; 4])> = (0..pts.len() as u32)
        .filter(|x| ![a, b, c].contains(x))
        .filter_map(|x| {
            let tet = match orient3d(at(a), at(b), at(c), at(x)) {
                Orientation::Zero => return None,
                Orientation::Positive => [a, b, c, x],
                Orientation::Negative => [a, c, b, x],
            };
            let [p, q, r, s] = tet.map(at);
            Some((-mean_ratio(p, q, r, s).abs(), tet))
        })
        .collect();
    apexes.sort_by(|p, q| p.0.total_cmp(&q.0).then(p.1[3].cmp(&q.1[3])));
    apexes.into_iter().take(MAX_APEXES).find_map(|(_, tet)| {
        let rest = cut_off(hole, k, tet)?;
        check_input(&rest).ok()?;
        Some((tet, rest))
    })
}

/// The hole left when positive tet `tet` (holding embedded triangle `k` as a face) is cut off:
/// the wall faces it covers go, its other faces join the wall facing into it, the triangle
/// leaves the embedded ones. `None` where a face of the tet lies on the wall the wrong way.
fn cut_off(hole: &RegionInput, k: usize, tet: [u32; 4]) -> Option<RegionInput> {
    let [a, b, c, d] = tet;
    // The tet's faces with right-hand normals pointing out of it.
    let outward = [[a, c, b], [a, b, d], [b, c, d], [a, d, c]];
    let mut boundary = hole.boundary.clone();
    for f in outward {
        let key = sorted(f);
        match boundary.iter().position(|g| sorted(*g) == key) {
            Some(i) if same_turn(boundary[i], f) => {
                boundary.swap_remove(i);
            }
            Some(_) => return None,
            None => boundary.push([f[0], f[2], f[1]]),
        }
    }
    let mut embedded = hole.embedded.clone();
    embedded.remove(k);
    Some(RegionInput {
        boundary,
        embedded,
        ..hole.clone()
    })
}

#[cfg(test)]
mod tests {
    use super::super::kernel;
    use super::*;

    /// The octahedron with corners ±x (0, 1), ±y (2, 3), ±z (4, 5), faces outward, and the fin
    /// from +z to ±x inside it: hinged on two of its edges, its third edge through the centre.
    fn octahedron_with_fin() -> RegionInput {
        let (vertices, boundary) = test_support::shapes::octahedron();
        RegionInput {
            name: "octahedron".into(),
            vertices,
            boundary,
            embedded: vec![[4, 0, 1]],
            lines: vec![],
        }
    }

    #[test]
    fn a_fin_hinged_on_two_edges_of_a_hole_is_peeled_and_the_rest_coned() {
        let hole = octahedron_with_fin();
        check_input(&hole).expect("a valid hole");
        let cone = |h: &RegionInput| {
            let (apex, tets) = kernel::cone(&h.vertices, &h.boundary, &[])?;
            Some((vec![apex], tets))
        };
        let (nodes, tets) = peel(&hole, &cone).expect("peeled");
        let mut pts = hole.vertices.clone();
        pts.extend(nodes);
        let mut volume = 0.0;
        for t in &tets {
            let [a, b, c, d] = t.map(|v| &pts[v as usize]);
            assert_eq!(orient3d(a, b, c, d), Orientation::Positive, "{t:?}");
            volume += geom::predicates::signed_volume(a, b, c, d);
        }
        assert!((volume - 4.0 / 3.0).abs() < 1e-12, "{volume}");
        // The fin is a face of a tet on each side.
        let holding = tets
            .iter()
            .filter(|t| [4, 0, 1].iter().all(|v| t.contains(v)));
        assert_eq!(holding.count(), 2);
    }

    #[test]
    fn a_hole_without_embedded_triangles_is_not_peeled() {
        let hole = RegionInput {
            embedded: vec![],
            ..octahedron_with_fin()
        };
        assert!(peel(&hole, &|_| Some((Vec::new(), Vec::new()))).is_none());
    }
}
