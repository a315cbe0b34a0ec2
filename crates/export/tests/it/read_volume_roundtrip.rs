//! Our msh 4.1 output (ASCII and binary) reads back into the same VolumeMesh.

use test_support::export_support;

use export::{Format, export};
use export_support::layered_box;
use geom::mesh::read::{read_msh, read_volume_msh};
use geom::mesh::{SurfaceKind, VolumeMesh};
use std::collections::BTreeMap;

fn without_kinds(mut m: VolumeMesh) -> VolumeMesh {
    for g in &mut m.surface_groups {
        g.kind = SurfaceKind::Other;
    }
    m
}

#[test]
fn msh_ascii_and_binary_round_trip_nodes_elements_groups_and_attributes() {
    let mesh = layered_box(6, 6);
    for format in [Format::Msh, Format::MshBinary] {
        let files = export(&mesh, "rt", format).unwrap();
        let back = read_volume_msh(&files[0].1, "rt.msh").unwrap();
        // Coordinates round-trip bit for bit in both encodings (shortest round-trip printing).
        assert_eq!(back.nodes, mesh.nodes, "{format:?}");
        // Elements come back grouped by region / group; compare as sorted sets with their tags.
        let mut a: Vec<_> = mesh.tets.iter().zip(&mesh.tet_region).collect();
        let mut b: Vec<_> = back.tets.iter().zip(&back.tet_region).collect();
        a.sort();
        b.sort();
        assert_eq!(a, b, "{format:?}");
        let mut a: Vec<_> = mesh.triangles.iter().zip(&mesh.triangle_group).collect();
        let mut b: Vec<_> = back.triangles.iter().zip(&back.triangle_group).collect();
        a.sort();
        b.sort();
        assert_eq!(a, b, "{format:?}");
        assert_eq!(
            back.regions, mesh.regions,
            "{format:?}: names, material ids and properties"
        );
        assert_eq!(
            back.surface_groups, mesh.surface_groups,
            "{format:?}: names and kinds"
        );
    }
}

#[test]
fn a_foreign_msh_without_kinds_reads_its_surfaces_as_other() {
    let mesh = layered_box(4, 3);
    let text = String::from_utf8(export(&mesh, "f", Format::Msh).unwrap().remove(0).1).unwrap();
    let (a, rest) = text.split_once("$GeorecipeSurfaceKinds").unwrap();
    let (_, b) = rest.split_once("$EndGeorecipeSurfaceKinds\n").unwrap();
    let back = read_volume_msh(format!("{a}{b}").as_bytes(), "f.msh").unwrap();
    assert_eq!(back.surface_groups, without_kinds(mesh).surface_groups);
}

#[test]
fn the_boundary_reader_sees_each_piece_of_a_surface_group_as_an_entity_named_after_it() {
    let mesh = layered_box(4, 3);
    let files = export(&mesh, "b", Format::MshBinary).unwrap();
    let b = read_msh(&files[0].1, "b.msh").unwrap();
    assert_eq!(b.triangles.len(), mesh.triangles.len());
    // Triangles per name, through the entities, as many as the group has.
    let mut got: BTreeMap<&str, usize> = BTreeMap::new();
    for t in &b.triangle_tag {
        *got.entry(b.tag_names[t].as_str()).or_default() += 1;
    }
    let mut want: BTreeMap<&str, usize> = BTreeMap::new();
    for &g in &mesh.triangle_group {
        *want
            .entry(mesh.surface_groups[g as usize].name.as_str())
            .or_default() += 1;
    }
    assert_eq!(got, want);
}

#[test]
fn a_binary_msh_cut_anywhere_is_an_error_naming_the_file() {
    let mesh = layered_box(4, 3);
    let bytes = &export(&mesh, "c", Format::MshBinary).unwrap()[0].1;
    // Cuts inside the node and element data (the trailing element data is optional).
    let end_elements = bytes
        .windows(12)
        .position(|w| w == b"$EndElements")
        .unwrap();
    for k in 1..60 {
        let cut = end_elements * k / 60;
        let e = read_volume_msh(&bytes[..cut], "c.msh").unwrap_err();
        assert_eq!(e.file, "c.msh");
    }
}

#[test]
fn a_binary_node_reference_out_of_range_is_refused() {
    let mesh = layered_box(4, 3);
    let mut bytes = export(&mesh, "c", Format::MshBinary).unwrap().remove(0).1;
    // The first tet's first node tag sits after the element header and block header.
    let start = bytes.windows(10).position(|w| w == b"$Elements\n").unwrap() + 10;
    let first_node = start + 4 * 8 + 3 * 4 + 8 + 8;
    bytes[first_node..first_node + 8].copy_from_slice(&123_456_789u64.to_le_bytes());
    let e = read_volume_msh(&bytes, "c.msh").unwrap_err();
    assert!(e.message.contains("node 123456789"), "{e}");
}

#[test]
fn msh_line_groups_round_trip_by_name_in_both_encodings() {
    let mut mesh = layered_box(4, 6);
    // Two "wells": chains along edges of the box's tets (any node pairs serve the writer).
    let t = mesh.tets[0];
    let u = mesh.tets[mesh.tets.len() - 1];
    mesh.lines = vec![
        geom::mesh::LineGroup {
            area: None,
            name: "W1".into(),
            lines: vec![[t[0], t[1]], [t[1], t[2]]],
        },
        geom::mesh::LineGroup {
            area: None,
            name: "W2".into(),
            lines: vec![[u[0], u[3]]],
        },
    ];
    for format in [Format::Msh, Format::MshBinary] {
        let files = export(&mesh, "rt", format).unwrap();
        let back = read_volume_msh(&files[0].1, "rt.msh").unwrap();
        assert_eq!(back.lines, mesh.lines, "{format:?}");
        assert_eq!(back.tets.len(), mesh.tets.len());
    }
}
