//! The side sets and node sets, one of each per surface group (surface, fault, box side) under
//! the group's name and id (group index + 1, as in every format), plus two side sets per fault,
//! `<fault>:front` and `<fault>:back` (the model's names for a surface's sides), with the ids
//! every format gives them, after the groups' ([`crate::sides::fault_sides`]).
//!
//! A group's side set names each of its triangles once, in triangle order, by the tet face of
//! the lowest element number: on an interior face (a horizon, a fault) that is the tet of the
//! region with the lower id, since blocks are numbered in region order. A fault's front set
//! names its faces from the tets on its front, the back set from those behind it, so a boundary
//! condition or a slip model can address each side apart. Empty sets are left out (a netCDF
//! dimension cannot be 0 long and meshio pairs node sets with names by position): their ids are
//! then unused.
//!
//! Each line group (well) with lines also has a node set of its line nodes under its name, after
//! the groups' ([`well_node_sets`]), id = the number of surface groups + well index + 1: meshio
//! names no element block, so these carry the wells' names there.
//!
//! Each named point (a well's crossing of a surface) is a node set of its one node under its
//! name, after the wells' ([`point_node_sets`]), id = the number of surface groups + the number
//! of line groups + point index + 1: Exodus has no point entity, and a one-node set is what a
//! solver reading Exodus (MOOSE, PyLith) takes a point source or a point constraint on.
//!
//! Each face set (the recipe's `[groups]`) has a side set, named from the tets of the lowest
//! element number like a group's, with the id every format gives it
//! ([`crate::face_sets`]: after the fault sides), and a node set, after the named points'
//! ([`face_set_node_sets`]).

use crate::face_sets;
use crate::sides::{FaceUse, fault_sides, on_side, side_name};
use crate::split_by;
use geom::mesh::VolumeMesh;
use std::collections::BTreeSet;

/// A named set of (element, side) pairs.
pub(crate) struct SideSet {
    pub(crate) id: usize,
    pub(crate) name: String,
    pub(crate) faces: Vec<FaceUse>,
}

/// A named set of 1-based node ids, ascending.
pub(crate) struct NodeSet {
    pub(crate) id: usize,
    pub(crate) name: String,
    pub(crate) nodes: Vec<u32>,
}

/// The side sets of `mesh`, given every triangle's face uses (lowest element first).
pub(crate) fn side_sets(mesh: &VolumeMesh, uses: &[Vec<FaceUse>]) -> Vec<SideSet> {
    let n = mesh.surface_groups.len();
    let by_group = split_by(&mesh.triangle_group, n);
    let pick = |tris: &[usize], f: &dyn Fn(&[FaceUse]) -> Option<FaceUse>| -> Vec<FaceUse> {
        tris.iter().filter_map(|&t| f(&uses[t])).collect()
    };
    let mut sets = Vec::new();
    for (g, tris) in by_group.iter().enumerate() {
        let name = mesh.surface_groups[g].name.clone();
        sets.push((g + 1, name, pick(tris, &|u| u.first().copied())));
    }
    for fault in fault_sides(mesh) {
        let name = &mesh.surface_groups[fault.group].name;
        let tris = &by_group[fault.group];
        for front in [true, false] {
            let faces = pick(tris, &|u| on_side(u, front));
            sets.push((fault.id(front), side_name(name, front), faces));
        }
    }
    let first = face_sets::first_id(&mesh.surface_groups);
    for (k, set) in mesh.face_sets.iter().enumerate() {
        let tris: Vec<usize> = set.triangles.iter().map(|&t| t as usize).collect();
        let faces = pick(&tris, &|u| u.first().copied());
        sets.push((first + k, set.name.clone(), faces));
    }
    sets.into_iter()
        .filter(|(_, _, faces)| !faces.is_empty())
        .map(|(id, name, faces)| SideSet { id, name, faces })
        .collect()
}

/// The node sets of `mesh`: each group's triangle nodes.
pub(crate) fn node_sets(mesh: &VolumeMesh) -> Vec<NodeSet> {
    split_by(&mesh.triangle_group, mesh.surface_groups.len())
        .iter()
        .enumerate()
        .filter(|(_, tris)| !tris.is_empty())
        .map(|(g, tris)| NodeSet {
            id: g + 1,
            name: mesh.surface_groups[g].name.clone(),
            nodes: triangle_nodes(mesh, tris.iter().copied()),
        })
        .collect()
}

/// The node sets of the wells of `mesh`: each line group's line nodes.
pub(crate) fn well_node_sets(mesh: &VolumeMesh) -> Vec<NodeSet> {
    let first = mesh.surface_groups.len() + 1;
    (mesh.lines.iter().enumerate())
        .filter(|(_, g)| !g.lines.is_empty())
        .map(|(w, g)| {
            let nodes: BTreeSet<u32> = g.lines.iter().flatten().copied().collect();
            NodeSet {
                id: first + w,
                name: g.name.clone(),
                nodes: nodes.into_iter().map(|v| v + 1).collect(),
            }
        })
        .collect()
}

/// The node sets of the face sets of `mesh`: each set's triangle nodes, ids from `first` (the
/// Exodus ids follow the named points', [`face_sets::first_node_set`]).
pub(crate) fn face_set_node_sets(mesh: &VolumeMesh, first: usize) -> Vec<NodeSet> {
    (mesh.face_sets.iter().enumerate())
        .filter(|(_, s)| !s.triangles.is_empty())
        .map(|(k, s)| NodeSet {
            id: first + k,
            name: s.name.clone(),
            nodes: triangle_nodes(mesh, s.triangles.iter().map(|&t| t as usize)),
        })
        .collect()
}

/// The 1-based ids of the nodes of these triangles, ascending.
fn triangle_nodes(mesh: &VolumeMesh, tris: impl Iterator<Item = usize>) -> Vec<u32> {
    let nodes: BTreeSet<u32> = tris.flat_map(|t| mesh.triangles[t]).collect();
    nodes.into_iter().map(|v| v + 1).collect()
}

/// The node sets of the named points of `mesh`: one node each, ids after the wells'.
pub(crate) fn point_node_sets(mesh: &VolumeMesh) -> Vec<NodeSet> {
    let first = mesh.surface_groups.len() + mesh.lines.len() + 1;
    (mesh.points.iter().enumerate())
        .map(|(i, p)| NodeSet {
            id: first + i,
            name: p.name.clone(),
            nodes: vec![p.node + 1],
        })
        .collect()
}
