//! An indexed triangle mesh with f64 coordinates: the support triangulation of a surface or a
//! patch, and the exchange type between import, intersection, splitting and surface meshing.

use super::BBox;
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
