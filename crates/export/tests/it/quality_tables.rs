//! The seed's Tables 1 and 2 computed by `export::quality` agree with check_mesh.py's JSON.

use test_support::{export_support, paths};

use export::quality::{render_table1, render_table2, table1, table2};
use export::{Format, export};
use export_support::*;
use geom::mesh::VolumeMesh;

/// The layered box with its interior nodes moved by a deterministic jitter (box faces stay put),
/// so element qualities spread out.
fn jittered() -> VolumeMesh {
    let mut m = layered_box(6, 6);
    let [x0, y0, z0, x1, y1, z1] = box_bounds();
    let (hx, hz) = ((x1 - x0) / 6.0, (z1 - z0) / 6.0);
    for (i, p) in m.nodes.iter_mut().enumerate() {
        let on_box = [
            p[0] == x0,
            p[0] == x1,
            p[1] == y0,
            p[1] == y1,
            p[2] == z0,
            p[2] == z1,
        ];
        if on_box.iter().any(|&b| b) {
            continue;
        }
        let s = i as f64;
        p[0] += 0.12 * hx * (1.7 * s).sin();
        p[1] += 0.12 * hx * (2.3 * s + 0.5).sin();
        p[2] += 0.12 * hz * (3.1 * s + 1.0).sin();
    }
    m
}

fn get(v: &serde_json::Value, path: &[&str]) -> f64 {
    let mut x = v;
    for k in path {
        x = &x[*k];
    }
    x.as_f64()
        .unwrap_or_else(|| panic!("no number at {path:?}"))
}

fn close(a: f64, b: f64, what: &str) {
    assert!(
        (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
        "{what}: ours {a} vs check_mesh {b}"
    );
}

#[test]
fn tables_match_check_mesh_json_per_region_and_overall() {
    if !python_has("meshio, numpy") {
        return;
    }
    let Some(tool) = checker() else { return };
    let mesh = jittered();
    let dir = tempfile::tempdir().unwrap();
    let paths = write_all(dir.path(), &export(&mesh, "q", Format::Msh).unwrap());
    let json = dir.path().join("q.json");
    let (ok, out) = run_checker(&tool, &paths[0], 3, Some(&json));
    assert!(ok, "{out}");
    let rep: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();

    let t2 = table2(&mesh);
    assert_eq!(t2.len(), 4);
    for (r, row) in t2.iter().take(3).enumerate() {
        let key = (r + 1).to_string();
        let reg = &rep["regions"][&key];
        assert_eq!(row.elements as u64, reg["elements"].as_u64().unwrap());
        assert_eq!(row.nodes as u64, reg["nodes"].as_u64().unwrap());
        close(row.avg, get(reg, &["avg"]), "avg");
        close(row.sd, get(reg, &["sd"]), "sd");
        close(row.min, get(reg, &["min"]), "min");
        close(row.pct_lt_0_3, get(reg, &["pct_lt_0.3"]), "% < 0.3");
        close(
            row.avg_paper,
            get(reg, &["paper_scale", "avg"]),
            "paper avg",
        );
    }
    let all = &t2[3];
    assert_eq!(all.name, "all");
    close(all.avg, get(&rep, &["mean_ratio", "avg"]), "all avg");
    close(all.min, get(&rep, &["mean_ratio", "min"]), "all min");
    close(all.sd, get(&rep, &["mean_ratio", "sd"]), "all sd");
    assert!(all.min < all.avg && all.avg < 1.0);

    let t1 = table1(&mesh);
    assert_eq!(t1.len(), mesh.surface_groups.len() + 1);
    let tall = t1.last().unwrap();
    assert_eq!(tall.triangles, mesh.triangles.len());
    close(tall.avg, get(&rep, &["tri_quality", "avg"]), "tri avg");
    close(tall.max, get(&rep, &["tri_quality", "max"]), "tri max");
    close(tall.sd, get(&rep, &["tri_quality", "sd"]), "tri sd");
    close(
        tall.pct_gt_1_15,
        get(&rep, &["tri_quality", "pct_gt_1.15"]),
        "tri % > 1.15",
    );
    close(
        tall.pct_gt_1_5,
        get(&rep, &["tri_quality", "pct_gt_1.5"]),
        "tri % > 1.5",
    );
}

#[test]
fn per_group_rows_count_their_own_triangles_and_nodes() {
    let mesh = layered_box(4, 3);
    let t1 = table1(&mesh);
    // Box side xmin: a 4 x 3 grid of squares, two triangles each, 5 x 4 nodes.
    assert_eq!(
        (t1[0].name.as_str(), t1[0].triangles, t1[0].nodes),
        ("xmin", 24, 20)
    );
    let t2 = table2(&mesh);
    assert_eq!(t2[1].name, "reservoir");
    assert_eq!(t2[1].elements, 4 * 4 * 6);
    assert_eq!(t2[1].nodes, 5 * 5 * 2);
}

#[test]
fn cubic_cells_give_kuhn_tets_of_one_known_quality() {
    // 6 x 6 x 3 cells of a 5000 x 5000 x 2500 box: cubes, cut into congruent Kuhn tets with
    // edges 1, 1, 1, √2, √2, √3 (Σl² = 10 h²) and V = h³/6: mean ratio 12·(1/2)^(2/3)/10.
    let t2 = table2(&layered_box(6, 3));
    let all = t2.last().unwrap();
    let want = 1.2 * 0.5f64.powf(2.0 / 3.0);
    assert!(
        (all.avg - want).abs() < 1e-12 && (all.min - want).abs() < 1e-12,
        "{all:?}"
    );
    assert!(all.sd < 1e-12);
    assert!((all.min_dihedral_deg - 45.0).abs() < 1e-9);
    assert_eq!((all.pct_lt_0_3, all.pct_lt_0_1), (0.0, 0.0));
}

#[test]
fn rendered_tables_are_aligned_and_mark_empty_groups() {
    let mut mesh = layered_box(4, 3);
    mesh.surface_groups.push(geom::mesh::SurfaceGroup {
        name: "unused".into(),
        kind: geom::mesh::SurfaceKind::Other,
    });
    let t1 = render_table1(&table1(&mesh));
    let lines: Vec<&str> = t1.lines().skip(1).collect();
    assert!(lines[0].starts_with("surface") && lines[0].contains("% > 1.15"));
    let unused = lines.iter().find(|l| l.starts_with("unused")).unwrap();
    assert!(unused.contains(" - "), "{unused}");
    let widths: Vec<usize> = lines
        .iter()
        .filter(|l| !l.contains(" - "))
        .map(|l| l.len())
        .collect();
    assert!(widths.windows(2).all(|w| w[0] == w[1]), "{t1}");
    let t2 = render_table2(&table2(&mesh));
    assert!(t2.contains("overburden") && t2.contains("min dihedral") && t2.contains("x0.79"));
    let json = serde_json::to_string(&export::quality::report(&mesh)).unwrap();
    assert!(json.contains("\"pct_lt_0_3\"") && json.contains("\"table1\""));
    // The empty group's statistics are NaN: JSON null, not a made-up number.
    assert!(
        json.contains("\"name\":\"unused\",\"nodes\":0,\"triangles\":0,\"avg\":null"),
        "{json}"
    );
    let both = export::quality::report(&mesh).render();
    assert!(both.starts_with("Table 1") && both.contains("\n\nTable 2"));
}

#[test]
fn each_regions_bound_on_its_dihedral_angles_is_the_sharpest_angle_its_surfaces_leave_it() {
    // The layered box: its horizons and the fault meet the box sides and each other at right
    // angles, and the faces' diagonals leave 180°; the Kuhn tets' smallest angle is 45°.
    let mesh = layered_box(6, 6);
    let rows = table2(&mesh);
    for row in &rows {
        let bound = row.min_dihedral_bound_deg.expect("a bound");
        assert!((bound - 90.0).abs() < 1e-9, "{}: {bound}", row.name);
        assert!(row.min_dihedral_deg <= bound, "{}", row.name);
        let at = row.min_dihedral_bound_at.expect("a place");
        let [x0, y0, z0, x1, y1, z1] = box_bounds();
        let on_box = [
            at[0] - x0,
            x1 - at[0],
            at[1] - y0,
            y1 - at[1],
            at[2] - z0,
            z1 - at[2],
        ];
        assert!(
            on_box.iter().any(|d| d.abs() < 1e-6),
            "{}: {at:?}",
            row.name
        );
    }
    let t2 = render_table2(&rows);
    assert!(
        t2.lines().nth(1).is_some_and(|l| l.contains("bound")),
        "{t2}"
    );
}

#[test]
fn table1_on_the_peer_didactic_surfaces_matches_check_mesh_tri_quality() {
    if !python_has("meshio, numpy") {
        return;
    }
    let Some(tool) = checker() else { return };
    let Some(path) = paths::shared("data/peer-boundaries/didactic_L1_surface.msh") else {
        return;
    };
    let b = geom::mesh::read::read_msh(&std::fs::read(&path).unwrap(), "didactic").unwrap();
    // One surface group per physical name (box, H1, H2, F1, F2), in name order.
    let names: std::collections::BTreeSet<&String> = b.tag_names.values().collect();
    let names: Vec<&String> = names.into_iter().collect();
    let mut mesh = VolumeMesh {
        nodes: b.vertices.clone(),
        triangles: b.triangles.clone(),
        ..Default::default()
    };
    for n in &names {
        mesh.surface_groups.push(geom::mesh::SurfaceGroup {
            name: (*n).clone(),
            kind: geom::mesh::SurfaceKind::Other,
        });
    }
    mesh.triangle_group = b
        .triangle_tag
        .iter()
        .map(|t| names.iter().position(|n| **n == b.tag_names[t]).unwrap() as u32)
        .collect();
    let script = r#"
import sys, json, importlib.util, numpy as np, meshio
spec = importlib.util.spec_from_file_location("cm", sys.argv[1]); cm = importlib.util.module_from_spec(spec); spec.loader.exec_module(cm)
m = meshio.read(sys.argv[2])
F = np.vstack([b.data for b in m.cells if b.type == "triangle"])
q, _ = cm.tri_quality(np.asarray(m.points, float), F)
print("JSON", json.dumps(cm.stats(q, hi=[1.15, 1.5])))
"#;
    let out = python(script, &[tool.to_str().unwrap(), path.to_str().unwrap()]);
    let json = out.lines().find_map(|l| l.strip_prefix("JSON ")).unwrap();
    let rep: serde_json::Value = serde_json::from_str(json).unwrap();
    let t1 = table1(&mesh);
    assert_eq!(t1.len(), 6);
    let all = &t1[5];
    assert_eq!(all.triangles as u64, rep["n"].as_u64().unwrap());
    close(all.avg, get(&rep, &["avg"]), "avg");
    close(all.sd, get(&rep, &["sd"]), "sd");
    close(all.max, get(&rep, &["max"]), "max");
    close(all.pct_gt_1_15, get(&rep, &["pct_gt_1.15"]), "% > 1.15");
    close(all.pct_gt_1_5, get(&rep, &["pct_gt_1.5"]), "% > 1.5");
    // Gmsh's frontal-Delaunay surfaces are close to equilateral on average.
    assert!(
        t1.iter().all(|r| r.avg > 1.0 && r.avg < 1.3),
        "{}",
        render_table1(&t1)
    );
}

#[test]
fn each_regions_worst_tet_is_placed_at_the_centroid_of_a_tet_with_its_smallest_angle() {
    let mesh = jittered();
    let rows = table2(&mesh);
    for (k, row) in rows.iter().enumerate().filter(|(_, r)| r.name != "all") {
        let at = row.min_dihedral_at.expect("a place");
        let worst = (mesh.tets.iter().zip(&mesh.tet_region))
            .filter(|(_, r)| **r as usize == k)
            .map(|(t, _)| t.map(|v| mesh.nodes[v as usize]))
            .find(|c| {
                (0..3).all(|d| (c.iter().map(|p| p[d]).sum::<f64>() / 4.0 - at[d]).abs() < 1e-9)
            })
            .unwrap_or_else(|| panic!("{}: no tet of the region is centred at {at:?}", row.name));
        let [a, b, c, d] = worst;
        let angle = export::quality::measures::tet_min_dihedral_deg(&a, &b, &c, &d);
        assert_eq!(angle, row.min_dihedral_deg, "{}", row.name);
    }
    // The whole mesh's row names the worst of all.
    let all = rows.last().expect("the row of all");
    assert!(all.min_dihedral_at.is_some());
}
