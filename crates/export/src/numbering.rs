//! Element numbers, shared by the writers: Exodus numbers elements consecutively across the
//! element blocks, in block order, from 1. Blocks are the regions in region order and a block
//! lists its tets in mesh order, so tet `t`'s number is its rank in that sequence (the Abaqus and
//! msh writers number their tets the same way). A region without tets has no block.
//!
//! The line elements (the wells) come after every tet: one block per line group that has lines,
//! in group order, each listing its lines in group order, numbered on from `tets + 1`. Exodus
//! and Abaqus write no triangle elements, so nothing lies between.

use crate::split_by;
use geom::mesh::VolumeMesh;

/// The element blocks and every tet's element number.
pub(crate) struct Numbering {
    /// Per block: its region index and its tets, in element-number order.
    pub(crate) blocks: Vec<(usize, Vec<usize>)>,
    /// Per tet: its 1-based element number.
    pub(crate) number: Vec<u32>,
    /// Per line group with lines, in group order: its index and the element number of its
    /// first line (its other lines follow on, in group order).
    pub(crate) wells: Vec<(usize, u32)>,
}

impl Numbering {
    /// Numbers the tets of `mesh` (whose region tags are in range), then its lines.
    pub(crate) fn new(mesh: &VolumeMesh) -> Numbering {
        let blocks: Vec<(usize, Vec<usize>)> = split_by(&mesh.tet_region, mesh.regions.len())
            .into_iter()
            .enumerate()
            .filter(|(_, tets)| !tets.is_empty())
            .collect();
        let mut number = vec![0u32; mesh.tets.len()];
        for (n, &t) in (1u32..).zip(blocks.iter().flat_map(|(_, tets)| tets)) {
            number[t] = n;
        }
        let mut next = (mesh.tets.len() as u32).saturating_add(1);
        let mut wells = Vec::new();
        for (g, group) in mesh.lines.iter().enumerate() {
            if !group.lines.is_empty() {
                wells.push((g, next));
                next = next.saturating_add(group.lines.len() as u32);
            }
        }
        Numbering {
            blocks,
            number,
            wells,
        }
    }
}
