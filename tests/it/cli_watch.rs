//! `recipe build --watch`: rebuilds on save (including save-by-rename), survives an invalid
//! recipe, and ignores its own outputs.

use crate::common_cli;
use common_cli::*;
use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

#[test]
fn watch_mode_rebuilds_on_saves_survives_an_invalid_recipe_and_sees_rename_over_saves() {
    let s = Scratch::didactic_built();
    let mut child = Command::new(env!("CARGO_BIN_EXE_recipe"))
        .args(["build", "--watch", "--max-builds", "3", "didactic.toml"])
        .current_dir(s.dir.path())
        .stderr(Stdio::piped())
        .stdout(Stdio::null())
        .spawn()
        .expect("spawn");
    let (tx, rx) = mpsc::channel();
    let stderr = child.stderr.take().unwrap();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    let wait_for = |needle: &str| -> Vec<String> {
        let mut seen = Vec::new();
        loop {
            match rx.recv_timeout(Duration::from_secs(300)) {
                Ok(l) => {
                    let hit = l.contains(needle);
                    seen.push(l);
                    if hit {
                        return seen;
                    }
                }
                Err(_) => panic!("no `{needle}` in:\n{}", seen.join("\n")),
            }
        }
    };
    wait_for("Watching");
    // An invalid edit: the watcher prints the error and keeps waiting.
    s.edit("size = 200.0", "size = \"big\"");
    let lines = wait_for("Watching");
    assert!(
        lines.iter().any(|l| l.contains("didactic.toml:")),
        "{lines:?}"
    );
    // A valid save by writing a temporary file and renaming it over the recipe.
    let fixed = std::fs::read_to_string(s.recipe())
        .unwrap()
        .replace("size = \"big\"", "size = 200.0");
    let tmp = s.path("didactic.toml.tmp~");
    std::fs::write(&tmp, fixed).unwrap();
    std::fs::rename(&tmp, s.recipe()).unwrap();
    let lines = wait_for("Finished");
    assert!(lines.iter().any(|l| l.contains("Finished")));
    let status = child.wait().expect("the watcher exits after --max-builds");
    assert!(status.success() || status.code() == Some(0));
}
