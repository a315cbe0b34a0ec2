//! One test per reader quirk of the issue, on small hand-written texts.

use gocad::import::{ImportOptions, Units, import_surface, import_surfaces, parse_gocad};
use test_support::paths;

fn opts() -> ImportOptions {
    ImportOptions::default()
}

fn named(name: &str) -> ImportOptions {
    ImportOptions {
        object: Some(name.into()),
        ..ImportOptions::default()
    }
}

const TRI: &str = "GOCAD TSurf 1\nHEADER {\nname: t\n}\nTFACE\nVRTX 1 0 0 0\nVRTX 2 1 0 0\nVRTX 3 0 1 0\nTRGL 1 2 3\nEND\n";

#[test]
fn a_minimal_surface_imports_with_its_name_vertices_and_triangle() {
    let s = import_surface(TRI.as_bytes(), "t.ts", &opts()).unwrap();
    assert_eq!(s.name, "t");
    assert_eq!(
        s.mesh.vertices,
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    );
    assert_eq!(s.mesh.triangles, vec![[0, 1, 2]]);
    assert_eq!(s.parts.len(), 1);
    assert_eq!(s.source.triangle_lines, vec![9]);
    assert_eq!(s.source.vertex_ids, vec![1, 2, 3]);
}

#[test]
fn crlf_tabs_trailing_tokens_comments_and_blank_lines_read_the_same() {
    let t = "# leading comment\r\nGOCAD\tTSurf 1\t\r\nHEADER {\r\nname:t\r\n}\r\n\r\nTFACE\r\n# c\r\nVRTX\t1  0 0 0 CNXYZ\r\nVRTX 2 1 0 0   \r\nVRTX 3 0 1 0\r\nTRGL 1 2 3 extra\r\nEND\r\n";
    let s = import_surface(t.as_bytes(), "t.ts", &opts()).unwrap();
    let r = import_surface(TRI.as_bytes(), "t.ts", &opts()).unwrap();
    assert_eq!(s.mesh, r.mesh);
    assert_eq!(s.name, "t");
}

#[test]
fn header_with_colon_and_name_with_equals_are_both_names() {
    let a = TRI.replace("HEADER {", "HEADER: {");
    assert_eq!(
        import_surface(a.as_bytes(), "a.ts", &opts()).unwrap().name,
        "t"
    );
    let b = TRI.replace("name: t", "name= t 1");
    assert_eq!(
        import_surface(b.as_bytes(), "b.ts", &opts()).unwrap().name,
        "t 1"
    );
    let c = TRI.replace("name: t", "name: \"Blah 1 2\"");
    assert_eq!(
        import_surface(c.as_bytes(), "c.ts", &opts()).unwrap().name,
        "Blah 1 2"
    );
}

#[test]
fn zpositive_depth_negates_z_and_keeps_the_corner_order() {
    let t = TRI
        .replace("TFACE", "GOCAD_ORIGINAL_COORDINATE_SYSTEM\nZPOSITIVE Depth\nEND_ORIGINAL_COORDINATE_SYSTEM\nTFACE")
        .replace("VRTX 3 0 1 0", "VRTX 3 0 1 250");
    let s = import_surface(t.as_bytes(), "d.ts", &opts()).unwrap();
    assert_eq!(s.mesh.vertices[2], [0.0, 1.0, -250.0]);
    assert_eq!(s.mesh.triangles, vec![[0, 1, 2]]);
}

#[test]
fn kilometre_axes_are_scaled_to_metres_and_kept_when_no_target_units() {
    let t = TRI.replace(
        "TFACE",
        "GOCAD_ORIGINAL_COORDINATE_SYSTEM\nAXIS_UNIT \"km\" \"km\" \"m\"\nEND_ORIGINAL_COORDINATE_SYSTEM\nTFACE",
    )
    .replace("VRTX 2 1 0 0", "VRTX 2 1.5 0 7");
    let s = import_surface(t.as_bytes(), "k.ts", &opts()).unwrap();
    assert_eq!(s.mesh.vertices[1], [1500.0, 0.0, 7.0]);
    let raw = import_surface(
        t.as_bytes(),
        "k.ts",
        &ImportOptions {
            target_units: None,
            ..opts()
        },
    )
    .unwrap();
    assert_eq!(raw.mesh.vertices[1], [1.5, 0.0, 7.0]);
    let km = import_surface(
        t.as_bytes(),
        "k.ts",
        &ImportOptions {
            target_units: Some(Units::Kilometre),
            ..opts()
        },
    )
    .unwrap();
    assert_eq!(km.mesh.vertices[1], [1.5, 0.0, 0.007]);
}

#[test]
fn an_unknown_zpositive_names_its_line() {
    let t = TRI.replace(
        "TFACE",
        "GOCAD_ORIGINAL_COORDINATE_SYSTEM\nZPOSITIVE Up\nEND_ORIGINAL_COORDINATE_SYSTEM\nTFACE",
    );
    let e = import_surface(t.as_bytes(), "z.ts", &opts()).unwrap_err();
    assert_eq!((e.line, e.file.as_str()), (6, "z.ts"));
    assert!(e.message.contains("ZPOSITIVE"), "{e}");
}

#[test]
fn pvrtx_keeps_property_values_per_column_with_esizes_and_quoted_names() {
    let t = "GOCAD TSurf 1\nPROPERTIES \" a b\" U\nESIZES 1 3\nTFACE\nPVRTX 0 0 0 0 9 1 2 3 CNXYZ\nPVRTX 1 1 0 0 8 4 5 6\nPVRTX 2 0 1 0 7 7 8 9\nTRGL 0 1 2\n";
    let s = import_surface(t.as_bytes(), "p.ts", &opts()).unwrap();
    assert_eq!(s.property_names, vec![" a b", "U[0]", "U[1]", "U[2]"]);
    assert_eq!(s.properties[0], vec![9.0, 8.0, 7.0]);
    assert_eq!(s.properties[3], vec![3.0, 6.0, 9.0]);
}

#[test]
fn a_pvrtx_with_too_few_values_names_the_line() {
    let t = "GOCAD TSurf 1\nPROPERTIES a b\nPVRTX 0 0 0 0 1\n";
    let e = parse_gocad(t.as_bytes(), "p.ts").unwrap_err();
    assert_eq!(e.line, 3);
    assert!(e.message.contains("declare 2"), "{e}");
}

#[test]
fn atom_and_patom_alias_an_earlier_vertex() {
    let t = "GOCAD TSurf 1\nTFACE\nVRTX 1 0 0 0\nVRTX 2 1 0 0\nVRTX 3 0 1 0\nTRGL 1 2 3\nTFACE\nATOM 4 2\nPATOM 5 3 77\nVRTX 6 1 1 0\nTRGL 4 6 5\nEND";
    let s = import_surface(t.as_bytes(), "a.ts", &opts()).unwrap();
    assert_eq!(s.mesh.vertices.len(), 4);
    assert_eq!(s.mesh.triangles, vec![[0, 1, 2], [1, 3, 2]]);
    assert_eq!(s.triangle_part, vec![0, 1]);
    assert_eq!(s.parts.len(), 2);
    assert_eq!(s.parts[1].line, 7);
}

#[test]
fn gaps_in_ids_and_zero_based_ids_are_resolved_by_id() {
    let t = "GOCAD TSurf 1\nVRTX 0 0 0 0\nVRTX 7 1 0 0\nVRTX 1000000 0 1 0\nTRGL 1000000 0 7\n";
    let s = import_surface(t.as_bytes(), "g.ts", &opts()).unwrap();
    assert_eq!(s.mesh.triangles, vec![[2, 0, 1]]);
}

#[test]
fn a_triangle_pointing_at_a_missing_vertex_names_the_line() {
    let t = "GOCAD TSurf 1\nVRTX 1 0 0 0\nVRTX 2 1 0 0\nVRTX 3 0 1 0\nTRGL 1 2 3\nTRGL 1 2 9\n";
    let e = import_surface(t.as_bytes(), "m.ts", &opts()).unwrap_err();
    assert_eq!(
        e.to_string(),
        "m.ts:6: TRGL points at vertex 9, which is not defined"
    );
}

#[test]
fn a_non_numeric_or_infinite_coordinate_names_the_line_and_axis() {
    let e = parse_gocad(b"GOCAD TSurf 1\nVRTX 1 0 blah 0\n", "n.ts").unwrap_err();
    assert_eq!(e.line, 2);
    assert!(
        e.message.contains("y coordinate 'blah' is not a number"),
        "{e}"
    );
    let e = parse_gocad(b"GOCAD TSurf 1\nVRTX 1 0 0 nan\n", "n.ts").unwrap_err();
    assert!(
        e.message.contains("z coordinate 'nan' is infinite or NaN"),
        "{e}"
    );
}

#[test]
fn a_coordinate_beyond_any_position_on_earth_is_refused_at_its_line_as_likely_no_data() {
    for (value, axis) in [("1e308", "x"), ("-2.5e13", "z")] {
        let vrtx = if axis == "x" {
            format!("VRTX 2 {value} 0 0")
        } else {
            format!("VRTX 2 0 0 {value}")
        };
        let t = format!("GOCAD TSurf 1\nVRTX 1 0 0 0\n{vrtx}\nVRTX 3 0 1 0\nTRGL 1 2 3\nEND\n");
        let e = import_surface(t.as_bytes(), "spike.ts", &ImportOptions::default()).unwrap_err();
        assert_eq!(e.line, 3, "{e}");
        assert!(
            e.message.contains(&format!("VRTX 2: {axis} coordinate")),
            "{e}"
        );
        assert!(e.message.contains("no-data value"), "{e}");
    }
    // A UTM northing in millimetres is still a position.
    let t = "GOCAD TSurf 1\nVRTX 1 0 7e9 0\nVRTX 2 1 7e9 0\nVRTX 3 0 7.000000001e9 0\nTRGL 1 2 3\nEND\n";
    assert!(import_surface(t.as_bytes(), "mm.ts", &ImportOptions::default()).is_ok());
}

#[test]
fn an_empty_file_is_named_without_a_line_zero() {
    let e = import_surface(b"", "empty.ts", &ImportOptions::default()).unwrap_err();
    let shown = e.to_string();
    assert!(
        shown.starts_with("empty.ts: the file holds no GOCAD object"),
        "{shown}"
    );
    assert!(
        shown.contains("it is empty, or not a gOcad ASCII file"),
        "{shown}"
    );
}

#[test]
fn a_duplicate_vertex_id_names_the_second_line() {
    let t = "GOCAD TSurf 1\nVRTX 1 0 0 0\nVRTX 2 1 0 0\nVRTX 1 0 1 0\n";
    let e = parse_gocad(t.as_bytes(), "d.ts").unwrap_err();
    assert_eq!(e.line, 4);
    assert!(e.message.contains("duplicate vertex id 1"), "{e}");
    // Sparse ids take the sorted path; same answer.
    let t = "GOCAD TSurf 1\nVRTX 100000000 0 0 0\nVRTX 2 1 0 0\nVRTX 100000000 0 1 0\n";
    assert_eq!(parse_gocad(t.as_bytes(), "d.ts").unwrap_err().line, 4);
}

#[test]
fn another_object_type_is_named_unless_skipped() {
    let t = format!("GOCAD SGrid 1\nHEADER {{\nname: box\n}}\nEND\n{TRI}");
    let e = import_surface(t.as_bytes(), "s.ts", &opts()).unwrap_err();
    assert_eq!(e.line, 1);
    assert!(e.message.contains("GOCAD SGrid"), "{e}");
    let s = import_surface(
        t.as_bytes(),
        "s.ts",
        &ImportOptions {
            skip_other_types: true,
            ..opts()
        },
    )
    .unwrap();
    assert_eq!(s.name, "t");
    let e = import_surface(t.as_bytes(), "s.ts", &named("box")).unwrap_err();
    assert!(e.message.contains("SGrid"), "{e}");
}

#[test]
fn several_surfaces_need_a_name_and_a_missing_end_closes_at_the_next_object() {
    let t = format!(
        "{}{}",
        TRI.replace("END\n", ""),
        TRI.replace("name: t", "name: u")
    );
    let f = parse_gocad(t.as_bytes(), "m.ts").unwrap();
    assert_eq!(f.objects.len(), 2);
    assert_eq!(f.objects[0].end_line, None);
    assert!(
        import_surface(t.as_bytes(), "m.ts", &opts())
            .unwrap_err()
            .message
            .contains("2 TSurf objects")
    );
    assert_eq!(
        import_surface(t.as_bytes(), "m.ts", &named("u"))
            .unwrap()
            .name,
        "u"
    );
    assert_eq!(
        import_surfaces(t.as_bytes(), "m.ts", &opts())
            .unwrap()
            .len(),
        2
    );
}

#[test]
fn a_group_flattens_its_member_surfaces_and_names_the_group() {
    let t = format!(
        "GOCAD HomogeneousGroup 1\nHEADER {{\nname:g\n}}\nTYPE TSurf\nBEGIN_MEMBERS\n{TRI}END_MEMBERS\n"
    );
    let f = parse_gocad(t.as_bytes(), "g.gp").unwrap();
    assert_eq!(f.objects.len(), 1);
    assert_eq!(f.objects[0].group.as_deref(), Some("g"));
    assert_eq!(
        import_surface(t.as_bytes(), "g.gp", &opts())
            .unwrap()
            .mesh
            .triangles
            .len(),
        1
    );
}

#[test]
fn bstone_and_border_resolve_to_vertex_indices() {
    let t = TRI.replace("END\n", "BSTONE 2\nBORDER 4 2 3\nEND\n");
    let s = import_surface(t.as_bytes(), "b.ts", &opts()).unwrap();
    assert_eq!(s.bstones, vec![1]);
    assert_eq!(s.borders, vec![[1, 2]]);
}

#[test]
fn a_model3d_keeps_regions_and_matches_tfaces_by_key_point() {
    let t = "GOCAD Model3d 1\nHEADER {\nname:m\n}\nTSURF t\nTFACE 7 boundary t\n 0 1 0\n 1 0 0\n 0 0 0\nREGION 8 Universe\n +7 -7 0\nLAYER L\n 8 0\nEND\n".to_string()
        + TRI;
    let f = parse_gocad(t.as_bytes(), "m.ml").unwrap();
    let m = f.model3d.as_ref().unwrap();
    assert_eq!(m.tfaces[0].key_points.len(), 3);
    assert_eq!(m.regions[0].sides, vec![7, -7]);
    assert_eq!(m.layers[0].ids, vec![8]);
    let s = import_surface(
        t.as_bytes(),
        "m.ml",
        &ImportOptions {
            skip_other_types: true,
            ..opts()
        },
    )
    .unwrap();
    assert_eq!(s.parts[0].model_tface, Some((7, "boundary".to_string())));
    assert_eq!(s.parts[0].name, "TFACE 7");
}

#[test]
fn a_file_without_objects_and_random_bytes_fail_cleanly() {
    assert!(
        import_surface(b"", "e.ts", &opts())
            .unwrap_err()
            .message
            .contains("no GOCAD object")
    );
    let header_only = "GOCAD TSurf 1\nHEADER {\nname:Testing12/3\n}\n";
    let e = import_surface(header_only.as_bytes(), "h.ts", &opts()).unwrap_err();
    assert_eq!(
        e.to_string(),
        "h.ts:1: TSurf object 'Testing12/3' has no triangles"
    );
    let junk: Vec<u8> = (0..2000u32)
        .map(|i| (i.wrapping_mul(2654435761) >> 13) as u8)
        .collect();
    assert!(import_surface(&junk, "j.ts", &opts()).is_err());
}

#[test]
fn the_surface_round_trips_through_postcard_for_the_cache() {
    let s = import_surface(TRI.as_bytes(), "t.ts", &opts()).unwrap();
    let bytes = postcard::to_stdvec(&s).unwrap();
    let back: gocad::import::ImportedSurface = postcard::from_bytes(&bytes).unwrap();
    assert_eq!(back, s);
}

#[test]
fn model_a4_fault_parts_get_their_model3d_tface_ids_and_types() {
    let Some(path) = paths::shared("data/gocad/ringmesh__RINGMesh/tests/data/modelA4.ml") else {
        return;
    };
    let bytes = std::fs::read(&path).expect("read");
    let s = import_surface(
        &bytes,
        "modelA4.ml",
        &ImportOptions {
            skip_other_types: true,
            ..named("F1fault")
        },
    )
    .unwrap();
    assert_eq!(s.parts.len(), 8);
    let mut ids: Vec<u64> = s
        .parts
        .iter()
        .map(|p| p.model_tface.as_ref().unwrap().0)
        .collect();
    ids.sort();
    assert_eq!(ids, (1..=8).collect::<Vec<u64>>());
    assert!(
        s.parts
            .iter()
            .all(|p| p.model_tface.as_ref().unwrap().1 == "normal_fault")
    );
    // ZPOSITIVE Depth: every z is the negated value of the text.
    let raw = gocad::import::parse_gocad(&bytes, "modelA4.ml").unwrap();
    let f1 = raw.objects.iter().find(|o| o.name == "F1fault").unwrap();
    assert_eq!(s.mesh.vertices[0][2], -f1.vertices[0][2]);
}

fn at(k: u32) -> ImportOptions {
    ImportOptions {
        object: Some(gocad::import::ObjectRef::Position(k)),
        ..opts()
    }
}

#[test]
fn objects_sharing_a_name_are_told_apart_by_their_position_in_the_file() {
    // An SGrid, then two TSurf objects named `t` (the second moved up by 5).
    let t = format!(
        "GOCAD SGrid 1\nHEADER {{\nname: grid\n}}\nEND\n{TRI}{}",
        TRI.replace("0 1 0\n", "0 1 5\n")
    );
    let e = import_surface(t.as_bytes(), "m.ts", &named("t")).unwrap_err();
    assert_eq!(e.line, 6, "{e}");
    for said in [
        "2 objects are named 't'",
        "#2 't' (line 6)",
        "#3 't' (line 16)",
        "`object = 2`",
    ] {
        assert!(e.message.contains(said), "`{said}` not in {e}");
    }
    let e = import_surface(t.as_bytes(), "m.ts", &opts()).unwrap_err();
    assert!(e.message.contains("SGrid"), "{e}");
    let skip = ImportOptions {
        skip_other_types: true,
        ..opts()
    };
    let e = import_surface(t.as_bytes(), "m.ts", &skip).unwrap_err();
    assert!(
        e.message.contains("2 TSurf objects") && e.message.contains("by its position"),
        "{e}"
    );
    let second = import_surface(t.as_bytes(), "m.ts", &at(3)).unwrap();
    assert_eq!(second.mesh.vertices[2], [0.0, 1.0, 5.0]);
    let first = import_surface(t.as_bytes(), "m.ts", &at(2)).unwrap();
    assert_eq!(first.mesh.vertices[2], [0.0, 1.0, 0.0]);
    let e = import_surface(t.as_bytes(), "m.ts", &at(1)).unwrap_err();
    assert!(e.message.contains("GOCAD SGrid"), "{e}");
    for k in [0, 4] {
        let e = import_surface(t.as_bytes(), "m.ts", &at(k)).unwrap_err();
        assert!(
            e.message.contains(&format!("no object #{k}")) && e.message.contains("3 GOCAD objects"),
            "{e}"
        );
    }
}

#[test]
fn a_giant_name_line_is_cut_to_a_few_kilobytes_and_the_surface_imports() {
    // 64 MB of name: a file whose newlines were lost. The mesh is what it would be, and the name
    // kept is short and says how long the line was.
    let giant = "n".repeat(64 << 20);
    let t = TRI.replace("name: t", &format!("name: {giant}"));
    let s = import_surface(t.as_bytes(), "t.ts", &opts()).unwrap();
    let r = import_surface(TRI.as_bytes(), "t.ts", &opts()).unwrap();
    assert_eq!(s.mesh, r.mesh);
    assert!(s.name.len() < 4200, "{} bytes kept", s.name.len());
    assert!(s.name.ends_with(&format!("({} bytes in all)", 64 << 20)));
}

#[test]
fn a_giant_properties_line_is_refused_at_its_line_without_reading_every_name() {
    // Eight million property names on one line: refused at the 4097th, naming the line.
    let names = "p ".repeat(8 << 20);
    let t = TRI.replace("TFACE\n", &format!("PROPERTIES {names}\nTFACE\n"));
    let e = import_surface(t.as_bytes(), "t.ts", &opts()).unwrap_err();
    assert_eq!(e.line, 5, "{e}");
    assert!(e.to_string().contains("more than 4096 PROPERTIES"), "{e}");
}
