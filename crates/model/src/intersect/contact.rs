//! Triangle–triangle contact, decided exactly. For two non-coplanar triangles the contact is a
//! segment (or a point) on the line where their planes meet; its ends are points of the boundary
//! of one triangle that lie in the other, so they are found by the segment–triangle test of the
//! seed (§2.3, eq. 1–6) run on each triangle's vertices and edges against the other triangle.
//! Each end is named by its locations on both surfaces ([`Location`]): the same geometric point
//! always gets the same name, whichever side found it. Coplanar pairs are split into those whose
//! interiors overlap (reported as coplanar contacts) and those touching along their boundaries.

use super::key::Location;
use super::locate::{
    TriLoc, coplanar_interiors_overlap, locate_coplanar, locate_crossing, projection_axis,
};
use geom::{Orientation, orient3d};

/// One triangle of one surface: its index, corner vertex indices and corner coordinates.
#[derive(Copy, Clone, Debug)]
pub struct Tri {
    pub index: u32,
    pub v: [u32; 3],
    pub p: [[f64; 3]; 3],
}

impl Tri {
    /// The global location of a location given in this triangle's own numbering.
    fn global(&self, l: TriLoc) -> Location {
        match l {
            TriLoc::Face => Location::Face(self.index),
            TriLoc::Edge(k) => Location::edge(self.v[k], self.v[(k + 1) % 3]),
            TriLoc::Vertex(k) => Location::Vertex(self.v[k]),
        }
    }
}

/// What two triangles share.
#[derive(Clone, Debug, PartialEq)]
pub enum Contact {
    /// Nothing.
    None,
    /// A single point or a segment, given by the distinct `(on_a, on_b)` locations of its ends
    /// (one or two of them, sorted).
    Points(Vec<(Location, Location)>),
    /// Coplanar triangles whose interiors overlap (the seed aborts here).
    CoplanarOverlap,
    /// Coplanar triangles touching only along their boundaries: the points, as for `Points`.
    CoplanarTouch(Vec<(Location, Location)>),
    /// More than two distinct contact points on non-coplanar triangles: impossible with exact
    /// predicates; kept as an explicit outcome so that no input can trigger a panic.
    Inconsistent,
}

fn all_strictly_one_side(o: &[Orientation; 3]) -> bool {
    (o[0] == Orientation::Positive
        && o[1] == Orientation::Positive
        && o[2] == Orientation::Positive)
        || (o[0] == Orientation::Negative
            && o[1] == Orientation::Negative
            && o[2] == Orientation::Negative)
}

fn side(t: &Tri, u: &Tri) -> [Orientation; 3] {
    [
        orient3d(&u.p[0], &u.p[1], &u.p[2], &t.p[0]),
        orient3d(&u.p[0], &u.p[1], &u.p[2], &t.p[1]),
        orient3d(&u.p[0], &u.p[1], &u.p[2], &t.p[2]),
    ]
}

/// The points where the boundary of `own` meets the closed triangle `other`, as
/// `(location on own, location on other)`. `o` are the sides of `own`'s corners w.r.t.
/// `other`'s plane; `other` must be non-degenerate and not coplanar with `own`.
fn boundary_points(
    own: &Tri,
    other: &Tri,
    o: &[Orientation; 3],
    out: &mut Vec<(Location, Location)>,
) {
    if let Some((axis, sign)) = projection_axis(&other.p) {
        for (k, ok) in o.iter().enumerate() {
            if *ok == Orientation::Zero
                && let Some(l) = locate_coplanar(&other.p, axis, sign, &own.p[k])
            {
                out.push((Location::Vertex(own.v[k]), other.global(l)));
            }
        }
    }
    for k in 0..3 {
        let l = (k + 1) % 3;
        if o[k] != Orientation::Zero
            && o[l] == o[k].flip()
            && let Some(loc) = locate_crossing(&other.p, &own.p[k], &own.p[l])
        {
            out.push((Location::edge(own.v[k], own.v[l]), other.global(loc)));
        }
    }
}

fn coplanar_points(
    own: &Tri,
    other: &Tri,
    axis: usize,
    sign: Orientation,
    out: &mut Vec<(Location, Location)>,
) {
    for k in 0..3 {
        if let Some(l) = locate_coplanar(&other.p, axis, sign, &own.p[k]) {
            out.push((Location::Vertex(own.v[k]), other.global(l)));
        }
    }
}

/// The exact contact of triangle `ta` of surface `a` with triangle `tb` of surface `b`. Both
/// must be non-degenerate (see [`super::locate::is_degenerate`]).
pub fn contact(ta: &Tri, tb: &Tri) -> Contact {
    let oa = side(ta, tb);
    if all_strictly_one_side(&oa) {
        return Contact::None;
    }
    let ob = side(tb, ta);
    if all_strictly_one_side(&ob) {
        return Contact::None;
    }
    let mut pts: Vec<(Location, Location)> = Vec::with_capacity(4);
    let coplanar = oa.iter().all(|&o| o == Orientation::Zero);
    if coplanar {
        let Some((axis, _)) = projection_axis(&tb.p) else {
            return Contact::None;
        };
        if coplanar_interiors_overlap(&ta.p, &tb.p, axis) {
            return Contact::CoplanarOverlap;
        }
        if let (Some((ax_b, s_b)), Some((ax_a, s_a))) =
            (projection_axis(&tb.p), projection_axis(&ta.p))
        {
            coplanar_points(ta, tb, ax_b, s_b, &mut pts);
            let mut rev = Vec::with_capacity(3);
            coplanar_points(tb, ta, ax_a, s_a, &mut rev);
            pts.extend(rev.into_iter().map(|(on_b, on_a)| (on_a, on_b)));
        }
    } else {
        boundary_points(ta, tb, &oa, &mut pts);
        let mut rev = Vec::with_capacity(3);
        boundary_points(tb, ta, &ob, &mut rev);
        pts.extend(rev.into_iter().map(|(on_b, on_a)| (on_a, on_b)));
    }
    pts.sort();
    pts.dedup();
    match (pts.len(), coplanar) {
        (0, _) => Contact::None,
        (1 | 2, false) => Contact::Points(pts),
        (1 | 2, true) => Contact::CoplanarTouch(pts),
        _ => Contact::Inconsistent,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(index: u32, v: [u32; 3], p: [[f64; 3]; 3]) -> Tri {
        Tri { index, v, p }
    }

    #[test]
    fn two_crossing_triangles_meet_in_a_segment_between_edge_crossings() {
        let a = tri(
            0,
            [0, 1, 2],
            [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]],
        );
        let b = tri(
            5,
            [10, 11, 12],
            [[1.0, -1.0, -1.0], [1.0, 5.0, -1.0], [1.0, 0.0, 3.0]],
        );
        match contact(&a, &b) {
            Contact::Points(p) => {
                assert_eq!(p.len(), 2);
                assert!(p.iter().all(|(_, on_b)| *on_b == Location::Face(5)));
            }
            other => panic!("expected a segment, got {other:?}"),
        }
    }

    #[test]
    fn a_shared_corner_is_found_once_from_both_sides() {
        let a = tri(
            0,
            [0, 1, 2],
            [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        );
        let b = tri(
            1,
            [7, 8, 9],
            [[0.0, 0.0, 0.0], [0.0, -1.0, 1.0], [-1.0, 0.0, 1.0]],
        );
        assert_eq!(
            contact(&a, &b),
            Contact::Points(vec![(Location::Vertex(0), Location::Vertex(7))])
        );
    }

    #[test]
    fn identical_coplanar_triangles_overlap() {
        let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert_eq!(
            contact(&tri(0, [0, 1, 2], p), &tri(0, [0, 1, 2], p)),
            Contact::CoplanarOverlap
        );
    }
}
