//! Exact intersection tests between the simplices the tetrahedral mesher manipulates.
//!
//! Every decision here (does a candidate tetrahedron's face cut a front triangle, is a front node
//! inside a candidate tetrahedron, does the boundary intersect itself) is taken with the exact
//! `orient3d`/`orient2d` predicates of `geom`: no epsilon, no constructed intersection point.
//! Triangles are given by node indices, so "touching" is judged combinatorially: two triangles may
//! meet exactly in the vertices/edge they share by index; any other contact — including two
//! distinct nodes at identical coordinates — is an improper intersection.

use geom::predicates::{Orientation, orient2d};

type P = [f64; 3];

/// The exact `orient3d` of `geom`, after two exact shortcuts for the degenerate inputs the
/// mesher meets all the time and on which the adaptive predicate takes its slowest path: a
/// repeated point (a determinant with two equal rows is zero) and four points sharing one
/// coordinate exactly (all on one axis-aligned plane, e.g. a box side: a zero column). Both are
/// decided by float equality, which is exact; everything else goes to the adaptive predicate.
#[inline]
pub fn orient3d(a: &P, b: &P, c: &P, d: &P) -> Orientation {
    if d == a || d == b || d == c || a == b || b == c || c == a {
        return Orientation::Zero;
    }
    for k in 0..3 {
        if a[k] == d[k] && b[k] == d[k] && c[k] == d[k] {
            return Orientation::Zero;
        }
    }
    geom::predicates::orient3d(a, b, c, d)
}

#[inline]
fn proj(p: &P, axis: usize) -> [f64; 2] {
    match axis {
        0 => [p[1], p[2]],
        1 => [p[2], p[0]],
        _ => [p[0], p[1]],
    }
}

/// The coordinate axis to drop so that the (non-degenerate) triangle `abc` projects to a
/// non-degenerate 2D triangle. The float normal suggests the axis; the exact `orient2d` confirms it.
pub fn plane_axis(a: &P, b: &P, c: &P) -> Option<usize> {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        (u[1] * v[2] - u[2] * v[1]).abs(),
        (u[2] * v[0] - u[0] * v[2]).abs(),
        (u[0] * v[1] - u[1] * v[0]).abs(),
    ];
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| n[j].total_cmp(&n[i]).then(i.cmp(&j)));
    order
        .into_iter()
        .find(|&k| orient2d(&proj(a, k), &proj(b, k), &proj(c, k)) != Orientation::Zero)
}

/// True when the triangle `abc` is degenerate (its three points are collinear or coincide), exactly.
pub fn triangle_is_degenerate(a: &P, b: &P, c: &P) -> bool {
    plane_axis(a, b, c).is_none()
}

#[inline]
fn s2(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> i32 {
    orient2d(a, b, c).sign()
}

/// Closed 2D segment-segment intersection (touching counts).
fn seg_seg_2d(p1: &[f64; 2], p2: &[f64; 2], q1: &[f64; 2], q2: &[f64; 2]) -> bool {
    let d1 = s2(p1, p2, q1);
    let d2 = s2(p1, p2, q2);
    let d3 = s2(q1, q2, p1);
    let d4 = s2(q1, q2, p2);
    if d1 == 0 && d2 == 0 {
        // Collinear: overlap of the projections on an axis along which the segment varies.
        let ax = if p1[0] != p2[0] || q1[0] != q2[0] {
            0
        } else {
            1
        };
        let (pa, pb) = min_max(p1[ax], p2[ax]);
        let (qa, qb) = min_max(q1[ax], q2[ax]);
        return pa <= qb && qa <= pb;
    }
    d1 * d2 <= 0 && d3 * d4 <= 0
}

#[inline]
fn min_max(a: f64, b: f64) -> (f64, f64) {
    if a <= b { (a, b) } else { (b, a) }
}

/// Closed point-in-triangle in 2D for a non-degenerate triangle.
fn point_in_tri_2d(p: &[f64; 2], a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> bool {
    let s = s2(a, b, c);
    s2(a, b, p) * s >= 0 && s2(b, c, p) * s >= 0 && s2(c, a, p) * s >= 0
}

/// Closed segment `pq` against closed triangle `abc`, both given in 3D (any contact counts).
pub fn seg_tri_closed(p: &P, q: &P, a: &P, b: &P, c: &P) -> bool {
    let op = orient3d(a, b, c, p);
    let oq = orient3d(a, b, c, q);
    if op == oq && op != Orientation::Zero {
        return false;
    }
    if op == Orientation::Zero && oq == Orientation::Zero {
        let Some(ax) = plane_axis(a, b, c) else {
            return false;
        };
        let (p2, q2, a2, b2, c2) = (
            proj(p, ax),
            proj(q, ax),
            proj(a, ax),
            proj(b, ax),
            proj(c, ax),
        );
        return point_in_tri_2d(&p2, &a2, &b2, &c2)
            || point_in_tri_2d(&q2, &a2, &b2, &c2)
            || seg_seg_2d(&p2, &q2, &a2, &b2)
            || seg_seg_2d(&p2, &q2, &b2, &c2)
            || seg_seg_2d(&p2, &q2, &c2, &a2);
    }
    let s1 = orient3d(p, q, a, b).sign();
    let s2v = orient3d(p, q, b, c).sign();
    let s3 = orient3d(p, q, c, a).sign();
    let pos = s1 > 0 || s2v > 0 || s3 > 0;
    let neg = s1 < 0 || s2v < 0 || s3 < 0;
    !(pos && neg)
}

/// True when `x` lies in the closed tetrahedron `abcd` (positively oriented).
#[inline]
pub fn point_in_closed_tet(x: &P, a: &P, b: &P, c: &P, d: &P) -> bool {
    orient3d(x, b, c, d) != Orientation::Negative
        && orient3d(a, x, c, d) != Orientation::Negative
        && orient3d(a, b, x, d) != Orientation::Negative
        && orient3d(a, b, c, x) != Orientation::Negative
}

/// True when triangles `t` and `u` (node indices into `pts`) intersect anywhere other than in the
/// vertices or edge they share by index. Identical vertex sets are not an intersection (the caller
/// decides what a repeated face means).
pub fn tri_tri_improper(t: [u32; 3], u: [u32; 3], pts: &[P]) -> bool {
    if t.iter().all(|i| u.contains(i)) {
        return false;
    }
    let tp = [
        &pts[t[0] as usize],
        &pts[t[1] as usize],
        &pts[t[2] as usize],
    ];
    let ou = [0, 1, 2].map(|i| orient3d(tp[0], tp[1], tp[2], &pts[u[i] as usize]));
    tri_tri_improper_with(t, u, ou, pts)
}

/// `tri_tri_improper` when the caller already knows `ou`, the exact orientations
/// `orient3d(t0, t1, t2, u_i)` of `u`'s vertices against `t`'s plane (the mesher shares them
/// between the tests of one candidate tetrahedron).
pub fn tri_tri_improper_with(t: [u32; 3], u: [u32; 3], ou: [Orientation; 3], pts: &[P]) -> bool {
    let shared_of = |i: u32| t.contains(&i) && u.contains(&i);
    let k = t.iter().filter(|&&i| u.contains(&i)).count();
    if k == 3 {
        return false;
    }
    let up = [
        &pts[u[0] as usize],
        &pts[u[1] as usize],
        &pts[u[2] as usize],
    ];
    if separated(&ou, &u, &shared_of) {
        return false;
    }
    let ot = [0, 1, 2].map(|i| orient3d(up[0], up[1], up[2], &pts[t[i] as usize]));
    if separated(&ot, &t, &shared_of) {
        return false;
    }
    if ou.iter().all(|&o| o == Orientation::Zero) {
        return coplanar_improper(t, u, pts);
    }
    if k == 2 {
        // Non-coplanar triangles sharing an edge meet exactly in that edge.
        return false;
    }
    for e in 0..3 {
        if edge_hits_improper(t[e], t[(e + 1) % 3], u, pts) {
            return true;
        }
        if edge_hits_improper(u[e], u[(e + 1) % 3], t, pts) {
            return true;
        }
    }
    false
}

/// All vertices off the plane are strictly on one side and the ones on it are shared vertices:
/// the triangle meets the other's plane only in shared vertices.
fn separated(o: &[Orientation; 3], v: &[u32; 3], shared_of: &impl Fn(u32) -> bool) -> bool {
    let mut side = 0;
    for i in 0..3 {
        match o[i] {
            Orientation::Zero => {
                if !shared_of(v[i]) {
                    return false;
                }
            }
            s => {
                let sg = s.sign();
                if side == 0 {
                    side = sg;
                } else if side != sg {
                    return false;
                }
            }
        }
    }
    side != 0
}

/// Does the edge `e0 e1` meet triangle `t` other than at a vertex it shares with `t`?
fn edge_hits_improper(e0: u32, e1: u32, t: [u32; 3], pts: &[P]) -> bool {
    let s0 = t.contains(&e0);
    let s1 = t.contains(&e1);
    let (a, b, c) = (
        &pts[t[0] as usize],
        &pts[t[1] as usize],
        &pts[t[2] as usize],
    );
    match (s0, s1) {
        (true, true) => false,
        (false, false) => seg_tri_closed(&pts[e0 as usize], &pts[e1 as usize], a, b, c),
        (true, false) => ray_enters_from_vertex(e0, e1, t, pts),
        (false, true) => ray_enters_from_vertex(e1, e0, t, pts),
    }
}

/// Segment from `v` (a vertex of `t`) to `w`: does it meet `t` beyond `v`?
fn ray_enters_from_vertex(v: u32, w: u32, t: [u32; 3], pts: &[P]) -> bool {
    let r = if t[0] == v {
        [t[0], t[1], t[2]]
    } else if t[1] == v {
        [t[1], t[2], t[0]]
    } else {
        [t[2], t[0], t[1]]
    };
    let (a, e, f) = (
        &pts[r[0] as usize],
        &pts[r[1] as usize],
        &pts[r[2] as usize],
    );
    let b = &pts[w as usize];
    if orient3d(a, e, f, b) != Orientation::Zero {
        return false;
    }
    let Some(ax) = plane_axis(a, e, f) else {
        return false;
    };
    let (a2, e2, f2, b2) = (proj(a, ax), proj(e, ax), proj(f, ax), proj(b, ax));
    let s = s2(&a2, &e2, &f2);
    s2(&a2, &e2, &b2) * s >= 0 && s2(&a2, &f2, &b2) * s <= 0
}

/// Coplanar triangles: improper when a non-shared vertex of one lies in the other, or two edges
/// meet other than at a shared endpoint.
fn coplanar_improper(t: [u32; 3], u: [u32; 3], pts: &[P]) -> bool {
    let tp = [
        &pts[t[0] as usize],
        &pts[t[1] as usize],
        &pts[t[2] as usize],
    ];
    let Some(ax) = plane_axis(tp[0], tp[1], tp[2]) else {
        return true;
    };
    let p2 = |i: u32| proj(&pts[i as usize], ax);
    let t2 = [p2(t[0]), p2(t[1]), p2(t[2])];
    let u2 = [p2(u[0]), p2(u[1]), p2(u[2])];
    for i in 0..3 {
        if !u.contains(&t[i]) && point_in_tri_2d(&t2[i], &u2[0], &u2[1], &u2[2]) {
            return true;
        }
        if !t.contains(&u[i]) && point_in_tri_2d(&u2[i], &t2[0], &t2[1], &t2[2]) {
            return true;
        }
    }
    for i in 0..3 {
        let (ta, tb) = (t[i], t[(i + 1) % 3]);
        for j in 0..3 {
            let (ua, ub) = (u[j], u[(j + 1) % 3]);
            let common = [ta == ua || ta == ub, tb == ua || tb == ub];
            match common {
                [true, true] => {}
                [false, false] => {
                    if seg_seg_2d(&p2(ta), &p2(tb), &p2(ua), &p2(ub)) {
                        return true;
                    }
                }
                _ => {
                    let (v, x) = if common[0] { (ta, tb) } else { (tb, ta) };
                    let y = if ua == v { ub } else { ua };
                    if same_ray(&p2(v), &p2(x), &p2(y)) {
                        return true;
                    }
                }
            }
        }
    }
    false
}

/// Segments `v x` and `v y` overlap beyond `v` (collinear, same direction).
fn same_ray(v: &[f64; 2], x: &[f64; 2], y: &[f64; 2]) -> bool {
    if s2(v, x, y) != 0 {
        return false;
    }
    let ax = if x[0] != v[0] { 0 } else { 1 };
    (x[ax] > v[ax]) == (y[ax] > v[ax]) && y[ax] != v[ax]
}

/// True when the three points lie on one line (or coincide), exactly: the three components of
/// `(b-a)×(c-a)` are the `orient2d` of the three coordinate projections.
pub fn collinear(a: &P, b: &P, c: &P) -> bool {
    (0..3).all(|k| s2(&proj(a, k), &proj(b, k), &proj(c, k)) == 0)
}

/// True when segment `e` (vertex ids) meets triangle `t` anywhere but in a vertex they share by
/// index. A segment that is an edge of `t` meets it along that edge.
pub fn seg_tri_improper(e: [u32; 2], t: [u32; 3], pts: &[P]) -> bool {
    if t.contains(&e[0]) && t.contains(&e[1]) {
        return true;
    }
    edge_hits_improper(e[0], e[1], t, pts)
}

/// True when segments `e` and `f` (vertex ids) meet anywhere but in a vertex they share by index
/// (the same segment twice meets itself everywhere).
pub fn seg_seg_improper(e: [u32; 2], f: [u32; 2], pts: &[P]) -> bool {
    let p = |v: u32| &pts[v as usize];
    let shared: Vec<u32> = e.iter().copied().filter(|v| f.contains(v)).collect();
    match shared.len() {
        0 => segs_meet_closed(p(e[0]), p(e[1]), p(f[0]), p(f[1])),
        1 => {
            let v = shared[0];
            let x = if e[0] == v { e[1] } else { e[0] };
            let y = if f[0] == v { f[1] } else { f[0] };
            same_ray_3d(p(v), p(x), p(y))
        }
        _ => true,
    }
}

/// Segments `v x` and `v y` overlap beyond `v` (collinear, same direction), or an end of one
/// coincides with `v` or the other's end.
fn same_ray_3d(v: &P, x: &P, y: &P) -> bool {
    if x == v || y == v || x == y {
        return true;
    }
    if !collinear(v, x, y) {
        return false;
    }
    let k = (0..3).find(|&k| x[k] != v[k]).unwrap_or(0);
    (x[k] > v[k]) == (y[k] > v[k])
}

/// Closed segments `pq` and `rs` (each of two distinct points) meet, exactly: coplanar, then
/// compared in a coordinate projection that is one to one on their plane (or line).
fn segs_meet_closed(p: &P, q: &P, r: &P, s: &P) -> bool {
    if orient3d(p, q, r, s) != Orientation::Zero {
        return false;
    }
    let axis = [(p, q, r), (p, q, s), (r, s, p), (r, s, q)]
        .into_iter()
        .find_map(|(a, b, c)| plane_axis(a, b, c))
        // All four on one line: drop an axis along which it does not run.
        .or_else(|| (0..3).rev().find(|&k| proj(p, k) != proj(q, k)));
    let Some(ax) = axis else { return true };
    seg_seg_2d(&proj(p, ax), &proj(q, ax), &proj(r, ax), &proj(s, ax))
}

/// True when the closed segment `ab` meets the closed axis-aligned box `[lo, hi]`, exactly
/// (separating axes: the box's three, and the segment's direction crossed with each box edge,
/// that is the box's corners strictly on one side of the segment's line in a projection).
pub fn seg_meets_box(a: &P, b: &P, lo: &P, hi: &P) -> bool {
    for k in 0..3 {
        let (s0, s1) = min_max(a[k], b[k]);
        if s1 < lo[k] || hi[k] < s0 {
            return false;
        }
    }
    for ax in 0..3 {
        let (a2, b2) = (proj(a, ax), proj(b, ax));
        let (l2, h2) = (proj(lo, ax), proj(hi, ax));
        let corners = [
            [l2[0], l2[1]],
            [h2[0], l2[1]],
            [l2[0], h2[1]],
            [h2[0], h2[1]],
        ];
        let sides = corners.map(|c| s2(&a2, &b2, &c));
        if sides.iter().all(|&x| x > 0) || sides.iter().all(|&x| x < 0) {
            return false;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts() -> Vec<P> {
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.2, 0.2, -1.0],
            [0.2, 0.2, 1.0],
            [1.0, 1.0, 0.0],
            [0.5, -0.5, 0.0],
        ]
    }

    #[test]
    fn the_shortcut_orient3d_agrees_with_the_adaptive_predicate_on_degenerate_and_general_points() {
        // A small lattice with repeated points, points sharing one coordinate (axis planes),
        // general positions and tiny offsets: every quadruple is compared.
        let mut pts: Vec<P> = Vec::new();
        for &x in &[0.0, 1.0, 1.0 + 1e-12] {
            for &y in &[0.0, 2.5] {
                for &z in &[-3.0, 0.1] {
                    pts.push([x, y, z]);
                }
            }
        }
        pts.push([0.3, 0.7, 0.0]);
        pts.push([0.0, 0.0, -3.0]);
        let n = pts.len();
        let mut zero = 0;
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    for l in (0..n).step_by(3) {
                        let (a, b, c, d) = (&pts[i], &pts[j], &pts[k], &pts[l]);
                        let fast = orient3d(a, b, c, d);
                        assert_eq!(fast, geom::predicates::orient3d(a, b, c, d));
                        zero += (fast == Orientation::Zero) as usize;
                    }
                }
            }
        }
        // The shortcuts were exercised (and agreed), and not every case was degenerate.
        assert!(zero > 0 && zero < n * n * n * n.div_ceil(3));
    }

    #[test]
    fn a_segment_piercing_a_triangle_is_an_intersection_and_one_beside_it_is_not() {
        let p = pts();
        assert!(seg_tri_closed(&p[4], &p[5], &p[0], &p[1], &p[2]));
        assert!(!seg_tri_closed(
            &[2.0, 2.0, -1.0],
            &[2.0, 2.0, 1.0],
            &p[0],
            &p[1],
            &p[2]
        ));
    }

    #[test]
    fn triangles_sharing_an_edge_on_opposite_sides_are_proper_but_folded_over_is_not() {
        let p = pts();
        assert!(!tri_tri_improper([0, 1, 2], [1, 6, 2], &p));
        // Same side of the shared edge 0-1 in the same plane: overlap.
        assert!(tri_tri_improper([0, 1, 2], [0, 1, 6], &p));
        // Other side of edge 0-1.
        assert!(!tri_tri_improper([0, 1, 2], [0, 7, 1], &p));
        // Non-coplanar sharing an edge.
        assert!(!tri_tri_improper([0, 1, 2], [0, 1, 3], &p));
    }

    #[test]
    fn a_triangle_through_another_is_improper_even_when_sharing_a_vertex() {
        let p = pts();
        assert!(tri_tri_improper([0, 1, 2], [4, 5, 6], &p));
        let mut q = p.clone();
        q.push([0.3, 0.3, -1.0]);
        q.push([0.3, 0.3, 1.0]);
        // shares vertex 0, crosses the interior of 0-1-2 along a segment
        assert!(tri_tri_improper([0, 1, 2], [0, 8, 9], &q));
        // shares vertex 0 only, lies above
        assert!(!tri_tri_improper([0, 1, 2], [0, 3, 5], &q));
    }

    #[test]
    fn duplicate_coordinates_under_different_indices_are_an_intersection() {
        let mut p = pts();
        p.push([1.0, 0.0, 0.0]);
        assert!(tri_tri_improper([0, 1, 2], [8, 3, 6], &p));
    }

    #[test]
    fn a_point_on_a_tet_face_is_in_the_closed_tet() {
        let p = pts();
        assert!(point_in_closed_tet(
            &[0.2, 0.2, 0.0],
            &p[0],
            &p[1],
            &p[2],
            &p[3]
        ));
        assert!(point_in_closed_tet(
            &[0.1, 0.1, 0.1],
            &p[0],
            &p[1],
            &p[2],
            &p[3]
        ));
        assert!(!point_in_closed_tet(
            &[0.5, 0.5, 0.5],
            &p[0],
            &p[1],
            &p[2],
            &p[3]
        ));
    }

    #[test]
    fn segments_meeting_only_at_a_shared_end_are_proper_and_overlapping_or_crossing_ones_are_not() {
        let p = vec![
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [2.0, 2.0, 2.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 1.0],
            [3.0, 3.0, 3.0],
            [1.0, 1.0, 0.0],
        ];
        // A polyline bending at vertex 1, and one going straight on.
        assert!(!seg_seg_improper([0, 1], [1, 3], &p));
        assert!(!seg_seg_improper([0, 1], [1, 2], &p));
        // Folding back over itself from the shared vertex.
        assert!(seg_seg_improper([1, 2], [1, 5], &p));
        // Two diagonals of the unit square's shadow crossing at (0.5, 0.5, 0.5).
        assert!(seg_seg_improper([0, 1], [3, 4], &p));
        // Skew segments do not meet.
        assert!(!seg_seg_improper([0, 1], [3, 6], &p));
        // Collinear and apart, collinear and overlapping.
        assert!(!seg_seg_improper([0, 1], [2, 5], &p));
        assert!(seg_seg_improper([0, 2], [1, 5], &p));
        // The same segment twice.
        assert!(seg_seg_improper([0, 1], [1, 0], &p));
    }

    #[test]
    fn a_segment_along_a_triangle_edge_or_touching_its_inside_meets_it_and_one_from_a_vertex_does_not()
     {
        let mut p = pts();
        p.push([0.25, 0.25, 0.0]);
        assert!(seg_tri_improper([0, 1], [0, 1, 2], &p));
        assert!(!seg_tri_improper([0, 3], [0, 1, 2], &p));
        assert!(seg_tri_improper([3, 8], [0, 1, 2], &p));
        assert!(seg_tri_improper([4, 5], [0, 1, 2], &p));
    }

    #[test]
    fn a_box_around_a_point_near_a_slanted_segment_meets_it_and_one_beside_it_does_not() {
        let (a, b) = ([0.0, 0.0, 0.0], [3.0, 1.0, 2.0]);
        let near = |c: P, r: f64| seg_meets_box(&a, &b, &c.map(|x| x - r), &c.map(|x| x + r));
        assert!(near([1.5, 0.5, 1.0], 1e-12));
        assert!(near([1.5, 0.5, 1.0 + 1e-3], 2e-3));
        assert!(!near([1.5, 0.5, 1.0 + 1e-3], 1e-4));
        assert!(!near([4.0, 1.5, 2.5], 0.1));
    }
}
