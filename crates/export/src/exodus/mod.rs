//! Exodus II writer (as read by VTK/ParaView, meshio, MOOSE, PyLith, Cubit and the SEACAS
//! tools), on the crate's own netCDF classic writer: Exodus II is a set of naming conventions
//! over netCDF, written here with the names of the Exodus library's `exodusII_int.h`.
//!
//! What the file carries and why:
//! - coordinates as `coordx`/`coordy`/`coordz` (the "large model" layout) in 8-byte floats;
//! - one 4-node tetrahedron element block per region with tets ([`blocks`]: names, ids = region
//!   index + 1, the material id as a block property);
//! - the material id and the numeric properties as element variables at one time step, time 0
//!   ([`fields`]), the cell data every viewer shows;
//! - one 2-node `BAR2` element block per line group (well) with lines, after the regions', and
//!   a node set of its nodes, both named after the well ([`blocks`], [`sets`]);
//! - a one-node node set per named point (a well's crossing of a surface), named after it, with
//!   ids after the wells' node sets ([`sets`]);
//! - a side set and a node set per surface group, and a front and a back side set per fault
//!   ([`sets`], [`crate::sides`] for the TETRA4 side numbering);
//! - a side set and a node set per face set (the recipe's `[groups]`), after those ([`sets`]);
//! - QA and info records naming the program and the model, and, given a [`Provenance`], the
//!   recipe and the key that identifies the build inputs ([`globals`]).
//!
//! Everything is written in index order and no field depends on the time of writing, so the
//! bytes are a pure function of the mesh, the model name and the provenance. Ids and counts are 32-bit, as
//! readers expect by default; a larger mesh is refused with a message.

mod blocks;
mod fields;
mod globals;
mod set_vars;
pub(crate) mod sets;
mod text;

use crate::netcdf::File;
use crate::numbering::Numbering;
use crate::{Provenance, sides};
use geom::mesh::VolumeMesh;
use globals::Common;

/// The shortest `len_name` Exodus readers assume (32 characters and a NUL).
const MIN_NAME_WIDTH: usize = 33;
/// The longest `len_name` the Exodus library accepts (255 characters and a NUL).
const MAX_NAME_WIDTH: usize = 256;

/// Writes `mesh` (indices checked in range) as the bytes of `<model>.exo`.
pub(super) fn write(
    mesh: &VolumeMesh,
    model: &str,
    provenance: &Provenance,
) -> Result<Vec<u8>, String> {
    fits_32_bits(mesh)?;
    let numbering = Numbering::new(mesh);
    let uses = sides::face_uses(mesh, &numbering.number);
    sides::every_triangle_a_face(mesh, &uses)?;
    let side_sets = sets::side_sets(mesh, &uses);
    let mut node_sets = sets::node_sets(mesh);
    node_sets.extend(sets::well_node_sets(mesh));
    node_sets.extend(sets::point_node_sets(mesh));
    let first = crate::face_sets::first_node_set(
        mesh.surface_groups.len(),
        mesh.lines.len(),
        mesh.points.len(),
    );
    node_sets.extend(sets::face_set_node_sets(mesh, first));
    let names = mesh
        .regions
        .iter()
        .flat_map(|r| std::iter::once(&r.name).chain(r.properties.keys()))
        .chain(side_sets.iter().map(|s| &s.name))
        .chain(mesh.lines.iter().map(|g| &g.name))
        .chain(mesh.points.iter().map(|p| &p.name))
        .chain(mesh.face_sets.iter().map(|s| &s.name));
    let width = names
        .map(|n| n.len() + 1)
        .fold(MIN_NAME_WIDTH, usize::max)
        .min(MAX_NAME_WIDTH);
    let mut f = File::default();
    let times = if numbering.blocks.is_empty() && numbering.wells.is_empty() {
        vec![]
    } else {
        vec![0.0]
    };
    let common = globals::put(&mut f, mesh, (model, provenance), width, times);
    if let Some(dims) = blocks::put(&mut f, &common, mesh, &numbering)? {
        fields::put(&mut f, &common, mesh, &dims);
    }
    set_vars::put_side_sets(&mut f, &common, &side_sets);
    set_vars::put_node_sets(&mut f, &common, &node_sets);
    f.to_bytes()
}

/// Fails when a node id, element number or set id would not fit a 32-bit Exodus integer.
fn fits_32_bits(mesh: &VolumeMesh) -> Result<(), String> {
    let wells = mesh.lines.len();
    let ids = mesh.regions.len()
        + 3 * mesh.surface_groups.len()
        + wells
        + mesh.points.len()
        + 2 * mesh.face_sets.len();
    let lines: usize = mesh.lines.iter().map(|g| g.lines.len()).sum();
    let elements = mesh.tets.len().saturating_add(lines);
    let largest = mesh.nodes.len().max(elements).max(ids);
    if largest >= i32::MAX as usize {
        return Err(format!(
            "the mesh has {} nodes, {} tets and {lines} line elements: too many for 32-bit \
             Exodus ids",
            mesh.nodes.len(),
            mesh.tets.len()
        ));
    }
    Ok(())
}
