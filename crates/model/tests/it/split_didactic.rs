//! The whole splitting chain on the shipped didactic model: every surface (horizons, faults,
//! box sides) is split along all its intersection curves, its patches are extracted, those
//! inside the box are kept, and the regions they bound are found: 3 layers on each side of the
//! through-going fault F1, with the dangling fault F2 inside three of them.

use crate::intersect_support;

use geom::{BBox, TriMesh};
use gocad::import::{ImportOptions, import_surface};
use model::intersect::split::{SplitSurface, split_model};
use model::intersect::{Intersection, SurfaceRef, box_sides, intersect};
use model::patches::{Patch, inside_box, patches};
use model::regions::{PatchIn, RegionOptions, find_regions_with};

const FILES: [(&str, &str); 4] = [
    ("H1", "H1_top_reservoir.ts"),
    ("H2", "H2_base_reservoir.ts"),
    ("F1", "F1_through.ts"),
    ("F2", "F2_dangling.ts"),
];

fn bbox() -> BBox {
    BBox {
        min: [500_000.0, 7_000_000.0, -2500.0],
        max: [505_000.0, 7_005_000.0, 0.0],
    }
}

/// All surfaces (geology then box sides) and the intersections the model needs.
fn model() -> (Vec<(String, TriMesh)>, Vec<Intersection>) {
    let dir = concat!(
        concat!(env!("CARGO_MANIFEST_DIR"), "/../.."),
        "/recipes/data/didactic/"
    );
    let mut surfaces: Vec<(String, TriMesh)> = FILES
        .iter()
        .map(|(name, file)| {
            let bytes = std::fs::read(format!("{dir}{file}")).expect("didactic data is shipped");
            let s = import_surface(&bytes, file, &ImportOptions::default()).expect("imports");
            (name.to_string(), s.mesh)
        })
        .collect();
    surfaces.extend(box_sides(&bbox()));
    let r = |n: &str| {
        let (name, mesh) = surfaces.iter().find(|s| s.0 == n).expect("known surface");
        SurfaceRef { name, mesh }
    };
    let mut pairs: Vec<(String, String)> = [
        ("H1", "F1"),
        ("H2", "F1"),
        ("H1", "F2"),
        ("H2", "F2"),
        ("F1", "F2"),
    ]
    .iter()
    .map(|(a, b)| (a.to_string(), b.to_string()))
    .collect();
    for (g, _) in FILES {
        for (side, _) in surfaces.iter().skip(4) {
            pairs.push((g.to_string(), side.clone()));
        }
    }
    let xs = pairs
        .iter()
        .map(|(a, b)| intersect(r(a), r(b)).expect("no coplanar contact"))
        .collect();
    (surfaces, xs)
}

fn split_every_surface(
    surfaces: &[(String, TriMesh)],
    xs: &[Intersection],
) -> Vec<(String, SplitSurface)> {
    let refs: Vec<(&str, &TriMesh)> = surfaces.iter().map(|(n, m)| (n.as_str(), m)).collect();
    let split = split_model(&refs, xs).unwrap_or_else(|e| panic!("splits: {e}"));
    surfaces.iter().map(|s| s.0.clone()).zip(split).collect()
}

#[test]
fn the_didactic_model_splits_into_patches_bounding_six_regions() {
    let (surfaces, xs) = model();
    let f1f2 = xs
        .iter()
        .find(|x| x.a == "F1" && x.b == "F2")
        .expect("F1 x F2");
    assert!(f1f2.curves.is_empty(), "F1 and F2 do not meet");
    let split = split_every_surface(&surfaces, &xs);
    for ((name, s), (_, original)) in split.iter().zip(&surfaces) {
        eprintln!("{name}: {} crossings", s.crossings.len());
        intersect_support::assert_sound(original, s);
    }
    // Where F1 meets a horizon and box.ymin or box.ymax, the three surfaces share one vertex.
    let crossing_bits = |n: &str| {
        let s = &split.iter().find(|s| s.0 == n).expect("surface").1;
        let mut v: Vec<[u64; 3]> = s
            .crossings
            .iter()
            .map(|&v| s.mesh.vertices[v as usize].map(f64::to_bits))
            .collect();
        v.sort_unstable();
        v
    };
    let (h1, h2, f1) = (
        crossing_bits("H1"),
        crossing_bits("H2"),
        crossing_bits("F1"),
    );
    let (ymin, ymax) = (crossing_bits("box.ymin"), crossing_bits("box.ymax"));
    assert_eq!(
        h1.len(),
        2,
        "H1 x F1 crosses H1 x box.ymin and H1 x box.ymax"
    );
    assert_eq!(h2.len(), 2);
    let mut h = [h1, h2].concat();
    h.sort_unstable();
    assert_eq!(f1, h, "F1 has the same four crossings, bit for bit");
    let mut y = [ymin, ymax].concat();
    y.sort_unstable();
    assert_eq!(y, h, "and so have the box sides");
    let b = bbox();
    let mut kept: Vec<PatchIn> = Vec::new();
    for (name, s) in &split {
        let ps: Vec<Patch> = patches(name, s);
        assert!(!ps.is_empty(), "{name} has patches");
        for p in ps.into_iter().filter(|p| inside_box(p, &b)) {
            kept.push(PatchIn {
                chart_of: None,
                name: p.name,
                surface: name.clone(),
                mesh: p.mesh,
            });
        }
    }
    for g in ["H1", "H2", "F1", "F2"] {
        let n = kept.iter().filter(|p| p.surface == g).count();
        eprintln!("{g}: {n} patches inside the box");
    }
    let model = find_regions_with(&kept, &[], &RegionOptions::with_faults(["F2"]))
        .unwrap_or_else(|e| panic!("regions: {e} ({:?}, {:?})", e.surface, e.at));
    assert_eq!(model.regions.len(), 6, "3 layers x 2 sides of F1");
    let dangling_f2: Vec<&PatchIn> = model
        .dangling
        .iter()
        .map(|&i| &kept[i as usize])
        .filter(|p| p.surface == "F2")
        .collect();
    assert_eq!(
        dangling_f2.len(),
        3,
        "F2 is cut by H1 and H2 into 3 dangling patches"
    );
    let hosting = model
        .regions
        .iter()
        .filter(|r| {
            r.sides
                .iter()
                .any(|f| kept[f.patch as usize].surface == "F2")
        })
        .count();
    assert_eq!(hosting, 3, "F2 dangles inside three regions");
}
