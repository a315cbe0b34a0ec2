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

#[derive(Debug, Clone, PartialEq)]
pub struct DiscretizeError(pub String);

impl std::fmt::Display for DiscretizeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// The most segments one curve may get: a guard against a size that is tiny by mistake.
pub const MAX_SEGMENTS: usize = 10_000_000;

/// Subdivides `polyline` (at least 2 points; closed curves repeat the first point at the end).
pub fn discretize(
    polyline: &[[f64; 3]],
    rule: &Subdivision,
) -> Result<Vec<[f64; 3]>, DiscretizeError> {
    if polyline.len() < 2 {
        return Err(DiscretizeError(format!(
            "a curve needs at least 2 points, got {}",
            polyline.len()
        )));
    }
    let mut cum = Vec::with_capacity(polyline.len());
    cum.push(0.0);
    for w in polyline.windows(2) {
        let d = dist(&w[0], &w[1]);
        cum.push(cum[cum.len() - 1] + d);
    }
    let length = cum[cum.len() - 1];
    if length.is_nan() || length <= 0.0 || length.is_infinite() {
        return Err(DiscretizeError(format!(
            "the curve has zero or non-finite length ({length})"
        )));
    }
    let lengths = segment_lengths(length, rule)?;
    let mut nodes = Vec::with_capacity(lengths.len() + 1);
    nodes.push(polyline[0]);
    let mut s = 0.0;
    let mut seg = 0usize;
    for l in &lengths[..lengths.len() - 1] {
        s += l;
        while seg + 2 < cum.len() && cum[seg + 1] < s {
            seg += 1;
        }
        let (a, b) = (cum[seg], cum[seg + 1]);
        let t = if b > a {
            ((s - a) / (b - a)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (p, q) = (&polyline[seg], &polyline[seg + 1]);
        nodes.push([
            p[0] + t * (q[0] - p[0]),
            p[1] + t * (q[1] - p[1]),
            p[2] + t * (q[2] - p[2]),
        ]);
    }
    nodes.push(polyline[polyline.len() - 1]);
    Ok(nodes)
}

/// The segment lengths for a curve of `length`, adding up to `length`.
pub fn segment_lengths(length: f64, rule: &Subdivision) -> Result<Vec<f64>, DiscretizeError> {
    match *rule {
        Subdivision::Count(n) => {
            if n == 0 {
                return Err(DiscretizeError(
                    "a curve needs a count of at least 1".into(),
                ));
            }
            Ok(vec![length / n as f64; n as usize])
        }
        Subdivision::Size {
            size,
            ratio,
            grading,
        } => {
            if !(size > 0.0 && size.is_finite()) {
                return Err(DiscretizeError(format!(
                    "size must be positive and finite, got {size}"
                )));
            }
            if !(ratio > 0.0 && ratio.is_finite()) {
                return Err(DiscretizeError(format!(
                    "ratio must be positive and finite, got {ratio}"
                )));
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
        return Err(DiscretizeError(format!(
            "size {size} would give {n} segments on a curve of length {length}: more than {MAX_SEGMENTS}"
        )));
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

    #[test]
    fn a_count_gives_equal_segments_and_keeps_the_end_vertices_bit_for_bit() {
        let p = vec![[0.1, 0.2, 0.3], [1.0, 0.2, 0.3], [1.0, 3.7, 0.3]];
        let n = discretize(&p, &Subdivision::Count(7)).unwrap();
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
        for q in discretize(&p, &Subdivision::Count(9)).unwrap() {
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
        )
        .unwrap();
        assert_eq!(n, line(50.0));
    }

    #[test]
    fn bad_rules_and_degenerate_curves_are_errors_not_panics() {
        assert!(discretize(&line(10.0), &Subdivision::Count(0)).is_err());
        assert!(
            discretize(
                &line(10.0),
                &Subdivision::Size {
                    size: 0.0,
                    ratio: 1.0,
                    grading: Grading::Geometric
                }
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
                }
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
                }
            )
            .is_err()
        );
        assert!(discretize(&[[0.0; 3]], &Subdivision::Count(2)).is_err());
        assert!(discretize(&[[1.0; 3], [1.0; 3]], &Subdivision::Count(2)).is_err());
    }

    #[test]
    fn the_same_curve_and_rule_give_the_same_bits() {
        let r = Subdivision::Size {
            size: 7.0,
            ratio: 1.1,
            grading: Grading::Bump,
        };
        assert_eq!(
            discretize(&line(333.3), &r).unwrap(),
            discretize(&line(333.3), &r).unwrap()
        );
    }
}
