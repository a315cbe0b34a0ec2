//! The constrained triangulation of one split triangle: its boundary polygon (the corners and
//! the curve points on its edges, in the triangle's own orientation), then every curve point
//! inside it, then every curve piece inside it as a constraint edge. This one procedure covers
//! every shape the curves can draw in a face: chains from border to border, chains ending
//! inside (a fault tip), closed loops and whole curves inside one face, branches and
//! T-junctions, crossings (already made vertices by the caller).
//!
//! What it decides, each time with an exact `orient2d` on the projected coordinates (the
//! projection and its sign are chosen exactly by the caller for the original triangle): which
//! triangle holds a new point (or which edge it lies on), which triangles a constraint crosses,
//! and the ears of the two holes a constraint leaves. It refuses (as a message for the caller's
//! error) what would need moving a point: a curve point outside its face or on its border in the
//! projection, two curve points at one projected place, a constraint through a point it does not
//! name, two constraints crossing at no shared point. Nothing here recurses.

use super::super::polygon::ear_clip;
use geom::{Orientation, orient2d};
use std::collections::{BTreeMap, BTreeSet};

/// A triangulation under construction: triangles (oriented as `sign` in the projection), the
/// live ones flagged, and the owner of each directed edge.
pub(super) struct Ct<'a> {
    tris: Vec<[u32; 3]>,
    alive: Vec<bool>,
    owner: BTreeMap<(u32, u32), usize>,
    locked: BTreeSet<[u32; 2]>,
    pt: &'a dyn Fn(u32) -> [f64; 2],
    sign: Orientation,
    last: usize,
}

/// Why a triangulation step failed, and the vertex it is about.
pub(super) type Refusal = (&'static str, u32);

impl<'a> Ct<'a> {
    /// The triangulation of the polygon `boundary` (simple, oriented as `sign` in `pt`).
    pub(super) fn new(
        boundary: &[u32],
        pt: &'a dyn Fn(u32) -> [f64; 2],
        sign: Orientation,
    ) -> Result<Ct<'a>, Refusal> {
        let first = boundary.first().copied().unwrap_or(0);
        let tris =
            ear_clip(boundary, pt, sign).ok_or(("the face could not be triangulated", first))?;
        let mut ct = Ct {
            tris: Vec::new(),
            alive: Vec::new(),
            owner: BTreeMap::new(),
            locked: BTreeSet::new(),
            pt,
            sign,
            last: 0,
        };
        for t in tris {
            ct.add(t);
        }
        Ok(ct)
    }

    fn add(&mut self, t: [u32; 3]) -> usize {
        let i = self.tris.len();
        self.tris.push(t);
        self.alive.push(true);
        for k in 0..3 {
            self.owner.insert((t[k], t[(k + 1) % 3]), i);
        }
        self.last = i;
        i
    }

    fn kill(&mut self, i: usize) {
        let t = self.tris[i];
        self.alive[i] = false;
        for k in 0..3 {
            if self.owner.get(&(t[k], t[(k + 1) % 3])) == Some(&i) {
                self.owner.remove(&(t[k], t[(k + 1) % 3]));
            }
        }
    }

    fn orient(&self, a: u32, b: u32, p: [f64; 2]) -> Orientation {
        orient2d(&(self.pt)(a), &(self.pt)(b), &p)
    }

    /// Signs of `p` against the three edges of triangle `i` (edge k runs from corner k).
    fn signs(&self, i: usize, p: [f64; 2]) -> [Orientation; 3] {
        let t = self.tris[i];
        [0, 1, 2].map(|k| self.orient(t[k], t[(k + 1) % 3], p))
    }

    /// The live triangle whose closed interior holds `p`: a walk from the last triangle made,
    /// crossing an edge that has `p` strictly beyond it, and a full scan if the walk runs long.
    fn locate(&self, p: [f64; 2]) -> Option<usize> {
        let outside = self.sign.flip();
        let mut i = self.last;
        if self.alive.get(i) == Some(&true) {
            for _ in 0..self.tris.len() + 3 {
                let s = self.signs(i, p);
                if s.iter().all(|&o| o != outside) {
                    return Some(i);
                }
                let t = self.tris[i];
                let next = (0..3)
                    .filter(|&k| s[k] == outside)
                    .find_map(|k| self.owner.get(&(t[(k + 1) % 3], t[k])).copied());
                match next {
                    Some(j) => i = j,
                    None => break,
                }
            }
        }
        (0..self.tris.len())
            .find(|&i| self.alive[i] && self.signs(i, p).iter().all(|&o| o != outside))
    }

    /// Insert vertex `v` strictly inside the polygon.
    pub(super) fn insert_point(&mut self, v: u32) -> Result<(), Refusal> {
        let p = (self.pt)(v);
        let i = self
            .locate(p)
            .ok_or(("a curve point lies outside its face in the projection", v))?;
        let s = self.signs(i, p);
        let t = self.tris[i];
        let zeros: Vec<usize> = (0..3).filter(|&k| s[k] == Orientation::Zero).collect();
        match zeros.as_slice() {
            [] => {
                self.kill(i);
                for k in 0..3 {
                    self.add([t[k], t[(k + 1) % 3], v]);
                }
            }
            [k] => {
                let (a, b, c) = (t[*k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let Some(&j) = self.owner.get(&(b, a)) else {
                    return Err((
                        "a curve point inside a face lies on its border in the projection",
                        v,
                    ));
                };
                if self.locked.contains(&[a.min(b), a.max(b)]) {
                    return Err(("a curve point lies on a curve it is not a point of", v));
                }
                let u = self.tris[j];
                let Some(d) = (0..3).find(|&m| u[m] != a && u[m] != b).map(|m| u[m]) else {
                    return Err(("the face could not be triangulated", v));
                };
                self.kill(i);
                self.kill(j);
                self.add([a, v, c]);
                self.add([v, b, c]);
                self.add([b, v, d]);
                self.add([v, a, d]);
            }
            _ => return Err(("two curve points are at one place in this face", v)),
        }
        Ok(())
    }

    /// Make `ab` an edge, kept by later steps.
    pub(super) fn insert_segment(&mut self, a: u32, b: u32) -> Result<(), Refusal> {
        if a == b {
            return Ok(());
        }
        self.locked.insert([a.min(b), a.max(b)]);
        if self.owner.contains_key(&(a, b)) || self.owner.contains_key(&(b, a)) {
            return Ok(());
        }
        let (pa, pb) = ((self.pt)(a), (self.pt)(b));
        let (left, right) = (self.sign, self.sign.flip());
        let side = |w: u32| orient2d(&pa, &pb, &(self.pt)(w));
        // The triangle at `a` that `ab` leaves through: b strictly inside its corner at a.
        let start = self
            .owner
            .range((a, 0)..=(a, u32::MAX))
            .map(|(_, &i)| i)
            .find_map(|i| {
                let t = self.tris[i];
                let k = (0..3).find(|&k| t[k] == a)?;
                let (x, y) = (t[(k + 1) % 3], t[(k + 2) % 3]);
                (side(x) == right && side(y) == left).then_some((i, x, y))
            });
        let Some((i0, mut x, mut y)) = start else {
            return Err(("a curve passes through a point it does not name", a));
        };
        let mut removed = vec![i0];
        let (mut rchain, mut lchain) = (vec![x], vec![y]);
        loop {
            if self.locked.contains(&[x.min(y), x.max(y)]) {
                return Err(("two curves cross here without a shared point", x));
            }
            let Some(&j) = self.owner.get(&(y, x)) else {
                return Err(("a curve leaves its face in the projection", x));
            };
            let u = self.tris[j];
            let Some(z) = (0..3).find(|&m| u[m] != x && u[m] != y).map(|m| u[m]) else {
                return Err(("the face could not be triangulated", x));
            };
            removed.push(j);
            if z == b {
                break;
            }
            match side(z) {
                o if o == left => {
                    lchain.push(z);
                    y = z;
                }
                o if o == right => {
                    rchain.push(z);
                    x = z;
                }
                _ => return Err(("a curve passes through a point it does not name", z)),
            }
        }
        for &i in &removed {
            self.kill(i);
        }
        // The hole left of a->b is a, b, then the left chain back; the right one b, a, then
        // the right chain forward.
        let mut lpoly = vec![a, b];
        lpoly.extend(lchain.iter().rev());
        let mut rpoly = vec![b, a];
        rpoly.extend(rchain.iter());
        for poly in [lpoly, rpoly] {
            let tris = ear_clip(&poly, self.pt, self.sign)
                .ok_or(("a piece could not be triangulated", poly[0]))?;
            for t in tris {
                self.add(t);
            }
        }
        Ok(())
    }

    /// The live triangles, in creation order, and the constraint edges.
    pub(super) fn finish(self) -> (Vec<[u32; 3]>, Vec<[u32; 2]>) {
        let tris = self
            .tris
            .iter()
            .zip(&self.alive)
            .filter_map(|(t, &a)| a.then_some(*t))
            .collect();
        (tris, self.locked.into_iter().collect())
    }
}

/// The triangles of a zero-area triangle whose edges carry curve points: a fan over its
/// boundary cycle (all zero-area, as the parent was), so that its neighbours stay conforming.
/// `None` when the cycle repeats a vertex.
pub(super) fn fan(boundary: &[u32]) -> Option<Vec<[u32; 3]>> {
    let mut sorted = boundary.to_vec();
    sorted.sort_unstable();
    if boundary.len() < 3 || sorted.windows(2).any(|w| w[0] == w[1]) {
        return None;
    }
    Some(
        (1..boundary.len() - 1)
            .map(|i| [boundary[0], boundary[i], boundary[i + 1]])
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn positive(pts: &[[f64; 2]], tris: &[[u32; 3]]) -> bool {
        tris.iter().all(|t| {
            orient2d(
                &pts[t[0] as usize],
                &pts[t[1] as usize],
                &pts[t[2] as usize],
            ) == Orientation::Positive
        })
    }

    #[test]
    fn a_closed_loop_inside_a_triangle_becomes_edges_of_positive_triangles() {
        let pts: Vec<[f64; 2]> = vec![
            [0.0, 0.0],
            [10.0, 0.0],
            [0.0, 10.0],
            [2.0, 2.0],
            [4.0, 2.0],
            [3.0, 4.0],
        ];
        let pt = |v: u32| pts[v as usize];
        let mut ct = Ct::new(&[0, 1, 2], &pt, Orientation::Positive).expect("triangle");
        for v in 3..6 {
            ct.insert_point(v).expect("inside");
        }
        for s in [[3, 4], [4, 5], [5, 3]] {
            ct.insert_segment(s[0], s[1]).expect("constraint");
        }
        let (tris, locked) = ct.finish();
        assert_eq!(tris.len(), 7, "3 + 2 * 3 - 2 triangles");
        assert!(positive(&pts, &tris));
        for s in [[3, 4], [4, 5], [3, 5]] {
            assert!(locked.contains(&s));
            assert!(
                tris.iter().any(|t| t.contains(&s[0]) && t.contains(&s[1])),
                "{s:?} is an edge"
            );
        }
    }

    #[test]
    fn a_constraint_through_an_unnamed_point_is_refused() {
        let pts: Vec<[f64; 2]> = vec![
            [0.0, 0.0],
            [10.0, 0.0],
            [0.0, 10.0],
            [1.0, 1.0],
            [2.0, 2.0],
            [3.0, 3.0],
        ];
        let pt = |v: u32| pts[v as usize];
        let mut ct = Ct::new(&[0, 1, 2], &pt, Orientation::Positive).expect("triangle");
        for v in [3, 5, 4] {
            ct.insert_point(v).expect("inside");
        }
        let e = ct.insert_segment(3, 5).expect_err("4 lies on 3-5");
        assert!(e.0.contains("through a point"), "{e:?}");
    }

    #[test]
    fn crossing_constraints_without_a_shared_point_are_refused() {
        let pts: Vec<[f64; 2]> = vec![
            [0.0, 0.0],
            [10.0, 0.0],
            [0.0, 10.0],
            [1.0, 1.0],
            [4.0, 4.0],
            [1.0, 4.0],
            [4.0, 1.0],
        ];
        let pt = |v: u32| pts[v as usize];
        let mut ct = Ct::new(&[0, 1, 2], &pt, Orientation::Positive).expect("triangle");
        for v in 3..7 {
            ct.insert_point(v).expect("inside");
        }
        ct.insert_segment(3, 4).expect("first");
        let e = ct.insert_segment(5, 6).expect_err("crosses the first");
        assert!(e.0.contains("cross"), "{e:?}");
    }

    #[test]
    fn a_clockwise_triangle_is_split_keeping_its_orientation() {
        let pts: Vec<[f64; 2]> = vec![[0.0, 0.0], [0.0, 10.0], [10.0, 0.0], [3.0, 3.0]];
        let pt = |v: u32| pts[v as usize];
        let mut ct = Ct::new(&[0, 1, 2], &pt, Orientation::Negative).expect("triangle");
        ct.insert_point(3).expect("inside");
        ct.insert_segment(0, 3).expect("an edge already");
        let (tris, _) = ct.finish();
        assert_eq!(tris.len(), 3);
        assert!(tris.iter().all(|t| orient2d(
            &pts[t[0] as usize],
            &pts[t[1] as usize],
            &pts[t[2] as usize]
        ) == Orientation::Negative));
    }
}
