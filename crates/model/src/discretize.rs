//! Stage `discretize`: subdivides one model curve (a polyline between topological vertices) into
//! the 1D finite-element nodes that every patch bounded by the curve will share, bit for bit.
//!
//! Decisions and why:
//! - The end nodes are the curve's end vertices, copied (never recomputed), so the curves meeting
//!   at a topological vertex agree on it exactly.
//! - Interior nodes lie on the polyline, placed by arc length; a node is never moved off the curve.
//! - `Count(n)` gives n equal segments. `Size { size, ratio, grading }` gives segments that start at
//!   `size` and grow by `ratio` per segment from the curve's start (`Geometric`) or from both ends
//!   towards the middle (`Bump`); the segment count is the nearest integer that fits and the first
//!   length is then rescaled so the segments add up to the curve length exactly.
//! - A curve's direction is its canonical direction in the model, so "from the start" is stable.
//! - Under a size rule no segment cuts across a bend of the curve sharper than
//!   [`MAX_CUT_TURN_DEG`]: the nodes follow the curve round a coarse body's shoulder whatever
//!   the size, as the surface meshes on both sides need (a segment is halved, or split at the
//!   vertex that strays most, so the pieces stay even). A count is the recipe's word and kept.
//! - Pins (where wells cross the curve) are nodes bit for bit: each takes the place of the
//!   nearest interior node when that is within a third of the segment holding it, else it is
//!   inserted (a `Count` then gets one segment more), so every patch bounded by the curve, and
//!   every region meeting it, has the crossing as a node.

use geom::predicates::dist;
use serde::{Deserialize, Serialize};

/// How the recipe asks one curve to be subdivided.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Subdivision {
    /// This many equal segments (at least 1).
    Count(u32),
    /// Target first segment `size`, growing by `ratio` (1.0 = uniform).
    Size {
        size: f64,
        ratio: f64,
        grading: Grading,
    },
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum Grading {
    /// Sizes grow from the curve's start to its end.
    Geometric,
    /// Sizes grow from both ends towards the middle (symmetric).
    Bump,
}

/// Why a curve cannot be subdivided: the curve, the rule or the size field is unusable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DiscretizeError {
    #[error("a curve needs at least 2 points, got {0}")]
    TooFewPoints(usize),
    #[error("the curve has zero or non-finite length ({0})")]
    Length(f64),
    #[error("the size field is {size} on the curve, at arc length {arc}")]
    SizeField { size: f64, arc: f64 },
    #[error("more than {MAX_SEGMENTS} segments: the size near a feature is too small")]
    FieldTooFine,
    #[error("a curve needs a count of at least 1")]
    ZeroCount,
    #[error("size must be positive and finite, got {0}")]
    Size(f64),
    #[error("ratio must be positive and finite, got {0}")]
    Ratio(f64),
    #[error(
        "size {size} would give {n} segments on a curve of length {length}: more than {MAX_SEGMENTS}"
    )]
    TooManySegments { size: f64, n: f64, length: f64 },
    #[error("a point to keep, ({}, {}, {}), names segment {segment}, which the curve does not have", point[0], point[1], point[2])]
    Pin { segment: u32, point: [f64; 3] },
}

/// A size field over space: the element size wanted at a point.
pub type SizeAt<'a> = &'a dyn Fn(&[f64; 3]) -> f64;

/// The most segments one curve may get: a guard against a size that is tiny by mistake.
pub const MAX_SEGMENTS: usize = 10_000_000;

/// Subdivides `polyline` (at least 2 points; closed curves repeat the first point at the end).
/// Under a `Size` rule a segment is then split at polyline vertices while one lies farther from
/// it than half its `clearance` (per point of `polyline`; empty: no bound), and while it cuts
/// across a bend of the curve, see `follow_bends`; a `Count` is kept exactly as given.
pub fn discretize(
    polyline: &[[f64; 3]],
    rule: &Subdivision,
    clearance: &[f64],
) -> Result<Vec<[f64; 3]>, DiscretizeError> {
    discretize_within(polyline, rule, clearance, None)
}

/// As [`discretize`], and where `size_at` (a size field over space) asks for shorter segments
/// than a uniform `Size` rule, segments follow it: the curve gets the whole number of segments
/// nearest to the integral of `1 / min(size, size_at)` along it, spread so that each holds an
/// equal share of that integral. Graded sizes (`ratio` other than 1) and counts are kept as
/// written.
pub fn discretize_within(
    polyline: &[[f64; 3]],
    rule: &Subdivision,
    clearance: &[f64],
    size_at: Option<SizeAt<'_>>,
) -> Result<Vec<[f64; 3]>, DiscretizeError> {
    discretize_pinned(polyline, rule, clearance, size_at, &[])
}

/// A point the curve's nodes must include bit for bit (where a well crosses the curve): on
/// polyline segment `segment` (from its point `segment` to the next, ends included).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pin {
    pub segment: u32,
    pub point: [f64; 3],
}

/// As [`discretize_within`], with every pin a node: a pin takes the place of the interior node
/// nearest it when that node is within a third of the segment holding the pin (so no segment
/// gets much shorter than the rule's), and is inserted between the two otherwise. A pin at a
/// curve end, or given twice, is one node; pins are placed in order of arc length.
pub fn discretize_pinned(
    polyline: &[[f64; 3]],
    rule: &Subdivision,
    clearance: &[f64],
    size_at: Option<SizeAt<'_>>,
    pins: &[Pin],
) -> Result<Vec<[f64; 3]>, DiscretizeError> {
    if polyline.len() < 2 {
        return Err(DiscretizeError::TooFewPoints(polyline.len()));
    }
    let mut cum = Vec::with_capacity(polyline.len());
    cum.push(0.0);
    for w in polyline.windows(2) {
        let d = dist(&w[0], &w[1]);
        cum.push(cum[cum.len() - 1] + d);
    }
    let length = cum[cum.len() - 1];
    if length.is_nan() || length <= 0.0 || length.is_infinite() {
        return Err(DiscretizeError::Length(length));
    }
    let curve = Polyline {
        points: polyline,
        cum: &cum,
    };
    let lengths = match (rule, size_at) {
        (Subdivision::Size { size, ratio, .. }, Some(f)) if *ratio == 1.0 => {
            field_lengths(&curve, *size, f)?
        }
        _ => segment_lengths(length, rule)?,
    };
    let mut stations = Vec::with_capacity(lengths.len() + 1 + pins.len());
    stations.push(Station::Vertex(0));
    let mut s = 0.0;
    for l in &lengths[..lengths.len() - 1] {
        s += l;
        stations.push(Station::Arc(s));
    }
    stations.push(Station::Vertex(polyline.len() - 1));
    let pins = pin_arcs(&curve, pins)?;
    let mut stations = place_pins(&curve, stations, &pins);
    if matches!(rule, Subdivision::Size { .. }) {
        let clearance = (clearance.len() == polyline.len()).then_some(clearance);
        stations = follow_bends(&curve, &stations, clearance);
    }
    Ok(stations.iter().map(|&st| curve.point(st)).collect())
}

/// Segment lengths along `curve` for the size `min(size, size_at(x))` (see
/// [`discretize_within`]). The integral is taken in steps of a quarter of the local size.
fn field_lengths(
    curve: &Polyline<'_>,
    size: f64,
    size_at: SizeAt<'_>,
) -> Result<Vec<f64>, DiscretizeError> {
    let length = curve.cum[curve.cum.len() - 1];
    let h = |s: f64| size_at(&curve.point(Station::Arc(s))).min(size);
    // (arc length, integral of 1/h up to it)
    let mut table = vec![(0.0, 0.0)];
    let (mut s, mut total) = (0.0, 0.0);
    while s < length {
        let here = h(s);
        if !(here > 0.0 && here.is_finite()) {
            return Err(DiscretizeError::SizeField { size: here, arc: s });
        }
        let ds = (0.25 * here).min(length - s);
        total += ds / h(s + 0.5 * ds);
        s += ds;
        table.push((s, total));
        if table.len() > 4 * MAX_SEGMENTS {
            return Err(DiscretizeError::FieldTooFine);
        }
    }
    let n = (total.round() as usize).max(1);
    let mut ends = Vec::with_capacity(n);
    let mut j = 1;
    for k in 1..n {
        let want = total * k as f64 / n as f64;
        while j + 1 < table.len() && table[j].1 < want {
            j += 1;
        }
        let ((s0, i0), (s1, i1)) = (table[j - 1], table[j]);
        let t = if i1 > i0 {
            (want - i0) / (i1 - i0)
        } else {
            0.0
        };
        ends.push(s0 + t * (s1 - s0));
    }
    ends.push(length);
    let mut prev = 0.0;
    Ok(ends
        .into_iter()
        .map(|e| {
            let l = e - prev;
            prev = e;
            l
        })
        .collect())
}

/// A node's place on the polyline: a vertex (copied bit for bit), an arc length, or a pin
/// (its point copied bit for bit, at its arc length).
#[derive(Copy, Clone, Debug, PartialEq)]
enum Station {
    Vertex(usize),
    Arc(f64),
    Pin([f64; 3], f64),
}

/// The pins strictly inside the curve with their arc lengths, in arc order, once each.
fn pin_arcs(curve: &Polyline<'_>, pins: &[Pin]) -> Result<Vec<([f64; 3], f64)>, DiscretizeError> {
    let (first, last) = (curve.points[0], curve.points[curve.points.len() - 1]);
    let mut out = Vec::with_capacity(pins.len());
    for pin in pins {
        let k = pin.segment as usize;
        if k + 1 >= curve.points.len() || pin.point.iter().any(|x| !x.is_finite()) {
            return Err(DiscretizeError::Pin {
                segment: pin.segment,
                point: pin.point,
            });
        }
        if pin.point == first || pin.point == last {
            continue;
        }
        let s = curve.cum[k] + dist(&curve.points[k], &pin.point);
        out.push((pin.point, s.min(curve.cum[k + 1])));
    }
    out.sort_by(|a, b| {
        a.1.total_cmp(&b.1)
            .then(a.0.map(f64::to_bits).cmp(&b.0.map(f64::to_bits)))
    });
    out.dedup_by(|a, b| a.0 == b.0);
    Ok(out)
}

/// `stations` (in arc order, ends first and last) with each pin placed: it replaces the nearer
/// neighbouring interior station that is not a pin when that lies within a third of the gap
/// between the two, and is inserted between them otherwise.
fn place_pins(
    curve: &Polyline<'_>,
    mut stations: Vec<Station>,
    pins: &[([f64; 3], f64)],
) -> Vec<Station> {
    for &(point, s) in pins {
        let j = stations
            .partition_point(|&st| curve.arc(st) < s)
            .clamp(1, stations.len() - 1);
        let (prev, next) = (j - 1, j);
        let (sp, sn) = (curve.arc(stations[prev]), curve.arc(stations[next]));
        let movable =
            |i: usize| i > 0 && i + 1 < stations.len() && !matches!(stations[i], Station::Pin(..));
        let third = (sn - sp) / 3.0;
        let pin = Station::Pin(point, s);
        if movable(prev) && s - sp <= (sn - s).min(third) {
            stations[prev] = pin;
        } else if movable(next) && sn - s <= third {
            stations[next] = pin;
        } else {
            stations.insert(next, pin);
        }
    }
    stations
}

/// A polyline with the arc length at each vertex.
struct Polyline<'a> {
    points: &'a [[f64; 3]],
    cum: &'a [f64],
}

impl Polyline<'_> {
    fn arc(&self, st: Station) -> f64 {
        match st {
            Station::Vertex(i) => self.cum[i],
            Station::Arc(s) | Station::Pin(_, s) => s,
        }
    }

    /// The point at `st`, interpolated on the polyline segment holding its arc length.
    fn point(&self, st: Station) -> [f64; 3] {
        let s = match st {
            Station::Vertex(i) => return self.points[i],
            Station::Pin(p, _) => return p,
            Station::Arc(s) => s,
        };
        let cum = self.cum;
        let seg = cum[1..cum.len() - 1].partition_point(|&c| c < s);
        let (a, b) = (cum[seg], cum[seg + 1]);
        let t = if b > a {
            ((s - a) / (b - a)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (p, q) = (&self.points[seg], &self.points[seg + 1]);
        [
            p[0] + t * (q[0] - p[0]),
            p[1] + t * (q[1] - p[1]),
            p[2] + t * (q[2] - p[2]),
        ]
    }
}

/// Splits every segment whose polyline strays from it, in two ways:
/// - while a polyline vertex strictly between a segment's ends lies farther from the segment than
///   half its clearance, the vertex that strays most beyond that becomes a node. Chords that cut
///   a bend short could otherwise cross the chords of a neighbouring curve of the same patch, and
///   no surface mesh can then be bounded by them (the argument is in `clearance`);
/// - while the curve strays from a segment by more than [`MAX_CUT_TURN_DEG`] allows, whatever
///   curves are near, it is split ([`cut_bend`]). A chord across a bend of a coarsely faceted
///   body leaves the surface by a quarter of its length: the surface mesh along it then folds
///   (a real salt body meshed at 1 to 3 km failed so, at every size, with chords 130 m off the
///   curve).
///
/// Every split adds a vertex or halves a segment whose curve turns within it, so this ends.
fn follow_bends(
    curve: &Polyline<'_>,
    stations: &[Station],
    clearance: Option<&[f64]>,
) -> Vec<Station> {
    let mut out = Vec::with_capacity(stations.len());
    out.push(stations[0]);
    for w in stations.windows(2) {
        split_bends(curve, w[0], w[1], clearance, &mut out);
    }
    out
}

/// Appends the stations after `a` up to and including `b`, splitting at strayed vertices (left
/// part first; a stack, not recursion, as a long winding curve may split many times).
fn split_bends(
    curve: &Polyline<'_>,
    a: Station,
    b: Station,
    clearance: Option<&[f64]>,
    out: &mut Vec<Station>,
) {
    let mut from = a;
    let mut pending = vec![b];
    while let Some(&to) = pending.last() {
        let strayed = clearance.and_then(|c| most_strayed(curve, from, to, c));
        let split = (strayed.map(Station::Vertex)).or_else(|| cut_bend(curve, from, to));
        match split {
            Some(st) => pending.push(st),
            None => {
                out.push(to);
                from = to;
                pending.pop();
            }
        }
    }
}

/// The polyline vertex strictly between `a` and `b` that lies farthest beyond half its clearance
/// from the segment `a`–`b`, if any does (the first one on ties).
fn most_strayed(curve: &Polyline<'_>, a: Station, b: Station, clearance: &[f64]) -> Option<usize> {
    let (pa, pb) = (curve.point(a), curve.point(b));
    let (sa, sb) = (curve.arc(a), curve.arc(b));
    let first = curve.cum.partition_point(|&c| c <= sa);
    let last = curve.cum.partition_point(|&c| c < sb);
    (first..last)
        .map(|i| {
            let d = point_segment_distance(&curve.points[i], &pa, &pb);
            (d - 0.5 * clearance[i], i)
        })
        .filter(|&(excess, _)| excess > 0.0)
        .max_by(|x, y| x.0.total_cmp(&y.0).then(y.1.cmp(&x.1)))
        .map(|(_, i)| i)
}

/// The largest turn (degrees) a segment may cut across at its middle: the curve may stray from
/// a segment by at most `tan(MAX_CUT_TURN_DEG / 2) / 2` times its length, as far as a corner of
/// this turn halfway along it strays (or an arc turning by twice as much). At 30° the corpus's
/// salt bodies took 30 to 47 % more tets for no better angle, and an onlap's tip fell from 1.2°
/// to 0.4°; at 45°, 10 to 25 % more, and the onlap is as it was.
pub const MAX_CUT_TURN_DEG: f64 = 45.0;

/// Where to split the segment `a`–`b` if the curve strays from it by more than
/// [`MAX_CUT_TURN_DEG`] allows: at the polyline vertex farthest from it when that lies in the
/// middle half of the segment's arc, else at the middle of the arc (so no piece is much shorter
/// than the other).
fn cut_bend(curve: &Polyline<'_>, a: Station, b: Station) -> Option<Station> {
    let (pa, pb) = (curve.point(a), curve.point(b));
    let (sa, sb) = (curve.arc(a), curve.arc(b));
    let first = curve.cum.partition_point(|&c| c <= sa);
    let last = curve.cum.partition_point(|&c| c < sb);
    let (d, far) = (first..last)
        .map(|i| (point_segment_distance(&curve.points[i], &pa, &pb), i))
        .max_by(|x, y| x.0.total_cmp(&y.0).then(y.1.cmp(&x.1)))?;
    let sag = 0.5 * (0.5 * MAX_CUT_TURN_DEG.to_radians()).tan();
    if d.partial_cmp(&(sag * dist(&pa, &pb))) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let t = (curve.cum[far] - sa) / (sb - sa);
    let mid = 0.5 * (sa + sb);
    if (0.25..=0.75).contains(&t) {
        Some(Station::Vertex(far))
    } else {
        // An arc too short to halve in f64 is left whole rather than given a zero-length piece.
        (sa < mid && mid < sb).then_some(Station::Arc(mid))
    }
}

/// Distance from `p` to the segment `a`–`b`.
fn point_segment_distance(p: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ap = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    let t = if len2 > 0.0 {
        ((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    dist(p, &[a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]])
}

/// The segment lengths for a curve of `length`, adding up to `length`.
pub fn segment_lengths(length: f64, rule: &Subdivision) -> Result<Vec<f64>, DiscretizeError> {
    match *rule {
        Subdivision::Count(n) => {
            if n == 0 {
                return Err(DiscretizeError::ZeroCount);
            }
            Ok(vec![length / n as f64; n as usize])
        }
        Subdivision::Size {
            size,
            ratio,
            grading,
        } => {
            if !(size > 0.0 && size.is_finite()) {
                return Err(DiscretizeError::Size(size));
            }
            if !(ratio > 0.0 && ratio.is_finite()) {
                return Err(DiscretizeError::Ratio(ratio));
            }
            match grading {
                Grading::Geometric => geometric(length, size, ratio),
                Grading::Bump => {
                    // Two geometric halves mirrored; an odd total keeps one middle segment.
                    let half = geometric(length / 2.0, size, ratio)?;
                    let mut v = half.clone();
                    v.extend(half.iter().rev());
                    Ok(v)
                }
            }
        }
    }
}

fn geometric(length: f64, size: f64, ratio: f64) -> Result<Vec<f64>, DiscretizeError> {
    let uniform = (ratio - 1.0).abs() < 1e-12;
    // Number of segments whose sizes h, h r, h r^2... best fill the length.
    let n_real = if uniform {
        length / size
    } else {
        (1.0 + length * (ratio - 1.0) / size).ln() / ratio.ln()
    };
    let n = if n_real.is_finite() {
        n_real.round().max(1.0)
    } else {
        1.0
    };
    if n > MAX_SEGMENTS as f64 {
        return Err(DiscretizeError::TooManySegments { size, n, length });
    }
    let n = n as usize;
    let first = if uniform {
        length / n as f64
    } else {
        length * (ratio - 1.0) / (ratio.powi(n as i32) - 1.0)
    };
    let mut v = Vec::with_capacity(n);
    let mut h = first;
    for _ in 0..n {
        v.push(h);
        if !uniform {
            h *= ratio;
        }
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(len: f64) -> Vec<[f64; 3]> {
        vec![
            [500_000.0, 7_000_000.0, -1200.0],
            [500_000.0 + len, 7_000_000.0, -1200.0],
        ]
    }

    fn pinned(polyline: &[[f64; 3]], rule: &Subdivision, pins: &[Pin]) -> Vec<[f64; 3]> {
        discretize_pinned(polyline, rule, &[], None, pins).expect("discretizes")
    }

    fn at(x: f64) -> [f64; 3] {
        [500_000.0 + x, 7_000_000.0, -1200.0]
    }

    #[test]
    fn a_pin_near_a_node_takes_its_place_and_one_between_nodes_is_inserted() {
        let l = line(1000.0);
        let rule = Subdivision::Count(10);
        let plain = pinned(&l, &rule, &[]);
        // 1 m from the node at 300: it moves there, and the count stays 10.
        let near = Pin {
            segment: 0,
            point: at(301.0),
        };
        let got = pinned(&l, &rule, std::slice::from_ref(&near));
        assert_eq!(got.len(), 11);
        assert_eq!(got[3], near.point);
        assert_eq!((got[2], got[4]), (plain[2], plain[4]));
        // Midway between 300 and 400: a node of its own.
        let mid = Pin {
            segment: 0,
            point: at(350.0),
        };
        let got = pinned(&l, &rule, std::slice::from_ref(&mid));
        assert_eq!(got.len(), 12);
        assert_eq!(got[4], mid.point);
        assert_eq!((got[3], got[5]), (plain[3], plain[4]));
    }

    #[test]
    fn pins_at_the_ends_twice_or_in_reverse_order_give_one_node_each_in_arc_order() {
        // A bent curve: the pins lie on its second segment.
        let l = vec![at(0.0), at(500.0), [500_500.0, 7_000_500.0, -1200.0]];
        let rule = Subdivision::Count(4);
        let p = |y: f64| Pin {
            segment: 1,
            point: [500_500.0, 7_000_000.0 + y, -1200.0],
        };
        let end = Pin {
            segment: 1,
            point: l[2],
        };
        let got = pinned(&l, &rule, &[p(400.0), end.clone(), p(130.0), p(400.0)]);
        let expected = pinned(&l, &rule, &[p(130.0), p(400.0)]);
        assert_eq!(got, expected);
        assert_eq!(got.iter().filter(|q| **q == p(130.0).point).count(), 1);
        let (i, j) = (
            got.iter().position(|q| *q == p(130.0).point).unwrap(),
            got.iter().position(|q| *q == p(400.0).point).unwrap(),
        );
        assert!(i < j, "in arc order");
        assert_eq!((got[0], *got.last().unwrap()), (l[0], l[2]));
        let bad = Pin {
            segment: 2,
            point: at(1.0),
        };
        assert!(discretize_pinned(&l, &rule, &[], None, &[bad]).is_err());
    }

    #[test]
    fn a_size_field_shortens_segments_near_its_feature_and_leaves_them_far_from_it() {
        let l = line(1000.0);
        let rule = Subdivision::Size {
            size: 100.0,
            ratio: 1.0,
            grading: Grading::Geometric,
        };
        let field = |x: &[f64; 3]| 10.0 + 0.2 * (x[0] - 500_000.0).abs();
        let nodes = discretize_within(&l, &rule, &[], Some(&field)).unwrap();
        assert_eq!(nodes.first(), l.first());
        assert_eq!(nodes.last(), l.last());
        let lens: Vec<f64> = nodes.windows(2).map(|w| dist(&w[0], &w[1])).collect();
        assert!(lens[0] < 15.0, "first segment {}", lens[0]);
        assert!(
            lens.windows(2).all(|w| w[1] >= w[0] - 1e-9),
            "growing: {lens:?}"
        );
        assert!((lens[lens.len() - 1] - 100.0).abs() < 15.0, "{lens:?}");
        let plain = discretize(&l, &rule, &[]).unwrap();
        assert_eq!(plain.len(), 11);
        // A field coarser than the rule everywhere changes nothing.
        let coarse = |_: &[f64; 3]| 1e9;
        assert_eq!(
            discretize_within(&l, &rule, &[], Some(&coarse)).unwrap(),
            plain
        );
    }

    #[test]
    fn a_count_gives_equal_segments_and_keeps_the_end_vertices_bit_for_bit() {
        let p = vec![[0.1, 0.2, 0.3], [1.0, 0.2, 0.3], [1.0, 3.7, 0.3]];
        let n = discretize(&p, &Subdivision::Count(7), &[]).unwrap();
        assert_eq!(n.len(), 8);
        assert_eq!(n[0], p[0]);
        assert_eq!(n[7], p[2]);
        // Arc-length position of each node along the two legs of the polyline.
        let total = 0.9 + 3.5;
        for (k, q) in n.iter().enumerate() {
            let s = if q[1] == 0.2 {
                q[0] - 0.1
            } else {
                0.9 + (q[1] - 0.2)
            };
            assert!(
                (s - k as f64 * total / 7.0).abs() < 1e-9,
                "node {k} at arc length {s}"
            );
        }
    }

    #[test]
    fn nodes_stay_on_the_polyline_around_a_bend() {
        let p = vec![[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [10.0, 10.0, 0.0]];
        for q in discretize(&p, &Subdivision::Count(9), &[]).unwrap() {
            assert!(q[1] == 0.0 || q[0] == 10.0, "{q:?} is off the polyline");
        }
    }

    #[test]
    fn a_size_with_ratio_grows_geometrically_and_fills_the_curve() {
        let l = segment_lengths(
            1000.0,
            &Subdivision::Size {
                size: 10.0,
                ratio: 1.2,
                grading: Grading::Geometric,
            },
        )
        .unwrap();
        assert!((l.iter().sum::<f64>() - 1000.0).abs() < 1e-9);
        for w in l.windows(2) {
            assert!((w[1] / w[0] - 1.2).abs() < 1e-12);
        }
        assert!(
            (l[0] - 10.0).abs() / 10.0 < 0.3,
            "first segment {} far from the asked size",
            l[0]
        );
    }

    #[test]
    fn a_bump_grading_is_symmetric() {
        let l = segment_lengths(
            1000.0,
            &Subdivision::Size {
                size: 10.0,
                ratio: 1.3,
                grading: Grading::Bump,
            },
        )
        .unwrap();
        let n = l.len();
        for i in 0..n / 2 {
            assert_eq!(l[i], l[n - 1 - i]);
        }
        assert!((l.iter().sum::<f64>() - 1000.0).abs() < 1e-9);
    }

    #[test]
    fn a_uniform_size_rounds_to_the_nearest_count() {
        let n = discretize(
            &line(1000.0),
            &Subdivision::Size {
                size: 100.0,
                ratio: 1.0,
                grading: Grading::Geometric,
            },
            &[],
        )
        .unwrap();
        assert_eq!(n.len(), 11);
        let n = discretize(
            &line(1040.0),
            &Subdivision::Size {
                size: 100.0,
                ratio: 1.0,
                grading: Grading::Geometric,
            },
            &[],
        )
        .unwrap();
        assert_eq!(n.len(), 11);
    }

    #[test]
    fn a_size_larger_than_the_curve_gives_one_segment() {
        let n = discretize(
            &line(50.0),
            &Subdivision::Size {
                size: 100.0,
                ratio: 1.0,
                grading: Grading::Geometric,
            },
            &[],
        )
        .unwrap();
        assert_eq!(n, line(50.0));
    }

    #[test]
    fn bad_rules_and_degenerate_curves_are_errors_not_panics() {
        assert!(discretize(&line(10.0), &Subdivision::Count(0), &[]).is_err());
        assert!(
            discretize(
                &line(10.0),
                &Subdivision::Size {
                    size: 0.0,
                    ratio: 1.0,
                    grading: Grading::Geometric
                },
                &[],
            )
            .is_err()
        );
        assert!(
            discretize(
                &line(10.0),
                &Subdivision::Size {
                    size: f64::NAN,
                    ratio: 1.0,
                    grading: Grading::Geometric
                },
                &[],
            )
            .is_err()
        );
        assert!(
            discretize(
                &line(1e9),
                &Subdivision::Size {
                    size: 1e-3,
                    ratio: 1.0,
                    grading: Grading::Geometric
                },
                &[],
            )
            .is_err()
        );
        assert!(discretize(&[[0.0; 3]], &Subdivision::Count(2), &[]).is_err());
        assert!(discretize(&[[1.0; 3], [1.0; 3]], &Subdivision::Count(2), &[]).is_err());
    }

    /// A polyline around three sides of a 100 m square, bent at its two corners.
    fn three_sides() -> Vec<[f64; 3]> {
        vec![
            [0.0, 0.0, 0.0],
            [0.0, 100.0, 0.0],
            [100.0, 100.0, 0.0],
            [100.0, 0.0, 0.0],
        ]
    }

    const ONE_SEGMENT: Subdivision = Subdivision::Size {
        size: 500.0,
        ratio: 1.0,
        grading: Grading::Geometric,
    };

    #[test]
    fn a_size_rule_keeps_the_corners_a_long_segment_would_cut_near_another_curve() {
        let n = discretize(&three_sides(), &ONE_SEGMENT, &[20.0; 4]).unwrap();
        assert_eq!(n, three_sides(), "both corners become nodes, bit for bit");
    }

    /// `n + 1` points on an arc of radius `r` turning by `degrees`.
    fn arc(r: f64, degrees: f64, n: usize) -> Vec<[f64; 3]> {
        (0..=n)
            .map(|i| {
                let a = (degrees * i as f64 / n as f64).to_radians();
                [r * a.sin(), r * (1.0 - a.cos()), 0.0]
            })
            .collect()
    }

    #[test]
    fn a_gently_bending_curve_with_no_other_curve_near_is_never_split() {
        // 40° of arc: the chord cuts the bend by 9 % of its length, under a 45° corner's 21 %.
        let p = arc(300.0, 40.0, 40);
        let far = vec![f64::INFINITY; p.len()];
        assert_eq!(discretize(&p, &ONE_SEGMENT, &far).unwrap().len(), 2);
    }

    #[test]
    fn a_curve_turning_back_keeps_its_corners_with_no_other_curve_near() {
        // A chord from end to end would cut across two right angles, 100 m off the curve.
        let far = [f64::INFINITY; 4];
        assert_eq!(
            discretize(&three_sides(), &ONE_SEGMENT, &far).unwrap(),
            three_sides()
        );
        // A count is the recipe's word, bends or not.
        let one = discretize(&three_sides(), &Subdivision::Count(1), &far).unwrap();
        assert_eq!(one.len(), 2);
    }

    #[test]
    fn no_segment_cuts_across_a_bend_of_a_round_curve_and_the_pieces_stay_even() {
        // Three quarters of a circle in 999 short pieces, at a size far above its length: every
        // segment keeps within what a 45° corner at its middle would stray, and as the splits
        // halve arcs, the segments are within a factor of two of each other.
        let p = arc(100.0, 270.0, 999);
        let n = discretize(&p, &ONE_SEGMENT, &[]).unwrap();
        let sag = 0.5 * (0.5 * MAX_CUT_TURN_DEG.to_radians()).tan();
        for q in &p {
            let off = (n.windows(2))
                .map(|w| point_segment_distance(q, &w[0], &w[1]) / dist(&w[0], &w[1]))
                .fold(f64::INFINITY, f64::min);
            assert!(off <= sag + 1e-12, "{q:?} strays by {off} of its segment");
        }
        let lengths: Vec<f64> = n.windows(2).map(|w| dist(&w[0], &w[1])).collect();
        let lo = lengths.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = lengths.iter().copied().fold(0.0, f64::max);
        assert!(hi <= 2.0 * lo + 1e-9, "{lengths:?}");
        assert!(
            (3..=8).contains(&lengths.len()),
            "{} segments",
            lengths.len()
        );
    }

    #[test]
    fn a_count_is_kept_even_across_corners() {
        let n = discretize(&three_sides(), &Subdivision::Count(1), &[20.0; 4]).unwrap();
        assert_eq!(n, vec![[0.0; 3], [100.0, 0.0, 0.0]]);
    }

    #[test]
    fn a_bend_is_split_only_when_it_strays_beyond_half_the_clearance() {
        // The middle vertex lies 5 m off the 200 m chord.
        let p = vec![[0.0; 3], [100.0, 5.0, 0.0], [200.0, 0.0, 0.0]];
        assert_eq!(discretize(&p, &ONE_SEGMENT, &[20.0; 3]).unwrap().len(), 2);
        assert_eq!(discretize(&p, &ONE_SEGMENT, &[8.0; 3]).unwrap().len(), 3);
    }

    #[test]
    fn every_segment_of_a_winding_curve_keeps_within_half_its_clearance() {
        // A 40-turn spiral of 4000 vertices discretized far coarser than one turn.
        let p: Vec<[f64; 3]> = (0..4000)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 100.0;
                let r = 100.0 + i as f64;
                [r * a.cos(), r * a.sin(), 0.1 * i as f64]
            })
            .collect();
        let n = discretize(&p, &ONE_SEGMENT, &vec![50.0; p.len()]).unwrap();
        // The polyline segment each node lies on, searched forwards (nodes follow the curve).
        let mut on = vec![0usize];
        for q in &n[1..n.len() - 1] {
            let from = *on.last().unwrap();
            let k = (from..p.len() - 1)
                .find(|&k| point_segment_distance(q, &p[k], &p[k + 1]) < 1e-9)
                .expect("every node lies on the polyline");
            on.push(k);
        }
        on.push(p.len() - 2);
        for (w, k) in n.windows(2).zip(on.windows(2)) {
            let bound = 25.0 + 1e-9;
            for v in &p[k[0] + 1..=k[1]] {
                assert!(point_segment_distance(v, &w[0], &w[1]) <= bound);
            }
        }
        assert!(n.len() > 40 * 4, "{} nodes for 40 turns", n.len());
    }

    #[test]
    fn the_same_curve_and_rule_give_the_same_bits() {
        let r = Subdivision::Size {
            size: 7.0,
            ratio: 1.1,
            grading: Grading::Bump,
        };
        assert_eq!(
            discretize(&line(333.3), &r, &[]).unwrap(),
            discretize(&line(333.3), &r, &[]).unwrap()
        );
    }
}
