//! TetGen `.node` / `.ele` / `.face` / `.edge` writer (TetGen's file formats, 1-based indices):
//! nodes without attributes or markers; tets with one attribute, the region id (region index +
//! 1, as TetGen's `-A` region attributes); faces with a boundary marker = surface group index +
//! 1, followed by the face's two tets as TetGen's `-nn` switch writes them (`.ele` numbers, -1
//! where there is none), the tet on the face's front first, the one behind it second: the front
//! being the side its right-hand normal points to, so each side of a fault (`<fault>:front` and
//! `<fault>:back` in the other formats) is a column, and a face is written once, as TetGen and
//! its readers expect (a second copy per side would be a duplicate face to them); and, only when the mesh has line groups (wells), edges (the line elements, group after
//! group) with a boundary marker = line group index + 1, as TetGen writes an `.edge` file only
//! when asked (`-e`). Files are named `<model>.1.node` etc. (by `super::file_names`), as TetGen
//! names the first refinement's output.
//!
//! The named points (the wells' crossings of the surfaces) are not written: a `.node` boundary
//! marker is one integer per node that TetGen itself sets on its boundary nodes, so using it
//! for a few labelled nodes would be read as a boundary marking. The msh, Exodus, VTU and
//! Abaqus files carry them.

use crate::numbering::Numbering;
use crate::sides::{FaceUse, face_uses, on_side};
use geom::mesh::VolumeMesh;
use std::fmt::Write as _;

/// The `.node`, `.ele`, `.face` and (with line groups) `.edge` texts, in that order (named by
/// `super::file_names`).
pub(super) fn write(mesh: &VolumeMesh, model: &str) -> Vec<Vec<u8>> {
    let mut node = String::new();
    let _ = writeln!(node, "# {model}: node x y z\n{} 3 0 0", mesh.nodes.len());
    for (i, p) in mesh.nodes.iter().enumerate() {
        let _ = writeln!(node, "{} {} {} {}", i + 1, p[0], p[1], p[2]);
    }
    let mut ele = String::new();
    let _ = writeln!(
        ele,
        "# {model}: tet n1 n2 n3 n4 region\n{} 4 1",
        mesh.tets.len()
    );
    for (i, (t, r)) in mesh.tets.iter().zip(&mesh.tet_region).enumerate() {
        let _ = writeln!(
            ele,
            "{} {} {} {} {} {}",
            i + 1,
            t[0] + 1,
            t[1] + 1,
            t[2] + 1,
            t[3] + 1,
            r + 1
        );
    }
    let mut texts = vec![node, ele, faces(mesh, model)];
    if !mesh.lines.is_empty() {
        texts.push(edges(mesh, model));
    }
    texts
        .into_iter()
        .map(|mut text| {
            text.shrink_to_fit();
            text.into_bytes()
        })
        .collect()
}

/// The `.face` text: every triangle with its surface group's id as boundary marker, then the
/// tets on its front and its back.
fn faces(mesh: &VolumeMesh, model: &str) -> String {
    let uses = face_uses(mesh, &Numbering::new(mesh).number);
    let mut face = String::new();
    let _ = writeln!(
        face,
        "# {model}: face n1 n2 n3 surface front_tet back_tet\n{} 1",
        mesh.triangles.len()
    );
    let tris = mesh.triangles.iter().zip(&mesh.triangle_group).zip(&uses);
    for (i, ((t, g), uses)) in tris.enumerate() {
        let _ = writeln!(
            face,
            "{} {} {} {} {} {} {}",
            i + 1,
            t[0] + 1,
            t[1] + 1,
            t[2] + 1,
            g + 1,
            tet_on(uses, true),
            tet_on(uses, false)
        );
    }
    face
}

/// The 1-based `.ele` number of the tet on the `front` (or back) of a face, -1 for none.
fn tet_on(uses: &[FaceUse], front: bool) -> i64 {
    on_side(uses, front).map_or(-1, |u| i64::from(u.tet) + 1)
}

/// The `.edge` text: every line element with its line group's id as boundary marker.
fn edges(mesh: &VolumeMesh, model: &str) -> String {
    let n: usize = mesh.lines.iter().map(|g| g.lines.len()).sum();
    let mut edge = String::new();
    let _ = writeln!(edge, "# {model}: edge n1 n2 well\n{n} 1");
    let lines = (mesh.lines.iter().enumerate())
        .flat_map(|(g, group)| group.lines.iter().map(move |l| (g, l)));
    for (i, (g, [a, b])) in lines.enumerate() {
        let _ = writeln!(edge, "{} {} {} {}", i + 1, a + 1, b + 1, g + 1);
    }
    edge
}
