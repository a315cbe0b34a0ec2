//! The radial order of the triangles around every edge, and the face-use links it implies.
//!
//! Around an edge `u→v` (welded ids, `u < v`) the incident triangles are half-planes; they are
//! sorted counter-clockwise about `v - u` (right-hand rule) with exact `orient3d` comparisons:
//! each half-plane is first classed against the first one as "the same", "in (0, π)", "opposite"
//! or "in (π, 2π)", and half-planes of one open half are ordered by the sign of `orient3d(u, v,
//! wa, wb)`. Between two consecutive half-planes lies a wedge of space; the face-use of each that
//! faces the wedge are linked. A triangle listing `u→v` has its front on its counter-clockwise
//! side. A free border edge (one triangle) links the triangle's two sides; two triangles lying
//! in the same half-plane (overlapping surfaces) are an error.

use super::weld::{P3, Soup, drop_axis, fmt_point};
use super::{PatchIn, RegionError};
use geom::{Orientation, orient2d, orient3d};
use std::cmp::Ordering;

/// Face-use index: `2 * triangle + (0 front, 1 back)`.
pub(super) fn fu(t: usize, front: bool) -> usize {
    2 * t + usize::from(!front)
}

/// Union-find over face-uses.
pub(super) use crate::union_find::UnionFind;

pub(super) struct Links {
    pub uf: UnionFind,
    /// Free border edges: (welded u, welded v, triangle).
    pub free_edges: Vec<(u32, u32, u32)>,
}

#[derive(Clone, Copy)]
struct Inc {
    tri: u32,
    /// The triangle lists the edge as `u→v` (lower id first).
    forward: bool,
    w: u32,
}

/// Half-plane class relative to the first one.
fn class(u: &P3, v: &P3, w0: &P3, w: &P3) -> u8 {
    match orient3d(u, v, w0, w) {
        Orientation::Positive => 1,
        Orientation::Negative => 3,
        Orientation::Zero => {
            if same_side_in_plane(u, v, w0, w) {
                0
            } else {
                2
            }
        }
    }
}

/// For `w` coplanar with the line `uv` and `w0` (not on it): whether `w` and `w0` are on the same
/// side of the line, decided exactly in a coordinate projection where `u, v, w0` do not degenerate.
fn same_side_in_plane(u: &P3, v: &P3, w0: &P3, w: &P3) -> bool {
    for k in 0..3 {
        let (pu, pv) = (drop_axis(u, k), drop_axis(v, k));
        let s0 = orient2d(&pu, &pv, &drop_axis(w0, k));
        if s0 != Orientation::Zero {
            return orient2d(&pu, &pv, &drop_axis(w, k)) == s0;
        }
    }
    true // unreachable for a non-degenerate triangle (checked when welding)
}

pub(super) fn link(soup: &Soup, patches: &[PatchIn]) -> Result<Links, RegionError> {
    let mut edges: Vec<(u32, u32, Inc)> = Vec::with_capacity(soup.tris.len() * 3);
    for (t, tri) in soup.tris.iter().enumerate() {
        for k in 0..3 {
            let (a, b, w) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
            let inc = Inc {
                tri: t as u32,
                forward: a < b,
                w,
            };
            edges.push((a.min(b), a.max(b), inc));
        }
    }
    let edges = sort_edges(edges, soup.points.len());
    let mut uf = UnionFind::new(soup.tris.len() * 2);
    let mut free_edges = Vec::new();
    let mut group: Vec<Inc> = Vec::new();
    let mut i = 0;
    while i < edges.len() {
        let (u, v) = (edges[i].0, edges[i].1);
        group.clear();
        while i < edges.len() && edges[i].0 == u && edges[i].1 == v {
            group.push(edges[i].2);
            i += 1;
        }
        if group.len() == 1 {
            free_edges.push((u, v, group[0].tri));
        }
        if group.len() > 2 {
            sort_around(soup, patches, u, v, &mut group)?;
        }
        let k = group.len();
        for j in 0..k {
            let (a, b) = (group[j], group[(j + 1) % k]);
            // a's counter-clockwise side faces the wedge, and so does b's clockwise side.
            uf.union(
                fu(a.tri as usize, a.forward),
                fu(b.tri as usize, !b.forward),
            );
        }
    }
    Ok(Links { uf, free_edges })
}

/// `edges` sorted by `(u, v, triangle)`: a counting sort on `u` (every `u < n`), then each
/// bucket (the few edges leaving one vertex) by `(v, triangle)`. The same order as a full sort,
/// in linear time on large models.
fn sort_edges(edges: Vec<(u32, u32, Inc)>, n: usize) -> Vec<(u32, u32, Inc)> {
    let mut start = vec![0usize; n + 1];
    for e in &edges {
        start[e.0 as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut order = vec![0u32; edges.len()];
    for (i, e) in edges.iter().enumerate() {
        order[fill[e.0 as usize]] = i as u32;
        fill[e.0 as usize] += 1;
    }
    let mut out: Vec<(u32, u32, Inc)> = order.iter().map(|&i| edges[i as usize]).collect();
    for w in start.windows(2) {
        out[w[0]..w[1]].sort_unstable_by_key(|e| (e.1, e.2.tri));
    }
    out
}

fn sort_around(
    soup: &Soup,
    patches: &[PatchIn],
    u: u32,
    v: u32,
    group: &mut [Inc],
) -> Result<(), RegionError> {
    let pu = soup.points[u as usize];
    let pv = soup.points[v as usize];
    let w0 = soup.points[group[0].w as usize];
    let mut keyed: Vec<(u8, Inc)> = group
        .iter()
        .map(|g| (class(&pu, &pv, &w0, &soup.points[g.w as usize]), *g))
        .collect();
    let cmp = |a: &(u8, Inc), b: &(u8, Inc)| -> Ordering {
        a.0.cmp(&b.0).then_with(|| {
            if a.0 == 1 || a.0 == 3 {
                let (wa, wb) = (soup.points[a.1.w as usize], soup.points[b.1.w as usize]);
                match orient3d(&pu, &pv, &wa, &wb) {
                    Orientation::Positive => Ordering::Less,
                    Orientation::Negative => Ordering::Greater,
                    Orientation::Zero => Ordering::Equal,
                }
            } else {
                Ordering::Equal
            }
        })
    };
    keyed.sort_by(cmp);
    for j in 1..keyed.len() {
        if cmp(&keyed[j - 1], &keyed[j]) == Ordering::Equal {
            let pa = &patches[soup.tri_patch[keyed[j - 1].1.tri as usize] as usize];
            let pb = &patches[soup.tri_patch[keyed[j].1.tri as usize] as usize];
            return Err(RegionError::new(
                format!(
                    "patches `{}` (surface `{}`) and `{}` (surface `{}`) overlap along the edge from {} to {}",
                    pa.name,
                    pa.surface,
                    pb.name,
                    pb.surface,
                    fmt_point(&pu),
                    fmt_point(&pv)
                ),
                Some(&pa.surface),
                Some(pu),
            ));
        }
    }
    for (g, k) in group.iter_mut().zip(keyed) {
        *g = k.1;
    }
    Ok(())
}
