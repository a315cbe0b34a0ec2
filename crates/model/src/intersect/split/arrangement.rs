//! Chords of several intersections crossing inside one triangle, and the constructions that make
//! the points shared by three surfaces identical on all of them.
//!
//! What it decides: whether two chords cross (exact `orient2d` on the projected coordinates).
//! Constructed coordinates (a crossing point; an edge meeting a face) are floats computed from
//! inputs put in a canonical order first, so every surface that constructs the same point gets
//! the same bits.

use geom::predicates::{cross, dot, sub};
use geom::{Orientation, orient2d};

/// Segments `pq` and `rs` cross at a single point interior to both (exact). `None` when they
/// do not meet, `Some(true)` for a proper crossing, `Some(false)` for any other contact
/// (touching, collinear overlap), which callers treat as unsupported.
pub fn crossing(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> Option<bool> {
    use Orientation::Zero;
    let (o1, o2) = (orient2d(&p, &q, &r), orient2d(&p, &q, &s));
    let (o3, o4) = (orient2d(&r, &s, &p), orient2d(&r, &s, &q));
    if o1 != Zero && o1 == o2.flip() && o3 != Zero && o3 == o4.flip() {
        return Some(true);
    }
    let within = |a: [f64; 2], b: [f64; 2], x: [f64; 2]| {
        (0..2).all(|k| a[k].min(b[k]) <= x[k] && x[k] <= a[k].max(b[k]))
    };
    let touch = (o1 == Zero && within(p, q, r))
        || (o2 == Zero && within(p, q, s))
        || (o3 == Zero && within(r, s, p))
        || (o4 == Zero && within(r, s, q));
    touch.then_some(false)
}

/// The point common to three planes, each given by a triangle; the triangles must be given in a
/// canonical order (the callers sort them by surface name) so the result is reproducible bit
/// for bit. Computed relative to the first triangle's first corner. `None` when the planes do
/// not meet in one point (a measure: the caller falls back to another construction).
pub fn three_planes(t: [[[f64; 3]; 3]; 3]) -> Option<[f64; 3]> {
    let o = t[0][0];
    let n: Vec<[f64; 3]> = t
        .iter()
        .map(|c| cross(&sub(&c[1], &c[0]), &sub(&c[2], &c[0])))
        .collect();
    let d: Vec<f64> = t
        .iter()
        .zip(&n)
        .map(|(c, n)| dot(n, &sub(&c[0], &o)))
        .collect();
    let (c12, c20, c01) = (
        cross(&n[1], &n[2]),
        cross(&n[2], &n[0]),
        cross(&n[0], &n[1]),
    );
    let det = dot(&n[0], &c12);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let x: [f64; 3] =
        [0, 1, 2].map(|k| o[k] + (d[0] * c12[k] + d[1] * c20[k] + d[2] * c01[k]) / det);
    let mut x = x;
    for tri in &t {
        snap(&mut x, tri);
    }
    x.iter().all(|c| c.is_finite()).then_some(x)
}

/// Where the segment `pq` crosses the plane of triangle `t`, with the endpoints put in
/// lexicographic order first (so the same edge seen from two sides gives the same bits).
pub fn edge_plane(p: [f64; 3], q: [f64; 3], t: [[f64; 3]; 3]) -> Option<[f64; 3]> {
    let lex = |a: &[f64; 3], b: &[f64; 3]| {
        (0..3)
            .map(|k| a[k].total_cmp(&b[k]))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    };
    let (p, q) = if lex(&p, &q).is_le() { (p, q) } else { (q, p) };
    let o = t[0];
    let n = cross(&sub(&t[1], &o), &sub(&t[2], &o));
    let (vp, vq) = (dot(&n, &sub(&p, &o)), dot(&n, &sub(&q, &o)));
    let s = vp / (vp - vq);
    if !s.is_finite() {
        return None;
    }
    let s = s.clamp(0.0, 1.0);
    let mut x = [0, 1, 2].map(|k| p[k] + s * (q[k] - p[k]));
    snap(&mut x, &t);
    Some(x)
}

/// A point known to lie in the plane of `t`: when that plane is `x_k = c` exactly (all three
/// corners share coordinate `k`), coordinate `k` of the point is exactly `c`, so it is set so
/// (the float construction may be off by an ulp, which would put a point on a box side just
/// outside the box).
fn snap(x: &mut [f64; 3], t: &[[f64; 3]; 3]) {
    for k in 0..3 {
        if t[0][k] == t[1][k] && t[0][k] == t[2][k] {
            x[k] = t[0][k];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_tells_proper_crossings_from_touches() {
        let c = crossing([0.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.0, 0.0]);
        assert_eq!(c, Some(true));
        let t = crossing([0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]);
        assert_eq!(t, Some(false));
        assert_eq!(
            crossing([0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]),
            None
        );
    }

    #[test]
    fn three_axis_planes_meet_at_their_common_point() {
        let x = [[3.0, 0.0, 0.0], [3.0, 1.0, 0.0], [3.0, 0.0, 1.0]];
        let y = [[0.0, 5.0, 0.0], [0.0, 5.0, 1.0], [1.0, 5.0, 0.0]];
        let z = [[0.0, 0.0, -2.0], [1.0, 0.0, -2.0], [0.0, 1.0, -2.0]];
        assert_eq!(three_planes([x, y, z]), Some([3.0, 5.0, -2.0]));
        assert_eq!(three_planes([x, x, z]), None);
    }

    #[test]
    fn an_edge_crossing_a_box_side_lands_exactly_on_it_whichever_way_it_is_given() {
        let side = [
            [500_000.1, 7_000_000.0, -10.0],
            [500_000.1, 7_000_010.0, -10.0],
            [500_000.1, 7_000_000.0, 10.0],
        ];
        let p = [499_993.7, 7_000_003.3, -1.234_567];
        let q = [500_007.9, 7_000_004.1, 2.345_678];
        let a = edge_plane(p, q, side).expect("crosses");
        let b = edge_plane(q, p, side).expect("crosses");
        assert_eq!(a[0], 500_000.1, "snapped onto the plane x = 500000.1");
        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
    }
}
