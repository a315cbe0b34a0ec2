//! Features a recipe refines near, as points: sampled on surfaces and curves closely enough that
//! the distance to the samples is the distance to the feature within a quarter of the size asked
//! there, and the size field such samples make (for curves; the meshers build their own).
//!
//! Decisions and why:
//! - Samples, not exact point-to-triangle distances: every mesher already answers "nearest point
//!   of a set" fast (an R-tree, a distance transform), and the error is bounded by the spacing.
//! - At most [`MAX_SAMPLES`] points per feature: past that the spacing widens evenly (a fault of
//!   tens of square kilometres refined to metres would otherwise cost more than its mesh).
//! - Sampling order follows the input order, so the same model gives the same points.

use geom::TriMesh;
use geom::predicates::dist;
use geom::refine::Refinement;
use rstar::RTree;

/// Samples per feature, at most.
pub const MAX_SAMPLES: usize = 400_000;

/// Points on the triangles of `meshes` no further apart than `spacing` (wider when that would
/// exceed [`MAX_SAMPLES`]): each triangle's corners and a barycentric grid inside.
pub fn sample_surfaces(meshes: &[&TriMesh], spacing: f64) -> Vec<[f64; 3]> {
    let divisions = |m: &TriMesh, t: &[u32; 3], h: f64| {
        let c = t.map(|v| m.vertices[v as usize]);
        let longest = dist(&c[0], &c[1])
            .max(dist(&c[1], &c[2]))
            .max(dist(&c[2], &c[0]));
        (longest / h).ceil().max(1.0) as usize
    };
    let count = |h: f64| -> usize {
        meshes
            .iter()
            .flat_map(|m| m.triangles.iter().map(move |t| (m, t)))
            .map(|(m, t)| {
                let n = divisions(m, t, h);
                (n + 1) * (n + 2) / 2
            })
            .sum()
    };
    let mut h = spacing;
    let n = count(h);
    if n > MAX_SAMPLES {
        h *= (n as f64 / MAX_SAMPLES as f64).sqrt();
    }
    let mut out = Vec::new();
    for m in meshes {
        for t in &m.triangles {
            let c = t.map(|v| m.vertices[v as usize]);
            let n = divisions(m, t, h);
            for i in 0..=n {
                for j in 0..=(n - i) {
                    let (a, b) = (i as f64 / n as f64, j as f64 / n as f64);
                    let w = 1.0 - a - b;
                    out.push([0, 1, 2].map(|k| w * c[0][k] + a * c[1][k] + b * c[2][k]));
                }
            }
        }
    }
    out
}

/// Points along `lines` no further apart than `spacing` (wider past [`MAX_SAMPLES`]).
pub fn sample_lines(lines: &[&[[f64; 3]]], spacing: f64) -> Vec<[f64; 3]> {
    let total: f64 = lines
        .iter()
        .flat_map(|l| l.windows(2))
        .map(|w| dist(&w[0], &w[1]))
        .sum();
    let h = spacing.max(total / MAX_SAMPLES as f64);
    let mut out = Vec::new();
    for l in lines {
        out.extend(l.first());
        for w in l.windows(2) {
            let n = (dist(&w[0], &w[1]) / h).ceil().max(1.0) as usize;
            for i in 1..=n {
                let t = i as f64 / n as f64;
                out.push([0, 1, 2].map(|k| w[0][k] + t * (w[1][k] - w[0][k])));
            }
        }
    }
    out
}

/// The size the refinements ask for at a point: the least over them of `size + slope · d`, the
/// slope no steeper than `max_slope`; infinite where there is none.
pub struct SizeNear {
    near: Vec<(RTree<[f64; 3]>, f64, f64)>,
}

impl SizeNear {
    pub fn new(refine: &[Refinement], max_slope: f64) -> SizeNear {
        SizeNear {
            near: refine
                .iter()
                .filter(|r| !r.points.is_empty())
                .map(|r| {
                    let slope = r.slope.min(max_slope).max(1e-9);
                    (RTree::bulk_load(r.points.clone()), r.size, slope)
                })
                .collect(),
        }
    }

    pub fn at(&self, x: &[f64; 3]) -> f64 {
        self.near
            .iter()
            .filter_map(|(tree, size, slope)| {
                tree.nearest_neighbor(*x).map(|p| size + slope * dist(p, x))
            })
            .fold(f64::INFINITY, f64::min)
    }

    pub fn is_empty(&self) -> bool {
        self.near.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_samples_are_no_further_apart_than_asked_and_cover_the_corners() {
        let m = TriMesh::new(
            vec![[0.0, 0.0, 0.0], [100.0, 0.0, 0.0], [0.0, 100.0, 0.0]],
            vec![[0, 1, 2]],
        );
        let pts = sample_surfaces(&[&m], 10.0);
        assert_eq!(
            pts.len(),
            16 * 17 / 2,
            "15 divisions of the 141 m hypotenuse"
        );
        for c in &m.vertices {
            assert!(pts.iter().any(|p| dist(p, c) < 1e-9));
        }
        // Any point of the triangle is within a spacing of a sample.
        for q in [[33.0, 33.0, 0.0], [5.0, 90.0, 0.0], [70.0, 1.0, 0.0]] {
            let d = pts
                .iter()
                .map(|p| dist(p, &q))
                .fold(f64::INFINITY, f64::min);
            assert!(d < 10.0, "{q:?} is {d} from the samples");
        }
    }

    #[test]
    fn line_samples_keep_the_ends_and_the_spacing() {
        let l = [[0.0, 0.0, 0.0], [95.0, 0.0, 0.0], [95.0, 50.0, 0.0]];
        let pts = sample_lines(&[&l], 10.0);
        assert_eq!(pts.first(), Some(&l[0]));
        assert_eq!(pts.last(), Some(&l[2]));
        assert!(pts.windows(2).all(|w| dist(&w[0], &w[1]) <= 10.0 + 1e-9));
    }

    #[test]
    fn the_size_near_grows_from_the_feature_no_faster_than_allowed() {
        let r = Refinement {
            points: vec![[0.0, 0.0, 0.0]],
            size: 10.0,
            slope: 0.5,
        };
        let f = SizeNear::new(&[r], 0.2);
        assert_eq!(f.at(&[0.0, 0.0, 0.0]), 10.0);
        assert!(
            (f.at(&[100.0, 0.0, 0.0]) - 30.0).abs() < 1e-9,
            "slope capped at 0.2"
        );
        assert_eq!(SizeNear::new(&[], 0.2).at(&[0.0; 3]), f64::INFINITY);
    }
}
