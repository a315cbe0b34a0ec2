//! The path cut at its crossings into pieces, each located in its region, and the resampling of
//! a piece.

use super::cross::Found;
use super::{WellError, WellPiece, WellRun};
use crate::regions::Locator;
use geom::predicates::dist;

type P3 = [f64; 3];

/// At least two finite stations, no two consecutive ones equal.
pub(super) fn check_path(stations: &[P3]) -> Result<(), WellError> {
    if stations.len() < 2 {
        return Err(WellError {
            message: format!(
                "the well path has {} station(s); it needs at least two",
                stations.len()
            ),
            segment: None,
            at: stations.first().copied(),
        });
    }
    if let Some(i) = stations
        .iter()
        .position(|p| p.iter().any(|c| !c.is_finite()))
    {
        return Err(WellError {
            message: format!("station {i} of the well path is not finite"),
            segment: Some(i.min(stations.len() - 2)),
            at: None,
        });
    }
    if let Some(i) = stations.windows(2).position(|w| w[0] == w[1]) {
        return Err(WellError {
            message: "two consecutive stations of the well path are at one place".into(),
            segment: Some(i),
            at: Some(stations[i]),
        });
    }
    Ok(())
}

/// A piece being gathered: points without consecutive repeats, and the path segment it
/// starts in.
struct Gather {
    points: Vec<P3>,
    segment: usize,
}

impl Gather {
    fn push(&mut self, p: P3) {
        if self.points.last() != Some(&p) {
            self.points.push(p);
        }
    }

    /// Ends the piece at `p` and starts the next one there, in segment `segment`.
    fn cut(&mut self, p: P3, segment: usize, done: &mut Vec<(usize, Vec<P3>)>) {
        self.push(p);
        let piece = std::mem::replace(&mut self.points, vec![p]);
        let first = std::mem::replace(&mut self.segment, segment);
        if piece.len() >= 2 {
            done.push((first, piece));
        }
    }
}

/// The pieces of the path between its crossings (sorted along it): those whose segments lie on
/// a patch (`on`, per segment) are runs, the others each in the region that strictly contains
/// it; pieces in no region are left out. Crossings never fall inside a run (refused before), so
/// every piece lies on one patch or on none.
pub(super) fn split(
    stations: &[P3],
    found: &[Found],
    on: &[Option<u32>],
    locator: &Locator,
) -> (Vec<WellPiece>, Vec<WellRun>) {
    let mut done = Vec::new();
    let mut g = Gather {
        points: vec![stations[0]],
        segment: 0,
    };
    let mut next = found.iter().peekable();
    for (j, s) in stations.iter().enumerate() {
        g.push(*s);
        // `found` is in path order: the crossings at station j, then those inside segment j.
        while let Some(f) = next.next_if(|f| f.station.unwrap_or(f.segment) == j) {
            g.cut(f.crossing.point, f.segment, &mut done);
        }
    }
    if g.points.len() >= 2 {
        done.push((g.segment, g.points));
    }
    let (mut pieces, mut runs) = (Vec::new(), Vec::new());
    for (segment, points) in done {
        if let Some(patch) = on[segment] {
            runs.push(WellRun { patch, points });
        } else if let Some(region) = locator.locate(inner_point(&points)) {
            pieces.push(WellPiece {
                region: region as u32,
                points,
            });
        }
    }
    (pieces, runs)
}

/// The midpoint of the piece's longest segment: off every patch, since crossings cut the path.
fn inner_point(points: &[P3]) -> P3 {
    let len2 = |w: &[P3]| (0..3).map(|k| (w[1][k] - w[0][k]).powi(2)).sum::<f64>();
    let w = points
        .windows(2)
        .max_by(|a, b| len2(a).total_cmp(&len2(b)))
        .expect("a piece has two points");
    [0, 1, 2].map(|k| 0.5 * (w[0][k] + w[1][k]))
}

/// The length along the polyline `points` from its first point to each of them.
pub fn lengths_along(points: &[P3]) -> Vec<f64> {
    let mut along = Vec::with_capacity(points.len());
    let mut s = 0.0;
    for (i, p) in points.iter().enumerate() {
        if i > 0 {
            s += dist(&points[i - 1], p);
        }
        along.push(s);
    }
    along
}

/// `points` resampled to segments of about `size` along its length, its two ends kept bit for
/// bit (a piece shorter than `size` becomes one segment).
pub fn resample(points: &[P3], size: f64) -> Vec<P3> {
    let (Some(&first), Some(&last)) = (points.first(), points.last()) else {
        return Vec::new();
    };
    let lengths: Vec<f64> = points.windows(2).map(|w| dist(&w[0], &w[1])).collect();
    let total: f64 = lengths.iter().sum();
    let n = if size > 0.0 && total.is_finite() {
        ((total / size).round() as usize).max(1)
    } else {
        1
    };
    let mut out = vec![first];
    let (mut seg, mut start) = (0usize, 0.0f64);
    for k in 1..n {
        let s = total * k as f64 / n as f64;
        while seg + 1 < lengths.len() && start + lengths[seg] < s {
            start += lengths[seg];
            seg += 1;
        }
        let f = if lengths[seg] > 0.0 {
            ((s - start) / lengths[seg]).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (a, b) = (points[seg], points[seg + 1]);
        out.push([0, 1, 2].map(|c| a[c] + f * (b[c] - a[c])));
    }
    if out.last() != Some(&last) {
        out.push(last);
    }
    out
}
