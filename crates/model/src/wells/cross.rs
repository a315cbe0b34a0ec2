//! Where a well path meets the patches: exact classification of each path segment against each
//! support triangle near it (`orient3d`, and `orient2d` in a coordinate projection for points in
//! a triangle's plane), one crossing per patch and place, and the refusals (a path along a patch,
//! a crossing on a patch's border).

use super::pieces::lengths_along;
use super::{WellCrossing, WellError};
use crate::regions::PatchIn;
use geom::predicates::{cross, dist, dot, sub};
use geom::{Orientation, orient2d, orient3d};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};
use std::collections::{BTreeMap, BTreeSet};

type P3 = [f64; 3];

/// A crossing with where on the path it is: inside segment `segment`, or at station `station`.
pub(super) struct Found {
    pub crossing: WellCrossing,
    pub segment: usize,
    pub station: Option<usize>,
}

/// Where a point or a segment meets a triangle: inside, on edge `k` (corners `k`, `k+1`), or at
/// corner `k`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Place {
    Outside,
    Face,
    Edge(usize),
    Corner(usize),
}

/// The support feature a crossing goes through, to keep one crossing per place.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Feature {
    Face(u32),
    Edge(u32, u32),
    Vertex(u32),
}

/// Where on the path: inside a segment through a feature, or at a station.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Spot {
    Segment(usize, Feature),
    Station(usize),
}

fn drop_axis(p: &P3, k: usize) -> [f64; 2] {
    match k {
        0 => [p[1], p[2]],
        1 => [p[0], p[2]],
        _ => [p[0], p[1]],
    }
}

/// The place from the signs of the three edge tests (edge k: corners k, k+1): all one sign is
/// the face, a zero marks the edge, two zeros the corner they share.
fn place_of(signs: [Orientation; 3]) -> Place {
    let pos = signs.contains(&Orientation::Positive);
    let neg = signs.contains(&Orientation::Negative);
    if pos && neg {
        return Place::Outside;
    }
    let zeros: Vec<usize> = (0..3).filter(|&k| signs[k] == Orientation::Zero).collect();
    match zeros.as_slice() {
        [] => Place::Face,
        [k] => Place::Edge(*k),
        [0, 1] => Place::Corner(1),
        [1, 2] => Place::Corner(2),
        [0, 2] => Place::Corner(0),
        _ => Place::Outside,
    }
}

/// A projection axis in which the triangle does not degenerate, with its orientation there.
fn projection(t: &[P3; 3]) -> Option<(usize, Orientation)> {
    (0..3).find_map(|k| {
        let s = orient2d(
            &drop_axis(&t[0], k),
            &drop_axis(&t[1], k),
            &drop_axis(&t[2], k),
        );
        (s != Orientation::Zero).then_some((k, s))
    })
}

/// Where `q`, coplanar with `t`, lies in the closed triangle.
fn place_in_plane(q: &P3, t: &[P3; 3]) -> Place {
    let Some((k, s)) = projection(t) else {
        return Place::Outside;
    };
    let [a, b, c] = t.map(|p| drop_axis(&p, k));
    let q = drop_axis(q, k);
    let mut signs = [
        orient2d(&a, &b, &q),
        orient2d(&b, &c, &q),
        orient2d(&c, &a, &q),
    ];
    if s == Orientation::Negative {
        signs = signs.map(Orientation::flip);
    }
    if signs.contains(&Orientation::Negative) {
        return Place::Outside;
    }
    place_of(signs)
}

/// Whether the closed 2D segments `ab` and `cd` meet.
fn segments_meet(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let (o1, o2) = (orient2d(&a, &b, &c), orient2d(&a, &b, &d));
    let (o3, o4) = (orient2d(&c, &d, &a), orient2d(&c, &d, &b));
    if o1 == Orientation::Zero && o2 == Orientation::Zero {
        let overlap = |k: usize| {
            let (lo, hi) = (a[k].min(b[k]), a[k].max(b[k]));
            c[k].max(d[k]) >= lo && c[k].min(d[k]) <= hi
        };
        return overlap(0) && overlap(1);
    }
    let one_side = |x: Orientation, y: Orientation| x == y && x != Orientation::Zero;
    !(one_side(o1, o2) || one_side(o3, o4))
}

/// Whether segment `pq`, coplanar with `t`, meets the closed triangle.
fn coplanar_meets(p: &P3, q: &P3, t: &[P3; 3]) -> bool {
    if place_in_plane(p, t) != Place::Outside || place_in_plane(q, t) != Place::Outside {
        return true;
    }
    let Some((k, _)) = projection(t) else {
        return false;
    };
    let [a, b, c] = t.map(|x| drop_axis(&x, k));
    let (p, q) = (drop_axis(p, k), drop_axis(q, k));
    [(a, b), (b, c), (c, a)]
        .iter()
        .any(|&(u, v)| segments_meet(p, q, u, v))
}

/// Where segment `pq` meets triangle `t` when `p` and `q` are strictly on either side of its
/// plane.
fn place_through(p: &P3, q: &P3, t: &[P3; 3]) -> Place {
    place_of([
        orient3d(p, q, &t[0], &t[1]),
        orient3d(p, q, &t[1], &t[2]),
        orient3d(p, q, &t[2], &t[0]),
    ])
}

/// Where segment `pq` crosses triangle `t` at `place` (not `Corner`): the combination of the
/// triangle's corners weighted by the volumes `pq` spans with the opposite edges, so the point is
/// on the triangle up to rounding (on a plane of constant z its z is exact), and on the edge when
/// `place` is an edge (the opposite corner's weight is exactly zero).
fn crossing_point(p: &P3, q: &P3, t: &[P3; 3], place: Place) -> P3 {
    let d = sub(q, p);
    let det = |u: &P3, v: &P3| dot(&d, &cross(&sub(u, p), &sub(v, p)));
    // Weight of corner k: the volume with the edge opposite it.
    let mut w = [det(&t[1], &t[2]), det(&t[2], &t[0]), det(&t[0], &t[1])];
    if let Place::Edge(k) = place {
        w[(k + 2) % 3] = 0.0;
    }
    let sum = w[0] + w[1] + w[2];
    if sum == 0.0 || !sum.is_finite() {
        return [0, 1, 2].map(|k| (t[0][k] + t[1][k] + t[2][k]) / 3.0);
    }
    let w = w.map(|x| x / sum);
    [0, 1, 2].map(|k| w[0] * t[0][k] + w[1] * t[1][k] + w[2] * t[2][k])
}

/// The border edges (used by one triangle) and border vertices of a patch.
struct Border {
    edges: BTreeSet<(u32, u32)>,
    vertices: BTreeSet<u32>,
}

impl Border {
    fn of(patch: &PatchIn) -> Border {
        let mut uses: BTreeMap<(u32, u32), u32> = BTreeMap::new();
        for t in &patch.mesh.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *uses.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        let edges: BTreeSet<(u32, u32)> = uses
            .into_iter()
            .filter(|&(_, n)| n == 1)
            .map(|(e, _)| e)
            .collect();
        let vertices = edges.iter().flat_map(|&(a, b)| [a, b]).collect();
        Border { edges, vertices }
    }

    fn holds(&self, f: Feature) -> bool {
        match f {
            Feature::Face(_) => false,
            Feature::Edge(a, b) => self.edges.contains(&(a, b)),
            Feature::Vertex(v) => self.vertices.contains(&v),
        }
    }
}

type Entry = GeomWithData<Rectangle<P3>, (u32, u32)>;

/// Every support triangle of every patch in an R-tree of bounding boxes.
fn index(patches: &[PatchIn]) -> RTree<Entry> {
    let mut entries = Vec::new();
    for (pi, p) in patches.iter().enumerate() {
        for (ti, t) in p.mesh.triangles.iter().enumerate() {
            let Some(c) = corners(p, t) else { continue };
            let lo = [0, 1, 2].map(|k| c[0][k].min(c[1][k]).min(c[2][k]));
            let hi = [0, 1, 2].map(|k| c[0][k].max(c[1][k]).max(c[2][k]));
            entries.push(GeomWithData::new(
                Rectangle::from_corners(lo, hi),
                (pi as u32, ti as u32),
            ));
        }
    }
    RTree::bulk_load(entries)
}

fn corners(p: &PatchIn, t: &[u32; 3]) -> Option<[P3; 3]> {
    let v = &p.mesh.vertices;
    Some([
        *v.get(t[0] as usize)?,
        *v.get(t[1] as usize)?,
        *v.get(t[2] as usize)?,
    ])
}

/// The feature of triangle `ti` (corner ids `t`) at `place`.
fn feature(ti: u32, t: &[u32; 3], place: Place) -> Feature {
    match place {
        Place::Edge(k) => {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            Feature::Edge(a.min(b), a.max(b))
        }
        Place::Corner(k) => Feature::Vertex(t[k]),
        _ => Feature::Face(ti),
    }
}

/// What one path segment meets: the crossings and stations on patches, in a deterministic order.
struct Walk<'a> {
    stations: &'a [P3],
    patches: &'a [PatchIn],
    along: Vec<f64>,
    borders: BTreeMap<u32, Border>,
    found: BTreeMap<(u32, Spot), Found>,
}

impl Walk<'_> {
    fn fail(&self, message: String, segment: usize, at: P3) -> WellError {
        WellError {
            message,
            segment: Some(segment),
            at: Some(at),
        }
    }

    /// Records a crossing of patch `pi` at `spot` unless it is already known; refuses one on the
    /// patch's border.
    fn record(
        &mut self,
        pi: u32,
        spot: Spot,
        f: Feature,
        make: impl FnOnce() -> Found,
    ) -> Result<(), WellError> {
        if self.found.contains_key(&(pi, spot)) {
            return Ok(());
        }
        let patch = &self.patches[pi as usize];
        let on_border = !matches!(f, Feature::Face(_))
            && self
                .borders
                .entry(pi)
                .or_insert_with(|| Border::of(patch))
                .holds(f);
        let found = make();
        if on_border {
            return Err(self.fail(
                format!(
                    "the well meets surface `{}` on a border of its patch `{}` (a curve, where surfaces meet or a fault ends); the crossing would have to be a node of that curve",
                    patch.surface, patch.name
                ),
                found.segment,
                found.crossing.point,
            ));
        }
        self.found.insert((pi, spot), found);
        Ok(())
    }

    fn segment(&mut self, i: usize, tree: &RTree<Entry>) -> Result<(), WellError> {
        let (p, q) = (self.stations[i], self.stations[i + 1]);
        let lo = [0, 1, 2].map(|k| p[k].min(q[k]));
        let hi = [0, 1, 2].map(|k| p[k].max(q[k]));
        let mut near: Vec<(u32, u32)> = tree
            .locate_in_envelope_intersecting(AABB::from_corners(lo, hi))
            .map(|e| e.data)
            .collect();
        near.sort_unstable();
        for (pi, ti) in near {
            let patch = &self.patches[pi as usize];
            let ids = patch.mesh.triangles[ti as usize];
            let Some(t) = corners(patch, &ids) else {
                continue;
            };
            if projection(&t).is_none() {
                continue;
            }
            let (op, oq) = (
                orient3d(&t[0], &t[1], &t[2], &p),
                orient3d(&t[0], &t[1], &t[2], &q),
            );
            let zero = Orientation::Zero;
            if op == zero && oq == zero {
                if coplanar_meets(&p, &q, &t) {
                    return Err(self.fail(
                        format!(
                            "the well runs along surface `{}` (patch `{}`): a segment of its path lies in the surface",
                            patch.surface, patch.name
                        ),
                        i,
                        p,
                    ));
                }
                continue;
            }
            if op == zero || oq == zero {
                let (j, s) = if op == zero { (i, p) } else { (i + 1, q) };
                let place = place_in_plane(&s, &t);
                if place == Place::Outside {
                    continue;
                }
                let along = self.along[j];
                let f = feature(ti, &ids, place);
                self.record(pi, Spot::Station(j), f, || Found {
                    crossing: WellCrossing {
                        patch: pi,
                        point: s,
                        along,
                    },
                    segment: j.min(self.stations.len() - 2),
                    station: Some(j),
                })?;
                continue;
            }
            if op == oq {
                continue;
            }
            let place = place_through(&p, &q, &t);
            if place == Place::Outside {
                continue;
            }
            let f = feature(ti, &ids, place);
            let point = match place {
                Place::Corner(k) => t[k],
                _ => crossing_point(&p, &q, &t, place),
            };
            let s = (dist(&p, &point) / dist(&p, &q)).clamp(0.0, 1.0);
            let along = self.along[i] + s * (self.along[i + 1] - self.along[i]);
            self.record(pi, Spot::Segment(i, f), f, || Found {
                crossing: WellCrossing {
                    patch: pi,
                    point,
                    along,
                },
                segment: i,
                station: None,
            })?;
        }
        Ok(())
    }
}

/// Every crossing of the path `stations` with `patches`, in path order (at a station, then
/// inside the segment that starts there, by length along it); two patches crossed at one point
/// are refused.
pub(super) fn crossings(stations: &[P3], patches: &[PatchIn]) -> Result<Vec<Found>, WellError> {
    let along = lengths_along(stations);
    let tree = index(patches);
    let mut walk = Walk {
        stations,
        patches,
        along,
        borders: BTreeMap::new(),
        found: BTreeMap::new(),
    };
    for i in 0..stations.len() - 1 {
        walk.segment(i, &tree)?;
    }
    let mut found: Vec<Found> = walk.found.into_values().collect();
    found.sort_by(|a, b| {
        let at = |f: &Found| (f.station.unwrap_or(f.segment), f.station.is_none());
        at(a)
            .cmp(&at(b))
            .then(a.crossing.along.total_cmp(&b.crossing.along))
            .then(a.crossing.patch.cmp(&b.crossing.patch))
    });
    for w in found.windows(2) {
        let (a, b) = (&w[0].crossing, &w[1].crossing);
        if a.point == b.point {
            let (pa, pb) = (&patches[a.patch as usize], &patches[b.patch as usize]);
            return Err(WellError {
                message: format!(
                    "the well meets patches `{}` and `{}` at one point (where surfaces meet); the crossing would have to be a node of their curve",
                    pa.name, pb.name
                ),
                segment: Some(w[1].segment),
                at: Some(b.point),
            });
        }
    }
    Ok(found)
}
