//! Exact location tests between a triangle and a point or a segment: where a point coplanar with
//! a triangle lies in it, where a segment that crosses a triangle's plane pierces it, whether two
//! coplanar triangles overlap in their interiors, and whether a triangle is degenerate. Every
//! answer comes from `orient3d`/`orient2d` on input coordinates (seed eq. 1, 6): no tolerance,
//! and no constructed point ever takes part in a decision.

use geom::{Orientation, orient2d, orient3d};

/// Where a point lies in a closed triangle `[p0, p1, p2]`, in the triangle's own numbering:
/// edge `k` joins corners `k` and `k + 1 (mod 3)`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum TriLoc {
    Face,
    Edge(usize),
    Vertex(usize),
}

/// The corner shared by triangle edges `e` and `f` (distinct, in 0..3).
fn common_corner(e: usize, f: usize) -> usize {
    match (e.min(f), e.max(f)) {
        (0, 1) => 1,
        (1, 2) => 2,
        _ => 0,
    }
}

/// Turn three edge signs (all of one sign or zero) into a location. `None` when the signs
/// disagree (outside) or when all three are zero (impossible for a non-degenerate triangle).
fn from_edge_signs(s: [Orientation; 3], inside: Orientation) -> Option<TriLoc> {
    if s.iter().any(|&o| o != Orientation::Zero && o != inside) {
        return None;
    }
    let zeros: Vec<usize> = (0..3).filter(|&k| s[k] == Orientation::Zero).collect();
    match zeros.as_slice() {
        [] => Some(TriLoc::Face),
        [e] => Some(TriLoc::Edge(*e)),
        [e, f] => Some(TriLoc::Vertex(common_corner(*e, *f))),
        _ => None,
    }
}

/// Drop coordinate `axis` (0, 1 or 2).
#[inline]
pub fn project(p: &[f64; 3], axis: usize) -> [f64; 2] {
    match axis {
        0 => [p[1], p[2]],
        1 => [p[2], p[0]],
        _ => [p[0], p[1]],
    }
}

/// An axis whose removal keeps the triangle non-degenerate in 2D, with the sign of the
/// projected triangle; `None` for a degenerate (collinear) triangle. The float normal only
/// orders the attempts; the answer is the exact `orient2d`.
pub fn projection_axis(t: &[[f64; 3]; 3]) -> Option<(usize, Orientation)> {
    let n = geom::predicates::cross(
        &geom::predicates::sub(&t[1], &t[0]),
        &geom::predicates::sub(&t[2], &t[0]),
    );
    let mut axes = [0usize, 1, 2];
    axes.sort_by(|&i, &j| n[j].abs().total_cmp(&n[i].abs()).then(i.cmp(&j)));
    for axis in axes {
        let o = orient2d(
            &project(&t[0], axis),
            &project(&t[1], axis),
            &project(&t[2], axis),
        );
        if o != Orientation::Zero {
            return Some((axis, o));
        }
    }
    None
}

/// True when the triangle's corners are collinear (or coincide): exactly zero area.
pub fn is_degenerate(t: &[[f64; 3]; 3]) -> bool {
    projection_axis(t).is_none()
}

/// Location of `x`, known to be coplanar with the non-degenerate triangle `t`, in the closed
/// triangle; `None` when outside. `axis`/`sign` come from [`projection_axis`]; since `x` lies in
/// the plane, the projected test decides the 3D question exactly.
pub fn locate_coplanar(
    t: &[[f64; 3]; 3],
    axis: usize,
    sign: Orientation,
    x: &[f64; 3],
) -> Option<TriLoc> {
    let q = [
        project(&t[0], axis),
        project(&t[1], axis),
        project(&t[2], axis),
    ];
    let xp = project(x, axis);
    let s = [
        orient2d(&q[0], &q[1], &xp),
        orient2d(&q[1], &q[2], &xp),
        orient2d(&q[2], &q[0], &xp),
    ];
    from_edge_signs(s, sign)
}

/// Where the segment `pq`, whose endpoints lie strictly on opposite sides of the plane of `t`,
/// pierces the closed triangle `t`; `None` when it passes outside. Uses the signed volumes of the
/// segment with each triangle edge: the line meets the triangle iff they agree in sign.
pub fn locate_crossing(t: &[[f64; 3]; 3], p: &[f64; 3], q: &[f64; 3]) -> Option<TriLoc> {
    let s = [
        orient3d(p, q, &t[0], &t[1]),
        orient3d(p, q, &t[1], &t[2]),
        orient3d(p, q, &t[2], &t[0]),
    ];
    let inside = s.iter().copied().find(|&o| o != Orientation::Zero)?;
    from_edge_signs(s, inside)
}

/// Whether two coplanar, non-degenerate triangles share interior points. Two convex polygons
/// have disjoint interiors iff a line through an edge of one weakly separates them, so the
/// test tries the six edge lines with exact `orient2d` in the common projection.
pub fn coplanar_interiors_overlap(t: &[[f64; 3]; 3], u: &[[f64; 3]; 3], axis: usize) -> bool {
    let pt = [
        project(&t[0], axis),
        project(&t[1], axis),
        project(&t[2], axis),
    ];
    let pu = [
        project(&u[0], axis),
        project(&u[1], axis),
        project(&u[2], axis),
    ];
    !(separated_by_an_edge_of(&pt, &pu) || separated_by_an_edge_of(&pu, &pt))
}

fn separated_by_an_edge_of(t: &[[f64; 2]; 3], u: &[[f64; 2]; 3]) -> bool {
    (0..3).any(|k| {
        let (a, b, c) = (&t[k], &t[(k + 1) % 3], &t[(k + 2) % 3]);
        let own = orient2d(a, b, c);
        u.iter().all(|v| {
            let o = orient2d(a, b, v);
            o == Orientation::Zero || o == own.flip()
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: [[f64; 3]; 3] = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];

    #[test]
    fn a_segment_through_a_corner_is_located_at_that_corner() {
        let loc = locate_crossing(&T, &[2.0, 0.0, 1.0], &[2.0, 0.0, -1.0]);
        assert_eq!(loc, Some(TriLoc::Vertex(1)));
    }

    #[test]
    fn a_segment_through_an_edge_midpoint_is_located_on_that_edge() {
        assert_eq!(
            locate_crossing(&T, &[1.0, 1.0, 1.0], &[1.0, 1.0, -3.0]),
            Some(TriLoc::Edge(1))
        );
        assert_eq!(
            locate_crossing(&T, &[0.5, 0.5, 1.0], &[0.5, 0.5, -3.0]),
            Some(TriLoc::Face)
        );
        assert_eq!(
            locate_crossing(&T, &[1.5, 1.5, 1.0], &[1.5, 1.5, -3.0]),
            None
        );
    }

    #[test]
    fn a_coplanar_point_is_located_exactly_at_utm_magnitudes() {
        let o = [512_345.125, 7_012_345.5, -1234.25];
        let t = [
            o,
            [o[0] + 3.0, o[1], o[2] + 1.0],
            [o[0], o[1] + 3.0, o[2] + 2.0],
        ];
        let (axis, sign) = projection_axis(&t).expect("non-degenerate");
        let mid = [o[0] + 1.5, o[1], o[2] + 0.5];
        assert_eq!(locate_coplanar(&t, axis, sign, &mid), Some(TriLoc::Edge(0)));
        assert_eq!(
            locate_coplanar(&t, axis, sign, &t[2]),
            Some(TriLoc::Vertex(2))
        );
    }

    #[test]
    fn collinear_corners_make_a_degenerate_triangle() {
        assert!(is_degenerate(&[
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [3.0, 3.0, 3.0]
        ]));
        assert!(!is_degenerate(&T));
    }

    #[test]
    fn coplanar_triangles_sharing_only_an_edge_do_not_overlap() {
        let u = [[2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [2.0, 2.0, 0.0]];
        assert!(!coplanar_interiors_overlap(&T, &u, 2));
        let v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [2.0, 2.0, 0.0]];
        assert!(coplanar_interiors_overlap(&T, &v, 2));
        assert!(coplanar_interiors_overlap(&T, &T, 2));
    }
}
