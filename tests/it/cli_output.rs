//! What `recipe build` prints on stderr: calm by default (a line per node that ran, one line
//! counting the cached ones, a short summary and the final line), every node and the quality
//! tables with `-v`, only the final line with `--quiet`.

use crate::common_cli;
use common_cli::*;
use std::collections::BTreeSet;

/// The stderr lines and the JSON report of `recipe build --json ARGS didactic.toml`.
fn build_lines(s: &Scratch, extra: &[&str]) -> (Vec<String>, serde_json::Value) {
    let (ok, r, err) = s.build(extra);
    assert!(ok, "{err}");
    (err.lines().map(String::from).collect(), r)
}

/// The nodes that have a status line of their own (`Verb name ...`).
fn nodes_with_a_line(lines: &[String], report: &serde_json::Value) -> BTreeSet<String> {
    let all: BTreeSet<String> = all_nodes(report).into_iter().collect();
    lines
        .iter()
        .filter_map(|l| l.split_whitespace().nth(1))
        .filter(|n| all.contains(*n))
        .map(String::from)
        .collect()
}

#[test]
fn a_no_op_build_of_the_example_prints_a_handful_of_lines_and_no_line_per_cached_node() {
    let s = Scratch::didactic_built();
    let (lines, r) = build_lines(&s, &[]);
    assert!(lines.len() <= 5, "{lines:#?}");
    assert_eq!(nodes_with_a_line(&lines, &r), BTreeSet::new(), "{lines:#?}");
    let cached: Vec<&String> = lines.iter().filter(|l| l.contains("Cached")).collect();
    let all = all_nodes(&r).len();
    assert!(all > 200, "{all} nodes");
    assert_eq!(cached.len(), 1, "{lines:#?}");
    assert!(
        cached[0].contains(&format!("Cached {all} nodes")),
        "{cached:?}"
    );
    assert!(!lines.iter().any(|l| l.contains("Table")), "{lines:#?}");
    assert!(lines.last().unwrap().trim_start().starts_with("Finished"));
}

#[test]
fn verbose_lists_every_node_and_prints_both_quality_tables() {
    let s = Scratch::didactic_built();
    let (lines, r) = build_lines(&s, &["-v"]);
    let listed = nodes_with_a_line(&lines, &r);
    let missing: Vec<String> = all_nodes(&r)
        .into_iter()
        .filter(|n| !listed.contains(n))
        .collect();
    assert_eq!(missing, Vec::<String>::new());
    let text = lines.join("\n");
    assert!(
        text.contains("Table 1") && text.contains("Table 2"),
        "{text}"
    );
}

#[test]
fn after_one_edit_the_build_prints_a_line_for_each_node_that_re_ran_and_none_for_the_cached_ones() {
    let s = Scratch::didactic_built();
    s.edit(
        "[regions]",
        "[mesh.regions.underburden_W]\ngrowth = 1.25\n\n[regions]",
    );
    let (lines, r) = build_lines(&s, &[]);
    let ran: BTreeSet<String> = nodes_in_state(&r, "ran").into_iter().collect();
    let expected: BTreeSet<String> = ["export", "mesh", "tet_mesh:underburden_W"]
        .map(String::from)
        .into();
    assert_eq!(ran, expected);
    assert_eq!(nodes_with_a_line(&lines, &r), ran, "{lines:#?}");
    let cached = all_nodes(&r).len() - ran.len();
    assert!(
        lines
            .iter()
            .any(|l| l.contains(&format!("Cached {cached} nodes"))),
        "{lines:#?}"
    );
}

#[test]
fn the_summary_names_the_region_count_the_tet_count_the_worst_tet_and_the_files() {
    let s = Scratch::didactic_built();
    let (lines, r) = build_lines(&s, &[]);
    let tets = r["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|n| n["name"] == "mesh")
        .expect("the mesh node")["counts"]["tets"]
        .as_u64()
        .unwrap();
    let quality: serde_json::Value = serde_json::from_slice(
        &std::fs::read(s.path("out/didactic/didactic.quality.json")).unwrap(),
    )
    .unwrap();
    let all = quality["table2"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["name"] == "all")
        .unwrap();
    let mesh = lines
        .iter()
        .find(|l| l.trim_start().starts_with("Mesh "))
        .unwrap_or_else(|| panic!("no summary: {lines:#?}"));
    for said in [
        "6 regions".to_string(),
        format!("{tets} tets"),
        format!("mean ratio {:.4}", all["min"].as_f64().unwrap()),
        format!("dihedral {:.2}°", all["min_dihedral_deg"].as_f64().unwrap()),
    ] {
        assert!(mesh.contains(&said), "`{said}` not in {mesh}");
    }
    let outputs = lines
        .iter()
        .find(|l| l.trim_start().starts_with("Outputs "))
        .unwrap_or_else(|| panic!("no output files: {lines:#?}"));
    for f in [
        "didactic.msh",
        "didactic.vtu",
        "validation.json",
        "report.html",
    ] {
        assert!(outputs.contains(f), "`{f}` not in {outputs}");
    }
}

#[test]
fn quiet_prints_only_the_final_line() {
    let s = Scratch::didactic_built();
    s.edit(
        "[regions]",
        "[mesh.regions.underburden_W]\nsize = 150.0\n\n[regions]",
    );
    for _ in 0..2 {
        // The first build re-runs three nodes, the second none.
        let (lines, _) = build_lines(&s, &["--quiet"]);
        assert_eq!(lines.len(), 1, "{lines:#?}");
        assert!(lines[0].trim_start().starts_with("Finished"), "{lines:#?}");
    }
    let (lines, _) = build_lines(&s, &["--quiet", "--explain"]);
    assert_eq!(lines.len(), 1, "{lines:#?}");
}
