//! The geometric pass: frontal Delaunay refinement (Rebay's method) in the parameter plane with
//! sizes measured in 3D.
//!
//! A triangle is *accepted* when its 3D circumradius is at most `ACCEPT` times that of the
//! equilateral triangle of the local size h (h/√3). The *active* triangles are the unaccepted
//! ones that touch the front: a fixed (loop or constraint) edge or an accepted neighbour. The worst
//! active triangle gets one new point on the perpendicular bisector of its front edge, at the
//! distance that makes the triangle on that edge as close to equilateral of size h as the
//! Delaunay cavity allows; the point is mapped onto the support through the flattening and
//! inserted by constrained Bowyer–Watson. So points are laid out front by front from the
//! boundary inwards, which is what gives mostly equilateral triangles (the seed's advancing-front
//! quality) while the Delaunay kernel keeps the triangulation valid at every step.
//! The 2D placement uses the local 2D/3D length ratio of the front edge, so the flattening's
//! isotropic distortion is undone; the remaining anisotropy is left to the smoothing pass.

use super::cdt::{Cdt, FREE, NONE, next, prev};
use super::quality::{circumradius, shape};
use super::size::SizeField;
use super::support::Support;
use geom::progress::Span;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Acceptance threshold on circumradius / (h/√3).
pub const ACCEPT: f64 = 1.2;
/// A new point closer than this fraction of h to a cavity vertex is refused.
const TOO_CLOSE: f64 = 0.55;
/// A new point whose new triangles include one with shape below this (c/c* above 2.5) is refused.
const MIN_NEW_SHAPE: f64 = 0.4;

pub struct Refiner<'a> {
    pub cdt: &'a mut Cdt,
    pub p3: &'a mut Vec<[f64; 3]>,
    pub support: &'a Support,
    pub size: &'a SizeField,
    rho: Vec<f64>,
    /// The support triangle under each vertex inserted here (`u32::MAX` for the others).
    pub stri: Vec<u32>,
}

/// How many points refinement will insert, for the progress bar only: the inside triangles'
/// area over that of the equilateral triangle of the local size (sampled at each triangle's
/// centroid and halfway from it to each corner), 1.45 points per such triangle. Size queries
/// are searches, so only about [`SAMPLES`] triangle slots, picked by a hash, are looked at: at most
/// 0.7 ms a patch, 0.5 % of a patch of 5,000 points. On the didactic model's refinements
/// (b)-(d), patches of 1,000 to 5,300 new points were estimated within 25 % of the count (one
/// 40 % over), smaller ones within a factor of 2.5.
pub fn expected_points(cdt: &Cdt, p3: &[[f64; 3]], size: &SizeField) -> f64 {
    let equilateral = 3f64.sqrt() / 4.0;
    let every = cdt.tri.len().div_ceil(SAMPLES).max(1);
    let mut sum = 0.0;
    for t in 0..cdt.tri.len() {
        if !geom::progress::sampled(t, every) || !cdt.alive[t] || !cdt.inside[t] {
            continue;
        }
        let [a, b, c] = cdt.tri[t].map(|v| p3[v as usize]);
        let area = geom::trimesh::triangle_area([&a, &b, &c]);
        let g = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
        let per_area = |p: &[f64; 3]| size.at(p).powi(-2) / equilateral;
        let mut density = per_area(&g);
        for q in [a, b, c] {
            density += per_area(&[0, 1, 2].map(|k| 0.5 * (g[k] + q[k])));
        }
        sum += area * density / 4.0;
    }
    let points = 1.45 * sum * every as f64 / 2.0;
    if points.is_finite() { points } else { 0.0 }
}

/// About how many triangle slots [`expected_points`] looks at.
const SAMPLES: usize = 256;

fn dist3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
fn dist2(a: &[f64; 2], b: &[f64; 2]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}

impl<'a> Refiner<'a> {
    pub fn new(
        cdt: &'a mut Cdt,
        p3: &'a mut Vec<[f64; 3]>,
        support: &'a Support,
        size: &'a SizeField,
    ) -> Self {
        Refiner {
            cdt,
            p3,
            support,
            size,
            rho: Vec::new(),
            stri: Vec::new(),
        }
    }

    fn ratio(&self, t: u32) -> f64 {
        let v = self.cdt.tri[t as usize];
        let a = &self.p3[v[0] as usize];
        let b = &self.p3[v[1] as usize];
        let c = &self.p3[v[2] as usize];
        let g = [
            (a[0] + b[0] + c[0]) / 3.0,
            (a[1] + b[1] + c[1]) / 3.0,
            (a[2] + b[2] + c[2]) / 3.0,
        ];
        let h = self.size.at(&g);
        circumradius(a, b, c) / (h / 3f64.sqrt())
    }

    fn set_rho(&mut self, t: u32, r: f64) {
        if self.rho.len() <= t as usize {
            self.rho.resize(t as usize + 1, 0.0);
        }
        self.rho[t as usize] = r;
    }

    fn accepted(&self, t: u32) -> bool {
        self.rho.get(t as usize).is_some_and(|&r| r <= ACCEPT)
    }

    /// Refines until every triangle is accepted or no point can be placed; at most `max_points`
    /// new points (an error beyond that). Reports on `bar` the points inserted of the `expected`
    /// ones.
    pub fn run(
        &mut self,
        max_points: usize,
        bar: Span<'_>,
        expected: f64,
    ) -> Result<usize, String> {
        let expected = expected.max(1.0);
        let mut heap: BinaryHeap<(u64, Reverse<u32>, [u32; 3])> = BinaryHeap::new();
        let live: Vec<u32> = self.cdt.live_triangles().collect();
        for &t in &live {
            let r = if self.cdt.inside[t as usize] {
                self.ratio(t)
            } else {
                0.0
            };
            self.set_rho(t, r);
        }
        for &t in &live {
            if self.cdt.inside[t as usize] && !self.accepted(t) {
                heap.push((
                    self.rho[t as usize].to_bits(),
                    Reverse(t),
                    self.cdt.tri[t as usize],
                ));
            }
        }
        let mut added = 0usize;
        let mut fan = Vec::new();
        while let Some((_, Reverse(t), verts)) = heap.pop() {
            let tu = t as usize;
            if !self.cdt.alive[tu]
                || self.cdt.tri[tu] != verts
                || !self.cdt.inside[tu]
                || self.accepted(t)
            {
                continue;
            }
            // Front edges.
            let mut best: Option<(f64, usize)> = None;
            for i in 0..3 {
                let n = self.cdt.nbr[tu][i];
                let front = self.cdt.fix[tu][i] != FREE
                    || n == NONE
                    || !self.cdt.inside[n as usize]
                    || self.accepted(n);
                if front {
                    let a = &self.p3[verts[next(i)] as usize];
                    let b = &self.p3[verts[prev(i)] as usize];
                    let l = dist3(a, b);
                    if best.is_none_or(|(bl, _)| l < bl) {
                        best = Some((l, i));
                    }
                }
            }
            let Some((l3, i)) = best else { continue };
            let Some(x2) = self.place(t, i, l3) else {
                self.set_rho(t, 0.0);
                self.push_neighbours(t, &mut heap);
                continue;
            };
            let ok = self.try_insert(t, x2, &mut fan);
            match ok {
                Some(_) => {
                    added += 1;
                    bar.reach(added as f64 / expected);
                    if added > max_points {
                        return Err(format!(
                            "refinement did not converge after {max_points} points (size field too small for the patch?)"
                        ));
                    }
                    let new_tris = fan.clone();
                    for &nt in &new_tris {
                        let r = self.ratio(nt);
                        self.set_rho(nt, r);
                    }
                    for &nt in &new_tris {
                        if !self.accepted(nt) {
                            heap.push((
                                self.rho[nt as usize].to_bits(),
                                Reverse(nt),
                                self.cdt.tri[nt as usize],
                            ));
                        } else {
                            self.push_neighbours(nt, &mut heap);
                        }
                    }
                }
                None => {
                    // Give up on this triangle: it becomes part of the front.
                    self.set_rho(t, 0.0);
                    self.push_neighbours(t, &mut heap);
                }
            }
        }
        Ok(added)
    }

    fn push_neighbours(&self, t: u32, heap: &mut BinaryHeap<(u64, Reverse<u32>, [u32; 3])>) {
        for i in 0..3 {
            let n = self.cdt.nbr[t as usize][i];
            if n != NONE
                && self.cdt.fix[t as usize][i] == FREE
                && self.cdt.inside[n as usize]
                && !self.accepted(n)
            {
                heap.push((
                    self.rho.get(n as usize).copied().unwrap_or(0.0).to_bits(),
                    Reverse(n),
                    self.cdt.tri[n as usize],
                ));
            }
        }
    }

    /// Rebay's point for front edge `i` of `t`, placed in the local metric of the flattening
    /// (so the new triangle is near-equilateral in 3D, not in the plane).
    fn place(&self, t: u32, i: usize, l3: f64) -> Option<[f64; 2]> {
        let v = self.cdt.tri[t as usize];
        let a2 = self.cdt.pts[v[next(i)] as usize];
        let b2 = self.cdt.pts[v[prev(i)] as usize];
        let c2 = self.cdt.pts[v[i] as usize];
        let m2 = [(a2[0] + b2[0]) * 0.5, (a2[1] + b2[1]) * 0.5];
        let l = match self.support.metric_at(&m2) {
            Some(l) => l,
            None => {
                let p = dist2(&a2, &b2);
                if !(p > 0.0) || !(l3 > 0.0) {
                    return None;
                }
                let s = l3 / p;
                [[s, 0.0], [0.0, s]]
            }
        };
        let fwd = |x: &[f64; 2]| [l[0][0] * x[0] + l[0][1] * x[1], l[1][1] * x[1]];
        let a = fwd(&a2);
        let b = fwd(&b2);
        let c = fwd(&c2);
        let p = dist2(&a, &b);
        if !(p > 0.0) {
            return None;
        }
        let a3 = &self.p3[v[next(i)] as usize];
        let b3 = &self.p3[v[prev(i)] as usize];
        let m3 = [
            (a3[0] + b3[0]) * 0.5,
            (a3[1] + b3[1]) * 0.5,
            (a3[2] + b3[2]) * 0.5,
        ];
        let h = self.size.at(&m3);
        let m = [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5];
        // Unit normal of ab pointing into t (towards c; a, b, c are counter-clockwise).
        let dir = [-(b[1] - a[1]) / p, (b[0] - a[0]) / p];
        let cc = circumcentre(&a, &b, &c)?;
        let q = (cc[0] - m[0]) * dir[0] + (cc[1] - m[1]) * dir[1];
        let mut rho_m = (h / 3f64.sqrt()).max(p * 0.5);
        if q > 0.0 {
            rho_m = rho_m.min((p * p * 0.25 + q * q) / (2.0 * q));
        }
        let d = rho_m + (rho_m * rho_m - p * p * 0.25).max(0.0).sqrt();
        let y = [m[0] + d * dir[0], m[1] + d * dir[1]];
        // Back to the plane: x = L⁻¹ y (L upper triangular).
        let x1 = y[1] / l[1][1];
        let x0 = (y[0] - l[0][1] * x1) / l[0][0];
        Some([x0, x1])
    }

    fn try_insert(&mut self, t: u32, x2: [f64; 2], fan: &mut Vec<u32>) -> Option<u32> {
        let t0 = self.cdt.locate(&x2, t)?;
        if !self.cdt.inside[t0 as usize] {
            return None;
        }
        let (sid, x3) = self.support.to_3d(&x2)?;
        let h = self.size.at(&x3);
        let p3 = &*self.p3;
        // Refuse a point too close to a vertex, or one that would make a sliver with a fixed
        // edge (a point dropped next to a long boundary segment): that sliver could never go.
        let mut accept = |_: &Cdt, edges: &[(u32, u32, u8)]| {
            edges.iter().all(|&(a, b, f)| {
                let (pa, pb) = (&p3[a as usize], &p3[b as usize]);
                dist3(pa, &x3) >= TOO_CLOSE * h && (f == FREE || !encroaches(pa, pb, &x3))
            })
        };
        let v = self.cdt.insert(x2, t0, &mut accept).ok()?;
        if self.p3.len() <= v as usize {
            self.p3.resize(v as usize + 1, [0.0; 3]);
        }
        self.p3[v as usize] = x3;
        if self.stri.len() <= v as usize {
            self.stri.resize(v as usize + 1, u32::MAX);
        }
        self.stri[v as usize] = sid;
        self.cdt.fan(v, fan);
        Some(v)
    }
}

/// Whether `x` sits so close to the fixed edge `ab` (within half its length, over it) that the
/// triangle it would make with the edge is a sliver that no later point could remove.
fn encroaches(a: &[f64; 3], b: &[f64; 3], x: &[f64; 3]) -> bool {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ax = [x[0] - a[0], x[1] - a[1], x[2] - a[2]];
    let l2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    if !(l2 > 0.0) {
        return false;
    }
    let t = (ax[0] * ab[0] + ax[1] * ab[1] + ax[2] * ab[2]) / l2;
    let foot = [a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]];
    (0.0..=1.0).contains(&t) && dist3(&foot, x) < 0.5 * l2.sqrt() && shape(a, b, x) < MIN_NEW_SHAPE
}

/// Circumcentre of a 2D triangle (floating point; a construction, not a decision).
pub fn circumcentre(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Option<[f64; 2]> {
    let bx = b[0] - a[0];
    let by = b[1] - a[1];
    let cx = c[0] - a[0];
    let cy = c[1] - a[1];
    let d = 2.0 * (bx * cy - by * cx);
    if d == 0.0 {
        return None;
    }
    let b2 = bx * bx + by * by;
    let c2 = cx * cx + cy * cy;
    Some([
        a[0] + (cy * b2 - by * c2) / d,
        a[1] + (bx * c2 - cx * b2) / d,
    ])
}
