//! The shipped example end to end: the build's tet mesh is read back by our msh reader and by the
//! independent checker `../shared/tools/check_mesh.py` (conformity, volume equal to the box, six
//! regions, dangling-fault triangles as tet faces), the groups carry the recipe's names, and the
//! build reports the model and the seed's quality tables.

use crate::common_cli;
use common_cli::*;
use geom::mesh::read::read_volume_msh;
use std::collections::BTreeMap;
use std::process::Command;

const REGIONS: [&str; 6] = [
    "overburden_E",
    "overburden_W",
    "reservoir_E",
    "reservoir_W",
    "underburden_E",
    "underburden_W",
];

#[test]
fn the_shipped_example_builds_a_mesh_that_the_independent_checker_accepts_in_msh_and_vtu() {
    let s = Scratch::didactic_built();
    let Some(check) = checker() else { return };
    for file in ["didactic.msh", "didactic.vtu"] {
        let out = Command::new("python3")
            .arg(&check)
            .arg(s.path("out/didactic").join(file))
            .args(["--regions", "6", "--box"])
            .args(["500000", "7000000", "-2500", "505000", "7005000", "0"])
            .output()
            .expect("python3 runs");
        let report = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{file}: {report}");
        assert!(report.contains("\"fail\": []"), "{file}: {report}");
    }
}

#[test]
fn the_msh_names_every_region_and_surface_and_the_dangling_fault_has_tets_on_both_sides() {
    let s = Scratch::didactic_built();
    let bytes = std::fs::read(s.path("out/didactic/didactic.msh")).expect("the mesh is written");
    let m = read_volume_msh(&bytes, "didactic.msh").expect("our reader reads it");
    let mut regions: Vec<&str> = m.regions.iter().map(|r| r.name.as_str()).collect();
    regions.sort();
    assert_eq!(regions, REGIONS);
    let groups: Vec<&str> = m.surface_groups.iter().map(|g| g.name.as_str()).collect();
    for g in ["F1", "F2", "H1", "H2", "box.xmin", "box.zmax"] {
        assert!(groups.contains(&g), "group {g} missing from {groups:?}");
    }
    assert!(m.tet_region.iter().all(|&r| (r as usize) < 6));
    // Every face of every tet, counted.
    let mut faces: BTreeMap<[u32; 3], u32> = BTreeMap::new();
    for t in &m.tets {
        for f in [
            [t[0], t[1], t[2]],
            [t[0], t[1], t[3]],
            [t[0], t[2], t[3]],
            [t[1], t[2], t[3]],
        ] {
            let mut f = f;
            f.sort_unstable();
            *faces.entry(f).or_default() += 1;
        }
    }
    let f2 = groups.iter().position(|g| *g == "F2").expect("F2") as u32;
    let mut n = 0;
    for (t, &g) in m.triangles.iter().zip(&m.triangle_group) {
        let mut k = *t;
        k.sort_unstable();
        let uses = faces.get(&k).copied().unwrap_or(0);
        if g == f2 {
            assert_eq!(uses, 2, "F2 triangle {t:?} is not between two tets");
            n += 1;
        } else {
            assert!(uses >= 1, "triangle {t:?} is not a tet face");
        }
    }
    assert!(n > 0, "the dangling fault is in the mesh");
}

#[test]
fn the_build_lists_the_model_in_json_and_prints_the_quality_tables_when_verbose() {
    let s = Scratch::didactic_built();
    let (ok, r, err) = s.build(&["-v"]);
    assert!(ok, "{err}");
    assert!(err.contains("Table 1") && err.contains("Table 2"), "{err}");
    for name in REGIONS {
        assert!(err.contains(name), "Table 2 lacks {name}");
    }
    let model = &r["model"];
    let curves: Vec<&str> = model["curves"]
        .as_array()
        .expect("curves")
        .iter()
        .filter_map(|c| c["name"].as_str())
        .collect();
    for c in ["F1/H1", "F1/H2", "F2/H1", "F2/H2"] {
        assert!(curves.contains(&c), "curve {c} missing from {curves:?}");
    }
    let dangling: Vec<&str> = model["patches"]
        .as_array()
        .expect("patches")
        .iter()
        .filter(|p| p["dangling"] == true)
        .filter_map(|p| p["name"].as_str())
        .collect();
    assert_eq!(dangling, ["F2#1", "F2#2", "F2#3"]);
    let regions = model["regions"].as_array().expect("regions");
    assert_eq!(regions.len(), 6);
    let res_e = regions
        .iter()
        .find(|r| r["name"] == "reservoir_E")
        .expect("reservoir_E");
    let sides: Vec<&str> = res_e["sides"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    assert!(
        sides.contains(&"F2#2:front") && sides.contains(&"F2#2:back"),
        "{sides:?}"
    );
    assert!(
        std::fs::read_to_string(s.path("out/didactic/didactic.quality.txt"))
            .is_ok_and(|t| t.contains("reservoir_E"))
    );
}

#[test]
fn every_recipe_format_is_written_and_meshio_reads_the_binary_vtu_and_the_abaqus_file_whole() {
    let s = Scratch::didactic();
    s.edit(
        "formats = [\"msh\", \"vtu\"]",
        "formats = [\"msh\", \"vtu-binary\", \"tetgen\", \"medit\", \"inp\"]",
    );
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    let dir = s.path("out/didactic");
    let bytes = std::fs::read(dir.join("didactic.msh")).expect("the msh is written");
    let tets = read_volume_msh(&bytes, "didactic.msh")
        .expect("reads")
        .tets
        .len();
    for f in [
        "didactic.1.node",
        "didactic.mesh",
        "didactic.inp",
        "didactic.vtu",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    let script = "import sys, meshio\n\
                  for f in sys.argv[1:]:\n    \
                  m = meshio.read(f)\n    \
                  print(sum(len(b.data) for b in m.cells if b.type == 'tetra'))\n";
    let out = Command::new("python3")
        .args(["-c", script])
        .arg(dir.join("didactic.inp"))
        .arg(dir.join("didactic.vtu"))
        .output();
    let Ok(out) = out
        .as_ref()
        .map_err(|_| eprintln!("skipping the meshio read: no python3"))
    else {
        return;
    };
    let stderr = String::from_utf8_lossy(&out.stderr);
    if stderr.contains("No module named") {
        eprintln!("skipping the meshio read: no meshio");
        return;
    }
    let counts: Vec<String> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(str::to_string)
        .collect();
    assert_eq!(counts, [tets.to_string(), tets.to_string()], "{stderr}");
}
