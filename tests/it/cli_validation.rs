//! What `recipe build` says about the imported surfaces' validation: what repair removed and what
//! remains, printed and in `validation.json`, which a build that fails later still writes.

use crate::common_cli;
use common_cli::*;

/// Two triangles sharing an edge through a duplicate of vertex 2 (7), which repair merges, and
/// a third triangle crossing the first, which repair cannot change.
const CROSSING: &str = "GOCAD TSurf 1
HEADER {
name:crossing
}
TFACE
VRTX 1 0 0 0
VRTX 2 10 0 0
VRTX 3 0 10 0
VRTX 4 2 2 -5
VRTX 5 3 3 5
VRTX 6 2 4 5
VRTX 7 10 0 0
VRTX 8 10 10 0
TRGL 1 2 3
TRGL 4 5 6
TRGL 3 7 8
END
";

fn validation(s: &Scratch, dir: &str) -> serde_json::Value {
    let path = s.path(dir).join("validation.json");
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_slice(&bytes).unwrap()
}

#[test]
fn a_self_intersection_that_repair_cannot_remove_is_reported_as_remaining() {
    let s = Scratch::didactic();
    std::fs::write(s.path("crossing.ts"), CROSSING).unwrap();
    std::fs::write(
        s.path("crossing.toml"),
        "[model]\nname = \"crossing\"\n\n[surfaces]\nbad = \"crossing.ts\"\n\n\
         [mesh]\nsize = 2.0\n\n[output]\ndir = \"out/crossing\"\n",
    )
    .unwrap();
    let out = s.recipe_cmd(&["build", "crossing.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    let summary = "2 validation findings: 1 repaired (1 duplicate vertex), \
                   1 remains (1 self-intersection)";
    assert!(
        err.contains(&format!("surface `bad`: {summary}")),
        "the warning says what remains: {err}"
    );
    assert!(!err.contains("(repaired)"), "{err}");
    let v = &validation(&s, "out/crossing")["bad"];
    assert_eq!(v["summary"], summary, "{v:#}");
    assert_eq!(v["counts"]["duplicate_vertex"], 1);
    assert_eq!(v["counts"]["self_intersection"], 1);
    assert_eq!(v["repaired"]["duplicate_vertex"], 1);
    assert_eq!(v["repaired"]["self_intersection"], 0);
    assert_eq!(v["remaining"]["duplicate_vertex"], 0);
    assert_eq!(v["remaining"]["self_intersection"], 1);
}

#[test]
fn a_build_that_fails_after_the_imports_still_writes_validation_json() {
    let s = Scratch::didactic();
    // A trim that discards nothing fails the `model` node, before anything is exported.
    add_a_trim_that_discards_nothing(&s);
    model_fails_saying(&s, &[], &[]);
    let v = validation(&s, "out/didactic");
    let names: Vec<&String> = v.as_object().unwrap().keys().collect();
    assert_eq!(names, ["F1", "F2", "H1", "H2"]);
    assert_eq!(v["H1"]["summary"], "clean");
    assert_eq!(v["H1"]["clean"], true);
}

#[test]
fn a_surface_that_was_not_imported_is_in_validation_json_with_the_reason() {
    let s = Scratch::didactic();
    let f = s.path("data/didactic/F2_dangling.ts");
    let text = std::fs::read_to_string(&f)
        .unwrap()
        .replacen("TRGL 1 ", "TRGL 99999 ", 1);
    std::fs::write(f, text).unwrap();
    let (ok, _, _) = s.build(&[]);
    assert!(!ok);
    let v = validation(&s, "out/didactic");
    let why = v["F2"]["error"].as_str().expect("an error");
    assert!(why.contains("F2_dangling.ts:"), "{why}");
    assert_eq!(v["F1"]["summary"], "clean");
}
