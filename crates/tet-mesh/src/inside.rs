//! Which side of a closed boundary an embedded segment lies on, decided exactly: the parity of
//! the boundary triangles a ray along +x crosses, cast from a point of the open segment.
//!
//! No float point of a segment's interior can be named in general, and a ray through an edge or
//! a vertex makes the count ambiguous, so the ray starts at a symbolically perturbed point
//! `q(ε) = u + ε (v - u) + ε² e_y + ε³ e_z` (ε infinitely small): a point of the open segment
//! next to `u`, nudged off every edge and plane that would make a tie. Every predicate the count
//! needs is affine in `q`, so its sign at `q(ε)` is the first non-zero of its value at `u`, its
//! value at `v`, and its two partial derivatives in y and z, each an exact `orient2d`, `orient3d`
//! or float comparison. The caller has checked that the open segment meets no boundary
//! triangle, so every point of it, `q(ε)` included, lies on the same side.

use geom::predicates::{Orientation, orient2d};

use super::exact::orient3d;

type P = [f64; 3];

/// The (y, z) projection, the plane the +x ray is seen in.
fn yz(p: &P) -> [f64; 2] {
    [p[1], p[2]]
}

/// The first non-zero sign of a symbolic expansion.
fn first(signs: impl IntoIterator<Item = i32>) -> i32 {
    signs.into_iter().find(|&s| s != 0).unwrap_or(0)
}

/// Sign of `orient2d(x, y, q(ε))` in the (y, z) projection.
fn turn(x: &P, y: &P, u: &P, v: &P) -> i32 {
    let (x2, y2) = (yz(x), yz(y));
    // Affine in q = (q_y, q_z): d/dq_y = x_z - y_z, d/dq_z = y_y - x_y.
    let cmp = |a: f64, b: f64| Orientation::from_f64(a - b).sign();
    first([
        orient2d(&x2, &y2, &yz(u)).sign(),
        orient2d(&x2, &y2, &yz(v)).sign(),
        cmp(x[2], y[2]),
        cmp(y[1], x[1]),
    ])
}

/// Whether the segment `uv` (its open part, next to `u`) lies inside the region the closed,
/// outward `boundary` encloses; `None` when the perturbed point lies on a boundary triangle
/// (the segment runs in it, which the caller's intersection test rules out). Scans every
/// triangle: the reference [`Rays`] is tested against.
#[cfg(test)]
pub fn segment_inside(u: &P, v: &P, pts: &[P], boundary: &[[u32; 3]]) -> Option<bool> {
    parity(u, v, pts, boundary.iter())
}

/// A closed boundary indexed for many parity queries: its triangles bucketed by their closed
/// (y, z) bounding boxes on a grid of about one cell per triangle. The perturbed ray of a query
/// stays infinitely close to the (y, z) of its start `u`, so it can only cross a triangle whose
/// closed box contains that point, and every such triangle is in the point's cell: cells are
/// found by one monotone float formula, so a box edge at the point's coordinate lands in the
/// point's cell. Each query then costs its cell, not the whole boundary.
pub struct Rays<'a> {
    pts: &'a [P],
    boundary: &'a [[u32; 3]],
    lo: [f64; 2],
    step: [f64; 2],
    cells: [usize; 2],
    /// Per cell (row-major in y, then z), the triangles whose box meets it.
    grid: Vec<Vec<u32>>,
}

impl<'a> Rays<'a> {
    pub fn new(pts: &'a [P], boundary: &'a [[u32; 3]]) -> Rays<'a> {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in boundary.iter().flatten().map(|&i| yz(&pts[i as usize])) {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let side = ((boundary.len() as f64).sqrt().ceil() as usize).clamp(1, 1024);
        let step = [0, 1].map(|k| {
            let span = hi[k] - lo[k];
            if span > 0.0 { span / side as f64 } else { 1.0 }
        });
        let mut rays = Rays {
            pts,
            boundary,
            lo,
            step,
            cells: [side, side],
            grid: vec![Vec::new(); side * side],
        };
        for (i, t) in boundary.iter().enumerate() {
            let corners = t.map(|v| yz(&pts[v as usize]));
            let (mut a, mut b) = ([usize::MAX; 2], [0; 2]);
            for c in &corners {
                let cell = rays.cell(c);
                for k in 0..2 {
                    a[k] = a[k].min(cell[k]);
                    b[k] = b[k].max(cell[k]);
                }
            }
            for y in a[0]..=b[0] {
                for z in a[1]..=b[1] {
                    rays.grid[y * side + z].push(i as u32);
                }
            }
        }
        rays
    }

    /// The cell of a (y, z) point, clamped to the grid.
    fn cell(&self, p: &[f64; 2]) -> [usize; 2] {
        [0, 1].map(|k| {
            let x = ((p[k] - self.lo[k]) / self.step[k]).floor();
            (x.max(0.0) as usize).min(self.cells[k] - 1)
        })
    }

    /// [`segment_inside`] against the indexed boundary.
    pub fn segment_inside(&self, u: &P, v: &P) -> Option<bool> {
        if self.boundary.is_empty() {
            return Some(false);
        }
        let [y, z] = self.cell(&yz(u));
        let near = &self.grid[y * self.cells[1] + z];
        parity(
            u,
            v,
            self.pts,
            near.iter().map(|&i| &self.boundary[i as usize]),
        )
    }
}

/// The parity of the crossings of the perturbed ray from `u` (towards `v`) with `triangles`.
fn parity<'t>(
    u: &P,
    v: &P,
    pts: &[P],
    triangles: impl Iterator<Item = &'t [u32; 3]>,
) -> Option<bool> {
    let mut crossings = 0usize;
    for t in triangles {
        let [a, b, c] = t.map(|i| &pts[i as usize]);
        // The x component of the right-hand normal: zero for a triangle parallel to the ray,
        // which the perturbed ray never meets.
        let nx = orient2d(&yz(a), &yz(b), &yz(c)).sign();
        if nx == 0 {
            continue;
        }
        let inside = [turn(a, b, u, v), turn(b, c, u, v), turn(c, a, u, v)];
        if inside.iter().any(|&s| s != nx) {
            continue;
        }
        // Which side of the plane q(ε) lies on: n·(q - a), with n_y and n_z the normal's other
        // components (the (z, x) and (x, y) projections' turns).
        let zx = |p: &P| [p[2], p[0]];
        let xy = |p: &P| [p[0], p[1]];
        let side = first([
            orient3d(a, b, c, u).sign(),
            orient3d(a, b, c, v).sign(),
            orient2d(&zx(a), &zx(b), &zx(c)).sign(),
            orient2d(&xy(a), &xy(b), &xy(c)).sign(),
        ]);
        if side == 0 {
            return None;
        }
        // The ray q + s e_x meets the plane at s = -n·(q - a) / n_x: ahead when the signs differ.
        if side != nx {
            crossings += 1;
        }
    }
    Some(crossings % 2 == 1)
}

/// Which vertices the boundary triangles use.
pub fn boundary_vertices(n: usize, boundary: &[[u32; 3]]) -> Vec<bool> {
    let mut on = vec![false; n];
    for &v in boundary.iter().flatten() {
        on[v as usize] = true;
    }
    on
}

/// The first item of each group of items joined at vertices off the boundary (`on_boundary`
/// marks its vertices), in item order. When no item crosses the boundary, the items of a group
/// lie on one side of it together, so testing one of each decides them all.
pub fn one_per_group<const N: usize>(items: &[[u32; N]], on_boundary: &[bool]) -> Vec<usize> {
    let mut parent: Vec<usize> = (0..items.len()).collect();
    let find = |parent: &mut Vec<usize>, mut x: usize| {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    };
    let mut at_vertex: Vec<(u32, usize)> = (items.iter().enumerate())
        .flat_map(|(k, s)| s.map(|v| (v, k)))
        .filter(|&(v, _)| !on_boundary[v as usize])
        .collect();
    at_vertex.sort_unstable();
    for w in at_vertex.windows(2) {
        if w[0].0 == w[1].0 {
            let (a, b) = (find(&mut parent, w[0].1), find(&mut parent, w[1].1));
            parent[a.max(b)] = a.min(b);
        }
    }
    (0..items.len())
        .filter(|&k| find(&mut parent, k) == k)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit cube's corners and its twelve outward triangles.
    #[test]
    fn segments_inside_and_outside_a_cube_are_told_apart_even_when_the_ray_runs_through_an_edge() {
        let (mut pts, tris) = test_support::shapes::cuboid([0.0; 3], [1.0; 3]);
        // The ray from the centre leaves through the middle of the +x side's diagonal.
        pts.extend([
            [0.5, 0.5, 0.5],
            [0.25, 0.25, 0.25],
            [3.0, 0.5, 0.5],
            [-1.0, -1.0, 0.5],
        ]);
        let (centre, low, far, away) = (8, 9, 10, 11);
        let inside = |u: usize, v: usize| segment_inside(&pts[u], &pts[v], &pts, &tris);
        assert_eq!(inside(centre, low), Some(true));
        // From a corner into the cube, along its space diagonal, and away from it.
        assert_eq!(inside(0, centre), Some(true));
        assert_eq!(inside(7, low), Some(true));
        assert_eq!(inside(0, 7), Some(true));
        assert_eq!(inside(1, far), Some(false));
        assert_eq!(inside(0, away), Some(false));
        assert_eq!(inside(far, away), Some(false));
    }

    #[test]
    fn the_indexed_rays_agree_with_the_scan_of_every_triangle() {
        let (mut pts, tris) = test_support::shapes::octahedron();
        // Points on a lattice of sixths through the octahedron's vertices, edges and faces and
        // the grid's cell edges (thirds), so that many rays start on a cell edge or run through
        // an edge or a vertex.
        let n = pts.len();
        for i in 0..13 {
            for j in 0..13 {
                for k in 0..13 {
                    pts.push([i, j, k].map(|c| -1.0 + c as f64 / 6.0));
                }
            }
        }
        let rays = Rays::new(&pts, &tris);
        for a in n..pts.len() {
            let b = n + (a * 7919) % (pts.len() - n);
            let (u, v) = (&pts[a], &pts[b]);
            assert_eq!(
                rays.segment_inside(u, v),
                segment_inside(u, v, &pts, &tris),
                "{u:?} {v:?}"
            );
        }
    }
}
