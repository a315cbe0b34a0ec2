//! Stage `intersect`: the exact intersection curves of two triangulated surfaces (seed §2.3).
//!
//! What it decides: which triangles of the two surfaces touch, where (as symbolic keys: which
//! vertex, edge or face of each surface contains each point), and how the contact segments chain
//! into curves. Every such decision uses exact `orient3d`/`orient2d` on input coordinates; no
//! tolerance enters. Only the coordinates of constructed points are floats (seed eq. 3).
//!
//! Pipeline: candidate pairs from R-trees of triangle boxes ([`candidates`]), exact contact of
//! each pair ([`contact`], built on [`locate`]), merging of points by key ([`key`]), iterative
//! polyline walk ([`assemble`]), coordinates from keys ([`construct`]). The box sides are
//! ordinary surfaces ([`box_sides()`]). [`split`] re-triangulates every surface to conform to
//! all its intersection curves at once (one exact constrained triangulation per original
//! triangle), with the points where three surfaces meet shared bit for bit.
//!
//! Symmetry: the surface whose name sorts first is always `a`, so `intersect(s, t)` and
//! `intersect(t, s)` give identical results (same curves, order and direction).
//!
//! Degenerate contacts are handled exactly: a vertex on the other surface, an edge lying in it,
//! shared vertices and curves through vertices all produce keys naming those vertices or edges.
//! Coplanar triangles whose interiors overlap are an error naming both surfaces and where,
//! unless they are one and the same triangle ([`shared`]): then `b` drops it, listed in
//! [`Intersection::shared`], and the curves are those of `a` with what `b` keeps (an error
//! where the two also cross elsewhere at under a degree: one part drawn twice).
//! Surfaces touching at isolated points without a contact segment (tangent contact at a vertex)
//! report those points in [`Intersection::touches`], not as curves. Zero-area triangles are
//! skipped (their edges are shared with their neighbours) and listed.

pub mod assemble;
pub mod box_sides;
pub mod candidates;
pub mod construct;
pub mod contact;
pub mod error;
pub mod key;
pub mod locate;
pub mod polygon;
pub mod shared;
pub mod split;

pub use box_sides::box_sides;
pub use error::{CoplanarContact, IntersectError};
pub use key::{Location, PointKey};

use contact::{Contact, Tri};
use geom::TriMesh;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// A named surface to intersect.
#[derive(Copy, Clone, Debug)]
pub struct SurfaceRef<'a> {
    pub name: &'a str,
    pub mesh: &'a TriMesh,
}

/// One point of an intersection curve: its key, coordinates, and its location on each surface
/// (what the splitting step needs to insert it).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CurvePoint {
    pub key: PointKey,
    pub xyz: [f64; 3],
    pub on_a: Location,
    pub on_b: Location,
}

/// One connected intersection curve. Open curves run between surface borders or branch points
/// (a curve that leaves a branch point and comes back to it repeats that point at both ends);
/// closed loops do not repeat their first point. `segments_faces[i]` is the pair (triangle of
/// `a`, triangle of `b`) containing segment `i`, which joins points `i` and `i + 1` (mod the
/// length for closed loops); when several pairs contain the same segment (an edge lying in the
/// other surface) the smallest pair is given.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct IntersectionCurve {
    pub points: Vec<CurvePoint>,
    pub closed: bool,
    pub segments_faces: Vec<(u32, u32)>,
}

/// The intersection of surfaces `a` and `b` (`a < b` by name).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Intersection {
    pub a: String,
    pub b: String,
    /// Canonical order: by their sequence of point keys (open curves start at the smaller end,
    /// closed loops at their smallest key).
    pub curves: Vec<IntersectionCurve>,
    /// Coplanar triangle pairs that touch only along their boundaries (informative; their
    /// common edges are part of the curves). Overlapping coplanar pairs are an error instead.
    pub coplanar: Vec<CoplanarContact>,
    /// Isolated contact points that belong to no curve (surfaces touching without crossing),
    /// sorted by key.
    pub touches: Vec<CurvePoint>,
    /// Zero-area triangles of `a` and of `b` met among the candidate pairs (skipped), sorted.
    pub degenerate_a: Vec<u32>,
    pub degenerate_b: Vec<u32>,
    /// Triangles the two surfaces hold in common (the same three points), as (triangle of `a`,
    /// triangle of `b`), sorted: `b` drops them, so no contact of them is computed, and the
    /// curves run where what `b` keeps meets `a` (the border of the common part among them).
    pub shared: Vec<(u32, u32)>,
}

fn check(s: &SurfaceRef) -> Result<(), IntersectError> {
    let m = s.mesh;
    if m.triangles.len() > u32::MAX as usize || m.vertices.len() > u32::MAX as usize {
        return Err(IntersectError::TooLarge {
            surface: s.name.to_string(),
            count: m.triangles.len(),
        });
    }
    for (t, tri) in m.triangles.iter().enumerate() {
        for &v in tri {
            match m.vertices.get(v as usize) {
                None => {
                    return Err(IntersectError::BadVertexIndex {
                        surface: s.name.to_string(),
                        triangle: t as u32,
                        vertex: v,
                        count: m.vertices.len(),
                    });
                }
                Some(p) if !p.iter().all(|c| c.is_finite()) => {
                    return Err(IntersectError::NonFinite {
                        surface: s.name.to_string(),
                        vertex: v,
                        xyz: *p,
                    });
                }
                Some(_) => {}
            }
        }
    }
    Ok(())
}

/// Triangle `t` of `m`; indices were checked by [`check`].
fn tri(m: &TriMesh, t: u32) -> Tri {
    let v = m.triangles[t as usize];
    Tri {
        index: t,
        v,
        p: [0, 1, 2].map(|k| m.vertices[v[k] as usize]),
    }
}

enum Outcome {
    Contact(Contact),
    DegenerateA,
    DegenerateB,
}

fn curve_point(key: PointKey, a: &TriMesh, b: &TriMesh) -> CurvePoint {
    let (on_a, on_b) = key.locations();
    CurvePoint {
        key,
        xyz: construct::point_xyz(&key, a, b),
        on_a,
        on_b,
    }
}

/// The exact intersection of two surfaces (see the module doc). Symmetric in its arguments.
pub fn intersect(s: SurfaceRef, t: SurfaceRef) -> Result<Intersection, IntersectError> {
    if s.name == t.name {
        return Err(IntersectError::SameSurface {
            name: s.name.to_string(),
        });
    }
    let (sa, sb) = if s.name < t.name { (s, t) } else { (t, s) };
    check(&sa)?;
    check(&sb)?;
    let (a, b) = (sa.mesh, sb.mesh);

    let pairs = candidates::candidate_pairs(a, b);
    let mut shared: Vec<(u32, u32)> = pairs
        .par_iter()
        .with_min_len(256)
        .filter(|&&(i, j)| shared::identical(a, i, b, j) && !locate::is_degenerate(&tri(a, i).p))
        .copied()
        .collect();
    shared.sort_unstable();
    let mut dropped: Vec<u32> = shared.iter().map(|&(_, j)| j).collect();
    dropped.sort_unstable();
    dropped.dedup();
    let outcomes: Vec<((u32, u32), Outcome)> = pairs
        .par_iter()
        .with_min_len(256)
        .filter(|&&(_, j)| dropped.binary_search(&j).is_err())
        .filter_map(|&(i, j)| {
            let (ta, tb) = (tri(a, i), tri(b, j));
            let out = if locate::is_degenerate(&ta.p) {
                Outcome::DegenerateA
            } else if locate::is_degenerate(&tb.p) {
                Outcome::DegenerateB
            } else {
                match contact::contact(&ta, &tb) {
                    Contact::None => return None,
                    c => Outcome::Contact(c),
                }
            };
            Some(((i, j), out))
        })
        .collect();

    let mut segments: Vec<(PointKey, PointKey, (u32, u32))> = Vec::new();
    let mut single: Vec<PointKey> = Vec::new();
    let mut overlaps = Vec::new();
    let mut coplanar = Vec::new();
    let (mut deg_a, mut deg_b) = (Vec::new(), Vec::new());
    for ((i, j), out) in outcomes {
        let c = match out {
            Outcome::DegenerateA => {
                deg_a.push(i);
                continue;
            }
            Outcome::DegenerateB => {
                deg_b.push(j);
                continue;
            }
            Outcome::Contact(c) => c,
        };
        let pts = match c {
            Contact::None => continue,
            Contact::CoplanarOverlap => {
                let (ta, tb) = (tri(a, i), tri(b, j));
                let axis = locate::projection_axis(&tb.p).map_or(2, |x| x.0);
                overlaps.push(CoplanarContact {
                    tri_a: i,
                    tri_b: j,
                    at: construct::coplanar_witness(&ta.p, &tb.p, axis),
                });
                continue;
            }
            Contact::Inconsistent => {
                let ta = tri(a, i);
                return Err(IntersectError::Inconsistent {
                    a: sa.name.to_string(),
                    b: sb.name.to_string(),
                    tri_a: i,
                    tri_b: j,
                    at: ta.p[0],
                });
            }
            Contact::CoplanarTouch(pts) => {
                let at = pts
                    .first()
                    .and_then(|&(la, lb)| PointKey::new(la, lb))
                    .map_or(tri(a, i).p[0], |k| construct::point_xyz(&k, a, b));
                coplanar.push(CoplanarContact {
                    tri_a: i,
                    tri_b: j,
                    at,
                });
                pts
            }
            Contact::Points(pts) => pts,
        };
        let keys: Vec<PointKey> = pts
            .iter()
            .filter_map(|&(la, lb)| PointKey::new(la, lb))
            .collect();
        match keys.as_slice() {
            [k] => single.push(*k),
            [k0, k1] => segments.push((*k0, *k1, (i, j))),
            _ => {}
        }
    }
    if !overlaps.is_empty() {
        return Err(IntersectError::Coplanar {
            a: sa.name.to_string(),
            b: sb.name.to_string(),
            contacts: overlaps,
        });
    }
    if !shared.is_empty()
        && let Some((angle, k)) = shared::redrawn(&segments, a, b)
    {
        return Err(IntersectError::Redrawn {
            a: sa.name.to_string(),
            b: sb.name.to_string(),
            shared: shared.len(),
            angle,
            at: construct::point_xyz(&k, a, b),
        });
    }
    deg_a.sort_unstable();
    deg_a.dedup();
    deg_b.sort_unstable();
    deg_b.dedup();

    let curves: Vec<IntersectionCurve> = assemble::assemble(&segments)
        .into_iter()
        .map(|c| IntersectionCurve {
            points: c.points.iter().map(|&k| curve_point(k, a, b)).collect(),
            closed: c.closed,
            segments_faces: c.faces,
        })
        .collect();

    let mut on_curves: Vec<PointKey> = segments.iter().flat_map(|s| [s.0, s.1]).collect();
    on_curves.sort_unstable();
    on_curves.dedup();
    single.sort_unstable();
    single.dedup();
    let touches = single
        .into_iter()
        .filter(|k| on_curves.binary_search(k).is_err())
        .map(|k| curve_point(k, a, b))
        .collect();

    Ok(Intersection {
        a: sa.name.to_string(),
        b: sb.name.to_string(),
        curves,
        coplanar,
        touches,
        degenerate_a: deg_a,
        degenerate_b: deg_b,
        shared,
    })
}
