//! `recipe tetmesh` on the thin (35 m) reservoir layer as full builds of the didactic
//! model cut it. Each case must mesh (the exact `verify` inside the mesher passes) and, when the
//! independent checker is available, pass `check_mesh.py` too.

use crate::common_cli::checker;
use std::path::PathBuf;
use std::process::Command;
use test_support::paths;

fn case_dir(case: &str) -> PathBuf {
    paths::data("tet_mesh/thin_layers").join(case)
}

fn mesh_case(case: &str, region: &str, embedded: bool) {
    let dir = case_dir(case);
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join(format!("{case}.msh"));
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_recipe"));
    cmd.arg("tetmesh").arg(dir.join(format!("{region}.off")));
    if embedded {
        cmd.arg("--embed")
            .arg(dir.join(format!("{region}.embedded.off")));
    }
    let run = cmd.arg("-o").arg(&out).output().unwrap();
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{case}: {err}");
    assert!(out.is_file(), "{case}: no mesh written");
    if let Some(check) = checker() {
        let res = Command::new("python3")
            .arg(check)
            .arg(&out)
            .args(["--regions", "1"])
            .output()
            .unwrap();
        assert!(
            res.status.success(),
            "{case}: check_mesh.py failed:\n{}",
            String::from_utf8_lossy(&res.stdout)
        );
    }
}

#[test]
fn the_east_reservoir_block_with_500_m_triangles_on_a_35_m_layer_meshes_and_verifies() {
    mesh_case("resE_size500", "reservoir_E", true);
}

#[test]
fn the_refined_east_reservoir_block_meshes_past_the_box_corner_and_verifies() {
    mesh_case("resE_refb", "reservoir_E", true);
}

#[test]
fn the_east_reservoir_block_of_the_f2_75_build_meshes_and_verifies() {
    mesh_case("resE_f2_75", "reservoir_E", true);
}

#[test]
fn the_west_reservoir_block_with_500_m_triangles_meshes_and_verifies() {
    mesh_case("resW_size500", "reservoir_W", false);
}
