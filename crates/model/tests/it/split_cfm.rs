//! Real data: the SCEC Community Fault Model faults of the Big Bend (1000 m TSurf files in
//! ../shared) and the six sides of a box cutting through them, every pair intersected, every
//! surface split along all its curves at once (fault × fault × box side triple points
//! included), in both orders of surfaces and intersections.

use crate::intersect_support;

use geom::{BBox, TriMesh};
use gocad::import::{ImportOptions, import_surface};
use intersect_support::{assert_sound, both};
use model::intersect::split::split_model;
use model::intersect::{Intersection, box_sides};
use std::path::{Path, PathBuf};
use test_support::paths;

/// The faults: all of the 1000 m sample except the 1857 rupture, which overlaps the Mojave
/// segment of the San Andreas (a coplanar contact, refused by `intersect`).
const FAULTS: [&str; 8] = [
    "CRFA-BPPM-LKWV-Lockwood_Valley_fault-CFM2_1000m",
    "CRFA-BPPM-PMTS-Pine_Mountain_fault-CFM2_1000m",
    "CRFA-BPPM-WEST-Big_Pine_fault-CFM2_1000m",
    "GRFS-GRFZ-WEST-Garlock_fault-CFM5_1000m",
    "GVFA-PLFZ-MULT-Pleito_fault-CFM2_1000m",
    "GVFA-WWFZ-MULT-White_Wolf_fault-CFM5_1000m",
    "SAFS-SAFZ-CRRZ-San_Andreas_fault-CFM4_1000m",
    "SAFS-SAFZ-MJVS-San_Andreas_fault-CFM4_1000m",
];

fn cfm_dir() -> Option<PathBuf> {
    paths::shared("data/gocad/SCECcode__CFM/CFM5.3_4/ts/1000m")
}

fn load(dir: &Path, stem: &str) -> TriMesh {
    let path = dir.join(format!("{stem}.ts"));
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    import_surface(&bytes, stem, &ImportOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .mesh
}

/// A box around all the faults whose east, south and top sides go through the middles of the
/// first three fault × fault curves, so that each of those curves ends on a box side inside a
/// face of it: a point shared by two faults and the side.
fn cutting_box(meshes: &[TriMesh], xs: &[Intersection]) -> BBox {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in meshes.iter().flat_map(|m| &m.vertices) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let mid = |i: usize| {
        let c = &xs[i].curves[0].points;
        c[c.len() / 2].xyz.map(|v| v.round() + 0.25)
    };
    BBox {
        min: [lo[0] - 1000.0, mid(1)[1], lo[2] - 1000.0],
        max: [mid(0)[0], hi[1] + 1000.0, mid(2)[2]],
    }
}

#[test]
fn the_big_bend_faults_and_a_box_through_them_split_soundly_in_both_orders() {
    let Some(dir) = cfm_dir() else { return };
    let meshes: Vec<TriMesh> = FAULTS.iter().map(|s| load(&dir, s)).collect();
    let mut surfaces: Vec<(String, TriMesh)> = FAULTS
        .iter()
        .map(|s| s.to_string())
        .zip(meshes.iter().cloned())
        .collect();
    let mut xs: Vec<Intersection> = Vec::new();
    let pairs = |surfaces: &[(String, TriMesh)], from: usize, xs: &mut Vec<Intersection>| {
        for i in 0..surfaces.len() {
            for j in (i + 1).max(from)..surfaces.len() {
                let ((na, a), (nb, b)) = (&surfaces[i], &surfaces[j]);
                if na.starts_with("box.") && nb.starts_with("box.") {
                    continue;
                }
                let x = both(na, a, nb, b).unwrap_or_else(|e| panic!("{e}"));
                if !x.curves.is_empty() {
                    xs.push(x);
                }
            }
        }
    };
    pairs(&surfaces, 0, &mut xs);
    let meeting_faults = xs.len();
    assert!(meeting_faults >= 3, "several faults meet: {meeting_faults}");
    surfaces.extend(box_sides(&cutting_box(&meshes, &xs)));
    pairs(&surfaces, FAULTS.len(), &mut xs);
    eprintln!(
        "{} intersections, {meeting_faults} between faults",
        xs.len()
    );
    let refs: Vec<(&str, &TriMesh)> = surfaces.iter().map(|(n, m)| (n.as_str(), m)).collect();
    let fwd = split_model(&refs, &xs).unwrap_or_else(|e| panic!("{e}"));
    let rs: Vec<(&str, &TriMesh)> = refs.iter().rev().copied().collect();
    let rx: Vec<Intersection> = xs.iter().rev().cloned().collect();
    let rev = split_model(&rs, &rx).unwrap_or_else(|e| panic!("reversed: {e}"));
    let mut crossings = 0;
    for (k, ((name, mesh), s)) in refs.iter().zip(&fwd).enumerate() {
        assert_sound(mesh, s);
        let r = &rev[refs.len() - 1 - k];
        assert_eq!(s.mesh, r.mesh, "{name}: the same split in both orders");
        assert_eq!(s.curve_edges, r.curve_edges, "{name}");
        crossings += s.crossings.len();
    }
    eprintln!("{crossings} crossings inside faces");
    assert!(
        crossings >= 3,
        "fault curves end on box sides inside faces: {crossings}"
    );
}
