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

/// A watcher on a built scratch copy of the example, its stderr lines arriving on a channel.
struct Watch {
    child: std::process::Child,
    lines: mpsc::Receiver<String>,
    seen: Vec<String>,
}

impl Watch {
    fn start(s: &Scratch, max_builds: usize) -> Watch {
        let mut child = Command::new(env!("CARGO_BIN_EXE_recipe"))
            .args(["build", "--watch", "--max-builds", &max_builds.to_string()])
            .arg("didactic.toml")
            .current_dir(s.dir.path())
            .stderr(Stdio::piped())
            .stdout(Stdio::null())
            .spawn()
            .expect("spawn");
        let (tx, lines) = mpsc::channel();
        let stderr = child.stderr.take().unwrap();
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                let _ = tx.send(line);
            }
        });
        Watch {
            child,
            lines,
            seen: Vec::new(),
        }
    }

    /// Every line up to and including the next one containing `needle`.
    fn until(&mut self, needle: &str) {
        loop {
            let l = self
                .lines
                .recv_timeout(Duration::from_secs(300))
                .unwrap_or_else(|_| panic!("no `{needle}` in:\n{}", self.seen.join("\n")));
            let hit = l.contains(needle);
            self.seen.push(l);
            if hit {
                return;
            }
        }
    }

    /// Collects what arrives for `secs` seconds.
    fn idle(&mut self, secs: u64) {
        let end = std::time::Instant::now() + Duration::from_secs(secs);
        while let Some(left) = end.checked_duration_since(std::time::Instant::now()) {
            match self.lines.recv_timeout(left) {
                Ok(l) => self.seen.push(l),
                Err(_) => break,
            }
        }
    }

    fn count(&self, needle: &str) -> usize {
        self.seen.iter().filter(|l| l.contains(needle)).count()
    }
}

impl Drop for Watch {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

#[test]
fn an_idle_watcher_builds_once_and_then_rests() {
    let s = Scratch::didactic_built();
    let mut w = Watch::start(&s, 2);
    w.until("Watching");
    w.idle(6);
    assert_eq!(w.count("Finished"), 1, "{:#?}", w.seen);
    assert!(
        w.child.try_wait().unwrap().is_none(),
        "it did not build again"
    );
}

#[test]
fn a_save_without_a_change_and_a_touch_do_not_rebuild_but_an_edit_rebuilds_once() {
    let s = Scratch::didactic_built();
    let mut w = Watch::start(&s, 3);
    w.until("Watching");
    let text = std::fs::read(s.recipe()).unwrap();
    std::fs::write(s.recipe(), &text).unwrap();
    let data = s.path("data/didactic/F2_dangling.ts");
    let f = std::fs::File::options().append(true).open(&data).unwrap();
    f.set_modified(std::time::SystemTime::now()).unwrap();
    drop(f);
    w.idle(3);
    assert_eq!(w.count("Finished"), 1, "{:#?}", w.seen);
    s.edit("\"F2\" = { size = 100.0 }", "\"F2\" = { size = 90.0 }");
    w.until("Watching");
    w.idle(3);
    assert_eq!(w.count("Finished"), 2, "one build per edit: {:#?}", w.seen);
}

#[test]
fn an_invalid_edit_prints_its_error_once() {
    let s = Scratch::didactic_built();
    let mut w = Watch::start(&s, 3);
    w.until("Watching");
    s.edit("size = 200.0", "size = \"big\"");
    w.until("Watching");
    w.idle(3);
    let errors = w.count("didactic.toml:");
    assert_eq!(errors, 1, "{:#?}", w.seen);
}
