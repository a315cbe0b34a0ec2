//! Exact orientation predicates (Shewchuk's adaptive arithmetic via `robust`), wrapped so that
//! every caller uses one sign convention. `orient3d` and `insphere`, called millions of times by
//! the tet mesher, first try Shewchuk's first-stage filter inline (the float determinant and its
//! proven error bound); only when it cannot decide does `robust` run, so the sign is always the
//! exact one.
//!
//! Convention: `orient3d(a, b, c, d)` is `Positive` when `d` lies on the side of the plane
//! `abc` that the right-hand normal `(b-a)×(c-a)` points to, i.e. when the tetrahedron `abcd` has
//! positive signed volume `det[b-a, c-a, d-a] / 6`. Note that `robust::orient3d` itself returns
//! the opposite sign (positive when `d` is *below* a counter-clockwise `abc`); the wrapper flips it.
//! `orient2d(a, b, c)` is `Positive` when `abc` turns counter-clockwise (same as `robust`).
//! `insphere(a, b, c, d, e)` is `Positive` when `e` is inside the circumsphere of the positively
//! oriented tetrahedron `abcd`.

use robust::Coord3D;

/// The sign of an exact predicate.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Orientation {
    Negative,
    Zero,
    Positive,
}

impl Orientation {
    #[inline]
    pub fn from_f64(v: f64) -> Self {
        if v > 0.0 {
            Orientation::Positive
        } else if v < 0.0 {
            Orientation::Negative
        } else {
            Orientation::Zero
        }
    }
    #[inline]
    pub fn flip(self) -> Self {
        match self {
            Orientation::Negative => Orientation::Positive,
            Orientation::Zero => Orientation::Zero,
            Orientation::Positive => Orientation::Negative,
        }
    }
    /// -1, 0 or 1.
    #[inline]
    pub fn sign(self) -> i32 {
        match self {
            Orientation::Negative => -1,
            Orientation::Zero => 0,
            Orientation::Positive => 1,
        }
    }
}

#[inline]
fn c3(p: &[f64; 3]) -> Coord3D<f64> {
    Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}

/// Half an ulp of 1 (Shewchuk's machine epsilon for round-to-nearest doubles).
const EPS: f64 = f64::EPSILON / 2.0;
/// Shewchuk's first-stage error bounds: a float determinant larger in magnitude than this times
/// its permanent has the exact determinant's sign.
const ORIENT3D_BOUND: f64 = (7.0 + 56.0 * EPS) * EPS;
const INSPHERE_BOUND: f64 = (16.0 + 224.0 * EPS) * EPS;

/// Exact side of `d` relative to the oriented plane `abc` (see the module doc for the sign).
/// The float determinant decides when its error bound proves its sign (nearly always, and
/// inlined); otherwise `robust`'s adaptive arithmetic does.
#[inline]
pub fn orient3d(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> Orientation {
    let (u, v, w) = (sub(a, d), sub(b, d), sub(c, d));
    let (vw, wv) = (v[0] * w[1], w[0] * v[1]);
    let (wu, uw) = (w[0] * u[1], u[0] * w[1]);
    let (uv, vu) = (u[0] * v[1], v[0] * u[1]);
    // robust's sign: positive when d is below abc.
    let det = u[2] * (vw - wv) + v[2] * (wu - uw) + w[2] * (uv - vu);
    let permanent = (vw.abs() + wv.abs()) * u[2].abs()
        + (wu.abs() + uw.abs()) * v[2].abs()
        + (uv.abs() + vu.abs()) * w[2].abs();
    let bound = ORIENT3D_BOUND * permanent;
    if det > bound || -det > bound {
        return Orientation::from_f64(-det);
    }
    Orientation::from_f64(-robust::orient3d(c3(a), c3(b), c3(c), c3(d)))
}

/// [`orient3d`] after two exact shortcuts for degenerate inputs, which meshes meet all the time
/// and on which the adaptive stage is slowest: a repeated point (a determinant with two equal
/// rows is zero) and four points sharing one coordinate exactly (all on one axis-aligned plane,
/// such as a box side: a zero column). Both are decided by float equality, which is exact.
#[inline]
pub fn orient3d_shortcut(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> Orientation {
    if d == a || d == b || d == c || a == b || b == c || c == a {
        return Orientation::Zero;
    }
    for k in 0..3 {
        if a[k] == d[k] && b[k] == d[k] && c[k] == d[k] {
            return Orientation::Zero;
        }
    }
    orient3d(a, b, c, d)
}

/// Exact turn of `abc` in the plane: `Positive` is counter-clockwise.
#[inline]
pub fn orient2d(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Orientation {
    Orientation::from_f64(robust::orient2d(
        robust::Coord { x: a[0], y: a[1] },
        robust::Coord { x: b[0], y: b[1] },
        robust::Coord { x: c[0], y: c[1] },
    ))
}

/// Exact in-circle test: `Positive` when `d` is strictly inside the circumcircle of the
/// counter-clockwise (see `orient2d`) triangle `abc`, `Negative` outside, `Zero` on it.
#[inline]
pub fn incircle(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> Orientation {
    Orientation::from_f64(robust::incircle(
        robust::Coord { x: a[0], y: a[1] },
        robust::Coord { x: b[0], y: b[1] },
        robust::Coord { x: c[0], y: c[1] },
        robust::Coord { x: d[0], y: d[1] },
    ))
}

/// Exact in-sphere test: `Positive` when `e` is strictly inside the circumsphere of the
/// positively oriented (see `orient3d`) tetrahedron `abcd`.
#[inline]
pub fn insphere(
    a: &[f64; 3],
    b: &[f64; 3],
    c: &[f64; 3],
    d: &[f64; 3],
    e: &[f64; 3],
) -> Orientation {
    // robust::insphere is positive when e is inside for abcd with robust::orient3d > 0, i.e.
    // negatively oriented in our convention; swapping a and b flips the orientation.
    let (a, b) = (b, a);
    let [p, q, r, s] = [sub(a, e), sub(b, e), sub(c, e), sub(d, e)];
    // 2x2 minors of the x, y columns, and their magnitudes.
    let m = |u: &[f64; 3], v: &[f64; 3]| (u[0] * v[1], v[0] * u[1]);
    let (pq, qr, rs, sp, pr, qs) = (
        m(&p, &q),
        m(&q, &r),
        m(&r, &s),
        m(&s, &p),
        m(&p, &r),
        m(&q, &s),
    );
    let d2 = |x: (f64, f64)| x.0 - x.1;
    let a2 = |x: (f64, f64)| x.0.abs() + x.1.abs();
    let pqr = p[2] * d2(qr) - q[2] * d2(pr) + r[2] * d2(pq);
    let qrs = q[2] * d2(rs) - r[2] * d2(qs) + s[2] * d2(qr);
    let rsp = r[2] * d2(sp) + s[2] * d2(pr) + p[2] * d2(rs);
    let spq = s[2] * d2(pq) + p[2] * d2(qs) + q[2] * d2(sp);
    let lift = |u: &[f64; 3]| dot(u, u);
    let (lp, lq, lr, ls) = (lift(&p), lift(&q), lift(&r), lift(&s));
    let det = (ls * pqr - lr * spq) + (lq * rsp - lp * qrs);
    let [zp, zq, zr, zs] = [p[2].abs(), q[2].abs(), r[2].abs(), s[2].abs()];
    let permanent = (a2(rs) * zq + a2(qs) * zr + a2(qr) * zs) * lp
        + (a2(sp) * zr + a2(pr) * zs + a2(rs) * zp) * lq
        + (a2(pq) * zs + a2(qs) * zp + a2(sp) * zq) * lr
        + (a2(qr) * zp + a2(pr) * zq + a2(pq) * zr) * ls;
    let bound = INSPHERE_BOUND * permanent;
    if det > bound || -det > bound {
        return Orientation::from_f64(det);
    }
    Orientation::from_f64(robust::insphere(c3(a), c3(b), c3(c), c3(d), c3(e)))
}

/// Signed volume of the tetrahedron `abcd` (floating point, for measures, never for decisions).
#[inline]
pub fn signed_volume(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    let u = sub(b, a);
    let v = sub(c, a);
    let w = sub(d, a);
    dot(&cross(&u, &v), &w) / 6.0
}

#[inline]
pub fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline]
pub fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
/// Euclidean distance (the squares summed in axis order, as every stage measures it).
#[inline]
pub fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(&d, &d).sqrt()
}
/// The length of a polyline: its segments' [`dist`] summed in order.
pub fn polyline_length(points: &[[f64; 3]]) -> f64 {
    points.windows(2).map(|w| dist(&w[0], &w[1])).sum()
}
#[inline]
pub fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: [f64; 3] = [0.0, 0.0, 0.0];
    const B: [f64; 3] = [1.0, 0.0, 0.0];
    const C: [f64; 3] = [0.0, 1.0, 0.0];

    #[test]
    fn a_point_above_a_counter_clockwise_triangle_is_positive() {
        assert_eq!(
            orient3d(&A, &B, &C, &[0.0, 0.0, 1.0]),
            Orientation::Positive
        );
        assert_eq!(
            orient3d(&A, &B, &C, &[0.0, 0.0, -1.0]),
            Orientation::Negative
        );
        assert!(signed_volume(&A, &B, &C, &[0.0, 0.0, 1.0]) > 0.0);
    }

    #[test]
    fn a_coplanar_point_at_utm_magnitudes_is_exactly_zero() {
        let o = [512_345.125, 7_012_345.5, -1234.25];
        let p = |dx: f64, dy: f64| [o[0] + dx, o[1] + dy, o[2]];
        assert_eq!(
            orient3d(&p(0.0, 0.0), &p(3.0, 0.0), &p(0.0, 3.0), &p(1.5, 1.5)),
            Orientation::Zero
        );
        let mut above = p(1.0, 1.0);
        above[2] += 1e-9;
        assert_eq!(
            orient3d(&p(0.0, 0.0), &p(3.0, 0.0), &p(0.0, 3.0), &above),
            Orientation::Positive
        );
    }

    #[test]
    fn insphere_is_positive_inside_a_positive_tetrahedron() {
        let d = [0.0, 0.0, 1.0];
        assert_eq!(orient3d(&A, &B, &C, &d), Orientation::Positive);
        assert_eq!(
            insphere(&A, &B, &C, &d, &[0.2, 0.2, 0.2]),
            Orientation::Positive
        );
        assert_eq!(
            insphere(&A, &B, &C, &d, &[5.0, 5.0, 5.0]),
            Orientation::Negative
        );
        assert_eq!(
            insphere(&A, &B, &C, &d, &[1.0, 1.0, 1.0]),
            Orientation::Zero
        );
    }

    /// Points at UTM magnitudes, many of them on shared planes and spheres (a lattice), so the
    /// float filters meet both easy and undecidable cases.
    fn lattice_points(n: usize, seed: u64) -> Vec<[f64; 3]> {
        let mut x = seed;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let o = [512_345.125, 7_012_345.5, -1234.25];
        (0..n)
            .map(|_| {
                let r = next();
                let jitter = if r % 4 == 0 {
                    ((r >> 8) % 1000) as f64 * 1e-12
                } else {
                    0.0
                };
                [0, 1, 2].map(|k| o[k] + ((r >> (16 + 8 * k)) % 4) as f64 * 0.5 + jitter)
            })
            .collect()
    }

    #[test]
    fn the_inlined_filters_give_the_signs_of_robusts_adaptive_predicates() {
        let p = lattice_points(64, 0x9e37_79b9_7f4a_7c15);
        let mut zeros = [0usize; 2];
        for i in 0..p.len() {
            let (a, b, c, d, e) = (
                p[i],
                p[(i * 7 + 1) % 64],
                p[(i * 11 + 2) % 64],
                p[(i * 13 + 3) % 64],
                p[(i * 17 + 5) % 64],
            );
            for (u, v, w, x, y) in [(a, b, c, d, e), (e, d, c, b, a), (b, a, d, c, e)] {
                let want = Orientation::from_f64(-robust::orient3d(c3(&u), c3(&v), c3(&w), c3(&x)));
                assert_eq!(orient3d(&u, &v, &w, &x), want);
                let want =
                    Orientation::from_f64(robust::insphere(c3(&v), c3(&u), c3(&w), c3(&x), c3(&y)));
                assert_eq!(insphere(&u, &v, &w, &x, &y), want);
                zeros[0] += (orient3d(&u, &v, &w, &x) == Orientation::Zero) as usize;
                zeros[1] += (want == Orientation::Zero) as usize;
            }
        }
        // The lattice does produce degenerate cases, which only the adaptive stage settles.
        assert!(zeros[0] > 0 && zeros[1] > 0, "{zeros:?}");
    }

    #[test]
    fn the_shortcut_orient3d_agrees_with_the_adaptive_predicate_on_degenerate_and_general_points() {
        // A small lattice with repeated points, points sharing one coordinate (axis planes),
        // general positions and tiny offsets: every quadruple is compared.
        let mut pts: Vec<[f64; 3]> = Vec::new();
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
                        let fast = orient3d_shortcut(a, b, c, d);
                        assert_eq!(fast, orient3d(a, b, c, d));
                        zero += (fast == Orientation::Zero) as usize;
                    }
                }
            }
        }
        // The shortcuts were exercised (and agreed), and not every case was degenerate.
        assert!(zero > 0 && zero < n * n * n * n.div_ceil(3));
    }

    #[test]
    fn orient2d_counter_clockwise_is_positive() {
        assert_eq!(
            orient2d(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0]),
            Orientation::Positive
        );
        assert_eq!(
            orient2d(&[0.0, 0.0], &[0.0, 1.0], &[1.0, 0.0]),
            Orientation::Negative
        );
    }
}
