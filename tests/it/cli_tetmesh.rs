//! `recipe tetmesh` on boundaries that no one here wrote (meshed by Gmsh), checked by the
//! independent checker `../shared/tools/check_mesh.py`.

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
