//! The recipe's named face sets (`[groups]`), numbered once for every writer: the `k`-th set (in
//! name order) of a mesh with `n` surface groups and `F` faults is 2D group, side set and VTU
//! value `n + 2F + k + 1`, after the fault sides; its Exodus node set is numbered after the named
//! points' (`n + W + P + k + 1` with `W` line groups and `P` points).
//!
//! Face sets may overlap each other and the surface groups, so a writer that gives each triangle
//! one tag (MEDIT's reference, TetGen's marker) cannot carry them; those formats leave them out.

use crate::sides::fault_sides_of;
use geom::mesh::{SurfaceGroup, VolumeMesh};

/// The id of the first face set of a mesh with these surface groups.
pub(crate) fn first_id(groups: &[SurfaceGroup]) -> usize {
    groups.len() + 2 * fault_sides_of(groups).len() + 1
}

/// The Exodus node set id of the first face set: after the surface groups', the wells' and the
/// named points'.
pub(crate) fn first_node_set(groups: usize, wells: usize, points: usize) -> usize {
    groups + wells + points + 1
}

/// Per triangle of `mesh`, the face sets holding it, ascending.
pub(crate) fn memberships(mesh: &VolumeMesh) -> Vec<Vec<usize>> {
    let mut of = vec![Vec::new(); mesh.triangles.len()];
    for (k, set) in mesh.face_sets.iter().enumerate() {
        for &t in &set.triangles {
            of[t as usize].push(k);
        }
    }
    of
}
