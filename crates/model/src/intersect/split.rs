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
mod cut;
mod points;
mod symbolic;
mod triangulate;

use super::Intersection;
use super::key::{Location, PointKey};
use super::locate::project;
use cut::Cut;
use geom::{Orientation, TriMesh, orient2d};
use points::Surface;
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
    let surface = Surface {
        name: surface_name,
        mesh,
        others,
    };
    surface.check_triangles()?;
    let (mut pts, partner) = surface.curve_points(intersections)?;
    symbolic::t_on_edges(&mut pts, &partner, others, intersections);
    let merged = surface.merge(&pts, intersections.len())?;
    let chords = surface.chords(intersections, &merged.vertex_of_each, &partner)?;
    let mut cut = Cut {
        surface,
        partner,
        vertices: merged.vertices,
        loc: merged.loc,
        on_chord: vec![Vec::new(); chords.len()],
        chords,
        crossings: Vec::new(),
    };
    cut.cross_chords()?;
    let places = cut.places();
    cut.points_on_chords(&places)?;
    let (pieces, curve_edges) = cut.pieces();
    let (triangles, parent) = cut.retriangulate(&places, &pieces)?;
    let vertex_of_each = merged.vertex_of_each;
    let mut crossings = cut.crossings;
    crossings.sort_unstable();
    Ok(SplitSurface {
        mesh: TriMesh::new(cut.vertices, triangles),
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

/// The corners of triangle `t` of `m`, `None` on a bad index.
fn tri_of(m: &TriMesh, t: u32) -> Option<[[f64; 3]; 3]> {
    let tri = m.triangles.get(t as usize)?;
    let mut c = [[0.0; 3]; 3];
    for k in 0..3 {
        c[k] = *m.vertices.get(tri[k] as usize)?;
    }
    Some(c)
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
