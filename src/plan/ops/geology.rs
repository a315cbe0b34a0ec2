//! The model counted as a geomodeller counts it: corners, lines, surfaces and regions as the
//! source file draws them (RINGMesh and OpenGeode count a Model3d so), without the cuts the
//! mesher needs.
//!
//! The model cuts more than the geology does: a crease sharper than the crease angle and the
//! seams between charts are curves of one surface that split one TFACE into several patches;
//! where such a curve ends on another, and at a kink, that curve is split in two. Counting
//! them would tell a user comparing with their modeller of entities the file does not hold.
//!
//! Decisions and why:
//! - Two patches are one surface when a curve of their one surface is all that parts them and
//!   both lie in the same part (TFACE): a crease or seam. A curve parting two TFACEs of one TSurf
//!   (a box folded round its edges, one TFACE per side) is a line of the file, and stays one.
//! - The other curves are lines. Where exactly two of them end at a vertex, bounding the same
//!   surfaces (counted as above), the vertex is there only because the mesher cut a line (a
//!   crease or seam ending on it, a kink sharper than the kink angle): the two are one line,
//!   and the vertex is no corner. A line that closes on itself that way keeps one corner, as
//!   the modellers count a closed line.
//! - Vertices are the curves' end points, matched by exact coordinates, as the topology made
//!   them.

use super::ModelData;
use model::union_find::UnionFind;
use serde::Serialize;
use std::collections::BTreeMap;

/// The model's entities as its source file draws them (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Counts {
    pub corners: usize,
    pub lines: usize,
    pub surfaces: usize,
    pub regions: usize,
}

/// Counts `model`'s entities as a geomodeller does (see the module doc).
pub fn counts(model: &ModelData) -> Counts {
    let curves = &model.topology.curves;
    let mut surface = UnionFind::new(model.patches.len());
    let mut internal = vec![false; curves.len()];
    for (k, c) in curves.iter().enumerate() {
        if let ([_], &[a, b]) = (c.surfaces.as_slice(), c.patches.as_slice()) {
            let (pa, pb) = (&model.patches[a as usize], &model.patches[b as usize]);
            if pa.surface == pb.surface && pa.part == pb.part {
                surface.union(a as usize, b as usize);
                internal[k] = true;
            }
        }
    }
    let of_patch: Vec<usize> = (0..model.patches.len()).map(|p| surface.find(p)).collect();
    let bounds = |k: usize| {
        let mut s: Vec<usize> = (curves[k].patches.iter())
            .map(|&p| of_patch[p as usize])
            .collect();
        s.sort_unstable();
        s.dedup();
        s
    };
    let mut ends: BTreeMap<[u64; 3], Vec<usize>> = BTreeMap::new();
    for (k, c) in curves.iter().enumerate().filter(|(k, _)| !internal[*k]) {
        for p in [c.points.first(), c.points.last()].into_iter().flatten() {
            ends.entry(p.map(f64::to_bits)).or_default().push(k);
        }
    }
    let mut line = UnionFind::new(curves.len());
    let mut cornered = vec![false; curves.len()];
    let mut corners = 0;
    for at in ends.values() {
        match at.as_slice() {
            &[a, b] if a != b && bounds(a) == bounds(b) => line.union(a, b),
            _ => {
                corners += 1;
                for &k in at {
                    cornered[k] = true;
                }
            }
        }
    }
    let mut lines = 0;
    let mut has_corner = vec![false; curves.len()];
    for k in (0..curves.len()).filter(|&k| !internal[k]) {
        has_corner[line.find(k)] |= cornered[k];
    }
    for k in (0..curves.len()).filter(|&k| !internal[k] && line.find(k) == k) {
        lines += 1;
        if !has_corner[k] {
            corners += 1;
        }
    }
    Counts {
        corners,
        lines,
        surfaces: (0..model.patches.len())
            .filter(|&p| of_patch[p] == p)
            .count(),
        regions: model.regions.regions.len(),
    }
}
