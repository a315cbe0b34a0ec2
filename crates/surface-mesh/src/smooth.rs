//! The topological pass (quality edge flips) and the smoothing pass (Laplacian with pull-back
//! onto the support), both in 3D, both guarded in the parameter plane.
//!
//! - A free interior edge is flipped when the sum of its two triangles' squared 3D c/c* drops and
//!   the quadrilateral is strictly convex in the parameter plane (exact `orient2d`), so the
//!   triangulation of the plane stays valid.
//! - A generated node tries the mean of its neighbours and the mean of the equilateral apexes on
//!   its fan's opposite edges (in 3D), each projected back onto the support (closest point: a
//!   walk over the support from the triangle the node sits on, the global R-tree search as the
//!   fallback); its parameter comes from that projection. A move is kept only if every incident
//!   triangle stays strictly counter-clockwise in the plane (exact), the fan's sum of squared c/c*
//!   drops and its worst shape does not degrade noticeably. Given nodes (loop and constraint
//!   nodes and points, all numbered below `first_free`) never move.
//!
//! Sweeps go in index order (Gauss–Seidel), so the result does not depend on anything but input.

use super::cdt::{Cdt, FREE, NONE, next, prev};
use super::quality::shape;
use super::support::Support;
use geom::predicates::{cross, dot, sub};
use geom::progress::Span;
use geom::{Orientation, orient2d};

/// The squared c/c* of a triangle of shape `s` (1/s²; large for a degenerate triangle).
fn energy(s: f64) -> f64 {
    if s > 1e-12 { 1.0 / (s * s) } else { 1e24 }
}

pub struct Smoother<'a> {
    pub cdt: &'a mut Cdt,
    pub p3: &'a mut Vec<[f64; 3]>,
    pub support: &'a Support,
    /// Vertices below this index never move (super vertices and given nodes, points included).
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

    /// One sweep of quality flips; returns how many edges flipped. An edge flips when the sum of
    /// the squared c/c* of its two triangles drops: the mean quality improves and the worse
    /// triangle weighs most. The sum strictly decreases with every flip, so sweeps terminate.
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
                let before = energy(self.tri_shape(t)) + energy(self.tri_shape(nb));
                let p = |k: u32| &self.p3[k as usize];
                let after = energy(shape(p(p0), p(p1), p(q))) + energy(shape(p(q), p(p2), p(p0)));
                if after < before * (1.0 - 1e-9) {
                    self.cdt.flip(t, i);
                    flips += 1;
                    break;
                }
            }
        }
        flips
    }

    /// One smoothing sweep over the generated nodes; returns how many moved.
    ///
    /// Each node tries two targets: the mean of its neighbours (Laplacian) and the mean of the
    /// apexes of the equilateral triangles erected on its fan's opposite edges (in the plane of
    /// the fan), which follows a graded mesh instead of pulling nodes to the coarse side. Each
    /// target is projected onto the support; the position kept is the valid one (every fan
    /// triangle strictly counter-clockwise in the plane, exactly) with the least fan energy (sum
    /// of squared c/c*), if that beats the current one and does not make the worst fan triangle
    /// noticeably worse.
    pub fn smooth_sweep(&mut self) -> usize {
        let mut fan = Vec::new();
        let mut moved = 0;
        for v in self.first_free..self.cdt.pts.len() as u32 {
            self.cdt.fan(v, &mut fan);
            if fan.is_empty() || fan.iter().any(|&t| !self.cdt.inside[t as usize]) {
                continue;
            }
            let opposite = |t: u32| {
                let tv = self.cdt.tri[t as usize];
                let k = tv.iter().position(|&x| x == v).unwrap_or(0);
                (tv[next(k)], tv[prev(k)])
            };
            let x0 = self.p3[v as usize];
            let mut lap = [0.0; 3];
            let mut normal = [0.0; 3];
            for &t in &fan {
                let (a, b) = opposite(t);
                let (pa, pb) = (&self.p3[a as usize], &self.p3[b as usize]);
                for c in 0..3 {
                    lap[c] += pa[c];
                }
                let n = cross(&sub(pa, &x0), &sub(pb, &x0));
                for c in 0..3 {
                    normal[c] += n[c];
                }
            }
            let m = fan.len() as f64;
            lap = lap.map(|x| x / m);
            let nl = dot(&normal, &normal).sqrt();
            let mut ideal = [0.0; 3];
            if nl > 0.0 {
                let nn = normal.map(|x| x / nl);
                for &t in &fan {
                    let (a, b) = opposite(t);
                    let (pa, pb) = (&self.p3[a as usize], &self.p3[b as usize]);
                    let e = sub(pb, pa);
                    // v sits to the left of a -> b seen from the normal: left = n x e.
                    let left = cross(&nn, &e);
                    let ll = dot(&left, &left).sqrt();
                    let el = dot(&e, &e).sqrt();
                    let k = if ll > 0.0 {
                        0.5 * 3f64.sqrt() * el / ll
                    } else {
                        0.0
                    };
                    for c in 0..3 {
                        ideal[c] += 0.5 * (pa[c] + pb[c]) + k * left[c];
                    }
                }
                ideal = ideal.map(|x| x / m);
            } else {
                ideal = lap;
            }
            let fan_quality = |x: &[f64; 3]| {
                let mut e = 0.0;
                let mut worst = f64::INFINITY;
                for &t in &fan {
                    let (a, b) = opposite(t);
                    let s = shape(x, &self.p3[a as usize], &self.p3[b as usize]);
                    e += energy(s);
                    worst = worst.min(s);
                }
                (e, worst)
            };
            let (e0, w0) = fan_quality(&x0);
            let hint = self.stri.get(v as usize).copied().unwrap_or(u32::MAX);
            let mut best: Option<(f64, super::support::OnSupport)> = None;
            for target in [ideal, lap] {
                let Some(on) = self.support.project_from(hint, &target) else {
                    continue;
                };
                let valid = fan.iter().all(|&t| {
                    let (a, b) = opposite(t);
                    orient2d(&on.uv, &self.cdt.pts[a as usize], &self.cdt.pts[b as usize])
                        == Orientation::Positive
                });
                if !valid {
                    continue;
                }
                let (e, w) = fan_quality(&on.xyz);
                if e < e0 * (1.0 - 1e-9)
                    && w >= w0.min(0.9) * 0.999
                    && best.as_ref().is_none_or(|(eb, _)| e < *eb)
                {
                    best = Some((e, on));
                }
            }
            if let Some((_, on)) = best {
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

    /// Alternating flips and smoothing: at most `rounds` rounds of both, then flips until none
    /// is left; reports each round on `bar` (the last flips as one more).
    pub fn run(&mut self, rounds: usize, bar: Span<'_>) {
        self.resync();
        for r in 0..rounds {
            let f = self.flip_sweep();
            let m = self.smooth_sweep();
            bar.step(r + 1, rounds + 1);
            if f == 0 && m == 0 {
                break;
            }
        }
        for _ in 0..20 {
            if self.flip_sweep() == 0 {
                break;
            }
        }
        bar.done();
    }
}
