//! The build says where the model's curves come closer than their mesh can resolve: two
//! dangling faults a few metres apart in the shipped example are named with the place and the
//! fix, and the example itself, whose closest curves are the reservoir's 35 m apart at 100 m
//! curves, gets no such warning.

use crate::common_cli;
use common_cli::*;

/// Adds `F3`, the dangling fault `F2` moved `dy` metres north, intersected with both horizons.
fn with_f3(s: &Scratch, dy: f64) {
    let f2 = std::fs::read_to_string(s.path("data/didactic/F2_dangling.ts")).expect("F2");
    let moved = |line: &str| -> String {
        let mut f: Vec<String> = line.split_whitespace().map(str::to_string).collect();
        if f.first().is_some_and(|k| k == "VRTX") {
            f[3] = format!("{:.3}", f[3].parse::<f64>().expect("y") + dy);
        }
        f.join(" ")
    };
    let f3 = (f2.lines().map(moved).collect::<Vec<_>>().join("\n"))
        .replace("name:F2_dangling", "name:F3_dangling");
    std::fs::write(s.path("data/didactic/F3_dangling.ts"), f3).expect("written");
    s.edit(
        "F2 = { file",
        "F3 = { file = \"data/didactic/F3_dangling.ts\", kind = \"fault\" }\nF2 = { file",
    );
    s.edit(
        "pairs = [[\"F2\", \"H1\"], [\"F2\", \"H2\"]]",
        "pairs = [[\"F2\", \"H1\"], [\"F2\", \"H2\"], [\"F3\", \"H1\"], [\"F3\", \"H2\"]]",
    );
}

#[test]
fn two_dangling_faults_five_metres_apart_are_named_with_the_place_and_the_fix() {
    let s = Scratch::didactic();
    with_f3(&s, 5.0);
    let (_, _, err) = s.build(&[]);
    let warning = (err.lines())
        .find(|l| l.contains("Warning curves") && l.contains("come within"))
        .unwrap_or_else(|| panic!("no warning about close curves in:\n{err}"));
    for needle in ["`F2#", "`F3#", "of each other", "mesh size 100"] {
        assert!(warning.contains(needle), "`{needle}` not in: {warning}");
    }
    assert!(
        warning.contains("`[[mesh.refine]]` with `curve = "),
        "{warning}"
    );
}

#[test]
fn the_shipped_example_and_faults_apart_by_a_few_elements_get_no_such_warning() {
    let s = Scratch::didactic();
    let (ok, _, err) = s.build(&[]);
    assert!(ok, "{err}");
    assert!(!err.contains("come within"), "{err}");
    let s = Scratch::didactic();
    with_f3(&s, 300.0);
    let (_, _, err) = s.build(&[]);
    assert!(!err.contains("come within"), "{err}");
}
