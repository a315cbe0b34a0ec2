//! `explain`, `graph`, `gc` and `clean`: the commands that read or tidy the cache.

use crate::common_cli;
use common_cli::*;

fn stdout_of(s: &Scratch, args: &[&str]) -> String {
    let out = s.recipe_cmd(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn explain_names_the_recipe_value_that_changed_with_old_and_new_values() {
    let s = Scratch::didactic_built();
    s.edit("\"F2\" = { size = 100.0 }", "\"F2\" = { size = 50.0 }");
    assert!(s.build(&[]).0);
    let text = stdout_of(&s, &["explain", "didactic.toml"]);
    let line = text
        .lines()
        .find(|l| l.starts_with("discretize:F2#1"))
        .expect("the F2 curve is listed");
    assert!(
        line.contains("mesh.curves.\"F2\".size") && line.contains("100") && line.contains("50"),
        "{line}"
    );
    let import = text.lines().find(|l| l.starts_with("import:H1")).unwrap();
    assert!(import.contains("cached"), "{import}");
}

#[test]
fn explain_says_an_input_file_changed() {
    let s = Scratch::didactic_built();
    let f = s.path("data/didactic/F2_dangling.ts");
    let text = std::fs::read_to_string(&f)
        .unwrap()
        .replace("END\n", "END\n# edited\n");
    std::fs::write(&f, text).unwrap();
    assert!(s.build(&[]).0);
    let text = stdout_of(&s, &["explain", "didactic.toml"]);
    let line = text
        .lines()
        .find(|l| l.starts_with("file:F2"))
        .expect("file node listed");
    assert!(line.contains("F2_dangling.ts"), "{line}");
}

#[test]
fn graph_prints_the_expanded_dag_with_node_states() {
    let s = Scratch::didactic_built();
    let dot = stdout_of(&s, &["graph", "didactic.toml"]);
    assert!(dot.starts_with("digraph"));
    for n in [
        "import:H1",
        "intersect:F1/H1",
        "model",
        "discretize:F1/H1",
        "surface_mesh:F2#2",
        "tet_mesh:reservoir_E",
        "mesh",
        "export",
    ] {
        assert!(dot.contains(n), "`{n}` missing from the graph");
    }
}

#[test]
fn explain_before_any_build_says_to_build_first() {
    let s = Scratch::didactic();
    let out = s.recipe_cmd(&["explain", "didactic.toml"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("recipe build"));
}

#[test]
fn gc_removes_entries_of_an_old_recipe_value_and_keeps_the_current_build_cached() {
    let s = Scratch::didactic_built();
    s.edit("\"F2\" = { size = 100.0 }", "\"F2\" = { size = 50.0 }");
    assert!(s.build(&[]).0);
    let before = read_tree(&s.path(".recipe")).len();
    let out = stdout_of(&s, &["gc", "didactic.toml"]);
    assert!(out.contains("removed"), "{out}");
    let after = read_tree(&s.path(".recipe")).len();
    assert!(after < before, "gc removed nothing ({before} → {after})");
    let (ok, r, _) = s.build(&[]);
    assert!(ok);
    assert_eq!(
        nodes_in_state(&r, "ran"),
        Vec::<String>::new(),
        "what the current build needs survived gc"
    );
}

#[test]
fn clean_removes_the_cache_and_the_next_build_runs_everything() {
    let s = Scratch::didactic_built();
    stdout_of(&s, &["clean", "didactic.toml"]);
    assert!(!s.path(".recipe").exists());
    let (ok, r, _) = s.build(&[]);
    assert!(ok);
    assert_eq!(nodes_in_state(&r, "cached"), Vec::<String>::new());
}

#[test]
fn the_json_report_carries_every_node_with_key_output_and_counts() {
    let s = Scratch::didactic_built();
    let (ok, r, _) = s.build(&[]);
    assert!(ok);
    let import = r["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|n| n["name"] == "import:H1")
        .unwrap();
    for k in ["kind", "state", "reason", "duration_ms", "key", "output"] {
        assert!(!import[k].is_null(), "`{k}` missing");
    }
    assert_eq!(import["counts"]["triangles"], 3120);
    assert_eq!(import["counts"]["findings"], 0);
}

/// Every file under the scratch folder, with its bytes.
fn snapshot(s: &Scratch) -> std::collections::BTreeMap<String, Vec<u8>> {
    read_tree(s.dir.path())
}

#[test]
fn clean_pointed_at_the_recipes_folder_deletes_nothing_and_says_why() {
    let s = Scratch::didactic();
    let before = snapshot(&s);
    for args in [
        &["clean", "didactic.toml", "--cache-dir", "."][..],
        &["clean", "didactic.toml", "--cache-dir", "data"][..],
        &["gc", "didactic.toml", "--cache-dir", "."][..],
    ] {
        let out = s.recipe_cmd(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains("is not a recipe cache"), "{args:?}: {err}");
        assert_eq!(snapshot(&s), before, "{args:?} touched the folder");
    }
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_recipe"))
        .args(["clean", "didactic.toml"])
        .current_dir(s.dir.path())
        .env("RECIPE_CACHE_DIR", s.dir.path())
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert_eq!(
        snapshot(&s),
        before,
        "RECIPE_CACHE_DIR pointing at the folder"
    );
}

#[test]
fn a_build_refuses_a_cache_dir_that_holds_the_users_files() {
    let s = Scratch::didactic();
    let before = snapshot(&s);
    let out = s.recipe_cmd(&["build", "--cache-dir", ".", "didactic.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("`didactic.toml`") && err.contains("not a recipe cache"),
        "{err}"
    );
    assert_eq!(snapshot(&s), before);
}

#[test]
fn clean_says_when_there_was_nothing_to_remove() {
    let s = Scratch::didactic();
    let out = stdout_of(&s, &["clean", "didactic.toml"]);
    assert!(out.contains("nothing to remove"), "{out}");
}

#[test]
fn gc_on_a_missing_cache_says_so_and_creates_nothing() {
    let s = Scratch::didactic();
    let out = stdout_of(&s, &["gc", "didactic.toml"]);
    assert!(out.contains("nothing to collect"), "{out}");
    assert!(!s.path(".recipe").exists(), "gc created the cache");
}

#[test]
fn an_unreadable_last_build_record_is_not_reported_as_missing() {
    let s = Scratch::didactic_built();
    let record = s.path(".recipe/last-report.json");
    std::fs::remove_file(&record).unwrap();
    std::fs::create_dir(&record).unwrap();
    let out = s.recipe_cmd(&["explain", "didactic.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("cannot read the last build's record"), "{err}");
    assert!(!err.contains("no build recorded"), "{err}");
}

#[test]
fn an_unreadable_lock_file_is_not_reported_as_missing() {
    let s = Scratch::didactic_built();
    let lock = s.path("didactic.toml.lock");
    std::fs::remove_file(&lock).unwrap();
    std::fs::create_dir(&lock).unwrap();
    let out = s.recipe_cmd(&["build", "--locked", "--quiet", "didactic.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("cannot be read"), "{err}");
    assert!(!err.contains("there is no lock file"), "{err}");
}
