//! MEDIT `.mesh` writer (INRIA ASCII format, read by mmg, FreeFem and meshio): `Vertices` with
//! reference 0, `Edges` (the wells' line elements, group after group) with reference = line
//! group index + 1, `Triangles` with reference = surface group index + 1, `Tetrahedra` with
//! reference = region index + 1, in the order mmg writes them. Indices are 1-based. A section
//! with no element is left out. MEDIT has no names: the references are the same ids as the msh
//! physical tags, so the names can be looked up there or in the report.
//!
//! A fault's sides are its triangles' winding: each triangle is written once, in the mesh's
//! vertex order, so its right-hand normal points to the fault's front (`<fault>:front` in the
//! other formats, whose ids MEDIT does not use). A second copy of a triangle per side, with the
//! side's id as reference, would be a duplicate boundary face to mmg and FreeFem, which read the
//! references as boundary labels on the tet faces.
//!
//! The named points (the wells' crossings of the surfaces) are not written: MEDIT's `Corners`
//! and `RequiredVertices` are remeshing constraints for mmg, not labels (no reference, no name),
//! and a vertex reference would give every other vertex a meaning it does not have. The msh,
//! Exodus, VTU and Abaqus files carry them.

use geom::mesh::VolumeMesh;
use std::fmt::Write as _;

pub(super) fn write(mesh: &VolumeMesh) -> Vec<u8> {
    let mut s = String::new();
    s.push_str("MeshVersionFormatted 2\n\nDimension 3\n\n");
    let _ = writeln!(s, "Vertices\n{}", mesh.nodes.len());
    for p in &mesh.nodes {
        let _ = writeln!(s, "{} {} {} 0", p[0], p[1], p[2]);
    }
    let edges: usize = mesh.lines.iter().map(|g| g.lines.len()).sum();
    if edges > 0 {
        let _ = writeln!(s, "\nEdges\n{edges}");
        for (g, group) in mesh.lines.iter().enumerate() {
            for [a, b] in &group.lines {
                let _ = writeln!(s, "{} {} {}", a + 1, b + 1, g + 1);
            }
        }
    }
    if !mesh.triangles.is_empty() {
        let _ = writeln!(s, "\nTriangles\n{}", mesh.triangles.len());
        for (t, g) in mesh.triangles.iter().zip(&mesh.triangle_group) {
            let _ = writeln!(s, "{} {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1, g + 1);
        }
    }
    if !mesh.tets.is_empty() {
        let _ = writeln!(s, "\nTetrahedra\n{}", mesh.tets.len());
        for (t, r) in mesh.tets.iter().zip(&mesh.tet_region) {
            let _ = writeln!(
                s,
                "{} {} {} {} {}",
                t[0] + 1,
                t[1] + 1,
                t[2] + 1,
                t[3] + 1,
                r + 1
            );
        }
    }
    s.push_str("\nEnd\n");
    s.shrink_to_fit();
    s.into_bytes()
}
