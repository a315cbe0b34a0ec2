//! Interior nodes by Delaunay refinement against the size field. In rounds, every tet whose
//! circumradius exceeds `SPLIT_RADIUS` times the local size proposes a point: its circumcenter,
//! or, when the tet stands on a boundary face and its circumcenter lies beyond that face, the
//! ideal apex over the face (the point an advancing front would place). The round's points are
//! inserted in Hilbert order, except those whose tet an earlier insertion of the round destroyed:
//! that point was nearly always refused as too close (six in seven in a 640k-tet region), after a
//! walk and a cavity; the new tets propose again in the next round if they are still too large.
//! A point is kept only if no vertex of its cavity is closer than
//! `MIN_SPACING` sizes and it stands at least `MIN_HEIGHT` sizes off every boundary face of its
//! cavity, so the spacing follows the size field and no flat tet is made against the boundary.
//! Only the tets a round created are examined in the next one; they propose as they are created,
//! while their corners are in cache, and proposals of tets destroyed since are dropped before the
//! round's sort. Deterministic: one thread, sorted work lists.

use geom::predicates::{cross, dist, dot, sub};
use geom::progress::Span;

use super::super::sizing::Background;
use super::tri::{FACE, Limits, NONE, P, Tri};
use geom::spatial_order::hilbert_sort;

/// A tet is split when its circumradius exceeds this many local sizes (a regular tet of edge h
/// has circumradius 0.61 h).
const SPLIT_RADIUS: f64 = 0.9;
/// Smallest distance from a new point to any vertex of its cavity, in local sizes.
const MIN_SPACING: f64 = 0.75;
/// Smallest distance from a new point to the plane of a boundary face of its cavity, in sizes.
const MIN_HEIGHT: f64 = 0.35;
/// Height of the ideal apex over a boundary face, in mean edge lengths (regular tet).
const APEX_HEIGHT: f64 = 0.816;

/// A proposed point, the slot of the tet that proposed it and that tet's [`fingerprint`].
type Cand = (P, u32, u32);
/// [`estimate`] looks at one tet slot in this many.
const ESTIMATE_EVERY: usize = 4;

/// The live tets' volume in units of the local size cubed, `∫ h⁻³ dV`, with `h` sampled at each
/// tet's centroid and halfway from it to each corner: what `progress` estimates refinement's
/// nodes from. From one slot in [`ESTIMATE_EVERY`], picked by a hash: within 2 % of the sum over
/// every tet on the didactic model's regions, for a quarter of its time (0.1-0.2 % of a region's).
pub fn estimate(tri: &Tri, bg: &Background) -> f64 {
    let mut sum = 0.0;
    for t in 0..tri.t.len() {
        if !geom::progress::sampled(t, ESTIMATE_EVERY) || !tri.alive(t as u32) {
            continue;
        }
        let [a, b, c, d] = tri.t[t].v.map(|v| tri.pts[v as usize]);
        let volume = dot(&sub(&b, &a), &cross(&sub(&c, &a), &sub(&d, &a))).abs() / 6.0;
        let g = [0, 1, 2].map(|k| 0.25 * (a[k] + b[k] + c[k] + d[k]));
        let per_volume = |p: &P| bg.size_at(p).powi(-3);
        let mut density = per_volume(&g);
        for q in [a, b, c, d] {
            density += per_volume(&[0, 1, 2].map(|k| 0.5 * (g[k] + q[k])));
        }
        sum += volume * density / 5.0;
    }
    let sum = sum * ESTIMATE_EVERY as f64;
    if sum.is_finite() { sum } else { 0.0 }
}

/// Refine in place, reporting on `bar` the points inserted of the `expected` ones.
pub fn refine(tri: &mut Tri, bg: &Background, bar: Span<'_>, expected: f64) {
    let expected = expected.max(1.0);
    let mut inserted = 0usize;
    let mut cands: Vec<Cand> = Vec::new();
    for t in 0..tri.t.len() as u32 {
        if tri.alive(t) {
            propose(tri, t, bg, &mut cands);
        }
    }
    let mut next: Vec<Cand> = Vec::new();
    let mut ids: Vec<u32> = Vec::new();
    let mut cpts: Vec<P> = Vec::new();
    tri.record = true;
    while !cands.is_empty() {
        cands.retain(|&(_, t, was)| tri.alive(t) && fingerprint(tri.t[t as usize].v) == was);
        cpts.clear();
        cpts.extend(cands.iter().map(|c| c.0));
        ids.clear();
        ids.extend(0..cands.len() as u32);
        hilbert_sort(&mut ids, &cpts);
        next.clear();
        let mut round = 0;
        for &k in &ids {
            let (p, from, was) = cands[k as usize];
            if !tri.alive(from) || fingerprint(tri.t[from as usize].v) != was {
                continue;
            }
            let h = bg.size_at(&p);
            let lim = Limits {
                min_dist: MIN_SPACING * h,
                min_height: MIN_HEIGHT * h,
            };
            tri.created.clear();
            if tri.insert(p, from, &lim).is_ok() {
                round += 1;
                inserted += 1;
                bar.reach(inserted as f64 / expected);
                // The new tets propose now, while their corners are in cache; a proposal whose
                // tet an insertion destroys before the next round is dropped then.
                for k in 0..tri.created.len() {
                    let t = tri.created[k];
                    propose(tri, t, bg, &mut next);
                }
            }
        }
        if round == 0 {
            break;
        }
        std::mem::swap(&mut cands, &mut next);
    }
    tri.created.clear();
    tri.record = false;
}

/// Push the point tet `t` proposes, if it proposes one.
fn propose(tri: &Tri, t: u32, bg: &Background, out: &mut Vec<Cand>) {
    if let Some(p) = proposal(tri, t, bg) {
        out.push((p, t, fingerprint(tri.t[t as usize].v)));
    }
}

/// A digest of a tet's vertices: when the slot of a proposing tet no longer holds the same tet,
/// its point is dropped. A collision only means an insertion is attempted, which checks
/// everything anyway.
fn fingerprint(tv: [u32; 4]) -> u32 {
    tv[0] ^ tv[1].rotate_left(8) ^ tv[2].rotate_left(16) ^ tv[3].rotate_left(24)
}

/// The point tet `t` proposes, if it is too large.
fn proposal(tri: &Tri, t: u32, bg: &Background) -> Option<P> {
    let tv = tri.t[t as usize].v;
    let [a, b, c, d] = tv.map(|v| tri.pts[v as usize]);
    let (cc, r) = circumcenter(&a, &b, &c, &d)?;
    let g = [0, 1, 2].map(|k| 0.25 * (a[k] + b[k] + c[k] + d[k]));
    let h = bg.size_at(&g).min(bg.size_at(&cc));
    if r <= SPLIT_RADIUS * h {
        return None;
    }
    // Against a boundary face the circumcenter may lie outside: take the ideal apex instead.
    for (i, f) in FACE.iter().enumerate() {
        let on_boundary =
            tri.t[t as usize].adj[i] == NONE || tri.t[t as usize].cons & (1 << i) != 0;
        if !on_boundary {
            continue;
        }
        let [x, y, z] = [f[0], f[1], f[2]].map(|k| tri.pts[tv[k] as usize]);
        let n = normal(&x, &y, &z);
        if dot(&sub(&cc, &x), &n) > 0.0 {
            let le = (dist(&x, &y) + dist(&y, &z) + dist(&z, &x)) / 3.0;
            let hh = APEX_HEIGHT * le.min(h);
            return Some([0, 1, 2].map(|k| (x[k] + y[k] + z[k]) / 3.0 - hh * n[k]));
        }
    }
    Some(cc)
}

/// Unit normal of `xyz` (pointing out of the tet for an outward face).
fn normal(x: &P, y: &P, z: &P) -> P {
    let n = cross(&sub(y, x), &sub(z, x));
    let l = dot(&n, &n).sqrt().max(f64::MIN_POSITIVE);
    n.map(|c| c / l)
}

/// Circumcenter and circumradius (float), `None` for a flat tet.
pub fn circumcenter(a: &P, b: &P, c: &P, d: &P) -> Option<(P, f64)> {
    let (u, v, w) = (sub(b, a), sub(c, a), sub(d, a));
    let (vw, wu, uv) = (cross(&v, &w), cross(&w, &u), cross(&u, &v));
    let den = 2.0 * dot(&u, &vw);
    if den == 0.0 || !den.is_finite() {
        return None;
    }
    let (lu, lv, lw) = (dot(&u, &u), dot(&v, &v), dot(&w, &w));
    let o = [0, 1, 2].map(|k| (lu * vw[k] + lv * wu[k] + lw * uv[k]) / den);
    Some(([a[0] + o[0], a[1] + o[1], a[2] + o[2]], dot(&o, &o).sqrt()))
}
