//! Stage `validate`: the seed's "black-list" of surface defects, found exactly and reported per
//! surface and part with entity ids, source lines and coordinates.
//!
//! It decides, for one imported surface: which vertices no triangle uses, which vertices coincide
//! (`Tolerances::merge_distance`, exact equality by default), which triangles are degenerate
//! (exactly collinear corners, by `orient2d` on the three axis planes) or duplicated, which
//! neighbours disagree on orientation, which edges carry three or more triangles, and which
//! non-adjacent triangles cross or overlap in one plane (`geom::broad_phase` and the exact
//! `geom::contact`, shared with the tet mesher's input check).
//! What to do about them is the recipe's choice: [`repair`] fixes what is safe, or the build stops.
//! Repair removes unreferenced and duplicate vertices, degenerate and duplicate triangles and
//! inconsistent orientation (except where a piece is not orientable); non-manifold edges,
//! coplanar overlaps and self-intersections remain. Validating the repaired surface says exactly
//! what remains, and [`repair_summary`] says it in one line.

mod checks;
mod repair;
mod report;
mod selfint;

pub use checks::canonical_vertices;
pub use geom::contact::Contact;
pub use repair::{RepairLog, repair};
pub use report::{Finding, FindingKind, ValidationReport, repair_summary, repaired_counts};

use crate::import::ImportedSurface;
use checks::{TriStatus, edge_sides, key_vertices, triangle_status};
use geom::Tolerances;

/// Runs every check of the black-list on one surface. Requires what import guarantees: every
/// triangle corner indexes an existing, finite vertex.
pub fn validate(s: &ImportedSurface, tol: &Tolerances) -> ValidationReport {
    let v = &s.mesh.vertices;
    let tris = &s.mesh.triangles;
    let mut r = ValidationReport::new(s);
    let canon = canonical_vertices(v, tol);

    // Unreferenced vertices.
    let mut used = vec![false; v.len()];
    for t in tris {
        for &i in t {
            used[i as usize] = true;
        }
    }
    for (i, u) in used.iter().enumerate() {
        if !u {
            r.push_vertices(s, FindingKind::UnreferencedVertex, &[i as u32]);
        }
    }
    // Coincident duplicates: one finding per group, members in index order.
    let mut groups: std::collections::BTreeMap<u32, Vec<u32>> = std::collections::BTreeMap::new();
    for (i, &c) in canon.iter().enumerate() {
        if c as usize != i {
            groups.entry(c).or_insert_with(|| vec![c]).push(i as u32);
        }
    }
    for members in groups.values() {
        r.push_vertices(s, FindingKind::DuplicateVertex, members);
    }

    let status = triangle_status(v, tris, &canon);
    for (t, st) in status.iter().enumerate() {
        match *st {
            TriStatus::Degenerate => {
                r.push_triangles(s, FindingKind::DegenerateTriangle, &[t as u32])
            }
            TriStatus::DuplicateOf(first) => {
                r.push_triangles(s, FindingKind::DuplicateTriangle, &[first, t as u32])
            }
            TriStatus::Ok => {}
        }
    }

    let sides = edge_sides(tris, &canon, &status);
    for g in sides.chunk_by(|a, b| a.key == b.key) {
        let tri_ids: Vec<u32> = g.iter().map(|x| x.tri).collect();
        let ends = key_vertices(g[0].key);
        if g.len() >= 3 {
            r.push_edge(s, FindingKind::NonManifoldEdge, ends, &tri_ids);
        } else if g.len() == 2 && g[0].forward == g[1].forward {
            r.push_edge(s, FindingKind::InconsistentOrientation, ends, &tri_ids);
        }
    }
    drop(sides);

    for (t, u, c) in selfint::find(v, tris, &canon, &status) {
        let kind = match c {
            Contact::CoplanarOverlap => FindingKind::CoplanarOverlap,
            _ => FindingKind::SelfIntersection,
        };
        r.push_triangles(s, kind, &[t, u]);
    }
    r.sort();
    r
}
