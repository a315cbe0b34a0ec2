//! Input validation for one region, before any tetrahedron is built: the mesher relies on a
//! closed, consistently and outward oriented, non-self-intersecting boundary, so each violation
//! is reported with the triangle(s) or edge and coordinates instead of surfacing later as a stuck
//! front. Intersections are decided with the exact tests of `geom::contact`, on the pairs of
//! overlapping boxes `geom::broad_phase` finds. The Delaunay path runs the
//! pairwise intersection test only when some triangle is not a face of the boundary's Delaunay
//! tetrahedralization (`check_shape`): on the peer model it was a fifth of a thin layer's time.

use super::inside::{Rays, boundary_vertices, one_per_group};
use super::{RegionInput, TetMeshError};
use geom::BBox;
use geom::broad_phase::overlapping_pairs;
use geom::contact::{Contact, Tri, triangle_contact, triangle_is_degenerate};

type P = [f64; 3];

/// Check closedness (every boundary edge used exactly twice, in opposite directions), orientation
/// (consistent, enclosing a positive volume), non-degenerate triangles, and that no two triangles
/// (boundary or embedded) intersect other than in shared vertices/edges (exact).
pub fn check_input(input: &RegionInput) -> Result<(), TetMeshError> {
    check_shape(input)?;
    check_embedded_inside(input)?;
    check_intersections(input)
}

/// [`check_input`] without the intersection test: what the Delaunay path checks first. It needs
/// the intersection test only when a triangle is not a face of the boundary's Delaunay
/// tetrahedralization: the faces of a valid tetrahedralization meet only in shared vertices and
/// edges, so triangles that are all faces cannot cross, touch improperly or overlap.
pub(crate) fn check_shape(input: &RegionInput) -> Result<(), TetMeshError> {
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
    let (all, named) = all_triangles(input);
    for (k, &t) in all.iter().enumerate() {
        let (kind, i) = named(k);
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
        let (lo, hi, at) = extent(&input.vertices, &input.boundary);
        return err(
            format!(
                "the boundary encloses a non-positive volume ({vol}) within ({}, {}, {}) to \
                 ({}, {}, {}): it must be oriented with normals pointing out of the region; \
                 where the region is a thin pocket between two surfaces, one most likely \
                 crosses the other and back there (noisy data: smooth or mend the surface)",
                lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
            ),
            Some(at),
        );
    }
    Ok(())
}

/// The box of the vertices of `tris` (low and high corners) and the vertex of theirs nearest
/// its centre (the first on ties): a place on the boundary to name.
fn extent(pts: &[P], tris: &[[u32; 3]]) -> (P, P, P) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for &v in tris.iter().flatten() {
        for k in 0..3 {
            lo[k] = lo[k].min(pts[v as usize][k]);
            hi[k] = hi[k].max(pts[v as usize][k]);
        }
    }
    let centre = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
    let d2 = |p: &P| (0..3).map(|k| (p[k] - centre[k]).powi(2)).sum::<f64>();
    let at = (tris.iter().flatten())
        .map(|&v| pts[v as usize])
        .min_by(|a, b| d2(a).total_cmp(&d2(b)))
        .unwrap_or(centre);
    (lo, hi, at)
}

/// Every embedded triangle lies inside the region, decided exactly for one triangle of each
/// group joined at vertices off the boundary (`inside::one_per_group`): the ray parity from a
/// point of the triangle next to its first corner, towards its centroid. A surface that lies
/// wholly outside (another region's fault, or a cavity's body given as embedded) would send the
/// mesher searching for minutes. A triangle crossing the boundary is the intersection test's
/// to report (run first when a test point lies outside); one whose test point lies on the
/// boundary is left to it too.
pub(crate) fn check_embedded_inside(input: &RegionInput) -> Result<(), TetMeshError> {
    let pts = &input.vertices;
    let on_boundary = boundary_vertices(pts.len(), &input.boundary);
    let rays = Rays::new(pts, &input.boundary);
    for k in one_per_group(&input.embedded, &on_boundary) {
        let t = input.embedded[k];
        let [a, b, c] = t.map(|v| pts[v as usize]);
        let centroid = [0, 1, 2].map(|i| (a[i] + b[i] + c[i]) / 3.0);
        if rays.segment_inside(&a, &centroid) == Some(false) {
            // Part of a triangle crossing the boundary is outside too: that crossing is the
            // cause to name.
            check_intersections(input)?;
            return Err(TetMeshError::new(
                &input.name,
                format!(
                    "embedded triangle {k} {t:?} ({a:?}, {b:?}, {c:?}) lies outside the region: \
                     an embedded surface (a dangling fault) must lie inside the region it is \
                     embedded in"
                ),
                Some(a),
            ));
        }
    }
    Ok(())
}

/// No two triangles (boundary or embedded) meet other than in shared vertices and edges.
pub(crate) fn check_intersections(input: &RegionInput) -> Result<(), TetMeshError> {
    let (all, named) = all_triangles(input);
    check_self_intersection(input, &all, named)
}

/// The boundary triangles then the embedded ones, and the kind and index of the `k`-th of them
/// (for messages).
fn all_triangles(
    input: &RegionInput,
) -> (
    Vec<[u32; 3]>,
    impl Fn(usize) -> (&'static str, usize) + use<>,
) {
    let all = input
        .boundary
        .iter()
        .chain(&input.embedded)
        .copied()
        .collect();
    let nb = input.boundary.len();
    let named = move |k: usize| {
        if k < nb {
            ("boundary", k)
        } else {
            ("embedded", k - nb)
        }
    };
    (all, named)
}

/// Every boundary triangle once, and every directed edge matched by exactly one opposite edge.
/// Sorted vectors, not maps of lists: on a thin layer (about one boundary triangle per tet) a map
/// with a list per edge was the mesher's largest allocation.
fn check_closed(input: &RegionInput) -> Result<(), TetMeshError> {
    let fail = |m: String, v: u32| {
        Err(TetMeshError::new(
            &input.name,
            m,
            Some(input.vertices[v as usize]),
        ))
    };
    let mut faces: Vec<([u32; 3], u32)> = input
        .boundary
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let mut s = *t;
            s.sort_unstable();
            (s, i as u32)
        })
        .collect();
    faces.sort_unstable();
    // The first repeat in triangle order: the smallest second index of a run, with the first.
    if let Some((j, i)) = faces
        .windows(2)
        .filter(|w| w[0].0 == w[1].0)
        .map(|w| (w[0].1, w[1].1))
        .min_by_key(|&(_, i)| i)
    {
        let t = input.boundary[i as usize];
        return fail(
            format!("boundary triangles {j} and {i} use the same vertices {t:?}"),
            t[0],
        );
    }
    drop(faces);
    let mut directed: Vec<(u32, u32, u32)> = Vec::with_capacity(3 * input.boundary.len());
    for (i, t) in input.boundary.iter().enumerate() {
        for e in 0..3 {
            directed.push((t[e], t[(e + 1) % 3], i as u32));
        }
    }
    directed.sort_unstable();
    // Every edge reversed, sorted too: the opposites of the runs, in the runs' order, are found
    // by one forward merge instead of a binary search each.
    let mut reversed: Vec<(u32, u32)> = directed.iter().map(|r| (r.1, r.0)).collect();
    reversed.sort_unstable();
    let mut at = 0;
    let runs = directed.chunk_by(|a, b| (a.0, a.1) == (b.0, b.1));
    for run in runs {
        let (u, v) = (run[0].0, run[0].1);
        let to = input.vertices[v as usize];
        if run.len() > 1 {
            let tris: Vec<u32> = run.iter().map(|r| r.2).collect();
            return fail(
                format!(
                    "boundary edge {u}-{v} (to {to:?}) is traversed in the same direction by triangles {tris:?}: inconsistent orientation or non-manifold edge"
                ),
                u,
            );
        }
        while reversed.get(at).is_some_and(|&r| r < (u, v)) {
            at += 1;
        }
        let opposite = reversed[at..].iter().take_while(|&&r| r == (u, v)).count();
        if opposite != 1 {
            return fail(
                format!(
                    "the boundary is not closed: edge {u}-{v} (to {to:?}) of triangle {} has no opposite triangle",
                    run[0].2
                ),
                u,
            );
        }
    }
    Ok(())
}

/// Signed volume enclosed by outward triangles (float measure, reference point at the centroid of
/// the vertices to limit cancellation at UTM magnitudes).
pub(crate) fn enclosed_volume(pts: &[P], tris: &[[u32; 3]]) -> f64 {
    enclosed_volume_bounded(pts, tris).0
}

/// [`enclosed_volume`] and a bound on its rounding error: the sum of the triangles' cones from
/// the reference point, each with [`Rounded::add`]'s bound.
pub(crate) fn enclosed_volume_bounded(pts: &[P], tris: &[[u32; 3]]) -> (f64, f64) {
    let o = reference_point(pts);
    let mut sum = Rounded::default();
    for t in tris {
        let [a, b, c] = t.map(|i| pts[i as usize]);
        sum.add(&o, &a, &b, &c);
    }
    (sum.volume, sum.bound())
}

/// A running sum of tets' signed volumes with a bound on its floating-point error: each
/// volume's determinant is off by at most a few units in the last place of its permanent (the
/// determinant with every product taken positive, as in Shewchuk's error bounds), and the sum of
/// `n` terms by at most `n` units in the last place of the sum of their magnitudes. Two volume
/// sums of one region that must agree exactly in real arithmetic are compared within their
/// bounds, so a thin region far smaller than its coordinates does not fail on rounding alone.
#[derive(Default)]
pub(crate) struct Rounded {
    pub volume: f64,
    magnitude: f64,
    permanent: f64,
    terms: f64,
}

impl Rounded {
    /// Adds the signed volume of tet `abcd`, as [`geom::predicates::signed_volume`] takes it.
    pub fn add(&mut self, a: &P, b: &P, c: &P, d: &P) {
        let v = geom::predicates::signed_volume(a, b, c, d);
        let [u, w, x] = [b, c, d].map(|q| [q[0] - a[0], q[1] - a[1], q[2] - a[2]]);
        let abs = |p: [f64; 3]| p.map(f64::abs);
        let [u, w, x] = [abs(u), abs(w), abs(x)];
        let perm = u[0] * (w[1] * x[2] + w[2] * x[1])
            + u[1] * (w[0] * x[2] + w[2] * x[0])
            + u[2] * (w[0] * x[1] + w[1] * x[0]);
        self.volume += v;
        self.magnitude += v.abs();
        self.permanent += perm / 6.0;
        self.terms += 1.0;
    }

    /// The bound on the error of [`Rounded::volume`].
    pub fn bound(&self) -> f64 {
        f64::EPSILON * (8.0 * self.permanent + self.terms * self.magnitude)
    }
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

/// No two triangles meet improperly; the first pair that does, in (k, j) order, is reported.
fn check_self_intersection(
    input: &RegionInput,
    all: &[[u32; 3]],
    named: impl Fn(usize) -> (&'static str, usize),
) -> Result<(), TetMeshError> {
    let pts = &input.vertices;
    let boxes: Vec<BBox> = all
        .iter()
        .map(|t| BBox::from_points(t.map(|v| &pts[v as usize])))
        .collect();
    // With whether the two use the same vertices.
    let bad = overlapping_pairs(&boxes, |k, j| {
        let (t, u) = (all[k as usize], all[j as usize]);
        let same = t.iter().all(|v| u.contains(v));
        let meet = || triangle_contact(&Tri::of(t, pts), &Tri::of(u, pts)) != Contact::None;
        (same || meet()).then_some(same)
    });
    let first = bad
        .first()
        .map(|&(k, j, same)| (k as usize, j as usize, same));
    let Some((k, j, same)) = first else {
        return Ok(());
    };
    let (t, u) = (all[k], all[j]);
    let (kind, i) = named(k);
    let (kind2, i2) = named(j);
    if same {
        return Err(TetMeshError::new(
            &input.name,
            format!(
                "{kind} triangle {i} {t:?} and {kind2} triangle {i2} {u:?} use the same vertices"
            ),
            Some(pts[t[0] as usize]),
        ));
    }
    Err(TetMeshError::new(
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
        Some(pts[t[0] as usize]),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The four outward faces of the tetrahedron `v` (by the sign of each face's volume with the
    /// opposite vertex).
    fn tet_shell(pts: &[P], v: [u32; 4]) -> Vec<[u32; 3]> {
        (0..4)
            .map(|k| {
                let f = [v[(k + 1) % 4], v[(k + 2) % 4], v[(k + 3) % 4]];
                let [a, b, c] = f.map(|i| pts[i as usize]);
                let d = pts[v[k] as usize];
                if geom::predicates::signed_volume(&a, &b, &c, &d) > 0.0 {
                    [f[0], f[2], f[1]]
                } else {
                    f
                }
            })
            .collect()
    }

    /// Two centimetre tetrahedra at UTM coordinates, the second shifted by `shift`.
    fn two_tets(shift: f64) -> RegionInput {
        let o = [500_000.123, 7_000_000.456, -1_234.5];
        let corner = |d: [f64; 3], s: f64| [o[0] + d[0] + s, o[1] + d[1] + s, o[2] + d[2] + s];
        let unit = [
            [0.0, 0.0, 0.0],
            [0.01, 0.0, 0.0],
            [0.0, 0.01, 0.0],
            [0.0, 0.0, 0.01],
        ];
        let mut vertices: Vec<P> = unit.iter().map(|&d| corner(d, 0.0)).collect();
        vertices.extend(unit.iter().map(|&d| corner(d, shift)));
        let mut boundary = tet_shell(&vertices, [0, 1, 2, 3]);
        boundary.extend(tet_shell(&vertices, [4, 5, 6, 7]));
        RegionInput {
            name: "two".into(),
            vertices,
            boundary,
            embedded: vec![],
            lines: Vec::new(),
        }
    }

    #[test]
    fn two_centimetre_shells_crossing_at_utm_coordinates_are_found_and_apart_they_pass() {
        let e = check_input(&two_tets(0.002)).unwrap_err();
        assert!(e.message.contains("self-intersection"), "{e}");
        check_input(&two_tets(0.02)).expect("disjoint shells are valid");
    }

    #[test]
    fn a_repeated_boundary_triangle_names_the_first_repeat_in_triangle_order() {
        let mut input = two_tets(0.02);
        let t = input.boundary[1];
        input.boundary.push([t[1], t[2], t[0]]);
        input.boundary.push(input.boundary[5]);
        let e = check_input(&input).unwrap_err();
        assert!(
            e.message
                .contains("boundary triangles 1 and 8 use the same vertices"),
            "{e}"
        );
    }

    #[test]
    fn an_edge_traversed_twice_the_same_way_names_both_triangles() {
        let mut input = two_tets(0.02);
        // Turn one shell's face round: its three edges now run the same way as a neighbour's.
        input.boundary[6].swap(1, 2);
        let e = check_input(&input).unwrap_err();
        assert!(e.message.contains("same direction by triangles"), "{e}");
        assert!(
            e.message.contains(", 6]") || e.message.contains("[6,"),
            "{e}"
        );
        assert!(e.at.is_some());
    }
}
