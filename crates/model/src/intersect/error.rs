//! Why an intersection cannot be computed: messages name both surfaces and give coordinates,
//! so a geologist can find the spot in gOcad and fix it.

use thiserror::Error;

/// Two coplanar triangles whose interiors overlap (or that touch along their boundaries, when
/// listed in [`super::Intersection::coplanar`]), with a point of their common part.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CoplanarContact {
    pub tri_a: u32,
    pub tri_b: u32,
    pub at: [f64; 3],
}

fn list_contacts(c: &[CoplanarContact]) -> String {
    let mut s: Vec<String> = c
        .iter()
        .take(5)
        .map(|c| {
            format!(
                "triangle {} × triangle {} at ({}, {}, {})",
                c.tri_a, c.tri_b, c.at[0], c.at[1], c.at[2]
            )
        })
        .collect();
    if c.len() > 5 {
        s.push(format!("… and {} more", c.len() - 5));
    }
    s.join("; ")
}

#[derive(Clone, Debug, PartialEq, Error)]
pub enum IntersectError {
    #[error(
        "surfaces `{a}` and `{b}` overlap where they are coplanar ({} triangle pairs): {}; \
         move or re-triangulate one of them",
        contacts.len(),
        list_contacts(contacts)
    )]
    Coplanar {
        a: String,
        b: String,
        contacts: Vec<CoplanarContact>,
    },
    #[error(
        "surfaces `{a}` and `{b}` hold {shared} triangle(s) in common, and elsewhere cross each \
         other at {angle:.2}° at ({}, {}, {}): one draws the other again there with other \
         triangles, so they cross over and over; keep one drawing of that part (cut it from the \
         other in the data, or discard the other's patches there with a `[[trim]]`)",
        at[0], at[1], at[2]
    )]
    Redrawn {
        a: String,
        b: String,
        shared: usize,
        angle: f64,
        at: [f64; 3],
    },
    #[error("cannot intersect surface `{name}` with itself")]
    SameSurface { name: String },
    #[error(
        "surface `{surface}`: triangle {triangle} refers to vertex {vertex}, but the surface has only {count} vertices"
    )]
    BadVertexIndex {
        surface: String,
        triangle: u32,
        vertex: u32,
        count: usize,
    },
    #[error("surface `{surface}`: vertex {vertex} has a non-finite coordinate ({}, {}, {})", xyz[0], xyz[1], xyz[2])]
    NonFinite {
        surface: String,
        vertex: u32,
        xyz: [f64; 3],
    },
    #[error("surface `{surface}` has {count} triangles, more than 2^32 - 1")]
    TooLarge { surface: String, count: usize },
    #[error(
        "surfaces `{a}` and `{b}`: triangles {tri_a} and {tri_b} near ({}, {}, {}) gave an inconsistent contact \
         (more than two contact points); please report this input",
        at[0], at[1], at[2]
    )]
    Inconsistent {
        a: String,
        b: String,
        tri_a: u32,
        tri_b: u32,
        at: [f64; 3],
    },
}
