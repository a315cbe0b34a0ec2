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
fn clean_and_gc_pointed_at_a_folder_another_program_tagged_delete_nothing() {
    // Cargo's `target/` carries the same cache tag, with another owner's line.
    let s = Scratch::didactic();
    let target = s.path("target");
    std::fs::create_dir_all(target.join("release")).unwrap();
    std::fs::write(
        target.join("CACHEDIR.TAG"),
        "Signature: 8a477f597d28d172789f06886806bc55\n# This file is a cache directory tag created by cargo.\n",
    )
    .unwrap();
    std::fs::write(target.join("release/recipe"), "a binary").unwrap();
    let before = snapshot(&s);
    for cmd in ["clean", "gc"] {
        let out = s.recipe_cmd(&[cmd, "didactic.toml", "--cache-dir", "target"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{cmd}: {err}");
        assert!(err.contains("is not a recipe cache"), "{cmd}: {err}");
        assert_eq!(snapshot(&s), before, "{cmd} touched the folder");
    }
}

#[test]
fn clean_leaves_a_file_the_user_put_in_the_cache_and_names_it() {
    let s = Scratch::didactic_built();
    std::fs::write(s.path(".recipe/notes.txt"), "mine").unwrap();
    let out = stdout_of(&s, &["clean", "didactic.toml"]);
    assert!(
        out.contains("removed the cache's entries") && out.contains("`notes.txt`"),
        "{out}"
    );
    assert_eq!(
        std::fs::read_to_string(s.path(".recipe/notes.txt")).unwrap(),
        "mine"
    );
    let left: Vec<_> = std::fs::read_dir(s.path(".recipe")).unwrap().collect();
    assert_eq!(left.len(), 1, "only the user's file is left");
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
    let record = s.record_of("didactic.toml").join("last-report.json");
    std::fs::remove_file(&record).unwrap();
    std::fs::create_dir(&record).unwrap();
    let out = s.recipe_cmd(&["explain", "didactic.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("is damaged: a directory, not a file"), "{err}");
    assert!(err.contains("run `recipe build didactic.toml`"), "{err}");
    assert!(!err.contains("no build recorded"), "{err}");
    next_build_records_it_again(&s);
}

/// The next build writes the last build's record anew, and `explain` reads it.
fn next_build_records_it_again(s: &Scratch) {
    let (ok, _, err) = s.build(&["--quiet"]);
    assert!(ok, "{err}");
    let out = s.recipe_cmd(&["explain", "didactic.toml"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_last_build_record_with_a_flipped_byte_is_refused_as_damaged_not_printed() {
    let s = Scratch::didactic_built();
    for (file, command) in [("last-report.json", "explain"), ("last-graph.dot", "graph")] {
        let record = s.record_of("didactic.toml").join(file);
        let mut bytes = std::fs::read(&record).unwrap();
        let at = bytes.len() / 2;
        bytes[at] ^= 0x04;
        std::fs::write(&record, &bytes).unwrap();
        let out = s.recipe_cmd(&[command, "didactic.toml"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{command}: {err}");
        assert!(out.stdout.is_empty(), "{command} printed a damaged record");
        assert!(err.contains("is damaged"), "{command}: {err}");
        assert!(
            err.contains("run `recipe build didactic.toml`"),
            "{command}: {err}"
        );
    }
    next_build_records_it_again(&s);
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

#[cfg(unix)]
#[test]
fn a_fifo_or_a_device_link_in_place_of_the_lock_file_is_named_and_blocks_nothing() {
    let s = Scratch::didactic_built();
    let lock = s.path("didactic.toml.lock");
    let make = |what: &str, p: &std::path::Path| match what {
        "a device" => std::os::unix::fs::symlink("/dev/zero", p).is_ok(),
        _ => (std::process::Command::new("mkfifo").arg(p).status()).is_ok_and(|st| st.success()),
    };
    for what in ["a FIFO (a named pipe)", "a device"] {
        std::fs::remove_file(&lock).unwrap();
        if !make(what, &lock) {
            eprintln!("skipped {what}: cannot make one here");
            std::fs::write(&lock, "").unwrap();
            continue;
        }
        let said = format!("it is {what}, not a file");
        // Named at once, by the build that checks the lock and by gc, which reads it too.
        for args in [
            &["build", "--locked", "--quiet", "didactic.toml"][..],
            &["gc", "didactic.toml"],
        ] {
            let out = s.recipe_cmd(args);
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
            assert!(
                err.contains(&said) && err.contains("didactic.toml.lock"),
                "{args:?}: {err}"
            );
        }
        // A build that writes the lock puts a lock file in its place.
        let out = s.recipe_cmd(&["build", "--quiet", "didactic.toml"]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            std::fs::symlink_metadata(&lock).unwrap().is_file(),
            "{what}"
        );
        assert!(
            s.recipe_cmd(&["build", "--locked", "--quiet", "didactic.toml"])
                .status
                .success()
        );
    }
}

/// Writes `other.toml` beside the example: the same model with another size for one region
/// (so the two recipes share every node but that region's, the mesh and the export) and its own
/// output directory; it shares the example's cache `.recipe/`.
fn other_recipe(s: &Scratch) {
    let text = std::fs::read_to_string(s.recipe())
        .unwrap()
        .replacen(
            "[regions]",
            "[mesh.regions.underburden_W]\nsize = 150.0\n\n[regions]",
            1,
        )
        .replacen("dir = \"out/didactic\"", "dir = \"out/other\"", 1);
    assert!(
        text.contains("out/other"),
        "the example's output directory moved"
    );
    std::fs::write(s.path("other.toml"), text).unwrap();
}

/// The nodes in which the example and `other.toml` differ.
const DIFFERING: [&str; 3] = ["tet_mesh:underburden_W", "mesh", "export"];

#[test]
fn gc_after_another_recipe_built_into_the_same_cache_keeps_what_each_recipes_lock_or_last_build_references()
 {
    let s = Scratch::didactic_built();
    other_recipe(&s);
    let (ok, r, err) = s.build_recipe("other.toml", &[]);
    assert!(ok, "{err}");
    let ran = nodes_in_state(&r, "ran");
    for n in DIFFERING {
        assert!(ran.contains(&n.to_string()), "`{n}` did not run: {ran:?}");
    }
    // The other recipe is kept by its last build alone; the example by its lock and last build.
    std::fs::remove_file(s.path("other.toml.lock")).unwrap();
    let out = stdout_of(&s, &["gc", "didactic.toml"]);
    assert!(out.contains("kept"), "{out}");
    let (ok, a, err) = s.build(&[]);
    assert!(ok, "{err}");
    for n in DIFFERING {
        assert_eq!(
            a["nodes"]
                .as_array()
                .unwrap()
                .iter()
                .find(|x| x["name"] == n)
                .unwrap()["state"],
            "cached",
            "`{n}` of the example re-ran after gc"
        );
    }
    assert_eq!(nodes_in_state(&a, "ran"), Vec::<String>::new());
    let (ok, b, err) = s.build_recipe("other.toml", &[]);
    assert!(ok, "{err}");
    assert_eq!(nodes_in_state(&b, "ran"), Vec::<String>::new());
}

#[test]
fn explain_after_another_recipe_built_into_the_same_cache_compares_against_the_recipes_own_last_build()
 {
    let s = Scratch::didactic_built();
    other_recipe(&s);
    assert!(s.build_recipe("other.toml", &[]).0);
    // The example's last build is still its own (its full first build), not the other's.
    let text = stdout_of(&s, &["explain", "didactic.toml"]);
    assert!(!text.contains("150"), "{text}");
    let line = |text: &str| {
        text.lines()
            .find(|l| l.starts_with("tet_mesh:underburden_W "))
            .unwrap_or_else(|| panic!("the region is listed: {text}"))
            .to_string()
    };
    assert!(line(&text).contains("new node"), "{}", line(&text));
    // An edit of the example is explained against the example's last build: from the global
    // size to 140, never from the other recipe's 150.
    s.edit(
        "[regions]",
        "[mesh.regions.underburden_W]\nsize = 140.0\n\n[regions]",
    );
    let (ok, _, err) = s.build(&["--explain"]);
    assert!(ok, "{err}");
    let built = err
        .lines()
        .find(|l| l.contains("tet_mesh:underburden_W"))
        .unwrap_or_else(|| panic!("the region re-ran: {err}"));
    for said in [
        built.to_string(),
        line(&stdout_of(&s, &["explain", "didactic.toml"])),
    ] {
        assert!(
            said.contains("mesh.regions.underburden_W.size: (none) → 140") && !said.contains("150"),
            "{said}"
        );
    }
}

/// A recipe importing one small surface `name` (no box: nothing is meshed, the build is quick).
fn small_recipe(dir: &std::path::Path, name: &str) {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(
        dir.join("s.ts"),
        "GOCAD TSurf 1\nHEADER {\nname:s\n}\nTFACE\nVRTX 1 0 0 0\nVRTX 2 10 0 0\n\
         VRTX 3 0 10 0\nVRTX 4 10 10 1\nTRGL 1 2 3\nTRGL 2 4 3\nEND\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("r.toml"),
        format!(
            "[model]\nname = \"{name}\"\n\n[surfaces]\n{name} = \"s.ts\"\n\n\
             [mesh]\nsize = 2.0\n\n[output]\ndir = \"out\"\n"
        ),
    )
    .unwrap();
}

#[test]
fn recipes_of_one_file_name_in_two_folders_sharing_a_cache_dir_keep_their_own_records_and_gc_forgets_a_deleted_ones()
 {
    let s = Scratch::didactic();
    small_recipe(&s.path("a"), "top");
    small_recipe(&s.path("b"), "base");
    let cache = ["--cache-dir", "shared-cache"];
    for r in ["a/r.toml", "b/r.toml"] {
        let (ok, _, err) = s.build_recipe(r, &cache);
        assert!(ok, "{r}: {err}");
    }
    let records = std::fs::read_dir(s.path("shared-cache/records"))
        .unwrap()
        .count();
    assert_eq!(records, 2);
    let a = stdout_of(&s, &["explain", "a/r.toml", "--cache-dir", "shared-cache"]);
    let b = stdout_of(&s, &["explain", "b/r.toml", "--cache-dir", "shared-cache"]);
    assert!(
        a.contains("import:top") && !a.contains("import:base"),
        "{a}"
    );
    assert!(
        b.contains("import:base") && !b.contains("import:top"),
        "{b}"
    );
    // b's recipe is deleted: the next gc forgets its record and what only it referenced.
    std::fs::remove_dir_all(s.path("b")).unwrap();
    let out = stdout_of(&s, &["gc", "a/r.toml", "--cache-dir", "shared-cache"]);
    assert!(
        out.contains("forgot the last build of") && out.contains("r.toml"),
        "{out}"
    );
    let removed: u64 = out
        .split("removed ")
        .nth(1)
        .and_then(|t| t.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{out}"));
    assert!(removed > 0, "{out}");
    let records = std::fs::read_dir(s.path("shared-cache/records"))
        .unwrap()
        .count();
    assert_eq!(records, 1);
    let (ok, r, err) = s.build_recipe("a/r.toml", &cache);
    assert!(ok, "{err}");
    assert_eq!(nodes_in_state(&r, "ran"), Vec::<String>::new());
}

#[test]
fn a_build_that_finds_the_cache_locked_waits_and_writes_nothing_until_it_has_the_lock() {
    let s = Scratch::didactic_built();
    s.edit("size = 200.0", "size = 190.0");
    let lock_file = s.path("didactic.toml.lock");
    let report = s.path("out/didactic/report.json");
    let before = (
        std::fs::read(&lock_file).unwrap(),
        std::fs::read(&report).unwrap(),
    );
    let held = engine::DirLock::acquire(&s.path(".recipe"), |_| {}).expect("the cache's lock");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_recipe"))
        .args(["build", "--quiet", "didactic.toml"])
        .current_dir(s.path(""))
        .env_remove("RECIPE_CACHE_DIR")
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run recipe");
    std::thread::sleep(std::time::Duration::from_millis(1500));
    assert!(
        child.try_wait().unwrap().is_none(),
        "the build did not wait"
    );
    assert_eq!(
        std::fs::read(&lock_file).unwrap(),
        before.0,
        "lock file written"
    );
    assert_eq!(std::fs::read(&report).unwrap(), before.1, "report written");
    drop(held);
    let out = child.wait_with_output().expect("the build ends");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_ne!(
        std::fs::read(&lock_file).unwrap(),
        before.0,
        "the edit reached the lock"
    );
    // What it wrote is what a locked build of the same recipe accepts.
    let (ok, _, err) = s.build(&["--locked"]);
    assert!(ok, "{err}");
}

/// The files a build leaves that must agree: its lock file, its mesh and its report's tet count.
fn build_state(s: &Scratch) -> (Vec<u8>, Vec<u8>, u64) {
    let report = std::fs::read(s.path("out/didactic/report.json")).expect("the report");
    let report: serde_json::Value = serde_json::from_slice(&report).expect("JSON");
    (
        std::fs::read(s.path("didactic.toml.lock")).expect("the lock file"),
        std::fs::read(s.path("out/didactic/didactic.msh")).expect("the mesh"),
        report["counts"]["tets"].as_u64().expect("a tet count"),
    )
}

#[test]
fn two_builds_of_two_versions_racing_leave_the_outputs_lock_and_report_of_one_of_them() {
    let old = "\"F2\" = { size = 100.0 }";
    let new = ["60.0", "70.0", "80.0"].map(|v| format!("\"F2\" = {{ size = {v} }}"));
    // Each version's files, built alone.
    let alone = |version: &str| {
        let s = Scratch::didactic_built();
        s.edit(old, version);
        let (ok, _, err) = s.build(&[]);
        assert!(ok, "{err}");
        build_state(&s)
    };
    let before = build_state(&Scratch::didactic_built());
    let s = Scratch::didactic_built();
    let spawn = || {
        std::process::Command::new(env!("CARGO_BIN_EXE_recipe"))
            .args(["build", "--quiet", "didactic.toml"])
            .current_dir(s.path(""))
            .env_remove("RECIPE_CACHE_DIR")
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("run recipe")
    };
    // Each round: the slow build of a new version, then, while it runs, the cached build of the
    // old one, which waits for the lock and finishes fast, just as the first one writes its last
    // files. Which one wins is the lock's to say, and may differ between rounds.
    for version in &new {
        let states = [before.clone(), alone(version)];
        assert_ne!(states[0].2, states[1].2, "the versions differ");
        s.edit(old, version);
        let slow = spawn();
        std::thread::sleep(std::time::Duration::from_millis(300));
        s.edit(version, old);
        let fast = spawn();
        for child in [slow, fast] {
            let out = child.wait_with_output().expect("the build ends");
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(out.status.success(), "{err}");
        }
        let now = build_state(&s);
        let won = states
            .iter()
            .position(|st| st.1 == now.1)
            .expect("the mesh is one version's");
        assert!(
            now.0 == states[won].0,
            "{version}: the lock is the mesh's version's"
        );
        assert_eq!(
            now.2, states[won].2,
            "{version}: the report is the mesh's version's"
        );
    }
}

/// Plants what a killed build of the example leaves (temporaries beside the output, the lock file
/// and in the record, a staging directory of a process that is gone) and a user's `.tmp-notes`.
fn plant_debris(s: &Scratch) {
    let record = s.record_of("didactic.toml");
    let left = [
        s.path("out/didactic/.tmp-didactic.msh.Ab12Cd"),
        s.path(".tmp-didactic.toml.lock.Zz9Yy8"),
        record.join(".tmp-last-report.json.q1w2e3"),
    ];
    for f in &left {
        std::fs::write(f, b"partial").unwrap();
    }
    let staging = s.path("out/.tmp-didactic-x1y2z3");
    std::fs::create_dir_all(&staging).unwrap();
    std::fs::write(staging.join(".georecipe-staging"), u32::MAX.to_string()).unwrap();
    std::fs::write(staging.join("didactic.msh"), b"partial").unwrap();
    std::fs::write(s.path("out/didactic/.tmp-notes"), b"the user's").unwrap();
}

#[test]
fn gc_removes_what_killed_builds_of_every_recorded_recipe_left_and_nothing_of_the_users() {
    let s = Scratch::didactic_built();
    // A second recipe in another folder, sharing the cache, with its own output directory.
    std::fs::create_dir_all(s.path("other")).unwrap();
    let text = std::fs::read_to_string(s.recipe()).unwrap();
    let other = text
        .replace("data/didactic/", "../data/didactic/")
        .replace("dir = \"out/didactic\"", "dir = \"results/didactic\"");
    std::fs::write(s.path("other/r.toml"), other).unwrap();
    let (ok, _, err) = s.build_recipe("other/r.toml", &["--cache-dir", ".recipe"]);
    assert!(ok, "{err}");
    plant_debris(&s);
    std::fs::write(
        s.path("other/results/didactic/.tmp-didactic.vtu.Qq1Ww2"),
        b"partial",
    )
    .unwrap();
    std::fs::write(s.path("other/.tmp-r.toml.lock.Ee3Rr4"), b"partial").unwrap();
    assert_eq!(debris(&s).len(), 6, "{:?}", debris(&s));
    let out = s.recipe_cmd(&["gc", "didactic.toml"]);
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(debris(&s), Vec::<String>::new());
    assert!(said.contains("removed 6 temporaries"), "{said}");
    assert!(
        s.path("out/didactic/.tmp-notes").exists(),
        "a user's file stays"
    );
}

#[test]
fn the_next_build_removes_what_killed_builds_left_and_nothing_of_the_users() {
    let s = Scratch::didactic_built();
    plant_debris(&s);
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert_eq!(debris(&s), Vec::<String>::new());
    assert!(
        s.path("out/didactic/.tmp-notes").exists(),
        "a user's file stays"
    );

    // A --locked build killed at some moment of its run: whatever it left, the next one clears.
    for delay_ms in [150, 600] {
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_recipe"))
            .args([
                "build",
                "--locked",
                "--quiet",
                "--cache-dir",
                "fresh",
                "didactic.toml",
            ])
            .current_dir(s.path(""))
            .spawn()
            .expect("run recipe");
        std::thread::sleep(std::time::Duration::from_millis(delay_ms));
        let _ = child.kill();
        let _ = child.wait();
        let (ok, _, err) = s.build(&["--cache-dir", "fresh"]);
        assert!(ok, "{err}");
        let left: Vec<String> = debris(&s)
            .into_iter()
            .filter(|p| !p.contains("/fresh/"))
            .collect();
        assert_eq!(left, Vec::<String>::new(), "after a kill at {delay_ms} ms");
    }
}

#[test]
fn a_build_killed_at_any_moment_leaves_nothing_that_the_next_build_does_not_clear() {
    let s = Scratch::didactic_built();
    let build = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_recipe"))
            .args(["build", "--quiet"])
            .args(args)
            .arg("didactic.toml")
            .current_dir(s.path(""))
            .env_remove("RECIPE_CACHE_DIR")
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("run recipe")
    };
    // How long a build from an empty cache takes here, to spread the kills over one.
    let started = std::time::Instant::now();
    let status = build(&["--cache-dir", "timed"])
        .wait()
        .expect("the build ends");
    assert!(status.success());
    let whole = started.elapsed();
    // Two versions in turn, so that every round writes outputs, a report and a lock file anew;
    // each round from an empty cache, so that early kills hit the cache's entries; plain builds
    // write into the output directory, --locked ones into a staging directory first.
    let sizes = ["\"F2\" = { size = 100.0 }", "\"F2\" = { size = 90.0 }"];
    let moments = 6;
    for (round, locked) in (0..2 * moments).map(|r| (r, r >= moments)) {
        s.edit(sizes[round % 2], sizes[(round + 1) % 2]);
        let cache = format!("cache{round}");
        let mut args = vec!["--cache-dir", cache.as_str()];
        if locked {
            args.push("--locked");
        }
        let mut child = build(&args);
        let at = whole.mul_f64(((round % moments) as f64 + 0.5) / moments as f64);
        std::thread::sleep(at);
        let _ = child.kill();
        let _ = child.wait();
        let (ok, _, err) = s.build(&["--cache-dir", cache.as_str()]);
        assert!(ok, "{err}");
        assert_eq!(
            debris(&s),
            Vec::<String>::new(),
            "after a kill at {at:?} of {whole:?} (locked: {locked})"
        );
    }
}

#[test]
fn running_out_of_file_descriptors_fails_the_build_saying_so_and_damages_no_cache_entry() {
    let s = Scratch::didactic_built();
    let (_, before, _) = s.build(&[]);
    let all = all_nodes(&before).len();
    s.edit("size = 200.0", "size = 210.0");
    // Five descriptors: the standard three, the cache lock and one more (EMFILE soon after).
    // Eight jobs, so that two of them hold a file at once whatever the machine's load: with
    // one job per core, a busy machine could run them one after the other to the end.
    let out = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -n 5 && exec '{}' build -j 8 --json didactic.toml",
            env!("CARGO_BIN_EXE_recipe")
        ))
        .current_dir(s.dir.path())
        .env_remove("RECIPE_CACHE_DIR")
        .output()
        .expect("sh runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{err}");
    assert!(err.contains("Too many open files"), "{err}");
    for word in ["corrupt", "damaged", "panicked"] {
        assert!(!err.contains(word), "`{word}` in:\n{err}");
    }
    // With descriptors again, the entries written before are used, none rebuilt as damaged.
    let (ok, after, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert!(
        !err.contains("damaged") && !err.contains("corrupt"),
        "{err}"
    );
    let cached = nodes_in_state(&after, "cached").len();
    assert_eq!(all_nodes(&after).len(), all);
    // At least what the same edit finds cached without the failed run in between.
    let control = Scratch::didactic_built();
    control.edit("size = 200.0", "size = 210.0");
    let (_, plain, _) = control.build(&[]);
    let unchanged = nodes_in_state(&plain, "cached").len();
    assert!(
        cached >= unchanged && unchanged > 0,
        "{cached} < {unchanged}"
    );
}

/// Every file under the scratch folder's default cache, with its bytes.
fn cache_tree(s: &Scratch) -> std::collections::BTreeMap<String, Vec<u8>> {
    read_tree(&s.path(".recipe"))
}

#[test]
fn a_read_only_cache_serves_a_warm_build_and_is_left_byte_for_byte_as_it_was() {
    let s = Scratch::didactic_built();
    let outputs = read_tree(&s.path("out/didactic"));
    std::fs::remove_dir_all(s.path("out/didactic")).unwrap();
    let before = cache_tree(&s);
    let (ok, report, err) = s.build(&["--read-only-cache", "--locked"]);
    assert!(ok, "{err}");
    assert!(err.contains("is read-only"), "{err}");
    assert!(nodes_in_state(&report, "ran").is_empty(), "{err}");
    assert_eq!(
        cache_tree(&s),
        before,
        "the read-only build wrote into the cache"
    );
    let again = read_tree(&s.path("out/didactic"));
    for (name, bytes) in &outputs {
        if name.ends_with(".msh") || name.ends_with(".vtu") {
            assert_eq!(again.get(name), Some(bytes), "{name} differs");
        }
    }
}

#[test]
fn a_read_only_cache_runs_what_it_lacks_and_stores_none_of_it() {
    let s = Scratch::didactic_built();
    s.edit("size = 200.0", "size = 210.0");
    let before = cache_tree(&s);
    let (ok, report, err) = s.build(&["--read-only-cache"]);
    assert!(ok, "{err}");
    let ran = nodes_in_state(&report, "ran");
    assert!(ran.iter().any(|n| n.starts_with("tet_mesh:")), "{ran:?}");
    assert!(!nodes_in_state(&report, "cached").is_empty());
    assert_eq!(
        cache_tree(&s),
        before,
        "the read-only build wrote into the cache"
    );
    // Nothing was stored, so a writing build runs the same nodes again (and stores them).
    let (ok, again, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert_eq!(nodes_in_state(&again, "ran"), ran);
    let (_, third, _) = s.build(&[]);
    assert!(nodes_in_state(&third, "ran").is_empty());
}

#[test]
fn a_read_only_build_refuses_a_directory_that_is_not_a_cache_and_creates_none() {
    let s = Scratch::didactic();
    let before = snapshot(&s);
    for dir in ["data", "missing"] {
        let out = s.recipe_cmd(&[
            "build",
            "--read-only-cache",
            "--cache-dir",
            dir,
            "didactic.toml",
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{dir}: {err}");
        let why = if dir == "data" {
            "is not a recipe cache"
        } else {
            "there is no cache to read"
        };
        assert!(err.contains(why), "{dir}: {err}");
        assert_eq!(snapshot(&s), before, "{dir}: the build wrote something");
    }
}

/// A cache that no write may touch while this guard lives: its files and folders lose their
/// write permissions, and where those do not bind (the superuser), they are made immutable
/// (`chattr +i`). Dropping it makes the cache writable again. `None` when neither works here.
struct Unwritable(std::path::PathBuf);

impl Unwritable {
    fn make(cache: &std::path::Path) -> Option<Unwritable> {
        let guard = Unwritable(cache.to_path_buf());
        guard.chmod(0o555);
        if !guard.writable() {
            return Some(guard);
        }
        let immutable = std::process::Command::new("chattr")
            .args(["-R", "+i"])
            .arg(cache)
            .status()
            .is_ok_and(|s| s.success());
        (immutable && !guard.writable()).then_some(guard)
    }

    fn writable(&self) -> bool {
        let probe = self.0.join("probe");
        let wrote = std::fs::write(&probe, b"x").is_ok();
        let _ = std::fs::remove_file(&probe);
        wrote
    }

    /// Every file to `mode & 0o444`, every folder to `mode`.
    fn chmod(&self, mode: u32) {
        use std::os::unix::fs::PermissionsExt;
        let mut dirs = vec![self.0.clone()];
        while let Some(d) = dirs.pop() {
            for e in std::fs::read_dir(&d).unwrap().flatten() {
                let (p, dir) = (e.path(), e.file_type().unwrap().is_dir());
                if dir {
                    dirs.push(p);
                } else {
                    let perm = std::fs::Permissions::from_mode(mode & 0o444 | (mode & 0o200));
                    std::fs::set_permissions(&p, perm).unwrap();
                }
            }
            std::fs::set_permissions(&d, std::fs::Permissions::from_mode(mode)).unwrap();
        }
    }
}

impl Drop for Unwritable {
    fn drop(&mut self) {
        let _ = std::process::Command::new("chattr")
            .args(["-R", "-i"])
            .arg(&self.0)
            .stderr(std::process::Stdio::null())
            .status();
        self.chmod(0o755);
    }
}

#[test]
fn a_cache_the_user_cannot_write_is_read_without_the_flag_and_gc_refuses_it() {
    let s = Scratch::didactic_built();
    let cache = s.path(".recipe");
    let before = cache_tree(&s);
    let Some(guard) = Unwritable::make(&cache) else {
        eprintln!(
            "note: neither permissions nor `chattr +i` keep writes out of a folder here; skipped"
        );
        return;
    };
    let (ok, report, err) = s.build(&["--locked"]);
    let out = s.recipe_cmd(&["gc", "didactic.toml"]);
    drop(guard);
    assert!(ok, "{err}");
    assert!(err.contains("is read-only"), "{err}");
    assert!(nodes_in_state(&report, "ran").is_empty());
    assert_eq!(cache_tree(&s), before);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{err}");
    assert!(err.contains("cannot be written"), "{err}");
}
