//! Damaged inputs: the readers return errors (naming the file) and never panic, whatever bytes
//! they are given.

use test_support::export_support;

use export::{Format, export};
use export_support::layered_box;
use geom::mesh::read::{read_by_extension, read_msh, read_obj, read_off, read_volume_msh};
use proptest::prelude::*;

const OFF: &str = "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n4 0 1 3 2\n";
const OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ng a\nf 1 2 3\ng b\nf -1 -2 -4 -3\n";

fn small_msh(binary: bool) -> Vec<u8> {
    let f = if binary {
        Format::MshBinary
    } else {
        Format::Msh
    };
    export(&layered_box(4, 3), "s", f).unwrap().remove(0).1
}

fn damage(mut bytes: Vec<u8>, edits: &[(usize, u8)], cut: usize) -> Vec<u8> {
    for &(at, b) in edits {
        if !bytes.is_empty() {
            let i = at % bytes.len();
            bytes[i] = b;
        }
    }
    bytes.truncate(cut.min(bytes.len()));
    bytes
}

proptest! {
    // FUZZ_CASES sets the count (`.ci/run` runs a longer, bounded hunt).
    #![proptest_config(test_support::proptest_config(test_support::fuzz_cases(96)))]

    #[test]
    fn damaged_off_and_obj_never_panic(edits in prop::collection::vec((0usize..200, any::<u8>()), 0..6), cut in 0usize..200) {
        let off = damage(OFF.as_bytes().to_vec(), &edits, cut);
        if let Err(e) = read_off(&off, "d.off") { prop_assert_eq!(e.file, "d.off"); }
        let obj = damage(OBJ.as_bytes().to_vec(), &edits, cut);
        if let Err(e) = read_obj(&obj, "d.obj") { prop_assert_eq!(e.file, "d.obj"); }
    }

    #[test]
    fn damaged_msh_never_panics(edits in prop::collection::vec((0usize..1_000_000, any::<u8>()), 1..8), binary: bool) {
        let bytes = small_msh(binary);
        let len = bytes.len();
        let bad = damage(bytes, &edits, len);
        let _ = read_msh(&bad, "d.msh");
        let _ = read_volume_msh(&bad, "d.msh");
    }

    #[test]
    fn any_bytes_give_an_error_or_a_mesh(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        for name in ["x.off", "x.obj", "x.msh"] {
            if let Ok(m) = read_by_extension(name, &bytes) {
                prop_assert!(m.triangles.iter().flatten().all(|&v| (v as usize) < m.vertices.len()));
            }
        }
    }
}

#[test]
fn a_polygon_with_two_vertices_is_refused_on_its_line() {
    let e = read_off(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "two.off").unwrap_err();
    assert_eq!(
        e.to_string(),
        "two.off:6: face 0 has 2 vertices; at least 3 are needed"
    );
}

#[test]
fn an_msh_without_mesh_format_is_not_taken_for_one() {
    let e = read_msh(b"$Nodes\n0\n$EndNodes\n", "n.msh").unwrap_err();
    assert_eq!(e.line, 1);
    assert!(e.message.contains("before $MeshFormat"), "{e}");
}

#[test]
fn an_msh_with_only_tets_has_no_boundary_triangles_to_give() {
    let mut mesh = layered_box(4, 3);
    mesh.triangles.clear();
    mesh.triangle_group.clear();
    let bytes = export(&mesh, "t", Format::Msh).unwrap().remove(0).1;
    let e = read_msh(&bytes, "t.msh").unwrap_err();
    assert!(e.message.contains("no triangles"), "{e}");
    assert_eq!(
        read_volume_msh(&bytes, "t.msh").unwrap().tets.len(),
        mesh.tets.len()
    );
}
