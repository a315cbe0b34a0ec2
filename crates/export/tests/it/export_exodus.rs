//! The Exodus II writer, checked byte for byte by the test-only netCDF reader (header layout,
//! dimensions, variables, attributes, data) and against the mesh it came from: blocks, side
//! numbering, side sets, fault sides, node sets; then read by netCDF4, meshio and VTK.

use test_support::export_support;
use test_support::netcdf_reader::{Nc, Val, text};

use export::{Format, export};
use export_support::*;
use geom::mesh::VolumeMesh;
use geom::predicates::{Orientation, orient3d};
use std::collections::BTreeSet;

/// The Exodus II manual's TETRA4 sides (1-based local nodes), written out independently of the
/// writer's table: side 1 = 1 2 4, side 2 = 2 3 4, side 3 = 1 4 3, side 4 = 1 3 2.
const SIDES: [[usize; 3]; 4] = [[1, 2, 4], [2, 3, 4], [1, 4, 3], [1, 3, 2]];

fn exo(mesh: &VolumeMesh) -> (Nc, Vec<u8>) {
    let mut files = export(mesh, "layered", Format::Exodus).unwrap();
    assert_eq!(files.len(), 1);
    let (name, bytes) = files.remove(0);
    assert_eq!(name, "layered.exo");
    (Nc::parse(&bytes).unwrap(), bytes)
}

/// Every element's nodes (1-based), in element-number order (blocks in order).
fn elements(nc: &Nc, bytes: &[u8]) -> Vec<[i32; 4]> {
    let blocks = nc.dim("num_el_blk").unwrap_or(0);
    (1..=blocks)
        .flat_map(|i| nc.ints(bytes, &format!("connect{i}")))
        .collect::<Vec<i32>>()
        .chunks(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

/// Side set `name`: its 1-based index among the side sets.
fn side_set(nc: &Nc, bytes: &[u8], name: &str) -> usize {
    let names = nc.strings(bytes, "ss_names");
    1 + names
        .iter()
        .position(|n| n == name)
        .unwrap_or_else(|| panic!("no side set {name} in {names:?}"))
}

/// The (element, side) pairs of side set `i`.
fn pairs(nc: &Nc, bytes: &[u8], i: usize) -> Vec<(i32, i32)> {
    let e = nc.ints(bytes, &format!("elem_ss{i}"));
    let s = nc.ints(bytes, &format!("side_ss{i}"));
    e.into_iter().zip(s).collect()
}

/// The sorted 0-based nodes of side `side` of element `elem`.
fn side_nodes(elems: &[[i32; 4]], elem: i32, side: i32) -> [u32; 3] {
    let e = elems[elem as usize - 1];
    let mut f = SIDES[side as usize - 1].map(|k| e[k - 1] as u32 - 1);
    f.sort_unstable();
    f
}

fn sorted(mut f: [u32; 3]) -> [u32; 3] {
    f.sort_unstable();
    f
}

/// What `script` prints about the `.exo` of `mesh`; `None` (with a note) when python3 lacks
/// `modules`.
fn read_with(mesh: &VolumeMesh, modules: &str, script: &str) -> Option<String> {
    if !python_has(modules) {
        return None;
    }
    let dir = tempfile::tempdir().unwrap();
    let files = export(mesh, "layered", Format::Exodus).unwrap();
    let paths = write_all(dir.path(), &files);
    Some(python(script, &[paths[0].to_str().unwrap()]))
}

fn triangles_of(mesh: &VolumeMesh, g: usize) -> Vec<[u32; 3]> {
    let tris = mesh.triangles.iter().zip(&mesh.triangle_group);
    tris.filter(|(_, x)| **x as usize == g)
        .map(|(t, _)| *t)
        .collect()
}

#[test]
fn the_file_is_a_64_bit_offset_netcdf_file_with_the_exodus_dimensions_and_attributes() {
    let mesh = layered_box(6, 6);
    let (nc, bytes) = exo(&mesh);
    assert_eq!((nc.version, nc.numrecs), (2, 1), "one time step");
    let dims = [
        ("num_dim", 3),
        ("num_nodes", mesh.nodes.len() as u32),
        ("num_elem", mesh.tets.len() as u32),
        ("num_el_blk", 3),
        ("num_side_sets", 9 + 2),
        ("num_node_sets", 9),
        ("len_name", 33),
        ("len_string", 33),
        ("len_line", 81),
        ("four", 4),
        ("time_step", 0),
        ("num_qa_rec", 1),
        ("num_info", 1),
        ("num_nod_per_el1", 4),
    ];
    for (name, len) in dims {
        assert_eq!(nc.dim(name), Some(len), "{name}");
    }
    let int = |n: &str| nc.attr(n).cloned();
    assert_eq!(int("floating_point_word_size"), Some(Val::Int(vec![8])));
    assert_eq!(int("file_size"), Some(Val::Int(vec![1])));
    assert_eq!(int("maximum_name_length"), Some(Val::Int(vec![32])));
    assert!(matches!(nc.attr("api_version"), Some(Val::Float(v)) if v[0] >= 8.0));
    assert_eq!(text(nc.attr("title")).as_deref(), Some("layered"));
    let time = nc.var("time_whole").unwrap();
    assert!(nc.is_record(time) && time.nc_type == 6);
    assert_eq!(nc.records(&bytes, "time_whole"), [0.0]);
    assert_eq!(nc.strings(&bytes, "info_records"), ["layered"]);
    let qa = nc.strings(&bytes, "qa_records");
    assert_eq!(qa[..2], ["georecipe", env!("CARGO_PKG_VERSION")]);
    assert_eq!(nc.strings(&bytes, "coor_names"), ["X", "Y", "Z"]);
}

#[test]
fn the_variables_lie_back_to_back_after_the_header_fixed_ones_first_then_the_record() {
    let (nc, bytes) = exo(&layered_box(4, 3));
    let mut at = nc.header_len as u64;
    for record in [false, true] {
        for v in nc.vars.iter().filter(|v| nc.is_record(v) == record) {
            assert_eq!(v.begin, at, "{}", v.name);
            let per_record: usize = nc.shape(v).iter().skip(record as usize).product();
            let size = per_record * [1, 1, 2, 4, 4, 8][v.nc_type as usize - 1];
            assert_eq!(v.vsize as usize, size.div_ceil(4) * 4, "{}", v.name);
            at += v.vsize as u64;
        }
    }
    assert_eq!(at as usize, bytes.len(), "one record ends the file");
}

#[test]
fn coordinates_and_connectivity_are_the_meshs_with_one_block_per_region_in_region_order() {
    let mesh = layered_box(6, 6);
    let (nc, bytes) = exo(&mesh);
    for (k, axis) in ["coordx", "coordy", "coordz"].into_iter().enumerate() {
        let want: Vec<f64> = mesh.nodes.iter().map(|p| p[k]).collect();
        assert_eq!(nc.doubles(&bytes, axis), want, "{axis}");
    }
    let names: Vec<&str> = mesh.regions.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(nc.strings(&bytes, "eb_names"), names);
    assert_eq!(nc.ints(&bytes, "eb_prop1"), [1, 2, 3]);
    assert_eq!(nc.ints(&bytes, "eb_status"), [1, 1, 1]);
    let connect = nc.var("connect2").unwrap();
    assert_eq!(
        text(
            connect
                .attrs
                .iter()
                .find(|a| a.0 == "elem_type")
                .map(|a| &a.1)
        )
        .as_deref(),
        Some("TETRA")
    );
    let mut want = Vec::new();
    for r in 0..3 {
        for (t, &tr) in mesh.tets.iter().zip(&mesh.tet_region) {
            if tr == r {
                want.push(t.map(|v| v as i32 + 1));
            }
        }
    }
    assert_eq!(elements(&nc, &bytes), want);
}

#[test]
fn materials_are_a_block_property_and_with_the_properties_element_variables_at_time_zero() {
    let mesh = layered_box(6, 6);
    let (nc, bytes) = exo(&mesh);
    let prop2 = nc.var("eb_prop2").unwrap();
    assert_eq!(
        prop2.attrs[0],
        ("name".to_string(), Val::Char(b"MATERIAL_ID".to_vec()))
    );
    assert_eq!(
        nc.ints(&bytes, "eb_prop2"),
        [3, 2, -1],
        "overburden has no material"
    );
    let names = nc.strings(&bytes, "name_elem_var");
    assert_eq!(names, ["MATERIAL_ID", "density", "porosity"]);
    assert_eq!(nc.ints(&bytes, "elem_var_tab"), [1; 9]);
    let n2 = nc.dim("num_el_in_blk2").unwrap() as usize;
    assert_eq!(nc.records(&bytes, "vals_elem_var1eb2"), vec![2.0; n2]);
    assert_eq!(nc.records(&bytes, "vals_elem_var3eb2"), vec![0.21; n2]);
    assert_eq!(nc.records(&bytes, "vals_elem_var1eb3")[0], -1.0);
    assert!(
        nc.records(&bytes, "vals_elem_var3eb1")[0].is_nan(),
        "no porosity below"
    );
}

#[test]
fn every_side_names_exactly_the_nodes_of_its_triangle_in_triangle_order() {
    let mesh = layered_box(6, 6);
    let (nc, bytes) = exo(&mesh);
    let elems = elements(&nc, &bytes);
    for (g, group) in mesh.surface_groups.iter().enumerate() {
        let i = side_set(&nc, &bytes, &group.name);
        let got = pairs(&nc, &bytes, i);
        let tris = triangles_of(&mesh, g);
        assert_eq!(
            got.len(),
            tris.len(),
            "{} names every triangle once",
            group.name
        );
        for ((e, s), t) in got.iter().zip(&tris) {
            assert_eq!(
                side_nodes(&elems, *e, *s),
                sorted(*t),
                "{} ({e}, {s})",
                group.name
            );
        }
    }
    let ids = nc.ints(&bytes, "ss_prop1");
    assert_eq!(
        ids,
        [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11],
        "group ids, then the fault's sides"
    );
}

#[test]
fn an_interior_face_is_named_from_the_tet_of_the_lower_region() {
    let mesh = layered_box(6, 6);
    let (nc, bytes) = exo(&mesh);
    let block_of = |e: i32| {
        let mut end = 0;
        (1..=3)
            .find(|b| {
                end += nc.dim(&format!("num_el_in_blk{b}")).unwrap() as i32;
                e <= end
            })
            .unwrap()
    };
    // "H2 base" separates regions 1 and 2, "H1 top" regions 2 and 3 (ids 1-based).
    for (name, block) in [("H2 base", 1), ("H1 top", 2)] {
        let i = side_set(&nc, &bytes, name);
        assert!(
            pairs(&nc, &bytes, i)
                .iter()
                .all(|(e, _)| block_of(*e) == block),
            "{name}"
        );
    }
}

#[test]
fn a_fault_has_a_front_and_a_back_side_set_with_the_tet_on_each_side() {
    let mesh = layered_box(6, 6);
    let (nc, bytes) = exo(&mesh);
    let elems = elements(&nc, &bytes);
    let tris = triangles_of(&mesh, 8);
    let front = pairs(&nc, &bytes, side_set(&nc, &bytes, "F2_dangling:front"));
    let back = pairs(&nc, &bytes, side_set(&nc, &bytes, "F2_dangling:back"));
    assert_eq!((front.len(), back.len()), (tris.len(), tris.len()));
    let p = |v: u32| &mesh.nodes[v as usize];
    for ((f, b), t) in front.iter().zip(&back).zip(&tris) {
        assert_ne!(f.0, b.0, "two different tets");
        for ((e, s), want) in [(f, Orientation::Positive), (b, Orientation::Negative)] {
            assert_eq!(side_nodes(&elems, *e, *s), sorted(*t));
            let apex = elems[*e as usize - 1]
                .iter()
                .map(|&v| v as u32 - 1)
                .find(|v| !t.contains(v))
                .unwrap();
            assert_eq!(orient3d(p(t[0]), p(t[1]), p(t[2]), p(apex)), want);
        }
    }
}

#[test]
fn every_group_has_a_node_set_of_its_triangle_nodes() {
    let mesh = layered_box(6, 6);
    let (nc, bytes) = exo(&mesh);
    let names = nc.strings(&bytes, "ns_names");
    let groups: Vec<&str> = mesh
        .surface_groups
        .iter()
        .map(|g| g.name.as_str())
        .collect();
    assert_eq!(names, groups);
    assert_eq!(nc.ints(&bytes, "ns_prop1"), (1..=9).collect::<Vec<i32>>());
    for (g, name) in groups.iter().enumerate() {
        let want: BTreeSet<i32> = triangles_of(&mesh, g)
            .iter()
            .flatten()
            .map(|&v| v as i32 + 1)
            .collect();
        let got = nc.ints(&bytes, &format!("node_ns{}", g + 1));
        assert_eq!(got, want.into_iter().collect::<Vec<_>>(), "{name}");
    }
}

#[test]
fn empty_regions_and_groups_get_no_block_or_set_and_the_others_keep_their_ids() {
    let mut mesh = layered_box(4, 3);
    mesh.regions.insert(
        0,
        geom::mesh::RegionGroup {
            name: "empty".into(),
            material: None,
            properties: Default::default(),
        },
    );
    mesh.tet_region.iter_mut().for_each(|r| *r += 1);
    mesh.surface_groups.push(geom::mesh::SurfaceGroup {
        name: "unused".into(),
        kind: geom::mesh::SurfaceKind::Fault,
    });
    let (nc, bytes) = exo(&mesh);
    assert_eq!(nc.ints(&bytes, "eb_prop1"), [2, 3, 4]);
    assert!(
        !nc.strings(&bytes, "ss_names")
            .contains(&"unused".to_string())
    );
    assert_eq!(nc.dim("num_node_sets"), Some(9));
}

#[test]
fn an_empty_mesh_is_a_valid_file_with_no_nodes_blocks_or_sets() {
    let bytes = export(&VolumeMesh::default(), "empty", Format::Exodus)
        .unwrap()
        .remove(0)
        .1;
    let nc = Nc::parse(&bytes).unwrap();
    for d in [
        "num_nodes",
        "num_elem",
        "num_el_blk",
        "num_side_sets",
        "num_node_sets",
    ] {
        assert_eq!(nc.dim(d), None, "{d}");
    }
    assert_eq!(nc.dim("num_dim"), Some(3));
    assert_eq!(nc.numrecs, 0, "no blocks, no time step");
}

#[test]
fn a_triangle_that_is_no_tet_face_is_refused_naming_its_group() {
    let mut mesh = layered_box(4, 3);
    let i = mesh.triangle_group.iter().position(|&g| g == 8).unwrap();
    mesh.triangles[i][2] = 0;
    let err = export(&mesh, "m", Format::Exodus).unwrap_err();
    assert!(
        err.contains("'F2_dangling'") && err.contains("not a face of any tet"),
        "{err}"
    );
}

#[test]
fn long_names_widen_len_name_and_the_bytes_do_not_change_between_writes() {
    let mut mesh = layered_box(4, 3);
    mesh.regions[0].name = "r".repeat(40);
    let (nc, bytes) = exo(&mesh);
    assert_eq!(nc.dim("len_name"), Some(41));
    assert_eq!(nc.strings(&bytes, "eb_names")[0], "r".repeat(40));
    assert_eq!(exo(&mesh).1, bytes);
}

const READERS: &str = r#"
import sys, netCDF4, meshio
ds = netCDF4.Dataset(sys.argv[1])
print("NC", ds.data_model, len(ds.dimensions["num_nodes"]), len(ds.dimensions["num_elem"]),
      len(ds.dimensions["num_side_sets"]))
print("EB", ";".join(netCDF4.chartostring(ds["eb_names"][:]).tolist()))
m = meshio.read(sys.argv[1], file_format="exodus")
print("MESHIO", len(m.points), sum(len(b.data) for b in m.cells), ";".join(sorted(m.point_sets)))
print("TYPES", ";".join(sorted(set(b.type for b in m.cells))), ";".join(sorted(m.cell_data)))
print("MATERIALS", ";".join(str(int(d[0])) for d in m.cell_data["MATERIAL_ID"]))
"#;

#[test]
fn netcdf4_and_meshio_read_the_file_with_its_counts_blocks_and_node_sets() {
    let mesh = layered_box(6, 6);
    let Some(out) = read_with(&mesh, "netCDF4, meshio", READERS) else {
        return;
    };
    let (nn, nt) = (mesh.nodes.len(), mesh.tets.len());
    assert!(
        out.contains(&format!("NC NETCDF3_64BIT_OFFSET {nn} {nt} 11\n")),
        "{out}"
    );
    assert!(
        out.contains("EB underburden;reservoir;overburden\n"),
        "{out}"
    );
    let mut sets: Vec<&str> = mesh
        .surface_groups
        .iter()
        .map(|g| g.name.as_str())
        .collect();
    sets.sort();
    assert!(
        out.contains(&format!("MESHIO {nn} {nt} {}\n", sets.join(";"))),
        "{out}"
    );
    assert!(
        out.contains("TYPES tetra MATERIAL_ID;density;porosity\n"),
        "{out}"
    );
    assert!(out.contains("MATERIALS 3;2;-1\n"), "{out}");
}

const VTK: &str = r#"
import sys, pyvista
r = pyvista.get_reader(sys.argv[1])
r.enable_all_cell_arrays()
m = r.read()
blocks = m["Element Blocks"]
print("BLOCKS", ";".join(blocks.keys()), sum(b.n_cells for b in blocks))
print("ARRAYS", ";".join(sorted(blocks[0].cell_data.keys())))
sides = m["Side Sets"]
for k in sides.keys():
    print("SIDE", k, sides[k].n_cells)
"#;

#[test]
fn vtk_reads_the_blocks_by_region_name_with_their_fields_and_every_side_set() {
    let mesh = layered_box(6, 6);
    let Some(out) = read_with(&mesh, "pyvista", VTK) else {
        return;
    };
    let nt = mesh.tets.len();
    assert!(
        out.contains(&format!("BLOCKS underburden;reservoir;overburden {nt}\n")),
        "{out}"
    );
    assert!(
        out.contains("ARRAYS MATERIAL_ID;ObjectId;density;porosity\n"),
        "{out}"
    );
    let fault = triangles_of(&mesh, 8).len();
    let mut want: Vec<String> = (0..mesh.surface_groups.len())
        .map(|g| {
            format!(
                "SIDE {} {}",
                mesh.surface_groups[g].name,
                triangles_of(&mesh, g).len()
            )
        })
        .collect();
    want.push(format!("SIDE F2_dangling:front {fault}"));
    want.push(format!("SIDE F2_dangling:back {fault}"));
    let got: Vec<&str> = out.lines().filter(|l| l.starts_with("SIDE ")).collect();
    assert_eq!(got, want);
}
