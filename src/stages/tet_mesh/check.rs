//! Input validation for one region, before any tetrahedron is built: the mesher relies on a
//! closed, consistently and outward oriented, non-self-intersecting boundary, so each violation
//! is reported with the triangle(s) or edge and coordinates instead of surfacing later as a stuck
//! front. Intersections are decided with the exact tests of `exact`.

use std::collections::BTreeMap;

use rstar::{AABB, RTree, primitives::GeomWithData, primitives::Rectangle};

use super::exact::{tri_tri_improper, triangle_is_degenerate};
use super::{RegionInput, TetMeshError};

type P = [f64; 3];

/// Check closedness (every boundary edge used exactly twice, in opposite directions), orientation
/// (consistent, enclosing a positive volume), non-degenerate triangles, and that no two triangles
/// (boundary or embedded) intersect other than in shared vertices/edges (exact).
pub fn check_input(input: &RegionInput) -> Result<(), TetMeshError> {
    let name = &input.name;
    let err = |m: String, at: Option<P>| Err(TetMeshError::new(name, m, at));
    let n = input.vertices.len();
    if n > u32::MAX as usize - 1 {
        return err(format!("too many vertices ({n})"), None);
    }
    for (i, p) in input.vertices.iter().enumerate() {
        if !p.iter().all(|c| c.is_finite()) {
            return err(
                format!("vertex {i} has a non-finite coordinate {p:?}"),
                None,
            );
        }
    }
    if input.boundary.is_empty() {
        return err("the boundary has no triangles".into(), None);
    }
    let all: Vec<(&str, usize, [u32; 3])> = input
        .boundary
        .iter()
        .enumerate()
        .map(|(i, t)| ("boundary", i, *t))
        .chain(
            input
                .embedded
                .iter()
                .enumerate()
                .map(|(i, t)| ("embedded", i, *t)),
        )
        .collect();
    for &(kind, i, t) in &all {
        if let Some(&v) = t.iter().find(|&&v| v as usize >= n) {
            return err(
                format!(
                    "{kind} triangle {i} {t:?} refers to vertex {v}, but there are only {n} vertices"
                ),
                None,
            );
        }
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return err(
                format!("{kind} triangle {i} {t:?} repeats a vertex"),
                Some(input.vertices[t[0] as usize]),
            );
        }
        let [a, b, c] = t.map(|v| input.vertices[v as usize]);
        if triangle_is_degenerate(&a, &b, &c) {
            return err(
                format!("{kind} triangle {i} {t:?} is degenerate (collinear vertices)"),
                Some(a),
            );
        }
    }
    check_closed(input)?;
    let vol = enclosed_volume(&input.vertices, &input.boundary);
    if vol.is_nan() || vol <= 0.0 {
        return err(
            format!(
                "the boundary encloses a non-positive volume ({vol}): it must be oriented with normals pointing out of the region"
            ),
            None,
        );
    }
    check_self_intersection(input, &all)
}

fn check_closed(input: &RegionInput) -> Result<(), TetMeshError> {
    let mut directed: BTreeMap<(u32, u32), Vec<usize>> = BTreeMap::new();
    let mut faces: BTreeMap<[u32; 3], usize> = BTreeMap::new();
    for (i, t) in input.boundary.iter().enumerate() {
        let mut s = *t;
        s.sort_unstable();
        if let Some(j) = faces.insert(s, i) {
            return Err(TetMeshError::new(
                &input.name,
                format!("boundary triangles {j} and {i} use the same vertices {t:?}"),
                Some(input.vertices[t[0] as usize]),
            ));
        }
        for e in 0..3 {
            directed.entry((t[e], t[(e + 1) % 3])).or_default().push(i);
        }
    }
    for (&(u, v), tris) in &directed {
        let at = Some(input.vertices[u as usize]);
        if tris.len() > 1 {
            return Err(TetMeshError::new(
                &input.name,
                format!(
                    "boundary edge {u}-{v} (to {:?}) is traversed in the same direction by triangles {tris:?}: inconsistent orientation or non-manifold edge",
                    input.vertices[v as usize]
                ),
                at,
            ));
        }
        match directed.get(&(v, u)) {
            Some(r) if r.len() == 1 => {}
            _ => {
                return Err(TetMeshError::new(
                    &input.name,
                    format!(
                        "the boundary is not closed: edge {u}-{v} (to {:?}) of triangle {} has no opposite triangle",
                        input.vertices[v as usize], tris[0]
                    ),
                    at,
                ));
            }
        }
    }
    Ok(())
}

/// Signed volume enclosed by outward triangles (float measure, reference point at the centroid of
/// the vertices to limit cancellation at UTM magnitudes).
pub(crate) fn enclosed_volume(pts: &[P], tris: &[[u32; 3]]) -> f64 {
    let o = reference_point(pts);
    let mut v = 0.0;
    for t in tris {
        let [a, b, c] = t.map(|i| pts[i as usize]);
        v += crate::geom::predicates::signed_volume(&o, &a, &b, &c);
    }
    v
}

pub(crate) fn reference_point(pts: &[P]) -> P {
    let mut o = [0.0; 3];
    for p in pts {
        for k in 0..3 {
            o[k] += p[k];
        }
    }
    let n = pts.len().max(1) as f64;
    [o[0] / n, o[1] / n, o[2] / n]
}

fn check_self_intersection(
    input: &RegionInput,
    all: &[(&str, usize, [u32; 3])],
) -> Result<(), TetMeshError> {
    let pts = &input.vertices;
    let boxes: Vec<GeomWithData<Rectangle<P>, usize>> = all
        .iter()
        .enumerate()
        .map(|(k, &(_, _, t))| {
            let (lo, hi) = bbox(t, pts);
            GeomWithData::new(Rectangle::from_corners(lo, hi), k)
        })
        .collect();
    let tree = RTree::bulk_load(boxes);
    for (k, &(kind, i, t)) in all.iter().enumerate() {
        let (lo, hi) = bbox(t, pts);
        let mut hits: Vec<usize> = tree
            .locate_in_envelope_intersecting(AABB::from_corners(lo, hi))
            .map(|g| g.data)
            .filter(|&j| j > k)
            .collect();
        hits.sort_unstable();
        for j in hits {
            let (kind2, i2, u) = all[j];
            let mut a = t;
            let mut b = u;
            a.sort_unstable();
            b.sort_unstable();
            if a == b {
                return Err(TetMeshError::new(
                    &input.name,
                    format!(
                        "{kind} triangle {i} {t:?} and {kind2} triangle {i2} {u:?} use the same vertices"
                    ),
                    Some(pts[t[0] as usize]),
                ));
            }
            if tri_tri_improper(t, u, pts) {
                let at = pts[t[0] as usize];
                return Err(TetMeshError::new(
                    &input.name,
                    format!(
                        "self-intersection: {kind} triangle {i} {t:?} ({:?}, {:?}, {:?}) intersects {kind2} triangle {i2} {u:?} ({:?}, {:?}, {:?})",
                        pts[t[0] as usize],
                        pts[t[1] as usize],
                        pts[t[2] as usize],
                        pts[u[0] as usize],
                        pts[u[1] as usize],
                        pts[u[2] as usize]
                    ),
                    Some(at),
                ));
            }
        }
    }
    Ok(())
}

fn bbox(t: [u32; 3], pts: &[P]) -> (P, P) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &v in &t {
        let p = pts[v as usize];
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}
