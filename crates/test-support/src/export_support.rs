//! Test support shared by the export, quality and reader tests: a structured layered box mesh
//! with box sides, horizons and a dangling fault, and helpers to run the Python readers and
//! `../shared/tools/check_mesh.py` (skipping when they are absent).
#![allow(dead_code)]

use geom::mesh::{RegionGroup, SurfaceGroup, SurfaceKind, VolumeMesh};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// UTM-like offsets applied to x and y.
pub const OX: f64 = 5.0e5;
pub const OY: f64 = 7.0e6;

/// The model box `[xmin, ymin, zmin, xmax, ymax, zmax]`.
pub fn box_bounds() -> [f64; 6] {
    [OX, OY, -2500.0, OX + 5000.0, OY + 5000.0, 0.0]
}

/// The orders in which a cube's Kuhn tets step along the axes from its low corner to its high
/// one: one tet each, six that fill the cube, the same diagonal in every cube (so cubes cut
/// alike conform).
pub const KUHN_ORDERS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

/// A box `[0,5000]² × [-2500,0]` (shifted by OX, OY) cut into `n × n × nz` cubes, each into 6 Kuhn
/// tets around its (0,0,0)–(1,1,1) diagonal (the same diagonal everywhere, so the mesh is
/// conforming). Three regions by z-layer (`nz` divisible by 3), surface groups: the six box sides,
/// two horizons (layer interfaces) and a dangling fault: the interior faces on the plane
/// x = 2500 with y in [1500, 3500] and z in the middle layer and the one above it.
pub fn layered_box(n: usize, nz: usize) -> VolumeMesh {
    assert!(nz.is_multiple_of(3) && n.is_multiple_of(2) && n >= 4);
    let [x0, y0, z0, x1, y1, z1] = box_bounds();
    let id = |i: usize, j: usize, k: usize| (i + (n + 1) * (j + (n + 1) * k)) as u32;
    let mut mesh = VolumeMesh::default();
    for k in 0..=nz {
        for j in 0..=n {
            for i in 0..=n {
                mesh.nodes.push([
                    x0 + (x1 - x0) * i as f64 / n as f64,
                    y0 + (y1 - y0) * j as f64 / n as f64,
                    z0 + (z1 - z0) * k as f64 / nz as f64,
                ]);
            }
        }
    }
    let layer = |k: usize| (3 * k / nz) as u32;
    for k in 0..nz {
        for j in 0..n {
            for i in 0..n {
                for p in KUHN_ORDERS {
                    let mut c = [i, j, k];
                    let mut t = [id(c[0], c[1], c[2]); 4];
                    for (s, &axis) in p.iter().enumerate() {
                        c[axis] += 1;
                        t[s + 1] = id(c[0], c[1], c[2]);
                    }
                    let q = t.map(|v| mesh.nodes[v as usize]);
                    if geom::predicates::signed_volume(&q[0], &q[1], &q[2], &q[3]) < 0.0 {
                        t.swap(2, 3);
                    }
                    mesh.tets.push(t);
                    mesh.tet_region.push(layer(k));
                }
            }
        }
    }
    let props = |d: f64, extra: Option<f64>| {
        let mut m = BTreeMap::from([("density".to_string(), d)]);
        if let Some(p) = extra {
            m.insert("porosity".to_string(), p);
        }
        m
    };
    mesh.regions = vec![
        RegionGroup {
            name: "underburden".into(),
            material: Some(3),
            properties: props(2600.0, None),
        },
        RegionGroup {
            name: "reservoir".into(),
            material: Some(2),
            properties: props(2300.0, Some(0.21)),
        },
        RegionGroup {
            name: "overburden".into(),
            material: None,
            properties: props(2200.0, None),
        },
    ];
    let sides = ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"];
    for s in sides {
        mesh.surface_groups.push(SurfaceGroup {
            name: s.into(),
            kind: SurfaceKind::Box,
        });
    }
    for h in ["H2 base", "H1 top"] {
        mesh.surface_groups.push(SurfaceGroup {
            name: h.into(),
            kind: SurfaceKind::Horizon,
        });
    }
    mesh.surface_groups.push(SurfaceGroup {
        name: "F2_dangling".into(),
        kind: SurfaceKind::Fault,
    });

    // Faces with their tets, in a deterministic order.
    let mut faces: BTreeMap<[u32; 3], Vec<usize>> = BTreeMap::new();
    for (ti, t) in mesh.tets.iter().enumerate() {
        for skip in 0..4 {
            let mut f: Vec<u32> = (0..4).filter(|&q| q != skip).map(|q| t[q]).collect();
            f.sort();
            faces.entry([f[0], f[1], f[2]]).or_default().push(ti);
        }
    }
    let ijk = |v: u32| {
        let v = v as usize;
        (
            v % (n + 1),
            (v / (n + 1)) % (n + 1),
            v / ((n + 1) * (n + 1)),
        )
    };
    for (f, owners) in &faces {
        let c: Vec<(usize, usize, usize)> = f.iter().map(|&v| ijk(v)).collect();
        let all = |pred: &dyn Fn(&(usize, usize, usize)) -> bool| c.iter().all(pred);
        let group = if owners.len() == 1 {
            if all(&|p| p.0 == 0) {
                Some(0)
            } else if all(&|p| p.0 == n) {
                Some(1)
            } else if all(&|p| p.1 == 0) {
                Some(2)
            } else if all(&|p| p.1 == n) {
                Some(3)
            } else if all(&|p| p.2 == 0) {
                Some(4)
            } else if all(&|p| p.2 == nz) {
                Some(5)
            } else {
                panic!("boundary face {f:?} off the box")
            }
        } else {
            let (ra, rb) = (mesh.tet_region[owners[0]], mesh.tet_region[owners[1]]);
            if ra != rb {
                Some(6 + ra.min(rb) as usize)
            } else if all(&|p| {
                p.0 == n / 2
                    && p.1 >= n * 3 / 10
                    && p.1 <= n * 7 / 10
                    && p.2 >= nz / 3
                    && p.2 <= nz * 5 / 6
            }) {
                Some(8)
            } else {
                None
            }
        };
        if let Some(g) = group {
            mesh.triangles.push(*f);
            mesh.triangle_group.push(g as u32);
        }
    }
    mesh.check_indices().unwrap();
    mesh
}

/// True when `python3 -c "import <modules>"` works; prints a skip note otherwise.
pub fn python_has(modules: &str) -> bool {
    let ok = Command::new("python3")
        .args(["-c", &format!("import {modules}")])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    if !ok {
        eprintln!("skipping: python3 with {modules} is absent");
    }
    ok
}

/// Runs a Python snippet with `args` (`sys.argv[1:]`); returns stdout, panicking with stderr on failure.
pub fn python(script: &str, args: &[&str]) -> String {
    let out = Command::new("python3")
        .arg("-c")
        .arg(script)
        .args(args)
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "python failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// `check_mesh.py` path, or None (with a note) when ../shared is absent.
pub fn checker() -> Option<PathBuf> {
    crate::paths::shared("tools/check_mesh.py")
}

/// Runs check_mesh.py on `file` with the box and region count; returns (exit ok, stdout).
pub fn run_checker(
    tool: &Path,
    file: &Path,
    regions: usize,
    json: Option<&Path>,
) -> (bool, String) {
    run_checker_in(tool, file, regions, json, box_bounds())
}

/// [`run_checker`] on a mesh that must fill the box `bounds` (low corner, then high corner).
pub fn run_checker_in(
    tool: &Path,
    file: &Path,
    regions: usize,
    json: Option<&Path>,
    bounds: [f64; 6],
) -> (bool, String) {
    let b = bounds.map(|v| v.to_string());
    let mut cmd = Command::new("python3");
    cmd.arg(tool)
        .arg(file)
        .arg("--box")
        .args(&b)
        .arg("--regions")
        .arg(regions.to_string());
    if let Some(j) = json {
        cmd.arg("--json").arg(j);
    }
    let out = cmd.output().expect("python3 runs");
    (
        out.status.success(),
        format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        ),
    )
}

/// Writes every `(name, bytes)` into `dir`; returns the paths.
pub fn write_all(dir: &Path, files: &[(String, Vec<u8>)]) -> Vec<PathBuf> {
    files
        .iter()
        .map(|(name, bytes)| {
            let p = dir.join(name);
            std::fs::write(&p, bytes).unwrap();
            p
        })
        .collect()
}
