//! Exact triangle–triangle intersection for the self-intersection and coplanar-overlap checks.
//!
//! Every decision is a sign of `orient3d` or `orient2d`; coplanar configurations are projected on
//! an axis plane where the triangle keeps a non-zero area (dropping a coordinate is exact), and
//! collinear overlaps are settled by exact coordinate comparisons. Triangles are non-degenerate.
//!
//! Pairs that share canonical vertices are judged by what they share: a shared edge only counts
//! when the two triangles are coplanar and fold onto the same side of it; a shared vertex only
//! counts when the triangles meet elsewhere too (the opposite side of one meets the other).

use geom::{Orientation, orient2d, orient3d};

type P = [f64; 3];

/// How two triangles meet.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Contact {
    None,
    /// They cross or touch beyond what they share, not in one plane.
    Crossing,
    /// They lie in one plane and overlap beyond what they share.
    CoplanarOverlap,
}

fn mixed(s: [Orientation; 3]) -> bool {
    s.contains(&Orientation::Positive) && s.contains(&Orientation::Negative)
}

/// The axis to drop so that the projection of the non-degenerate triangle `abc` has non-zero area.
fn drop_axis(a: &P, b: &P, c: &P) -> usize {
    for k in [2, 0, 1] {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        if orient2d(&[a[i], a[j]], &[b[i], b[j]], &[c[i], c[j]]) != Orientation::Zero {
            return k;
        }
    }
    2
}

fn proj(p: &P, k: usize) -> [f64; 2] {
    [p[(k + 1) % 3], p[(k + 2) % 3]]
}

fn on_segment_2d(p: &[f64; 2], q: &[f64; 2], r: &[f64; 2]) -> bool {
    // r is collinear with pq: inside the closed segment iff inside its box.
    r[0] >= p[0].min(q[0])
        && r[0] <= p[0].max(q[0])
        && r[1] >= p[1].min(q[1])
        && r[1] <= p[1].max(q[1])
}

/// Closed segment–segment intersection in the plane.
fn seg_seg_2d(p: &[f64; 2], q: &[f64; 2], a: &[f64; 2], b: &[f64; 2]) -> bool {
    let d1 = orient2d(p, q, a);
    let d2 = orient2d(p, q, b);
    let d3 = orient2d(a, b, p);
    let d4 = orient2d(a, b, q);
    use Orientation::Zero;
    if d1 != Zero && d2 != Zero && d1 != d2 && d3 != Zero && d4 != Zero && d3 != d4 {
        return true;
    }
    (d1 == Zero && on_segment_2d(p, q, a))
        || (d2 == Zero && on_segment_2d(p, q, b))
        || (d3 == Zero && on_segment_2d(a, b, p))
        || (d4 == Zero && on_segment_2d(a, b, q))
}

fn point_in_tri_2d(p: &[f64; 2], a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> bool {
    !mixed([orient2d(a, b, p), orient2d(b, c, p), orient2d(c, a, p)])
}

/// Closed segment `pq` against closed triangle `abc`, all in one plane.
fn coplanar_seg_tri(p: &P, q: &P, a: &P, b: &P, c: &P) -> bool {
    let k = drop_axis(a, b, c);
    let (p, q, a, b, c) = (proj(p, k), proj(q, k), proj(a, k), proj(b, k), proj(c, k));
    point_in_tri_2d(&p, &a, &b, &c)
        || point_in_tri_2d(&q, &a, &b, &c)
        || seg_seg_2d(&p, &q, &a, &b)
        || seg_seg_2d(&p, &q, &b, &c)
        || seg_seg_2d(&p, &q, &c, &a)
}

/// Closed segment `pq` (p ≠ q) against closed non-degenerate triangle `abc`.
#[cfg(test)]
pub fn seg_tri(p: &P, q: &P, a: &P, b: &P, c: &P) -> bool {
    seg_tri_with(p, q, a, b, c, orient3d(a, b, c, p), orient3d(a, b, c, q))
}

/// `seg_tri` with the sides of `p` and `q` relative to plane `abc` already known.
fn seg_tri_with(p: &P, q: &P, a: &P, b: &P, c: &P, op: Orientation, oq: Orientation) -> bool {
    if op == oq && op != Orientation::Zero {
        return false;
    }
    if op == Orientation::Zero && oq == Orientation::Zero {
        return coplanar_seg_tri(p, q, a, b, c);
    }
    !mixed([
        orient3d(p, q, a, b),
        orient3d(p, q, b, c),
        orient3d(p, q, c, a),
    ])
}

fn all_strict_same(s: [Orientation; 3]) -> bool {
    s[0] != Orientation::Zero && s[0] == s[1] && s[1] == s[2]
}

/// Two triangles without a common vertex.
pub fn disjoint_pair(t: [&P; 3], u: [&P; 3]) -> Contact {
    let su = [
        orient3d(t[0], t[1], t[2], u[0]),
        orient3d(t[0], t[1], t[2], u[1]),
        orient3d(t[0], t[1], t[2], u[2]),
    ];
    if all_strict_same(su) {
        return Contact::None;
    }
    let st = [
        orient3d(u[0], u[1], u[2], t[0]),
        orient3d(u[0], u[1], u[2], t[1]),
        orient3d(u[0], u[1], u[2], t[2]),
    ];
    if all_strict_same(st) {
        return Contact::None;
    }
    let coplanar = su.iter().all(|&o| o == Orientation::Zero);
    let hit = (0..3).any(|k| {
        seg_tri_with(
            t[k],
            t[(k + 1) % 3],
            u[0],
            u[1],
            u[2],
            st[k],
            st[(k + 1) % 3],
        )
    }) || (0..3).any(|k| {
        seg_tri_with(
            u[k],
            u[(k + 1) % 3],
            t[0],
            t[1],
            t[2],
            su[k],
            su[(k + 1) % 3],
        )
    });
    match (hit, coplanar) {
        (false, _) => Contact::None,
        (true, true) => Contact::CoplanarOverlap,
        (true, false) => Contact::Crossing,
    }
}

/// Triangles `(v, a, b)` and `(v, c, d)` sharing only the vertex `v`.
pub fn vertex_pair(v: &P, a: &P, b: &P, c: &P, d: &P) -> Contact {
    let oc = orient3d(v, a, b, c);
    let od = orient3d(v, a, b, d);
    if oc == od && oc != Orientation::Zero {
        return Contact::None;
    }
    let oa = orient3d(v, c, d, a);
    let ob = orient3d(v, c, d, b);
    if oa == ob && oa != Orientation::Zero {
        return Contact::None;
    }
    if !(seg_tri_with(a, b, v, c, d, oa, ob) || seg_tri_with(c, d, v, a, b, oc, od)) {
        return Contact::None;
    }
    if oc == Orientation::Zero && od == Orientation::Zero {
        Contact::CoplanarOverlap
    } else {
        Contact::Crossing
    }
}

/// Triangles `(u, v, a)` and `(u, v, b)` sharing the edge `uv`: they overlap only when coplanar
/// with `a` and `b` on the same side of `uv`.
pub fn edge_pair(u: &P, v: &P, a: &P, b: &P) -> Contact {
    if orient3d(u, v, a, b) != Orientation::Zero {
        return Contact::None;
    }
    let k = drop_axis(u, v, a);
    let (pu, pv) = (proj(u, k), proj(v, k));
    let sa = orient2d(&pu, &pv, &proj(a, k));
    let sb = orient2d(&pu, &pv, &proj(b, k));
    if sa == sb && sa != Orientation::Zero {
        Contact::CoplanarOverlap
    } else {
        Contact::None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const O: P = [0.0, 0.0, 0.0];

    #[test]
    fn a_segment_piercing_a_triangle_meets_it_and_one_beside_it_does_not() {
        let (a, b, c) = ([0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]);
        assert!(seg_tri(&[1.0, 1.0, -1.0], &[1.0, 1.0, 1.0], &a, &b, &c));
        assert!(!seg_tri(&[3.0, 3.0, -1.0], &[3.0, 3.0, 1.0], &a, &b, &c));
        // Touching the edge exactly counts (closed triangles).
        assert!(seg_tri(&[2.0, 0.0, -1.0], &[2.0, 0.0, 1.0], &a, &b, &c));
    }

    #[test]
    fn crossing_triangles_at_utm_magnitudes_are_found_exactly() {
        let o = [512_345.125, 7_012_345.5, -1234.25];
        let p = |x: f64, y: f64, z: f64| [o[0] + x, o[1] + y, o[2] + z];
        let t = [p(0.0, 0.0, 0.0), p(10.0, 0.0, 0.0), p(0.0, 10.0, 0.0)];
        let u = [p(1.0, 1.0, -1.0), p(1.0, 1.0, 1.0), p(5.0, -3.0, 0.5)];
        assert_eq!(
            disjoint_pair([&t[0], &t[1], &t[2]], [&u[0], &u[1], &u[2]]),
            Contact::Crossing
        );
        let far = [p(1.0, 1.0, 0.001), p(1.0, 1.0, 1.0), p(5.0, -3.0, 0.5)];
        assert_eq!(
            disjoint_pair([&t[0], &t[1], &t[2]], [&far[0], &far[1], &far[2]]),
            Contact::None
        );
    }

    #[test]
    fn coplanar_overlapping_triangles_are_an_overlap_not_a_crossing() {
        let t = [O, [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]];
        let u = [[1.0, 1.0, 0.0], [5.0, 1.0, 0.0], [1.0, 5.0, 0.0]];
        assert_eq!(
            disjoint_pair([&t[0], &t[1], &t[2]], [&u[0], &u[1], &u[2]]),
            Contact::CoplanarOverlap
        );
    }

    #[test]
    fn a_fan_around_a_shared_vertex_does_not_intersect_but_a_fold_does() {
        let (a, b) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert_eq!(
            vertex_pair(&O, &a, &b, &[-1.0, 0.0, 0.0], &[0.0, -1.0, 0.2]),
            Contact::None
        );
        // The second triangle passes through the first one's interior.
        assert_eq!(
            vertex_pair(&O, &a, &b, &[1.0, 1.0, -1.0], &[1.0, 1.0, 1.0]),
            Contact::Crossing
        );
    }

    #[test]
    fn a_shared_edge_overlaps_only_when_folded_flat() {
        let (u, v) = (O, [1.0, 0.0, 0.0]);
        assert_eq!(
            edge_pair(&u, &v, &[0.0, 1.0, 0.0], &[0.0, -1.0, 0.0]),
            Contact::None
        );
        assert_eq!(
            edge_pair(&u, &v, &[0.0, 1.0, 0.0], &[0.0, 1.0, 1.0]),
            Contact::None
        );
        assert_eq!(
            edge_pair(&u, &v, &[0.0, 1.0, 0.0], &[0.5, 2.0, 0.0]),
            Contact::CoplanarOverlap
        );
    }
}
