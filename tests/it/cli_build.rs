//! The `recipe build` command on the shipped example: caching, incremental rebuilds, the lock
//! file, reproducibility across job counts, and cache repair.

use crate::common_cli;
use common_cli::*;

#[test]
fn a_second_build_with_nothing_changed_runs_nothing() {
    let s = Scratch::didactic();
    let (ok, first, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert!(!nodes_in_state(&first, "ran").is_empty());
    let (ok, second, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert_eq!(nodes_in_state(&second, "ran"), Vec::<String>::new());
    assert_eq!(all_nodes(&first), all_nodes(&second));
    assert!(s.path("out/didactic/didactic.curves.vtu").is_file());
    assert!(s.path("out/didactic/validation.json").is_file());
    assert!(s.path("didactic.toml.lock").is_file());
}

#[test]
fn one_and_two_jobs_give_byte_identical_outputs_and_lock_files() {
    let a = Scratch::didactic();
    let b = Scratch::didactic();
    assert!(a.build(&["-j", "1"]).0);
    assert!(b.build(&["-j", "2"]).0);
    // Everything but the report, which records how long each step took.
    let outputs = |s: &Scratch| {
        let mut t = read_tree(&s.path("out"));
        t.retain(|k, _| !k.ends_with("report.html") && !k.ends_with("report.json"));
        t
    };
    assert!(outputs(&a).len() >= 6);
    assert_eq!(outputs(&a), outputs(&b));
    assert_eq!(
        std::fs::read(a.path("didactic.toml.lock")).unwrap(),
        std::fs::read(b.path("didactic.toml.lock")).unwrap()
    );
}

#[test]
fn editing_one_curve_rule_reruns_only_those_curves_the_patches_they_bound_the_regions_those_bound_and_the_export()
 {
    let s = Scratch::didactic_built();
    s.edit("\"F2\" = { size = 100.0 }", "\"F2\" = { size = 50.0 }");
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    let ran = nodes_in_state(&r, "ran");
    // The dangling fault F2 crosses the reservoir on the east side of F1 only: its curves bound
    // the F2 patches and constrain the horizon patches it crosses; those bound the east regions.
    for n in &ran {
        let allowed = (n.starts_with("discretize:") && n.contains("F2"))
            || n.starts_with("surface_mesh:F2#")
            || n.starts_with("surface_mesh:H1#")
            || n.starts_with("surface_mesh:H2#")
            || (n.starts_with("tet_mesh:") && n.ends_with("_E"))
            || n == "mesh"
            || n == "export";
        assert!(
            allowed,
            "`{n}` re-ran but does not depend on the F2 curve rule"
        );
    }
    for must in [
        "discretize:F2/H1",
        "surface_mesh:F2#2",
        "tet_mesh:reservoir_E",
        "mesh",
        "export",
    ] {
        assert!(
            ran.contains(&must.to_string()),
            "`{must}` did not re-run: {ran:?}"
        );
    }
    // What did NOT re-run: the model and everything upstream, every curve without F2, the box
    // and F1 patches, and the three regions west of F1.
    for n in all_nodes(&r) {
        let untouched = n.starts_with("import:")
            || n.starts_with("intersect:")
            || n == "model"
            || n.starts_with("curve:")
            || n.starts_with("patch:")
            || (n.starts_with("discretize:") && !n.contains("F2"))
            || n.starts_with("surface_mesh:box.")
            || n.starts_with("surface_mesh:F1#")
            || (n.starts_with("tet_mesh:") && n.ends_with("_W"));
        if untouched {
            assert!(!ran.contains(&n), "`{n}` re-ran");
        }
    }
}

#[test]
fn a_comment_or_whitespace_edit_reruns_nothing() {
    let s = Scratch::didactic_built();
    s.edit("[mesh]\n", "# a new comment\n\n[mesh]   \n");
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert_eq!(nodes_in_state(&r, "ran"), Vec::<String>::new());
}

#[test]
fn touching_an_imported_file_reruns_nothing_but_changing_it_reruns_its_import() {
    let s = Scratch::didactic_built();
    let f = s.path("data/didactic/F2_dangling.ts");
    let text = std::fs::read(&f).unwrap();
    std::fs::write(&f, &text).unwrap();
    let (_, r, _) = s.build(&[]);
    assert_eq!(nodes_in_state(&r, "ran"), Vec::<String>::new());
    let mut changed = text.clone();
    changed.extend_from_slice(b"\n# an appended comment changes the bytes, not the surface\n");
    std::fs::write(&f, &changed).unwrap();
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    let ran = nodes_in_state(&r, "ran");
    assert!(ran.contains(&"import:F2".to_string()), "{ran:?}");
    // The surface is the same, so nothing downstream of the import re-runs (early cutoff).
    assert!(
        ran.iter().all(|n| n == "import:F2" || n == "file:F2"),
        "{ran:?}"
    );
}

#[test]
fn a_locked_build_fails_with_a_readable_diff_when_a_size_changes() {
    let s = Scratch::didactic_built();
    assert!(
        s.build(&["--locked"]).0,
        "an unchanged recipe passes --locked"
    );
    s.edit("\"F2\" = { size = 100.0 }", "\"F2\" = { size = 50.0 }");
    let (ok, _, err) = s.build(&["--locked"]);
    assert!(!ok);
    assert!(err.contains("discretize:F2"), "{err}");
    assert!(err.contains("didactic.toml.lock"), "{err}");
}

/// The names in `out/` (the output directory's parent) that are not `didactic`: a staging
/// directory left behind would be one.
fn beside_the_outputs(s: &Scratch) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(s.path("out"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "didactic")
        .collect();
    v.sort();
    v
}

#[test]
fn a_locked_build_that_changes_the_mesh_leaves_every_output_and_the_lock_untouched() {
    let s = Scratch::didactic_built();
    let outputs = read_tree(&s.path("out"));
    let lock = std::fs::read(s.path("didactic.toml.lock")).unwrap();
    s.edit("\"F2\" = { size = 100.0 }", "\"F2\" = { size = 50.0 }");
    let (ok, _, err) = s.build(&["--locked"]);
    assert!(!ok && err.contains("didactic.toml.lock"), "{err}");
    assert!(
        read_tree(&s.path("out")) == outputs,
        "a file in out/ changed, or one was added or removed"
    );
    assert_eq!(std::fs::read(s.path("didactic.toml.lock")).unwrap(), lock);
    assert_eq!(beside_the_outputs(&s), Vec::<String>::new());
}

#[test]
fn a_locked_build_that_fails_in_a_node_leaves_every_output_and_the_lock_untouched() {
    let s = Scratch::didactic_built();
    let outputs = read_tree(&s.path("out"));
    let lock = std::fs::read(s.path("didactic.toml.lock")).unwrap();
    // A trim that discards nothing fails the `model` node.
    add_a_trim_that_discards_nothing(&s);
    model_fails_saying(&s, &["--locked"], &[]);
    assert!(
        read_tree(&s.path("out")) == outputs,
        "a file in out/ changed, or one was added or removed"
    );
    assert_eq!(std::fs::read(s.path("didactic.toml.lock")).unwrap(), lock);
    assert_eq!(beside_the_outputs(&s), Vec::<String>::new());
}

#[test]
fn a_locked_build_that_matches_publishes_its_outputs_into_a_missing_output_dir() {
    let s = Scratch::didactic_built();
    let mut outputs = read_tree(&s.path("out"));
    std::fs::remove_dir_all(s.path("out")).unwrap();
    let (ok, _, err) = s.build(&["--locked"]);
    assert!(ok, "{err}");
    let mut now = read_tree(&s.path("out"));
    // The report records how long each step took; it is there, the rest is byte-identical.
    for t in [&mut outputs, &mut now] {
        for report in ["didactic/report.html", "didactic/report.json"] {
            assert!(t.remove(report).is_some(), "{report}");
        }
    }
    assert!(now == outputs, "the published outputs differ");
    assert_eq!(beside_the_outputs(&s), Vec::<String>::new());
}

#[test]
fn a_lock_is_not_rewritten_over_an_output_that_changed_without_a_version_bump() {
    let s = Scratch::didactic_built();
    // As if `discretize:F2#1` had recorded another output under the key it has now: what the
    // lock would show after the operation's code changed and its version did not.
    let lock = s.path("didactic.toml.lock");
    let text = std::fs::read_to_string(&lock).unwrap();
    let at = text
        .find("[nodes.\"discretize:F2#1\"]")
        .expect("the node is locked");
    let out = at + text[at..].find("output = \"").unwrap() + "output = \"".len();
    let mut edited = text.clone();
    edited.replace_range(out..out + 64, &"0".repeat(64));
    std::fs::write(&lock, &edited).unwrap();
    let fresh = s.path("fresh-cache");
    let (ok, _, err) = s.build(&["--cache-dir", fresh.to_str().unwrap()]);
    assert!(!ok, "the build refuses to update the lock");
    assert!(
        err.contains("discretize:F2#1") && err.contains("version bump"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(&lock).unwrap(),
        edited,
        "the lock is untouched"
    );
    let (ok, _, err) = s.build(&["--locked", "--cache-dir", fresh.to_str().unwrap()]);
    assert!(!ok && err.contains("version bump"), "{err}");
}

#[test]
fn corrupt_or_truncated_cache_entries_are_detected_and_repaired() {
    let s = Scratch::didactic_built();
    let (ok, first, _) = s.build(&[]);
    assert!(ok);
    let mut n = 0;
    for (i, (rel, bytes)) in read_tree(&s.path(".recipe")).into_iter().enumerate() {
        if rel.contains("lock") || rel.ends_with(".json") || bytes.is_empty() {
            continue;
        }
        let p = s.path(".recipe").join(&rel);
        if i % 2 == 0 {
            std::fs::write(&p, &bytes[..bytes.len() / 2]).unwrap();
        } else {
            let mut b = bytes.clone();
            b[0] ^= 0xff;
            std::fs::write(&p, b).unwrap();
        }
        n += 1;
    }
    assert!(n > 0, "the cache has entries");
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert!(err.contains("corrupt"), "the corruption is reported: {err}");
    let (ok, third, _) = s.build(&[]);
    assert!(ok);
    assert_eq!(nodes_in_state(&third, "ran"), Vec::<String>::new());
    assert_eq!(all_nodes(&first), all_nodes(&third));
}

#[test]
fn the_model_of_the_shipped_example_has_six_regions_named_by_the_recipe_with_the_dangling_fault_inside()
 {
    let s = Scratch::didactic_built();
    let (ok, r, err) = s.build(&[]);
    assert!(ok, "{err}");
    let model = r["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|n| n["name"] == "model")
        .expect("a model node");
    assert_eq!(model["counts"]["regions"], 6);
    assert_eq!(
        model["counts"]["dangling_patches"], 3,
        "F2 is cut by H1 and H2 into three dangling patches"
    );
    let note = model["notes"][0].as_str().unwrap();
    for n in [
        "overburden_W",
        "overburden_E",
        "reservoir_W",
        "reservoir_E",
        "underburden_W",
        "underburden_E",
    ] {
        assert!(note.contains(n), "region `{n}` not named: {note}");
    }
}
