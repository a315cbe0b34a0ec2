//! TetGen `.node` / `.ele` / `.face` / `.edge` writer (TetGen's file formats, 1-based indices):
//! nodes without attributes or markers; tets with one attribute, the region id (region index +
//! 1, as TetGen's `-A` region attributes); faces with a boundary marker = surface group index +
//! 1; and, only when the mesh has line groups (wells), edges (the line elements, group after
//! group) with a boundary marker = line group index + 1, as TetGen writes an `.edge` file only
//! when asked (`-e`). Files are named `<model>.1.node` etc. (by `super::file_names`), as TetGen
//! names the first refinement's output.
//!
//! The named points (the wells' crossings of the surfaces) are not written: a `.node` boundary
//! marker is one integer per node that TetGen itself sets on its boundary nodes, so using it
//! for a few labelled nodes would be read as a boundary marking. The msh, Exodus, VTU and
//! Abaqus files carry them.

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
    let mut face = String::new();
    let _ = writeln!(
        face,
        "# {model}: face n1 n2 n3 surface\n{} 1",
        mesh.triangles.len()
    );
    for (i, (t, g)) in mesh.triangles.iter().zip(&mesh.triangle_group).enumerate() {
        let _ = writeln!(
            face,
            "{} {} {} {} {}",
            i + 1,
            t[0] + 1,
            t[1] + 1,
            t[2] + 1,
            g + 1
        );
    }
    let mut texts = vec![node, ele, face];
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
