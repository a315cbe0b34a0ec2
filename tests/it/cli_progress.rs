//! Progress bars are for people at a terminal: `recipe build` draws none when its output goes
//! to a pipe or a file, nor with `--quiet` at a terminal, where without it it does. The bars'
//! delay is set to zero (`RECIPE_BAR_DELAY_MS`), so every node that reports progress would
//! draw one at once. The terminal is a pseudo-terminal from util-linux's `script`; without it
//! those cases print a note and skip.

use crate::common_cli::Scratch;
use std::process::{Command, Stdio};

/// What a drawn bar leaves in the output: its bar characters, or a terminal escape sequence.
fn has_bar_traces(out: &str) -> bool {
    out.contains('█') || out.contains('░') || out.contains("\x1b[")
}

#[test]
fn a_build_whose_output_goes_to_pipes_draws_no_bar() {
    let s = Scratch::didactic();
    let out = Command::new(env!("CARGO_BIN_EXE_recipe"))
        .args(["build", "--json", "didactic.toml"])
        .current_dir(s.dir.path())
        .env_remove("RECIPE_CACHE_DIR")
        .env("RECIPE_BAR_DELAY_MS", "0")
        .env("TERM", "xterm-256color")
        .output()
        .expect("run recipe");
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("Meshed tet_mesh:"), "{stderr}");
    assert!(!has_bar_traces(&stdout), "{stdout}");
    assert!(!has_bar_traces(&stderr), "{stderr}");
}

/// `recipe build ARGS didactic.toml` in a fresh copy of the example, on a pseudo-terminal;
/// returns everything it wrote there, or `None` when there is no `script` to make one.
fn build_at_a_terminal(args: &str) -> Option<String> {
    let script = Command::new("script")
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status();
    if !script.is_ok_and(|s| s.success()) {
        eprintln!("note: no util-linux `script` to make a terminal with: skipped");
        return None;
    }
    let s = Scratch::didactic();
    let command = format!(
        "'{}' build {args} didactic.toml",
        env!("CARGO_BIN_EXE_recipe")
    );
    let out = Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .current_dir(s.dir.path())
        .env_remove("RECIPE_CACHE_DIR")
        .env("RECIPE_BAR_DELAY_MS", "0")
        .env("TERM", "xterm-256color")
        .stdin(Stdio::null())
        .output()
        .expect("run script");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{text}");
    assert!(text.contains("Finished didactic"), "{text}");
    Some(text)
}

#[test]
fn a_build_at_a_terminal_draws_bars_and_a_quiet_one_draws_none() {
    let Some(normal) = build_at_a_terminal("") else {
        return;
    };
    assert!(normal.contains('█') || normal.contains('░'), "{normal}");
    let quiet = build_at_a_terminal("--quiet").expect("script was there a moment ago");
    assert!(!has_bar_traces(&quiet), "{quiet}");
}
