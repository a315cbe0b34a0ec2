//! The element blocks: one per region that has tets, in region order, named by the region and
//! identified by `eb_prop1` ("ID") = region index + 1, the id of every other format. Each block
//! is `TETRA` (4 nodes; the Exodus name meshio also maps, where it does not know `TETRA4`) with
//! 1-based node ids in the mesh's node order. `eb_prop2` ("MATERIAL_ID") is the region's
//! material id, -1 where the recipe gives none (as in the msh "material" view), for programs
//! that read block properties through the Exodus API; [`super::fields`] makes it, and the
//! numeric properties, cell data for the viewers.
//!
//! Then one block per line group (well) that has lines, in group order, named by the well:
//! `BAR2` elements (2 nodes; VTK reads them as line cells, meshio as `line`), id = the number of
//! regions + well index + 1 (block ids must differ from the regions'), material -1. Exodus also
//! has edge blocks (`num_ed_blk`, `ebconn*`), but meshio reads only `connect*` variables, so a
//! well written as an edge block would vanish there; an element block is read by both.

use super::Common;
use super::text::rows;
use crate::netcdf::{DimId, File, Values};
use crate::numbering::Numbering;
use geom::mesh::VolumeMesh;

/// The dimensions of the blocks: `num_el_blk` and each block's `num_el_in_blk`, with the
/// region each block holds (`None` for a well's).
pub(super) struct BlockDims {
    pub(super) count: DimId,
    pub(super) sizes: Vec<(Option<usize>, DimId, usize)>,
}

/// One element block as written.
struct Block<'a> {
    region: Option<usize>,
    id: i32,
    name: &'a str,
    material: i32,
    elem_type: &'static str,
    per_el: usize,
    /// 1-based node ids, `per_el` per element.
    connect: Vec<i32>,
}

/// Writes the block table (`eb_status`, ids, material ids, names) and every block; `None` when
/// there is no block.
pub(super) fn put(
    f: &mut File,
    c: &Common,
    mesh: &VolumeMesh,
    numbering: &Numbering,
) -> Result<Option<BlockDims>, String> {
    let blocks = all_blocks(mesh, numbering)?;
    if blocks.is_empty() {
        return Ok(None);
    }
    let num_elem: usize = blocks.iter().map(|b| b.connect.len() / b.per_el).sum();
    f.dim("num_elem", num_elem);
    let num_blk = f.dim("num_el_blk", blocks.len());
    f.var("eb_status", &[num_blk], Values::Int(vec![1; blocks.len()]));
    let ids = blocks.iter().map(|b| b.id).collect();
    f.var("eb_prop1", &[num_blk], Values::Int(ids))
        .attr("name", Values::text("ID"));
    let materials = blocks.iter().map(|b| b.material).collect();
    f.var("eb_prop2", &[num_blk], Values::Int(materials))
        .attr("name", Values::text("MATERIAL_ID"));
    let names = blocks.iter().map(|b| b.name);
    f.var(
        "eb_names",
        &[num_blk, c.len_name.0],
        rows(names, c.len_name.1),
    );
    let sizes = (1..)
        .zip(blocks)
        .map(|(i, b)| {
            let n = b.connect.len() / b.per_el;
            (b.region, put_block(f, i, b), n)
        })
        .collect();
    Ok(Some(BlockDims {
        count: num_blk,
        sizes,
    }))
}

/// The regions' blocks, then the wells'.
fn all_blocks<'a>(mesh: &'a VolumeMesh, numbering: &Numbering) -> Result<Vec<Block<'a>>, String> {
    let mut blocks = Vec::new();
    for (r, tets) in &numbering.blocks {
        let connect = tets
            .iter()
            .flat_map(|&t| mesh.tets[t])
            .map(|v| v as i32 + 1)
            .collect();
        blocks.push(Block {
            region: Some(*r),
            id: *r as i32 + 1,
            name: &mesh.regions[*r].name,
            material: material(mesh, *r)?,
            elem_type: "TETRA",
            per_el: 4,
            connect,
        });
    }
    for &(g, _) in &numbering.wells {
        let group = &mesh.lines[g];
        let connect = group
            .lines
            .iter()
            .flatten()
            .map(|&v| v as i32 + 1)
            .collect();
        blocks.push(Block {
            region: None,
            id: (mesh.regions.len() + g + 1) as i32,
            name: &group.name,
            material: -1,
            elem_type: "BAR2",
            per_el: 2,
            connect,
        });
    }
    Ok(blocks)
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
fn put_block(f: &mut File, i: usize, b: Block) -> DimId {
    let num_el = f.dim(&format!("num_el_in_blk{i}"), b.connect.len() / b.per_el);
    let per_el = f.dim(&format!("num_nod_per_el{i}"), b.per_el);
    f.var(
        &format!("connect{i}"),
        &[num_el, per_el],
        Values::Int(b.connect),
    )
    .attr("elem_type", Values::text(b.elem_type));
    num_el
}
