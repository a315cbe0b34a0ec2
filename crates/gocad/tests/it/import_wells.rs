//! Well import on hand-written Well files modelled on the public ones (no Well file is in the
//! shared data): a vertical well in an Elevation frame laid out like AuScope's `wl2Test.wl`, a
//! deviated well in a Depth frame with measured depths in feet (CRLF, no final newline), a path
//! given by VRTX, a well group, logs, and one test per refused input.

use gocad::import::{
    ImportOptions, ObjectRef, Units, WellPath, import_surface, import_well, import_wells,
    parse_gocad,
};

fn opts() -> ImportOptions {
    ImportOptions::default()
}

fn named(name: &str) -> ImportOptions {
    ImportOptions {
        object: Some(name.into()),
        ..opts()
    }
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-9)
}

/// A vertical well: head at sea level, first station at the kelly bushing 94 m above it, two
/// markers with their description lines, a zone and a log.
const VERTICAL: &str = "GOCAD Well 1
HEADER {
name: W1
}
GOCAD_ORIGINAL_COORDINATE_SYSTEM
NAME Default
AXIS_NAME X Y Z
AXIS_UNIT m m m
ZPOSITIVE Elevation
END_ORIGINAL_COORDINATE_SYSTEM
WP_CATALOG_FILE \"W1__zms@@\"
PATH_ZM_UNIT m
WREF 377318.5 8372318.25 0
DATUM SeaLevel
KB 94
PATH 0 94 0 0
PATH 1586.5 -1492.5 0 0
ZM_NPTS 2
MRKR Top_A 1 230.5
UNIT A_Grp
FEATURE A_Grp
MRKR Base_A 1 680
NO_FEATURE
ZONE default 230.5 680 -1
WELL_CURVE
PROPERTY GR
PROPERTY_UNIT API
ZM_UNIT m
REC 100 55.5
REC 200 60
END_CURVE
END
";

#[test]
fn a_vertical_well_keeps_its_head_stations_and_measured_depths() {
    let w = import_well(VERTICAL.as_bytes(), "w1.wl", &opts()).unwrap();
    assert_eq!(w.name, "W1");
    assert_eq!(w.file, "w1.wl");
    assert_eq!(w.head, [377318.5, 8372318.25, 0.0]);
    assert_eq!(
        w.stations,
        vec![
            [377318.5, 8372318.25, 94.0],
            [377318.5, 8372318.25, -1492.5]
        ]
    );
    assert_eq!(w.measured_depth, vec![0.0, 1586.5]);
    assert_eq!(w.station_lines, vec![16, 17]);
}

#[test]
fn markers_are_placed_on_the_path_by_measured_depth() {
    let w = import_well(VERTICAL.as_bytes(), "w1.wl", &opts()).unwrap();
    let m: Vec<(&str, f64, usize)> = w
        .markers
        .iter()
        .map(|m| (m.name.as_str(), m.md, m.line))
        .collect();
    assert_eq!(m, vec![("Top_A", 230.5, 19), ("Base_A", 680.0, 22)]);
    // 230.5 m along a vertical hole from the kelly bushing at +94 m.
    assert!(close(w.markers[0].xyz, [377318.5, 8372318.25, -136.5]));
    assert!(close(w.markers[1].xyz, [377318.5, 8372318.25, -586.0]));
}

/// A deviated well written in a Depth frame with measured depths in feet; CRLF, no final newline.
const DEVIATED: &str = "GOCAD Well 1\r\nHEADER {\r\nname: D-2\r\n}\r\nGOCAD_ORIGINAL_COORDINATE_SYSTEM\r\nAXIS_UNIT m m m\r\nZPOSITIVE Depth\r\nEND_ORIGINAL_COORDINATE_SYSTEM\r\nPATH_ZM_UNIT ft\r\nWREF 1000 2000 -25\r\nPATH 0 -25 0 0\r\nPATH 1000 279.8 0 0\r\nPATH 2000 520 150 50\r\nPATH 3000 700 400 120\r\nMRKR Top_Res 1 2500\r\nDIPDEG 120 15\r\nMRKR \"Base Res\" 1 3000\r\nEND";

#[test]
fn a_deviated_depth_well_is_turned_z_up_and_its_feet_become_metres() {
    let w = import_well(DEVIATED.as_bytes(), "d2.wl", &opts()).unwrap();
    assert_eq!(w.head, [1000.0, 2000.0, 25.0]);
    assert_eq!(
        w.stations,
        vec![
            [1000.0, 2000.0, 25.0],
            [1000.0, 2000.0, -279.8],
            [1150.0, 2050.0, -520.0],
            [1400.0, 2120.0, -700.0]
        ]
    );
    let ft = 0.3048;
    assert_eq!(
        w.measured_depth,
        vec![0.0, 1000.0 * ft, 2000.0 * ft, 3000.0 * ft]
    );
    // 2500 ft lies half way between the stations at 2000 ft and 3000 ft.
    assert!((w.markers[0].md - 2500.0 * ft).abs() < 1e-9);
    assert!(close(w.markers[0].xyz, [1275.0, 2085.0, -610.0]));
    // A quoted name, and a marker at the last station.
    assert_eq!(w.markers[1].name, "Base Res");
    assert_eq!(w.markers[1].xyz, [1400.0, 2120.0, -700.0]);
}

#[test]
fn measured_depths_stay_as_written_when_the_target_is_their_unit() {
    let feet = ImportOptions {
        target_units: Some(Units::Foot),
        ..opts()
    };
    let w = import_well(DEVIATED.as_bytes(), "d2.wl", &feet).unwrap();
    assert_eq!(w.measured_depth, vec![0.0, 1000.0, 2000.0, 3000.0]);
    assert_eq!(w.markers[0].md, 2500.0);
}

#[test]
fn a_path_of_vrtx_stations_measures_its_depth_along_the_path() {
    let t = "GOCAD Well 1\nHEADER {name: V}\nWREF 0 0 10\nVRTX 0 0 10\nVRTX 1 0 0 -90\nVRTX 30 40 -90\nMRKR m 1 125\nEND\n";
    let w = import_well(t.as_bytes(), "v.wl", &opts()).unwrap();
    assert_eq!(w.name, "V");
    // `VRTX 1 0 0 -90`: four numbers, the first an id.
    assert_eq!(
        w.stations,
        vec![[0.0, 0.0, 10.0], [0.0, 0.0, -90.0], [30.0, 40.0, -90.0]]
    );
    assert_eq!(w.measured_depth, vec![0.0, 100.0, 150.0]);
    assert_eq!(w.markers[0].xyz, [15.0, 20.0, -90.0]);
}

#[test]
fn a_zpositive_in_the_body_of_a_well_counts_as_the_coordinate_systems() {
    let t = "GOCAD Well 1\nHEADER {\nname: old\n}\nZPOSITIVE Depth\nWREF 5 5 0\nPATH 0 0 0 0\nPATH 100 100 0 0\nEND\n";
    let w = import_well(t.as_bytes(), "old.wl", &opts()).unwrap();
    assert_eq!(w.stations[1], [5.0, 5.0, -100.0]);
    let clash = VERTICAL.replace("WREF", "ZPOSITIVE Depth\nWREF");
    let e = import_well(clash.as_bytes(), "w1.wl", &opts()).unwrap_err();
    assert_eq!(e.line, 13);
    assert!(
        e.message
            .contains("contradicts the coordinate system's ZPOSITIVE Elevation (line 9)"),
        "{e}"
    );
}

#[test]
fn a_log_block_in_braces_is_skipped_as_well() {
    let t = VERTICAL
        .replace("WELL_CURVE\n", "WELL_CURVE {\n")
        .replace("END_CURVE\n", "}\n");
    let w = import_well(t.as_bytes(), "w1.wl", &opts()).unwrap();
    assert_eq!(w.markers.len(), 2);
}

#[test]
fn a_log_block_left_open_ends_at_the_end_of_its_well() {
    let t = format!("{}{}", VERTICAL.replace("END_CURVE\n", ""), DEVIATED);
    let all = import_wells(t.as_bytes(), "two.wl", &opts()).unwrap();
    let names: Vec<&str> = all.iter().map(|w| w.name.as_str()).collect();
    assert_eq!(names, vec!["W1", "D-2"]);
}

fn group(members: &[&str]) -> String {
    format!(
        "GOCAD HomogeneousGroup 1\nHEADER {{\nname: field\n}}\nTYPE Well\nBEGIN_MEMBERS\n{}END_MEMBERS\nEND\n",
        members.concat()
    )
}

#[test]
fn a_well_group_yields_its_wells_in_order_and_one_by_name_or_position() {
    let deviated = format!("{DEVIATED}\r\n");
    let g = group(&[VERTICAL, &deviated]);
    let all: Vec<WellPath> = import_wells(g.as_bytes(), "field.gp", &opts()).unwrap();
    assert_eq!(all.len(), 2);
    let d = import_well(g.as_bytes(), "field.gp", &named("D-2")).unwrap();
    assert_eq!(d.stations.len(), 4);
    let first = ImportOptions {
        object: Some(ObjectRef::Position(1)),
        ..opts()
    };
    assert_eq!(
        import_well(g.as_bytes(), "field.gp", &first).unwrap().name,
        "W1"
    );
    let e = import_well(g.as_bytes(), "field.gp", &named("W9")).unwrap_err();
    assert_eq!(e.file, "field.gp");
    assert_eq!(
        e.message,
        "no object named 'W9'; Well objects here: #1 'W1' (line 7), #2 'D-2' (line 39)"
    );
    let e = import_well(g.as_bytes(), "field.gp", &opts()).unwrap_err();
    assert!(e.message.contains("the file holds 2 Well objects"), "{e}");
}

#[test]
fn a_decreasing_measured_depth_names_the_station_and_the_one_before() {
    let t = VERTICAL.replace("ZM_NPTS 2", "PATH 1500 -1400 0 0");
    let e = import_well(t.as_bytes(), "w1.wl", &opts()).unwrap_err();
    assert_eq!((e.file.as_str(), e.line), ("w1.wl", 18));
    assert!(
        e.message.starts_with(
            "this station's measured depth 1500 is less than the previous station's 1586.5 \
             (line 17)"
        ),
        "{e}"
    );
}

#[test]
fn a_marker_beyond_the_end_of_the_path_names_its_line_and_the_depths() {
    let t = VERTICAL.replace("MRKR Base_A 1 680", "MRKR Deep 1 1600");
    let e = import_well(t.as_bytes(), "w1.wl", &opts()).unwrap_err();
    assert_eq!(e.line, 22);
    assert!(
        e.message.starts_with(
            "marker 'Deep' at measured depth 1600 lies beyond the path, whose stations span \
             measured depths 0 to 1586.5 (lines 16 to 17)"
        ),
        "{e}"
    );
    // Feet as written, not the metres they become.
    let t = DEVIATED.replace("MRKR Top_Res 1 2500", "MRKR Top_Res 1 3100");
    let e = import_well(t.as_bytes(), "d2.wl", &opts()).unwrap_err();
    assert!(e.message.contains("depth 3100 lies beyond"), "{e}");
    assert!(
        e.message.contains("depths 0 to 3000 (lines 11 to 14)"),
        "{e}"
    );
}

#[test]
fn a_well_without_head_or_stations_is_refused_with_what_is_missing() {
    let t = VERTICAL.replace("WREF 377318.5 8372318.25 0\n", "");
    let e = import_well(t.as_bytes(), "w1.wl", &opts()).unwrap_err();
    assert_eq!(e.line, 1);
    assert!(
        e.message.starts_with("Well object 'W1' has no WREF record"),
        "{e}"
    );
    let t = VERTICAL
        .replace("PATH 0 94 0 0\n", "")
        .replace("PATH 1586.5 -1492.5 0 0\n", "");
    let e = import_well(t.as_bytes(), "w1.wl", &opts()).unwrap_err();
    assert!(e.message.contains("has no path station"), "{e}");
}

#[test]
fn survey_stations_tvd_paths_and_a_second_head_are_refused_at_their_line() {
    let cases = [
        ("PATH 0 94 0 0", "STATION 0 0 0", "STATION"),
        ("PATH 0 94 0 0", "TVD_PATH 0 94 0 0", "TVD_PATH is not read"),
        ("DATUM SeaLevel", "WREF 1 2 3", "a second WREF"),
        (
            "PATH 1586.5 -1492.5 0 0",
            "VRTX 377318.5 8372318.25 -1492.5",
            "a VRTX station in a path given by PATH records (from line 16)",
        ),
        (
            "PATH 0 94 0 0",
            "PATH 0 94 0",
            "PATH has 3 numbers where 4 are expected",
        ),
        ("MRKR Base_A 1 680", "MRKR Base_A 680", "MRKR needs a name"),
    ];
    for (from, to, says) in cases {
        let t = VERTICAL.replacen(from, to, 1);
        let e = import_well(t.as_bytes(), "w1.wl", &opts()).unwrap_err();
        let line = t.lines().position(|l| l == to).unwrap() + 1;
        assert_eq!(e.line, line, "{to}: {e}");
        assert!(e.message.contains(says), "{to}: {e}");
    }
}

#[test]
fn tvss_path_stations_read_as_path_stations() {
    let t = VERTICAL.replace("PATH ", "TVSS_PATH ");
    let a = import_well(t.as_bytes(), "w1.wl", &opts()).unwrap();
    let b = import_well(VERTICAL.as_bytes(), "w1.wl", &opts()).unwrap();
    assert_eq!(a, b);
}

const TRI: &str = "GOCAD TSurf 1\nHEADER {\nname: t\n}\nTFACE\nVRTX 1 0 0 0\nVRTX 2 1 0 0\nVRTX 3 0 1 0\nTRGL 1 2 3\nEND\n";

#[test]
fn a_broken_well_does_not_stop_the_surfaces_of_its_file_from_importing() {
    let t = format!(
        "{TRI}{}",
        VERTICAL.replace("PATH 0 94 0 0", "STATION 0 0 0")
    );
    let skip = ImportOptions {
        skip_other_types: true,
        ..opts()
    };
    assert!(import_surface(t.as_bytes(), "m.gp", &skip).is_ok());
    assert_eq!(parse_gocad(t.as_bytes(), "m.gp").unwrap().objects.len(), 2);
    assert_eq!(
        import_well(t.as_bytes(), "m.gp", &named("W1"))
            .unwrap_err()
            .line,
        26
    );
}

#[test]
fn a_well_value_beyond_any_position_on_earth_is_refused_at_its_line() {
    let t = VERTICAL.replace(
        "WREF 377318.5 8372318.25 0",
        "WREF 377318.5 8372318.25 1e200",
    );
    let line = t.lines().position(|l| l.starts_with("WREF")).unwrap() + 1;
    let e = import_well(t.as_bytes(), "w1.wl", &opts()).unwrap_err();
    assert_eq!(e.line, line, "{e}");
    assert!(e.message.contains("WREF"), "{e}");
    assert!(e.message.contains("no-data value"), "{e}");
}
