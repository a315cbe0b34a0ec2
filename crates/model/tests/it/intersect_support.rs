//! Helpers shared by the `intersect_*` integration tests: surface generators, a runner that
//! intersects every pair in both orders and demands identical results, and a checker that every
//! curve point lies on both triangles its segment claims.
#![allow(dead_code)]

use geom::{Orientation, TriMesh, orient3d};
use model::intersect::split::SplitSurface;
use model::intersect::{CurvePoint, IntersectError, Intersection, Location, SurfaceRef, intersect};
use std::collections::BTreeMap;

/// A structured grid surface: `(nu + 1) × (nv + 1)` vertices `f(i, j)`, each cell split along
/// the diagonal from `(i, j)` to `(i + 1, j + 1)`.
pub fn grid(nu: usize, nv: usize, f: impl Fn(usize, usize) -> [f64; 3]) -> TriMesh {
    let mut vertices = Vec::with_capacity((nu + 1) * (nv + 1));
    for j in 0..=nv {
        for i in 0..=nu {
            vertices.push(f(i, j));
        }
    }
    let id = |i: usize, j: usize| (j * (nu + 1) + i) as u32;
    let mut triangles = Vec::with_capacity(2 * nu * nv);
    for j in 0..nv {
        for i in 0..nu {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::new(vertices, triangles)
}

/// Intersect `(na, a)` with `(nb, b)` in both argument orders, assert the results are identical,
/// check every curve, and return the result.
pub fn both(na: &str, a: &TriMesh, nb: &str, b: &TriMesh) -> Result<Intersection, IntersectError> {
    let r1 = intersect(
        SurfaceRef { name: na, mesh: a },
        SurfaceRef { name: nb, mesh: b },
    );
    let r2 = intersect(
        SurfaceRef { name: nb, mesh: b },
        SurfaceRef { name: na, mesh: a },
    );
    assert_eq!(
        r1, r2,
        "intersect({na}, {nb}) differs from intersect({nb}, {na})"
    );
    if let Ok(x) = &r1 {
        let (ma, mb) = if na < nb { (a, b) } else { (b, a) };
        check_points(x, ma, mb, 1e-6);
    }
    r1
}

fn corners(m: &TriMesh, t: u32) -> [[f64; 3]; 3] {
    let v = m.triangles[t as usize];
    [0, 1, 2].map(|k| m.vertices[v[k] as usize])
}

/// The location must be a face of triangle `t`'s closure.
fn location_in_triangle(l: Location, m: &TriMesh, t: u32) -> bool {
    let v = m.triangles[t as usize];
    match l {
        Location::Vertex(i) => v.contains(&i),
        Location::Edge(i, j) => v.contains(&i) && v.contains(&j),
        Location::Face(f) => f == t,
    }
}

fn plane_distance(c: &[[f64; 3]; 3], p: &[f64; 3]) -> f64 {
    let u = [c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2]];
    let v = [c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2]];
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let w = [p[0] - c[0][0], p[1] - c[0][1], p[2] - c[0][2]];
    ((n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) / len).abs()
}

fn check_on(p: &CurvePoint, own_vertex: Option<u32>, other: &[[f64; 3]; 3], tol: f64, what: &str) {
    if own_vertex.is_some() {
        assert_eq!(
            orient3d(&other[0], &other[1], &other[2], &p.xyz),
            Orientation::Zero,
            "{what}: vertex point {:?} is not exactly on the other triangle's plane",
            p.key
        );
    } else {
        let d = plane_distance(other, &p.xyz);
        assert!(
            d <= tol,
            "{what}: constructed point {:?} is {d} from the plane",
            p.key
        );
    }
}

/// Every segment's end points lie on both triangles of the segment: combinatorially (their
/// locations are faces of the triangles' closures) and geometrically (exactly for vertices,
/// within `tol` for constructed points).
pub fn check_points(x: &Intersection, a: &TriMesh, b: &TriMesh, tol: f64) {
    for (ci, c) in x.curves.iter().enumerate() {
        let n = c.points.len();
        let segs = if c.closed { n } else { n - 1 };
        assert_eq!(
            c.segments_faces.len(),
            segs,
            "curve {ci}: one face pair per segment"
        );
        for (s, &(ta, tb)) in c.segments_faces.iter().enumerate() {
            for p in [&c.points[s], &c.points[(s + 1) % n]] {
                assert!(
                    location_in_triangle(p.on_a, a, ta),
                    "curve {ci} seg {s}: {:?} not on a's triangle {ta}",
                    p.key
                );
                assert!(
                    location_in_triangle(p.on_b, b, tb),
                    "curve {ci} seg {s}: {:?} not on b's triangle {tb}",
                    p.key
                );
                let va = if let Location::Vertex(i) = p.on_a {
                    Some(i)
                } else {
                    None
                };
                let vb = if let Location::Vertex(i) = p.on_b {
                    Some(i)
                } else {
                    None
                };
                check_on(p, va, &corners(b, tb), tol, "on b");
                check_on(p, vb, &corners(a, ta), tol, "on a");
            }
        }
    }
}

fn normal(m: &TriMesh, t: usize) -> [f64; 3] {
    let [a, b, c] = m.corners(t);
    let (u, v) = (
        [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
        [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
    );
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

/// Conforming (each directed edge once, each edge in at most two triangles), same topology
/// (Euler characteristic), same area, children oriented like their parents, and every curve
/// segment an edge of the result.
pub fn assert_sound(original: &TriMesh, s: &SplitSurface) {
    let m = &s.mesh;
    let mut directed = BTreeMap::new();
    let mut undirected: BTreeMap<[u32; 2], usize> = BTreeMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            assert!(
                directed.insert((a, b), ()).is_none(),
                "directed edge {a}->{b} twice"
            );
            *undirected.entry([a.min(b), a.max(b)]).or_default() += 1;
        }
    }
    assert!(undirected.values().all(|&n| n <= 2));
    let used: std::collections::BTreeSet<u32> = m.triangles.iter().flatten().copied().collect();
    let euler = |v: usize, e: usize, f: usize| v as i64 - e as i64 + f as i64;
    let mut orig_edges = std::collections::BTreeSet::new();
    for t in &original.triangles {
        for k in 0..3 {
            orig_edges.insert([t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])]);
        }
    }
    let orig_used: std::collections::BTreeSet<u32> =
        original.triangles.iter().flatten().copied().collect();
    assert_eq!(
        euler(used.len(), undirected.len(), m.triangles.len()),
        euler(orig_used.len(), orig_edges.len(), original.triangles.len())
    );
    assert!((m.area() - original.area()).abs() <= 1e-9 * original.area());
    for (t, &p) in s.parent.iter().enumerate() {
        let (n, np) = (normal(m, t), normal(original, p as usize));
        assert!(
            n[0] * np[0] + n[1] * np[1] + n[2] * np[2] > 0.0,
            "triangle {t} flipped against parent {p}"
        );
    }
    for e in &s.curve_edges {
        assert!(
            undirected.contains_key(e),
            "curve segment {e:?} is not an edge"
        );
    }
}
