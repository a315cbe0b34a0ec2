//! The tet optimizer must reach the seed's bar (mean ratio at least 0.3, smallest
//! dihedral at least 10°) wherever the boundary allows it, on region inputs cut from our shipped
//! example (`tests/data/tet_mesh/quality/README.md` says where each case comes from and what
//! the boundary forces). Every mesh is verified exactly inside `mesh_region`.

use std::collections::BTreeMap;
use std::path::Path;

use tet_mesh::{RegionInput, SizeField, TetMeshOptions, TetMeshOutput, mesh_region, quality};

fn read_off(path: &Path) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let text = std::fs::read_to_string(path).expect("case file");
    let mut it = text.split_whitespace();
    assert_eq!(it.next(), Some("OFF"), "{}", path.display());
    let mut num = || it.next().expect("number").to_string();
    let n: usize = num().parse().expect("vertex count");
    let m: usize = num().parse().expect("face count");
    num();
    let vertices = (0..n)
        .map(|_| [0; 3].map(|_| num().parse::<f64>().expect("coordinate")))
        .collect();
    let faces = (0..m)
        .map(|_| {
            assert_eq!(num(), "3");
            [0; 3].map(|_| num().parse::<u32>().expect("index"))
        })
        .collect();
    (vertices, faces)
}

/// The boundary and its embedded triangles, matched to the boundary's vertices by exact
/// coordinates.
pub fn case(name: &str) -> RegionInput {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join("tests/data/tet_mesh/quality");
    let (mut vertices, boundary) = read_off(&dir.join(format!("{name}.off")));
    let (ev, ef) = read_off(&dir.join(format!("{name}.embedded.off")));
    let mut ids: BTreeMap<[u64; 3], u32> = vertices
        .iter()
        .enumerate()
        .map(|(i, p)| (p.map(f64::to_bits), i as u32))
        .collect();
    let map: Vec<u32> = ev
        .iter()
        .map(|p| {
            *ids.entry(p.map(f64::to_bits)).or_insert_with(|| {
                vertices.push(*p);
                (vertices.len() - 1) as u32
            })
        })
        .collect();
    let embedded = ef.iter().map(|f| f.map(|i| map[i as usize])).collect();
    RegionInput {
        name: name.into(),
        vertices,
        boundary,
        embedded,
        lines: Vec::new(),
    }
}

/// The shipped build's size field (`[mesh] size = 200` with the recipe defaults).
pub fn build_size() -> SizeField {
    SizeField {
        size: 200.0,
        min_size: 2.0,
        max_size: 2000.0,
        growth: 1.3,
        refine: Vec::new(),
    }
}

/// The tets below the bar: (mean ratio, min dihedral, tet).
fn below_bar(out: &TetMeshOutput) -> Vec<(f64, f64, [u32; 4])> {
    out.tets
        .iter()
        .filter_map(|&t| {
            let [a, b, c, d] = t.map(|i| out.nodes[i as usize]);
            let q = quality::mean_ratio(&a, &b, &c, &d);
            let dh = quality::min_dihedral_deg(&a, &b, &c, &d);
            (q < 0.3 || dh < 10.0).then_some((q, dh, t))
        })
        .collect()
}

#[test]
fn the_shipped_east_overburden_around_the_dangling_fault_reaches_the_bar() {
    let input = case("shipped_overburden_E");
    let out = mesh_region(&input, &build_size(), &TetMeshOptions::default()).expect("meshes");
    let s = &out.stats;
    assert!(s.min_mean_ratio >= 0.3, "{s:?}");
    assert!(s.min_dihedral_deg >= 10.0, "{s:?}");
    assert!(below_bar(&out).is_empty());
    // The optimizer must not buy the worst tet with the average.
    assert!(s.avg_mean_ratio >= 0.8, "{s:?}");
}

#[test]
fn the_shipped_east_reservoir_misses_the_bar_only_on_tets_pinned_to_the_boundary() {
    let input = case("shipped_reservoir_E");
    let out = mesh_region(&input, &build_size(), &TetMeshOptions::default()).expect("meshes");
    let s = &out.stats;
    // Where the 35 m layer's boundary forces it (README): the corner tet on two boundary faces
    // is bounded near 0.31 and is 0.269 today; mid-layer apexes over 200 m triangles give ~10°.
    assert!(s.min_mean_ratio >= 0.26, "{s:?}");
    assert!(s.min_dihedral_deg >= 9.0, "{s:?}");
    let faces: std::collections::BTreeSet<[u32; 3]> = input
        .boundary
        .iter()
        .map(|f| {
            let mut k = *f;
            k.sort_unstable();
            k
        })
        .collect();
    let bad = below_bar(&out);
    // 8 with the front, 9 with the Delaunay method: all of them on a boundary face (below).
    assert!(bad.len() <= 12, "{} tets below the bar", bad.len());
    for (q, dh, t) in bad {
        let on_boundary = [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]
            .iter()
            .any(|f| {
                let mut k = f.map(|i| t[i]);
                k.sort_unstable();
                faces.contains(&k)
            });
        assert!(
            on_boundary,
            "a free tet below the bar: MR {q}, {dh}° at {:?}",
            out.nodes[t[0] as usize]
        );
    }
}
