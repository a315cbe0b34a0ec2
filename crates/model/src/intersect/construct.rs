//! Coordinates of intersection points, constructed from their symbolic keys alone (so a point
//! has one set of coordinates however many triangle pairs found it). Vertices are copied
//! bit-for-bit; an edge crossing a face is placed with the seed's eq. 3, the ratio of the signed
//! volumes of the edge's endpoints over the face, computed relative to the face's first corner
//! so that UTM-sized coordinates do not swamp metre-sized triangles; an edge crossing an edge
//! uses the closest point of the two lines, relative to the first edge's first endpoint. These
//! floats are measures only: no decision is ever taken with them.

use super::key::{Location, PointKey};
use geom::TriMesh;
use geom::predicates::{cross, dot, sub};

fn vtx(m: &TriMesh, i: u32) -> [f64; 3] {
    m.vertices.get(i as usize).copied().unwrap_or([f64::NAN; 3])
}

fn lerp(p: &[f64; 3], q: &[f64; 3], t: f64) -> [f64; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.5
    };
    [
        p[0] + t * (q[0] - p[0]),
        p[1] + t * (q[1] - p[1]),
        p[2] + t * (q[2] - p[2]),
    ]
}

/// Seed eq. 3: where edge `pq` crosses the plane of triangle `t`, with the signed volumes taken
/// relative to `t`'s first corner.
fn edge_face(p: &[f64; 3], q: &[f64; 3], m: &TriMesh, t: u32) -> [f64; 3] {
    let Some(tri) = m.triangles.get(t as usize) else {
        return lerp(p, q, 0.5);
    };
    let o = vtx(m, tri[0]);
    let b = sub(&vtx(m, tri[1]), &o);
    let c = sub(&vtx(m, tri[2]), &o);
    let n = cross(&b, &c);
    let vp = dot(&n, &sub(p, &o));
    let vq = dot(&n, &sub(q, &o));
    lerp(p, q, vp / (vp - vq))
}

/// Closest point on line `pq` to line `rs` (the two edges cross, so this is their common point).
fn edge_edge(p: &[f64; 3], q: &[f64; 3], r: &[f64; 3], s: &[f64; 3]) -> [f64; 3] {
    let d1 = sub(q, p);
    let d2 = sub(s, r);
    let w = sub(p, r);
    let (a, b, c) = (dot(&d1, &d1), dot(&d1, &d2), dot(&d2, &d2));
    let (d, e) = (dot(&d1, &w), dot(&d2, &w));
    let den = a * c - b * b;
    lerp(p, q, (b * e - c * d) / den)
}

/// The coordinates of the point named `key`, between surfaces `a` and `b`.
pub fn point_xyz(key: &PointKey, a: &TriMesh, b: &TriMesh) -> [f64; 3] {
    match key.locations() {
        (Location::Vertex(i), _) => vtx(a, i),
        (_, Location::Vertex(j)) => vtx(b, j),
        (Location::Edge(i, j), Location::Face(t)) => edge_face(&vtx(a, i), &vtx(a, j), b, t),
        (Location::Face(t), Location::Edge(i, j)) => edge_face(&vtx(b, i), &vtx(b, j), a, t),
        (Location::Edge(i, j), Location::Edge(k, l)) => {
            edge_edge(&vtx(a, i), &vtx(a, j), &vtx(b, k), &vtx(b, l))
        }
        (Location::Face(_), Location::Face(_)) => [f64::NAN; 3],
    }
}

/// A point of the common part of two coplanar triangles whose interiors overlap, for the error
/// report: the mean of the corners of each lying in the other and of the proper crossings of
/// their edges (all of which lie in the convex common part, hence so does their mean).
pub fn coplanar_witness(t: &[[f64; 3]; 3], u: &[[f64; 3]; 3], axis: usize) -> [f64; 3] {
    use super::locate::{locate_coplanar, project, projection_axis};
    use geom::{Orientation, orient2d};
    let mut pts: Vec<[f64; 3]> = Vec::new();
    if let (Some((at, st)), Some((au, su))) = (projection_axis(t), projection_axis(u)) {
        pts.extend(t.iter().filter(|p| locate_coplanar(u, au, su, p).is_some()));
        pts.extend(u.iter().filter(|p| locate_coplanar(t, at, st, p).is_some()));
    }
    for i in 0..3 {
        let (p, q) = (&t[i], &t[(i + 1) % 3]);
        let (p2, q2) = (project(p, axis), project(q, axis));
        for j in 0..3 {
            let (r, s) = (&u[j], &u[(j + 1) % 3]);
            let (r2, s2) = (project(r, axis), project(s, axis));
            let (o1, o2) = (orient2d(&p2, &q2, &r2), orient2d(&p2, &q2, &s2));
            let (o3, o4) = (orient2d(&r2, &s2, &p2), orient2d(&r2, &s2, &q2));
            let proper = o1 != Orientation::Zero
                && o2 == o1.flip()
                && o3 != Orientation::Zero
                && o4 == o3.flip();
            if proper {
                // 2D line intersection, relative to p.
                let d = [q2[0] - p2[0], q2[1] - p2[1]];
                let e = [s2[0] - r2[0], s2[1] - r2[1]];
                let w = [r2[0] - p2[0], r2[1] - p2[1]];
                let den = d[0] * e[1] - d[1] * e[0];
                pts.push(lerp(p, q, (w[0] * e[1] - w[1] * e[0]) / den));
            }
        }
    }
    if pts.is_empty() {
        pts.extend(t.iter());
    }
    let n = pts.len() as f64;
    let o = pts[0];
    let mut m = [0.0; 3];
    for p in &pts {
        for k in 0..3 {
            m[k] += (p[k] - o[k]) / n;
        }
    }
    [o[0] + m[0], o[1] + m[1], o[2] + m[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_edge_crossing_a_face_at_utm_magnitudes_is_placed_to_the_micrometre() {
        let o = [512_345.125, 7_012_345.5, -1234.25];
        let b = TriMesh::new(
            vec![o, [o[0] + 4.0, o[1], o[2]], [o[0], o[1] + 4.0, o[2]]],
            vec![[0, 1, 2]],
        );
        let a = TriMesh::new(
            vec![
                [o[0] + 1.0, o[1] + 1.0, o[2] - 1.0],
                [o[0] + 1.0, o[1] + 1.0, o[2] + 3.0],
            ],
            vec![],
        );
        let x = point_xyz(&PointKey::EdgeFace { a: (0, 1), b: 0 }, &a, &b);
        assert!((x[2] - o[2]).abs() < 1e-6, "{x:?}");
        assert_eq!([x[0], x[1]], [o[0] + 1.0, o[1] + 1.0]);
    }

    #[test]
    fn two_crossing_edges_meet_at_their_common_point() {
        let a = TriMesh::new(vec![[0.0, 0.0, 0.0], [2.0, 2.0, 0.0]], vec![]);
        let b = TriMesh::new(vec![[0.0, 2.0, 0.0], [2.0, 0.0, 0.0]], vec![]);
        let x = point_xyz(
            &PointKey::EdgeEdge {
                a: (0, 1),
                b: (0, 1),
            },
            &a,
            &b,
        );
        assert!(
            (x[0] - 1.0).abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12,
            "{x:?}"
        );
    }
}
