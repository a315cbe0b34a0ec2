//! Exact geometry shared by every stage: predicates (the only place orientation and
//! inside/outside decisions are taken), the one `Tolerances` struct, bounding boxes and
//! triangle meshes with f64 coordinates as read (never rescaled), the exact contact tests
//! between triangles and segments (`contact`) with the broad phase that proposes their pairs
//! (`broad_phase`), the closest point of a triangle (`closest`), and the FE mesh types the
//! meshing stages exchange (`mesh`, with readers for the formats meshes come in);
//! `progress`, how a long stage reports how far it got without knowing who watches; and
//! `spatial_order`, the order in which the Delaunay meshers insert points.

pub mod adjacency;
pub mod bbox;
pub mod broad_phase;
pub mod closest;
pub mod contact;
pub mod facets;
pub mod mesh;
pub mod predicates;
pub mod progress;
pub mod refine;
pub mod spatial_order;
pub mod stretch;
pub mod tolerances;
pub mod trimesh;
pub mod units;

pub use bbox::BBox;
pub use predicates::{Orientation, insphere, orient2d, orient3d};
pub use tolerances::Tolerances;
pub use trimesh::{TriMesh, point_key};
pub use units::Units;

/// A point in model coordinates (metres, or the recipe's units), as read from the input.
pub type Point3 = [f64; 3];

/// How an error message ends with the place it concerns: ` at (x, y, z)`, or nothing.
pub fn at_suffix(at: &Option<Point3>) -> String {
    match at {
        Some(p) => format!(" at ({}, {}, {})", p[0], p[1], p[2]),
        None => String::new(),
    }
}
