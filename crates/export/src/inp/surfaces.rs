//! The boundary groups: a `*Nset` per surface group (for boundary conditions on nodes) and a
//! `*Surface, type=ELEMENT` per side set, built from one `*Elset` per face number. The faces
//! are the Exodus side sets' (see `exodus::sets`), so a fault has its group surface (each face
//! once) and `front` and `back` surfaces (the tets on each side). The sides of a fault share
//! their nodes (the mesh is conforming), so the fault's one node set serves both.

use super::labels::{Labels, list};
use crate::exodus::sets::{NodeSet, SideSet};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

/// The C3D4 face (S1 = nodes 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1) of each TETRA4 side
/// (1 = 1-2-4, 2 = 2-3-4, 3 = 1-4-3, 4 = 1-3-2).
const FACE_OF_SIDE: [u32; 4] = [2, 3, 4, 1];

pub(super) fn put(s: &mut String, labels: &Labels, node_sets: &[NodeSet], side_sets: &[SideSet]) {
    for set in node_sets {
        let _ = writeln!(s, "*Nset, nset={}", labels.sets[&set.id]);
        list(s, set.nodes.iter().map(|&v| v as usize));
    }
    for set in side_sets {
        surface(s, &labels.sets[&set.id], set);
    }
}

/// One element set per face number, then the surface naming them.
fn surface(s: &mut String, label: &str, set: &SideSet) {
    let mut faces: BTreeMap<u32, BTreeSet<usize>> = BTreeMap::new();
    for f in &set.faces {
        let face = FACE_OF_SIDE[f.side as usize - 1];
        faces.entry(face).or_default().insert(f.elem as usize);
    }
    for (f, elems) in &faces {
        let _ = writeln!(s, "*Elset, elset={label}_S{f}");
        list(s, elems.iter().copied());
    }
    let _ = writeln!(s, "*Surface, type=ELEMENT, name={label}");
    for f in faces.keys() {
        let _ = writeln!(s, "{label}_S{f}, S{f}");
    }
}
