//! How near a point is to a patch: whether it lies exactly on one of its triangles (exact
//! predicates), and its distance to the patch (floating point, a measure, computed relative to
//! the point so that UTM-sized coordinates keep their precision).

use geom::predicates::{cross, dot, sub};
use geom::{Orientation, TriMesh, orient2d, orient3d};

/// Whether `p` lies on the closed triangle `abc`, exactly: coplanar by `orient3d`, then inside
/// or on the border in a projection where the triangle keeps a non-zero area. A degenerate
/// triangle (zero area in every projection) holds nothing.
pub fn on_triangle(p: &[f64; 3], a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> bool {
    if orient3d(a, b, c, p) != Orientation::Zero {
        return false;
    }
    for axis in 0..3 {
        let drop = |q: &[f64; 3]| match axis {
            0 => [q[1], q[2]],
            1 => [q[2], q[0]],
            _ => [q[0], q[1]],
        };
        let (a2, b2, c2, p2) = (drop(a), drop(b), drop(c), drop(p));
        let turn = orient2d(&a2, &b2, &c2);
        if turn == Orientation::Zero {
            continue;
        }
        return [(&a2, &b2), (&b2, &c2), (&c2, &a2)]
            .iter()
            .all(|(u, v)| orient2d(u, v, &p2) != turn.flip());
    }
    false
}

/// The distance from the origin to the segment `ab`.
fn segment_distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let ab = sub(b, a);
    let len2 = dot(&ab, &ab);
    let t = if len2 > 0.0 {
        (-dot(a, &ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = [a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]];
    dot(&q, &q).sqrt()
}

/// The distance from `p` to the closed triangle `abc`: to its plane when the foot of the
/// perpendicular falls inside, else to the nearest edge.
pub fn triangle_distance(p: &[f64; 3], a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> f64 {
    let (a, b, c) = (sub(a, p), sub(b, p), sub(c, p));
    let n = cross(&sub(&b, &a), &sub(&c, &a));
    let n2 = dot(&n, &n);
    if n2 > 0.0 {
        // The foot is inside when it sees every edge turning the same way as the normal.
        let h = dot(&a, &n) / n2;
        let f = [h * n[0], h * n[1], h * n[2]];
        let inside = [(&a, &b), (&b, &c), (&c, &a)]
            .iter()
            .all(|(u, v)| dot(&cross(&sub(v, u), &sub(&f, u)), &n) >= 0.0);
        if inside {
            return dot(&f, &f).sqrt();
        }
    }
    segment_distance(&a, &b)
        .min(segment_distance(&b, &c))
        .min(segment_distance(&c, &a))
}

/// How near `p` is to a patch: exactly on it, and the smallest distance to its triangles.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Nearness {
    pub exact: bool,
    pub distance: f64,
}

/// [`Nearness`] of `p` to `mesh` (whose indices the caller has checked).
pub fn nearness(p: &[f64; 3], mesh: &TriMesh) -> Nearness {
    let mut out = Nearness {
        exact: false,
        distance: f64::INFINITY,
    };
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t);
        if on_triangle(p, a, b, c) {
            return Nearness {
                exact: true,
                distance: 0.0,
            };
        }
        out.distance = out.distance.min(triangle_distance(p, a, b, c));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: [f64; 3] = [500_000.0, 7_000_000.0, -100.0];
    const B: [f64; 3] = [500_010.0, 7_000_000.0, -100.0];
    const C: [f64; 3] = [500_000.0, 7_000_010.0, -100.0];

    #[test]
    fn a_point_on_an_edge_is_on_the_triangle_and_one_just_beyond_is_not() {
        assert!(on_triangle(&[500_005.0, 7_000_000.0, -100.0], &A, &B, &C));
        assert!(on_triangle(&[500_002.0, 7_000_002.0, -100.0], &A, &B, &C));
        assert!(!on_triangle(&[500_005.0, 6_999_999.5, -100.0], &A, &B, &C));
        assert!(!on_triangle(&[500_002.0, 7_000_002.0, -99.5], &A, &B, &C));
    }

    #[test]
    fn distances_go_to_the_plane_inside_and_to_the_nearest_edge_or_corner_outside() {
        let d = triangle_distance(&[500_002.0, 7_000_002.0, -97.0], &A, &B, &C);
        assert!((d - 3.0).abs() < 1e-9, "{d}");
        let d = triangle_distance(&[500_005.0, 6_999_996.0, -100.0], &A, &B, &C);
        assert!((d - 4.0).abs() < 1e-9, "{d}");
        let d = triangle_distance(&[499_997.0, 6_999_996.0, -100.0], &A, &B, &C);
        assert!((d - 5.0).abs() < 1e-9, "{d}");
    }
}
