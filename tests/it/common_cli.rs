//! Shared helpers for the command-line integration tests (`crate::common_cli`).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A scratch copy of the shipped didactic recipe and its data.
pub struct Scratch {
    pub dir: tempfile::TempDir,
}

impl Scratch {
    pub fn didactic() -> Scratch {
        let dir = tempfile::tempdir().expect("temp dir");
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("recipes");
        copy_dir(
            &src.join("data/didactic"),
            &dir.path().join("data/didactic"),
        );
        std::fs::copy(src.join("didactic.toml"), dir.path().join("didactic.toml"))
            .expect("copy recipe");
        Scratch { dir }
    }
    /// A scratch copy whose cache, lock file and outputs already hold a full build of the shipped
    /// recipe: the build runs once per test binary and is copied, so each test pays only for what
    /// its edit re-runs.
    pub fn didactic_built() -> Scratch {
        static BASE: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
        let base = BASE.get_or_init(|| {
            let s = Scratch::didactic();
            let (ok, _, err) = s.build(&[]);
            assert!(ok, "the shipped recipe builds: {err}");
            s.dir.keep()
        });
        let dir = tempfile::tempdir().expect("temp dir");
        copy_dir(base, dir.path());
        Scratch { dir }
    }
    pub fn recipe(&self) -> PathBuf {
        self.dir.path().join("didactic.toml")
    }
    pub fn path(&self, rel: &str) -> PathBuf {
        self.dir.path().join(rel)
    }
    pub fn edit(&self, from: &str, to: &str) {
        let p = self.recipe();
        let s = std::fs::read_to_string(&p).unwrap();
        assert!(s.contains(from), "the recipe has no `{from}`");
        std::fs::write(&p, s.replacen(from, to, 1)).unwrap();
    }
    /// The record of `recipe` (a path relative to the scratch folder) in the default cache
    /// `.recipe/`: the one whose `recipe` file leads back to it.
    pub fn record_of(&self, recipe: &str) -> PathBuf {
        let records = self.path(".recipe/records");
        let want = format!("../{recipe}");
        std::fs::read_dir(&records)
            .unwrap_or_else(|e| panic!("{}: {e}", records.display()))
            .map(|e| e.unwrap().path())
            .find(|d| engine::checked::read(&d.join("recipe")).is_ok_and(|r| r == want.as_bytes()))
            .unwrap_or_else(|| panic!("no record of {recipe} in {}", records.display()))
    }
    /// `recipe build --json ARGS RECIPE` for another recipe in the scratch folder; returns
    /// (success, report JSON, stderr).
    pub fn build_recipe(&self, recipe: &str, extra: &[&str]) -> (bool, serde_json::Value, String) {
        let mut args = vec!["build", "--json"];
        args.extend_from_slice(extra);
        args.push(recipe);
        let out = self.recipe_cmd(&args);
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        let json = serde_json::from_slice(&out.stdout).unwrap_or(serde_json::Value::Null);
        (out.status.success(), json, stderr)
    }
    pub fn recipe_cmd(&self, args: &[&str]) -> Output {
        Command::new(env!("CARGO_BIN_EXE_recipe"))
            .args(args)
            .current_dir(self.dir.path())
            .env_remove("RECIPE_CACHE_DIR")
            .output()
            .expect("run recipe")
    }
    /// `recipe build --json ARGS didactic.toml`; returns (success, report JSON, stderr).
    pub fn build(&self, extra: &[&str]) -> (bool, serde_json::Value, String) {
        self.build_recipe("didactic.toml", extra)
    }
}

pub fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        if e.file_type().unwrap().is_dir() {
            copy_dir(&e.path(), &to.join(e.file_name()));
        } else {
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
}

/// Adds to `s`'s recipe a trim that discards nothing: an error of the `model` node, found before
/// anything is meshed or exported.
pub fn add_a_trim_that_discards_nothing(s: &Scratch) {
    s.edit(
        "[mesh]\n",
        "[[trim]]\nsurface = \"F1\"\ndiscard = { area_below = 0.001 }\n\n[mesh]\n",
    );
}

/// Builds `s` with `extra` arguments; the build must fail in the `model` node with an error
/// holding every one of `needles`. Returns the error output.
pub fn model_fails_saying(s: &Scratch, extra: &[&str], needles: &[&str]) -> String {
    let (ok, r, err) = s.build(extra);
    assert!(!ok);
    assert!(
        nodes_in_state(&r, "failed").contains(&"model".to_string()),
        "{err}"
    );
    for n in needles {
        assert!(err.contains(n), "`{n}` not in:\n{err}");
    }
    err
}

/// Node names in the report whose state is `state`, sorted.
pub fn nodes_in_state(report: &serde_json::Value, state: &str) -> Vec<String> {
    let mut v: Vec<String> = report["nodes"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter(|n| n["state"] == state)
                .filter_map(|n| n["name"].as_str().map(String::from))
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

pub fn all_nodes(report: &serde_json::Value) -> Vec<String> {
    let mut v: Vec<String> = report["nodes"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|n| n["name"].as_str().map(String::from))
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// Every file under `dir`, relative path → bytes.
pub fn read_tree(dir: &Path) -> std::collections::BTreeMap<String, Vec<u8>> {
    let mut m = std::collections::BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                m.insert(
                    p.strip_prefix(dir).unwrap().display().to_string(),
                    std::fs::read(&p).unwrap(),
                );
            }
        }
    }
    m
}

/// `../shared/tools/check_mesh.py` when it and python3 with numpy and meshio are present; else
/// prints why the independent check is skipped.
pub fn checker() -> Option<PathBuf> {
    let p = test_support::paths::shared("tools/check_mesh.py")?;
    let ok = Command::new("python3")
        .args(["-c", "import numpy, meshio"])
        .status()
        .is_ok_and(|s| s.success());
    if !ok {
        eprintln!("skipping the independent check: python3 with numpy and meshio is absent");
        return None;
    }
    Some(p)
}

/// Asserts that `check_mesh.py` passes `msh` with `regions` regions (skipped, with a note, where
/// the checker is absent); `what` names the mesh in the failure.
pub fn passes_check_mesh(msh: &Path, regions: usize, what: &str) {
    assert!(msh.is_file(), "{what}: no msh written at {}", msh.display());
    let Some(check) = checker() else {
        return;
    };
    let out = Command::new("python3")
        .arg(&check)
        .arg(msh)
        .args(["--regions", &regions.to_string()])
        .output()
        .expect("python3 runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && text.contains("\"fail\": []"),
        "{what}: {text}"
    );
}

/// Every temporary or staging directory a killed write could have left anywhere under the
/// scratch folder (a user's own `.tmp-notes` aside).
pub fn debris(s: &Scratch) -> Vec<String> {
    let mut out = Vec::new();
    let mut stack = vec![s.path("")];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if name.starts_with(engine::store::TEMP_PREFIX) && name != ".tmp-notes" {
                out.push(e.path().display().to_string());
            }
            if e.file_type().unwrap().is_dir() {
                stack.push(e.path());
            }
        }
    }
    out.sort();
    out
}

/// The smallest dihedral angle of a build's tets, from its quality tables (`quality.json`).
pub fn worst_dihedral(quality_json: &Path) -> f64 {
    let text = std::fs::read(quality_json).expect("the quality tables");
    let q: serde_json::Value = serde_json::from_slice(&text).expect("JSON");
    let rows = q["table2"].as_array().expect("rows");
    let all = rows
        .iter()
        .find(|r| r["name"] == "all")
        .expect("a row of all");
    all["min_dihedral_deg"].as_f64().expect("an angle")
}
