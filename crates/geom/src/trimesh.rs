//! An indexed triangle mesh with f64 coordinates: the support triangulation of a surface or a
//! patch, and the exchange type between import, intersection, splitting and surface meshing.

use super::BBox;

/// A point's coordinates as bits, -0.0 taken as 0.0: a map key under which two points are one
/// exactly when their coordinates are equal.
pub fn point_key(p: &[f64; 3]) -> [u64; 3] {
    p.map(|x| if x == 0.0 { 0 } else { x.to_bits() })
}
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TriMesh {
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    pub fn new(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Self {
        TriMesh {
            vertices,
            triangles,
        }
    }
    pub fn bbox(&self) -> BBox {
        BBox::from_points(self.vertices.iter())
    }
    pub fn corners(&self, t: usize) -> [&[f64; 3]; 3] {
        let [a, b, c] = self.triangles[t];
        [
            &self.vertices[a as usize],
            &self.vertices[b as usize],
            &self.vertices[c as usize],
        ]
    }
    pub fn triangle_bbox(&self, t: usize) -> BBox {
        BBox::from_points(self.corners(t))
    }
    /// The border edges (used by exactly one triangle), each as (smaller id, larger id).
    pub fn border_edges(&self) -> std::collections::BTreeSet<(u32, u32)> {
        let mut uses: std::collections::BTreeMap<(u32, u32), u32> = Default::default();
        for t in &self.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *uses.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        (uses.into_iter())
            .filter(|&(_, n)| n == 1)
            .map(|(e, _)| e)
            .collect()
    }
    /// The unit normal of every triangle (zero where a triangle has none or names a vertex the
    /// mesh does not have).
    pub fn unit_normals(&self) -> Vec<[f64; 3]> {
        use super::predicates::{cross, dot, sub};
        let normal = |tri: &[u32; 3]| {
            let p = |k: usize| self.vertices.get(tri[k] as usize);
            let (Some(a), Some(b), Some(c)) = (p(0), p(1), p(2)) else {
                return [0.0; 3];
            };
            let n = cross(&sub(b, a), &sub(c, a));
            let l = dot(&n, &n).sqrt();
            if l > 0.0 { n.map(|x| x / l) } else { [0.0; 3] }
        };
        self.triangles.iter().map(normal).collect()
    }
    /// Sum of triangle areas (floating point, for measures).
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| triangle_area(self.corners(t)))
            .sum()
    }
}

/// Area of a triangle (floating point, for measures).
pub fn triangle_area([a, b, c]: [&[f64; 3]; 3]) -> f64 {
    use super::predicates::{cross, sub};
    let n = cross(&sub(b, a), &sub(c, a));
    0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
}
