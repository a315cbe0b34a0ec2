//! The given points (isolated nodes, where wells cross the patch): whether each stays clear of the
//! loops and constraints, and the local size the mesh is graded from around it.
//!
//! A point on a loop or constraint segment, away from the segment's nodes, cannot be an isolated
//! node: the segment must stay one mesh edge. It is decided exactly in the flattening (`orient2d`
//! zero, within the segment's box), and also within `tol` × the point's local size in 3D (the
//! distance at which a given node counts as lying on the support), because a point computed on a
//! segment in 3D may round to either side of it in the plane. Likewise a point within that
//! distance of another given node, without being bit-identical to it, is refused: the two would
//! be one node for every purpose but the tet mesher's. Whether a point lies inside the patch at
//! all is decided exactly by the triangulation's inside labelling (`triangulate_given`).
//!
//! Sizes: a point has no segment; its local size is the target size clamped to [min, max] (as
//! `given_sizes` sets it), lowered to the distance to the nearest other given node. So two points
//! closer than the target size, or a point near a loop node, get a mesh graded down to their
//! spacing instead of needles between them. A point closer to a loop or constraint segment than
//! about half the segment's length still makes a flat triangle with it: the segment must stay
//! one edge, and the point is the apex nearest to it.

use super::input::GivenNodes;
use super::{PatchInput, SurfaceMeshError, fail};
use geom::predicates::{dist, dot, sub};
use geom::{Orientation, orient2d};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};

/// Checks the points of `given` (nodes from `first_point` on) against the loop and constraint
/// segments `segs` and the other given nodes (see the module doc); returns the local sizes of all
/// given nodes for the size field: `hloc`, with each point's lowered to its nearest other node.
pub fn check_points(
    input: &PatchInput,
    given: &GivenNodes,
    uv: &[[f64; 2]],
    segs: &[(u32, u32)],
    tol: f64,
    hloc: &[f64],
) -> Result<Vec<f64>, SurfaceMeshError> {
    let mut hfield = hloc.to_vec();
    let ng = given.nodes.len();
    if given.first_point == ng {
        return Ok(hfield);
    }
    let nodes = &given.nodes;
    let origin = nodes[0];
    let rel = |p: &[f64; 3]| [p[0] - origin[0], p[1] - origin[1], p[2] - origin[2]];
    let scale = nodes
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, c| m.max(c.abs()));
    let tree2: RTree<GeomWithData<Rectangle<[f64; 2]>, usize>> = RTree::bulk_load(
        segs.iter()
            .enumerate()
            .map(|(k, &(a, b))| {
                GeomWithData::new(Rectangle::from_corners(uv[a as usize], uv[b as usize]), k)
            })
            .collect(),
    );
    let tree3: RTree<GeomWithData<Rectangle<[f64; 3]>, usize>> = RTree::bulk_load(
        segs.iter()
            .enumerate()
            .map(|(k, &(a, b))| {
                let (pa, pb) = (rel(&nodes[a as usize]), rel(&nodes[b as usize]));
                GeomWithData::new(Rectangle::from_corners(pa, pb), k)
            })
            .collect(),
    );
    let node_tree: RTree<GeomWithData<[f64; 3], usize>> = RTree::bulk_load(
        nodes
            .iter()
            .enumerate()
            .map(|(i, p)| GeomWithData::new(rel(p), i))
            .collect(),
    );
    for v in given.first_point..ng {
        let k = given.point_of(v).unwrap_or(v - given.first_point);
        let p = nodes[v];
        let name = |n: u32| node_name(given, n as usize);
        // Exactly on a segment in the plane.
        let q = uv[v];
        let mut near: Vec<usize> = tree2
            .locate_in_envelope_intersecting(AABB::from_point(q))
            .map(|s| s.data)
            .collect();
        near.sort_unstable();
        for s in near {
            let (a, b) = segs[s];
            let (ua, ub) = (uv[a as usize], uv[b as usize]);
            if q == ua || q == ub {
                let n = if q == ua { a } else { b };
                return Err(fail(
                    input,
                    format!(
                        "point {k} lands on the same place of the support as {}, without being bit-identical to it",
                        name(n)
                    ),
                    Some(p),
                ));
            }
            let in_box = ua[0].min(ub[0]) <= q[0]
                && q[0] <= ua[0].max(ub[0])
                && ua[1].min(ub[1]) <= q[1]
                && q[1] <= ua[1].max(ub[1]);
            if in_box && orient2d(&ua, &ub, &q) == Orientation::Zero {
                return Err(fail(
                    input,
                    format!(
                        "point {k} lies on {} (a point must be strictly inside the patch, off its loops and constraints)",
                        given.segment_name(s)
                    ),
                    Some(p),
                ));
            }
        }
        // Within the tolerance of a segment in 3D.
        let r = tol * hloc[v];
        let reach = r * (1.0 + 1e-9) + 16.0 * f64::EPSILON * scale;
        let pr = rel(&p);
        let env = AABB::from_corners(pr.map(|c| c - reach), pr.map(|c| c + reach));
        let mut near: Vec<usize> = tree3
            .locate_in_envelope_intersecting(env)
            .map(|s| s.data)
            .collect();
        near.sort_unstable();
        for s in near {
            let (a, b) = segs[s];
            let (d, t) = to_segment(&p, &nodes[a as usize], &nodes[b as usize]);
            if d <= r {
                let message = if t <= 0.0 || t >= 1.0 {
                    let n = if t <= 0.0 { a } else { b };
                    format!(
                        "point {k} is {d:.3e} from {}, within the tolerance {r:.3e}, without being bit-identical to it",
                        name(n)
                    )
                } else {
                    format!(
                        "point {k} lies on {} within the tolerance {r:.3e} ({d:.3e} from it; a point must be strictly inside the patch, off its loops and constraints)",
                        given.segment_name(s)
                    )
                };
                return Err(fail(input, message, Some(p)));
            }
        }
        // The nearest other given node: not within the tolerance; it bounds the local size.
        let other = node_tree
            .nearest_neighbor_iter(pr)
            .find(|n| n.data != v)
            .map(|n| n.data);
        if let Some(w) = other {
            let d = dist(&p, &nodes[w]);
            if d <= r {
                return Err(fail(
                    input,
                    format!(
                        "point {k} is {d:.3e} from {}, within the tolerance {r:.3e}, without being bit-identical to it",
                        name(w as u32)
                    ),
                    Some(p),
                ));
            }
            hfield[v] = hfield[v].min(d);
        }
    }
    Ok(hfield)
}

/// Given node `v` named for messages: "node 12 (a loop node)", "point 3".
fn node_name(given: &GivenNodes, v: usize) -> String {
    match given.point_of(v) {
        Some(k) => format!("point {k}"),
        None if given.loop_visits[v] > 0 => format!("node {v} (a loop node)"),
        None => format!("node {v} (a constraint node)"),
    }
}

/// The distance from `p` to segment `a b` in 3D, and the parameter of the foot of the
/// perpendicular along it (below 0 or above 1 when the closest point is an end).
fn to_segment(p: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> (f64, f64) {
    let ab = sub(b, a);
    let l2 = dot(&ab, &ab);
    let t = if l2 > 0.0 {
        dot(&sub(p, a), &ab) / l2
    } else {
        0.0
    };
    let s = t.clamp(0.0, 1.0);
    let foot = [a[0] + s * ab[0], a[1] + s * ab[1], a[2] + s * ab[2]];
    (dist(p, &foot), t)
}
