//! Where nodes go on a segment, as parameters `t` of its points `a + t (b - a)`.
//!
//! To the size field (`placement`): as many pieces as the segment is long in local sizes (its
//! length integrated against `1 / size`, rounded), with equal shares of that integral, so the
//! pieces follow the size where it varies along a long well.
//!
//! On a missing piece (`split_params`), in order of preference: where the piece starts at a
//! vertex other segments end at too, the power-of-two distance from it within the piece's middle
//! third (Shewchuk's concentric shells: the segments meeting there are split at the same
//! distances, so a split of one does not crowd the other and force it to split closer again);
//! then the midpoint and the fractions 3/8, 5/8, 1/4, 3/4 of the piece, those at least half their
//! distance to the piece's ends clear of the vertices round the piece first, the others by how
//! clear they are (a node next to a vertex the piece passes makes a needle).

use geom::predicates::dist;

use super::super::super::super::lines::point_on;
use super::super::super::super::sizing::Background;
use super::super::super::tri::{NONE, Tri};
use super::super::flips::crossed_faces;
use super::super::star;

type P = [f64; 3];

/// Samples per local size when the length in sizes is integrated.
const SAMPLES_PER_SIZE: f64 = 4.0;
/// The most samples along one segment.
const MAX_SAMPLES: usize = 1 << 16;
/// Fractions of a missing piece tried, in order of preference.
const FRACTIONS: [f64; 5] = [0.5, 0.375, 0.625, 0.25, 0.75];
/// A fraction is clear when no vertex round the piece is nearer than this share of its distance
/// to the piece's nearer end.
const CLEAR: f64 = 0.5;

/// Parameters of the nodes dividing segment `ab` to the size field, increasing, in `(0, 1)`.
pub fn placement(a: &P, b: &P, bg: &Background) -> Vec<f64> {
    let len = dist(a, b);
    if !(len > 0.0 && len.is_finite()) {
        return Vec::new();
    }
    let per_length = |t: f64| {
        let h = bg.size_at(&point_on(a, b, t));
        if h > 0.0 && h.is_finite() {
            1.0 / h
        } else {
            0.0
        }
    };
    // The integral of 1 / size from a, sampled (trapezoids) at a quarter size or finer.
    let (mut ts, mut acc) = (vec![0.0], vec![0.0]);
    let (mut t, mut f) = (0.0, per_length(0.0));
    while t < 1.0 {
        let step = if f > 0.0 {
            1.0 / (SAMPLES_PER_SIZE * f * len)
        } else {
            1.0
        };
        let next = if ts.len() + 1 >= MAX_SAMPLES {
            1.0
        } else {
            (t + step.max(1.0 / MAX_SAMPLES as f64)).min(1.0)
        };
        let g = per_length(next);
        let last = acc[acc.len() - 1];
        acc.push(last + (next - t) * len * 0.5 * (f + g));
        ts.push(next);
        (t, f) = (next, g);
    }
    let total = acc[acc.len() - 1];
    let pieces = total.round().max(1.0) as usize;
    let mut out = Vec::with_capacity(pieces - 1);
    let mut j = 0;
    for i in 1..pieces {
        let target = total * i as f64 / pieces as f64;
        while j + 2 < acc.len() && acc[j + 1] < target {
            j += 1;
        }
        let span = acc[j + 1] - acc[j];
        let frac = if span > 0.0 {
            ((target - acc[j]) / span).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let t = ts[j] + frac * (ts[j + 1] - ts[j]);
        if t > 0.0 && t < 1.0 && out.last().is_none_or(|&l| t > l) {
            out.push(t);
        }
    }
    out
}

/// Parameters to try for a node on the missing piece from `u` (at `t0`) to `v` (at `t1`) of the
/// segment `ab`, best first; `apex`: whether the piece starts at `a`, or ends at `b`, where other
/// segments end too.
pub fn split_params(
    tri: &Tri,
    vtet: &[u32],
    (u, t0): (u32, f64),
    (v, t1): (u32, f64),
    (a, b): (P, P),
    apex: (bool, bool),
) -> Vec<f64> {
    let len = dist(&a, &b);
    let mut out = Vec::with_capacity(FRACTIONS.len() + 1);
    if apex.0 != apex.1 {
        // Distance from the apex to the piece's far end; the piece starts at the apex.
        let far = if apex.0 { t1 * len } else { (1.0 - t0) * len };
        let d = (far / 3.0).log2().ceil().exp2();
        if d >= far / 3.0 && d <= 2.0 * far / 3.0 {
            let t = if apex.0 { d / len } else { 1.0 - d / len };
            if t > t0 && t < t1 {
                out.push(t);
            }
        }
    }
    let near = vertices_round(tri, vtet, u, v);
    let piece = (t1 - t0) * len;
    let mut scored: Vec<(f64, usize, f64)> = FRACTIONS
        .iter()
        .enumerate()
        .map(|(i, &f)| {
            let t = t0 + f * (t1 - t0);
            let p = point_on(&a, &b, t);
            let clear = near
                .iter()
                .map(|&x| dist(&p, &tri.pts[x as usize]))
                .fold(f64::INFINITY, f64::min);
            let score = (clear / (f.min(1.0 - f) * piece)).min(CLEAR);
            (score, i, t)
        })
        .collect();
    scored.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
    out.extend(scored.into_iter().map(|s| s.2));
    out
}

/// The vertices of the faces the piece `uv` crosses, or of the tets round `u` when it crosses
/// none strictly; without `u` and `v`, sorted.
fn vertices_round(tri: &Tri, vtet: &[u32], u: u32, v: u32) -> Vec<u32> {
    let crossed = crossed_faces(tri, u, v, vtet);
    let mut out: Vec<u32> = if crossed.is_empty() {
        match vtet.get(u as usize) {
            Some(&t) if t != NONE => star(tri, u, t).flat_map(|s| tri.t[s as usize].v).collect(),
            _ => Vec::new(),
        }
    } else {
        crossed.iter().flat_map(|&(t, i)| tri.face(t, i)).collect()
    };
    out.retain(|&x| x != u && x != v);
    out.sort_unstable();
    out.dedup();
    out
}
