//! The degenerate-contact corpus in tests/data/intersect: each JSON file holds two small
//! surfaces at UTM coordinates and what their intersection must be (number and shape of curves,
//! which kinds of point keys appear — named from the surface whose name sorts first —, touch points, coplanar pairs or a coplanar error). Every
//! case is run in both argument orders.

use crate::intersect_support;

use geom::TriMesh;
use intersect_support::both;
use model::intersect::IntersectError;
use serde::Deserialize;
use std::collections::BTreeSet;
use std::path::Path;

#[derive(Deserialize)]
struct Surface {
    name: String,
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
}

#[derive(Deserialize)]
struct Expect {
    #[serde(default)]
    error: Option<String>,
    #[serde(default)]
    curves: Vec<(bool, usize)>,
    #[serde(default)]
    touches: usize,
    #[serde(default)]
    kinds: Vec<String>,
    #[serde(default)]
    coplanar: usize,
}

#[derive(Deserialize)]
struct Case {
    description: String,
    a: Surface,
    b: Surface,
    expect: Expect,
}

fn kind(k: &model::intersect::PointKey) -> String {
    match serde_json::to_value(k) {
        Ok(serde_json::Value::Object(m)) => m.keys().next().cloned().unwrap_or_default(),
        other => panic!("unexpected key encoding {other:?}"),
    }
}

fn run(path: &Path) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let case: Case =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let name = path.display();
    let a = TriMesh::new(case.a.vertices, case.a.triangles);
    let b = TriMesh::new(case.b.vertices, case.b.triangles);
    let r = both(&case.a.name, &a, &case.b.name, &b);
    match (case.expect.error.as_deref(), r) {
        (
            Some("coplanar"),
            Err(IntersectError::Coplanar {
                a: na,
                b: nb,
                contacts,
            }),
        ) => {
            let mut names = [case.a.name.as_str(), case.b.name.as_str()];
            names.sort();
            assert_eq!([na.as_str(), nb.as_str()], names, "{name}");
            assert!(!contacts.is_empty(), "{name}");
        }
        (None, Ok(x)) => {
            let shapes: Vec<(bool, usize)> = x
                .curves
                .iter()
                .map(|c| (c.closed, c.points.len()))
                .collect();
            assert_eq!(shapes, case.expect.curves, "{name}: {}", case.description);
            assert_eq!(x.touches.len(), case.expect.touches, "{name}: touches");
            assert_eq!(
                x.coplanar.len(),
                case.expect.coplanar,
                "{name}: coplanar pairs"
            );
            let kinds: BTreeSet<String> = x
                .curves
                .iter()
                .flat_map(|c| c.points.iter().map(|p| kind(&p.key)))
                .collect();
            let expected: BTreeSet<String> = case.expect.kinds.iter().cloned().collect();
            assert_eq!(kinds, expected, "{name}: key kinds");
        }
        (e, r) => panic!(
            "{name}: expected {e:?}, got {:?}",
            r.map(|x| x.curves.len())
        ),
    }
}

#[test]
fn every_case_of_the_degenerate_corpus_gives_its_expected_curves_in_both_orders() {
    let dir = Path::new(concat!(
        concat!(env!("CARGO_MANIFEST_DIR"), "/../.."),
        "/tests/data/intersect"
    ));
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .expect("the corpus directory")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    assert!(files.len() >= 8, "corpus has {} cases", files.len());
    for f in &files {
        run(f);
    }
}
