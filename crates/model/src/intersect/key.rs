//! Symbolic provenance of intersection points. A point where surface `a` meets surface `b` is
//! named by the smallest mesh entity containing it on each surface (vertex, edge or face). These
//! names are decided by exact predicates only, so the same point found from two different triangle
//! pairs gets the same key and merges by key, never by distance; the coordinates are constructed
//! afterwards from the key alone.

use serde::{Deserialize, Serialize};

/// Where a point lies on one surface: the smallest mesh entity that contains it.
/// Edges are stored with the smaller vertex index first.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Location {
    /// Exactly at vertex `i`.
    Vertex(u32),
    /// In the relative interior of the edge between vertices `i < j`.
    Edge(u32, u32),
    /// In the relative interior of triangle `t`.
    Face(u32),
}

impl Location {
    /// An edge location with its vertices sorted (the canonical form).
    pub fn edge(i: u32, j: u32) -> Location {
        if i <= j {
            Location::Edge(i, j)
        } else {
            Location::Edge(j, i)
        }
    }
}

/// The canonical key of an intersection point: its location on surface `a` (the surface whose
/// name sorts first) and on surface `b`. The variant name reads "location on a, location on b";
/// e.g. `EdgeFace { a: (i, j), b: t }` is edge `ij` of `a` crossing the interior of triangle `t`
/// of `b`. Two faces cannot meet in a single point, so there is no `FaceFace`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum PointKey {
    VertexVertex { a: u32, b: u32 },
    VertexEdge { a: u32, b: (u32, u32) },
    EdgeVertex { a: (u32, u32), b: u32 },
    VertexFace { a: u32, b: u32 },
    FaceVertex { a: u32, b: u32 },
    EdgeEdge { a: (u32, u32), b: (u32, u32) },
    EdgeFace { a: (u32, u32), b: u32 },
    FaceEdge { a: u32, b: (u32, u32) },
}

impl PointKey {
    /// The key of a point at `on_a` on surface `a` and `on_b` on surface `b`; `None` for two faces.
    pub fn new(on_a: Location, on_b: Location) -> Option<PointKey> {
        use Location::*;
        Some(match (on_a, on_b) {
            (Vertex(a), Vertex(b)) => PointKey::VertexVertex { a, b },
            (Vertex(a), Edge(i, j)) => PointKey::VertexEdge { a, b: (i, j) },
            (Edge(i, j), Vertex(b)) => PointKey::EdgeVertex { a: (i, j), b },
            (Vertex(a), Face(b)) => PointKey::VertexFace { a, b },
            (Face(a), Vertex(b)) => PointKey::FaceVertex { a, b },
            (Edge(i, j), Edge(k, l)) => PointKey::EdgeEdge {
                a: (i, j),
                b: (k, l),
            },
            (Edge(i, j), Face(b)) => PointKey::EdgeFace { a: (i, j), b },
            (Face(a), Edge(k, l)) => PointKey::FaceEdge { a, b: (k, l) },
            (Face(_), Face(_)) => return None,
        })
    }

    /// The location of the point on surface `a` and on surface `b`.
    pub fn locations(&self) -> (Location, Location) {
        use Location::*;
        match *self {
            PointKey::VertexVertex { a, b } => (Vertex(a), Vertex(b)),
            PointKey::VertexEdge { a, b } => (Vertex(a), Edge(b.0, b.1)),
            PointKey::EdgeVertex { a, b } => (Edge(a.0, a.1), Vertex(b)),
            PointKey::VertexFace { a, b } => (Vertex(a), Face(b)),
            PointKey::FaceVertex { a, b } => (Face(a), Vertex(b)),
            PointKey::EdgeEdge { a, b } => (Edge(a.0, a.1), Edge(b.0, b.1)),
            PointKey::EdgeFace { a, b } => (Edge(a.0, a.1), Face(b)),
            PointKey::FaceEdge { a, b } => (Face(a), Edge(b.0, b.1)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_key_round_trips_through_its_locations() {
        let k =
            PointKey::new(Location::edge(7, 3), Location::Face(2)).expect("edge x face is a point");
        assert_eq!(k, PointKey::EdgeFace { a: (3, 7), b: 2 });
        assert_eq!(k.locations(), (Location::Edge(3, 7), Location::Face(2)));
    }

    #[test]
    fn two_faces_have_no_point_key() {
        assert_eq!(PointKey::new(Location::Face(0), Location::Face(1)), None);
    }
}
