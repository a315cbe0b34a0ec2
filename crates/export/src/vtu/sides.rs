//! The faults' sides as VTU cells. A VTU cell carries one value per array, and a fault triangle
//! has two sides, so each side of a fault gets its own copy of the fault's triangles: after every
//! other cell, side by side in id order (`<fault>:front`, then `<fault>:back`, fault after
//! fault, as the Exodus side sets), each copy oriented out of the tet on its side (reversed on
//! the front, as Exodus and Gmsh orient a side) and left out where no tet lies on that side. The
//! copies carry the side's id in the `fault_side` array and -1 (NaN) in every other array, so
//! thresholding `surface` still gives each triangle once and thresholding `fault_side` gives one
//! side, as a boundary condition or a slip model addresses it.

use crate::numbering::Numbering;
use crate::sides::{face_uses, fault_sides, on_side, side_name};
use crate::split_by;
use geom::mesh::VolumeMesh;

/// The side cells of a mesh and the names of its fault sides.
pub(super) struct SideCells {
    /// Per cell: its three nodes (oriented out of its tet) and its side's id.
    pub(super) cells: Vec<([u32; 3], i32)>,
    /// Every fault side's name and id, in id order (sides without cells included).
    pub(super) names: Vec<(String, i32)>,
}

impl SideCells {
    /// The side cells of `mesh` (indices checked in range).
    pub(super) fn new(mesh: &VolumeMesh) -> SideCells {
        let faults = fault_sides(mesh);
        let mut out = SideCells {
            cells: Vec::new(),
            names: Vec::new(),
        };
        if faults.is_empty() {
            return out;
        }
        let uses = face_uses(mesh, &Numbering::new(mesh).number);
        let by_group = split_by(&mesh.triangle_group, mesh.surface_groups.len());
        for fault in faults {
            let name = &mesh.surface_groups[fault.group].name;
            for front in [true, false] {
                let id = fault.id(front) as i32;
                out.names.push((side_name(name, front), id));
                let tris = by_group[fault.group].iter();
                let faces = tris.filter(|&&t| on_side(&uses[t], front).is_some());
                let oriented = faces.map(|&t| outward(mesh.triangles[t], front));
                out.cells.extend(oriented.map(|tri| (tri, id)));
            }
        }
        out
    }

    /// The number of side cells.
    pub(super) fn len(&self) -> usize {
        self.cells.len()
    }
}

/// `tri` oriented out of the tet on its `front` (reversed) or its back (as it is).
fn outward([a, b, c]: [u32; 3], front: bool) -> [u32; 3] {
    if front { [a, c, b] } else { [a, b, c] }
}
