//! Splitting (first step): insert the curves of one intersection into one of its two surfaces so
//! that the triangulation conforms to them: every curve point becomes a vertex (existing vertex,
//! or a new vertex on an edge or inside a face) and every curve segment becomes an edge.
//!
//! Each original triangle is re-triangulated on its own: its boundary polygon (corners plus the
//! curve points on its edges, shared with the neighbours, so the result stays conforming) is cut
//! along the chords the curves draw across it, and each piece is ear-clipped. Orientation tests
//! use `orient2d` in a projection chosen exactly for the original triangle, on the (float)
//! coordinates of the points; new triangles keep the orientation of their parent.
//!
//! Supported: curves crossing triangles from border to border, through any number of points
//! inside the face, and curves that end inside a face (a dangling fault edge): the dangling end
//! is joined by an extra, non-curve edge to a polygon vertex it sees. Not yet supported, reported
//! as [`SplitError::Unsupported`] with the triangle and a coordinate: curves branching inside a
//! face, a curve lying entirely inside a single face, or a curve touching a zero-area triangle.
//! Isolated touch points are not inserted. Several intersections on one surface (curves
//! crossing each other inside a face) need the arrangement of their segments: the next step.

use super::Intersection;
use super::key::{Location, PointKey};
use super::locate::{project, projection_axis};
use super::polygon::{ear_clip, improve};
use crate::geom::{Orientation, TriMesh, orient2d};
use std::collections::BTreeMap;
use thiserror::Error;

/// Which surface of an [`Intersection`] to split.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Side {
    A,
    B,
}

/// A surface re-triangulated to conform to intersection curves.
#[derive(Clone, Debug, PartialEq)]
pub struct SplitSurface {
    /// Original vertices first (same indices), then one new vertex per new curve point, in key
    /// order.
    pub mesh: TriMesh,
    /// For each triangle of `mesh`, the original triangle it lies in.
    pub parent: Vec<u32>,
    /// The vertex of `mesh` of each curve point.
    pub vertex_of: BTreeMap<PointKey, u32>,
    /// The curve segments as sorted vertex pairs of `mesh`, sorted.
    pub curve_edges: Vec<[u32; 2]>,
}

#[derive(Clone, Debug, PartialEq, Error)]
pub enum SplitError {
    #[error("splitting `{surface}`: triangle {triangle} near ({}, {}, {}): {what}", at[0], at[1], at[2])]
    Unsupported {
        surface: String,
        triangle: u32,
        at: [f64; 3],
        what: String,
    },
    #[error(
        "splitting `{surface}`: the intersection refers to triangle or vertex {index}, which the surface does not have"
    )]
    BadIndex { surface: String, index: u32 },
}

fn loc_of(p: &super::CurvePoint, side: Side) -> Location {
    if side == Side::A { p.on_a } else { p.on_b }
}

/// Split `mesh` (surface `a` or `b` of `x`, chosen by `side`) along the curves of `x`.
pub fn split(mesh: &TriMesh, x: &Intersection, side: Side) -> Result<SplitSurface, SplitError> {
    let name = if side == Side::A { &x.a } else { &x.b };
    let bad = |index: u32| SplitError::BadIndex {
        surface: name.clone(),
        index,
    };
    let nv = mesh.vertices.len() as u32;
    let mut vertices = mesh.vertices.clone();
    let mut vertex_of: BTreeMap<PointKey, u32> = BTreeMap::new();
    let mut loc: BTreeMap<u32, Location> = BTreeMap::new();
    let mut keys: Vec<&super::CurvePoint> = x.curves.iter().flat_map(|c| c.points.iter()).collect();
    keys.sort_by_key(|p| p.key);
    keys.dedup_by(|p, q| p.key == q.key);
    for p in keys {
        let l = loc_of(p, side);
        let v = match l {
            Location::Vertex(v) if v < nv => v,
            Location::Vertex(v) => return Err(bad(v)),
            _ => {
                vertices.push(p.xyz);
                vertices.len() as u32 - 1
            }
        };
        vertex_of.insert(p.key, v);
        loc.insert(v, l);
    }
    // Points on each original edge, and inside each face.
    let mut on_edge: BTreeMap<(u32, u32), Vec<u32>> = BTreeMap::new();
    let mut chords: BTreeMap<u32, Vec<[u32; 2]>> = BTreeMap::new();
    for (&v, &l) in &loc {
        if let Location::Edge(i, j) = l {
            on_edge.entry((i, j)).or_default().push(v);
        }
    }
    let mut curve_edges = Vec::new();
    for c in &x.curves {
        let n = c.points.len();
        for (s, &(ta, tb)) in c.segments_faces.iter().enumerate() {
            let (p, q) = (&c.points[s], &c.points[(s + 1) % n]);
            let (Some(&vp), Some(&vq)) = (vertex_of.get(&p.key), vertex_of.get(&q.key)) else {
                continue;
            };
            curve_edges.push([vp.min(vq), vp.max(vq)]);
            let t = if side == Side::A { ta } else { tb };
            chords.entry(t).or_default().push([vp, vq]);
        }
    }
    curve_edges.sort_unstable();
    curve_edges.dedup();

    let mut triangles = Vec::with_capacity(mesh.triangles.len());
    let mut parent = Vec::with_capacity(mesh.triangles.len());
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let t = t as u32;
        if tri.iter().any(|&v| v >= nv) {
            return Err(bad(t));
        }
        let edge_pts = |a: u32, b: u32| on_edge.get(&(a.min(b), a.max(b)));
        let touched =
            chords.contains_key(&t) || (0..3).any(|k| edge_pts(tri[k], tri[(k + 1) % 3]).is_some());
        if !touched {
            triangles.push(*tri);
            parent.push(t);
            continue;
        }
        let corners = [0, 1, 2].map(|k| vertices[tri[k] as usize]);
        let Some((axis, sign)) = projection_axis(&corners) else {
            return Err(SplitError::Unsupported {
                surface: name.clone(),
                triangle: t,
                at: corners[0],
                what: "a curve touches this zero-area triangle".to_string(),
            });
        };
        let pt = |v: u32| project(&vertices[v as usize], axis);
        // Boundary cycle, in the triangle's own orientation.
        let mut boundary = Vec::new();
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            boundary.push(a);
            if let Some(list) = edge_pts(a, b) {
                let (pa, pb) = (vertices[a as usize], vertices[b as usize]);
                let d = [pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]];
                let mut along: Vec<(f64, u32)> = list
                    .iter()
                    .map(|&v| {
                        let p = vertices[v as usize];
                        (
                            (p[0] - pa[0]) * d[0] + (p[1] - pa[1]) * d[1] + (p[2] - pa[2]) * d[2],
                            v,
                        )
                    })
                    .collect();
                along.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
                boundary.extend(along.into_iter().map(|(_, v)| v));
            }
        }
        let err = |what: &str, v: u32| SplitError::Unsupported {
            surface: name.clone(),
            triangle: t,
            at: vertices[v as usize],
            what: what.to_string(),
        };
        let on_boundary = |v: u32| boundary.contains(&v);
        // Chords that are not pieces of the boundary, walked into chains boundary → boundary.
        let mut segs: Vec<[u32; 2]> = chords
            .get(&t)
            .map(|c| {
                c.iter()
                    .filter(|s| {
                        let (i, j) = (
                            boundary.iter().position(|&v| v == s[0]),
                            boundary.iter().position(|&v| v == s[1]),
                        );
                        match (i, j) {
                            (Some(i), Some(j)) => {
                                let m = boundary.len();
                                (i + 1) % m != j && (j + 1) % m != i
                            }
                            _ => true,
                        }
                    })
                    .map(|s| [s[0].min(s[1]), s[0].max(s[1])])
                    .collect()
            })
            .unwrap_or_default();
        segs.sort_unstable();
        segs.dedup();
        let mut adj: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
        for s in &segs {
            adj.entry(s[0]).or_default().push(s[1]);
            adj.entry(s[1]).or_default().push(s[0]);
        }
        for (&v, n) in &adj {
            if !on_boundary(v) && n.len() > 2 {
                return Err(err("curves branch inside this face", v));
            }
        }
        let mut used = vec![false; segs.len()];
        let seg_id = |a: u32, b: u32| segs.binary_search(&[a.min(b), a.max(b)]).ok();
        let mut chains: Vec<Vec<u32>> = Vec::new();
        for (&start, nbrs) in &adj {
            if !on_boundary(start) {
                continue;
            }
            for &first in nbrs {
                let Some(s0) = seg_id(start, first) else {
                    continue;
                };
                if used[s0] {
                    continue;
                }
                used[s0] = true;
                let mut chain = vec![start, first];
                let mut cur = first;
                while !on_boundary(cur) {
                    let prev = chain[chain.len() - 2];
                    let next = adj
                        .get(&cur)
                        .and_then(|n| n.iter().copied().find(|&w| w != prev));
                    let Some(next) = next else {
                        break; // a dangling end, joined to the polygon below
                    };
                    if let Some(s) = seg_id(cur, next) {
                        used[s] = true;
                    }
                    chain.push(next);
                    cur = next;
                }
                chains.push(chain);
            }
        }
        if let Some(i) = used.iter().position(|u| !u) {
            return Err(err("a curve lies entirely inside this face", segs[i][0]));
        }
        // Cut the polygon along each chain.
        let mut polys: Vec<Vec<u32>> = vec![boundary.clone()];
        for chain in &chains {
            let mut chain = chain.clone();
            let s = chain[0];
            let pi = polys.iter().position(|p| {
                p.contains(&s)
                    && (!on_boundary(chain[chain.len() - 1]) || p.contains(&chain[chain.len() - 1]))
                    && chain_inside(p, &chain, &pt, sign)
            });
            let Some(pi) = pi else {
                return Err(err("curves cross inside this face", s));
            };
            let last = chain[chain.len() - 1];
            if !on_boundary(last) {
                // A dangling end: join it to a polygon vertex it sees, so the chain cuts the piece.
                let w = bridge(&polys[pi], &chain, &pt, sign).ok_or_else(|| {
                    err("a curve ending inside this face could not be joined", last)
                })?;
                chain.push(w);
            }
            let e = chain[chain.len() - 1];
            let p = polys.swap_remove(pi);
            let (i, j) = (
                p.iter().position(|&v| v == s).unwrap_or(0),
                p.iter().position(|&v| v == e).unwrap_or(0),
            );
            let m = p.len();
            // First piece: boundary from e to s, then the chain from s to e (without repeats).
            let mut p1: Vec<u32> = (0..m)
                .map(|k| p[(j + k) % m])
                .take_while(|&v| v != s)
                .collect();
            p1.extend(chain[..chain.len() - 1].iter().copied());
            let mut p2: Vec<u32> = (0..m)
                .map(|k| p[(i + k) % m])
                .take_while(|&v| v != e)
                .collect();
            p2.extend(
                chain[1..]
                    .iter()
                    .rev()
                    .copied()
                    .collect::<Vec<_>>()
                    .into_iter()
                    .take(chain.len() - 1),
            );
            polys.push(p1);
            polys.push(p2);
        }
        let mut local = Vec::new();
        for p in &polys {
            local.extend(
                ear_clip(p, &pt, sign)
                    .ok_or_else(|| err("a piece could not be triangulated", p[0]))?,
            );
        }
        let locked: Vec<[u32; 2]> = chains
            .iter()
            .flat_map(|c| c.windows(2).map(|w| [w[0].min(w[1]), w[0].max(w[1])]))
            .collect();
        improve(&mut local, &locked, &pt, sign);
        for tr in local {
            triangles.push(tr);
            parent.push(t);
        }
    }
    Ok(SplitSurface {
        mesh: TriMesh::new(vertices, triangles),
        parent,
        vertex_of,
        curve_edges,
    })
}

/// Closed segments `pq` and `rs` share a point (exact `orient2d` on the given coordinates).
fn segments_meet(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> bool {
    let (o1, o2) = (orient2d(&p, &q, &r), orient2d(&p, &q, &s));
    let (o3, o4) = (orient2d(&r, &s, &p), orient2d(&r, &s, &q));
    let within = |a: [f64; 2], b: [f64; 2], x: [f64; 2]| {
        (0..2).all(|k| a[k].min(b[k]) <= x[k] && x[k] <= a[k].max(b[k]))
    };
    if o1 != Orientation::Zero && o1 == o2.flip() && o3 != Orientation::Zero && o3 == o4.flip() {
        return true;
    }
    (o1 == Orientation::Zero && within(p, q, r))
        || (o2 == Orientation::Zero && within(p, q, s))
        || (o3 == Orientation::Zero && within(r, s, p))
        || (o4 == Orientation::Zero && within(r, s, q))
}

/// A vertex `w` of polygon `p` (not on the chain) that the chain's dangling end sees: the
/// segment from the end to `w` enters `p` at `w` and meets no polygon edge and no chain
/// segment except at its own ends. The nearest such vertex (ties: smallest index).
fn bridge(
    p: &[u32],
    chain: &[u32],
    pt: &dyn Fn(u32) -> [f64; 2],
    sign: Orientation,
) -> Option<u32> {
    let end = chain[chain.len() - 1];
    let pe = pt(end);
    let m = p.len();
    let mut best: Option<(f64, u32)> = None;
    for &w in p {
        if chain.contains(&w) {
            continue;
        }
        let pw = pt(w);
        let clear_of_polygon = (0..m).all(|k| {
            let (a, b) = (p[k], p[(k + 1) % m]);
            a == w || b == w || !segments_meet(pe, pw, pt(a), pt(b))
        });
        let clear_of_chain = chain
            .windows(2)
            .all(|s| s[1] == end || !segments_meet(pe, pw, pt(s[0]), pt(s[1])));
        if clear_of_polygon && clear_of_chain && chain_inside(p, &[w, end], pt, sign) {
            let d = (pw[0] - pe[0]).powi(2) + (pw[1] - pe[1]).powi(2);
            if best.is_none_or(|(bd, bw)| d < bd || (d == bd && w < bw)) {
                best = Some((d, w));
            }
        }
    }
    best.map(|(_, w)| w)
}

/// Whether the chain leaves its first vertex into the interior of polygon `p` (at that vertex,
/// the chain's second point lies strictly inside the polygon's corner angle).
fn chain_inside(p: &[u32], chain: &[u32], pt: &dyn Fn(u32) -> [f64; 2], sign: Orientation) -> bool {
    let m = p.len();
    let Some(i) = p.iter().position(|&v| v == chain[0]) else {
        return false;
    };
    let (prev, cur, next) = (pt(p[(i + m - 1) % m]), pt(p[i]), pt(p[(i + 1) % m]));
    let q = pt(chain[1]);
    let left_of = |a: &[f64; 2], b: &[f64; 2]| orient2d(a, b, &q) == sign;
    let convex = orient2d(&prev, &cur, &next) != sign.flip();
    if convex {
        left_of(&cur, &next) && left_of(&prev, &cur)
    } else {
        left_of(&cur, &next) || left_of(&prev, &cur)
    }
}
