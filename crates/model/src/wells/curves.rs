//! The model's curves as a well sees them: which curve segment a support edge is, and which
//! curve point a support vertex is, found by exact coordinates (the patches' supports and the
//! curves' polylines share their points bit for bit), so a crossing on a curve becomes a pin of
//! that curve's discretization instead of a refusal.

use super::CurvePin;
use geom::point_key as key;
use std::collections::BTreeMap;

type P3 = [f64; 3];

/// The curves' segments and points, by coordinates.
#[derive(Default)]
pub struct CurveIndex {
    /// Both ends' keys, smaller first → curve, segment.
    segments: BTreeMap<([u64; 3], [u64; 3]), CurvePin>,
    /// A polyline point's key → the first curve (in index order) through it and the segment
    /// starting there (the last segment for a curve's last point).
    points: BTreeMap<[u64; 3], CurvePin>,
    /// Per curve, its polyline.
    polylines: Vec<Vec<P3>>,
}

impl CurveIndex {
    /// Indexes `polylines` (a curve's points in order; a closed curve repeats its first point).
    pub fn new(polylines: Vec<Vec<P3>>) -> CurveIndex {
        let mut segments = BTreeMap::new();
        let mut points = BTreeMap::new();
        for (c, line) in polylines.iter().enumerate() {
            let last = line.len().saturating_sub(2);
            for (i, p) in line.iter().enumerate() {
                let pin = CurvePin {
                    curve: c as u32,
                    segment: i.min(last) as u32,
                };
                points.entry(key(p)).or_insert(pin);
            }
            for (i, w) in line.windows(2).enumerate() {
                let (a, b) = (key(&w[0]), key(&w[1]));
                let pin = CurvePin {
                    curve: c as u32,
                    segment: i as u32,
                };
                segments.entry((a.min(b), a.max(b))).or_insert(pin);
            }
        }
        CurveIndex {
            segments,
            points,
            polylines,
        }
    }

    /// The curve segment joining `a` and `b`, with its ends in the curve's order.
    pub(super) fn segment(&self, a: &P3, b: &P3) -> Option<(CurvePin, P3, P3)> {
        let (ka, kb) = (key(a), key(b));
        let pin = *self.segments.get(&(ka.min(kb), ka.max(kb)))?;
        let line = &self.polylines[pin.curve as usize];
        let s = pin.segment as usize;
        Some((pin, line[s], line[s + 1]))
    }

    /// The curve point at `p`, if a curve passes through it.
    pub(super) fn point(&self, p: &P3) -> Option<CurvePin> {
        self.points.get(&key(p)).copied()
    }
}

/// Where segment `pq` crosses the curve segment `ab` (given in the curve's order, so every patch
/// along it computes the same bits): the point of `ab` nearest the line `pq`, `a` or `b` exactly
/// at the ends.
pub(super) fn on_segment(p: &P3, q: &P3, a: &P3, b: &P3) -> P3 {
    use geom::predicates::{cross, dot, sub};
    let (d, e) = (sub(q, p), sub(b, a));
    let n = cross(&e, &d);
    let nn = dot(&n, &n);
    if nn == 0.0 || !nn.is_finite() {
        return *a;
    }
    let u = (dot(&cross(&sub(p, a), &d), &n) / nn).clamp(0.0, 1.0);
    if u == 0.0 {
        return *a;
    }
    if u == 1.0 {
        return *b;
    }
    [0, 1, 2].map(|k| a[k] + u * e[k])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_segment_is_found_from_either_end_and_a_crossing_on_it_is_the_same_bits_both_ways() {
        let line = vec![[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [10.0, 10.0, -0.0]];
        let index = CurveIndex::new(vec![line.clone()]);
        let (pin, a, b) = index
            .segment(&line[2], &line[1])
            .expect("the second segment");
        assert_eq!((pin.curve, pin.segment), (0, 1));
        assert_eq!((a, b), (line[1], line[2]));
        assert_eq!(index.point(&[10.0, 10.0, 0.0]).map(|p| p.segment), Some(1));
        assert!(index.segment(&line[0], &line[2]).is_none());
        // A well from (13, 3, 1) to (7, 3, -1) crosses it at (10, 3, 0), whichever way round.
        let (p, q) = ([13.0, 3.0, 1.0], [7.0, 3.0, -1.0]);
        let x = on_segment(&p, &q, &a, &b);
        assert_eq!(x, on_segment(&q, &p, &a, &b));
        assert!(
            (x[1] - 3.0).abs() < 1e-12 && x[0] == 10.0 && x[2] == 0.0,
            "{x:?}"
        );
    }
}
