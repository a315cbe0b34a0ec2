//! Exact tests between the simplices the tetrahedral mesher manipulates.
//!
//! Every decision (does a candidate tetrahedron's face cut a front triangle, is a front node
//! inside a candidate tetrahedron, does the boundary intersect itself) is taken with the exact
//! `orient3d`/`orient2d` predicates of `geom`: no epsilon, no constructed intersection point.
//! Triangles are given by node indices, so "touching" is judged combinatorially: two triangles may
//! meet exactly in the vertices/edge they share by index; any other contact — including two
//! distinct nodes at identical coordinates — is an improper intersection (`geom::contact`, which
//! surface validation shares).

use geom::predicates::Orientation;

type P = [f64; 3];

/// The exact `orient3d` with shortcuts for repeated and axis-coplanar points, which the mesher
/// meets all the time (`geom::predicates::orient3d_shortcut`).
pub use geom::predicates::orient3d_shortcut as orient3d;

/// True when `x` lies in the closed tetrahedron `abcd` (positively oriented).
#[inline]
pub fn point_in_closed_tet(x: &P, a: &P, b: &P, c: &P, d: &P) -> bool {
    orient3d(x, b, c, d) != Orientation::Negative
        && orient3d(a, x, c, d) != Orientation::Negative
        && orient3d(a, b, x, d) != Orientation::Negative
        && orient3d(a, b, c, x) != Orientation::Negative
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
        ]
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
}
