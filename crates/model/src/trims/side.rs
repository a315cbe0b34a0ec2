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
//!
//! A closed surface encloses `q` when the column above `q` crosses it an odd number of times
//! (the same count, so the same exact decision).

use geom::{Orientation, TriMesh, orient2d, orient3d};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};
use std::collections::{BTreeMap, BTreeSet};

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

/// Where a point lies relative to a closed surface.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Enclosure {
    Inside,
    Outside,
    /// A vertex of the surface, or on a triangle the column crosses.
    On,
}

/// A point of an edge that an odd number of triangles of `mesh` use (one: a free border; three:
/// a sheet hanging off), vertices matched by their coordinates so that copies of one point along
/// a cut count as one, the smallest such edge first; `None` when the surface is closed and the
/// parity of the column's crossings says inside or outside.
pub fn free_border(mesh: &TriMesh) -> Option<[f64; 3]> {
    let mut uses = BTreeMap::new();
    edge_uses(mesh, &mut uses);
    let odd = uses.into_iter().find(|(_, n)| n % 2 == 1)?;
    Some(odd.0.0.map(f64::from_bits))
}

/// An edge by its ends' coordinate bits, the smaller first.
pub(super) type EdgeBits = ([u64; 3], [u64; 3]);

/// Counts into `into` the triangles of `mesh` on each edge, edges matched by their ends'
/// coordinates (triangles pointing at missing vertices are left out).
pub(super) fn edge_uses(mesh: &TriMesh, into: &mut BTreeMap<EdgeBits, u32>) {
    let nv = mesh.vertices.len();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tri.iter().any(|&v| v as usize >= nv) {
            continue;
        }
        let c = mesh.corners(t);
        for k in 0..3 {
            let (a, b) = (bits(c[k]), bits(c[(k + 1) % 3]));
            *into.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
}

/// A surface prepared for vertical casts.
pub struct Column<'a> {
    mesh: &'a TriMesh,
    tree: RTree<GeomWithData<Rectangle<[f64; 2]>, u32>>,
    /// The surface's vertices, by coordinate bits: the curve points shared bit for bit with the
    /// surfaces split along it.
    vertices: BTreeSet<[u64; 3]>,
    /// The surface's triangles as sorted triples of vertex coordinates' bits.
    triangles: BTreeSet<[[u64; 3]; 3]>,
}

/// A triangle as the sorted triple of its corners' coordinate bits.
fn triangle_key(c: [&[f64; 3]; 3]) -> [[u64; 3]; 3] {
    let mut k = c.map(bits);
    k.sort();
    k
}

fn xy(p: &[f64; 3]) -> [f64; 2] {
    [p[0], p[1]]
}

pub(super) fn bits(p: &[f64; 3]) -> [u64; 3] {
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
            triangles: (0..mesh.triangles.len())
                .filter(|&t| mesh.triangles[t].iter().all(|&v| (v as usize) < nv))
                .map(|t| triangle_key(mesh.corners(t)))
                .collect(),
        }
    }

    /// Where `q` lies relative to the surface (see the module doc).
    pub fn locate(&self, q: &[f64; 3]) -> Verdict {
        let Some((up, down)) = self.crossings(q) else {
            return Verdict::On;
        };
        match (up + down, up % 2 == 1) {
            (0, _) => Verdict::Uncovered,
            (n, _) if n % 2 == 0 => Verdict::Folded(n),
            (_, true) => Verdict::Below,
            (_, false) => Verdict::Above,
        }
    }

    /// Whether a closed surface encloses `q`: the column above `q` crosses it an odd number of
    /// times. Meaningless for a surface that is not closed (see [`free_border`]).
    pub fn enclosure(&self, q: &[f64; 3]) -> Enclosure {
        match self.crossings(q) {
            None => Enclosure::On,
            Some((up, _)) if up % 2 == 1 => Enclosure::Inside,
            Some(_) => Enclosure::Outside,
        }
    }

    /// Whether the surface has a triangle with exactly these corners (bit for bit, in any
    /// order): two surfaces that share a face there.
    pub fn has_triangle(&self, corners: [&[f64; 3]; 3]) -> bool {
        self.triangles.contains(&triangle_key(corners))
    }

    /// How many times the column through `q` crosses the surface above and below `q`; `None`
    /// when `q` is on the surface.
    fn crossings(&self, q: &[f64; 3]) -> Option<(u32, u32)> {
        if self.vertices.contains(&bits(q)) {
            return None;
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
                (Orientation::Zero, _) => return None,
                (s, t) => s == t,
            };
            if above {
                down += 1;
            } else {
                up += 1;
            }
        }
        Some((up, down))
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

    fn cuboid() -> TriMesh {
        let (v, t) = test_support::shapes::cuboid([0.0; 3], [2.0; 3]);
        TriMesh::new(v, t)
    }

    #[test]
    fn a_closed_surface_encloses_points_by_the_parity_of_the_column_above_them() {
        for (v, t) in [
            test_support::shapes::cuboid([0.0; 3], [2.0; 3]),
            test_support::shapes::octahedron(),
        ] {
            // The octahedron scaled and moved to have the cuboid's centre.
            let v = if v.len() == 6 {
                v.iter().map(|p| p.map(|x| 1.0 + x)).collect()
            } else {
                v
            };
            let m = TriMesh::new(v, t);
            let c = Column::new(&m);
            assert_eq!(c.enclosure(&[1.0, 1.0, 1.0]), Enclosure::Inside);
            assert_eq!(c.enclosure(&[0.9, 1.2, 1.3]), Enclosure::Inside);
            assert_eq!(c.enclosure(&[1.0, 1.0, 3.0]), Enclosure::Outside, "above");
            assert_eq!(c.enclosure(&[1.0, 1.0, -1.0]), Enclosure::Outside, "below");
            assert_eq!(c.enclosure(&[3.0, 1.0, 1.0]), Enclosure::Outside, "beside");
            assert_eq!(c.enclosure(&m.vertices[0]), Enclosure::On, "a vertex");
        }
        // Exactly under a corner of the cuboid's top: the column crosses it once all the same.
        let m = cuboid();
        let c = Column::new(&m);
        assert_eq!(c.enclosure(&[1.0, 1.0, 0.5]), Enclosure::Inside);
        assert_eq!(c.enclosure(&[1.0, 1.0, 2.0]), Enclosure::On, "on the top");
    }

    #[test]
    fn a_surface_is_closed_when_every_edge_has_an_even_number_of_triangles() {
        assert_eq!(free_border(&cuboid()), None);
        let mut open = cuboid();
        let gone = open.triangles.pop().expect("a triangle");
        let at = free_border(&open).expect("a free border");
        assert!(
            gone.iter().any(|&v| open.vertices[v as usize] == at),
            "{at:?}"
        );
        // A copy of a vertex along a cut is the same point: still closed.
        let mut cut = cuboid();
        cut.vertices.push(cut.vertices[0]);
        let last = cut.vertices.len() as u32 - 1;
        let t = cut
            .triangles
            .iter()
            .position(|t| t.contains(&0))
            .expect("one");
        cut.triangles[t] = cut.triangles[t].map(|v| if v == 0 { last } else { v });
        assert_eq!(free_border(&cut), None);
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
