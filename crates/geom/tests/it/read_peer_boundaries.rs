//! The boundary readers on the peer-meshed didactic model (../shared/data/peer-boundaries) and
//! on damaged copies of it.

use geom::mesh::read::{BoundaryMesh, read_by_extension, read_msh, read_obj, read_off};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use test_support::paths;

fn peer_dir() -> Option<PathBuf> {
    paths::shared("data/peer-boundaries")
}

/// Every undirected edge of a closed surface is used exactly twice.
fn is_closed(m: &BoundaryMesh) -> bool {
    let mut edges: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    edges.values().all(|&c| c == 2)
}

#[test]
fn each_region_off_has_the_counts_of_its_header_and_is_closed() {
    let Some(dir) = peer_dir() else { return };
    let mut seen = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_str().unwrap().to_string();
        if !(name.starts_with("region_L1_") && name.ends_with(".off")) {
            continue;
        }
        let bytes = std::fs::read(&p).unwrap();
        let header = String::from_utf8_lossy(&bytes)
            .lines()
            .nth(1)
            .unwrap()
            .to_string();
        let n: Vec<usize> = header
            .split_whitespace()
            .map(|t| t.parse().unwrap())
            .collect();
        let m = read_off(&bytes, &name).unwrap();
        assert_eq!(
            (m.vertices.len(), m.triangles.len()),
            (n[0], n[1]),
            "{name}"
        );
        assert!(is_closed(&m), "{name} is not closed as read");
        seen += 1;
    }
    assert_eq!(seen, 6);
}

fn meta(dir: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(dir.join("didactic_L1_meta.json")).unwrap()).unwrap()
}

#[test]
fn the_surface_msh_has_entity_tags_named_as_in_the_meta_file() {
    let Some(dir) = peer_dir() else { return };
    let m = read_msh(
        &std::fs::read(dir.join("didactic_L1_surface.msh")).unwrap(),
        "didactic_L1_surface.msh",
    )
    .unwrap();
    let meta = meta(&dir);
    let surfaces = meta["surfaces"].as_object().unwrap();
    assert_eq!(m.tag_names.len(), surfaces.len());
    for (tag, name) in surfaces {
        let t: i32 = tag.parse().unwrap();
        assert_eq!(
            m.tag_names.get(&t).map(String::as_str),
            name.as_str(),
            "entity {t}"
        );
    }
    assert_eq!(m.vertices.len(), 10453);
    assert_eq!(m.triangles.len(), 21619);
    // The dangling fault's patches carry the triangle counts the meta file gives per region.
    let count = |t: i32| m.triangle_tag.iter().filter(|&&x| x == t).count() as u64;
    let checks = &meta["region_checks"];
    assert_eq!(
        count(17),
        checks["underburden_E"]["embedded_fault_triangles"]
            .as_u64()
            .unwrap()
    );
    assert_eq!(
        count(27),
        checks["reservoir_E"]["embedded_fault_triangles"]
            .as_u64()
            .unwrap()
    );
    assert_eq!(
        count(32),
        checks["overburden_E"]["embedded_fault_triangles"]
            .as_u64()
            .unwrap()
    );
}

#[test]
fn the_plc_obj_has_one_tag_per_gmsh_surface_and_the_same_triangles_as_the_msh() {
    let Some(dir) = peer_dir() else { return };
    let obj = read_obj(
        &std::fs::read(dir.join("plc_L1.obj")).unwrap(),
        "plc_L1.obj",
    )
    .unwrap();
    let msh = read_by_extension(
        "didactic_L1_surface.msh",
        &std::fs::read(dir.join("didactic_L1_surface.msh")).unwrap(),
    )
    .unwrap();
    assert_eq!(obj.tag_names.len(), 32);
    assert_eq!(
        obj.tag_names.get(&17).map(String::as_str),
        Some("surf17_F2_dangling")
    );
    assert_eq!(obj.triangles, msh.triangles);
    assert_eq!(obj.triangle_tag, msh.triangle_tag);
    for (a, b) in obj.vertices.iter().zip(&msh.vertices) {
        assert!((0..3).all(|k| (a[k] - b[k]).abs() < 1e-5), "{a:?} vs {b:?}");
    }
}

#[test]
fn gmsh_rewrites_of_the_msh_in_binary_4_1_and_ascii_2_2_read_the_same() {
    let Some(dir) = peer_dir() else { return };
    let ok = Command::new("python3")
        .args(["-c", "import gmsh"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    if !ok {
        eprintln!("skipping: python3 with gmsh is absent");
        return;
    }
    let src = dir.join("didactic_L1_surface.msh");
    let reference = read_msh(&std::fs::read(&src).unwrap(), "ref").unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let script = r#"
import sys, gmsh
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(sys.argv[1])
gmsh.option.setNumber("Mesh.Binary", 1); gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.write(sys.argv[2])
gmsh.option.setNumber("Mesh.Binary", 0); gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
gmsh.option.setNumber("Mesh.SaveAll", 0)
gmsh.write(sys.argv[3])
gmsh.finalize()
"#;
    let (bin, v22) = (tmp.path().join("bin.msh"), tmp.path().join("v22.msh"));
    let out = Command::new("python3")
        .args([
            "-c",
            script,
            src.to_str().unwrap(),
            bin.to_str().unwrap(),
            v22.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for p in [bin, v22] {
        let m = read_msh(&std::fs::read(&p).unwrap(), p.to_str().unwrap()).unwrap();
        assert_eq!(m.triangles.len(), reference.triangles.len(), "{p:?}");
        // Same triangles (as coordinate triples) with the same entity tags, whatever the numbering.
        let key = |mm: &BoundaryMesh, i: usize| {
            let mut c: Vec<[u64; 3]> = mm.triangles[i]
                .iter()
                .map(|&v| mm.vertices[v as usize].map(f64::to_bits))
                .collect();
            c.sort();
            (c, mm.triangle_tag[i])
        };
        let mut a: Vec<_> = (0..m.triangles.len()).map(|i| key(&m, i)).collect();
        let mut b: Vec<_> = (0..reference.triangles.len())
            .map(|i| key(&reference, i))
            .collect();
        a.sort();
        b.sort();
        assert!(a == b, "{p:?} differs from the ASCII 4.1 original");
        assert_eq!(
            m.tag_names.get(&17).map(String::as_str),
            Some("F2_dangling"),
            "{p:?}"
        );
    }
}

#[test]
fn truncated_copies_of_the_real_files_are_errors_never_panics() {
    let Some(dir) = peer_dir() else { return };
    for name in [
        "region_L1_reservoir_W.off",
        "plc_L1.obj",
        "didactic_L1_surface.msh",
    ] {
        let bytes = std::fs::read(dir.join(name)).unwrap();
        let mut errors = 0;
        for k in 1..40 {
            let cut = bytes.len() * k / 40;
            if let Err(e) = read_by_extension(name, &bytes[..cut]) {
                assert_eq!(e.file, name);
                assert!(e.line >= 1, "{e}");
                errors += 1;
            }
        }
        // OBJ has no counts: a cut only fails when it leaves a dangling face line or group.
        if name.ends_with(".obj") {
            continue;
        }
        assert_eq!(errors, 39, "{name}: some truncations were accepted");
    }
}

#[test]
fn a_bad_index_in_the_real_off_names_its_line() {
    let Some(dir) = peer_dir() else { return };
    let text = std::fs::read_to_string(dir.join("region_L1_reservoir_W.off")).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let target = 2 + 1923 + 100; // 0-based index of face 100
    lines[target] = "3 0 1 999999".to_string();
    let e = read_off(lines.join("\n").as_bytes(), "res.off").unwrap_err();
    assert_eq!(e.line, target + 1, "{e}");
    assert!(
        e.to_string().starts_with(&format!(
            "res.off:{}: face 100 refers to vertex 999999",
            target + 1
        )),
        "{e}"
    );
}
