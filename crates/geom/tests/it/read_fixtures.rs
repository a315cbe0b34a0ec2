//! Small boundary files under tests/data/meshes (for the standalone mesher's tests too): what
//! each reader makes of them.

use geom::mesh::read::{BoundaryMesh, read_by_extension};

fn read(name: &str) -> Result<BoundaryMesh, geom::mesh::read::ReadError> {
    let path = concat!(
        concat!(env!("CARGO_MANIFEST_DIR"), "/../.."),
        "/tests/data/meshes/"
    );
    let bytes = std::fs::read(format!("{path}{name}")).unwrap();
    read_by_extension(name, &bytes)
}

/// Signed volume enclosed by the triangles (positive when they face outward).
fn enclosed_volume(m: &BoundaryMesh, tag: i32) -> f64 {
    let mut v = 0.0;
    for (t, &g) in m.triangles.iter().zip(&m.triangle_tag) {
        if g != tag {
            continue;
        }
        let [a, b, c] = t.map(|i| m.vertices[i as usize]);
        v += geom::predicates::signed_volume(&[0.0; 3], &a, &b, &c);
    }
    v
}

#[test]
fn the_obj_and_msh_cubes_hold_the_same_box_and_fault_under_their_names() {
    let obj = read("cube_with_fault.obj").unwrap();
    let msh = read("cube_with_fault_v22.msh").unwrap();
    assert_eq!(obj.triangles, msh.triangles);
    assert_eq!(obj.tag_names.values().collect::<Vec<_>>(), ["box", "fault"]);
    assert_eq!(msh.tag_names.get(&10).map(String::as_str), Some("box"));
    assert_eq!(msh.tag_names.get(&20).map(String::as_str), Some("fault"));
    assert!((enclosed_volume(&obj, 1) - 1.0).abs() < 1e-12);
    assert!((enclosed_volume(&msh, 10) - 1.0).abs() < 1e-12);
    assert_eq!(obj.triangle_tag.iter().filter(|&&t| t == 2).count(), 2);
}

#[test]
fn the_off_cube_of_quads_becomes_twelve_outward_triangles() {
    let off = read("cube.off").unwrap();
    assert_eq!(off.triangles.len(), 12);
    assert!((enclosed_volume(&off, 0) - 1.0).abs() < 1e-12);
}

#[test]
fn the_broken_fixtures_are_refused_with_file_and_line() {
    assert_eq!(
        read("truncated.off").unwrap_err().to_string(),
        "truncated.off:6: unexpected end of file: expected vertex 3 of 8"
    );
    assert_eq!(
        read("bad_index.obj").unwrap_err().to_string(),
        "bad_index.obj:6: face refers to vertex 4, but the file has 3 vertices"
    );
}
