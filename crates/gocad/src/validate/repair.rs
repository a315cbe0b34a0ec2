//! Safe repairs of the black-list: merge coincident vertices (onto the lowest index), drop
//! degenerate and duplicate triangles, make orientation consistent per connected piece (each
//! piece keeps the orientation of its lowest-index triangle), and drop the vertices no triangle
//! uses. Non-manifold edges and intersections are not "safe" to fix here; they are counted in the
//! log as left for the recipe to decide.

use super::checks::{TriStatus, canonical_vertices, edge_sides, triangle_status};
use super::report::{FindingKind, ValidationReport};
use crate::import::{ImportedSurface, SourceMap};
use geom::{Tolerances, TriMesh};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, VecDeque};

/// What `repair` did, with indices of the *input* surface.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RepairLog {
    /// Vertices merged into a coincident lower-index vertex.
    pub merged_vertices: usize,
    /// Vertices removed because no kept triangle uses them (after merging).
    pub removed_vertices: usize,
    pub dropped_degenerate: Vec<u32>,
    pub dropped_duplicate: Vec<u32>,
    /// Triangles whose corner order was reversed.
    pub flipped: Vec<u32>,
    /// Edges where orientation could not be made consistent (non-orientable pieces).
    pub orientation_conflicts: usize,
    /// Findings of the report that repair does not touch, by kind.
    pub not_repaired: BTreeMap<String, u64>,
}

const NONE: u32 = u32::MAX;

/// Repairs what is safe; returns the repaired surface and what was done.
pub fn repair(
    s: &ImportedSurface,
    report: &ValidationReport,
    tol: &Tolerances,
) -> (ImportedSurface, RepairLog) {
    let v = &s.mesh.vertices;
    let tris = &s.mesh.triangles;
    let mut log = RepairLog::default();
    for kind in [
        FindingKind::NonManifoldEdge,
        FindingKind::CoplanarOverlap,
        FindingKind::SelfIntersection,
    ] {
        let n = report.of_kind(kind).count() as u64;
        if n > 0 {
            log.not_repaired.insert(kind.name().to_string(), n);
        }
    }
    let canon = canonical_vertices(v, tol);
    log.merged_vertices = canon
        .iter()
        .enumerate()
        .filter(|(i, c)| **c as usize != *i)
        .count();
    let status = triangle_status(v, tris, &canon);

    // Orientation: flip parity per kept triangle, breadth-first over 2-triangle edges.
    let sides = edge_sides(tris, &canon, &status);
    let mut nbr = vec![(NONE, false); tris.len() * 3];
    for g in sides.chunk_by(|a, b| a.key == b.key) {
        if let [a, b] = g {
            let same = a.forward == b.forward;
            nbr[a.tri as usize * 3 + a.k as usize] = (b.tri, same);
            nbr[b.tri as usize * 3 + b.k as usize] = (a.tri, same);
        }
    }
    drop(sides);
    let mut flip: Vec<Option<bool>> = vec![None; tris.len()];
    let mut queue = VecDeque::new();
    for seed in 0..tris.len() {
        if status[seed] != TriStatus::Ok || flip[seed].is_some() {
            continue;
        }
        flip[seed] = Some(false);
        queue.push_back(seed);
        while let Some(x) = queue.pop_front() {
            let fx = flip[x].unwrap_or(false);
            for k in 0..3 {
                let (y, same) = nbr[x * 3 + k];
                if y == NONE {
                    continue;
                }
                let want = fx ^ same;
                match flip[y as usize] {
                    None => {
                        flip[y as usize] = Some(want);
                        queue.push_back(y as usize);
                    }
                    Some(f) if f != want => log.orientation_conflicts += 1,
                    Some(_) => {}
                }
            }
        }
    }
    // Each conflicting edge is seen from both sides.
    log.orientation_conflicts /= 2;

    // Kept triangles on canonical vertices, then vertex compaction.
    let mut new_index = vec![NONE; v.len()];
    let mut kept_vertices: Vec<u32> = Vec::new();
    let mut triangles = Vec::new();
    let mut triangle_part = Vec::new();
    let mut triangle_lines = Vec::new();
    for (t, tri) in tris.iter().enumerate() {
        match status[t] {
            TriStatus::Degenerate => {
                log.dropped_degenerate.push(t as u32);
                continue;
            }
            TriStatus::DuplicateOf(_) => {
                log.dropped_duplicate.push(t as u32);
                continue;
            }
            TriStatus::Ok => {}
        }
        let mut c = tri.map(|i| canon[i as usize]);
        if flip[t] == Some(true) {
            c.swap(1, 2);
            log.flipped.push(t as u32);
        }
        triangles.push(c);
        triangle_part.push(s.triangle_part.get(t).copied().unwrap_or(0));
        triangle_lines.push(s.source.triangle_lines.get(t).copied().unwrap_or(0));
    }
    let mut referenced: Vec<u32> = triangles.iter().flatten().copied().collect();
    referenced.sort_unstable();
    referenced.dedup();
    for &old in &referenced {
        new_index[old as usize] = kept_vertices.len() as u32;
        kept_vertices.push(old);
    }
    for tri in &mut triangles {
        *tri = tri.map(|i| new_index[i as usize]);
    }
    log.removed_vertices = (v.len() - log.merged_vertices).saturating_sub(kept_vertices.len());
    let map = |i: u32| {
        canon
            .get(i as usize)
            .and_then(|&c| new_index.get(c as usize))
            .copied()
            .filter(|&n| n != NONE)
    };
    let mut bstones: Vec<u32> = s.bstones.iter().filter_map(|&b| map(b)).collect();
    bstones.sort_unstable();
    bstones.dedup();
    let borders = s
        .borders
        .iter()
        .filter_map(|&[a, b]| Some([map(a)?, map(b)?]))
        .collect();
    let pick = |old: &[u32], k: &Vec<u32>| {
        k.iter()
            .map(|&i| old.get(i as usize).copied().unwrap_or(0))
            .collect::<Vec<u32>>()
    };
    let mut parts = s.parts.clone();
    for p in &mut parts {
        p.triangle_count = 0;
    }
    for &p in &triangle_part {
        if let Some(part) = parts.get_mut(p as usize) {
            part.triangle_count += 1;
        }
    }
    let out = ImportedSurface {
        name: s.name.clone(),
        mesh: TriMesh::new(
            kept_vertices.iter().map(|&i| v[i as usize]).collect(),
            triangles,
        ),
        triangle_part,
        parts,
        bstones,
        borders,
        property_names: s.property_names.clone(),
        properties: s
            .properties
            .iter()
            .map(|col| {
                kept_vertices
                    .iter()
                    .map(|&i| col.get(i as usize).copied().unwrap_or(f64::NAN))
                    .collect()
            })
            .collect(),
        source: SourceMap {
            file: s.source.file.clone(),
            vertex_ids: kept_vertices
                .iter()
                .map(|&i| s.source.vertex_ids.get(i as usize).copied().unwrap_or(0))
                .collect(),
            vertex_lines: pick(&s.source.vertex_lines, &kept_vertices),
            triangle_lines,
        },
    };
    (out, log)
}
