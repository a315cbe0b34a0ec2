//! The VTU cell arrays, one value per cell (tets, then triangles, then lines, then the faults'
//! side cells): `MaterialIDs`, `region`, `surface`, the region properties, when the mesh has
//! line groups `well`, when it has faults `fault_side`, and per face set (the recipe's
//! `[groups]`, which may overlap) `group:<name>`, its id on the triangles it holds. -1 stands for "none" in the integer
//! arrays (ids start at 1 and material ids may be 0), NaN for a property a region does not have
//! (and on every cell but a tet).

use super::Extra;
use super::writer::Writer;
use crate::property_names;
use geom::mesh::VolumeMesh;
use std::iter::repeat_n;

/// Each region's material id as `MaterialIDs` holds it (-1 for none); fails on one that does
/// not fit Int32.
pub(super) fn materials(mesh: &VolumeMesh) -> Result<Vec<i32>, String> {
    mesh.regions
        .iter()
        .map(|r| match r.material {
            None => Ok(-1),
            Some(m) => i32::try_from(m).map_err(|_| {
                format!(
                    "region '{}' has material {m}: VTU MaterialIDs are 32-bit",
                    r.name
                )
            }),
        })
        .collect()
}

/// Writes every cell array; `materials` from [`materials`], `extra` the cells after the tets.
pub(super) fn put(w: &mut Writer, mesh: &VolumeMesh, materials: &[i32], extra: &Extra) {
    let (nt, nf, nl, ns) = (
        mesh.tets.len(),
        extra.triangles,
        extra.lines,
        extra.sides.len(),
    );
    w.array("MaterialIDs", 1, per_tet(mesh, extra, |r| materials[r]));
    w.array("region", 1, per_tet(mesh, extra, |r| r as i32 + 1));
    let surface = mesh.triangle_group.iter().map(|&g| g as i32 + 1);
    let surface = repeat_n(-1, nt).chain(surface);
    w.array("surface", 1, surface.chain(repeat_n(-1, nl + ns)));
    for name in &property_names(mesh) {
        let value = |r: u32| {
            let region = &mesh.regions[r as usize];
            region.properties.get(name).copied().unwrap_or(f64::NAN)
        };
        let tets = mesh.tet_region.iter().map(|&r| value(r));
        w.array(name, 1, tets.chain(repeat_n(f64::NAN, extra.len())));
    }
    if !mesh.lines.is_empty() {
        let lines = (mesh.lines.iter().enumerate())
            .flat_map(|(g, group)| repeat_n(g as i32 + 1, group.lines.len()));
        let lines = repeat_n(-1, nt + nf).chain(lines);
        w.array("well", 1, lines.chain(repeat_n(-1, ns)));
    }
    if !extra.sides.names.is_empty() {
        let sides = extra.sides.cells.iter().map(|&(_, id)| id);
        w.array("fault_side", 1, repeat_n(-1, nt + nf + nl).chain(sides));
    }
    let first = crate::face_sets::first_id(&mesh.surface_groups) as i32;
    for (k, set) in mesh.face_sets.iter().enumerate() {
        let mut on = vec![-1i32; nf];
        for &t in &set.triangles {
            on[t as usize] = first + k as i32;
        }
        let cells = repeat_n(-1, nt).chain(on).chain(repeat_n(-1, nl + ns));
        w.array(&format!("group:{}", set.name), 1, cells);
    }
}

/// `f(region)` on every tet, then -1 on every other cell.
fn per_tet<'a>(
    mesh: &'a VolumeMesh,
    extra: &Extra,
    f: impl Fn(usize) -> i32 + 'a,
) -> impl Iterator<Item = i32> + 'a {
    let tets = mesh.tet_region.iter().map(move |&r| f(r as usize));
    tets.chain(repeat_n(-1, extra.len()))
}
