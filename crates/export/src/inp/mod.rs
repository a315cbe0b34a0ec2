//! Abaqus `.inp` writer (also read by CalculiX, PyLith's converters and meshio): `*Node`, one
//! `*Element, type=C3D4, elset=<region>` block per region, one `*Element, type=T3D2,
//! elset=<well>` block per line group (well) with lines, a material and a solid section per
//! region ([`materials`]), and the boundary groups ([`surfaces`]): a node set and an
//! element-face surface per surface group, a surface per side of every fault, a node set and
//! a surface per face set (the recipe's `[groups]`), then a one-node `*Nset` per named point
//! (a well's crossing of a surface). A well gets a truss section (`*Solid Section` with its
//! cross-section area) when the recipe gives it an `area`; otherwise the analyst adds one (a
//! `**` comment says so) before Abaqus runs the file.
//!
//! Element numbers, side sets and fault sides are the Exodus writer's (tets numbered in region
//! order from 1, then the wells' line elements in group order; a face named from the tet of the
//! lowest element number, a fault side from the tets on that side), so the two files name the
//! same elements and faces. Abaqus names cannot hold spaces, commas or colons: names are
//! sanitised and made unique ([`labels`]; `F1:front` becomes `F1_front`), and `**` comment
//! lines, which every reader skips, pair each label with the original name, id and material.

mod labels;
mod materials;
mod surfaces;

use crate::exodus::sets;
use crate::numbering::Numbering;
use crate::sides;
use geom::mesh::VolumeMesh;
use labels::Labels;
use std::fmt::Write as _;

/// Fails when a surface triangle is not a face of any tet (Abaqus surfaces are element faces).
pub(super) fn write(mesh: &VolumeMesh, model: &str) -> Result<Vec<u8>, String> {
    let numbering = Numbering::new(mesh);
    let uses = sides::face_uses(mesh, &numbering.number);
    sides::every_triangle_a_face(mesh, &uses)?;
    let side_sets = sets::side_sets(mesh, &uses);
    let mut node_sets = sets::node_sets(mesh);
    // A face set's node set goes by its surface's label: under its side set's id.
    let first = crate::face_sets::first_id(&mesh.surface_groups);
    node_sets.extend(sets::face_set_node_sets(mesh, first));
    let labels = Labels::new(mesh, &side_sets);
    let mut s = String::new();
    let _ = writeln!(s, "*Heading\n georecipe model {model}");
    labels.comments(&mut s, mesh, &side_sets);
    s.push_str("*Node\n");
    for (i, p) in mesh.nodes.iter().enumerate() {
        let _ = writeln!(s, "{}, {}, {}, {}", i + 1, p[0], p[1], p[2]);
    }
    for (r, tets) in &numbering.blocks {
        let _ = writeln!(s, "*Element, type=C3D4, elset={}", labels.regions[*r]);
        for &t in tets {
            let [a, b, c, d] = mesh.tets[t];
            let n = numbering.number[t];
            let _ = writeln!(s, "{n}, {}, {}, {}, {}", a + 1, b + 1, c + 1, d + 1);
        }
    }
    for &(w, first) in &numbering.wells {
        let _ = writeln!(s, "*Element, type=T3D2, elset={}", labels.wells[w]);
        for (n, [a, b]) in (first..).zip(&mesh.lines[w].lines) {
            let _ = writeln!(s, "{n}, {}, {}", a + 1, b + 1);
        }
    }
    materials::put(&mut s, mesh, &labels, &numbering);
    surfaces::put(&mut s, &labels, &node_sets, &side_sets);
    for (p, label) in mesh.points.iter().zip(&labels.points) {
        let _ = writeln!(s, "*Nset, nset={label}\n{}", p.node + 1);
    }
    s.shrink_to_fit();
    Ok(s.into_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_that_is_no_tet_face_is_refused_with_its_coordinates() {
        let mesh = VolumeMesh {
            nodes: vec![
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
                [5.0, 5.0, 5.0],
            ],
            tets: vec![[0, 1, 2, 3]],
            tet_region: vec![0],
            regions: vec![geom::mesh::RegionGroup {
                name: "r".into(),
                material: None,
                properties: Default::default(),
            }],
            triangles: vec![[0, 1, 2], [0, 1, 4]],
            triangle_group: vec![0, 0],
            surface_groups: vec![geom::mesh::SurfaceGroup {
                name: "fault".into(),
                kind: geom::mesh::SurfaceKind::Fault,
            }],
            lines: Vec::new(),
            points: Vec::new(),
            face_sets: Vec::new(),
        };
        let e = write(&mesh, "m").unwrap_err();
        assert!(
            e.contains("'fault' triangle 1") && e.contains("[5.0, 5.0, 5.0]"),
            "{e}"
        );
    }
}
