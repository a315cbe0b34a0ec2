//! Triple points decided from provenance, not from rounded coordinates. Where a fault ends on
//! another fault inside a horizon face, the end of the first fault's curve (its border edge
//! crossing the horizon) lies exactly on the second fault's curve whenever that border edge
//! lies in the second fault's plane. The constructed coordinates cannot show it (they are
//! rounded), so it is decided here on input coordinates with exact `orient3d`, and the point
//! is then built the same way on all three surfaces: the border edge meeting the horizon's
//! plane. When the T point falls exactly on an edge of the horizon, it arrives twice on that
//! edge (from each fault) and the two are merged by the same exact test ([`t_on_edges`]).

use super::super::construct::point_xyz;
use super::super::key::{Location, PointKey};
use super::super::locate::is_degenerate;
use super::{Intersection, Pt, Side, find_mesh};
use geom::{Orientation, TriMesh, orient3d};
use std::collections::BTreeMap;

/// The edge of the partner surface that a chord runs along, from the partner locations of its
/// two ends: two vertices, an edge and one of its vertices, or one edge twice.
pub(super) fn partner_edge(ends: [Location; 2]) -> Option<(u32, u32)> {
    use Location::*;
    let e = match ends {
        [Vertex(a), Vertex(b)] if a != b => (a.min(b), a.max(b)),
        [Edge(i, j), Vertex(a)] | [Vertex(a), Edge(i, j)] if a == i || a == j => (i, j),
        [Edge(i, j), Edge(k, l)] if (i, j) == (k, l) => (i, j),
        _ => return None,
    };
    Some(e)
}

/// The points of `q` at `at` (a vertex, or every point of an edge) lie in the plane of the
/// non-degenerate triangle `plane` (exact). `false` for a face location, a bad index or a
/// degenerate plane.
pub(super) fn lies_in_plane(q: &TriMesh, at: Location, plane: &[[f64; 3]; 3]) -> bool {
    if is_degenerate(plane) {
        return false;
    }
    let on = |v: u32| {
        q.vertices
            .get(v as usize)
            .is_some_and(|p| orient3d(&plane[0], &plane[1], &plane[2], p) == Orientation::Zero)
    };
    match at {
        Location::Vertex(v) => on(v),
        Location::Edge(i, j) => on(i) && on(j),
        Location::Face(_) => false,
    }
}

/// The lines of edge `s` of surface `p` and edge `e` of surface `q` lie in one plane (exact);
/// `false` on a bad index. Where `s` crosses a face holding `e`, they then meet at one point.
pub(super) fn edges_coplanar(p: &TriMesh, s: (u32, u32), q: &TriMesh, e: (u32, u32)) -> bool {
    let v = |m: &TriMesh, i: u32| m.vertices.get(i as usize).copied();
    match (v(p, s.0), v(p, s.1), v(q, e.0), v(q, e.1)) {
        (Some(a), Some(b), Some(c), Some(d)) => orient3d(&a, &b, &c, &d) == Orientation::Zero,
        _ => false,
    }
}

/// Where edge `s` of surface `sn` meets edge `e` of surface `gn`, built exactly as `intersect`
/// builds that edge-edge point (from the surface whose name sorts first), so the bits agree
/// with the curve point the two surfaces' own intersection carries. `None` on a bad index.
pub(super) fn edge_edge_xyz(
    sn: &str,
    sm: &TriMesh,
    s: (u32, u32),
    gn: &str,
    gm: &TriMesh,
    e: (u32, u32),
) -> Option<[f64; 3]> {
    let ok = |m: &TriMesh, e: (u32, u32)| e.0.max(e.1) < m.vertices.len() as u32;
    if !ok(sm, s) || !ok(gm, e) {
        return None;
    }
    let (ls, le) = (Location::edge(s.0, s.1), Location::edge(e.0, e.1));
    let x = if sn < gn {
        point_xyz(&PointKey::new(ls, le)?, sm, gm)
    } else {
        point_xyz(&PointKey::new(le, ls)?, gm, sm)
    };
    x.iter().all(|c| c.is_finite()).then_some(x)
}

/// A curve of this surface running along edge `.1` of the other surface of intersection `.0`.
type AlongEdge = (usize, (u32, u32));

/// A fault ending on another exactly where they cross an edge of a third surface (this one):
/// the point comes twice, from the fault that ends (its border edge or vertex meets this edge)
/// and from the other (its face meets this edge). When that border lies in the other fault's
/// plane (exact), the two are one point and take the first one's coordinates. Conversely, a
/// point where another surface's edge crosses a face of this one lies on this surface's curve
/// along a third surface's border edge when the two edges are coplanar (exact): it takes their
/// edge-edge construction, the bits the third surface has.
pub(super) fn t_on_edges(
    pts: &mut [Pt],
    partner: &[&str],
    others: &[(&str, &TriMesh)],
    intersections: &[(&Intersection, Side)],
) {
    let mesh_of = |ix: usize| partner.get(ix).and_then(|n| find_mesh(others, n));
    let corners = |m: &TriMesh, f: u32| -> Option<[[f64; 3]; 3]> {
        let t = m.triangles.get(f as usize)?;
        let c = |k: usize| m.vertices.get(t[k] as usize).copied();
        Some([c(0)?, c(1)?, c(2)?])
    };
    let mut by_edge: BTreeMap<Location, Vec<usize>> = BTreeMap::new();
    for (i, p) in pts.iter().enumerate() {
        if matches!(p.loc, Location::Edge(..)) {
            by_edge.entry(p.loc).or_default().push(i);
        }
    }
    for list in by_edge.values() {
        for &q in list {
            let (Location::Face(f), Some(fm)) = (pts[q].oloc, mesh_of(pts[q].ix)) else {
                continue;
            };
            let Some(plane) = corners(fm, f) else {
                continue;
            };
            let found = list
                .iter()
                .copied()
                .filter(|&p| pts[p].ix != pts[q].ix && !matches!(pts[p].oloc, Location::Face(_)))
                .filter(|&p| {
                    mesh_of(pts[p].ix).is_some_and(|gm| lies_in_plane(gm, pts[p].oloc, &plane))
                })
                .min_by_key(|&p| (partner[pts[p].ix], pts[p].key));
            if let Some(p) = found {
                pts[q].xyz = pts[p].xyz;
            }
        }
    }
    // Curves of this surface along another surface's edge, per face of this surface.
    let mut along: BTreeMap<u32, Vec<AlongEdge>> = BTreeMap::new();
    for (ix, &(x, side)) in intersections.iter().enumerate() {
        for c in &x.curves {
            let n = c.points.len();
            for (s, &(ta, tb)) in c.segments_faces.iter().enumerate() {
                let (Some(p), Some(q)) = (c.points.get(s), c.points.get((s + 1) % n.max(1))) else {
                    continue;
                };
                let (t, ends) = if side == Side::A {
                    (ta, [p.on_b, q.on_b])
                } else {
                    (tb, [p.on_a, q.on_a])
                };
                if let Some(e) = partner_edge(ends) {
                    along.entry(t).or_default().push((ix, e));
                }
            }
        }
    }
    for p in pts.iter_mut() {
        let (Location::Face(t), Location::Edge(i, j)) = (p.loc, p.oloc) else {
            continue;
        };
        let (Some(sm), Some(list)) = (mesh_of(p.ix), along.get(&t)) else {
            continue;
        };
        let found = list
            .iter()
            .filter(|&&(ix, _)| ix != p.ix)
            .filter_map(|&(ix, e)| Some((partner[ix], mesh_of(ix)?, e)))
            .filter(|&(_, gm, e)| edges_coplanar(sm, (i, j), gm, e))
            .min_by_key(|&(gn, _, e)| (gn, e));
        if let Some((gn, gm, e)) = found
            && let Some(x) = edge_edge_xyz(partner[p.ix], sm, (i, j), gn, gm, e)
        {
            p.xyz = x;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chord_between_two_ends_of_one_partner_edge_runs_along_it() {
        use Location::*;
        assert_eq!(partner_edge([Vertex(7), Vertex(3)]), Some((3, 7)));
        assert_eq!(partner_edge([Edge(3, 7), Vertex(7)]), Some((3, 7)));
        assert_eq!(partner_edge([Edge(3, 7), Edge(3, 7)]), Some((3, 7)));
        assert_eq!(partner_edge([Edge(3, 7), Vertex(8)]), None);
        assert_eq!(partner_edge([Face(1), Vertex(8)]), None);
    }

    #[test]
    fn an_edge_in_a_plane_is_found_exactly_and_a_degenerate_plane_never_holds_it() {
        let q = TriMesh::new(
            vec![
                [500_104.25, 7_000_010.0, -160.0],
                [500_104.25, 7_000_010.0, -40.0],
                [500_104.26, 7_000_010.0, -40.0],
            ],
            vec![[0, 1, 2]],
        );
        let wall = [
            [500_104.25, 6_999_000.0, -500.0],
            [500_104.25, 7_001_000.0, -500.0],
            [500_104.25, 7_000_000.0, 500.0],
        ];
        assert!(lies_in_plane(&q, Location::Edge(0, 1), &wall));
        assert!(!lies_in_plane(&q, Location::Edge(1, 2), &wall));
        let flat = [wall[0], wall[1], wall[1]];
        assert!(!lies_in_plane(&q, Location::Vertex(0), &flat));
    }
}
