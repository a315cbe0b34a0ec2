//! Shared builders for the surface mesher tests and bench: piecewise-linear supports over a
//! parameter rectangle, loops whose nodes lie exactly on the support's border edges, and the
//! assertions every case makes.
#![allow(dead_code)]

use geom::TriMesh;
use surface_mesh::quality::{QualityStats, stats};
use surface_mesh::{PatchInput, SurfaceMeshOutput, SurfaceSize, mesh_patch, verify};

pub const UTM: [f64; 3] = [5.0e5, 7.0e6, 0.0];

/// A support sampled from `f` on an (nx × ny)-cell grid of `[u0,u1] × [v0,v1]`, triangles
/// counter-clockwise in (u, v).
pub struct Grid<F: Fn(f64, f64) -> [f64; 3]> {
    pub nx: usize,
    pub ny: usize,
    pub u: (f64, f64),
    pub v: (f64, f64),
    pub f: F,
    pub offset: [f64; 3],
}

impl<F: Fn(f64, f64) -> [f64; 3]> Grid<F> {
    fn vertex(&self, i: usize, j: usize) -> [f64; 3] {
        let u = self.u.0 + (self.u.1 - self.u.0) * i as f64 / self.nx as f64;
        let v = self.v.0 + (self.v.1 - self.v.0) * j as f64 / self.ny as f64;
        let p = (self.f)(u, v);
        [
            p[0] + self.offset[0],
            p[1] + self.offset[1],
            p[2] + self.offset[2],
        ]
    }

    pub fn support(&self) -> TriMesh {
        let mut vs = Vec::new();
        for j in 0..=self.ny {
            for i in 0..=self.nx {
                vs.push(self.vertex(i, j));
            }
        }
        let id = |i: usize, j: usize| (j * (self.nx + 1) + i) as u32;
        let mut ts = Vec::new();
        for j in 0..self.ny {
            for i in 0..self.nx {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                ts.push([a, b, c]);
                ts.push([a, c, d]);
            }
        }
        TriMesh::new(vs, ts)
    }

    /// The support point over parameter (u, v) (piecewise linear, exactly on the support).
    pub fn at(&self, u: f64, v: f64) -> [f64; 3] {
        let su = (u - self.u.0) / (self.u.1 - self.u.0) * self.nx as f64;
        let sv = (v - self.v.0) / (self.v.1 - self.v.0) * self.ny as f64;
        let i = (su.floor() as i64).clamp(0, self.nx as i64 - 1) as usize;
        let j = (sv.floor() as i64).clamp(0, self.ny as i64 - 1) as usize;
        let s = su - i as f64;
        let t = sv - j as f64;
        let a = self.vertex(i, j);
        let b = self.vertex(i + 1, j);
        let c = self.vertex(i + 1, j + 1);
        let d = self.vertex(i, j + 1);
        let mut p = [0.0; 3];
        for k in 0..3 {
            p[k] = if s >= t {
                a[k] + (s - t) * (b[k] - a[k]) + t * (c[k] - a[k])
            } else {
                a[k] + s * (c[k] - a[k]) + (t - s) * (d[k] - a[k])
            };
        }
        p
    }

    /// The rectangle's border as a counter-clockwise loop with `nu` and `nv` segments per side.
    pub fn border_loop(&self, nu: usize, nv: usize) -> Vec<[f64; 3]> {
        let (u0, u1) = self.u;
        let (v0, v1) = self.v;
        let mut l = Vec::new();
        for k in 0..nu {
            l.push(self.at(u0 + (u1 - u0) * k as f64 / nu as f64, v0));
        }
        for k in 0..nv {
            l.push(self.at(u1, v0 + (v1 - v0) * k as f64 / nv as f64));
        }
        for k in 0..nu {
            l.push(self.at(u1 - (u1 - u0) * k as f64 / nu as f64, v1));
        }
        for k in 0..nv {
            l.push(self.at(u0, v1 - (v1 - v0) * k as f64 / nv as f64));
        }
        l
    }

    /// A clockwise circle of `n` nodes around (cu, cv) of parameter radius r.
    pub fn hole(&self, cu: f64, cv: f64, r: f64, n: usize) -> Vec<[f64; 3]> {
        (0..n)
            .map(|k| {
                let a = -2.0 * std::f64::consts::PI * k as f64 / n as f64;
                self.at(cu + r * a.cos(), cv + r * a.sin())
            })
            .collect()
    }
}

pub fn wavy(x: f64, y: f64) -> [f64; 3] {
    [
        x,
        y,
        -1200.0 + 80.0 * (x / 900.0).sin() * (y / 1100.0).cos(),
    ]
}

pub fn uniform(size: f64) -> SurfaceSize {
    SurfaceSize {
        size,
        min_size: size * 0.1,
        max_size: size,
        growth: 1.2,
    }
}

/// Meshes and makes the assertions every case makes; returns the mesh and its quality.
pub fn mesh_and_check(
    input: &PatchInput,
    size: &SurfaceSize,
    max_mean: f64,
    max_worst: f64,
) -> (SurfaceMeshOutput, QualityStats) {
    let t0 = std::time::Instant::now();
    let out = match mesh_patch(input, size) {
        Ok(o) => o,
        Err(e) => panic!("{e}"),
    };
    let secs = t0.elapsed().as_secs_f64();
    verify(input, &out, 1e-6).unwrap_or_else(|e| panic!("verify: {e}"));
    // Given nodes first, bit-identical, once each (loops that touch share the node), in the
    // documented order: loop nodes, then constraint nodes, then points.
    let mut k = 0;
    let mut seen = std::collections::BTreeSet::new();
    let given = input.loops.iter().flatten();
    for p in given
        .chain(input.constraints.iter().flatten())
        .chain(&input.points)
    {
        if seen.insert(p.map(f64::to_bits)) {
            assert_eq!(out.nodes[k].map(f64::to_bits), p.map(f64::to_bits));
            k += 1;
        }
    }
    let q = stats(&out.nodes, &out.triangles);
    eprintln!(
        "CASE {:<40} tris {:>7} mean {:.4} sd {:.4} max {:.3} >1.15 {:>5.2}% >1.5 {:>5.2}% time {:.3}s",
        input.name, q.triangles, q.mean, q.sd, q.max, q.pct_above_1_15, q.pct_above_1_5, secs
    );
    assert!(
        q.mean <= max_mean,
        "{}: mean c/c* {} > {}",
        input.name,
        q.mean,
        max_mean
    );
    assert!(
        q.max <= max_worst,
        "{}: worst c/c* {} > {}: {:?}",
        input.name,
        q.max,
        max_worst,
        worst(&out)
    );
    (out, q)
}

/// The worst triangle's corners (debugging aid in failure messages).
pub fn worst(out: &SurfaceMeshOutput) -> ([f64; 3], [f64; 3], [f64; 3], f64) {
    use surface_mesh::quality::c_ratio;
    let mut best = ([0.0; 3], [0.0; 3], [0.0; 3], 0.0);
    for t in &out.triangles {
        let p = t.map(|v| out.nodes[v as usize]);
        let q = c_ratio(&p[0], &p[1], &p[2]);
        if q > best.3 {
            best = (p[0], p[1], p[2], q);
        }
    }
    best
}
