//! `recipe tetmesh` on boundaries that no one here wrote (meshed by Gmsh), checked by the
//! independent checker `../shared/tools/check_mesh.py`, and with embedded wells (`--embed-lines`)
//! written as line elements.

use crate::common_cli::checker;
use std::path::{Path, PathBuf};
use std::process::Command;
use test_support::paths;

/// The Gmsh-meshed peer boundaries, or `None` (with a note) when ../shared lacks them.
fn peer_dir() -> Option<PathBuf> {
    paths::shared("data/peer-boundaries")
}

fn mesh_region(region: &str, embed_entity: Option<&str>) {
    let Some(pb) = peer_dir() else { return };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join(format!("{region}.msh"));
    let mut args: Vec<String> = vec![
        "tetmesh".into(),
        pb.join(format!("region_L1_{region}.off"))
            .display()
            .to_string(),
        "-o".into(),
        out.display().to_string(),
    ];
    if let Some(e) = embed_entity {
        args.extend([
            "--embed".into(),
            pb.join("didactic_L1_surface.msh").display().to_string(),
            "--embed-tags".into(),
            e.into(),
            "--weld".into(),
            "1e-5".into(),
        ]);
    }
    let run = Command::new(env!("CARGO_BIN_EXE_recipe"))
        .args(&args)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{err}");
    assert!(out.is_file());
    if let Some(tool) = checker() {
        let check = Command::new("python3")
            .arg(tool)
            .arg(&out)
            .args(["--regions", "1"])
            .output()
            .unwrap();
        assert!(
            check.status.success(),
            "check_mesh.py failed:\n{}",
            String::from_utf8_lossy(&check.stdout)
        );
    }
}

#[test]
fn the_peer_meshed_overburden_west_block_meshes_and_passes_the_independent_checker() {
    mesh_region("overburden_W", None);
}

#[test]
fn the_peer_meshed_reservoir_east_block_with_its_dangling_fault_meshes_and_passes_the_checker() {
    mesh_region("reservoir_E", Some("27"));
}

#[test]
fn a_boundary_given_inward_oriented_is_turned_around_exactly_and_meshes_the_same() {
    let Some(pb) = peer_dir() else { return };
    let src = std::fs::read_to_string(pb.join("region_L1_reservoir_W.off")).unwrap();
    let lines: Vec<&str> = src.lines().collect();
    let counts: Vec<usize> = lines[1]
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    let mut flipped: Vec<String> = lines[..2 + counts[0]]
        .iter()
        .map(|l| l.to_string())
        .collect();
    for l in &lines[2 + counts[0]..2 + counts[0] + counts[1]] {
        let p: Vec<&str> = l.split_whitespace().collect();
        flipped.push(format!("{} {} {} {}", p[0], p[1], p[3], p[2]));
    }
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("inward.off");
    std::fs::write(&input, flipped.join("\n") + "\n").unwrap();
    let tets = |off: &Path, out: &Path| -> String {
        let (ok, err) = tetmesh(off, out);
        assert!(ok, "{err}");
        err.lines()
            .find(|l| l.contains("Finished"))
            .unwrap_or_default()
            .split(':')
            .nth(1)
            .unwrap_or_default()
            .split(" in ")
            .next()
            .unwrap_or_default()
            .to_string()
    };
    let a = tets(
        &pb.join("region_L1_reservoir_W.off"),
        &dir.path().join("a.msh"),
    );
    let b = tets(&input, &dir.path().join("b.msh"));
    assert!(a.contains("tets"), "{a}");
    assert_eq!(a, b, "both orientations give the same tet and node counts");
}

/// The OFF text of closed boxes, each given as (min, max) and written with outward triangles.
fn boxes_off(boxes: &[([f64; 3], [f64; 3])]) -> String {
    let mut vertices = String::new();
    let mut faces = String::new();
    for (k, (lo, hi)) in boxes.iter().enumerate() {
        let (corners, triangles) = test_support::shapes::cuboid(*lo, *hi);
        for p in corners {
            vertices.push_str(&format!("{} {} {}\n", p[0], p[1], p[2]));
        }
        for t in triangles {
            let t = t.map(|v| v as usize + 8 * k);
            faces.push_str(&format!("3 {} {} {}\n", t[0], t[1], t[2]));
        }
    }
    format!(
        "OFF\n{} {} 0\n{vertices}{faces}",
        8 * boxes.len(),
        12 * boxes.len()
    )
}

/// `recipe tetmesh <off> -o <out>`, its exit status and standard error.
fn tetmesh(off: &Path, out: &Path) -> (bool, String) {
    let run = Command::new(env!("CARGO_BIN_EXE_recipe"))
        .arg("tetmesh")
        .arg(off)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    (
        run.status.success(),
        String::from_utf8_lossy(&run.stderr).into_owned(),
    )
}

#[test]
fn a_boundary_with_an_inner_shell_meshes_the_space_between_the_shells_only() {
    // A host block around a lens-like body: the inner box written outward like a solid, as a
    // modeller exports it; the mesher must turn it to face into the cavity.
    let dir = tempfile::tempdir().unwrap();
    let off = dir.path().join("host.off");
    std::fs::write(
        &off,
        boxes_off(&[
            ([0.0, 0.0, 0.0], [10.0, 10.0, 10.0]),
            ([3.0, 4.0, 4.5], [7.0, 6.0, 5.5]),
        ]),
    )
    .unwrap();
    let out = dir.path().join("host.msh");
    let (ok, err) = tetmesh(&off, &out);
    assert!(ok, "{err}");
    let mesh = geom::mesh::read::read_volume_msh(&std::fs::read(&out).unwrap(), "host.msh")
        .expect("the msh reads back");
    let volume: f64 = mesh
        .tets
        .iter()
        .map(|t| {
            let [a, b, c, d] = t.map(|v| mesh.nodes[v as usize]);
            geom::predicates::signed_volume(&a, &b, &c, &d)
        })
        .sum();
    assert!(
        (volume - (1000.0 - 8.0)).abs() < 1e-6,
        "meshed volume {volume}"
    );
}

#[test]
fn two_boxes_side_by_side_are_refused_as_not_one_region() {
    let dir = tempfile::tempdir().unwrap();
    let off = dir.path().join("two.off");
    std::fs::write(
        &off,
        boxes_off(&[
            ([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
            ([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]),
        ]),
    )
    .unwrap();
    let (ok, err) = tetmesh(&off, &dir.path().join("two.msh"));
    assert!(!ok);
    assert!(
        err.contains("2 shells do not bound one region together"),
        "{err}"
    );
    assert!(!dir.path().join("two.msh").exists(), "no partial output");
}

/// `recipe tetmesh <boundary> --embed-lines <lines> -o <out>`, its exit status and standard error.
fn tetmesh_with_lines(boundary: &Path, lines: &Path, out: &Path) -> (bool, String) {
    let run = Command::new(env!("CARGO_BIN_EXE_recipe"))
        .arg("tetmesh")
        .arg(boundary)
        .arg("--embed-lines")
        .arg(lines)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    (
        run.status.success(),
        String::from_utf8_lossy(&run.stderr).into_owned(),
    )
}

#[test]
fn a_well_given_with_embed_lines_is_written_as_line_elements_along_tet_edges() {
    let dir = tempfile::tempdir().unwrap();
    let off = dir.path().join("block.off");
    std::fs::write(&off, boxes_off(&[([0.0; 3], [10.0, 10.0, 10.0])])).unwrap();
    // A deviated well from a box corner (a boundary vertex) into the block, given as an OBJ
    // polyline, and a second one as msh line elements.
    let stations = [
        [0.0, 0.0, 10.0],
        [1.5, 1.25, 8.0],
        [3.25, 2.5, 5.5],
        [4.0, 4.5, 3.0],
    ];
    let mut obj = String::new();
    for p in &stations {
        obj.push_str(&format!("v {} {} {}\n", p[0], p[1], p[2]));
    }
    obj.push_str("l 1 2 3 4\n");
    let well = dir.path().join("W1.obj");
    std::fs::write(&well, obj).unwrap();
    let out = dir.path().join("block.msh");
    let (ok, err) = tetmesh_with_lines(&off, &well, &out);
    assert!(ok, "{err}");
    assert!(err.contains("Embedded 3 line segments"), "{err}");
    let bytes = std::fs::read(&out).unwrap();
    let text = String::from_utf8_lossy(&bytes);
    assert!(
        text.contains("1 1 \"W1\""),
        "a 1D group named after the file"
    );
    let mesh = geom::mesh::read::read_volume_msh(&bytes, "block.msh").unwrap();
    let lines = geom::mesh::read::read_msh_lines(&bytes, "block.msh").unwrap();
    assert_eq!(lines.vertices, mesh.nodes);
    // Every line element is an edge of a tet.
    let mut edges = std::collections::BTreeSet::new();
    for t in &mesh.tets {
        for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
            edges.insert([t[i].min(t[j]), t[i].max(t[j])]);
        }
    }
    for l in &lines.lines {
        assert!(edges.contains(&[l[0].min(l[1]), l[0].max(l[1])]), "{l:?}");
    }
    // They chain from the first station to the last through points of the polyline.
    let at = |v: u32| mesh.nodes[v as usize];
    assert_eq!(at(lines.lines[0][0]), stations[0]);
    assert_eq!(at(lines.lines[lines.lines.len() - 1][1]), stations[3]);
    for w in lines.lines.windows(2) {
        assert_eq!(w[0][1], w[1][0]);
    }
    let on_path = |p: [f64; 3]| {
        stations.windows(2).any(|s| {
            let (a, b) = (s[0], s[1]);
            let d: Vec<f64> = (0..3).map(|k| b[k] - a[k]).collect();
            let l2: f64 = d.iter().map(|x| x * x).sum();
            let t = (0..3).map(|k| (p[k] - a[k]) * d[k]).sum::<f64>() / l2;
            let e: f64 = (0..3).map(|k| (a[k] + t * d[k] - p[k]).powi(2)).sum();
            (-1e-12..=1.0 + 1e-12).contains(&t) && e.sqrt() < 1e-9
        })
    };
    assert!(lines.lines.iter().flatten().all(|&v| on_path(at(v))));
    if let Some(tool) = checker() {
        let check = Command::new("python3")
            .arg(tool)
            .arg(&out)
            .args(["--regions", "1"])
            .output()
            .unwrap();
        assert!(
            check.status.success(),
            "check_mesh.py failed on a file with line elements:\n{}",
            String::from_utf8_lossy(&check.stdout)
        );
    }

    // The same well as msh line elements (format 2.2).
    let mut msh = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n");
    for (i, p) in stations.iter().enumerate() {
        msh.push_str(&format!("{} {} {} {}\n", i + 1, p[0], p[1], p[2]));
    }
    msh.push_str("$EndNodes\n$Elements\n3\n1 1 2 0 1 1 2\n2 1 2 0 1 2 3\n3 1 2 0 1 3 4\n");
    msh.push_str("$EndElements\n");
    let well2 = dir.path().join("W2.msh");
    std::fs::write(&well2, msh).unwrap();
    let out2 = dir.path().join("block2.msh");
    let (ok, err) = tetmesh_with_lines(&off, &well2, &out2);
    assert!(ok, "{err}");
    let lines2 = geom::mesh::read::read_msh_lines(&std::fs::read(&out2).unwrap(), "b2.msh");
    assert_eq!(lines2.unwrap().lines.len(), lines.lines.len());
}

#[test]
fn embed_lines_writes_the_well_in_a_vtu_and_refuses_a_well_leaving_the_block() {
    let dir = tempfile::tempdir().unwrap();
    let off = dir.path().join("block.off");
    std::fs::write(&off, boxes_off(&[([0.0; 3], [10.0, 10.0, 10.0])])).unwrap();
    let inside = dir.path().join("inside.obj");
    std::fs::write(&inside, "v 5 5 5\nv 5 5 8\nl 1 2\n").unwrap();
    let (ok, err) = tetmesh_with_lines(&off, &inside, &dir.path().join("block.vtu"));
    assert!(ok, "{err}");
    let vtu = std::fs::read_to_string(dir.path().join("block.vtu")).unwrap();
    assert!(
        vtu.contains("Name=\"well:inside\" NumberOfTuples=\"1\" format=\"ascii\">1<"),
        "the well's name in the names table"
    );
    let well = dir.path().join("well.obj");
    std::fs::write(&well, "v 5 5 5\nv 5 5 12\nl 1 2\n").unwrap();
    let (ok, err) = tetmesh_with_lines(&off, &well, &dir.path().join("block.msh"));
    assert!(!ok);
    assert!(
        err.contains("line segment 0 [8, 9] from [5.0, 5.0, 5.0] to [5.0, 5.0, 12.0]"),
        "{err}"
    );
    assert!(!dir.path().join("block.msh").exists(), "no partial output");
}
