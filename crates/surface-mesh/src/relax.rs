//! A projection mended where a few triangles turn over: teeth of the border folded back, and the
//! vertices round the rest relaxed to their Tutte positions among the others, which keep their
//! projected places.
//!
//! A chart of a smoothed closed body faces one way but for a handful of triangles (teeth of its
//! stair-stepped border curled round the body's rim, a step of that stair running backwards):
//! the projection onto its mean plane turns those over, so the whole chart went to a Tutte embedding. Pinned on the border's projection,
//! that embedding turned two of a 3 km channel top's 13,000 triangles over as well (its border
//! is far from convex), and pinned on a circle it squeezed the strip so much that the surface
//! mesh made there folded on the support, whatever the size.
//!
//! Decisions and why:
//! - A turned triangle with a corner in no other triangle is a tooth of the border curled round
//!   the body's rim (seven of the smoothed channel's eight): that corner is mirrored across the
//!   tooth's base, which unfolds the tooth as the rim would unroll, and moves nothing else.
//! - The corners of the triangles still turned move, border ones too (a step of the border's
//!   stair that runs backwards on the plane cannot be mended from inside), and so do the interior
//!   vertices within a few rings of them; every other vertex keeps its projection, where the
//!   projection keeps the support's shapes. A vertex moved goes to the mean value weighted mean
//!   of its neighbours (the weights of `tutte`), solved for all the moved ones at once: inside a
//!   small region with a nearly convex rim, Tutte's theorem makes that one to one, and each ring
//!   more makes the rim rounder.
//! - A flat triangle (a needle of the support, zero area in 3D) is left to the Tutte embedding:
//!   relaxed, it takes an area in the plane that maps onto a segment, and the mesh made there
//!   folds.
//! - The result must pass the exact test of every flattening (`param::injective`); when no ring
//!   count up to [`MAX_RINGS`] does, or the triangles turned over are more than a few
//!   ([`MAX_TURNED`]), the chart goes to the Tutte embedding as before.

use super::param::{border_crosses, injective};
use super::sparse::Rows;
use geom::{Orientation, TriMesh, orient2d};

/// Most rings of neighbours round the turned triangles that are relaxed.
const MAX_RINGS: usize = 6;

/// Most triangles turned over in the projection that relaxing mends: a thousandth of the
/// support's, and at least this many.
const MAX_TURNED: usize = 16;

/// The projection `uv` of the support `s` (border `loops`), its turned triangles mended by
/// relaxing the interior vertices round them, when that makes it one to one.
pub fn mended(s: &TriMesh, loops: &[Vec<u32>], uv: &[[f64; 2]]) -> Option<Vec<[f64; 2]>> {
    let first = turned(s, uv)?;
    if first.is_empty() || first.len() > MAX_TURNED.max(s.triangles.len() / 1000) {
        return None;
    }
    let nv = s.vertices.len();
    let mut uses = vec![0u32; nv];
    for &v in s.triangles.iter().flatten() {
        uses[v as usize] += 1;
    }
    let mut uv = uv.to_vec();
    unfold_teeth(s, &mut uv, &first, &uses);
    if border_crosses(loops, &uv) {
        return None;
    }
    let mut on_border = vec![false; nv];
    for &v in loops.iter().flatten() {
        on_border[v as usize] = true;
    }
    let movable = |v: u32| !on_border[v as usize] && uses[v as usize] > 0;
    let mut free = vec![false; nv];
    for t in turned(s, &uv)? {
        for v in s.triangles[t as usize] {
            free[v as usize] = uses[v as usize] > 0;
        }
    }
    if !free.contains(&true) {
        return injective(s, loops, &uv).then_some(uv);
    }
    let rows = Rows::new(&super::tutte::mean_value_weights(s), nv);
    for _ in 0..MAX_RINGS {
        let relaxed = relax(&rows, &uv, &free);
        if injective(s, loops, &relaxed) {
            return Some(relaxed);
        }
        free = widened(s, &free, &movable);
    }
    None
}

/// Folds each turned triangle of `turned` that has a corner in no other triangle (a tooth of
/// the border, wrapped round a body's rim) back over its base: that corner is mirrored across
/// the line through the other two. `uses` counts each vertex's triangles.
fn unfold_teeth(s: &TriMesh, uv: &mut [[f64; 2]], turned: &[u32], uses: &[u32]) {
    for &t in turned {
        let tri = s.triangles[t as usize];
        let Some(k) = (0..3).find(|&k| uses[tri[k] as usize] == 1) else {
            continue;
        };
        let [p, a, b] = [0, 1, 2].map(|i| uv[tri[(k + i) % 3] as usize]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        if !(len2 > 0.0) {
            continue;
        }
        let along = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2;
        let foot = [a[0] + along * d[0], a[1] + along * d[1]];
        uv[tri[k] as usize] = [2.0 * foot[0] - p[0], 2.0 * foot[1] - p[1]];
    }
}

/// The triangles clockwise in `uv` (exact); `None` if one is flat there (a needle of the support
/// itself, which no relaxing makes a triangle in 3D).
fn turned(s: &TriMesh, uv: &[[f64; 2]]) -> Option<Vec<u32>> {
    let mut out = Vec::new();
    for (t, tri) in s.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|v| uv[v as usize]);
        match orient2d(&a, &b, &c) {
            Orientation::Positive => {}
            Orientation::Negative => out.push(t as u32),
            Orientation::Zero => return None,
        }
    }
    Some(out)
}

/// `free` and the `movable` vertices one edge from it.
fn widened(s: &TriMesh, free: &[bool], movable: &impl Fn(u32) -> bool) -> Vec<bool> {
    let mut out = free.to_vec();
    for t in &s.triangles {
        if t.iter().any(|&v| free[v as usize]) {
            for &v in t {
                out[v as usize] |= movable(v);
            }
        }
    }
    out
}

/// `uv` with the `free` vertices at their weighted means of their neighbours, solved together.
fn relax(rows: &Rows, uv: &[[f64; 2]], free: &[bool]) -> Vec<[f64; 2]> {
    let pinned: Vec<bool> = free.iter().map(|&f| !f).collect();
    let mut out = uv.to_vec();
    for k in 0..2 {
        let x = rows.solve(&pinned, uv, k);
        for (i, q) in out.iter_mut().enumerate() {
            if free[i] {
                q[k] = x[i];
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::param::{border_loops, mean_plane_uv};

    /// A square grid of `n × n` cells of 1 m, flat but for vertex `bump` (in the grid's
    /// numbering), pushed across its neighbours by `push` in x and lifted by `lift`, so that
    /// the projection turns the triangles on one side of it over.
    fn grid_with_a_fold(n: usize, bump: usize, push: f64, lift: f64) -> TriMesh {
        let mut v = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                v.push([i as f64, j as f64, 0.0]);
            }
        }
        v[bump][0] += push;
        v[bump][2] += lift;
        let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let mut t = Vec::new();
        for j in 0..n {
            for i in 0..n {
                t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        TriMesh::new(v, t)
    }

    #[test]
    fn a_vertex_folded_over_its_neighbours_is_relaxed_back_and_nothing_else_moves() {
        // The middle vertex of an 8 × 8 grid pushed 1.5 m over its neighbour, 0.5 m up.
        let s = grid_with_a_fold(8, 4 * 9 + 4, 1.5, 0.5);
        let loops = border_loops(&s).ok().expect("a disk");
        let uv = mean_plane_uv(&s).expect("a mean plane");
        assert!(!injective(&s, &loops, &uv), "the projection folds");
        let mended = mended(&s, &loops, &uv).expect("mended");
        assert!(injective(&s, &loops, &mended));
        // The border keeps its projection, and vertices three rings or more from the fold are
        // where the projection put them.
        for &v in loops.iter().flatten() {
            assert_eq!(mended[v as usize], uv[v as usize]);
        }
        let far = (0..81usize).filter(|&v| {
            let (i, j) = (v % 9, v / 9);
            i.abs_diff(4).max(j.abs_diff(4)) >= 3
        });
        for v in far {
            assert_eq!(mended[v], uv[v], "vertex {v}");
        }
    }

    #[test]
    fn a_projection_without_a_turned_triangle_or_with_a_crossing_border_is_not_mended() {
        let flat = grid_with_a_fold(4, 12, 0.0, 0.0);
        let loops = border_loops(&flat).ok().expect("a disk");
        let uv = mean_plane_uv(&flat).expect("a mean plane");
        assert_eq!(mended(&flat, &loops, &uv), None);
        // A border vertex drawn across the square and past its far side: the border crosses
        // itself there.
        let mut uv = uv;
        let far = uv[4 * 5 + 2];
        uv[2] = [2.0 * far[0] - uv[2][0], 2.0 * far[1] - uv[2][1]];
        assert!(!turned(&flat, &uv).expect("no flat triangle").is_empty());
        assert_eq!(mended(&flat, &loops, &uv), None);
    }
}
