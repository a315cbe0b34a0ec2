//! Real data: intersecting SCEC Community Fault Model faults (1000 m resolution TSurf files in
//! ../shared). A tiny VRTX/PVRTX/ATOM/TRGL reader lives here; the real importer is elsewhere.

use crate::intersect_support;

use geom::TriMesh;
use intersect_support::both;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use test_support::paths;

fn cfm_dir() -> Option<PathBuf> {
    paths::shared("data/gocad/SCECcode__CFM/CFM5.3_4/ts/1000m")
}

fn bad<T>(path: &Path, n: usize, line: &str) -> T {
    panic!("{}:{}: cannot read `{line}`", path.display(), n + 1)
}

/// Read the vertices and triangles of every TFACE of a TSurf file into one mesh.
fn read_tsurf(path: &Path) -> TriMesh {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut ids: BTreeMap<u64, u32> = BTreeMap::new();
    let mut m = TriMesh::default();
    for (n, line) in text.lines().enumerate() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.first().copied() {
            Some("VRTX" | "PVRTX") if w.len() >= 5 => {
                let id: u64 = w[1].parse().unwrap_or_else(|_| bad(path, n, line));
                let p =
                    [2, 3, 4].map(|k| w[k].parse::<f64>().unwrap_or_else(|_| bad(path, n, line)));
                ids.insert(id, m.vertices.len() as u32);
                m.vertices.push(p);
            }
            Some("ATOM" | "PATOM") if w.len() >= 3 => {
                let id: u64 = w[1].parse().unwrap_or_else(|_| bad(path, n, line));
                let of: u64 = w[2].parse().unwrap_or_else(|_| bad(path, n, line));
                let v = *ids.get(&of).unwrap_or_else(|| bad(path, n, line));
                ids.insert(id, v);
            }
            Some("TRGL") if w.len() >= 4 => {
                let t = [1, 2, 3].map(|k| {
                    let id: u64 = w[k].parse().unwrap_or_else(|_| bad(path, n, line));
                    *ids.get(&id).unwrap_or_else(|| bad(path, n, line))
                });
                m.triangles.push(t);
            }
            _ => {}
        }
    }
    m
}

fn load(dir: &Path, stem: &str) -> TriMesh {
    let m = read_tsurf(&dir.join(format!("{stem}.ts")));
    assert!(
        m.triangles.len() > 100,
        "{stem}: {} triangles",
        m.triangles.len()
    );
    m
}

fn report(x: &model::intersect::Intersection) {
    let n: usize = x.curves.iter().map(|c| c.points.len()).sum();
    eprintln!(
        "{} × {}: {} curves, {n} points, {} touches",
        x.a,
        x.b,
        x.curves.len(),
        x.touches.len()
    );
    for c in &x.curves {
        let (p, q) = (c.points[0].xyz, c.points[c.points.len() - 1].xyz);
        eprintln!(
            "  {} points, closed {}, from {p:?} to {q:?}",
            c.points.len(),
            c.closed
        );
    }
}

#[test]
fn garlock_west_crosses_pleito_in_the_same_curve_both_ways() {
    let Some(dir) = cfm_dir() else { return };
    let garlock = load(&dir, "GRFS-GRFZ-WEST-Garlock_fault-CFM5_1000m");
    let pleito = load(&dir, "GVFA-PLFZ-MULT-Pleito_fault-CFM2_1000m");
    let x = both("garlock_west", &garlock, "pleito", &pleito).expect("no coplanar contact");
    report(&x);
    assert_eq!(x.curves.len(), 1);
    assert!(x.curves[0].points.len() >= 3);
}

#[test]
fn lockwood_valley_meets_san_andreas_carrizo_in_two_curves_both_ways() {
    let Some(dir) = cfm_dir() else { return };
    let lockwood = load(&dir, "CRFA-BPPM-LKWV-Lockwood_Valley_fault-CFM2_1000m");
    let saf = load(&dir, "SAFS-SAFZ-CRRZ-San_Andreas_fault-CFM4_1000m");
    let x = both("lockwood_valley", &lockwood, "saf_carrizo", &saf).expect("no coplanar contact");
    report(&x);
    assert_eq!(x.curves.len(), 2);
}

/// In the 1000 m CFM files the western Garlock (y >= 3 853 423) stops 13 km short of the
/// Mojave San Andreas segment (y <= 3 840 486): no curve, no touch.
#[test]
fn garlock_west_and_san_andreas_mojave_do_not_meet_in_the_1000m_model() {
    let Some(dir) = cfm_dir() else { return };
    let garlock = load(&dir, "GRFS-GRFZ-WEST-Garlock_fault-CFM5_1000m");
    let saf = load(&dir, "SAFS-SAFZ-MJVS-San_Andreas_fault-CFM4_1000m");
    let x = both("garlock_west", &garlock, "saf_mojave", &saf).expect("no coplanar contact");
    assert!(x.curves.is_empty() && x.touches.is_empty());
}

/// The 1857 rupture surface re-uses 1,169 triangles of the Mojave segment, point for point, and
/// elsewhere draws the same fault again with its own, finer triangles: the two cross each other
/// at a hair's angle over and over. One part drawn twice is an error naming both and where.
#[test]
fn the_1857_rupture_drawing_the_mojave_segment_again_is_an_error_naming_both() {
    let Some(dir) = cfm_dir() else { return };
    let rupture = load(&dir, "SAFS-SAFZ-1857-San_Andreas_fault_rupture-CFM5_1000m");
    let saf = load(&dir, "SAFS-SAFZ-MJVS-San_Andreas_fault-CFM4_1000m");
    let e = both("saf_1857", &rupture, "saf_mojave", &saf).expect_err("drawn twice");
    let model::intersect::IntersectError::Redrawn {
        shared, angle, at, ..
    } = &e
    else {
        panic!("{e}")
    };
    assert_eq!(*shared, 1169);
    assert!(*angle < 1.0, "{angle}");
    assert!(saf.bbox().contains(at), "{at:?}");
    let msg = e.to_string();
    assert!(
        msg.contains("`saf_1857`") && msg.contains("`saf_mojave`"),
        "{msg}"
    );
}

#[test]
fn every_pair_of_the_sample_faults_intersects_identically_in_both_orders() {
    let Some(dir) = cfm_dir() else { return };
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("listing")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "ts"))
        .collect();
    files.sort();
    let meshes: Vec<(String, TriMesh)> = files
        .iter()
        .map(|p| {
            (
                p.file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default(),
                read_tsurf(p),
            )
        })
        .collect();
    let mut meeting = 0;
    for (i, (na, a)) in meshes.iter().enumerate() {
        for (nb, b) in meshes.iter().skip(i + 1) {
            match both(na, a, nb, b) {
                Ok(x) => {
                    if !x.curves.is_empty() {
                        meeting += 1;
                    }
                    eprintln!(
                        "{na} × {nb}: {} curves, {} touches",
                        x.curves.len(),
                        x.touches.len()
                    );
                }
                Err(e) => eprintln!("{na} × {nb}: {e}"),
            }
        }
    }
    assert!(meeting >= 4, "several of these faults meet: {meeting}");
}

/// Real faults are split along their curves on both sides, including where a curve ends
/// inside a face (the other fault's border), and the results are sound.
#[test]
fn crossing_cfm_faults_are_split_soundly_on_both_sides() {
    let Some(dir) = cfm_dir() else { return };
    use model::intersect::split::{Side, split};
    for (s1, s2) in [
        (
            "GRFS-GRFZ-WEST-Garlock_fault-CFM5_1000m",
            "GVFA-PLFZ-MULT-Pleito_fault-CFM2_1000m",
        ),
        (
            "CRFA-BPPM-LKWV-Lockwood_Valley_fault-CFM2_1000m",
            "SAFS-SAFZ-CRRZ-San_Andreas_fault-CFM4_1000m",
        ),
        (
            "CRFA-BPPM-PMTS-Pine_Mountain_fault-CFM2_1000m",
            "CRFA-BPPM-WEST-Big_Pine_fault-CFM2_1000m",
        ),
    ] {
        let (a, b) = (load(&dir, s1), load(&dir, s2));
        let x = both(s1, &a, s2, &b).expect("no coplanar contact");
        let (ma, mb) = if s1 < s2 { (&a, &b) } else { (&b, &a) };
        let sa = split(ma, &x, Side::A).unwrap_or_else(|e| panic!("{e}"));
        let sb = split(mb, &x, Side::B).unwrap_or_else(|e| panic!("{e}"));
        intersect_support::assert_sound(ma, &sa);
        intersect_support::assert_sound(mb, &sb);
        let segs: usize = x.curves.iter().map(|c| c.segments_faces.len()).sum();
        assert_eq!(sa.curve_edges.len(), segs, "{s1} × {s2}");
        assert_eq!(sb.curve_edges.len(), segs, "{s1} × {s2}");
    }
}
