//! Exact point/segment tests against triangles: the parity (ray casting) point-in-closed-surface
//! test behind `locate`, the exterior decision and nesting, and the construction of points
//! verified to lie just off one side of a triangle.
//!
//! Ray casting: a segment from the query point to a point beyond the bounding box is tested
//! against each triangle with `orient3d` only. A segment through an edge, a vertex or in a
//! triangle's plane is degenerate: another far point (a fixed, deterministic sequence) is tried,
//! so every counted crossing is a proper one and the parity is exact.

use super::PatchIn;
use super::weld::{P3, drop_axis};
use geom::predicates::{cross, sub};
use geom::{BBox, Orientation, orient2d, orient3d};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};

pub(super) type Tri = [P3; 3];

/// The model's triangles with an R-tree of their boxes: [`near_point`] asks which of them a short
/// segment may touch once per shell, and a scan of them all made that quadratic in the number of
/// patches (a fault of thousands of triangles touching at corners, each a dangling shell).
pub(super) struct Indexed<'a> {
    pub tris: &'a [Tri],
    boxes: RTree<GeomWithData<Rectangle<P3>, usize>>,
}

impl<'a> Indexed<'a> {
    pub fn new(tris: &'a [Tri]) -> Self {
        let boxes = (tris.iter().enumerate())
            .map(|(k, t)| {
                let b = BBox::from_points(t.iter());
                GeomWithData::new(Rectangle::from_corners(b.min, b.max), k)
            })
            .collect();
        Indexed {
            tris,
            boxes: RTree::bulk_load(boxes),
        }
    }

    /// The triangles whose boxes meet `b` (closed boxes, as [`BBox::overlaps`]), in no order.
    fn meeting(&self, b: &BBox) -> impl Iterator<Item = usize> + '_ {
        let env = AABB::from_corners(b.min, b.max);
        (self.boxes.locate_in_envelope_intersecting(env)).map(|g| g.data)
    }
}

#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum Loc {
    Inside,
    Outside,
    OnBoundary,
}

enum Cross {
    No,
    Proper,
    Degenerate,
    OnTriangle,
}

/// Whether `q`, coplanar with `abc`, lies in the closed triangle (exact, in a coordinate
/// projection where the triangle does not degenerate).
pub(super) fn in_coplanar_triangle(q: &P3, [a, b, c]: &Tri) -> bool {
    for k in 0..3 {
        let (pa, pb, pc, pq) = (
            drop_axis(a, k),
            drop_axis(b, k),
            drop_axis(c, k),
            drop_axis(q, k),
        );
        let s = orient2d(&pa, &pb, &pc);
        if s == Orientation::Zero {
            continue;
        }
        let bad = s.flip();
        return orient2d(&pa, &pb, &pq) != bad
            && orient2d(&pb, &pc, &pq) != bad
            && orient2d(&pc, &pa, &pq) != bad;
    }
    false
}

fn signs3(q: &P3, f: &P3, [a, b, c]: &Tri) -> (bool, bool) {
    let s = [
        orient3d(q, f, a, b),
        orient3d(q, f, b, c),
        orient3d(q, f, c, a),
    ];
    (
        s.contains(&Orientation::Positive),
        s.contains(&Orientation::Negative),
    )
}

fn crossing(q: &P3, f: &P3, t: &Tri) -> Cross {
    let [a, b, c] = t;
    let sq = orient3d(a, b, c, q);
    let sf = orient3d(a, b, c, f);
    if sq == Orientation::Zero {
        if in_coplanar_triangle(q, t) {
            return Cross::OnTriangle;
        }
        return if sf == Orientation::Zero {
            Cross::Degenerate
        } else {
            Cross::No
        };
    }
    if sf == Orientation::Zero || sq == sf {
        return Cross::No;
    }
    let s = [
        orient3d(q, f, a, b),
        orient3d(q, f, b, c),
        orient3d(q, f, c, a),
    ];
    let pos = s.contains(&Orientation::Positive);
    let neg = s.contains(&Orientation::Negative);
    if pos && neg {
        Cross::No
    } else if s.contains(&Orientation::Zero) {
        Cross::Degenerate
    } else {
        Cross::Proper
    }
}

fn frac(x: f64) -> f64 {
    x - x.floor()
}

/// The k-th far point for ray casting from `q`: beyond the box in +x, with deterministic slopes.
fn far_point(q: &P3, bbox: &BBox, k: usize) -> P3 {
    let e = bbox.extent();
    let mut l = e[0].max(e[1]).max(e[2]).max(1.0);
    for ((qi, lo), hi) in q.iter().zip(&bbox.min).zip(&bbox.max) {
        l = l.max((qi - lo).abs()).max((qi - hi).abs());
    }
    let a = frac(0.5 + k as f64 * 0.618_033_988_749_894_9) - 0.5;
    let b = frac(0.5 + k as f64 * 0.754_877_666_246_692_7) - 0.5;
    [
        bbox.max[0].max(q[0]) + 2.0 * l,
        q[1] + (a + 0.0137) * l,
        q[2] + (b + 0.0071) * l,
    ]
}

/// Whether the closed box `b` may meet the closed triangle `t`: `false` only when all three
/// corners lie strictly beyond one face of the box (exact comparisons of input coordinates), so
/// nothing inside the box (a segment between two of its corners, a point) touches `t`. The
/// cheap rejection in front of the `orient3d` tests: the rays of [`parity`] are nearly parallel
/// to x, so their boxes are thin in y and z.
#[inline]
pub(super) fn may_meet(b: &BBox, t: &Tri) -> bool {
    (0..3).all(|k| {
        let lo = t[0][k].min(t[1][k]).min(t[2][k]);
        let hi = t[0][k].max(t[1][k]).max(t[2][k]);
        lo <= b.max[k] && b.min[k] <= hi
    })
}

/// Parity of `q` against the closed surface made of `tris` (exact); `None` when every tried ray
/// is degenerate.
pub(super) fn parity(q: &P3, tris: &[Tri], bbox: &BBox) -> Option<Loc> {
    for k in 0..64 {
        let f = far_point(q, bbox, k);
        let seg = BBox::from_points([q, &f]);
        let mut count = 0usize;
        let mut degenerate = false;
        for t in tris.iter().filter(|t| may_meet(&seg, t)) {
            match crossing(q, &f, t) {
                Cross::OnTriangle => return Some(Loc::OnBoundary),
                Cross::Proper => count += 1,
                Cross::Degenerate => degenerate = true,
                Cross::No => {}
            }
        }
        if !degenerate {
            return Some(if count % 2 == 1 {
                Loc::Inside
            } else {
                Loc::Outside
            });
        }
    }
    None
}

/// Whether the closed segment `qr` may touch the closed triangle: `false` only when it provably
/// does not (exact).
fn segment_may_touch(q: &P3, r: &P3, t: &Tri) -> bool {
    let [a, b, c] = t;
    let sq = orient3d(a, b, c, q);
    let sr = orient3d(a, b, c, r);
    if sq == sr && sq != Orientation::Zero {
        return false;
    }
    if sq == Orientation::Zero && sr == Orientation::Zero {
        return true;
    }
    let (pos, neg) = signs3(q, r, t);
    !(pos && neg)
}

/// A point just off side `front` of triangle `t` of `all`, verified exactly: the segment from it
/// to its mirror point crosses `t` properly through its interior and touches no other triangle,
/// so the point lies in the open cell of space that face-use faces.
pub(super) fn near_point(all: &Indexed, t: usize, front: bool) -> Option<P3> {
    let tri = all.tris.get(t)?;
    let [a, b, c] = tri;
    let (ab, ac) = (sub(b, a), sub(c, a));
    let n = cross(&ab, &ac);
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    let sign = if front { 1.0 } else { -1.0 };
    let dir = [sign * n[0] / len, sign * n[1] / len, sign * n[2] / len];
    let g = [
        a[0] + (ab[0] + ac[0]) / 3.0,
        a[1] + (ab[1] + ac[1]) / 3.0,
        a[2] + (ab[2] + ac[2]) / 3.0,
    ];
    let want = if front {
        Orientation::Positive
    } else {
        Orientation::Negative
    };
    let mut h = 0.1 * (0.5 * len).sqrt();
    for _ in 0..24 {
        let q = [g[0] + dir[0] * h, g[1] + dir[1] * h, g[2] + dir[2] * h];
        let r = [g[0] - dir[0] * h, g[1] - dir[1] * h, g[2] - dir[2] * h];
        h *= 0.25;
        if orient3d(a, b, c, &q) != want || orient3d(a, b, c, &r) != want.flip() {
            continue;
        }
        let (pos, neg) = signs3(&q, &r, tri);
        let through = [
            orient3d(&q, &r, a, b),
            orient3d(&q, &r, b, c),
            orient3d(&q, &r, c, a),
        ];
        if (pos && neg) || through.contains(&Orientation::Zero) {
            continue;
        }
        let seg = BBox::from_points([&q, &r]);
        let clear = (all.meeting(&seg)).all(|u| u == t || !segment_may_touch(&q, &r, &all.tris[u]));
        if clear {
            return Some(q);
        }
    }
    None
}

/// Patches appearing with exactly one side in a shell (`face_uses` sorted by patch).
pub(super) fn one_sided(face_uses: &[super::FaceUse]) -> Vec<u32> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < face_uses.len() {
        let p = face_uses[i].patch;
        let mut j = i + 1;
        while j < face_uses.len() && face_uses[j].patch == p {
            j += 1;
        }
        if j == i + 1 {
            out.push(p);
        }
        i = j;
    }
    out
}

pub(super) fn patch_tris(patches: &[PatchIn], ids: impl IntoIterator<Item = u32>) -> Vec<Tri> {
    let ids: Vec<u32> = ids.into_iter().collect();
    let n = ids
        .iter()
        .filter_map(|&p| patches.get(p as usize))
        .map(|p| p.mesh.triangles.len())
        .sum();
    let mut out = Vec::with_capacity(n);
    for p in ids {
        let Some(patch) = patches.get(p as usize) else {
            continue;
        };
        let m = &patch.mesh;
        for t in &m.triangles {
            if let (Some(a), Some(b), Some(c)) = (
                m.vertices.get(t[0] as usize),
                m.vertices.get(t[1] as usize),
                m.vertices.get(t[2] as usize),
            ) {
                out.push([*a, *b, *c]);
            }
        }
    }
    out
}

pub(super) fn patches_bbox(patches: &[PatchIn]) -> BBox {
    patches
        .iter()
        .fold(BBox::empty(), |b, p| b.union(&p.mesh.bbox()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetra(v: [P3; 4]) -> Vec<Tri> {
        vec![
            [v[0], v[1], v[2]],
            [v[0], v[3], v[1]],
            [v[1], v[3], v[2]],
            [v[0], v[2], v[3]],
        ]
    }

    #[test]
    fn a_ray_through_a_vertex_is_retried_and_the_parity_stays_exact() {
        let q = [0.0, 0.0, 0.0];
        let bbox = BBox {
            min: [-1.0; 3],
            max: [1.0; 3],
        };
        let f0 = far_point(&q, &bbox, 0);
        // A vertex exactly on the first ray (halving is exact), the others behind the origin.
        let m = [f0[0] / 2.0, f0[1] / 2.0, f0[2] / 2.0];
        assert_eq!(orient3d(&q, &f0, &m, &[0.0, 0.0, 1.0]), Orientation::Zero);
        let t = tetra([m, [-1.0, -1.0, -1.0], [-1.0, 1.0, -1.0], [-1.0, 0.0, 1.0]]);
        assert!(matches!(crossing(&q, &f0, &t[0]), Cross::Degenerate));
        assert_eq!(parity(&q, &t, &bbox), Some(Loc::Inside));
        assert_eq!(parity(&[-2.0, 0.0, 0.0], &t, &bbox), Some(Loc::Outside));
        assert_eq!(parity(&m, &t, &bbox), Some(Loc::OnBoundary));
    }

    #[test]
    fn a_point_built_off_a_face_is_on_the_requested_side_and_clear_of_neighbours() {
        let t = tetra([
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ]);
        for (i, tri) in t.iter().enumerate() {
            for front in [true, false] {
                let q = near_point(&Indexed::new(&t), i, front).expect("a point");
                let want = if front {
                    Orientation::Positive
                } else {
                    Orientation::Negative
                };
                assert_eq!(orient3d(&tri[0], &tri[1], &tri[2], &q), want);
            }
        }
        // A triangle lying on top of another one leaves no room on that side.
        let mut twice = t.clone();
        twice.push(t[0]);
        assert_eq!(near_point(&Indexed::new(&twice), 0, true), None);
    }
}
