//! Splitting: insert the curves of every intersection of one surface into its triangulation so
//! that it conforms to all of them: every curve point becomes a vertex (existing vertex, or a
//! new vertex on an edge or inside a face), every curve segment becomes one or more edges, and
//! where curves of two intersections cross inside a face the crossing becomes a vertex of both.
//!
//! Points merge when they are the same place on the surface: the same vertex, or the same edge
//! or face with bit-identical coordinates. To make points shared by three surfaces identical on
//! all of them, [`split_all_with`] takes the other surfaces' meshes and constructs coordinates
//! from inputs in a canonical order: an edge crossing a face from its endpoints in lexicographic
//! order (a box edge seen from two box sides), a crossing of two curves inside a face as the
//! common point of the three triangles' planes taken in surface-name order.
//!
//! Where a fault ends on another fault inside a third surface's face (a T-junction), the end of
//! the first curve lies on the second curve; rounded coordinates cannot show it, so it is decided
//! from provenance (`symbolic`: the ending fault's border edge lies in the other fault's plane,
//! exact `orient3d` on input coordinates) and the point is built the same way on all three
//! surfaces (that border edge meeting the third surface's plane).
//!
//! Each curve segment inside a triangle (a chord) is first cut at every point lying on it:
//! crossings with other intersections' chords, T-junctions, points exactly on it (exact
//! `orient2d`), and, for a chord running along an edge of the triangle, the border points of that
//! edge between its ends. Each original triangle is then re-triangulated on its own as a
//! constrained triangulation (`triangulate`) of its boundary polygon (corners plus the curve
//! points on its edges, shared with the neighbours, so the result stays conforming), its inner
//! curve points and its chord pieces: chains from border to border, dangling ends, branches,
//! closed loops and whole curves inside one face all go through the same steps. Every decision is
//! an exact `orient2d` in a projection chosen exactly for the original triangle, on the (float)
//! coordinates of the points; new triangles keep the orientation of their parent. A zero-area
//! triangle (skipped by `intersect`) with curve points on its edges is fanned into zero-area
//! triangles so that its neighbours stay conforming.
//!
//! Reported as [`SplitError::Unsupported`], with the triangle and a coordinate, only what would
//! need moving a constructed point: a curve point outside its face or on its border in the
//! projection (rounding of a point very near an edge), two curve points at one projected place,
//! two chords of one intersection crossing, a chord inside a zero-area triangle (which
//! `intersect` never produces). Isolated touch points are not inserted.

pub mod arrangement;
mod symbolic;
mod triangulate;

use super::Intersection;
use super::key::{Location, PointKey};
use super::locate::{project, projection_axis};
use super::polygon::improve;
use geom::{Orientation, TriMesh, orient2d};
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
    /// Original vertices first (same indices), then one new vertex per new curve point (sorted
    /// by location on the surface, then coordinates), then one per crossing of two curves.
    pub mesh: TriMesh,
    /// For each triangle of `mesh`, the original triangle it lies in.
    pub parent: Vec<u32>,
    /// The vertex of `mesh` of each curve point of the first intersection (the only one for
    /// [`split`]); see `vertex_of_each` for all of them.
    pub vertex_of: BTreeMap<PointKey, u32>,
    /// For each intersection given to [`split_all`], in order, the vertex of each curve point.
    pub vertex_of_each: Vec<BTreeMap<PointKey, u32>>,
    /// Vertices created where curves of two intersections cross inside a face, sorted.
    pub crossings: Vec<u32>,
    /// The curve segments (pieces between crossings) as sorted vertex pairs of `mesh`, sorted.
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
    #[error(
        "splitting `{surface}`: intersection `{a}` x `{b}` does not involve this surface on the side given"
    )]
    WrongSurface {
        surface: String,
        a: String,
        b: String,
    },
}

/// Split `mesh` (surface `a` or `b` of `x`, chosen by `side`) along the curves of `x`.
pub fn split(mesh: &TriMesh, x: &Intersection, side: Side) -> Result<SplitSurface, SplitError> {
    let name = if side == Side::A { &x.a } else { &x.b };
    split_all(name, mesh, &[(x, side)])
}

/// Split surface `surface_name` along the curves of all `intersections` (each with the side
/// this surface is on). Coordinates of curve points are used as given; see [`split_all_with`]
/// to make points shared by three surfaces bit-identical everywhere.
pub fn split_all(
    surface_name: &str,
    mesh: &TriMesh,
    intersections: &[(&Intersection, Side)],
) -> Result<SplitSurface, SplitError> {
    split_all_with(surface_name, mesh, intersections, &[])
}

/// Split every surface of a model along all the intersections that involve it (picking each
/// intersection's side by name), with the other surfaces' meshes for canonical shared points.
/// The result is in the order of `surfaces`. Surfaces are split in parallel (each on its own,
/// so the result does not depend on the thread count); on failure the error is the one of the
/// first failing surface in `surfaces` order.
pub fn split_model(
    surfaces: &[(&str, &TriMesh)],
    intersections: &[Intersection],
) -> Result<Vec<SplitSurface>, SplitError> {
    use rayon::prelude::*;
    let each: Vec<Result<SplitSurface, SplitError>> = surfaces
        .par_iter()
        .map(|&(name, mesh)| {
            let mine: Vec<(&Intersection, Side)> = intersections
                .iter()
                .filter_map(|x| {
                    if x.a == name {
                        Some((x, Side::A))
                    } else if x.b == name {
                        Some((x, Side::B))
                    } else {
                        None
                    }
                })
                .collect();
            split_all_with(name, mesh, &mine, surfaces)
        })
        .collect();
    each.into_iter().collect()
}

/// One curve point as seen on the surface being split.
struct Pt {
    ix: usize,
    key: PointKey,
    loc: Location,
    /// Where the point lies on the other surface of its intersection.
    oloc: Location,
    xyz: [f64; 3],
}

/// One chord: a curve segment inside triangle `t` of the surface, with the other surface's
/// name and the triangle of it containing the segment.
#[derive(Clone)]
struct Chord {
    t: u32,
    v: [u32; 2],
    other: usize,
    other_face: u32,
    /// Where its two ends lie on the other surface.
    ends: [Location; 2],
}

/// As [`split_all`], with the meshes of the other surfaces (by name) used to construct shared
/// points canonically (see the module doc). Missing meshes fall back to the given coordinates.
pub fn split_all_with(
    surface_name: &str,
    mesh: &TriMesh,
    intersections: &[(&Intersection, Side)],
    others: &[(&str, &TriMesh)],
) -> Result<SplitSurface, SplitError> {
    let name = surface_name.to_string();
    let bad = |index: u32| SplitError::BadIndex {
        surface: name.clone(),
        index,
    };
    let nv = mesh.vertices.len() as u32;
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tri.iter().any(|&v| v >= nv) {
            return Err(bad(t as u32));
        }
    }
    let other_mesh = |n: &str| find_mesh(others, n);
    let tri_of = |m: &TriMesh, t: u32| -> Option<[[f64; 3]; 3]> {
        let tri = m.triangles.get(t as usize)?;
        let mut c = [[0.0; 3]; 3];
        for k in 0..3 {
            c[k] = *m.vertices.get(tri[k] as usize)?;
        }
        Some(c)
    };
    let vert = |m: &TriMesh, v: u32| m.vertices.get(v as usize).copied();

    // Curve points, with canonical coordinates where possible.
    let mut pts: Vec<Pt> = Vec::new();
    let mut partner: Vec<&str> = Vec::new();
    for (ix, &(x, side)) in intersections.iter().enumerate() {
        let (me, them) = if side == Side::A {
            (&x.a, &x.b)
        } else {
            (&x.b, &x.a)
        };
        if me != surface_name {
            return Err(SplitError::WrongSurface {
                surface: name.clone(),
                a: x.a.clone(),
                b: x.b.clone(),
            });
        }
        partner.push(them);
        let om = other_mesh(them);
        for p in x.curves.iter().flat_map(|c| c.points.iter()) {
            let (la, lb) = (p.on_a, p.on_b);
            let (loc, oloc) = if side == Side::A { (la, lb) } else { (lb, la) };
            let xyz = match (loc, oloc, om) {
                (Location::Vertex(v), _, _) => vert(mesh, v).ok_or_else(|| bad(v))?,
                (Location::Edge(i, j), Location::Face(f), Some(om)) => {
                    match (vert(mesh, i), vert(mesh, j), tri_of(om, f)) {
                        (Some(pi), Some(pj), Some(tf)) => {
                            arrangement::edge_plane(pi, pj, tf).unwrap_or(p.xyz)
                        }
                        _ => p.xyz,
                    }
                }
                (Location::Face(t), Location::Edge(i, j), Some(om)) => {
                    match (vert(om, i), vert(om, j), tri_of(mesh, t)) {
                        (Some(pi), Some(pj), Some(tf)) => {
                            arrangement::edge_plane(pi, pj, tf).unwrap_or(p.xyz)
                        }
                        _ => p.xyz,
                    }
                }
                _ => p.xyz,
            };
            pts.push(Pt {
                ix,
                key: p.key,
                loc,
                oloc,
                xyz,
            });
        }
    }
    symbolic::t_on_edges(&mut pts, &partner, others, intersections);
    // Merge: same vertex, or same edge/face with bit-identical coordinates.
    let place = |p: &Pt| -> (Location, [u64; 3]) {
        match p.loc {
            Location::Vertex(_) => (p.loc, [0; 3]),
            _ => (p.loc, p.xyz.map(f64::to_bits)),
        }
    };
    let mut vertices = mesh.vertices.clone();
    let mut at_place: BTreeMap<(Location, [u64; 3]), u32> = BTreeMap::new();
    let mut order: Vec<&Pt> = pts.iter().collect();
    order.sort_by_key(|p| place(p));
    for p in order {
        let k = place(p);
        if at_place.contains_key(&k) {
            continue;
        }
        let v = match p.loc {
            Location::Vertex(v) if v < nv => v,
            Location::Vertex(v) => return Err(bad(v)),
            Location::Edge(i, j) if i >= nv || j >= nv => return Err(bad(i.max(j))),
            Location::Face(t) if t as usize >= mesh.triangles.len() => return Err(bad(t)),
            _ => {
                vertices.push(p.xyz);
                vertices.len() as u32 - 1
            }
        };
        at_place.insert(k, v);
    }
    let mut vertex_of_each: Vec<BTreeMap<PointKey, u32>> =
        vec![BTreeMap::new(); intersections.len()];
    let mut loc: BTreeMap<u32, Location> = BTreeMap::new();
    for p in &pts {
        if let Some(&v) = at_place.get(&place(p)) {
            vertex_of_each[p.ix].insert(p.key, v);
            loc.insert(v, p.loc);
        }
    }

    // Chords per triangle.
    let mut chords: Vec<Chord> = Vec::new();
    for (ix, &(x, side)) in intersections.iter().enumerate() {
        for c in &x.curves {
            let n = c.points.len();
            for (s, &(ta, tb)) in c.segments_faces.iter().enumerate() {
                let (Some(p), Some(q)) = (c.points.get(s), c.points.get((s + 1) % n.max(1))) else {
                    continue;
                };
                let map = &vertex_of_each[ix];
                let (Some(&vp), Some(&vq)) = (map.get(&p.key), map.get(&q.key)) else {
                    continue;
                };
                if vp == vq {
                    continue;
                }
                let (t, of) = if side == Side::A { (ta, tb) } else { (tb, ta) };
                if t as usize >= mesh.triangles.len() {
                    return Err(bad(t));
                }
                let oloc = |c: &super::CurvePoint| if side == Side::A { c.on_b } else { c.on_a };
                chords.push(Chord {
                    t,
                    v: [vp, vq],
                    other: ix,
                    other_face: of,
                    ends: [oloc(p), oloc(q)],
                });
            }
        }
    }
    // Ties (one segment in two intersections) are broken by the other surface's name, not by
    // the order the intersections were given in.
    chords.sort_by(|c, d| {
        let k = |c: &Chord| (c.t, c.v[0].min(c.v[1]), c.v[0].max(c.v[1]));
        k(c).cmp(&k(d))
            .then_with(|| partner[c.other].cmp(partner[d.other]))
            .then(c.other_face.cmp(&d.other_face))
    });
    chords.dedup_by_key(|c| (c.t, c.v[0].min(c.v[1]), c.v[0].max(c.v[1])));

    // Crossings of chords of different intersections inside a triangle.
    let unsupported = |t: u32, at: [f64; 3], what: &str| SplitError::Unsupported {
        surface: name.clone(),
        triangle: t,
        at,
        what: what.to_string(),
    };
    // Crossing points on each chord (index into `chords`).
    let mut on_chord: Vec<Vec<u32>> = vec![Vec::new(); chords.len()];
    let mut crossing_at: BTreeMap<Vec<(String, u32)>, u32> = BTreeMap::new();
    let mut crossings = Vec::new();
    let mut start = 0;
    while start < chords.len() {
        let t = chords[start].t;
        let end = start + chords[start..].iter().take_while(|c| c.t == t).count();
        let corners = tri_of(mesh, t).ok_or_else(|| bad(t))?;
        let multi = chords[start..end]
            .iter()
            .any(|c| c.other != chords[start].other);
        if multi {
            let Some((axis, _)) = projection_axis(&corners) else {
                return Err(unsupported(
                    t,
                    corners[0],
                    "a curve touches this zero-area triangle",
                ));
            };
            // T-junctions known from provenance: an end of chord j inside the face lies on
            // chord i when its point on j's surface (a vertex, or an edge) lies in the plane
            // of i's other face, or when chord i runs along an edge of its other surface and
            // that point is on an edge coplanar with it.
            for i in start..end {
                let ci = &chords[i];
                let Some(im) = other_mesh(partner[ci.other]) else {
                    continue;
                };
                let Some(plane) = tri_of(im, ci.other_face) else {
                    continue;
                };
                let ie = symbolic::partner_edge(ci.ends);
                let meets = |q: &TriMesh, at: Location| match (ie, at) {
                    (Some(e), Location::Edge(a, b)) => symbolic::edges_coplanar(q, (a, b), im, e),
                    _ => symbolic::lies_in_plane(q, at, &plane),
                };
                let (p0, p1) = (vertices[ci.v[0] as usize], vertices[ci.v[1] as usize]);
                let d = [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]];
                let along = |w: u32| {
                    let x = vertices[w as usize];
                    (x[0] - p0[0]) * d[0] + (x[1] - p0[1]) * d[1] + (x[2] - p0[2]) * d[2]
                };
                for cj in &chords[start..end] {
                    let Some(q) = other_mesh(partner[cj.other]).filter(|_| cj.other != ci.other)
                    else {
                        continue;
                    };
                    for (&w, &at) in cj.v.iter().zip(&cj.ends) {
                        if !ci.v.contains(&w)
                            && loc.get(&w) == Some(&Location::Face(t))
                            && meets(q, at)
                            && along(w) > 0.0
                            && along(w) < along(ci.v[1])
                        {
                            on_chord[i].push(w);
                        }
                    }
                }
            }
            for i in start..end {
                for j in i + 1..end {
                    let (ci, cj) = (&chords[i], &chords[j]);
                    if ci.other == cj.other
                        || ci.v.iter().any(|v| cj.v.contains(v))
                        || on_chord[i].iter().any(|v| cj.v.contains(v))
                        || on_chord[j].iter().any(|v| ci.v.contains(v))
                    {
                        continue;
                    }
                    let p = |v: u32| project(&vertices[v as usize], axis);
                    match arrangement::crossing(p(ci.v[0]), p(ci.v[1]), p(cj.v[0]), p(cj.v[1])) {
                        // A touch is found below, as a point lying on a chord.
                        None | Some(false) => {}
                        Some(true) => {
                            let mut key = vec![
                                (name.clone(), t),
                                (partner[ci.other].to_string(), ci.other_face),
                                (partner[cj.other].to_string(), cj.other_face),
                            ];
                            key.sort();
                            let v = match crossing_at.get(&key) {
                                Some(&v) => v,
                                None => {
                                    let xyz = along_edge_xyz(ci, cj, &partner, others)
                                        .unwrap_or_else(|| {
                                            crossing_xyz(
                                                &key,
                                                surface_name,
                                                mesh,
                                                others,
                                                [ci.v, cj.v]
                                                    .map(|s| s.map(|v| vertices[v as usize])),
                                                axis,
                                            )
                                        });
                                    vertices.push(xyz);
                                    let v = vertices.len() as u32 - 1;
                                    crossing_at.insert(key, v);
                                    crossings.push(v);
                                    loc.insert(v, Location::Face(t));
                                    v
                                }
                            };
                            on_chord[i].push(v);
                            on_chord[j].push(v);
                        }
                    }
                }
            }
        }
        start = end;
    }
    // Points on each original edge, and inside each original face.
    let mut on_edge: BTreeMap<(u32, u32), Vec<u32>> = BTreeMap::new();
    let mut in_face: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    for (&v, &l) in &loc {
        match l {
            Location::Edge(i, j) => on_edge.entry((i, j)).or_default().push(v),
            Location::Face(t) => in_face.entry(t).or_default().push(v),
            Location::Vertex(_) => {}
        }
    }
    // Further points on each chord: the triangle's border points between its ends when it
    // runs along an edge, else any point of the triangle lying exactly on it.
    let mut start = 0;
    while start < chords.len() {
        let t = chords[start].t;
        let end = start + chords[start..].iter().take_while(|c| c.t == t).count();
        let tri = mesh.triangles[t as usize];
        let corners = tri_of(mesh, t).ok_or_else(|| bad(t))?;
        let Some((axis, _)) = projection_axis(&corners) else {
            return Err(unsupported(
                t,
                corners[0],
                "a curve runs inside this zero-area triangle",
            ));
        };
        let sides = |v: u32| -> u8 {
            (0..3usize)
                .filter(|&k| {
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    v == a || v == b || loc.get(&v) == Some(&Location::Edge(a.min(b), a.max(b)))
                })
                .fold(0, |m, k| m | (1 << k))
        };
        let edge_of = |k: usize| {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            on_edge.get(&(a.min(b), a.max(b)))
        };
        let mut local: Vec<u32> = tri.to_vec();
        for k in 0..3 {
            local.extend(edge_of(k).into_iter().flatten());
        }
        local.extend(in_face.get(&t).into_iter().flatten());
        for (c, xs) in chords[start..end].iter().zip(&mut on_chord[start..end]) {
            let common = sides(c.v[0]) & sides(c.v[1]);
            if let Some(k) = (0..3).find(|&k| common & (1 << k) != 0) {
                let (p, q) = (vertices[c.v[0] as usize], vertices[c.v[1] as usize]);
                let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
                let along = |v: u32| {
                    let x = vertices[v as usize];
                    (x[0] - p[0]) * d[0] + (x[1] - p[1]) * d[1] + (x[2] - p[2]) * d[2]
                };
                let len2 = along(c.v[1]);
                xs.extend(
                    edge_of(k)
                        .into_iter()
                        .flatten()
                        .filter(|&&w| along(w) > 0.0 && along(w) < len2),
                );
                continue;
            }
            let p = |v: u32| project(&vertices[v as usize], axis);
            let (p0, p1) = (p(c.v[0]), p(c.v[1]));
            for &w in &local {
                if !c.v.contains(&w) && on_open_segment(p0, p1, p(w)) {
                    xs.push(w);
                }
            }
        }
        start = end;
    }
    // Chord pieces between the points on them.
    let mut pieces: BTreeMap<u32, Vec<[u32; 2]>> = BTreeMap::new();
    let mut curve_edges = Vec::new();
    for (c, xs) in chords.iter().zip(&mut on_chord) {
        let (p, q) = (vertices[c.v[0] as usize], vertices[c.v[1] as usize]);
        let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let along = |v: u32| {
            let x = vertices[v as usize];
            (x[0] - p[0]) * d[0] + (x[1] - p[1]) * d[1] + (x[2] - p[2]) * d[2]
        };
        xs.sort_by(|a, b| along(*a).total_cmp(&along(*b)).then(a.cmp(b)));
        xs.dedup();
        let chain: Vec<u32> = std::iter::once(c.v[0])
            .chain(xs.iter().copied())
            .chain(std::iter::once(c.v[1]))
            .collect();
        for w in chain.windows(2) {
            let e = [w[0].min(w[1]), w[0].max(w[1])];
            curve_edges.push(e);
            pieces.entry(c.t).or_default().push(e);
        }
    }
    curve_edges.sort_unstable();
    curve_edges.dedup();

    let mut triangles = Vec::with_capacity(mesh.triangles.len());
    let mut parent = Vec::with_capacity(mesh.triangles.len());
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let t = t as u32;
        let edge_pts = |a: u32, b: u32| on_edge.get(&(a.min(b), a.max(b)));
        let touched = pieces.contains_key(&t)
            || in_face.contains_key(&t)
            || (0..3).any(|k| edge_pts(tri[k], tri[(k + 1) % 3]).is_some());
        if !touched {
            triangles.push(*tri);
            parent.push(t);
            continue;
        }
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
        let corners = [0, 1, 2].map(|k| vertices[tri[k] as usize]);
        let Some((axis, sign)) = projection_axis(&corners) else {
            // A zero-area triangle (skipped by `intersect`) with curve points on its edges:
            // fanned, so that its neighbours stay conforming.
            let fan = match pieces.contains_key(&t) || in_face.contains_key(&t) {
                true => None,
                false => triangulate::fan(&boundary),
            };
            let fan = fan.ok_or_else(|| {
                unsupported(t, corners[0], "a curve runs inside this zero-area triangle")
            })?;
            for tr in fan {
                triangles.push(tr);
                parent.push(t);
            }
            continue;
        };
        let pt = |v: u32| project(&vertices[v as usize], axis);
        let err = |(what, v): triangulate::Refusal| unsupported(t, vertices[v as usize], what);
        // Chord pieces that are not pieces of the boundary.
        let m = boundary.len();
        // The first position of each boundary vertex, for lookups by binary search.
        let mut first: Vec<(u32, usize)> =
            boundary.iter().enumerate().map(|(i, &v)| (v, i)).collect();
        first.sort_unstable();
        first.dedup_by_key(|x| x.0);
        let position = |v: u32| {
            first
                .binary_search_by_key(&v, |x| x.0)
                .ok()
                .map(|k| first[k].1)
        };
        let mut segs: Vec<[u32; 2]> = pieces
            .get(&t)
            .map(|c| {
                c.iter()
                    .copied()
                    .filter(|s| {
                        let i = position(s[0]);
                        let j = position(s[1]);
                        match (i, j) {
                            (Some(i), Some(j)) => (i + 1) % m != j && (j + 1) % m != i,
                            _ => true,
                        }
                    })
                    .collect()
            })
            .unwrap_or_default();
        segs.sort_unstable();
        segs.dedup();
        let mut inner: Vec<u32> = segs
            .iter()
            .flatten()
            .copied()
            .filter(|v| !boundary.contains(v))
            .chain(in_face.get(&t).into_iter().flatten().copied())
            .collect();
        inner.sort_unstable();
        inner.dedup();
        let mut ct = triangulate::Ct::new(&boundary, &pt, sign).map_err(err)?;
        for v in inner {
            ct.insert_point(v).map_err(err)?;
        }
        for s in &segs {
            ct.insert_segment(s[0], s[1]).map_err(err)?;
        }
        let (mut local, locked) = ct.finish();
        improve(&mut local, &locked, &pt, sign);
        for tr in local {
            triangles.push(tr);
            parent.push(t);
        }
    }
    crossings.sort_unstable();
    Ok(SplitSurface {
        mesh: TriMesh::new(vertices, triangles),
        parent,
        vertex_of: vertex_of_each.first().cloned().unwrap_or_default(),
        vertex_of_each,
        crossings,
        curve_edges,
    })
}

/// `x` lies in the open segment `pq` (a coordinate comparison, then exact `orient2d`).
fn on_open_segment(p: [f64; 2], q: [f64; 2], x: [f64; 2]) -> bool {
    let within = (0..2).all(|k| p[k].min(q[k]) <= x[k] && x[k] <= p[k].max(q[k]));
    within && x != p && x != q && orient2d(&p, &q, &x) == Orientation::Zero
}

/// The crossing of two chords when exactly one of them runs along an edge of its other surface
/// (a fault's border edge lying in the plane of the fault it ends on): that edge meeting the
/// plane of the other chord's other face, built as where that third surface is split, so all
/// three surfaces get the same bits. `None` otherwise or when a mesh is missing.
fn along_edge_xyz(
    ci: &Chord,
    cj: &Chord,
    partner: &[&str],
    others: &[(&str, &TriMesh)],
) -> Option<[f64; 3]> {
    let (along, across) = match (
        symbolic::partner_edge(ci.ends),
        symbolic::partner_edge(cj.ends),
    ) {
        (Some(e), None) => ((ci, e), cj),
        (None, Some(e)) => ((cj, e), ci),
        _ => return None,
    };
    let ((c, e), m) = (along, find_mesh(others, partner.get(across.other)?)?);
    let q = find_mesh(others, partner.get(c.other)?)?;
    let plane = m.triangles.get(across.other_face as usize)?;
    let corner = |v: u32| m.vertices.get(v as usize).copied();
    let plane = [corner(plane[0])?, corner(plane[1])?, corner(plane[2])?];
    let (p, r) = (q.vertices.get(e.0 as usize)?, q.vertices.get(e.1 as usize)?);
    arrangement::edge_plane(*p, *r, plane)
}

/// The mesh of surface `n` among `others`.
fn find_mesh<'a>(others: &[(&str, &'a TriMesh)], n: &str) -> Option<&'a TriMesh> {
    others.iter().find(|o| o.0 == n).map(|o| o.1)
}

/// Coordinates of the crossing named by `key` (three (surface, triangle) pairs sorted by name):
/// the common point of the three planes when all meshes are known, else the crossing of the two
/// chords (`segs`, 3D endpoints) computed in the projection `axis` and lifted along the first.
fn crossing_xyz(
    key: &[(String, u32)],
    me: &str,
    mesh: &TriMesh,
    others: &[(&str, &TriMesh)],
    segs: [[[f64; 3]; 2]; 2],
    axis: usize,
) -> [f64; 3] {
    let tri = |(s, t): &(String, u32)| -> Option<[[f64; 3]; 3]> {
        let m = if s == me { mesh } else { find_mesh(others, s)? };
        let tri = m.triangles.get(*t as usize)?;
        let mut c = [[0.0; 3]; 3];
        for k in 0..3 {
            c[k] = *m.vertices.get(tri[k] as usize)?;
        }
        Some(c)
    };
    if let (Some(a), Some(b), Some(c)) = (
        key.first().and_then(tri),
        key.get(1).and_then(tri),
        key.get(2).and_then(tri),
    ) && let Some(x) = arrangement::three_planes([a, b, c])
    {
        return x;
    }
    let [[p, q], [r, s]] = segs;
    let (p2, q2, r2, s2) = (
        project(&p, axis),
        project(&q, axis),
        project(&r, axis),
        project(&s, axis),
    );
    let cr = |u: [f64; 2], v: [f64; 2]| u[0] * v[1] - u[1] * v[0];
    let d1 = [q2[0] - p2[0], q2[1] - p2[1]];
    let d2 = [s2[0] - r2[0], s2[1] - r2[1]];
    let w = [r2[0] - p2[0], r2[1] - p2[1]];
    let den = cr(d1, d2);
    let u = if den != 0.0 { cr(w, d2) / den } else { 0.5 };
    let u = if u.is_finite() {
        u.clamp(0.0, 1.0)
    } else {
        0.5
    };
    [0, 1, 2].map(|k| p[k] + u * (q[k] - p[k]))
}
