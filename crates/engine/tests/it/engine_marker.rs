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
    assert_eq!(clean(&o.cache_dir).unwrap(), Cleaned::Removed);
    assert!(!o.cache_dir.exists());
    assert_eq!(clean(&o.cache_dir).unwrap(), Cleaned::Absent);
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
    assert_eq!(clean(&o.cache_dir).unwrap(), Cleaned::Removed);
}

#[test]
fn a_folder_named_like_a_cache_at_its_top_but_holding_a_users_files_is_not_adopted() {
    // Each time the top names are only a cache's, and something below is the user's.
    let hash = "0123456789abcdef".repeat(4);
    let mine: [&[&str]; 5] = [
        &["objects/photo.jpg"],
        &["records/thesis.txt"],
        &["records/r/notes.txt", "records/r/manifest.bin"],
        &["actions/keep/draft.md"],
        &["lock", "objects/ABCDEF.txt"],
    ];
    for files in mine {
        let dir = tempfile::tempdir().unwrap();
        for f in files.iter().chain([&format!("objects/{hash}").as_str()]) {
            let p = dir.path().join(f);
            std::fs::create_dir_all(p.parent().unwrap()).unwrap();
            std::fs::write(&p, "mine").unwrap();
        }
        let mut o = opts(dir.path(), 1);
        o.cache_dir = dir.path().to_path_buf();
        let e = build(one_node(), &o, &|_| {}).unwrap_err();
        assert!(matches!(e, EngineError::NotACache { .. }), "{files:?}: {e}");
        let named = files
            .iter()
            .find(|f| !f.ends_with("manifest.bin") && **f != "lock");
        let named = named
            .unwrap()
            .split('/')
            .take(2)
            .collect::<Vec<_>>()
            .join("/");
        assert!(e.to_string().contains(&named), "{files:?}: {e}");
        assert!(clean(dir.path()).is_err() && gc(dir.path(), &[]).is_err());
        for f in files {
            assert_eq!(std::fs::read(dir.path().join(f)).unwrap(), b"mine", "{f}");
        }
    }
}

#[cfg(unix)]
#[test]
fn a_link_among_a_caches_entries_is_not_a_caches_own() {
    let dir = tempfile::tempdir().unwrap();
    let theirs = tempfile::tempdir().unwrap();
    std::fs::write(theirs.path().join("thesis.txt"), "mine").unwrap();
    std::fs::create_dir_all(dir.path().join("objects")).unwrap();
    let link = dir
        .path()
        .join("objects")
        .join("0123456789abcdef".repeat(4));
    std::os::unix::fs::symlink(theirs.path().join("thesis.txt"), link).unwrap();
    let mut o = opts(dir.path(), 1);
    o.cache_dir = dir.path().to_path_buf();
    let e = build(one_node(), &o, &|_| {}).unwrap_err();
    assert!(e.to_string().contains("(a link)"), "{e}");
    assert_eq!(
        std::fs::read(theirs.path().join("thesis.txt")).unwrap(),
        b"mine"
    );
}

/// Cargo's tag, as it writes it in `target/`: the convention's signature, another owner.
const CARGOS_TAG: &str = "Signature: 8a477f597d28d172789f06886806bc55\n\
    # This file is a cache directory tag created by cargo.\n\
    # For information about cache directory tags see https://bford.info/cachedir/\n";

#[test]
fn a_folder_another_program_tagged_as_its_cache_is_neither_cleaned_collected_nor_built_into() {
    // Cargo's `target/`, or a folder its owner tagged to keep it out of backups.
    for extra in [&[][..], &["objects/notes.txt"][..]] {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join(MARKER), CARGOS_TAG).unwrap();
        for f in extra {
            let p = dir.path().join(f);
            std::fs::create_dir_all(p.parent().unwrap()).unwrap();
            std::fs::write(p, "mine").unwrap();
        }
        assert!(!is_cache(dir.path()));
        let e = clean(dir.path()).unwrap_err();
        assert!(matches!(e, EngineError::NotACache { .. }), "{e}");
        assert!(e.to_string().contains("not ours"), "{e}");
        assert!(gc(dir.path(), &[]).is_err());
        let mut o = opts(dir.path(), 1);
        o.cache_dir = dir.path().to_path_buf();
        assert!(build(one_node(), &o, &|_| {}).is_err());
        assert_eq!(
            std::fs::read_to_string(dir.path().join(MARKER)).unwrap(),
            CARGOS_TAG
        );
        for f in extra {
            assert_eq!(std::fs::read(dir.path().join(f)).unwrap(), b"mine");
        }
    }
}

/// Writes "mine" at each of `files` under `dir`.
fn put(dir: &Path, files: &[&str]) {
    for f in files {
        let p = dir.join(f);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, "mine").unwrap();
    }
}

#[test]
fn clean_removes_a_caches_own_entries_and_leaves_the_files_a_user_put_inside_it() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    assert!(run(one_node(), &o).ok);
    let mine = ["notes.txt", "objects/photo.jpg", "records/x/draft.md"];
    put(&o.cache_dir, &mine);
    let left = match clean(&o.cache_dir).unwrap() {
        Cleaned::Kept(left) => left,
        other => panic!("{other:?}"),
    };
    assert_eq!(
        left,
        ["notes.txt", "objects/photo.jpg", "records/x/draft.md"]
    );
    for f in mine {
        assert_eq!(std::fs::read(o.cache_dir.join(f)).unwrap(), b"mine", "{f}");
    }
    // Nothing of the cache is left: no marker, lock, manifest, entry or record file.
    assert_eq!(entries(&o.cache_dir), ["notes.txt", "objects", "records"]);
    assert_eq!(entries(&o.cache_dir.join("objects")), ["photo.jpg"]);
    assert_eq!(entries(&o.cache_dir.join("records")), ["x"]);
    assert!(!is_cache(&o.cache_dir));
    // And with no marker left, the folder is the user's: it is not cleaned again.
    assert!(clean(&o.cache_dir).is_err());
}

#[test]
fn gc_and_forget_remove_only_store_entries_and_record_files_never_a_users_file_among_them() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    assert!(run(one_node(), &o).ok);
    let record = format!("records/{}", o.record);
    let mine = [
        "objects/photo.jpg".to_string(),
        "actions/notes".to_string(),
        format!("{record}/draft.md"),
    ];
    let mine: Vec<&str> = mine.iter().map(String::as_str).collect();
    put(&o.cache_dir, &mine);
    std::fs::create_dir_all(o.cache_dir.join("objects/album")).unwrap();
    assert!(forget(&o.cache_dir, &o.record).unwrap());
    let stats = gc(&o.cache_dir, &[]).unwrap();
    assert!(stats.removed >= 2, "{stats:?}");
    for f in &mine {
        assert_eq!(std::fs::read(o.cache_dir.join(f)).unwrap(), b"mine", "{f}");
    }
    assert_eq!(
        entries(&o.cache_dir.join("objects")),
        ["album", "photo.jpg"]
    );
    assert_eq!(entries(&o.cache_dir.join("actions")), ["notes"]);
    assert_eq!(entries(&o.cache_dir.join(&record)), ["draft.md"]);
}

#[cfg(unix)]
#[test]
fn a_fifo_or_a_link_in_place_of_the_marker_marks_nothing_and_blocks_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    assert!(run(one_node(), &o).ok);
    let marker = o.cache_dir.join(MARKER);
    let text = std::fs::read(&marker).unwrap();
    std::fs::remove_file(&marker).unwrap();
    let status = std::process::Command::new("mkfifo").arg(&marker).status();
    if status.is_ok_and(|s| s.success()) {
        // Were the FIFO opened, the test would hang here: no writer ever comes.
        assert!(!is_cache(&o.cache_dir));
        assert!(clean(&o.cache_dir).is_err());
        std::fs::remove_file(&marker).unwrap();
    }
    let real = dir.path().join("real-tag");
    std::fs::write(&real, text).unwrap();
    std::os::unix::fs::symlink(&real, &marker).unwrap();
    assert!(
        !is_cache(&o.cache_dir),
        "a link is not the cache's own marker"
    );
    assert!(clean(&o.cache_dir).is_err());
    assert!(o.cache_dir.join("objects").exists());
}
