//! The wells (line groups) in every format, read back by the real readers where there are some
//! (meshio, VTK through PyVista, netCDF4; a reader that is absent skips with a note) and parsed
//! here where there are none (TetGen's `.edge`, the element numbers of the Abaqus file).

use test_support::export_support;
use test_support::netcdf_reader::{Nc, text};

use export::{Format, export, file_names};
use export_support::*;
use geom::mesh::{LineGroup, VolumeMesh};
use std::collections::BTreeSet;

/// `layered_box(4, 6)` with two wells along tet edges: "W1", vertical through the whole box at
/// grid column (2, 2), and "W2 deviated", down the cube diagonals from (1, 1, 1) to (3, 3, 3)
/// and one step down.
pub(crate) fn with_wells() -> VolumeMesh {
    let mut mesh = layered_box(4, 6);
    let id = |i: u32, j: u32, k: u32| i + 5 * (j + 5 * k);
    let chain = |nodes: &[u32]| nodes.windows(2).map(|w| [w[0], w[1]]).collect();
    mesh.lines = vec![
        LineGroup {
            area: None,
            name: "W1".into(),
            lines: chain(&(0..=6).rev().map(|k| id(2, 2, k)).collect::<Vec<_>>()),
        },
        LineGroup {
            area: None,
            name: "W2 deviated".into(),
            lines: chain(&[id(3, 3, 3), id(2, 2, 2), id(1, 1, 1), id(1, 1, 0)]),
        },
    ];
    // Every segment is an edge of a tet, as a meshed well's are.
    let edges: BTreeSet<[u32; 2]> = (mesh.tets.iter())
        .flat_map(|t| {
            let t = *t;
            (0..4).flat_map(move |a| (a + 1..4).map(move |b| sorted2([t[a], t[b]])))
        })
        .collect();
    for l in mesh.lines.iter().flat_map(|g| &g.lines) {
        assert!(edges.contains(&sorted2(*l)), "{l:?} is no tet edge");
    }
    mesh
}

fn sorted2([a, b]: [u32; 2]) -> [u32; 2] {
    [a.min(b), a.max(b)]
}

/// The line counts of the wells, in group order (6 and 3).
fn counts(mesh: &VolumeMesh) -> Vec<usize> {
    mesh.lines.iter().map(|g| g.lines.len()).collect()
}

/// Writes `format`'s files of `mesh` into a new directory; returns it and the paths.
fn written(mesh: &VolumeMesh, format: Format) -> (tempfile::TempDir, Vec<std::path::PathBuf>) {
    let dir = tempfile::tempdir().unwrap();
    let paths = write_all(dir.path(), &export(mesh, "wells", format).unwrap());
    (dir, paths)
}

#[test]
fn the_test_wells_have_six_and_three_segments() {
    assert_eq!(counts(&with_wells()), [6, 3]);
}

/// Per cell block of the VTU (meshio): its type, count and the set of each array's values.
const MESHIO_VTU: &str = r#"
import sys, meshio, numpy as np
m = meshio.read(sys.argv[1])
for i, b in enumerate(m.cells):
    vals = lambda k: ",".join(sorted(set(str(x) for x in m.cell_data[k][i].tolist())))
    print("BLOCK", b.type, len(b.data), *(k + "=" + vals(k) for k in
          ("MaterialIDs", "region", "surface", "density", "well")))
    if b.type == "line":
        for w in sorted(set(m.cell_data["well"][i].tolist())):
            print("WELL", w, int((m.cell_data["well"][i] == w).sum()))
for k, v in sorted(m.field_data.items()):
    if k.startswith("well:"):
        print("FIELD", k, int(v[0]))
"#;

#[test]
fn meshio_reads_each_wells_line_cells_by_id_and_name_from_both_vtu_encodings() {
    if !python_has("meshio") {
        return;
    }
    let mesh = with_wells();
    for format in [Format::Vtu, Format::VtuBinary] {
        let (_dir, paths) = written(&mesh, format);
        let out = python(MESHIO_VTU, &[paths[0].to_str().unwrap()]);
        let got: Vec<&str> = out.lines().collect();
        let (nt, nf) = (mesh.tets.len(), mesh.triangles.len());
        let want = [
            format!(
                "BLOCK tetra {nt} MaterialIDs=-1,2,3 region=1,2,3 surface=-1 \
                 density=2200.0,2300.0,2600.0 well=-1"
            ),
            format!(
                "BLOCK triangle {nf} MaterialIDs=-1 region=-1 surface=1,2,3,4,5,6,7,8,9 \
                 density=nan well=-1"
            ),
            "BLOCK line 9 MaterialIDs=-1 region=-1 surface=-1 density=nan well=1,2".to_string(),
            "WELL 1 6".to_string(),
            "WELL 2 3".to_string(),
            // The fault's sides, after the lines.
            "BLOCK triangle 12 MaterialIDs=-1 region=-1 surface=-1 density=nan well=-1".into(),
            "FIELD well:W1 1".to_string(),
            "FIELD well:W2 deviated 2".to_string(),
        ];
        assert_eq!(got, want, "{format:?}");
    }
}

/// What VTK reads from the VTU: line cells (type 3) per `well` id, and the `well:` names.
const PYVISTA_VTU: &str = r#"
import sys, pyvista, numpy as np
m = pyvista.read(sys.argv[1])
well = m.cell_data["well"]
print("TYPE", well.dtype)
lines = m.celltypes == 3
print("NONLINE", ",".join(str(x) for x in sorted(set(well[~lines].tolist()))))
for w in sorted(set(well[lines].tolist())):
    print("WELL", w, int((well[lines] == w).sum()))
print("NAMES", ";".join(f"{k}={int(m.field_data[k][0])}" for k in sorted(m.field_data.keys())
                        if k.startswith("well:")))
"#;

#[test]
fn vtk_reads_each_wells_line_cells_by_id_and_name_from_the_vtu() {
    if !python_has("pyvista") {
        return;
    }
    let mesh = with_wells();
    for format in [Format::Vtu, Format::VtuBinary] {
        let (_dir, paths) = written(&mesh, format);
        let out = python(PYVISTA_VTU, &[paths[0].to_str().unwrap()]);
        let want =
            "TYPE int32\nNONLINE -1\nWELL 1 6\nWELL 2 3\nNAMES well:W1=1;well:W2 deviated=2\n";
        assert_eq!(out, want, "{format:?}");
    }
}

#[test]
fn the_vtu_of_a_mesh_without_wells_has_no_well_array() {
    let text = |m: &VolumeMesh| String::from_utf8(export(m, "m", Format::Vtu).unwrap().remove(0).1);
    let plain = text(&layered_box(4, 6)).unwrap();
    assert!(!plain.contains("well"), "no well array or name");
    let wells = text(&with_wells()).unwrap();
    assert!(wells.contains("<DataArray type=\"Int32\" Name=\"well\" format=\"ascii\">"));
}

#[test]
fn exodus_wells_are_bar2_blocks_after_the_regions_numbered_after_the_tets_with_node_sets() {
    let mesh = with_wells();
    let bytes = export(&mesh, "wells", Format::Exodus).unwrap().remove(0).1;
    let nc = Nc::parse(&bytes).unwrap();
    let nt = mesh.tets.len() as u32;
    assert_eq!(nc.dim("num_elem"), Some(nt + 9));
    assert_eq!(nc.dim("num_el_blk"), Some(5));
    let names = nc.strings(&bytes, "eb_names");
    assert_eq!(
        names,
        [
            "underburden",
            "reservoir",
            "overburden",
            "W1",
            "W2 deviated"
        ]
    );
    assert_eq!(nc.ints(&bytes, "eb_prop1"), [1, 2, 3, 4, 5]);
    assert_eq!(nc.ints(&bytes, "eb_prop2"), [3, 2, -1, -1, -1]);
    for (b, group) in [(4, &mesh.lines[0]), (5, &mesh.lines[1])] {
        let connect = nc.var(&format!("connect{b}")).unwrap();
        let elem_type = connect.attrs.iter().find(|a| a.0 == "elem_type");
        assert_eq!(text(elem_type.map(|a| &a.1)).as_deref(), Some("BAR2"));
        assert_eq!(nc.dim(&format!("num_nod_per_el{b}")), Some(2));
        let want: Vec<i32> = group
            .lines
            .iter()
            .flatten()
            .map(|&v| v as i32 + 1)
            .collect();
        assert_eq!(
            nc.ints(&bytes, &format!("connect{b}")),
            want,
            "{}",
            group.name
        );
        // Every element variable is on every block: -1 and NaN on a well.
        assert_eq!(
            nc.records(&bytes, &format!("vals_elem_var1eb{b}")),
            vec![-1.0; group.lines.len()]
        );
        assert!(nc.records(&bytes, &format!("vals_elem_var2eb{b}"))[0].is_nan());
    }
    assert_eq!(nc.ints(&bytes, "elem_var_tab"), [1; 15]);
    // Node sets: the nine surface groups', then the wells' (ids 10 and 11).
    let ns = nc.strings(&bytes, "ns_names");
    assert_eq!(ns[9..], ["W1", "W2 deviated"]);
    assert_eq!(nc.ints(&bytes, "ns_prop1"), (1..=11).collect::<Vec<i32>>());
    for (i, group) in [(10, &mesh.lines[0]), (11, &mesh.lines[1])] {
        let want: BTreeSet<i32> = group
            .lines
            .iter()
            .flatten()
            .map(|&v| v as i32 + 1)
            .collect();
        let got = nc.ints(&bytes, &format!("node_ns{i}"));
        assert_eq!(got, want.into_iter().collect::<Vec<_>>(), "{}", group.name);
    }
}

const EXODUS_READERS: &str = r#"
import sys, netCDF4, meshio, numpy as np
ds = netCDF4.Dataset(sys.argv[1])
print("NC", len(ds.dimensions["num_elem"]), ";".join(netCDF4.chartostring(ds["eb_names"][:]).tolist()))
m = meshio.read(sys.argv[1], file_format="exodus")
for i, b in enumerate(m.cells):
    mat = ",".join(str(int(x)) for x in sorted(set(m.cell_data["MATERIAL_ID"][i].tolist())))
    print("BLOCK", b.type, len(b.data), mat)
for k in sorted(m.point_sets):
    if k.startswith("W"):
        print("SET", k, len(m.point_sets[k]))
"#;

#[test]
fn netcdf4_and_meshio_read_the_exodus_wells_as_line_blocks_with_named_node_sets() {
    if !python_has("netCDF4, meshio") {
        return;
    }
    let mesh = with_wells();
    let (_dir, paths) = written(&mesh, Format::Exodus);
    let out = python(EXODUS_READERS, &[paths[0].to_str().unwrap()]);
    let tets = |r: u32| mesh.tet_region.iter().filter(|&&x| x == r).count();
    let want = [
        format!(
            "NC {} underburden;reservoir;overburden;W1;W2 deviated",
            mesh.tets.len() + 9
        ),
        format!("BLOCK tetra {} 3", tets(0)),
        format!("BLOCK tetra {} 2", tets(1)),
        format!("BLOCK tetra {} -1", tets(2)),
        "BLOCK line 6 -1".to_string(),
        "BLOCK line 3 -1".to_string(),
        "SET W1 7".to_string(),
        "SET W2 deviated 4".to_string(),
    ];
    assert_eq!(out.lines().collect::<Vec<_>>(), want, "{out}");
}

const EXODUS_VTK: &str = r#"
import sys, pyvista
r = pyvista.get_reader(sys.argv[1])
r.enable_all_cell_arrays()
r.node_sets.enable_all()
m = r.read()
blocks = m["Element Blocks"]
for k in blocks.keys():
    b = blocks[k]
    print("BLOCK", k, b.n_cells, ",".join(str(t) for t in sorted(set(b.celltypes.tolist()))))
sets = m["Node Sets"]
for k in sets.keys():
    if k.startswith("W"):
        print("SET", k, sets[k].n_points)
"#;

#[test]
fn vtk_reads_the_exodus_wells_as_blocks_of_line_cells_and_node_sets_by_name() {
    if !python_has("pyvista") {
        return;
    }
    let mesh = with_wells();
    let (_dir, paths) = written(&mesh, Format::Exodus);
    let out = python(EXODUS_VTK, &[paths[0].to_str().unwrap()]);
    let tets = |r: u32| mesh.tet_region.iter().filter(|&&x| x == r).count();
    let want = [
        format!("BLOCK underburden {} 10", tets(0)),
        format!("BLOCK reservoir {} 10", tets(1)),
        format!("BLOCK overburden {} 10", tets(2)),
        "BLOCK W1 6 3".to_string(),
        "BLOCK W2 deviated 3 3".to_string(),
        "SET W1 7".to_string(),
        "SET W2 deviated 4".to_string(),
    ];
    assert_eq!(out.lines().collect::<Vec<_>>(), want, "{out}");
}

const MESHIO_MEDIT: &str = r#"
import sys, meshio, numpy as np
m = meshio.read(sys.argv[1])
for i, b in enumerate(m.cells):
    if b.type == "line":
        ref = m.cell_data["medit:ref"][i]
        for w in sorted(set(ref.tolist())):
            print("WELL", w, int((ref == w).sum()))
print("TYPES", ";".join(b.type for b in m.cells))
"#;

#[test]
fn meshio_reads_the_medit_edges_with_each_wells_reference() {
    if !python_has("meshio") {
        return;
    }
    let (_dir, paths) = written(&with_wells(), Format::Medit);
    let out = python(MESHIO_MEDIT, &[paths[0].to_str().unwrap()]);
    assert_eq!(out, "WELL 1 6\nWELL 2 3\nTYPES line;triangle;tetra\n");
}

#[test]
fn tetgen_writes_an_edge_file_with_each_wells_marker_only_for_a_mesh_with_wells() {
    let mesh = with_wells();
    let files = export(&mesh, "m", Format::TetGen).unwrap();
    let names: Vec<&str> = files.iter().map(|f| f.0.as_str()).collect();
    assert_eq!(names, ["m.1.node", "m.1.ele", "m.1.face", "m.1.edge"]);
    assert_eq!(file_names("m", Format::TetGen, &mesh), names);
    let edge = String::from_utf8(files[3].1.clone()).unwrap();
    let mut rows = edge.lines().filter(|l| !l.starts_with('#'));
    assert_eq!(rows.next(), Some("9 1"), "nine edges with markers");
    let mut got: Vec<Vec<[u32; 2]>> = vec![Vec::new(); 2];
    for (k, row) in rows.enumerate() {
        let v: Vec<u32> = row.split_whitespace().map(|t| t.parse().unwrap()).collect();
        assert_eq!((v.len(), v[0] as usize), (4, k + 1), "{row}");
        got[v[3] as usize - 1].push([v[1] - 1, v[2] - 1]);
    }
    assert_eq!(got[0], mesh.lines[0].lines);
    assert_eq!(got[1], mesh.lines[1].lines);
    let plain = export(&layered_box(4, 6), "m", Format::TetGen).unwrap();
    assert_eq!(plain.len(), 3, "no .edge without wells");
}

const MESHIO_INP: &str = r#"
import sys, meshio
m = meshio.read(sys.argv[1])
print("TYPES", ";".join(f"{b.type}:{len(b.data)}" for b in m.cells))
for k in sorted(m.cell_sets):
    if k.startswith("W"):
        print("SET", k, sum(len(x) for x in m.cell_sets[k]))
"#;

#[test]
fn abaqus_wells_are_t3d2_element_sets_numbered_after_the_tets_and_read_by_meshio() {
    let mesh = with_wells();
    let (_dir, paths) = written(&mesh, Format::Inp);
    let text = std::fs::read_to_string(&paths[0]).unwrap();
    let block = |label: &str| {
        let head = format!("*Element, type=T3D2, elset={label}\n");
        let start = text.find(&head).unwrap() + head.len();
        let body = &text[start..];
        let end = body.find('*').unwrap_or(body.len());
        body[..end]
            .lines()
            .map(|l| {
                let v: Vec<u32> = l.split(", ").map(|t| t.parse().unwrap()).collect();
                (v[0], [v[1] - 1, v[2] - 1])
            })
            .collect::<Vec<_>>()
    };
    let nt = mesh.tets.len() as u32;
    let (w1, w2) = (block("W1"), block("W2_deviated"));
    let numbers: Vec<u32> = w1.iter().chain(&w2).map(|(n, _)| *n).collect();
    assert_eq!(numbers, (nt + 1..=nt + 9).collect::<Vec<_>>());
    let nodes = |b: &[(u32, [u32; 2])]| b.iter().map(|(_, l)| *l).collect::<Vec<_>>();
    assert_eq!(nodes(&w1), mesh.lines[0].lines);
    assert_eq!(nodes(&w2), mesh.lines[1].lines);
    assert!(
        text.contains("** well 2 \"W2 deviated\" elset=W2_deviated"),
        "{text}"
    );
    if !python_has("meshio") {
        return;
    }
    let out = python(MESHIO_INP, &[paths[0].to_str().unwrap()]);
    let tets = |r: u32| mesh.tet_region.iter().filter(|&&x| x == r).count();
    let want = format!(
        "TYPES tetra:{};tetra:{};tetra:{};line:6;line:3\nSET W1 6\nSET W2_deviated 3\n",
        tets(0),
        tets(1),
        tets(2)
    );
    assert_eq!(out, want);
}

#[test]
fn an_abaqus_well_with_an_area_gets_a_truss_section_and_one_without_is_told_to_add_one() {
    let mut mesh = with_wells();
    mesh.lines[0].area = Some(0.0314);
    let (_dir, paths) = written(&mesh, Format::Inp);
    let text = std::fs::read_to_string(&paths[0]).unwrap();
    assert!(
        text.contains(
            "*Material, name=WELL_W1\n*Solid Section, elset=W1, material=WELL_W1\n0.0314,\n"
        ),
        "{text}"
    );
    assert!(text.contains("** well 1 \"W1\" elset=W1 (T3D2, section area 0.0314)"));
    assert!(
        !text.contains("elset=W2_deviated, material"),
        "W2 has no area"
    );
    assert!(text.contains("\"W2 deviated\" elset=W2_deviated (T3D2 without a section"));
    // Every element set with elements has a section once each: the regions' and W1's.
    let sections = text.matches("*Solid Section").count();
    assert_eq!(sections, mesh.regions.len() + 1);
    if !python_has("meshio") {
        return;
    }
    let out = python(MESHIO_INP, &[paths[0].to_str().unwrap()]);
    assert!(out.contains("SET W1 6\n"), "{out}");
}

#[test]
fn a_mesh_with_wells_exports_in_every_format_with_the_same_bytes_every_time() {
    let (a, b) = (with_wells(), with_wells());
    for f in Format::EVERY {
        let files = export(&a, "d", f).unwrap();
        assert_eq!(files, export(&b, "d", f).unwrap(), "{f:?}");
        let names: Vec<String> = files.into_iter().map(|(n, _)| n).collect();
        assert_eq!(names, file_names("d", f, &a), "{f:?}");
    }
}

#[test]
fn a_well_group_without_lines_is_named_but_gets_no_elements() {
    let mut mesh = with_wells();
    mesh.lines.insert(
        0,
        LineGroup {
            area: None,
            name: "dry".into(),
            lines: vec![],
        },
    );
    let bytes = export(&mesh, "m", Format::Exodus).unwrap().remove(0).1;
    let nc = Nc::parse(&bytes).unwrap();
    // Its block and node set are left out (no zero-length dimension); the others keep their ids.
    assert_eq!(nc.ints(&bytes, "eb_prop1"), [1, 2, 3, 5, 6]);
    assert_eq!(nc.ints(&bytes, "ns_prop1")[9..], [11, 12]);
    let vtu = String::from_utf8(export(&mesh, "m", Format::Vtu).unwrap().remove(0).1).unwrap();
    assert!(vtu.contains("Name=\"well:dry\" NumberOfTuples=\"1\" format=\"ascii\">1<"));
    assert!(vtu.contains("Name=\"well:W1\" NumberOfTuples=\"1\" format=\"ascii\">2<"));
    let medit = String::from_utf8(export(&mesh, "m", Format::Medit).unwrap().remove(0).1).unwrap();
    let edges = medit.split_once("\nEdges\n9\n").unwrap().1;
    assert!(
        edges.lines().next().unwrap().ends_with(" 2"),
        "W1 is now well 2"
    );
}
