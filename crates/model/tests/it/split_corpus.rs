//! The degenerate-splitting corpus in tests/data/split: each JSON file holds a few small surfaces
//! at UTM coordinates and what splitting them along all their pairwise intersections must give
//! (patches per surface, and how many points are curve vertices of three surfaces, bit for bit).
//! Every pair is intersected in both argument orders, and the whole model is split in both
//! orders of surfaces and intersections, which must agree.

use crate::intersect_support;

use geom::TriMesh;
use intersect_support::{assert_sound, both};
use model::intersect::Intersection;
use model::intersect::split::split_model;
use model::patches::patches;
use serde::Deserialize;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

#[derive(Deserialize)]
struct Surface {
    name: String,
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
}

#[derive(Deserialize)]
struct Expect {
    patches: BTreeMap<String, usize>,
    triple_points: usize,
}

#[derive(Deserialize)]
struct Case {
    description: String,
    surfaces: Vec<Surface>,
    expect: Expect,
}

fn run(path: &Path) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let case: Case =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let file = path.display();
    let meshes: Vec<(String, TriMesh)> = case
        .surfaces
        .into_iter()
        .map(|s| (s.name, TriMesh::new(s.vertices, s.triangles)))
        .collect();
    let mut xs: Vec<Intersection> = Vec::new();
    for i in 0..meshes.len() {
        for j in i + 1..meshes.len() {
            let ((na, a), (nb, b)) = (&meshes[i], &meshes[j]);
            let x = both(na, a, nb, b).unwrap_or_else(|e| panic!("{file}: {e}"));
            if !x.curves.is_empty() {
                xs.push(x);
            }
        }
    }
    let refs: Vec<(&str, &TriMesh)> = meshes.iter().map(|(n, m)| (n.as_str(), m)).collect();
    let fwd = split_model(&refs, &xs).unwrap_or_else(|e| panic!("{file}: {e}"));
    let rs: Vec<(&str, &TriMesh)> = refs.iter().rev().copied().collect();
    let rx: Vec<Intersection> = xs.iter().rev().cloned().collect();
    let rev = split_model(&rs, &rx).unwrap_or_else(|e| panic!("{file} reversed: {e}"));
    let mut holders: BTreeMap<[u64; 3], BTreeSet<&str>> = BTreeMap::new();
    for (k, ((name, mesh), s)) in refs.iter().zip(&fwd).enumerate() {
        let r = &rev[refs.len() - 1 - k];
        assert_eq!(s.mesh, r.mesh, "{file}: {name} differs in the other order");
        assert_eq!(s.curve_edges, r.curve_edges, "{file}: {name}");
        assert_sound(mesh, s);
        let n = patches(name, s).len();
        let want = case.expect.patches.get(*name).copied();
        assert_eq!(Some(n), want, "{file}: patches of {name}");
        for &v in s.curve_edges.iter().flatten() {
            let at = s.mesh.vertices[v as usize].map(f64::to_bits);
            holders.entry(at).or_default().insert(name);
        }
    }
    let triple = holders.values().filter(|s| s.len() >= 3).count();
    assert_eq!(
        triple, case.expect.triple_points,
        "{file}: points on curves of three surfaces ({})",
        case.description
    );
}

#[test]
fn every_case_of_the_split_corpus_splits_as_expected_in_both_orders() {
    let dir = Path::new(concat!(
        concat!(env!("CARGO_MANIFEST_DIR"), "/../.."),
        "/tests/data/split"
    ));
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .expect("the corpus is shipped")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    assert!(files.len() >= 6, "{} cases", files.len());
    for f in &files {
        run(f);
    }
}
