//! The recipe's attributes as element variables at one time step (time 0), the only form of
//! per-cell data that VTK/ParaView and meshio both read from Exodus: `MATERIAL_ID` (the
//! material id, -1 where none), then every region property by name. Each variable is defined on
//! every block (`elem_var_tab` all 1) because meshio joins a variable's blocks by position; a
//! block whose region lacks a property holds NaN, as in the msh and VTU outputs. A well's block
//! holds -1 and NaN, as line cells do in the VTU.
//!
//! Block attributes would need no time step, but VTK's reader (9.x) carries one block's
//! attribute names over to the next and then reads the wrong columns, so they are not used.

use super::Common;
use super::blocks::BlockDims;
use super::text::rows;
use crate::netcdf::{File, Values};
use crate::property_names;
use geom::mesh::VolumeMesh;

/// Writes the element variables of the blocks of dimensions `blocks` (at the one time step).
pub(super) fn put(f: &mut File, c: &Common, mesh: &VolumeMesh, blocks: &BlockDims) {
    let props = property_names(mesh);
    let names: Vec<&str> = std::iter::once("MATERIAL_ID")
        .chain(props.iter().map(String::as_str))
        .collect();
    let num_var = f.dim("num_elem_var", names.len());
    let name_rows = rows(names.iter().copied(), c.len_name.1);
    f.var("name_elem_var", &[num_var, c.len_name.0], name_rows);
    let table = vec![1; blocks.sizes.len() * names.len()];
    f.var("elem_var_tab", &[blocks.count, num_var], Values::Int(table));
    for (b, &(region, dim, len)) in blocks.sizes.iter().enumerate() {
        let region = region.map(|r| &mesh.regions[r]);
        let material = region.and_then(|r| r.material).map_or(-1.0, |m| m as f64);
        let values = std::iter::once(material).chain(props.iter().map(|p| {
            region
                .and_then(|r| r.properties.get(p).copied())
                .unwrap_or(f64::NAN)
        }));
        for (v, value) in values.enumerate() {
            let name = format!("vals_elem_var{}eb{}", v + 1, b + 1);
            f.var(&name, &[c.time_step, dim], Values::Double(vec![value; len]));
        }
    }
}
