//! Which side of a surface a point lies on, "above" meaning larger z: the vertical line through
//! the point is cast against the surface, exactly.
//!
//! The surface's triangles are indexed by their xy boxes. A triangle is crossed by the vertical
//! through `q` when `q`'s xy projection lies inside the triangle's projection; the projection of
//! `q` is symbolically perturbed by `(ε, ε²)` so that it never lies on a projected edge or vertex
//! (simulation of simplicity): each orientation that is exactly zero is replaced by the sign of
//! the perturbation's leading term, a comparison of input coordinates. Neighbouring triangles
//! therefore agree on which of them holds the perturbed point, and a surface that is a height
//! field over `q` is crossed exactly once. Vertical triangles (zero projected area) are never
//! crossed. Whether the crossing is above or below `q` is an exact `orient3d` against the
//! triangle, oriented by its projection.
//!
//! With `up` crossings above `q` and `down` below, `q` is below the surface when `up` is odd and
//! above it when `down` is odd: the surface separates the column into the part that reaches
//! z = +∞ and the part that reaches z = −∞. An even total (a fold that crosses the column twice,
//! or none: the surface does not cover `q`'s xy) leaves the side undefined. A point that is a
//! vertex of the surface, or lies on one of its crossed triangles, is on the surface.

use geom::{Orientation, TriMesh, orient2d, orient3d};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};
use std::collections::BTreeSet;

/// Where a point lies relative to a surface.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Larger z than the surface in its column.
    Above,
    Below,
    /// On the surface: a vertex of it, or on a triangle the column crosses.
    On,
    /// The vertical through the point does not meet the surface.
    Uncovered,
    /// The vertical meets the surface an even, non-zero number of times (a fold).
    Folded(u32),
}

/// A surface prepared for vertical casts.
pub struct Column<'a> {
    mesh: &'a TriMesh,
    tree: RTree<GeomWithData<Rectangle<[f64; 2]>, u32>>,
    /// The surface's vertices, by coordinate bits: the curve points shared bit for bit with the
    /// surfaces split along it.
    vertices: BTreeSet<[u64; 3]>,
}

fn xy(p: &[f64; 3]) -> [f64; 2] {
    [p[0], p[1]]
}

fn bits(p: &[f64; 3]) -> [u64; 3] {
    p.map(|c| if c == 0.0 { 0 } else { c.to_bits() })
}

/// The sign of `orient2d(a, b, q + (ε, ε²))` for infinitesimal ε > 0; `Zero` only when `a` and
/// `b` have the same xy.
fn perturbed(a: &[f64; 2], b: &[f64; 2], q: &[f64; 2]) -> Orientation {
    match orient2d(a, b, q) {
        Orientation::Zero => {
            // (b - a) × (ε, ε²) = (bx - ax) ε² - (by - ay) ε: the ε term leads.
            if a[1] != b[1] {
                Orientation::from_f64(if a[1] > b[1] { 1.0 } else { -1.0 })
            } else {
                Orientation::from_f64(if b[0] > a[0] {
                    1.0
                } else if b[0] < a[0] {
                    -1.0
                } else {
                    0.0
                })
            }
        }
        o => o,
    }
}

impl<'a> Column<'a> {
    /// Indexes `mesh`; triangles pointing at missing vertices are left out (the split surfaces
    /// given here come from `split_model`, which has checked them).
    pub fn new(mesh: &'a TriMesh) -> Column<'a> {
        let nv = mesh.vertices.len();
        let items = mesh
            .triangles
            .iter()
            .enumerate()
            .filter(|(_, t)| t.iter().all(|&v| (v as usize) < nv))
            .map(|(i, _)| {
                let c = mesh.corners(i);
                let lo = [
                    c[0][0].min(c[1][0]).min(c[2][0]),
                    c[0][1].min(c[1][1]).min(c[2][1]),
                ];
                let hi = [
                    c[0][0].max(c[1][0]).max(c[2][0]),
                    c[0][1].max(c[1][1]).max(c[2][1]),
                ];
                GeomWithData::new(Rectangle::from_corners(lo, hi), i as u32)
            })
            .collect();
        Column {
            mesh,
            tree: RTree::bulk_load(items),
            vertices: mesh.vertices.iter().map(bits).collect(),
        }
    }

    /// Where `q` lies relative to the surface (see the module doc).
    pub fn locate(&self, q: &[f64; 3]) -> Verdict {
        if self.vertices.contains(&bits(q)) {
            return Verdict::On;
        }
        let q2 = xy(q);
        let (mut up, mut down) = (0u32, 0u32);
        for item in self
            .tree
            .locate_in_envelope_intersecting(AABB::from_point(q2))
        {
            let [a, b, c] = self.mesh.corners(item.data as usize);
            let (a2, b2, c2) = (xy(a), xy(b), xy(c));
            let turn = orient2d(&a2, &b2, &c2);
            if turn == Orientation::Zero {
                continue; // vertical: never crossed by a vertical line in general position
            }
            let inside = [(&a2, &b2), (&b2, &c2), (&c2, &a2)]
                .iter()
                .all(|(u, v)| perturbed(u, v, &q2) == turn);
            if !inside {
                continue;
            }
            // Positive: q is on the side of the upward normal when the projection turns
            // counter-clockwise, i.e. above the triangle.
            let side = orient3d(a, b, c, q);
            let above = match (side, turn) {
                (Orientation::Zero, _) => return Verdict::On,
                (s, t) => s == t,
            };
            if above {
                down += 1;
            } else {
                up += 1;
            }
        }
        match (up + down, up % 2 == 1) {
            (0, _) => Verdict::Uncovered,
            (n, _) if n % 2 == 0 => Verdict::Folded(n),
            (_, true) => Verdict::Below,
            (_, false) => Verdict::Above,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square [0, 2]² at height z, split along its diagonal, with counter-clockwise or
    /// clockwise triangles.
    fn square(z: f64, ccw: bool) -> TriMesh {
        let t = if ccw {
            vec![[0, 1, 2], [0, 2, 3]]
        } else {
            vec![[0, 2, 1], [0, 3, 2]]
        };
        TriMesh::new(
            vec![[0.0, 0.0, z], [2.0, 0.0, z], [2.0, 2.0, z], [0.0, 2.0, z]],
            t,
        )
    }

    #[test]
    fn a_point_over_a_plane_is_above_it_whatever_the_triangle_order() {
        for ccw in [true, false] {
            let m = square(0.0, ccw);
            let c = Column::new(&m);
            assert_eq!(c.locate(&[0.5, 1.5, 1.0]), Verdict::Above);
            assert_eq!(c.locate(&[0.5, 1.5, -1.0]), Verdict::Below);
            assert_eq!(c.locate(&[0.5, 1.5, 0.0]), Verdict::On);
            assert_eq!(c.locate(&[3.0, 1.0, 1.0]), Verdict::Uncovered);
        }
    }

    #[test]
    fn a_point_exactly_over_the_shared_diagonal_or_a_vertex_is_crossed_once() {
        let m = square(0.0, true);
        let c = Column::new(&m);
        assert_eq!(c.locate(&[1.0, 1.0, 5.0]), Verdict::Above);
        assert_eq!(c.locate(&[1.0, 1.0, -5.0]), Verdict::Below);
        assert_eq!(c.locate(&[0.0, 0.0, -5.0]), Verdict::Below);
        assert_eq!(c.locate(&[0.0, 0.0, 5.0]), Verdict::Above);
        assert_eq!(c.locate(&[2.0, 2.0, 0.0]), Verdict::On, "a vertex");
        // On the outer border the perturbation may step off the surface: (2 + ε, 2 + ε²).
        assert_eq!(c.locate(&[2.0, 2.0, 5.0]), Verdict::Uncovered);
    }

    #[test]
    fn two_stacked_sheets_cross_the_column_twice_and_leave_the_side_undefined() {
        let a = square(0.0, true);
        let mut m = square(1.0, true);
        m.vertices.extend(a.vertices);
        m.triangles
            .extend(a.triangles.iter().map(|t| t.map(|v| v + 4)));
        let c = Column::new(&m);
        assert_eq!(c.locate(&[0.5, 1.5, 0.5]), Verdict::Folded(2));
        assert_eq!(c.locate(&[0.5, 1.5, 2.0]), Verdict::Folded(2));
    }
}
