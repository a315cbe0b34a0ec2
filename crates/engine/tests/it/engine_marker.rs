//! Only a directory the engine marked as its cache is ever cleaned, collected or built into: a
//! `--cache-dir` pointing at a recipe's folder, the working directory, `/` or a home directory
//! loses nothing.

use crate::engine_support::{Runs, konst, opts, run};
use engine::marker::{MARKER, is_cache};
use engine::*;
use std::path::Path;

/// A folder as a user has it: a recipe, its data and a hidden file.
fn users_folder(dir: &Path) {
    std::fs::write(dir.join("north.toml"), "[model]\nname = \"n\"\n").unwrap();
    std::fs::create_dir_all(dir.join("data")).unwrap();
    std::fs::write(dir.join("data/top.ts"), "GOCAD TSurf 1\n").unwrap();
    std::fs::write(dir.join(".bashrc"), "# mine\n").unwrap();
}

fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn one_node() -> BuildGraph {
    let mut g = BuildGraph::new();
    g.add_op("a", konst(1, &Runs::default()), &[]).unwrap();
    g
}

#[test]
fn clean_refuses_a_users_folder_and_touches_nothing_in_it() {
    let dir = tempfile::tempdir().unwrap();
    users_folder(dir.path());
    let before = entries(dir.path());
    let e = clean(dir.path()).unwrap_err();
    assert!(matches!(e, EngineError::NotACache { .. }), "{e}");
    assert!(
        e.to_string().contains("`.bashrc`, `data`, `north.toml`"),
        "{e}"
    );
    assert_eq!(entries(dir.path()), before, "not even a lock file was made");
}

#[test]
fn clean_and_gc_refuse_an_empty_folder_that_no_build_marked() {
    let dir = tempfile::tempdir().unwrap();
    let e = clean(dir.path()).unwrap_err();
    assert!(e.to_string().contains(MARKER), "{e}");
    assert!(gc(dir.path(), &[]).is_err());
    assert!(dir.path().exists() && entries(dir.path()).is_empty());
}

#[test]
fn clean_and_gc_refuse_the_root_directory_and_a_home_directory() {
    assert!(matches!(
        clean(Path::new("/")),
        Err(EngineError::NotACache { .. })
    ));
    assert!(gc(Path::new("/"), &[]).is_err());
    let home = tempfile::tempdir().unwrap();
    users_folder(home.path());
    std::fs::create_dir_all(home.path().join(".cache")).unwrap();
    let before = entries(home.path());
    assert!(clean(home.path()).is_err());
    assert!(gc(home.path(), &[]).is_err());
    assert_eq!(entries(home.path()), before);
}

#[test]
fn a_build_will_not_make_a_users_folder_its_cache() {
    let dir = tempfile::tempdir().unwrap();
    users_folder(dir.path());
    let before = entries(dir.path());
    let mut o = opts(dir.path(), 1);
    o.cache_dir = dir.path().to_path_buf();
    let e = build(one_node(), &o, &|_| {}).unwrap_err();
    assert!(matches!(e, EngineError::NotACache { .. }), "{e}");
    assert_eq!(entries(dir.path()), before);
}

#[test]
fn a_cache_a_build_made_is_marked_cleaned_once_then_reported_absent() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    assert!(run(one_node(), &o).ok);
    assert!(is_cache(&o.cache_dir));
    assert!(clean(&o.cache_dir).unwrap());
    assert!(!o.cache_dir.exists());
    assert!(!clean(&o.cache_dir).unwrap());
    // gc of a missing cache does nothing and creates nothing.
    assert_eq!(gc(&o.cache_dir, &[]).unwrap(), GcStats::default());
    assert!(!o.cache_dir.exists());
}

#[test]
fn a_cache_made_before_the_marker_is_adopted_by_its_next_build() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    assert!(run(one_node(), &o).ok);
    std::fs::remove_file(o.cache_dir.join(MARKER)).unwrap();
    assert!(clean(&o.cache_dir).is_err(), "unmarked: not cleaned");
    assert!(run(one_node(), &o).ok, "its entries are all a cache's own");
    assert!(is_cache(&o.cache_dir));
    assert!(clean(&o.cache_dir).unwrap());
}
