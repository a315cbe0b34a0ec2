//! A build where nothing changed, on the shipped example: it reads no mesh from the cache and
//! writes no output file, the report included; what it does not read stays repairable.

use crate::common_cli;
use common_cli::*;
use std::path::Path;
use std::time::{Duration, SystemTime};

/// A time long before any build, to tell a file written again from one left alone.
fn long_ago() -> SystemTime {
    SystemTime::UNIX_EPOCH + Duration::from_secs(1_000_000_000)
}

/// Every file of the output directory, dated [`long_ago`].
fn backdate(dir: &Path) {
    for rel in read_tree(dir).keys() {
        let f = std::fs::File::options()
            .write(true)
            .open(dir.join(rel))
            .unwrap();
        f.set_modified(long_ago()).unwrap();
    }
}

/// The files of the output directory whose date is not [`long_ago`] (written again).
fn rewritten(dir: &Path) -> Vec<String> {
    read_tree(dir)
        .into_keys()
        .filter(|rel| {
            std::fs::metadata(dir.join(rel))
                .unwrap()
                .modified()
                .unwrap()
                != long_ago()
        })
        .collect()
}

/// Flips every byte of the cached outputs of the nodes of `kinds` (lengths kept): a build that
/// read one would report it corrupt.
fn damage_outputs(s: &Scratch, report: &serde_json::Value, kinds: &[&str]) -> usize {
    let mut n = 0;
    for node in report["nodes"].as_array().unwrap() {
        if !kinds.contains(&node["kind"].as_str().unwrap()) {
            continue;
        }
        let p = s
            .path(".recipe/objects")
            .join(node["output"].as_str().unwrap());
        let bytes: Vec<u8> = std::fs::read(&p).unwrap().iter().map(|b| !b).collect();
        std::fs::write(&p, bytes).unwrap();
        n += 1;
    }
    n
}

#[test]
fn a_build_where_nothing_changed_reads_no_mesh_and_writes_no_output_file() {
    let s = Scratch::didactic_built();
    // The first build after the full one writes the report again: its steps are now cached.
    let (ok, first, err) = s.build(&[]);
    assert!(ok, "{err}");
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(s.path("out/didactic/report.json")).unwrap())
            .unwrap();
    assert_eq!(report["steps_by_state"]["cached"], 224);
    let meshes = ["surface_mesh", "tet_mesh", "mesh", "export"];
    assert_eq!(damage_outputs(&s, &first, &meshes), 32 + 6 + 1 + 1);
    let out = s.path("out/didactic");
    let before = read_tree(&out);
    backdate(&out);
    let (ok, second, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert!(!err.contains("corrupt"), "a damaged mesh was read: {err}");
    assert_eq!(nodes_in_state(&second, "ran"), Vec::<String>::new());
    assert_eq!(rewritten(&out), Vec::<String>::new());
    assert!(read_tree(&out) == before, "the outputs changed");
}

/// `report.json` of the example's output directory, every step's duration zero.
fn timeless_report(s: &Scratch) -> serde_json::Value {
    let text = std::fs::read(s.path("out/didactic/report.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_slice(&text).unwrap();
    for step in v["steps"].as_array_mut().unwrap() {
        step["duration_ms"] = 0.into();
    }
    v
}

#[test]
fn a_report_removed_or_edited_is_written_again_by_a_build_where_nothing_changed() {
    let s = Scratch::didactic_built();
    assert!(s.build(&[]).0);
    let report = timeless_report(&s);
    let out = s.path("out/didactic");
    std::fs::remove_file(out.join("report.html")).unwrap();
    std::fs::write(out.join("report.json"), b"{}").unwrap();
    backdate(&out);
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert_eq!(rewritten(&out), ["report.html", "report.json"]);
    assert!(
        timeless_report(&s) == report,
        "the same report, timings aside"
    );
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("224 steps: 224 cached."));
}
