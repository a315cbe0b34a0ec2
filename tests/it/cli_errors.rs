//! Bad input to the command line: every error names the place and exits non-zero, never a panic.

use crate::common_cli;
use common_cli::*;

fn fails_with(s: &Scratch, args: &[&str], needles: &[&str]) {
    let out = s.recipe_cmd(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "exit code for {args:?}: {err}");
    assert!(!err.contains("panicked"), "{err}");
    for n in needles {
        assert!(err.contains(n), "`{n}` not in:\n{err}");
    }
}

#[test]
fn a_misspelt_key_names_the_line_and_suggests_the_key() {
    let s = Scratch::didactic();
    s.edit("size = 200.0", "szie = 200.0");
    fails_with(
        &s,
        &["build", "didactic.toml"],
        &["didactic.toml:", "szie", "size"],
    );
    fails_with(&s, &["check", "didactic.toml"], &["didactic.toml:", "szie"]);
}

#[test]
fn a_missing_imported_file_is_named_with_the_recipe_line() {
    let s = Scratch::didactic();
    std::fs::remove_file(s.path("data/didactic/F2_dangling.ts")).unwrap();
    fails_with(
        &s,
        &["build", "didactic.toml"],
        &["didactic.toml:", "F2_dangling.ts"],
    );
}

#[test]
fn a_curve_rule_that_matches_no_curve_of_the_model_fails_the_build_with_its_selector() {
    let s = Scratch::didactic();
    s.edit(
        "\"H1/F1\" = { size = 100.0 }",
        "\"H1/H2\" = { size = 100.0 }",
    );
    fails_with(&s, &["build", "didactic.toml"], &["H1/H2"]);
}

#[test]
fn a_corrupt_surface_file_fails_its_import_with_file_and_line_and_other_nodes_still_run() {
    let s = Scratch::didactic();
    let f = s.path("data/didactic/F2_dangling.ts");
    let text = std::fs::read_to_string(&f)
        .unwrap()
        .replacen("TRGL 1 ", "TRGL 99999 ", 1);
    std::fs::write(&f, text).unwrap();
    let (ok, r, err) = s.build(&[]);
    assert!(!ok);
    assert!(err.contains("F2_dangling.ts:"), "{err}");
    assert!(nodes_in_state(&r, "failed").contains(&"import:F2".to_string()));
    assert!(
        nodes_in_state(&r, "ran").contains(&"import:H1".to_string()),
        "independent nodes keep going"
    );
}

#[test]
fn check_accepts_the_shipped_recipe() {
    let s = Scratch::didactic();
    let out = s.recipe_cmd(&["check", "didactic.toml"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_missing_recipe_is_an_error_not_a_panic() {
    let s = Scratch::didactic();
    fails_with(&s, &["build", "nope.toml"], &["nope.toml"]);
}

#[test]
fn a_trim_that_discards_nothing_fails_the_model_and_points_at_its_recipe_line() {
    let s = Scratch::didactic();
    add_a_trim_that_discards_nothing(&s);
    // The trim's line is quoted with its header underlined, and its surface is named.
    let err = model_fails_saying(
        &s,
        &[],
        &[
            "error: `model` failed: [[trim]] #1 (surface = \"F1\"",
            "no patch has an area below 0.001",
            "--> didactic.toml:",
            " | [[trim]]\n   | ^^^^^^^^\n",
        ],
    );
    assert!(
        !err.contains("error `model` failed"),
        "shown once, as a recipe error: {err}"
    );
}

/// Runs `recipe args` in `s` with standard output given as `stdout`; returns the exit code and
/// standard error.
fn run_with_stdout(
    s: &Scratch,
    args: &[&str],
    stdout: std::process::Stdio,
) -> (Option<i32>, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_recipe"))
        .current_dir(s.path("."))
        .args(args)
        .stdout(stdout)
        .output()
        .expect("the recipe binary runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn a_reader_that_closed_standard_output_ends_the_command_quietly() {
    let s = Scratch::didactic_built();
    for args in [
        &["explain", "didactic.toml"][..],
        &["graph", "didactic.toml"][..],
    ] {
        // The read end is closed before the command writes anything.
        let (reader, writer) = std::io::pipe().expect("a pipe");
        drop(reader);
        let (code, err) = run_with_stdout(&s, args, writer.into());
        assert_eq!(code, Some(141), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(err.is_empty(), "{args:?} says nothing: {err}");
    }
}

#[test]
fn a_json_build_whose_reader_closed_standard_output_leaves_its_report_and_lock_current() {
    let s = Scratch::didactic_built();
    let tets = || {
        let text = std::fs::read(s.path("out/didactic/report.json")).expect("the report");
        let report: serde_json::Value = serde_json::from_slice(&text).expect("JSON");
        report["counts"]["tets"].as_u64().expect("a tet count")
    };
    let before = tets();
    s.edit("\"F2\" = { size = 100.0 }", "\"F2\" = { size = 50.0 }");
    let (reader, writer) = std::io::pipe().expect("a pipe");
    drop(reader);
    let (code, err) = run_with_stdout(&s, &["build", "--json", "didactic.toml"], writer.into());
    assert_eq!(code, Some(141), "{err}");
    // The report and the lock file were written before the JSON: they are the edited build's.
    assert_ne!(tets(), before, "the report is the edited recipe's");
    let (ok, _, err) = s.build(&["--locked"]);
    assert!(ok, "the lock file is the edited recipe's: {err}");
}

#[test]
fn a_full_standard_output_is_an_error_message_not_a_panic() {
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        eprintln!("note: no /dev/full here; skipped");
        return;
    };
    let s = Scratch::didactic_built();
    let (code, err) = run_with_stdout(&s, &["explain", "didactic.toml"], full.into());
    assert_eq!(code, Some(1), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(err.contains("cannot write to standard output"), "{err}");
    // The help and the version are output too: a full stream is an error, a closed one quiet.
    for flag in ["--help", "--version"] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let (code, err) = run_with_stdout(&s, &[flag], full.into());
        assert_eq!(code, Some(1), "{flag}: {err}");
        assert!(
            err.contains("cannot write to standard output"),
            "{flag}: {err}"
        );
        let (reader, writer) = std::io::pipe().expect("a pipe");
        drop(reader);
        let (code, err) = run_with_stdout(&s, &[flag], writer.into());
        assert_eq!(code, Some(141), "{flag}: {err}");
        assert!(err.is_empty(), "{flag}: {err}");
    }
    // Every other command that writes to standard output (`clean` last: it removes the cache).
    for args in [
        &["check", "didactic.toml"][..],
        &["graph", "didactic.toml"],
        &["build", "--json", "didactic.toml"],
        &["gc", "didactic.toml"],
        &["clean", "didactic.toml"],
    ] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let (code, err) = run_with_stdout(&s, args, full.into());
        assert_eq!(code, Some(1), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(
            err.contains("cannot write to standard output"),
            "{args:?}: {err}"
        );
    }
}

/// Runs `recipe args` in `s` with standard error given as `stderr` and standard output captured;
/// returns the exit code.
fn run_with_stderr(s: &Scratch, args: &[&str], stderr: std::process::Stdio) -> Option<i32> {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_recipe"))
        .current_dir(s.path("."))
        .args(args)
        .env_remove("RECIPE_CACHE_DIR")
        .stderr(stderr)
        .output()
        .expect("the recipe binary runs");
    out.status.code()
}

/// Streams for standard error that take nothing.
#[derive(Clone, Copy, Debug)]
enum Sink {
    /// `/dev/full`: every write fails with ENOSPC.
    Full,
    /// A pipe whose reader is gone: every write fails with EPIPE.
    Closed,
    /// A non-blocking socket already full, its reader alive but reading nothing: every write
    /// fails with EAGAIN.
    Blocked,
}

impl Sink {
    /// The stream, and what must stay open while the command runs; `None` where the machine has
    /// no such stream.
    fn open(self) -> Option<(std::process::Stdio, Option<std::os::unix::net::UnixStream>)> {
        match self {
            Sink::Full => {
                let f = std::fs::OpenOptions::new().write(true).open("/dev/full");
                f.ok().map(|f| (f.into(), None))
            }
            Sink::Closed => {
                let (reader, writer) = std::io::pipe().expect("a pipe");
                drop(reader);
                Some((writer.into(), None))
            }
            Sink::Blocked => {
                use std::io::Write as _;
                let (reader, mut writer) = std::os::unix::net::UnixStream::pair().ok()?;
                writer.set_nonblocking(true).ok()?;
                let chunk = [b'x'; 4096];
                while writer.write(&chunk).is_ok() {}
                Some((std::os::fd::OwnedFd::from(writer).into(), Some(reader)))
            }
        }
    }
}

#[test]
fn a_full_closed_or_blocked_standard_error_changes_no_exit_status_and_no_output() {
    // Progress, warnings and errors go to standard error; a stream that takes none of them is
    // the user's to mind, so every command ends as it would have, with no panic (101).
    let s = Scratch::didactic_built();
    s.edit("\"F2\" = { size = 100.0 }", "\"F2\" = { size = 80.0 }");
    for sink in [Sink::Full, Sink::Closed, Sink::Blocked] {
        if sink.open().is_none() {
            eprintln!("note: no {sink:?} stream here; skipped");
            continue;
        }
        let runs: [(&[&str], i32); 4] = [
            (&["build", "didactic.toml"], 0),
            (&["check", "didactic.toml"], 0),
            (&["explain", "didactic.toml"], 0),
            (&["check", "missing.toml"], 1),
        ];
        for (args, status) in runs {
            let (err, _open) = sink.open().expect("as above");
            assert_eq!(
                run_with_stderr(&s, args, err),
                Some(status),
                "{args:?} with standard error {sink:?}"
            );
        }
    }
    // The edited build above wrote its outputs and lock: a locked build agrees with them.
    let (ok, _, err) = s.build(&["--locked"]);
    assert!(
        ok,
        "the build with nowhere to report finished its work: {err}"
    );
}

#[test]
fn check_whose_reader_reads_nothing_ends_quietly() {
    let s = Scratch::didactic();
    let (reader, writer) = std::io::pipe().expect("a pipe");
    drop(reader);
    let (code, err) = run_with_stdout(&s, &["check", "didactic.toml"], writer.into());
    assert_eq!(code, Some(141), "{err}");
    assert!(err.is_empty(), "{err}");
}

#[test]
fn check_catches_a_region_point_outside_the_box_without_building() {
    let s = Scratch::didactic();
    s.edit(
        "overburden_E = { point = [504000.0, 7001000.0, -600.0]",
        "overburden_E = { point = [504000.0, 7010000.0, -600.0]",
    );
    let needles = [
        "didactic.toml:34:37",
        "^^^^^^^^^",
        "region `overburden_E`: the point [504000, 7010000, -600] is outside the box [500000, 7000000, -2500]..[505000, 7005000, 0]",
        "y = 7010000 is above the box's `max` y = 7005000",
        "`[box]` (line 16)",
        "move the point into its region or widen the box",
    ];
    fails_with(&s, &["check", "didactic.toml"], &needles);
    assert!(
        !s.path(".recipe").exists(),
        "check builds nothing and writes no cache"
    );
    fails_with(&s, &["build", "didactic.toml"], &needles);
    assert!(
        !s.path("out").exists(),
        "the build stops before any node runs"
    );
}

#[test]
fn a_region_point_on_a_surface_fails_the_model_at_its_regions_line_with_the_fix() {
    let s = Scratch::didactic();
    // A vertex of H1, inside the box but on the horizon: strictly inside no region.
    s.edit(
        "[output]",
        "on_h1 = { point = [501068.203, 7001122.535, -1161.209] }\n\n[output]",
    );
    model_fails_saying(
        &s,
        &[],
        &[
            "error: `model` failed: region name `on_h1`: the point",
            "is strictly inside no region",
            "--> didactic.toml:40:1\n",
            "\n40 | on_h1 = { point = [501068.203, 7001122.535, -1161.209] }\n   | ^^^^^\n",
            "= help: the point is inside the model's extent but in no region: it lies on a surface",
            "move it off the surfaces",
        ],
    );
}

#[test]
fn a_box_that_meets_no_surface_fails_the_model_at_the_box_line_naming_each_extent() {
    let s = Scratch::didactic();
    s.edit(
        "min = [500000.0, 7000000.0, -2500.0]\nmax = [505000.0, 7005000.0, 0.0]",
        "min = [0.0, 0.0, -2500.0]\nmax = [5000.0, 5000.0, 0.0]",
    );
    // The regions' points would be outside this box too, which the recipe check reports first.
    let p = s.recipe();
    let text = std::fs::read_to_string(&p).unwrap();
    let kept: Vec<&str> = text.lines().filter(|l| !l.contains("point =")).collect();
    std::fs::write(&p, kept.join("\n")).unwrap();
    let err = model_fails_saying(
        &s,
        &[],
        &[
            "error: `model` failed: the box [0, 0, -2500]..[5000, 5000, 0] meets no imported surface",
            "--> didactic.toml:16:1\n",
            "\n16 | [box]\n   | ^^^^^\n",
            "`F2` spans [502600, 7003125, -1503.109]..[504200, 7003475, -896.891]",
            "different coordinates",
            "give `[box]` corners that cover the surfaces, or write `around = [\"F1\", \"F2\", \"H1\", \"H2\"]`",
        ],
    );
    assert!(!err.contains("matches no curve"), "{err}");
}

#[test]
fn an_intersected_surface_outside_the_box_fails_the_model_at_the_box_line_with_the_fix() {
    let s = Scratch::didactic();
    // F2 spans y 7003125..7003475: a box ending at 7003000 leaves it out.
    s.edit(
        "max = [505000.0, 7005000.0, 0.0]",
        "max = [505000.0, 7003000.0, 0.0]",
    );
    let err = model_fails_saying(
        &s,
        &[],
        &[
            "error: `model` failed: the surface `F2`, listed in `[intersect]`, lies entirely outside the box [500000, 7000000, -2500]..[505000, 7003000, 0]",
            "(y 7003125..7003475 against the box's 7000000..7003000)",
            "\n16 | [box]\n   | ^^^^^\n",
            "= help: widen `[box]` to cover it, or, if it is not part of this model, remove `F2` from `[intersect]`",
        ],
    );
    assert!(!err.contains("matches no curve"), "{err}");
}

#[test]
fn two_surfaces_that_meet_without_an_intersect_pair_are_named_with_the_pair_to_add() {
    let s = Scratch::didactic();
    s.edit(
        "pairs = [[\"F2\", \"H1\"], [\"F2\", \"H2\"]]",
        "pairs = [[\"F2\", \"H1\"]]",
    );
    let (_, r, err) = s.build(&[]);
    assert!(
        err.contains("surfaces `F2` and `H2` meet") && err.contains("add `[\"F2\", \"H2\"]`"),
        "{err}"
    );
    let crossings = r["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|n| n["name"] == "crossings")
        .expect("the check ran");
    assert_eq!(crossings["counts"]["unpaired"], 1);
    let report = std::fs::read_to_string(s.path("out/didactic/report.json")).unwrap();
    assert!(report.contains("`[intersect]` does not pair them"));
    // With the pair back, nothing is unpaired.
    s.edit(
        "pairs = [[\"F2\", \"H1\"]]",
        "pairs = [[\"F2\", \"H1\"], [\"F2\", \"H2\"]]",
    );
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert!(!err.contains("does not pair"), "{err}");
}

#[test]
fn a_recipe_that_is_not_utf8_is_refused_at_the_line_and_column_of_the_byte() {
    let s = Scratch::didactic();
    let p = s.recipe();
    let text = std::fs::read(&p).unwrap();
    let at = text
        .windows(18)
        .position(|w| w == b"name = \"didactic\"\n")
        .unwrap();
    let mut bytes = text[..at].to_vec();
    bytes.extend_from_slice(b"name = \"d\xe9mo\"\n");
    bytes.extend_from_slice(&text[at + 18..]);
    std::fs::write(&p, &bytes).unwrap();
    let line = text[..at].iter().filter(|&&b| b == b'\n').count() + 1;
    fails_with(
        &s,
        &["check", "didactic.toml"],
        &[
            &format!("didactic.toml:{line}:10: the recipe is not UTF-8 text (byte 0xe9 here)"),
            "save the recipe as UTF-8",
        ],
    );
}

#[test]
fn a_fifo_given_as_a_surface_file_is_named_as_a_fifo_and_nothing_blocks() {
    let s = Scratch::didactic();
    let fifo = s.path("data/pipe.ts");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|st| st.success()) {
        eprintln!("skipped: mkfifo is not available");
        return;
    }
    s.edit("data/didactic/F2_dangling.ts", "data/pipe.ts");
    let needles = ["file `data/pipe.ts` of surface `F2` is a FIFO (a named pipe), not a file"];
    fails_with(&s, &["check", "didactic.toml"], &needles);
    fails_with(&s, &["build", "didactic.toml"], &needles);
}

#[test]
fn a_surface_that_reaches_past_the_box_uncut_is_named_as_meshed_nowhere() {
    // A flat sheet 300 m down, wider than the box, in `[surfaces]` but in no `[intersect]`
    // entry: uncut, it reaches past the box, so all of it is discarded.
    let s = Scratch::didactic();
    std::fs::write(
        s.path("data/didactic/sheet.ts"),
        "GOCAD TSurf 1\nHEADER {\nname:sheet\n}\nTFACE\nVRTX 1 499000 6999000 -300\n\
         VRTX 2 506000 6999000 -300\nVRTX 3 506000 7006000 -300\nVRTX 4 499000 7006000 -300\n\
         TRGL 1 2 3\nTRGL 1 3 4\nEND\n",
    )
    .unwrap();
    s.edit(
        "F2 = { file",
        "S = { file = \"data/didactic/sheet.ts\", kind = \"horizon\" }\nF2 = { file",
    );
    let (_, r, err) = s.build(&[]);
    let said = "didactic.toml:14:1: surface `S` has no part in the model, so it is meshed \
                nowhere: it is not cut by the box";
    assert!(err.contains(said), "{err}");
    assert!(err.contains("`all = [\"box\", \"S\", ...]`"), "{err}");
    assert!(
        r["model"]["patches"].as_array().is_some(),
        "the model was built"
    );
    let report = std::fs::read_to_string(s.path("out/didactic/report.json")).unwrap();
    assert!(report.contains("surface `S` has no part in the model"));
}

#[test]
fn a_surface_its_trims_discard_whole_is_named_as_meshed_nowhere_and_one_kept_is_not() {
    let s = Scratch::didactic();
    s.edit("\"F2\" = { size = 100.0 }\n", "");
    let recipe = std::fs::read_to_string(s.recipe()).unwrap();
    std::fs::write(
        s.recipe(),
        format!("{recipe}\n[[trim]]\nsurface = \"F2\"\ndiscard = {{ area_below = 1e12 }}\n"),
    )
    .unwrap();
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert!(
        err.contains(
            "surface `F2` has no part in the model, so it is meshed nowhere: the `[[trim]]` \
             entries that select it discarded all of it"
        ),
        "{err}"
    );
    assert!(!err.contains("`H1` has no part"), "{err}");
}
