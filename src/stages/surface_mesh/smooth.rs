//! The topological pass (quality edge flips) and the smoothing pass (Laplacian with pull-back
//! onto the support), both in 3D, both guarded in the parameter plane.
//!
//! - A free interior edge is flipped when the worse of its two triangles' 3D shapes improves and
//!   the quadrilateral is strictly convex in the parameter plane (exact `orient2d`), so the
//!   triangulation of the plane stays valid.
//! - A generated node moves to the mean of its neighbours in 3D, then is projected back onto the
//!   support (closest point: a walk over the support from the triangle the node sits on, the
//!   global R-tree search as the fallback); its parameter comes from that projection. The move is kept
//!   only if every incident triangle stays strictly counter-clockwise in the plane (exact) and the
//!   worst incident 3D shape does not degrade. Given loop and constraint nodes never move.
//!
//! Sweeps go in index order (Gauss–Seidel), so the result does not depend on anything but input.

use super::cdt::{Cdt, FREE, NONE, next, prev};
use super::quality::shape;
use super::support::Support;
use crate::geom::{Orientation, orient2d};

pub struct Smoother<'a> {
    pub cdt: &'a mut Cdt,
    pub p3: &'a mut Vec<[f64; 3]>,
    pub support: &'a Support,
    /// Vertices below this index never move (super vertices and given nodes).
    pub first_free: u32,
    /// The support triangle under each vertex (hint for local projections).
    pub stri: Vec<u32>,
}

impl Smoother<'_> {
    fn tri_shape(&self, t: u32) -> f64 {
        let v = self.cdt.tri[t as usize];
        shape(
            &self.p3[v[0] as usize],
            &self.p3[v[1] as usize],
            &self.p3[v[2] as usize],
        )
    }

    /// One sweep of quality flips; returns how many edges flipped.
    pub fn flip_sweep(&mut self) -> usize {
        let mut flips = 0;
        let n = self.cdt.tri.len();
        for t in 0..n as u32 {
            if !self.cdt.alive[t as usize] || !self.cdt.inside[t as usize] {
                continue;
            }
            for i in 0..3 {
                let nb = self.cdt.nbr[t as usize][i];
                if nb == NONE
                    || self.cdt.fix[t as usize][i] != FREE
                    || !self.cdt.inside[nb as usize]
                {
                    continue;
                }
                if !self.cdt.flippable(t, i) {
                    continue;
                }
                let v = self.cdt.tri[t as usize];
                let (p0, p1, p2) = (v[i], v[next(i)], v[prev(i)]);
                let w = self.cdt.tri[nb as usize];
                let Some(q) = w.iter().copied().find(|&x| x != p1 && x != p2) else {
                    continue;
                };
                let before = self.tri_shape(t).min(self.tri_shape(nb));
                let p = |k: u32| &self.p3[k as usize];
                let after = shape(p(p0), p(p1), p(q)).min(shape(p(q), p(p2), p(p0)));
                if after > before * (1.0 + 1e-9) + 1e-12 {
                    self.cdt.flip(t, i);
                    flips += 1;
                    break;
                }
            }
        }
        flips
    }

    /// One Laplacian sweep over the generated nodes; returns how many moved.
    pub fn smooth_sweep(&mut self) -> usize {
        let mut fan = Vec::new();
        let mut moved = 0;
        for v in self.first_free..self.cdt.pts.len() as u32 {
            self.cdt.fan(v, &mut fan);
            if fan.is_empty() || fan.iter().any(|&t| !self.cdt.inside[t as usize]) {
                continue;
            }
            let mut sum = [0.0; 3];
            let mut worst = f64::INFINITY;
            for &t in &fan {
                let tv = self.cdt.tri[t as usize];
                let k = tv.iter().position(|&x| x == v).unwrap_or(0);
                let nb = &self.p3[tv[next(k)] as usize];
                for c in 0..3 {
                    sum[c] += nb[c];
                }
                worst = worst.min(self.tri_shape(t));
            }
            let m = fan.len() as f64;
            let target = [sum[0] / m, sum[1] / m, sum[2] / m];
            let hint = self.stri.get(v as usize).copied().unwrap_or(u32::MAX);
            let Some(on) = self.support.project_from(hint, &target) else {
                continue;
            };
            let ok = fan.iter().all(|&t| {
                let tv = self.cdt.tri[t as usize];
                let k = tv.iter().position(|&x| x == v).unwrap_or(0);
                orient2d(
                    &on.uv,
                    &self.cdt.pts[tv[next(k)] as usize],
                    &self.cdt.pts[tv[prev(k)] as usize],
                ) == Orientation::Positive
            });
            if !ok {
                continue;
            }
            let mut new_worst = f64::INFINITY;
            for &t in &fan {
                let tv = self.cdt.tri[t as usize];
                let k = tv.iter().position(|&x| x == v).unwrap_or(0);
                new_worst = new_worst.min(shape(
                    &on.xyz,
                    &self.p3[tv[next(k)] as usize],
                    &self.p3[tv[prev(k)] as usize],
                ));
            }
            if new_worst >= worst.min(0.9) * 0.999 {
                self.cdt.pts[v as usize] = on.uv;
                self.p3[v as usize] = on.xyz;
                self.stri[v as usize] = on.tri;
                moved += 1;
            }
        }
        moved
    }

    /// Re-derives every generated node's parameter from its 3D position by projection, so the
    /// mesher and `verify` see the same parameters.
    pub fn resync(&mut self) {
        self.stri.resize(self.cdt.pts.len(), u32::MAX);
        for v in self.first_free..self.cdt.pts.len() as u32 {
            let hint = self.stri[v as usize];
            let on = self.support.project_hinted(hint, &self.p3[v as usize]);
            if let Some(on) = on {
                self.cdt.pts[v as usize] = on.uv;
                self.p3[v as usize] = on.xyz;
                self.stri[v as usize] = on.tri;
            }
        }
    }

    /// Alternating flips and smoothing.
    pub fn run(&mut self, rounds: usize) {
        self.resync();
        for _ in 0..rounds {
            let f = self.flip_sweep();
            let m = self.smooth_sweep();
            if f == 0 && m == 0 {
                break;
            }
        }
        for _ in 0..20 {
            if self.flip_sweep() == 0 {
                break;
            }
        }
    }
}
