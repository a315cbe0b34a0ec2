//! A refinement near a feature, as every mesher takes it: points sampled on the feature (a
//! surface, a curve, a point), the element size there, and the rate at which the size may grow
//! with the distance from it. The size it asks for at `x` is `size + slope · d(x, feature)`;
//! each mesher takes the least of that and its own sizes, with the slope no steeper than its own
//! growth allows (a steeper one would make elements that change size faster than the mesh can
//! keep well shaped).

use serde::{Deserialize, Serialize};

/// One refinement (see the module doc).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Refinement {
    /// Points on the feature, closer together than half of `size` along it, so the distance to
    /// them is within a quarter of `size` of the distance to the feature.
    pub points: Vec<[f64; 3]>,
    /// Element size at the feature.
    pub size: f64,
    /// Growth of the size per unit of distance from the feature.
    pub slope: f64,
}

impl Refinement {
    /// How far from the feature the size it asks for stays below `size`.
    pub fn reach(&self, size: f64) -> f64 {
        if size <= self.size {
            0.0
        } else if self.slope > 0.0 {
            (size - self.size) / self.slope
        } else {
            f64::INFINITY
        }
    }

    /// The bounding box of its points, grown by `margin`; `None` without points.
    pub fn bounds(&self, margin: f64) -> Option<([f64; 3], [f64; 3])> {
        let mut it = self.points.iter();
        let first = *it.next()?;
        let (mut lo, mut hi) = (first, first);
        for p in it {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        Some((lo.map(|x| x - margin), hi.map(|x| x + margin)))
    }
}

/// Do the boxes `a` and `b` (`(lo, hi)`) overlap?
pub fn boxes_meet(a: ([f64; 3], [f64; 3]), b: ([f64; 3], [f64; 3])) -> bool {
    (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reach_is_where_the_size_grown_from_the_feature_meets_the_given_one() {
        let r = Refinement {
            points: vec![[0.0; 3]],
            size: 20.0,
            slope: 0.2,
        };
        assert_eq!(r.reach(200.0), 900.0);
        assert_eq!(r.reach(10.0), 0.0);
        let flat = Refinement { slope: 0.0, ..r };
        assert_eq!(flat.reach(200.0), f64::INFINITY);
    }

    #[test]
    fn boxes_meet_when_they_overlap_on_every_axis_and_not_otherwise() {
        let r = Refinement {
            points: vec![[0.0, 0.0, 0.0], [10.0, 1.0, 1.0]],
            size: 1.0,
            slope: 0.1,
        };
        let b = r.bounds(5.0).unwrap();
        assert_eq!(b, ([-5.0, -5.0, -5.0], [15.0, 6.0, 6.0]));
        assert!(boxes_meet(b, ([14.0, 5.0, 5.0], [20.0, 20.0, 20.0])));
        assert!(!boxes_meet(b, ([16.0, 0.0, 0.0], [20.0, 1.0, 1.0])));
        assert_eq!(Refinement::default().bounds(1.0), None);
    }
}
