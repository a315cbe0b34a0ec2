//! Support re-triangulation with the surface mesher on real exports: the shipped didactic
//! horizon (an irregular gOcad-like triangulation at UTM coordinates) and a real SCEC CFM fault
//! (San Andreas 1857 rupture, 1000 m resolution, from ../shared). Shape and borders are kept.

use geom::TriMesh;
use surface_mesh::quality::stats;
use surface_mesh::retriangulate;
use test_support::paths;

/// A minimal TSurf reader for these fixtures (VRTX/PVRTX and TRGL), welding vertices with
/// bit-identical coordinates (the repair the import stage does on seams).
fn read_tsurf(text: &str) -> TriMesh {
    let mut ids = std::collections::BTreeMap::new();
    let mut at = std::collections::BTreeMap::new();
    let mut vs: Vec<[f64; 3]> = Vec::new();
    let mut ts = Vec::new();
    for line in text.lines() {
        let f: Vec<&str> = line.split_whitespace().collect();
        match f.first() {
            Some(&"VRTX") | Some(&"PVRTX") => {
                let id: u64 = f[1].parse().unwrap();
                let p: [f64; 3] = [
                    f[2].parse().unwrap(),
                    f[3].parse().unwrap(),
                    f[4].parse().unwrap(),
                ];
                let k = *at.entry(p.map(f64::to_bits)).or_insert_with(|| {
                    vs.push(p);
                    (vs.len() - 1) as u32
                });
                ids.insert(id, k);
            }
            Some(&"TRGL") => {
                let g = |k: usize| ids[&f[k].parse::<u64>().unwrap()];
                let t = [g(1), g(2), g(3)];
                if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                    ts.push(t);
                }
            }
            _ => {}
        }
    }
    TriMesh::new(vs, ts)
}

fn border_edges(m: &TriMesh) -> Vec<([f64; 3], [f64; 3])> {
    let mut directed = std::collections::BTreeSet::new();
    for t in &m.triangles {
        for i in 0..3 {
            directed.insert((t[i], t[(i + 1) % 3]));
        }
    }
    directed
        .iter()
        .filter(|(a, b)| !directed.contains(&(*b, *a)))
        .map(|&(a, b)| (m.vertices[a as usize], m.vertices[b as usize]))
        .collect()
}

fn dist_to_segment(p: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let ab: Vec<f64> = (0..3).map(|k| b[k] - a[k]).collect();
    let ap: Vec<f64> = (0..3).map(|k| p[k] - a[k]).collect();
    let l2: f64 = ab.iter().map(|x| x * x).sum();
    let t = if l2 > 0.0 {
        (ap.iter().zip(&ab).map(|(x, y)| x * y).sum::<f64>() / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (0..3)
        .map(|k| (a[k] + t * ab[k] - p[k]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// The new border runs along the old one, the area is kept, the shapes are good.
fn check(old: &TriMesh, new: &TriMesh, size: f64, max_mean: f64) {
    let old_border = border_edges(old);
    for (a, _) in border_edges(new) {
        let d = old_border
            .iter()
            .map(|(p, q)| dist_to_segment(&a, p, q))
            .fold(f64::INFINITY, f64::min);
        assert!(
            d < 1e-6 * size,
            "new border node {a:?} is {d} off the old border"
        );
    }
    let (ao, an) = (old.area(), new.area());
    assert!((an - ao).abs() < 0.01 * ao, "area {ao} became {an}");
    let q = stats(&new.vertices, &new.triangles);
    eprintln!(
        "RETRI tris {} -> {} mean {:.4} sd {:.4} max {:.3} >1.15 {:.2}% >1.5 {:.2}%",
        old.triangles.len(),
        q.triangles,
        q.mean,
        q.sd,
        q.max,
        q.pct_above_1_15,
        q.pct_above_1_5
    );
    assert!(q.mean <= max_mean, "mean c/c* {}", q.mean);
}

#[test]
fn the_shipped_didactic_horizon_is_retriangulated_at_100_m_keeping_its_border_and_area() {
    let path = paths::repo().join("recipes/data/didactic/H1_top_reservoir.ts");
    let Ok(text) = std::fs::read_to_string(&path) else {
        eprintln!("skipping: {} is absent", path.display());
        return;
    };
    let old = read_tsurf(&text);
    let new = retriangulate(&old, 100.0).unwrap_or_else(|e| panic!("{e}"));
    check(&old, &new, 100.0, 1.03);
    // The border corners (box corners of the horizon) are kept bit for bit.
    let xs: Vec<f64> = old.vertices.iter().map(|p| p[0]).collect();
    let xmin = xs.iter().copied().fold(f64::INFINITY, f64::min);
    let corner = old.vertices.iter().find(|p| p[0] == xmin).copied().unwrap();
    assert!(
        new.vertices
            .iter()
            .any(|p| p.map(f64::to_bits) == corner.map(f64::to_bits))
    );
}

fn cfm(name: &str) -> Option<TriMesh> {
    let path = paths::shared(&format!(
        "data/gocad/SCECcode__CFM/CFM5.3_4/ts/1000m/{name}"
    ))?;
    let text = std::fs::read_to_string(&path).expect("read");
    Some(read_tsurf(&text))
}

#[test]
fn the_real_garlock_fault_is_retriangulated_on_its_support() {
    let Some(old) = cfm("GRFS-GRFZ-WEST-Garlock_fault-CFM5_1000m.ts") else {
        return;
    };
    let new = retriangulate(&old, 1500.0).unwrap_or_else(|e| panic!("{e}"));
    check(&old, &new, 1500.0, 1.10);
}

#[test]
fn the_merged_san_andreas_1857_fault_with_opposite_patches_is_refused_with_the_place() {
    // Its merged pieces are oriented oppositely: once the seams are welded, an edge is used twice
    // in the same direction. The mesher must say so, with the edge and the place, not guess.
    let Some(old) = cfm("SAFS-SAFZ-1857-San_Andreas_fault_rupture-CFM5_1000m.ts") else {
        return;
    };
    let e = retriangulate(&old, 2000.0).unwrap_err();
    let at = e.at.expect("a place");
    assert!(old.vertices.contains(&at), "{e}");
    assert!(e.to_string().contains("same direction"), "{e}");
}

#[test]
fn a_border_turn_is_kept_as_a_corner_only_above_the_kink_angle_given() {
    // A square whose top border bends up by 16° at (300, 1060).
    let apex = [300.0, 1060.0, 0.0];
    let m = TriMesh::new(
        vec![
            [500.0, 500.0, 0.0],
            [0.0, 0.0, 0.0],
            [1000.0, 0.0, 0.0],
            [1000.0, 1000.0, 0.0],
            apex,
            [0.0, 1000.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5], [0, 5, 1]],
    );
    let has_apex = |kink: f64| {
        let new = surface_mesh::retriangulate_keeping(&m, 130.0, &[], kink)
            .unwrap_or_else(|e| panic!("{e}"));
        new.vertices.contains(&apex)
    };
    assert!(has_apex(10.0), "a 16° turn is a corner at a 10° kink angle");
    assert!(
        !has_apex(30.0),
        "and not at 30°: the border is resampled through it"
    );
}
