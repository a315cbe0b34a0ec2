//! The element blocks: one per region that has tets, in region order, named by the region and
//! identified by `eb_prop1` ("ID") = region index + 1, the id of every other format. Each block
//! is `TETRA` (4 nodes; the Exodus name meshio also maps, where it does not know `TETRA4`) with
//! 1-based node ids in the mesh's node order. `eb_prop2` ("MATERIAL_ID") is the region's
//! material id, -1 where the recipe gives none (as in the msh "material" view), for programs
//! that read block properties through the Exodus API; [`super::fields`] makes it, and the
//! numeric properties, cell data for the viewers.

use super::Common;
use super::text::rows;
use crate::netcdf::{DimId, File, Values};
use crate::numbering::Numbering;
use geom::mesh::VolumeMesh;

/// The dimensions of the blocks: `num_el_blk` and each block's `num_el_in_blk`.
pub(super) struct BlockDims {
    pub(super) count: DimId,
    pub(super) sizes: Vec<DimId>,
}

/// Writes the block table (`eb_status`, ids, material ids, names) and every block; `None` when
/// there is no block.
pub(super) fn put(
    f: &mut File,
    c: &Common,
    mesh: &VolumeMesh,
    numbering: &Numbering,
) -> Result<Option<BlockDims>, String> {
    let blocks = &numbering.blocks;
    if blocks.is_empty() {
        return Ok(None);
    }
    let num_elem: usize = blocks.iter().map(|(_, tets)| tets.len()).sum();
    f.dim("num_elem", num_elem);
    let num_blk = f.dim("num_el_blk", blocks.len());
    let regions: Vec<usize> = blocks.iter().map(|(r, _)| *r).collect();
    f.var("eb_status", &[num_blk], Values::Int(vec![1; blocks.len()]));
    let ids = regions.iter().map(|&r| r as i32 + 1).collect();
    f.var("eb_prop1", &[num_blk], Values::Int(ids))
        .attr("name", Values::text("ID"));
    let materials = regions
        .iter()
        .map(|&r| material(mesh, r))
        .collect::<Result<_, _>>()?;
    f.var("eb_prop2", &[num_blk], Values::Int(materials))
        .attr("name", Values::text("MATERIAL_ID"));
    let names = regions.iter().map(|&r| mesh.regions[r].name.as_str());
    f.var(
        "eb_names",
        &[num_blk, c.len_name.0],
        rows(names, c.len_name.1),
    );
    let sizes = blocks
        .iter()
        .enumerate()
        .map(|(i, (_, tets))| put_block(f, mesh, i + 1, tets))
        .collect();
    Ok(Some(BlockDims {
        count: num_blk,
        sizes,
    }))
}

/// The region's material id as an Exodus property (32-bit), -1 when none.
fn material(mesh: &VolumeMesh, r: usize) -> Result<i32, String> {
    let region = &mesh.regions[r];
    region.material.map_or(Ok(-1), |m| {
        i32::try_from(m).map_err(|_| {
            format!(
                "region '{}': material {m} does not fit an Exodus property (32-bit)",
                region.name
            )
        })
    })
}

/// Block `i` (1-based): its connectivity; returns its `num_el_in_blk` dimension.
fn put_block(f: &mut File, mesh: &VolumeMesh, i: usize, tets: &[usize]) -> DimId {
    let num_el = f.dim(&format!("num_el_in_blk{i}"), tets.len());
    let per_el = f.dim(&format!("num_nod_per_el{i}"), 4);
    let connect = tets
        .iter()
        .flat_map(|&t| mesh.tets[t])
        .map(|v| v as i32 + 1)
        .collect();
    f.var(
        &format!("connect{i}"),
        &[num_el, per_el],
        Values::Int(connect),
    )
    .attr("elem_type", Values::text("TETRA"));
    num_el
}
