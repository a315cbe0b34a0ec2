//! The shipped example with wells (`recipes/didactic_wells.toml`): every well segment is a chain
//! of tet edges whose crossings are nodes of the surfaces they cross, the mesh passes the
//! independent checker, editing one well re-runs only what it touches, a well outside the
//! model is an error in the recipe's terms, and the report lists each well's crossings, regions
//! and file markers.

use crate::common_cli;
use common_cli::*;
use geom::mesh::VolumeMesh;
use geom::mesh::read::read_volume_msh;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Command;

const RECIPE: &str = "didactic_wells.toml";

/// A scratch copy of the didactic data with the wells recipe, built once per test binary.
fn built() -> Scratch {
    static BASE: std::sync::OnceLock<std::path::PathBuf> = std::sync::OnceLock::new();
    let base = BASE.get_or_init(|| {
        let s = Scratch::didactic();
        let src = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("recipes")
            .join(RECIPE);
        std::fs::copy(src, s.path(RECIPE)).expect("copy the wells recipe");
        let (ok, _, err) = s.build_recipe(RECIPE, &[]);
        assert!(ok, "the wells recipe builds: {err}");
        s.dir.keep()
    });
    let dir = tempfile::tempdir().expect("temp dir");
    copy_dir(base, dir.path());
    Scratch { dir }
}

fn mesh_of(s: &Scratch) -> VolumeMesh {
    let file = s.path("out/didactic_wells/didactic_wells.msh");
    read_volume_msh(
        &std::fs::read(&file).expect("the msh"),
        "didactic_wells.msh",
    )
    .expect("reads")
}

fn edit(s: &Scratch, from: &str, to: &str) {
    let p = s.path(RECIPE);
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(text.contains(from), "the recipe has no `{from}`");
    std::fs::write(&p, text.replacen(from, to, 1)).unwrap();
}

/// Builds the scratch copy again: the nodes that ran and the report.
fn rebuilt(s: &Scratch) -> (Vec<String>, serde_json::Value) {
    let (ok, r, err) = s.build_recipe(RECIPE, &[]);
    assert!(ok, "{err}");
    (nodes_in_state(&r, "ran"), r)
}

fn assert_ran(ran: &[String], must: &[&str]) {
    for m in must {
        assert!(ran.iter().any(|n| n == m), "`{m}` did not re-run: {ran:?}");
    }
}

/// The nodes of a well's lines in chain order; panics unless they form one open chain.
fn chain(lines: &[[u32; 2]]) -> Vec<u32> {
    let mut next: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    for &[a, b] in lines {
        next.entry(a).or_default().push(b);
        next.entry(b).or_default().push(a);
    }
    assert!(next.values().all(|n| n.len() <= 2), "the well branches");
    let ends: Vec<u32> = next
        .iter()
        .filter(|(_, n)| n.len() == 1)
        .map(|(&v, _)| v)
        .collect();
    assert_eq!(ends.len(), 2, "one open chain");
    let mut path = vec![ends[0]];
    let mut prev = u32::MAX;
    while let Some(&n) = next[path.last().unwrap()].iter().find(|&&n| n != prev) {
        prev = *path.last().unwrap();
        path.push(n);
    }
    assert_eq!(path.len(), next.len(), "every line is on the chain");
    path
}

/// Writes `path` as the gOcad PLine `data/didactic/<name>.pl`, adds it to the recipe as well
/// `name` with `options` (`", size = 100.0"`), and builds again.
fn add_pline_well(
    s: &Scratch,
    name: &str,
    path: &[[f64; 3]],
    options: &str,
) -> (Vec<String>, serde_json::Value) {
    let mut pline = format!("GOCAD PLine 1\nHEADER {{\nname:{name}\n}}\nILINE\n");
    for (i, p) in path.iter().enumerate() {
        pline += &format!("VRTX {} {} {} {}\n", i + 1, p[0], p[1], p[2]);
    }
    for i in 1..path.len() {
        pline += &format!("SEG {i} {}\n", i + 1);
    }
    pline += "END\n";
    std::fs::write(s.path(&format!("data/didactic/{name}.pl")), pline).unwrap();
    let entry = format!("{name} = {{ file = \"data/didactic/{name}.pl\"{options} }}\nW2 = {{ file");
    edit(s, "W2 = { file", &entry);
    rebuilt(s)
}

/// Every edge of a tet, its smaller node first.
fn tet_edges(mesh: &VolumeMesh) -> BTreeSet<(u32, u32)> {
    let mut edges = BTreeSet::new();
    for t in &mesh.tets {
        for i in 0..4 {
            for j in i + 1..4 {
                edges.insert((t[i].min(t[j]), t[i].max(t[j])));
            }
        }
    }
    edges
}

/// The surface groups each node is on.
fn surfaces_at_nodes(mesh: &VolumeMesh) -> BTreeMap<u32, BTreeSet<&str>> {
    let mut on: BTreeMap<u32, BTreeSet<&str>> = BTreeMap::new();
    for (t, &g) in mesh.triangles.iter().zip(&mesh.triangle_group) {
        for &v in t {
            on.entry(v)
                .or_default()
                .insert(&mesh.surface_groups[g as usize].name);
        }
    }
    on
}

#[test]
fn every_well_segment_is_a_chain_of_tet_edges_through_nodes_of_the_surfaces_it_crosses() {
    let s = built();
    let mesh = mesh_of(&s);
    let edges = tet_edges(&mesh);
    let names: Vec<&str> = mesh.lines.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["W1", "W2"]);
    let on = surfaces_at_nodes(&mesh);
    let crosses = |w: &str, want: &[&str]| {
        let g = mesh.lines.iter().find(|g| g.name == w).unwrap();
        for &[a, b] in &g.lines {
            assert!(
                edges.contains(&(a.min(b), a.max(b))),
                "{w}: [{a}, {b}] is no tet edge"
            );
        }
        let path = chain(&g.lines);
        let met: BTreeSet<&str> = path
            .iter()
            .flat_map(|v| on.get(v).into_iter().flatten())
            .copied()
            .collect();
        let want: BTreeSet<&str> = want.iter().copied().collect();
        assert_eq!(
            met, want,
            "{w}: the surfaces whose nodes the well passes through"
        );
        // It starts on the top of the box (the part above it is left out).
        let top = path
            .iter()
            .map(|&v| mesh.nodes[v as usize][2])
            .fold(f64::MIN, f64::max);
        assert_eq!(top, 0.0, "{w} starts at the box top");
    };
    crosses("W1", &["box.zmax", "H1", "H2"]);
    crosses("W2", &["box.zmax", "H1", "F1", "H2"]);
}

#[test]
fn report_json_lists_each_wells_crossings_in_md_order_its_regions_and_its_picks() {
    let s = built();
    let out = s.path("out/didactic_wells");
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("report.json")).unwrap()).unwrap();
    let wells = v["wells"].as_array().expect("a wells array");
    let names: Vec<&str> = wells.iter().map(|w| w["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["W1", "W2"]);
    let check = |w: &serde_json::Value, file: &str, crossed: &[&str], regions: &[&str]| {
        let name = w["name"].as_str().unwrap();
        assert_eq!(w["file"], file);
        assert_eq!(w["error"], serde_json::Value::Null, "{name}");
        assert!(w["stations"].as_u64().unwrap() > 2, "{name}");
        assert!(w["mesh_edges"].as_u64().unwrap() > 5, "{name}");
        assert!(w["length"].as_f64().unwrap() > 1000.0, "{name}");
        assert_eq!(w["regions"], serde_json::json!(regions), "{name}");
        let markers = w["markers"].as_array().unwrap();
        let mds: Vec<f64> = markers.iter().map(|m| m["md"].as_f64().unwrap()).collect();
        assert!(
            mds.windows(2).all(|p| p[0] <= p[1]),
            "{name}: MD order {mds:?}"
        );
        let of = |kind: &str| -> Vec<&serde_json::Value> {
            markers.iter().filter(|m| m["kind"] == kind).collect()
        };
        let crossings = of("crossing");
        let surfaces: Vec<&str> = crossings
            .iter()
            .map(|c| c["name"].as_str().unwrap())
            .collect();
        assert_eq!(surfaces, crossed, "{name}: the surfaces crossed");
        assert!(
            crossings
                .iter()
                .all(|c| c["patch"].as_str().unwrap().contains('#'))
        );
        // The generator puts the file's H1 pick on the path a little off the model's H1.
        let h1 = crossings[surfaces.iter().position(|&s| s == "H1").unwrap()];
        let picks = of("file");
        assert_eq!(picks.len(), 1, "{name}");
        let pick = picks[0];
        assert_eq!(pick["name"], "H1_pick");
        let delta = pick["md"].as_f64().unwrap() - h1["md"].as_f64().unwrap();
        assert!(
            delta.abs() < 5.0,
            "{name}: H1_pick is {delta} m of MD off H1"
        );
        assert_eq!(pick["nearest"]["surface"], "H1");
        assert!((pick["nearest"]["delta_md"].as_f64().unwrap() - delta).abs() < 1e-9);
    };
    check(
        &wells[0],
        "data/didactic/W1_vertical.wl",
        &["box.zmax", "H1", "H2"],
        &["overburden_E", "reservoir_E", "underburden_E"],
    );
    check(
        &wells[1],
        "data/didactic/W2_deviated.wl",
        &["box.zmax", "H1", "F1", "H2"],
        &[
            "overburden_W",
            "reservoir_W",
            "reservoir_E",
            "underburden_E",
        ],
    );
    // The page: the section, and the wells drawn on Figure 1 (before Figure 2).
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("<h2>Wells (2)</h2>"));
    let figure1 = &html[..html.find("Figure 2.").unwrap()];
    assert_eq!(figure1.matches("<polyline").count(), 2);
}

#[test]
fn each_crossing_is_a_named_point_at_a_node_of_the_crossed_surface_on_the_well() {
    let s = built();
    let mesh = mesh_of(&s);
    let names: Vec<&str> = mesh.points.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "W1:H1",
            "W1:H2",
            "W1:box.zmax",
            "W2:F1",
            "W2:H1",
            "W2:H2",
            "W2:box.zmax"
        ]
    );
    for p in &mesh.points {
        let (well, surface) = p.name.split_once(':').unwrap();
        let on_surface = (mesh.triangles.iter().zip(&mesh.triangle_group))
            .filter(|(_, g)| mesh.surface_groups[**g as usize].name == surface)
            .any(|(t, _)| t.contains(&p.node));
        assert!(
            on_surface,
            "{}: node {} is on no {surface} triangle",
            p.name, p.node
        );
        let g = mesh.lines.iter().find(|g| g.name == well).unwrap();
        assert!(
            g.lines.iter().flatten().any(|&v| v == p.node),
            "{}: node {} is not on the well",
            p.name,
            p.node
        );
    }
    let top = |name: &str| {
        let p = mesh.points.iter().find(|p| p.name == name).unwrap();
        mesh.nodes[p.node as usize][2]
    };
    assert_eq!(top("W1:box.zmax"), 0.0);
    assert!(top("W1:H1") > top("W1:H2"), "H1 lies above H2 along W1");
}

#[test]
fn the_reports_id_table_numbers_each_named_point_as_the_msh_and_exodus_writers_do() {
    let s = built();
    let mesh = mesh_of(&s);
    let text = std::fs::read_to_string(s.path("out/didactic_wells/report.json")).unwrap();
    let report: serde_json::Value = serde_json::from_str(&text).unwrap();
    let rows = report["ids"].as_array().expect("an ids table");
    let points: Vec<&serde_json::Value> = rows.iter().filter(|r| r["kind"] == "point").collect();
    assert_eq!(points.len(), mesh.points.len());
    // Exodus node sets: one per surface group, then per well, then per named point.
    let first_set = mesh.surface_groups.len() + mesh.lines.len() + 1;
    for (i, (row, p)) in points.iter().zip(&mesh.points).enumerate() {
        assert_eq!(row["name"], p.name.as_str());
        assert_eq!(row["msh"], format!("0D group {}", i + 1));
        assert_eq!(row["exodus"], format!("node set {}", first_set + i));
    }
    assert!(
        rows.iter()
            .any(|r| r["kind"] == "well" && r["name"] == "W1")
    );
}

#[test]
fn the_example_with_wells_passes_the_independent_checker() {
    let s = built();
    let Some(check) = checker() else { return };
    let out = Command::new("python3")
        .arg(&check)
        .arg(s.path("out/didactic_wells/didactic_wells.msh"))
        .args(["--regions", "6", "--box"])
        .args(["500000", "7000000", "-2500", "505000", "7005000", "0"])
        .output()
        .expect("python3 runs");
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{report}");
    assert!(report.contains("\"fail\": []"), "{report}");
}

#[test]
fn editing_one_wells_size_reruns_the_meshes_within_its_reach_and_nothing_else() {
    let s = built();
    edit(&s, "size = 50.0 }", "size = 60.0 }");
    let (ran, r) = rebuilt(&s);
    assert_ran(
        &ran,
        &[
            "well_cut:W2",
            "tet_mesh:reservoir_W",
            "tet_mesh:reservoir_E",
            "mesh",
            "export",
        ],
    );
    assert!(
        ran.iter().any(|n| n.starts_with("surface_mesh:H1#")),
        "{ran:?}"
    );
    // Far from W2 (more than its size's reach, 1 km at the surfaces' growth): the sides of the
    // box at y = 0 and x = 5000.
    for n in all_nodes(&r) {
        let untouched = n.starts_with("import:")
            || n.starts_with("well:")
            || n.starts_with("discretize:")
            || n.starts_with("surface_mesh:box.ymin#")
            || n.starts_with("surface_mesh:box.xmax#")
            || n == "model"
            || n == "well_cut:W1";
        assert!(!(untouched && ran.contains(&n)), "`{n}` re-ran");
    }
}

#[test]
fn moving_a_well_at_the_mesh_size_reruns_the_patches_and_regions_it_crosses_only() {
    let s = built();
    let f = s.path("data/didactic/W1_vertical.wl");
    let text = std::fs::read_to_string(&f).unwrap();
    // 10 m east: W1 still crosses the same surfaces of the eastern block.
    std::fs::write(&f, text.replace("WREF 502600", "WREF 502610")).unwrap();
    let (ran, _) = rebuilt(&s);
    assert_ran(
        &ran,
        &[
            "well:W1",
            "well_cut:W1",
            "tet_mesh:reservoir_E",
            "mesh",
            "export",
        ],
    );
    let meshed: Vec<&String> = ran
        .iter()
        .filter(|n| n.starts_with("surface_mesh:") || n.starts_with("tet_mesh:"))
        .collect();
    let expected = [
        "surface_mesh:H1#4",
        "surface_mesh:H2#4",
        "surface_mesh:box.zmax#2",
        "tet_mesh:overburden_E",
        "tet_mesh:reservoir_E",
        "tet_mesh:underburden_E",
    ];
    assert_eq!(meshed, expected, "only what W1 crosses is meshed again");
    assert!(!ran.contains(&"well_cut:W2".to_string()));
    assert!(
        !ran.iter().any(|n| n.starts_with("discretize:")),
        "W1 crosses no curve: {ran:?}"
    );
}

#[test]
fn a_well_restricted_to_the_reservoir_is_embedded_there_only() {
    let s = built();
    edit(
        &s,
        "size = 50.0 }",
        "size = 50.0, regions = [\"reservoir_E\", \"reservoir_W\"] }",
    );
    let (_, _) = rebuilt(&s);
    let mesh = mesh_of(&s);
    let w2 = mesh.lines.iter().find(|g| g.name == "W2").expect("W2");
    let zs: Vec<f64> = w2
        .lines
        .iter()
        .flatten()
        .map(|&v| mesh.nodes[v as usize][2])
        .collect();
    let (top, bottom) = zs
        .iter()
        .fold((f64::MIN, f64::MAX), |(a, b), &z| (a.max(z), b.min(z)));
    // The reservoir lies between about 1160 and 1340 m below the box top along W2's path.
    assert!(
        top < -1100.0 && bottom > -1400.0,
        "W2 spans z {bottom} .. {top}"
    );
    let w1 = mesh.lines.iter().find(|g| g.name == "W1").expect("W1");
    assert_eq!(w1.lines.len(), 11, "W1 keeps every region");
}

#[test]
fn a_line_running_along_the_seafloor_then_down_is_edges_of_the_seafloor_mesh_then_of_tets() {
    let s = built();
    // A flowline on the box top from (503500, 7003000) to (504200, 7003600), then a vertical
    // well down to 1800 m: a gOcad PLine.
    let path = [
        [503500.0, 7003000.0, 0.0],
        [504200.0, 7003600.0, 0.0],
        [504200.0, 7003600.0, -1800.0],
    ];
    let (ran, r) = add_pline_well(&s, "W3", &path, ", size = 100.0");
    assert_ran(&ran, &["well_cut:W3", "surface_mesh:box.zmax#2", "mesh"]);
    let cut = r["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|n| n["name"] == "well_cut:W3");
    assert_eq!(
        cut.unwrap()["counts"]["runs"],
        1,
        "one stretch on the seafloor"
    );
    let mesh = mesh_of(&s);
    let edges = tet_edges(&mesh);
    let on = surfaces_at_nodes(&mesh);
    let g = mesh
        .lines
        .iter()
        .find(|g| g.name == "W3")
        .expect("W3's group");
    let path = chain(&g.lines);
    let mut top_edges = BTreeSet::new();
    for (t, &grp) in mesh.triangles.iter().zip(&mesh.triangle_group) {
        if mesh.surface_groups[grp as usize].name == "box.zmax" {
            for k in 0..3 {
                top_edges.insert((t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])));
            }
        }
    }
    let mut along_top = 0;
    for &[a, b] in &g.lines {
        let e = (a.min(b), a.max(b));
        assert!(edges.contains(&e), "[{a}, {b}] is no tet edge");
        if mesh.nodes[a as usize][2] == 0.0 && mesh.nodes[b as usize][2] == 0.0 {
            assert!(
                top_edges.contains(&e),
                "[{a}, {b}] on the seafloor is no seafloor edge"
            );
            along_top += 1;
        }
    }
    // 922 m along the top at size 100: about 9 edges, each a seafloor mesh edge.
    assert!(
        (8..=10).contains(&along_top),
        "{along_top} edges along the top"
    );
    let met: BTreeSet<&str> = path
        .iter()
        .flat_map(|v| on.get(v).into_iter().flatten())
        .copied()
        .collect();
    assert_eq!(met, BTreeSet::from(["box.zmax", "H1", "H2"]));
    // Where it leaves the seafloor is a marker; the run's start, the path's, is not.
    let p = mesh
        .points
        .iter()
        .find(|p| p.name == "W3:box.zmax")
        .expect("W3:box.zmax");
    assert_eq!(mesh.nodes[p.node as usize], [504200.0, 7003600.0, 0.0]);
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(s.path("out/didactic_wells/report.json")).unwrap())
            .unwrap();
    let w3 = &report["wells"].as_array().unwrap()[2];
    assert_eq!(w3["name"], "W3");
    let length = w3["length"].as_f64().unwrap();
    assert!(
        (length - (922.0 + 1800.0)).abs() < 2.0,
        "W3 is {length} m long"
    );
}

#[test]
fn a_well_entering_the_box_through_its_edge_crosses_both_sides_at_one_node_of_that_curve() {
    let s = built();
    // Down through the edge where the west side meets the top, at y = 7002000, then vertical.
    let path = [
        [499900.0, 7002000.0, 100.0],
        [500100.0, 7002000.0, -100.0],
        [500100.0, 7002000.0, -1800.0],
    ];
    let (ran, r) = add_pline_well(&s, "W4", &path, "");
    let pins = r["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|n| n["name"] == "curve_pins");
    assert_eq!(pins.expect("a curve_pins node")["counts"]["pins"], 1);
    // Every curve looks for its pins again (cheap); only the crossed one changes, so only
    // the patches along it or near W4 mesh again.
    for n in &ran {
        let far = ["box.xmax#", "box.zmin#", "box.ymin#", "box.ymax#", "F2#"];
        let far = far
            .iter()
            .any(|f| n.starts_with(&format!("surface_mesh:{f}")));
        assert!(!far, "`{n}` re-ran");
    }
    assert_ran(
        &ran,
        &["discretize:box.xmin/box.zmax", "surface_mesh:box.zmax#1"],
    );
    let mesh = mesh_of(&s);
    let node = |name: &str| {
        let p = mesh.points.iter().find(|p| p.name == name);
        p.unwrap_or_else(|| panic!("no named point {name}")).node
    };
    let v = node("W4:box.xmin");
    assert_eq!(v, node("W4:box.zmax"), "one node for both sides");
    let x = mesh.nodes[v as usize];
    assert_eq!((x[0], x[2]), (500000.0, 0.0));
    assert!((x[1] - 7002000.0).abs() < 1e-6, "{x:?}");
    let on = surfaces_at_nodes(&mesh);
    assert_eq!(on[&v], BTreeSet::from(["box.xmin", "box.zmax"]));
    let g = mesh
        .lines
        .iter()
        .find(|g| g.name == "W4")
        .expect("W4's group");
    let path = chain(&g.lines);
    assert!(
        path.first() == Some(&v) || path.last() == Some(&v),
        "W4 starts at the edge"
    );
    let edges = tet_edges(&mesh);
    assert!(
        g.lines
            .iter()
            .all(|&[a, b]| edges.contains(&(a.min(b), a.max(b))))
    );
}

#[test]
fn giving_a_well_an_area_reruns_only_mesh_and_export_and_writes_its_abaqus_section() {
    let s = built();
    edit(&s, "size = 50.0 }", "size = 50.0, area = 0.05 }");
    edit(
        &s,
        "formats = [\"msh\", \"vtu\"]",
        "formats = [\"msh\", \"vtu\", \"inp\"]",
    );
    let (ran, _) = rebuilt(&s);
    assert_eq!(ran, ["export", "mesh"]);
    let inp = std::fs::read_to_string(s.path("out/didactic_wells/didactic_wells.inp")).unwrap();
    assert!(
        inp.contains("*Solid Section, elset=W2, material=WELL_W2\n0.05,\n"),
        "no section for W2"
    );
    assert!(!inp.contains("elset=W1, material"), "W1 has no area");
}

#[test]
fn a_well_outside_the_model_is_an_error_naming_the_well_and_its_file() {
    let s = built();
    let f = s.path("data/didactic/W1_vertical.wl");
    let text = std::fs::read_to_string(&f).unwrap();
    // 10 km east of the box.
    std::fs::write(&f, text.replace("WREF 502600", "WREF 512600")).unwrap();
    let (ok, r, err) = s.build_recipe(RECIPE, &[]);
    assert!(!ok);
    assert!(
        nodes_in_state(&r, "failed").contains(&"well_cut:W1".to_string()),
        "{err}"
    );
    for needle in ["well `W1`", "W1_vertical.wl", "outside every region"] {
        assert!(err.contains(needle), "`{needle}` not in:\n{err}");
    }
    // The report keeps what is known of the well (its file, stations and picks) and says why
    // the rest is missing.
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(s.path("out/didactic_wells/report.json")).unwrap())
            .unwrap();
    let w1 = &v["wells"][0];
    assert_eq!(w1["name"], "W1");
    assert_eq!(w1["file"], "data/didactic/W1_vertical.wl");
    assert!(w1["stations"].as_u64().unwrap() > 2);
    assert!(
        w1["error"]
            .as_str()
            .unwrap()
            .contains("outside every region")
    );
    assert_eq!(w1["regions"], serde_json::json!([]));
    assert_eq!(w1["length"], serde_json::Value::Null);
    let kinds: Vec<&str> = (w1["markers"].as_array().unwrap().iter())
        .map(|m| m["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["file"]);
}
