//! The recipe's `[groups]`: named boundary groups of patches, as the shipped example's build
//! writes them and the ecosystem's readers read them (gmsh, netCDF4 for Exodus, meshio for
//! Abaqus, PyVista/VTK for VTU), counted against the surface groups of the same build; the
//! errors a wrong group gets; and what an edit of a group re-runs.

use crate::common_cli;
use common_cli::*;
use geom::mesh::VolumeMesh;
use geom::mesh::read::read_volume_msh;
use std::collections::BTreeMap;
use test_support::export_support::{python, python_has};

/// The groups the tests add: one box side, both kept patches of H1 apart and together, and
/// two box sides by a glob.
const GROUPS: &str = "\n[groups]\nseafloor = \"box.zmax\"\nh1_west = \"H1#2\"\n\
h1_east = \"H1#4\"\nreservoir_top = [\"H1#2\", \"H1#4\"]\nsides = \"box.x*\"\n";

/// The example with [`GROUPS`], built in msh, VTU, Exodus and Abaqus; and its msh read back.
fn built() -> (Scratch, VolumeMesh) {
    let s = Scratch::didactic_built();
    s.edit(
        "formats = [\"msh\", \"vtu\"]",
        &format!("formats = [\"msh\", \"vtu\", \"exodus\", \"inp\"]\n{GROUPS}"),
    );
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    let bytes = std::fs::read(s.path("out/didactic/didactic.msh")).expect("the msh is written");
    (s, read_volume_msh(&bytes, "didactic.msh").expect("reads"))
}

/// Triangles per surface group of `mesh`, by name.
fn group_sizes(mesh: &VolumeMesh) -> BTreeMap<String, usize> {
    let mut out = BTreeMap::new();
    for &g in &mesh.triangle_group {
        *out.entry(mesh.surface_groups[g as usize].name.clone())
            .or_default() += 1;
    }
    out
}

/// `name count` lines printed by a reader script, as a map.
fn counts(printed: &str) -> BTreeMap<String, usize> {
    (printed.lines())
        .filter_map(|l| l.rsplit_once(' '))
        .map(|(name, n)| (name.to_string(), n.parse().expect("a count")))
        .collect()
}

/// Each group's count against the surface groups: the box sides', H1 split in two, H1 whole.
fn assert_counts(what: &str, got: &BTreeMap<String, usize>, groups: &BTreeMap<String, usize>) {
    let n = |k: &str| {
        got.get(k)
            .copied()
            .unwrap_or_else(|| panic!("{what}: no `{k}` in {got:?}"))
    };
    assert_eq!(n("seafloor"), groups["box.zmax"], "{what}");
    assert_eq!(
        n("sides"),
        groups["box.xmin"] + groups["box.xmax"],
        "{what}"
    );
    assert_eq!(n("reservoir_top"), groups["H1"], "{what}");
    assert_eq!(n("h1_west") + n("h1_east"), groups["H1"], "{what}");
    assert!(n("h1_west") > 0 && n("h1_east") > 0, "{what}: {got:?}");
}

const GMSH: &str = r#"
import sys, gmsh
gmsh.initialize(); gmsh.option.setNumber("General.Verbosity", 0)
gmsh.open(sys.argv[1])
for dim, tag in gmsh.model.getPhysicalGroups(2):
    n = 0
    for e in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
        for tags in gmsh.model.mesh.getElements(dim, e)[1]:
            n += len(tags)
    print(gmsh.model.getPhysicalName(dim, tag), n)
"#;

const NETCDF4: &str = r#"
import sys, netCDF4
ds = netCDF4.Dataset(sys.argv[1])
names = netCDF4.chartostring(ds["ss_names"][:]).tolist()
for i, name in enumerate(names):
    print(name, len(ds.dimensions["num_side_ss%d" % (i + 1)]))
nodes = netCDF4.chartostring(ds["ns_names"][:]).tolist()
for i, name in enumerate(nodes):
    print("nodes:" + name, len(ds.dimensions["num_nod_ns%d" % (i + 1)]))
"#;

const MESHIO_INP: &str = r#"
import sys, meshio
m = meshio.read(sys.argv[1])
for name, nodes in m.point_sets.items():
    print("nodes:" + name, len(nodes))
"#;

const PYVISTA: &str = r#"
import sys, pyvista
m = pyvista.read(sys.argv[1])
for name in m.cell_data.keys():
    if name.startswith("group:"):
        a = m.cell_data[name]
        ids = sorted(set(int(x) for x in a if x >= 0))
        assert ids == [int(m.field_data[name][0])], (name, ids)
        print(name[len("group:"):], int((a >= 0).sum()))
"#;

#[test]
fn groups_reach_msh_exodus_and_vtu_with_their_patches_triangles_as_real_readers_count_them() {
    if !python_has("gmsh, netCDF4, pyvista") {
        return;
    }
    let (s, mesh) = built();
    let groups = group_sizes(&mesh);
    let file = |ext: &str| {
        s.path(&format!("out/didactic/didactic.{ext}"))
            .display()
            .to_string()
    };
    assert_counts("gmsh", &counts(&python(GMSH, &[&file("msh")])), &groups);
    let exodus = counts(&python(NETCDF4, &[&file("exo")]));
    assert_counts("Exodus side sets", &exodus, &groups);
    // A group's node set holds exactly the nodes of the surface groups it gathers.
    assert_eq!(exodus["nodes:seafloor"], exodus["nodes:box.zmax"]);
    assert_eq!(exodus["nodes:reservoir_top"], exodus["nodes:H1"]);
    assert_counts("VTU", &counts(&python(PYVISTA, &[&file("vtu")])), &groups);
}

#[test]
fn an_abaqus_reader_finds_each_groups_node_set_under_its_name() {
    if !python_has("meshio") {
        return;
    }
    let (s, _) = built();
    let inp = s.path("out/didactic/didactic.inp").display().to_string();
    let sets = counts(&python(MESHIO_INP, &[&inp]));
    assert_eq!(sets["nodes:seafloor"], sets["nodes:box_zmax"]);
    assert_eq!(sets["nodes:reservoir_top"], sets["nodes:H1"]);
    assert!(sets["nodes:h1_west"] < sets["nodes:H1"]);
    let text = std::fs::read_to_string(&inp).expect("the inp is written");
    assert!(text.contains("*Surface, type=ELEMENT, name=seafloor\n"));
}

#[test]
fn the_id_table_numbers_each_group_after_the_fault_sides_as_the_files_do() {
    let (s, _) = built();
    let json: serde_json::Value = serde_json::from_slice(
        &std::fs::read(s.path("out/didactic/report.json")).expect("report.json"),
    )
    .expect("json");
    let rows = json["ids"].as_array().expect("ids");
    let row = |name: &str| {
        (rows.iter())
            .find(|r| r["name"] == name && r["kind"] == "group")
            .unwrap_or_else(|| panic!("no group row `{name}`"))
    };
    // 10 surface groups and 2 faults: the groups take 15.. in name order.
    assert_eq!(row("h1_east")["msh"], "2D group 15");
    assert_eq!(row("sides")["exodus"], "side set 19, node set 15");
    assert_eq!(row("seafloor")["vtu"], "group:seafloor 18");
    assert_eq!(row("seafloor")["medit"], "—");
}

#[test]
fn a_group_naming_a_trimmed_patch_fails_at_its_recipe_entry_listing_the_patches_kept() {
    let s = Scratch::didactic_built();
    s.edit(
        "[output]",
        "[groups]\ntop = [\"H1#2\", \"H1#3\"]\n\n[output]",
    );
    let err = model_fails_saying(
        &s,
        &[],
        &[
            "group selector `H1#3` matches no patch of the model",
            "`H1#2`, `H1#4`",
        ],
    );
    assert!(err.contains("top = [\"H1#2\", \"H1#3\"]"), "{err}");
}

#[test]
fn editing_a_group_reruns_the_mesh_and_the_export_and_no_mesher() {
    let s = Scratch::didactic_built();
    s.edit("[output]", "[groups]\ntop = \"H1#2\"\n\n[output]");
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    s.edit("top = \"H1#2\"", "top = [\"H1#2\", \"box.zmax\"]");
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    let ran = nodes_in_state(&r, "ran");
    assert!(ran.contains(&"mesh".to_string()) && ran.contains(&"export".to_string()));
    let others: Vec<&String> = (ran.iter())
        .filter(|n| !["mesh", "export"].contains(&n.as_str()))
        .collect();
    assert!(
        others.is_empty(),
        "re-ran besides mesh and export: {others:?}"
    );
    assert!(all_nodes(&r).iter().any(|n| n.starts_with("tet_mesh:")));
}
