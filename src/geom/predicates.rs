//! Exact orientation predicates (Shewchuk's adaptive arithmetic via `robust`), wrapped so that
//! every caller uses one sign convention.
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

/// Exact side of `d` relative to the oriented plane `abc` (see the module doc for the sign).
#[inline]
pub fn orient3d(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> Orientation {
    Orientation::from_f64(-robust::orient3d(c3(a), c3(b), c3(c), c3(d)))
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
    Orientation::from_f64(robust::insphere(c3(b), c3(a), c3(c), c3(d), c3(e)))
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
