//! Where a well path meets the patches: exact classification of each path segment against each
//! support triangle near it (`orient3d`, and `orient2d` in a coordinate projection for points in
//! a triangle's plane), one crossing per patch and place, and the refusals (a path along a patch,
//! a crossing on a patch's border).

use super::curves::{CurveIndex, on_segment};
use super::pieces::lengths_along;
use super::{CurvePin, WellCrossing, WellError};
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
        let edges = patch.mesh.border_edges();
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

/// Whether `p` lies on the support of `patch` away from its border (inside a triangle, or on
/// an edge or vertex that is not on the border), decided exactly.
pub(crate) fn inside_patch(p: &P3, patch: &PatchIn) -> bool {
    let mut border = None;
    for (ti, ids) in patch.mesh.triangles.iter().enumerate() {
        let Some(t) = corners(patch, ids) else {
            continue;
        };
        let lo = [0, 1, 2].map(|k| t[0][k].min(t[1][k]).min(t[2][k]));
        let hi = [0, 1, 2].map(|k| t[0][k].max(t[1][k]).max(t[2][k]));
        if (0..3).any(|k| p[k] < lo[k] || p[k] > hi[k]) || projection(&t).is_none() {
            continue;
        }
        if orient3d(&t[0], &t[1], &t[2], p) != Orientation::Zero {
            continue;
        }
        let place = place_in_plane(p, &t);
        if place == Place::Outside {
            continue;
        }
        let f = feature(ti as u32, ids, place);
        return !border.get_or_insert_with(|| Border::of(patch)).holds(f);
    }
    false
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
    curves: &'a CurveIndex,
    along: Vec<f64>,
    borders: BTreeMap<u32, Border>,
    found: BTreeMap<(u32, Spot), Found>,
    /// Per path segment, the patch it lies on, if any.
    on: Vec<Option<u32>>,
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
    /// patch's border but on no curve (a border is made of curves, so that is a broken model).
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
        let found = make();
        let on_border = found.crossing.curve.is_none()
            && !matches!(f, Feature::Face(_))
            && self
                .borders
                .entry(pi)
                .or_insert_with(|| Border::of(patch))
                .holds(f);
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

    /// The model curve through `place` of the support triangle `t`: the curve segment that is
    /// its edge there, or the curve point that is its corner.
    fn curve_at(&self, t: &[P3; 3], place: Place) -> Option<CurvePin> {
        match place {
            Place::Edge(k) => self.curves.segment(&t[k], &t[(k + 1) % 3]).map(|s| s.0),
            Place::Corner(k) => self.curves.point(&t[k]),
            _ => None,
        }
    }

    fn border(&mut self, pi: u32) -> &Border {
        let patch = &self.patches[pi as usize];
        self.borders.entry(pi).or_insert_with(|| Border::of(patch))
    }

    /// Records station `j`, lying in the plane of triangle `ti` (corner ids `ids`, corners `t`)
    /// of patch `pi`, as a crossing when it lies on the triangle.
    fn station(
        &mut self,
        pi: u32,
        ti: u32,
        (ids, t): ([u32; 3], &[P3; 3]),
        j: usize,
    ) -> Result<(), WellError> {
        let s = self.stations[j];
        let place = place_in_plane(&s, t);
        if place == Place::Outside {
            return Ok(());
        }
        let along = self.along[j];
        let f = feature(ti, &ids, place);
        let segment = j.min(self.stations.len() - 2);
        let curve = self.curve_at(t, place);
        self.record(pi, Spot::Station(j), f, || Found {
            crossing: WellCrossing {
                patch: pi,
                point: s,
                along,
                curve,
            },
            segment,
            station: Some(j),
        })
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
        // The triangles the segment lies in the plane of and meets, per patch; then the others.
        let mut flat: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
        let mut across = Vec::new();
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
            if op == Orientation::Zero && oq == Orientation::Zero {
                if coplanar_meets(&p, &q, &t) {
                    flat.entry(pi).or_default().push(ti);
                }
                continue;
            }
            across.push((pi, ti, ids, t, op, oq));
        }
        for (pi, tris) in flat {
            self.in_plane(i, pi, &tris)?;
        }
        for (pi, ti, ids, t, op, oq) in across {
            if self.on[i] == Some(pi) {
                continue;
            }
            self.through(i, (pi, ti), (ids, &t), (op, oq))?;
        }
        Ok(())
    }

    /// Segment `i` in the plane of the triangles `tris` of patch `pi`, meeting each: it lies on
    /// the patch when they cover it whole; it touches the patch when they meet it at points only
    /// (its stations there are crossings); running along the patch for part of it, or meeting
    /// the patch's border (a curve) while on it, is refused.
    fn in_plane(&mut self, i: usize, pi: u32, tris: &[u32]) -> Result<(), WellError> {
        let (p, q) = (self.stations[i], self.stations[i + 1]);
        let patch = &self.patches[pi as usize];
        let tri = |ti: u32| {
            let ids = patch.mesh.triangles[ti as usize];
            (
                ids,
                corners(patch, &ids).expect("indexed triangles have corners"),
            )
        };
        let spans: Vec<(f64, f64)> = tris
            .iter()
            .map(|&ti| {
                let (ids, t) = tri(ti);
                span(&p, &q, &t, ids)
            })
            .collect();
        let coverage = coverage(&spans);
        if coverage == Coverage::Points {
            for &ti in tris {
                let (ids, t) = tri(ti);
                self.station(pi, ti, (ids, &t), i)?;
                self.station(pi, ti, (ids, &t), i + 1)?;
            }
            return Ok(());
        }
        let (surface, name) = (patch.surface.clone(), patch.name.clone());
        for &ti in tris {
            let (ids, t) = tri(ti);
            if let Some(at) = self.meets_border(pi, &p, &q, (ids, &t)) {
                return Err(self.fail(
                    format!(
                        "the well runs along surface `{surface}` (patch `{name}`) onto the patch's border (a curve, where surfaces meet or a fault ends); a path lying on a surface must leave it inside the patch"
                    ),
                    i,
                    at,
                ));
            }
        }
        if coverage == Coverage::Part {
            return Err(self.fail(
                format!(
                    "the well runs along surface `{surface}` (patch `{name}`) for part of a segment and leaves it between two stations; a path lying on a surface must have a station where it leaves it"
                ),
                i,
                p,
            ));
        }
        if let Some(other) = self.on[i].filter(|&o| o != pi) {
            let o = &self.patches[other as usize];
            return Err(self.fail(
                format!(
                    "the well runs along patches `{}` and `{name}` at once",
                    o.name
                ),
                i,
                p,
            ));
        }
        self.on[i] = Some(pi);
        Ok(())
    }

    /// A corner of a border edge of the triangle (corner ids `ids`, corners `t`) of patch `pi`
    /// that segment `pq`, in the triangle's plane, meets, if it meets one.
    fn meets_border(
        &mut self,
        pi: u32,
        p: &P3,
        q: &P3,
        (ids, t): ([u32; 3], &[P3; 3]),
    ) -> Option<P3> {
        let (k, _) = projection(t)?;
        let border = self.border(pi);
        (0..3).find_map(|e| {
            let (a, b) = (ids[e], ids[(e + 1) % 3]);
            let on = border.edges.contains(&(a.min(b), a.max(b)));
            let (u, v) = (t[e], t[(e + 1) % 3]);
            let meets = segments_meet(
                drop_axis(p, k),
                drop_axis(q, k),
                drop_axis(&u, k),
                drop_axis(&v, k),
            );
            (on && meets).then_some(u)
        })
    }

    /// Segment `i` against triangle `ti` of patch `pi` whose plane it is not in (`op`, `oq`: the
    /// sides of its plane its ends are on).
    fn through(
        &mut self,
        i: usize,
        (pi, ti): (u32, u32),
        (ids, t): ([u32; 3], &[P3; 3]),
        (op, oq): (Orientation, Orientation),
    ) -> Result<(), WellError> {
        let (p, q) = (self.stations[i], self.stations[i + 1]);
        if op == Orientation::Zero || oq == Orientation::Zero {
            let j = if op == Orientation::Zero { i } else { i + 1 };
            return self.station(pi, ti, (ids, t), j);
        }
        if op == oq {
            return Ok(());
        }
        let place = place_through(&p, &q, t);
        if place == Place::Outside {
            return Ok(());
        }
        let f = feature(ti, &ids, place);
        let (point, curve) = match place {
            Place::Corner(k) => (t[k], self.curves.point(&t[k])),
            Place::Edge(k) => match self.curves.segment(&t[k], &t[(k + 1) % 3]) {
                Some((pin, a, b)) => (on_segment(&p, &q, &a, &b), Some(pin)),
                None => (crossing_point(&p, &q, t, place), None),
            },
            _ => (crossing_point(&p, &q, t, place), None),
        };
        let s = (dist(&p, &point) / dist(&p, &q)).clamp(0.0, 1.0);
        let along = self.along[i] + s * (self.along[i + 1] - self.along[i]);
        self.record(pi, Spot::Segment(i, f), f, || Found {
            crossing: WellCrossing {
                patch: pi,
                point,
                along,
                curve,
            },
            segment: i,
            station: None,
        })
    }
}

/// How the triangles a segment lies in the plane of cover it.
#[derive(Debug, PartialEq)]
enum Coverage {
    /// At points only.
    Points,
    /// Along part of it.
    Part,
    /// From end to end.
    Whole,
}

/// Whether the spans (parameters along the segment, 0 to 1) cover it: their ends are computed
/// the same way from the same support edge or vertex by every triangle that shares it, so two
/// spans that meet there meet bit for bit, and which triangles and edges the segment meets is
/// decided exactly before. Only on a support with a T-junction (a corner on a neighbour's edge)
/// may two meeting spans differ by rounding; the gap is then refused as `Part`, never a path
/// accepted that leaves the surface.
fn coverage(spans: &[(f64, f64)]) -> Coverage {
    let mut open: Vec<(f64, f64)> = spans.iter().copied().filter(|(a, b)| a < b).collect();
    if open.is_empty() {
        return Coverage::Points;
    }
    open.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    if open[0].0 > 0.0 {
        return Coverage::Part;
    }
    let mut reach = 0.0f64;
    for (a, b) in open {
        if a > reach {
            return Coverage::Part;
        }
        reach = reach.max(b);
    }
    if reach >= 1.0 {
        Coverage::Whole
    } else {
        Coverage::Part
    }
}

/// The parameters (0 at `p`, 1 at `q`) of the part of segment `pq` inside triangle `t` (corner
/// ids `ids`), both in its plane: the ends of the segment inside it, its corners on the segment
/// and the points where the segment crosses its edges. Exact tests decide which; an edge's
/// parameter is computed from its corners in id order and a corner's from the corner alone, so
/// every triangle sharing them gets the same bits.
fn span(p: &P3, q: &P3, t: &[P3; 3], ids: [u32; 3]) -> (f64, f64) {
    let Some((k, _)) = projection(t) else {
        return (1.0, 0.0);
    };
    let (p2, q2) = (drop_axis(p, k), drop_axis(q, k));
    let d = sub(q, p);
    let dd = dot(&d, &d);
    let mut ts = Vec::with_capacity(4);
    if place_in_plane(p, t) != Place::Outside {
        ts.push(0.0);
    }
    if place_in_plane(q, t) != Place::Outside {
        ts.push(1.0);
    }
    for c in 0..3 {
        let v = t[c];
        let between = (0..3).all(|a| p[a].min(q[a]) <= v[a] && v[a] <= p[a].max(q[a]));
        if between && orient2d(&p2, &q2, &drop_axis(&v, k)) == Orientation::Zero {
            ts.push(dot(&sub(&v, p), &d) / dd);
        }
        let (a, b) = if ids[c] < ids[(c + 1) % 3] {
            (t[c], t[(c + 1) % 3])
        } else {
            (t[(c + 1) % 3], t[c])
        };
        let (a2, b2) = (drop_axis(&a, k), drop_axis(&b, k));
        let strict = |x: Orientation, y: Orientation| {
            x != Orientation::Zero && y != Orientation::Zero && x != y
        };
        if strict(orient2d(&p2, &q2, &a2), orient2d(&p2, &q2, &b2))
            && strict(orient2d(&a2, &b2, &p2), orient2d(&a2, &b2, &q2))
        {
            let e = sub(&b, &a);
            let n = cross(&d, &e);
            ts.push(dot(&cross(&sub(&a, p), &e), &n) / dot(&n, &n));
        }
    }
    let ts = ts.into_iter().map(|x| x.clamp(0.0, 1.0));
    ts.fold((1.0f64, 0.0f64), |(lo, hi), x| (lo.min(x), hi.max(x)))
}

/// Every crossing of the path `stations` with `patches`, in path order (at a station, then
/// inside the segment that starts there, by length along it), and per segment the patch it lies
/// on; two patches crossed at one point, and a crossing where the path lies on a patch, are
/// refused.
pub(super) fn crossings(
    stations: &[P3],
    patches: &[PatchIn],
    curves: &CurveIndex,
) -> Result<(Vec<Found>, Vec<Option<u32>>), WellError> {
    let along = lengths_along(stations);
    let tree = index(patches);
    let mut walk = Walk {
        stations,
        patches,
        curves,
        along,
        borders: BTreeMap::new(),
        found: BTreeMap::new(),
        on: vec![None; stations.len() - 1],
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
        if a.point == b.point && (a.curve.is_none() || b.curve.is_none()) {
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
    let on = walk.on;
    if let Some(f) = found.iter().find(|f| lies_on_at(&on, f).is_some()) {
        let (c, lying) = (&f.crossing, lies_on_at(&on, f).expect("found"));
        return Err(WellError {
            message: format!(
                "the well meets surface `{}` (patch `{}`) where it runs along patch `{}`; the crossing would have to be a node of their curve",
                patches[c.patch as usize].surface,
                patches[c.patch as usize].name,
                patches[lying as usize].name
            ),
            segment: Some(f.segment),
            at: Some(c.point),
        });
    }
    Ok((found, on))
}

/// The patch the path lies on at crossing `f` when the crossing is inside a segment lying on
/// a patch, or at a station between two segments lying on one.
fn lies_on_at(on: &[Option<u32>], f: &Found) -> Option<u32> {
    match f.station {
        None => on[f.segment],
        Some(j) if j > 0 && j < on.len() && on[j - 1] == on[j] => on[j],
        Some(_) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom::TriMesh;

    /// A flat square at z = 0 (x in 0..1) bent up along x = 1 into a slope reaching z = 1 at
    /// x = 2.
    fn bent() -> Vec<PatchIn> {
        let v = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.0, 1.0],
            [2.0, 1.0, 1.0],
        ];
        let t = vec![[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]];
        vec![PatchIn {
            name: "s#1".into(),
            surface: "s".into(),
            mesh: TriMesh::new(v, t),
            chart_of: None,
        }]
    }

    #[test]
    fn spans_that_meet_or_overlap_cover_a_segment_and_a_gap_or_a_short_end_does_not() {
        assert_eq!(coverage(&[(0.0, 0.5), (0.5, 1.0)]), Coverage::Whole);
        assert_eq!(
            coverage(&[(0.3, 1.0), (0.0, 0.6), (0.2, 0.2)]),
            Coverage::Whole
        );
        assert_eq!(coverage(&[(0.0, 0.5), (0.6, 1.0)]), Coverage::Part);
        assert_eq!(coverage(&[(0.0, 0.9)]), Coverage::Part);
        assert_eq!(coverage(&[(0.1, 1.0)]), Coverage::Part);
        assert_eq!(coverage(&[(0.0, 0.0), (1.0, 1.0)]), Coverage::Points);
    }

    #[test]
    fn a_path_lying_on_the_flat_part_of_a_bent_patch_is_a_run_and_one_going_on_past_the_bend_is_refused()
     {
        let patches = bent();
        let (found, on) = crossings(
            &[[0.2, 0.5, 0.0], [0.9, 0.5, 0.0]],
            &patches,
            &CurveIndex::default(),
        )
        .expect("a run");
        assert!(found.is_empty());
        assert_eq!(on, [Some(0)]);
        let e = crossings(
            &[[0.2, 0.5, 0.0], [1.5, 0.5, 0.0]],
            &patches,
            &CurveIndex::default(),
        )
        .err()
        .expect("it leaves the surface at the bend, between stations");
        assert!(e.message.contains("for part of a segment"), "{e}");
        // With a station at the bend it lies on the flat part, then leaves the surface there.
        let (found, on) = crossings(
            &[[0.2, 0.5, 0.0], [1.0, 0.5, 0.0], [1.5, 0.5, 0.0]],
            &patches,
            &CurveIndex::default(),
        )
        .expect("a run, then off");
        assert_eq!(on, [Some(0), None]);
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].crossing.point, [1.0, 0.5, 0.0]);
        // Up the slope and on along the flat part, the other way round.
        let (_, on) = crossings(
            &[[1.5, 0.5, 0.5], [1.0, 0.5, 0.0], [0.3, 0.5, 0.0]],
            &patches,
            &CurveIndex::default(),
        )
        .expect("two runs");
        assert_eq!(on, [Some(0), Some(0)]);
    }
}
