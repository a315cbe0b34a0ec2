//! The shipped example written as Exodus II (`formats = ["msh", "exo"]`, the alias) and read by
//! the ecosystem's readers: netCDF4 (the raw dimensions and names), meshio (points, cells, node
//! sets, cell data) and VTK through PyVista (blocks by region name, fields, side sets), each
//! checked against the msh of the same build. A reader that is absent skips with a note.

use crate::common_cli;
use common_cli::*;
use geom::mesh::VolumeMesh;
use geom::mesh::read::read_volume_msh;
use test_support::export_support::{python, python_has};

/// A build of the example in msh and Exodus, with porosity on `reservoir_E`; the msh read back.
fn built() -> (Scratch, VolumeMesh) {
    let s = Scratch::didactic_built();
    s.edit(
        "formats = [\"msh\", \"vtu\"]",
        "formats = [\"msh\", \"exo\"]",
    );
    s.edit(
        "-1264.9], material = 2 }",
        "-1264.9], material = 2, properties = { porosity = 0.21 } }",
    );
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    let bytes = std::fs::read(s.path("out/didactic/didactic.msh")).expect("the msh is written");
    let mesh = read_volume_msh(&bytes, "didactic.msh").expect("reads");
    (s, mesh)
}

/// The mesh of [`built`] and what `script` prints about its `.exo`; `None` (with a note) when
/// python3 lacks `modules`.
fn read_with(modules: &str, script: &str) -> Option<(VolumeMesh, String)> {
    if !python_has(modules) {
        return None;
    }
    let (s, mesh) = built();
    let exo = s.path("out/didactic/didactic.exo").display().to_string();
    Some((mesh, python(script, &[&exo])))
}

/// `(name, triangles)` per surface group, then the faults' front and back side sets.
fn side_sets(mesh: &VolumeMesh) -> Vec<(String, usize)> {
    let count = |g: usize| {
        mesh.triangle_group
            .iter()
            .filter(|&&x| x as usize == g)
            .count()
    };
    let groups = mesh.surface_groups.iter().enumerate();
    let mut sets: Vec<(String, usize)> = groups
        .clone()
        .map(|(g, s)| (s.name.clone(), count(g)))
        .collect();
    for (g, s) in groups.filter(|(_, s)| s.kind == geom::mesh::SurfaceKind::Fault) {
        sets.push((format!("{}:front", s.name), count(g)));
        sets.push((format!("{}:back", s.name), count(g)));
    }
    sets
}

const NETCDF4: &str = r#"
import sys, netCDF4
ds = netCDF4.Dataset(sys.argv[1])
print("FORMAT", ds.data_model)
for d in ["num_nodes", "num_elem", "num_el_blk", "num_side_sets", "num_node_sets"]:
    print("DIM", d, len(ds.dimensions[d]))
for v in ["eb_names", "ss_names", "ns_names"]:
    print("NAMES", v, ";".join(netCDF4.chartostring(ds[v][:]).tolist()))
print("MATERIALS", ";".join(str(x) for x in ds["eb_prop2"][:]))
"#;

#[test]
fn netcdf4_reads_the_example_exodus_with_the_meshs_counts_and_names() {
    let Some((mesh, out)) = read_with("netCDF4", NETCDF4) else {
        return;
    };
    let sets = side_sets(&mesh);
    let groups: Vec<&str> = mesh
        .surface_groups
        .iter()
        .map(|g| g.name.as_str())
        .collect();
    let regions: Vec<&str> = mesh.regions.iter().map(|r| r.name.as_str()).collect();
    let set_names: Vec<&str> = sets.iter().map(|(n, _)| n.as_str()).collect();
    for want in [
        "FORMAT NETCDF3_64BIT_OFFSET".to_string(),
        format!("DIM num_nodes {}", mesh.nodes.len()),
        format!("DIM num_elem {}", mesh.tets.len()),
        format!("DIM num_el_blk {}", regions.len()),
        format!("DIM num_side_sets {}", sets.len()),
        format!("DIM num_node_sets {}", groups.len()),
        format!("NAMES eb_names {}", regions.join(";")),
        format!("NAMES ss_names {}", set_names.join(";")),
        format!("NAMES ns_names {}", groups.join(";")),
    ] {
        assert!(out.lines().any(|l| l == want), "{want} not in\n{out}");
    }
    let materials: Vec<String> = mesh
        .regions
        .iter()
        .map(|r| r.material.unwrap_or(-1).to_string())
        .collect();
    assert!(
        out.contains(&format!("MATERIALS {}\n", materials.join(";"))),
        "{out}"
    );
}

const MESHIO: &str = r#"
import sys, meshio
m = meshio.read(sys.argv[1], file_format="exodus")
print("COUNTS", len(m.points), ";".join(f"{b.type}:{len(b.data)}" for b in m.cells))
print("NODESETS", ";".join(f"{k}:{len(v)}" for k, v in m.point_sets.items()))
print("POROSITY", ";".join(str(d[0]) for d in m.cell_data["porosity"]))
"#;

#[test]
fn meshio_reads_the_example_exodus_with_its_blocks_node_sets_and_properties() {
    let Some((mesh, out)) = read_with("netCDF4, meshio", MESHIO) else {
        return;
    };
    let blocks: Vec<String> = (0..mesh.regions.len() as u32)
        .map(|r| {
            format!(
                "tetra:{}",
                mesh.tet_region.iter().filter(|&&x| x == r).count()
            )
        })
        .collect();
    let counts = format!("COUNTS {} {}\n", mesh.nodes.len(), blocks.join(";"));
    assert!(out.contains(&counts), "{counts} not in\n{out}");
    let node_sets: Vec<String> = (0..mesh.surface_groups.len())
        .map(|g| {
            let mut nodes: Vec<u32> = mesh
                .triangles
                .iter()
                .zip(&mesh.triangle_group)
                .filter(|(_, x)| **x as usize == g)
                .flat_map(|(t, _)| *t)
                .collect();
            nodes.sort_unstable();
            nodes.dedup();
            format!("{}:{}", mesh.surface_groups[g].name, nodes.len())
        })
        .collect();
    assert!(
        out.contains(&format!("NODESETS {}\n", node_sets.join(";"))),
        "{out}"
    );
    let porosity: Vec<&str> = mesh
        .regions
        .iter()
        .map(|r| {
            if r.name == "reservoir_E" {
                "0.21"
            } else {
                "nan"
            }
        })
        .collect();
    assert!(
        out.contains(&format!("POROSITY {}\n", porosity.join(";"))),
        "{out}"
    );
}

const PYVISTA: &str = r#"
import sys, pyvista
r = pyvista.get_reader(sys.argv[1])
r.enable_all_cell_arrays()
r.node_sets.enable_all()
m = r.read()
for k in m["Element Blocks"].keys():
    b = m["Element Blocks"][k]
    print("BLOCK", k, b.n_cells, int(b.cell_data["MATERIAL_ID"][0]))
for k in m["Side Sets"].keys():
    print("SIDE", k, m["Side Sets"][k].n_cells)
for k in m["Node Sets"].keys():
    print("NODES", k, m["Node Sets"][k].n_points)
"#;

#[test]
fn vtk_reads_the_example_exodus_with_a_block_per_region_and_every_side_set() {
    let Some((mesh, out)) = read_with("pyvista", PYVISTA) else {
        return;
    };
    let blocks: Vec<String> = mesh
        .regions
        .iter()
        .enumerate()
        .map(|(r, g)| {
            let n = mesh.tet_region.iter().filter(|&&x| x as usize == r).count();
            format!("BLOCK {} {n} {}", g.name, g.material.unwrap_or(-1))
        })
        .collect();
    let got: Vec<&str> = out.lines().filter(|l| l.starts_with("BLOCK ")).collect();
    assert_eq!(got, blocks);
    let sides: Vec<String> = side_sets(&mesh)
        .iter()
        .map(|(n, c)| format!("SIDE {n} {c}"))
        .collect();
    let got: Vec<&str> = out.lines().filter(|l| l.starts_with("SIDE ")).collect();
    assert_eq!(got, sides);
    let node_sets = out.lines().filter(|l| l.starts_with("NODES ")).count();
    assert_eq!(node_sets, mesh.surface_groups.len(), "{out}");
}

const RECORDS: &str = r#"
import sys, netCDF4
ds = netCDF4.Dataset(sys.argv[1])
for rec in ds["qa_records"][:]:
    print("QA", ";".join(netCDF4.chartostring(rec).tolist()))
for line in netCDF4.chartostring(ds["info_records"][:]).tolist():
    print("INFO", line)
"#;

/// The `[nodes.export]` key of the lock file beside `s`'s recipe.
fn locked_export_key(s: &Scratch) -> String {
    let lock = std::fs::read_to_string(s.path("didactic.toml.lock")).expect("the lock is written");
    let after = lock
        .split("[nodes.export]\nkey = \"")
        .nth(1)
        .expect("an export node");
    after[..64].to_string()
}

#[test]
fn the_exodus_qa_and_info_records_name_the_recipe_and_the_lock_files_export_key() {
    if !python_has("netCDF4") {
        return;
    }
    let (s, _) = built();
    let exo = s.path("out/didactic/didactic.exo").display().to_string();
    let out = python(RECORDS, &[&exo]);
    let key = locked_export_key(&s);
    for want in [
        format!("QA georecipe;{};;", env!("CARGO_PKG_VERSION")),
        format!("QA didactic.toml;{};;", &key[..32]),
        "INFO didactic".to_string(),
        "INFO recipe didactic.toml".to_string(),
        format!("INFO key {key}"),
    ] {
        assert!(out.lines().any(|l| l == want), "{want} not in\n{out}");
    }
}
