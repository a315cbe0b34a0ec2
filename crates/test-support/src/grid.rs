//! A structured tet mesh of about a million tets for the report's size test and bench: a grid
//! of `nx × ny × nz` cubes (six Kuhn tets each, conforming) in three layers, with the box sides and
//! the two layer interfaces (H1, H2) tagged.

use geom::mesh::{RegionGroup, SurfaceGroup, SurfaceKind, VolumeMesh};

pub fn grid(nx: usize, ny: usize, nz: usize) -> VolumeMesh {
    let mut m = VolumeMesh::default();
    let id = |i: usize, j: usize, k: usize| (k * (ny + 1) * (nx + 1) + j * (nx + 1) + i) as u32;
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                m.nodes
                    .push([i as f64 * 50.0, j as f64 * 50.0, -(k as f64) * 40.0]);
            }
        }
    }
    let layer = |k: usize| (3 * k / nz) as u32;
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let c = |b: usize| id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
                for p in [[1, 3], [3, 2], [2, 6], [6, 4], [4, 5], [5, 1]] {
                    m.tets.push([c(0), c(p[0]), c(p[1]), c(7)]);
                    m.tet_region.push(layer(k));
                }
            }
        }
    }
    for name in ["overburden", "reservoir", "underburden"] {
        m.regions.push(RegionGroup {
            name: name.into(),
            material: None,
            properties: Default::default(),
        });
    }
    for (name, kind) in [
        ("box", SurfaceKind::Box),
        ("H1", SurfaceKind::Horizon),
        ("H2", SurfaceKind::Horizon),
    ] {
        m.surface_groups.push(SurfaceGroup {
            name: name.into(),
            kind,
        });
    }
    let mut tri = |a: u32, b: u32, c: u32, d: u32, g: u32| {
        m.triangles.push([a, b, c]);
        m.triangles.push([a, c, d]);
        m.triangle_group.extend([g, g]);
    };
    // Horizontal planes: top and bottom (box), the two layer interfaces (H1, H2).
    let planes = [
        (0, 0),
        (nz, 0),
        (nz.div_ceil(3), 1),
        ((2 * nz).div_ceil(3), 2),
    ];
    for (k, g) in planes {
        for j in 0..ny {
            for i in 0..nx {
                tri(
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    g,
                );
            }
        }
    }
    // The four vertical walls.
    for k in 0..nz {
        for i in 0..nx {
            tri(
                id(i, 0, k),
                id(i + 1, 0, k),
                id(i + 1, 0, k + 1),
                id(i, 0, k + 1),
                0,
            );
            tri(
                id(i, ny, k),
                id(i + 1, ny, k),
                id(i + 1, ny, k + 1),
                id(i, ny, k + 1),
                0,
            );
        }
        for j in 0..ny {
            tri(
                id(0, j, k),
                id(0, j + 1, k),
                id(0, j + 1, k + 1),
                id(0, j, k + 1),
                0,
            );
            tri(
                id(nx, j, k),
                id(nx, j + 1, k),
                id(nx, j + 1, k + 1),
                id(nx, j, k + 1),
                0,
            );
        }
    }
    m
}
