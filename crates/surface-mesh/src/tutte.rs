//! The Tutte embedding of a support that does not project onto a plane one to one (recumbent
//! folds, caps down to their equator, a horizon whose lips overlap round a reverse fault).
//!
//! Decisions and why:
//! - Mean value weights (Floater's), from the support's own 3D angles. They are positive for
//!   every triangle, so Tutte's theorem in Floater's form still makes the embedding of a disk one
//!   to one when its outer border is convex; and they reproduce a flat patch exactly, so the
//!   plane keeps the support's shapes. Weights from edge lengths alone ignore the angles: on a
//!   coarse, irregular support they stretched triangles many times over, and a mesh made in such
//!   a plane folds back on the support.
//! - The outer border is first pinned where it projects onto the mean plane, when that is a
//!   simple counter-clockwise polygon, and the result is kept only if it is one to one
//!   (`param::injective`, exact). A nearly flat horizon whose only defect is a slit with
//!   overlapping lips (a reverse fault dying out inside it) then stays almost isometric. Otherwise
//!   the outer border is pinned to a circle by arc length (same perimeter as in 3D, so sizes keep
//!   their scale), where the theorem guarantees the embedding; a circle distorts an elongated or
//!   notched patch everywhere, hence it comes second.
//! - Every other border cycle (a hole) is closed by a virtual cone vertex tied to its vertices by
//!   the inverse of its mean edge length: the coned support is a disk.
//! - A pinch (a vertex that a traced border loop passes twice: a hole touching the outer border,
//!   two holes touching) splits its loop into simple cycles, each pinned or coned on its own, so
//!   the pinch stays one point with the support's fans and the cones in turn round it.
//! - The weights are not symmetric: the system is solved by BiCGSTAB (`sparse`).

use super::param::{
    ParamError, counter_clockwise, first_non_positive, injective, mean_plane_uv, simple_cycles,
};
use super::segments::first_crossing;
use super::sparse::Rows;
use geom::TriMesh;
use geom::predicates::{cross, dist, dot, sub};
use std::collections::BTreeMap;

/// Added to every mean value weight's angle term, so that a degenerate (zero-angle) corner still
/// gives a strictly positive weight, as the theorem needs.
const POSITIVE_FLOOR: f64 = 1e-9;

/// Embeds the support with border loops `traced` (from `param::border_loops`).
pub fn embed(s: &TriMesh, traced: &[Vec<u32>]) -> Result<Vec<[f64; 2]>, ParamError> {
    let loops: Vec<Vec<u32>> = traced.iter().flat_map(|l| simple_cycles(l)).collect();
    let lens = loop_lengths(s, &loops);
    let outer = (0..lens.len()).fold(0, |o, i| if lens[i] > lens[o] { i } else { o });
    if !(lens[outer] > 0.0) {
        return Err(ParamError {
            message: "the support border has zero length".into(),
            at: None,
        });
    }
    let system = System::new(s, &loops, outer, &lens);
    if let Some(plane) = mean_plane_uv(s)
        && simple_and_counter_clockwise(&loops[outer], &plane)
    {
        let uv = system.solve(&loops[outer], |v| plane[v as usize]);
        if injective(s, &loops, &uv) {
            return Ok(uv);
        }
    }
    let circle = circle_pins(s, &loops[outer], lens[outer]);
    let uv = system.solve(&loops[outer], |v| circle[&v]);
    if let Some(t) = first_non_positive(s, &uv) {
        let [a, b, c] = s.corners(t);
        return Err(ParamError {
            message: "the support cannot be flattened without folding (a triangle inverts in its Tutte embedding)".into(),
            at: Some([0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0)),
        });
    }
    Ok(uv)
}

/// Whether the polygon `cycle` is simple and counter-clockwise in `uv` (exact).
fn simple_and_counter_clockwise(cycle: &[u32], uv: &[[f64; 2]]) -> bool {
    let n = cycle.len();
    let segs: Vec<([f64; 2], [f64; 2])> = (0..n)
        .map(|i| (uv[cycle[i] as usize], uv[cycle[(i + 1) % n] as usize]))
        .collect();
    first_crossing(&segs).is_none() && counter_clockwise(cycle, uv) == Some(true)
}

/// The 3D length of each border cycle.
fn loop_lengths(s: &TriMesh, loops: &[Vec<u32>]) -> Vec<f64> {
    let p = |v: u32| &s.vertices[v as usize];
    loops
        .iter()
        .map(|l| {
            (0..l.len())
                .map(|i| dist(p(l[i]), p(l[(i + 1) % l.len()])))
                .sum()
        })
        .collect()
}

/// The outer cycle on a circle of perimeter `total`, by arc length from its first vertex.
fn circle_pins(s: &TriMesh, l: &[u32], total: f64) -> BTreeMap<u32, [f64; 2]> {
    let radius = total / (2.0 * std::f64::consts::PI);
    let mut acc = 0.0;
    let mut pins = BTreeMap::new();
    for i in 0..l.len() {
        let ang = 2.0 * std::f64::consts::PI * acc / total;
        pins.insert(l[i], [radius * ang.cos(), radius * ang.sin()]);
        acc += dist(
            &s.vertices[l[i] as usize],
            &s.vertices[l[(i + 1) % l.len()] as usize],
        );
    }
    pins
}

/// The linear system of the embedding: one row per support vertex and per cone vertex, and
/// which rows are fixed whatever the outer border's pins (vertices no triangle uses).
struct System {
    rows: Rows,
    unused: Vec<bool>,
    nv: usize,
}

impl System {
    fn new(s: &TriMesh, loops: &[Vec<u32>], outer: usize, lens: &[f64]) -> Self {
        let nv = s.vertices.len();
        let mut w = mean_value_weights(s);
        let mut unused = vec![true; nv];
        for t in &s.triangles {
            for &v in t {
                unused[v as usize] = false;
            }
        }
        let mut cone = nv as u32;
        for (li, l) in loops.iter().enumerate() {
            if li == outer {
                continue;
            }
            let tie = 1.0 / (lens[li] / l.len() as f64).max(f64::MIN_POSITIVE.sqrt());
            for &v in l {
                *w.entry((v, cone)).or_insert(0.0) += tie;
                *w.entry((cone, v)).or_insert(0.0) += tie;
            }
            cone += 1;
        }
        unused.resize(cone as usize, false);
        System {
            rows: Rows::new(&w, cone as usize),
            unused,
            nv,
        }
    }

    /// The support vertices' positions with the `outer` cycle pinned at `pin`.
    fn solve(&self, outer: &[u32], pin: impl Fn(u32) -> [f64; 2]) -> Vec<[f64; 2]> {
        let mut pinned = self.unused.clone();
        let mut uv = vec![[0.0f64; 2]; pinned.len()];
        for &v in outer {
            pinned[v as usize] = true;
            uv[v as usize] = pin(v);
        }
        for k in 0..2 {
            let x = self.rows.solve(&pinned, &uv, k);
            for (i, q) in uv.iter_mut().enumerate() {
                if !pinned[i] {
                    q[k] = x[i];
                }
            }
        }
        uv.truncate(self.nv);
        uv
    }
}

/// Floater's mean value weights, row vertex first: w(i, j) = (tan(α/2) + tan(β/2)) / |ij|, with
/// α and β the angles at i of the triangles on edge ij (one on a border edge).
pub(crate) fn mean_value_weights(s: &TriMesh) -> BTreeMap<(u32, u32), f64> {
    let mut w: BTreeMap<(u32, u32), f64> = BTreeMap::new();
    let floor = f64::MIN_POSITIVE.sqrt();
    for t in &s.triangles {
        for k in 0..3 {
            let (i, j, l) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            let p = &s.vertices[i as usize];
            let u = sub(&s.vertices[j as usize], p);
            let v = sub(&s.vertices[l as usize], p);
            let (lu, lv) = (dot(&u, &u).sqrt(), dot(&v, &v).sqrt());
            let c = cross(&u, &v);
            // tan(θ/2) = |u × v| / (|u||v| + u·v), bounded where θ nears 180°.
            let half = dot(&c, &c).sqrt() / (lu * lv + dot(&u, &v)).max(1e-12 * lu * lv + floor);
            let term = half.min(1e12) + POSITIVE_FLOOR;
            *w.entry((i, j)).or_insert(0.0) += term / lu.max(floor);
            *w.entry((i, l)).or_insert(0.0) += term / lv.max(floor);
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_walk_through_a_pinch_splits_into_simple_cycles() {
        assert_eq!(simple_cycles(&[1, 2, 3]), vec![vec![1, 2, 3]]);
        assert_eq!(
            simple_cycles(&[0, 1, 2, 1, 3]),
            vec![vec![1, 2], vec![0, 1, 3]]
        );
        assert_eq!(
            simple_cycles(&[5, 1, 2, 5, 3, 4]),
            vec![vec![5, 1, 2], vec![5, 3, 4]]
        );
    }

    #[test]
    fn mean_value_weights_reproduce_a_flat_fan() {
        // A vertex inside a flat irregular fan sits at the weighted mean of its neighbours.
        let ring = [
            [3.0, 0.5, 0.0],
            [1.0, 2.0, 0.0],
            [-2.0, 1.0, 0.0],
            [-1.0, -2.5, 0.0],
            [2.0, -1.0, 0.0],
        ];
        let mut vertices = vec![[0.2, -0.1, 0.0]];
        vertices.extend(ring);
        let triangles = (0..5u32).map(|k| [0, 1 + k, 1 + (k + 1) % 5]).collect();
        let s = TriMesh::new(vertices.clone(), triangles);
        let w = mean_value_weights(&s);
        let (mut sum, mut mean) = (0.0, [0.0; 2]);
        for j in 1..6u32 {
            let wj = w[&(0, j)];
            sum += wj;
            mean = [0, 1].map(|k| mean[k] + wj * vertices[j as usize][k]);
        }
        for k in 0..2 {
            assert!(
                (mean[k] / sum - vertices[0][k]).abs() < 1e-6,
                "{mean:?} / {sum}"
            );
        }
    }
}
