//! PLine import: the public `.pl` and group files with their own upstream counts, and one test per
//! rule on small hand-written texts.

use gocad::import::{
    ImportOptions, ObjectRef, Polyline, Units, import_line, import_lines, import_surface,
};
use test_support::paths;

fn opts() -> ImportOptions {
    ImportOptions::default()
}

fn named(name: &str) -> ImportOptions {
    ImportOptions {
        object: Some(name.into()),
        ..opts()
    }
}

/// A shared file's bytes, or `None` (with a note) when the shared data is absent.
fn shared(rel: &str) -> Option<Vec<u8>> {
    let p = paths::shared(&format!("data/gocad/{rel}"))?;
    Some(std::fs::read(p).expect("readable"))
}

const GEODE: &str = "Geode-solutions__OpenGeode-GeosciencesIO/tests/data";
const AUSCOPE: &str = "AuScope__geomodel-2-3dweb/test";
const EARTHSCI_PLINE: &str = "GeoscienceAustralia__earthsci/plugins/au.gov.ga.earthsci.worldwind.tests/resources/au/gov/ga/earthsci/worldwind/common/layers/model/gocad/pline.gp";

/// Every segment end is a vertex and every segment has a part.
fn assert_well_formed(l: &Polyline) {
    let n = l.vertices.len() as u32;
    assert!(l.segments.iter().flatten().all(|&v| v < n), "{}", l.name);
    assert_eq!(l.segment_part.len(), l.segments.len());
    assert_eq!(l.segment_lines.len(), l.segments.len());
    let counted: usize = l.parts.iter().map(|p| p.segment_count).sum();
    assert_eq!(counted, l.segments.len());
    assert_eq!(l.source.vertex_ids.len(), l.vertices.len());
}

#[test]
fn normal_lines_pl_reads_11391_vertices_and_11374_segments() {
    let Some(bytes) = shared(&format!("{GEODE}/normal_lines.pl")) else {
        return;
    };
    let l = import_line(&bytes, "normal_lines.pl", &opts()).unwrap();
    assert_eq!(l.name, "ls-fcl-25");
    assert_eq!(l.vertices.len(), 11_391);
    assert_eq!(l.segments.len(), 11_374);
    assert_eq!(l.parts.len(), 17);
    let y: f64 = "6075853.2641601562".parse().unwrap();
    assert_eq!(l.vertices[0], [313590.0, y, 319.0]);
    assert_well_formed(&l);
}

#[test]
fn closed_lines_pl_reads_9395_vertices_and_9395_segments_and_closes_its_loops() {
    let Some(bytes) = shared(&format!("{GEODE}/closed_lines.pl")) else {
        return;
    };
    let l = import_line(&bytes, "closed_lines.pl", &opts()).unwrap();
    assert_eq!(l.vertices.len(), 9_395);
    assert_eq!(l.segments.len(), 9_395);
    assert_eq!(l.parts.len(), 74);
    // The last SEG, `SEG 9395 9334`, goes back to its loop's first vertex.
    assert_eq!(l.segments.last(), Some(&[9394, 9333]));
    assert_well_formed(&l);
}

#[test]
fn auscope_pltest_reads_two_ilines_of_six_segments_with_depth_negated() {
    let Some(bytes) = shared(&format!("{AUSCOPE}/regression/input/plTest.pl")) else {
        return;
    };
    let l = import_line(&bytes, "plTest.pl", &opts()).unwrap();
    assert_eq!(l.name, "Rectangle");
    assert_eq!(l.vertices.len(), 12);
    assert_eq!(
        l.parts
            .iter()
            .map(|p| (p.name.as_str(), p.line, p.segment_count))
            .collect::<Vec<_>>(),
        vec![("ILINE 1", 15, 6), ("ILINE 2", 28, 6)]
    );
    // ZPOSITIVE Depth: `VRTX 1 868000 7016000 -1467.5` lies 1467.5 m above the datum.
    assert_eq!(l.vertices[0], [868000.0, 7016000.0, 1467.5]);
    assert_eq!(l.segments[5], [5, 0]);
    assert_eq!(l.segment_part[6], 1);
    assert_well_formed(&l);
}

#[test]
fn auscope_test003_and_test037_read_one_segment_each() {
    for (f, seg_line) in [("test003.pl", 17), ("test037.pl", 18)] {
        let Some(bytes) = shared(&format!("{AUSCOPE}/unit/gocad_import/input/{f}")) else {
            return;
        };
        let l = import_line(&bytes, f, &opts()).unwrap();
        assert_eq!((l.name.as_str(), l.vertices.len()), ("BLAH", 2), "{f}");
        assert_eq!(l.segments, vec![[0, 1]], "{f}");
        assert_eq!(l.segment_lines, vec![seg_line], "{f}");
    }
}

#[test]
fn a_nested_group_yields_its_three_lines_in_file_order_and_one_by_name() {
    let Some(bytes) = shared(&format!("{AUSCOPE}/regression/input/2layer.gp")) else {
        return;
    };
    let all = import_lines(&bytes, "2layer.gp", &opts()).unwrap();
    let names: Vec<&str> = all.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, vec!["test_line1", "test_line2", "test_line3"]);
    assert!(all.iter().all(|l| l.segments.len() == 2));
    let two = import_line(&bytes, "2layer.gp", &named("test_line2")).unwrap();
    assert_eq!(two.vertices[0], [393373.90625, 5398726.5, -368.339996338]);
    let e = import_line(&bytes, "2layer.gp", &opts()).unwrap_err();
    assert!(e.message.contains("3 PLine objects"), "{e}");
}

#[test]
fn earthsci_pline_group_reads_pvrtx_coordinates_without_their_property_values() {
    // Its PVRTX carry 6 values where PROPERTIES declares 7: a surface would be refused, a line
    // keeps no property values, so the coordinates are all it needs.
    let Some(bytes) = shared(EARTHSCI_PLINE) else {
        return;
    };
    let l = import_line(&bytes, "pline.gp", &opts()).unwrap();
    assert_eq!(l.name, "pline.asc");
    assert_eq!(
        l.vertices,
        vec![
            [150.12479808, -25.98275359, -296.323],
            [150.12363831, -25.98263431, -647.108]
        ]
    );
    assert_eq!(l.segments, vec![[0, 1]]);
}

const LINE: &str = "GOCAD PLine 1\r\nHEADER {\r\nname: fault trace\r\n}\r\nGOCAD_ORIGINAL_COORDINATE_SYSTEM\r\nAXIS_UNIT \"km\" \"km\" \"m\"\r\nZPOSITIVE Depth\r\nEND_ORIGINAL_COORDINATE_SYSTEM\r\nPROPERTIES a\r\nILINE\r\nPVRTX 1 1 2 300 7\r\nVRTX 2 1.5 2 310\r\nATOM 3 2\r\nVRTX 4 2 2 320\r\nSEG 1 2\r\nSEG 3 4\r\nILINE\r\nVRTX 5 0 0 0\r\nVRTX 6 0 1 0\r\nSEG 5 6\r\nEND";

#[test]
fn a_crlf_line_without_final_newline_scales_units_negates_depth_and_resolves_atoms() {
    let l = import_line(LINE.as_bytes(), "t.pl", &opts()).unwrap();
    assert_eq!(l.name, "fault trace");
    assert_eq!(l.vertices.len(), 5);
    assert_eq!(l.vertices[0], [1000.0, 2000.0, -300.0]);
    assert_eq!(l.vertices[1], [1500.0, 2000.0, -310.0]);
    // ATOM 3 repeats vertex 2: the second SEG starts where the first ends.
    assert_eq!(l.segments, vec![[0, 1], [1, 2], [3, 4]]);
    assert_eq!(l.segment_part, vec![0, 0, 1]);
    assert_eq!(l.segment_lines, vec![15, 16, 20]);
    assert_eq!(l.source.vertex_ids, vec![1, 2, 4, 5, 6]);
    assert_eq!(l.source.vertex_lines, vec![11, 12, 14, 18, 19]);
    let km = ImportOptions {
        target_units: Some(Units::Kilometre),
        ..opts()
    };
    assert_eq!(
        import_line(LINE.as_bytes(), "t.pl", &km).unwrap().vertices[0],
        [1.0, 2.0, -0.3]
    );
}

#[test]
fn segments_before_any_iline_make_one_part_named_after_the_object_line() {
    let t = "GOCAD PLine 1\nVRTX 1 0 0 0\nVRTX 2 1 0 0\nSEG 1 2\nEND\n";
    let l = import_line(t.as_bytes(), "p.pl", &opts()).unwrap();
    assert_eq!(l.parts.len(), 1);
    assert_eq!((l.parts[0].name.as_str(), l.parts[0].line), ("ILINE 1", 1));
}

#[test]
fn a_seg_pointing_at_a_missing_vertex_names_the_file_and_line() {
    let t = LINE.replace("SEG 5 6", "SEG 5 9");
    let e = import_line(t.as_bytes(), "bad.pl", &opts()).unwrap_err();
    assert_eq!((e.file.as_str(), e.line), ("bad.pl", 20));
    assert_eq!(e.message, "SEG points at vertex 9, which is not defined");
}

#[test]
fn a_bad_coordinate_in_a_line_names_its_line() {
    let t = LINE.replace("VRTX 5 0 0 0", "VRTX 5 0 blah 0");
    let e = import_line(t.as_bytes(), "bad.pl", &opts()).unwrap_err();
    assert_eq!(e.line, 18);
    assert!(e.message.contains("'blah' is not a number"), "{e}");
}

const TRI: &str = "GOCAD TSurf 1\nHEADER {\nname: t\n}\nTFACE\nVRTX 1 0 0 0\nVRTX 2 1 0 0\nVRTX 3 0 1 0\nTRGL 1 2 3\nEND\n";

#[test]
fn a_broken_line_does_not_stop_the_surfaces_of_its_file_from_importing() {
    let t = format!("{TRI}{}", LINE.replace("SEG 5 6", "SEG 5 9"));
    let skip = ImportOptions {
        skip_other_types: true,
        ..opts()
    };
    let s = import_surface(t.as_bytes(), "mixed.gp", &skip).unwrap();
    assert_eq!(s.mesh.triangles.len(), 1);
    let e = import_line(t.as_bytes(), "mixed.gp", &named("fault trace")).unwrap_err();
    assert_eq!(e.line, 30);
}

#[test]
fn a_name_no_line_has_lists_the_lines_of_the_file() {
    let t = format!("{TRI}{LINE}");
    let e = import_line(t.as_bytes(), "m.gp", &named("nope")).unwrap_err();
    assert_eq!(e.file, "m.gp");
    assert_eq!(
        e.message,
        "no object named 'nope'; PLine objects here: #2 'fault trace' (line 11)"
    );
    let e = import_line(TRI.as_bytes(), "t.ts", &named("nope")).unwrap_err();
    assert_eq!(
        e.message,
        "no object named 'nope'; PLine objects here: none; the file holds TSurf #1 't' (line 1)"
    );
}

#[test]
fn a_surface_asked_for_as_a_line_is_refused_by_its_type() {
    let t = format!("{TRI}{LINE}");
    let e = import_line(t.as_bytes(), "m.gp", &named("t")).unwrap_err();
    assert_eq!(e.line, 1);
    assert!(
        e.message
            .contains("is a GOCAD TSurf where a PLine line is expected"),
        "{e}"
    );
    let by_position = ImportOptions {
        object: Some(ObjectRef::Position(2)),
        ..opts()
    };
    assert_eq!(
        import_line(t.as_bytes(), "m.gp", &by_position)
            .unwrap()
            .name,
        "fault trace"
    );
}

#[test]
fn a_line_without_segments_is_an_error_naming_it() {
    let t = "GOCAD PLine 1\nHEADER {\nname: dots\n}\nVRTX 1 0 0 0\nEND\n";
    let e = import_line(t.as_bytes(), "d.pl", &opts()).unwrap_err();
    assert_eq!(e.line, 1);
    assert_eq!(
        e.message,
        "PLine object 'dots' has no segments (no SEG record)"
    );
}

fn pline(body: &str) -> Polyline {
    let text = format!("GOCAD PLine 1\r\nHEADER {{\r\nname:w\r\n}}\r\n{body}END\r\n");
    import_line(text.as_bytes(), "w.pl", &opts()).expect("a valid PLine")
}

#[test]
fn a_pline_read_as_a_path_starts_at_its_higher_end_and_follows_its_segments() {
    // Segments given out of order and reversed: the path still runs from the top down.
    let l = pline(
        "ILINE\r\nVRTX 1 0 0 -300\r\nVRTX 2 5 0 0\r\nVRTX 3 2 0 -100\r\nSEG 3 1\r\nSEG 2 3\r\n",
    );
    let (path, lines) = l.open_path().expect("one chain");
    assert_eq!(
        path,
        [[5.0, 0.0, 0.0], [2.0, 0.0, -100.0], [0.0, 0.0, -300.0]]
    );
    assert_eq!(lines, [7, 8, 6], "the VRTX record of each point");
}

#[test]
fn a_pline_that_branches_closes_or_breaks_is_not_a_path_and_the_error_names_the_line() {
    let branch = pline(
        "ILINE\r\nVRTX 1 0 0 0\r\nVRTX 2 0 0 -1\r\nVRTX 3 1 0 -2\r\nVRTX 4 -1 0 -2\r\nSEG 1 2\r\nSEG 2 3\r\nSEG 2 4\r\n",
    );
    let e = branch.open_path().expect_err("branches");
    assert!(e.message.contains("branches"), "{e}");
    assert_eq!(
        (e.file.as_str(), e.line),
        ("w.pl", 7),
        "the branching vertex's VRTX"
    );
    let closed = pline(
        "ILINE\r\nVRTX 1 0 0 0\r\nVRTX 2 1 0 -1\r\nVRTX 3 -1 0 -1\r\nSEG 1 2\r\nSEG 2 3\r\nSEG 3 1\r\n",
    );
    assert!(
        closed
            .open_path()
            .expect_err("closed")
            .message
            .contains("closed")
    );
    let broken = pline(
        "ILINE\r\nVRTX 1 0 0 0\r\nVRTX 2 0 0 -1\r\nILINE\r\nVRTX 3 5 0 0\r\nVRTX 4 5 0 -1\r\nSEG 1 2\r\nSEG 3 4\r\n",
    );
    let e = broken.open_path().expect_err("two pieces");
    assert!(e.message.contains("several pieces"), "{e}");
}
