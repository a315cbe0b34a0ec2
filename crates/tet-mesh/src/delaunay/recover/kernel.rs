//! A hole meshed as a cone from one new node: where the hole is star-shaped, every tet joining
//! a surface triangle to a point of its kernel (the points that see every triangle from the
//! inside) is valid, and together they fill it exactly. Recovery holes are small and often thin
//! twisted prisms that no tetrahedralization of their own vertices fills (as Schönhardt's
//! polyhedron) and that are too thin for the front's sized nodes; one node in the kernel fills
//! them, and the optimizer then moves it.
//!
//! The point is the centre of the largest ball inside every triangle's inner half-space (a small
//! linear program, solved in floats): the kernel point farthest from the hole's surface. Whether
//! it sees every triangle is then decided exactly.

use geom::predicates::Orientation;

use super::super::super::exact::orient3d;
use super::super::tri::P;

/// Linear programs larger than this (triangles) are not tried: a widened hole, which the front
/// meshes better than a cone.
const MAX_FACES: usize = 400;
/// Simplex pivots per constraint before the program is given up.
const PIVOTS_PER_ROW: usize = 50;

/// The tets of the cone from a new node (numbered `pts.len()`) over the closed surface `faces`
/// (outward right-hand normals), and the node; `None` where no point sees every face, or where
/// one of the `segments` (which must later become chains of edges) passes through the ball
/// round the node.
pub fn cone(pts: &[P], faces: &[[u32; 3]], segments: &[[P; 2]]) -> Option<(P, Vec<[u32; 4]>)> {
    if faces.len() > MAX_FACES {
        return None;
    }
    let (x, radius) = kernel_centre(pts, faces)?;
    if segments.iter().any(|s| segment_distance(&x, s) <= radius) {
        return None;
    }
    // Each tet turned so that it is positive: the face's reverse, then the apex.
    let sees = |f: &[u32; 3]| {
        orient3d(
            &pts[f[1] as usize],
            &pts[f[0] as usize],
            &pts[f[2] as usize],
            &x,
        ) == Orientation::Positive
    };
    if !faces.iter().all(sees) {
        return None;
    }
    let apex = pts.len() as u32;
    Some((x, faces.iter().map(|f| [f[1], f[0], f[2], apex]).collect()))
}

/// Distance from `p` to the segment `s` (floats: it only keeps a node clear of a segment).
fn segment_distance(p: &P, s: &[P; 2]) -> f64 {
    let d = [0, 1, 2].map(|k| s[1][k] - s[0][k]);
    let w = [0, 1, 2].map(|k| p[k] - s[0][k]);
    let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let t = if dd > 0.0 {
        ((w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = [0, 1, 2].map(|k| w[k] - t * d[k]);
    (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt()
}

/// The centre of the largest ball in every face's inner half-space and its radius, if positive.
fn kernel_centre(pts: &[P], faces: &[[u32; 3]]) -> Option<(P, f64)> {
    // Local, scaled coordinates: y = (x - c) / e in [-1, 1]³.
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &v in faces.iter().flatten() {
        for k in 0..3 {
            lo[k] = lo[k].min(pts[v as usize][k]);
            hi[k] = hi[k].max(pts[v as usize][k]);
        }
    }
    let c = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
    let e = (0..3).map(|k| 0.5 * (hi[k] - lo[k])).fold(0.0, f64::max);
    if e <= 0.0 {
        return None;
    }
    let local = |v: u32| [0, 1, 2].map(|k| (pts[v as usize][k] - c[k]) / e);
    // Per face: the inward unit normal `a` and offset `b`, inside meaning a·y - b ≥ 0.
    let mut planes = Vec::with_capacity(faces.len());
    for f in faces {
        let [p, q, r] = f.map(local);
        let u = [0, 1, 2].map(|k| q[k] - p[k]);
        let w = [0, 1, 2].map(|k| r[k] - p[k]);
        let n = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if len == 0.0 || !len.is_finite() {
            return None;
        }
        let a = n.map(|x| -x / len);
        planes.push((a, a[0] * p[0] + a[1] * p[1] + a[2] * p[2]));
    }
    let (y, radius) = largest_ball(&planes)?;
    (radius > 1e-9).then(|| ([0, 1, 2].map(|k| c[k] + e * y[k]), e * radius))
}

/// Maximises `t` over `y` in [-1, 1]³ with `a·y - t ≥ b` for every plane; returns `(y, t)`.
///
/// With `u = y + 1` and `s = t + T` (`T` large enough that `u = 0, s = 0` is feasible) every
/// constraint reads `-a·u + s ≤ T - b - a·1`, with a non-negative right side: a simplex from the
/// slack basis, Bland's rule against cycling.
fn largest_ball(planes: &[([f64; 3], f64)]) -> Option<([f64; 3], f64)> {
    let big = planes.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max) + 2.0;
    // Rows: the planes, then u_k ≤ 2, then s ≤ T + 1. Columns: u0, u1, u2, s, the slacks, rhs.
    let m = planes.len() + 4;
    let cols = 4 + m + 1;
    let mut tab = vec![0.0; (m + 1) * cols];
    let mut basis: Vec<usize> = (4..4 + m).collect();
    for (i, (a, b)) in planes.iter().enumerate() {
        let row = &mut tab[i * cols..(i + 1) * cols];
        for k in 0..3 {
            row[k] = -a[k];
        }
        row[3] = 1.0;
        row[cols - 1] = big - b - (a[0] + a[1] + a[2]);
    }
    for k in 0..4 {
        let i = planes.len() + k;
        tab[i * cols + k] = 1.0;
        tab[i * cols + cols - 1] = if k < 3 { 2.0 } else { big + 1.0 };
    }
    for (i, &b) in basis.iter().enumerate() {
        tab[i * cols + b] = 1.0;
    }
    // Objective row: maximise s.
    tab[m * cols + 3] = -1.0;
    for _ in 0..PIVOTS_PER_ROW * m {
        let Some(enter) = (0..cols - 1).find(|&j| tab[m * cols + j] < -1e-12) else {
            let mut z = [0.0; 4];
            for (i, &b) in basis.iter().enumerate() {
                if b < 4 {
                    z[b] = tab[i * cols + cols - 1];
                }
            }
            return Some(([z[0] - 1.0, z[1] - 1.0, z[2] - 1.0], z[3] - big));
        };
        let mut leave: Option<(f64, usize, usize)> = None;
        for i in 0..m {
            let a = tab[i * cols + enter];
            if a > 1e-12 {
                let ratio = tab[i * cols + cols - 1] / a;
                let better = match leave {
                    None => true,
                    Some((r, _, b)) => ratio < r || (ratio == r && basis[i] < b),
                };
                if better {
                    leave = Some((ratio, i, basis[i]));
                }
            }
        }
        let (_, row, _) = leave?;
        pivot(&mut tab, cols, row, enter);
        basis[row] = enter;
    }
    None
}

/// One simplex pivot on (`row`, `col`) of the tableau.
fn pivot(tab: &mut [f64], cols: usize, row: usize, col: usize) {
    let p = tab[row * cols + col];
    for j in 0..cols {
        tab[row * cols + j] /= p;
    }
    let rows = tab.len() / cols;
    for i in 0..rows {
        if i == row {
            continue;
        }
        let f = tab[i * cols + col];
        if f != 0.0 {
            for j in 0..cols {
                tab[i * cols + j] -= f * tab[row * cols + j];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The prism over a counter-clockwise `plan` from z = 0 to 1, its caps triangulated by
    /// `caps` (counter-clockwise in plan): outward triangles.
    fn prism(plan: &[[f64; 2]], caps: &[[u32; 3]]) -> (Vec<P>, Vec<[u32; 3]>) {
        let n = plan.len() as u32;
        let mut pts: Vec<P> = plan.iter().map(|p| [p[0], p[1], 0.0]).collect();
        pts.extend(plan.iter().map(|p| [p[0], p[1], 1.0]));
        let mut faces: Vec<[u32; 3]> = Vec::new();
        for &[a, b, c] in caps {
            faces.push([a, c, b]);
            faces.push([a + n, b + n, c + n]);
        }
        for i in 0..n {
            let j = (i + 1) % n;
            faces.push([i, j, j + n]);
            faces.push([i, j + n, i + n]);
        }
        (pts, faces)
    }

    #[test]
    fn a_cube_is_coned_from_its_centre() {
        let (pts, faces) = test_support::shapes::cuboid([0.0; 3], [1.0; 3]);
        let (x, tets) = cone(&pts, &faces, &[]).expect("a convex hole is star-shaped");
        for k in 0..3 {
            assert!((x[k] - 0.5).abs() < 1e-9, "{x:?}");
        }
        assert_eq!(tets.len(), 12);
        // A well through the centre keeps the node away.
        assert!(cone(&pts, &faces, &[[[0.5, 0.5, 0.0], [0.5, 0.5, 1.0]]]).is_none());
    }

    #[test]
    fn a_twisted_prism_no_tetrahedralization_fills_is_coned() {
        // Schönhardt's polyhedron: a triangular prism whose top is turned by 30°.
        let tri = |r: f64, z: f64, turn: f64| -> Vec<P> {
            (0..3)
                .map(|i| {
                    let a = turn + i as f64 * 2.0 * std::f64::consts::PI / 3.0;
                    [r * a.cos(), r * a.sin(), z]
                })
                .collect()
        };
        let mut pts = tri(1.0, 0.0, 0.0);
        pts.extend(tri(1.0, 1.0, 0.5));
        // Bottom (normal down), top (up), and each side quad split along its reflex diagonal.
        let mut faces = vec![[0, 2, 1], [3, 4, 5]];
        for i in 0..3u32 {
            let j = (i + 1) % 3;
            faces.push([i, j, 3 + j]);
            faces.push([i, 3 + j, 3 + i]);
        }
        let (_, tets) = cone(&pts, &faces, &[]).expect("the twisted prism sees its axis");
        assert_eq!(tets.len(), 8);
    }

    #[test]
    fn a_u_shaped_hole_whose_arms_hide_each_other_is_refused() {
        // The left arm's inner side x = 1 and the right arm's x = 2 face each other, so no point
        // sees both.
        let u = [
            [0., 0.],
            [3., 0.],
            [3., 3.],
            [2., 3.],
            [2., 1.],
            [1., 1.],
            [1., 3.],
            [0., 3.],
        ];
        let caps = [
            [0, 1, 4],
            [0, 4, 5],
            [1, 2, 3],
            [1, 3, 4],
            [0, 5, 6],
            [0, 6, 7],
        ];
        let (pts, faces) = prism(&u, &caps);
        assert!(cone(&pts, &faces, &[]).is_none());
        // Without its right arm (an L) it is star-shaped.
        let l = [[0., 0.], [3., 0.], [3., 1.], [1., 1.], [1., 3.], [0., 3.]];
        let caps = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]];
        let (pts, faces) = prism(&l, &caps);
        let (x, tets) = cone(&pts, &faces, &[]).expect("an L sees its corner");
        assert!(x[0] < 1.0 && x[1] < 1.0, "{x:?}");
        assert_eq!(tets.len(), faces.len());
    }
}
