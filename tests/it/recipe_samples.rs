//! The sample bad recipes under `tests/data/recipes/bad/` each fail with the error their first
//! line announces (`# expect: LINE:COL: message | help`), at that position; the good samples
//! parse.

use std::path::{Path, PathBuf};

use georecipe::recipe::parse;

fn samples(dir: &str) -> Vec<PathBuf> {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/recipes")).join(dir);
    let mut v: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    v.sort();
    v
}

#[test]
fn every_bad_sample_fails_where_and_how_its_header_says() {
    let files = samples("bad");
    assert!(files.len() >= 8, "bad samples present");
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        let expect = text
            .lines()
            .next()
            .and_then(|l| l.strip_prefix("# expect: "))
            .unwrap_or_else(|| panic!("{} has no `# expect:` header", path.display()));
        let (pos, rest) = expect.split_once(": ").unwrap_or((expect, ""));
        let (message, help) = rest
            .split_once(" | ")
            .map_or((rest, None), |(m, h)| (m, Some(h)));
        let label = format!(
            "bad/{}",
            path.file_name().and_then(|n| n.to_str()).unwrap_or("")
        );
        let d = match parse(Path::new(&label), &text) {
            Ok(_) => panic!("{label} parsed"),
            Err(d) => d,
        };
        let all: String = d.iter().map(|d| format!("{d}\n")).collect();
        let hit = d
            .iter()
            .find(|d| format!("{}:{}", d.line, d.col) == pos && d.message.contains(message));
        let Some(hit) = hit else {
            panic!("{label}: no error `{message}` at {pos}; got:\n{all}")
        };
        assert!(hit.to_string().contains(&format!("{label}:{pos}")), "{hit}");
        if let Some(h) = help {
            assert!(
                hit.help.as_deref().is_some_and(|x| x.contains(h)),
                "{label}: help lacks `{h}`:\n{hit}"
            );
        }
    }
}

#[test]
fn every_good_sample_parses() {
    for path in samples("") {
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        if let Err(d) = parse(&path, &text) {
            panic!(
                "{}:\n{}",
                path.display(),
                d.iter()
                    .map(|d| d.to_string())
                    .collect::<Vec<_>>()
                    .join("\n")
            );
        }
    }
}
