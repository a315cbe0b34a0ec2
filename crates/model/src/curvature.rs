//! How fine the curvature of the patches along a curve asks its nodes to be.
//!
//! A patch's surface mesh gets smaller elements where its support bends
//! (`surface_mesh::CurvatureSizes`: about 20° of normal turn per element), whatever the recipe's
//! size. Its border nodes are the nodes of its curves, fixed before the patch is meshed. A curve
//! discretized at the recipe's size alone then has segments many times longer than the
//! triangles beside it (a salt body's contact with a horizon at 250 m next to 25 m triangles),
//! and the thin triangles between the two are boundary faces the tet mesher cannot recover
//! without a node on them. So each curve point gets the size the curvature of every patch along
//! the curve asks for there, graded as a surface mesh grades it, and the curve is discretized at
//! no more than that.
//!
//! Only patches of smooth surfaces count (a smoothed support): a support as read is faceted at
//! the data's resolution, and its facets' kinks, taken as curvature, refined the curves of the
//! corpus's unsmoothed salt, lens and SCEC cases into worse tets (a lens host's dihedral fell
//! from 7° to 3.6°, a Tejon Pass block no longer meshed).
//! A curvature size above a patch's own diameter is not computed: no element of that patch is
//! larger. No recipe size enters this step.
//!
//! The sizes are then graded, together with the sizes narrow patches ask of their seams and
//! creases (`width`), over every curve of the model at that same growth, by distance in
//! space: a point gets no more than any curve point's size plus the growth times the distance
//! between them. Each patch's curvature sizes see that patch only, and the two borders of a
//! narrow patch can lie along patches that bend very differently (a strip left between two crease
//! curves at a lens's rim: one border at 4 m, the other at 30 m, 10 m apart); the surface mesh
//! between such borders can only be needles, which the tet mesher cannot recover. Graded, the
//! borders of any patch, and curves near each other anywhere, are at most the growth apart.

use crate::Curve;
use crate::regions::PatchIn;
use rayon::prelude::*;
use rstar::RTree;
use rstar::primitives::GeomWithData;
use surface_mesh::CurvatureSizes;

/// The sizes grade by this much per unit of distance, a surface mesh's steepest growth.
const SLOPE: f64 = surface_mesh::MAX_SURFACE_GROWTH - 1.0;
/// Sources of sizes within this factor of each other share one search tree (see [`graded`]).
const LEVEL_RATIO: f64 = 1.25;

/// Per curve, per point of its polyline, the least curvature size of the patches along it that
/// belong to a surface of `smooth` (infinite where none bends enough to ask for one), graded
/// together with the `narrow` places of every curve (`width::narrow_sizes`); and those places
/// graded alike. Every curve's list is empty when no patch is smooth and no place narrow.
pub fn curvature_sizes(
    curves: &[Curve],
    patches: &[PatchIn],
    smooth: &[String],
    narrow: &[Vec<[f64; 4]>],
) -> (Vec<Vec<f64>>, Vec<Vec<[f64; 4]>>) {
    let any_smooth = patches.iter().any(|p| smooth.contains(&p.surface));
    if !any_smooth && narrow.iter().all(Vec::is_empty) {
        return (
            vec![Vec::new(); curves.len()],
            vec![Vec::new(); curves.len()],
        );
    }
    let fields: Vec<Option<CurvatureSizes>> = patches
        .par_iter()
        .map(|p| {
            (smooth.contains(&p.surface))
                .then(|| CurvatureSizes::new(&p.mesh, p.mesh.bbox().diagonal()))
        })
        .collect();
    let own: Vec<Vec<f64>> = curves
        .iter()
        .map(|c| {
            let along: Vec<&CurvatureSizes> = (c.patches.iter())
                .filter_map(|&p| fields.get(p as usize)?.as_ref())
                .collect();
            (c.points.iter())
                .map(|x| along.iter().map(|f| f.at(x)).fold(f64::INFINITY, f64::min))
                .collect()
        })
        .collect();
    let sources: Vec<([f64; 3], f64)> = (curves.iter().zip(&own))
        .flat_map(|(c, h)| c.points.iter().copied().zip(h.iter().copied()))
        .chain(narrow.iter().flatten().map(|s| ([s[0], s[1], s[2]], s[3])))
        .collect();
    let at = graded(sources);
    let points = (curves.par_iter().zip(&own))
        .map(|(c, h)| (c.points.iter().zip(h)).map(|(p, &h)| at(p, h)).collect())
        .collect();
    let places = narrow
        .par_iter()
        .map(|n| {
            n.iter()
                .map(|s| [s[0], s[1], s[2], at(&[s[0], s[1], s[2]], s[3])])
                .collect()
        })
        .collect();
    (points, places)
}

/// The size field graded from `sources`: at a point with its own size `h`, the least of `h`
/// and, over every source `q`, `size(q) + SLOPE · |p − q|`. Exact: the sources are bucketed by
/// size into levels within `LEVEL_RATIO` of each other, each level searched nearest first until
/// no farther point can do better, the levels finest first until none can.
fn graded(sources: Vec<([f64; 3], f64)>) -> impl Fn(&[f64; 3], f64) -> f64 + Sync {
    type Source = GeomWithData<[f64; 3], f64>;
    let mut sources: Vec<Source> = (sources.into_iter())
        .filter(|(_, h)| h.is_finite())
        .map(|(p, h)| GeomWithData::new(p, h))
        .collect();
    sources.sort_by(|a, b| a.data.total_cmp(&b.data));
    let mut levels: Vec<(f64, RTree<Source>)> = Vec::new();
    let mut rest = sources.as_slice();
    while let Some(first) = rest.first() {
        let lo = first.data;
        let n = rest.partition_point(|s| s.data <= lo * LEVEL_RATIO);
        levels.push((lo, RTree::bulk_load(rest[..n].to_vec())));
        rest = &rest[n..];
    }
    move |p: &[f64; 3], mut best: f64| {
        for (lo, tree) in &levels {
            if *lo >= best {
                break;
            }
            for (q, d2) in tree.nearest_neighbor_iter_with_distance_2(*p) {
                let d = SLOPE * d2.sqrt();
                if lo + d >= best {
                    break;
                }
                best = best.min(q.data + d);
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom::TriMesh;

    /// A half cylinder of radius 150 m, faceted every 9°.
    fn half_cylinder() -> TriMesh {
        let (vs, ts) = test_support::shapes::half_cylinder(20);
        TriMesh::new(vs, ts)
    }

    /// [`graded`] from every curve point's own size, at every curve point.
    fn graded_at(curves: &[Curve], own: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let sources = (curves.iter().zip(own))
            .flat_map(|(c, h)| c.points.iter().copied().zip(h.iter().copied()))
            .collect();
        let at = graded(sources);
        (curves.iter().zip(own))
            .map(|(c, h)| (c.points.iter().zip(h)).map(|(p, &h)| at(p, h)).collect())
            .collect()
    }

    fn patch(name: &str, mesh: TriMesh) -> PatchIn {
        PatchIn {
            name: name.into(),
            surface: name.into(),
            mesh,
            chart_of: None,
        }
    }

    fn curve(patches: Vec<u32>, points: Vec<[f64; 3]>) -> Curve {
        Curve {
            name: "c".into(),
            surfaces: vec!["s".into()],
            patches,
            points,
            closed: false,
            clearance: Vec::new(),
            curvature_size: Vec::new(),
            narrow_size: Vec::new(),
        }
    }

    #[test]
    fn a_curve_near_a_finer_one_grades_from_it_at_a_surface_meshes_growth() {
        // A strip's two borders 10 m apart: one bent to 4 m, the other asking nothing.
        let fine = (0..=20).map(|i| [4.0 * i as f64, 0.0, 0.0]).collect();
        let coarse = vec![[0.0, 10.0, 0.0], [80.0, 10.0, 0.0]];
        let far = vec![[0.0, 1.0e4, 0.0]];
        let curves = [
            curve(vec![0], fine),
            curve(vec![1], coarse),
            curve(vec![2], far),
        ];
        let own = vec![vec![4.0; 21], vec![f64::INFINITY; 2], vec![3.0]];
        let g = graded_at(&curves, &own);
        assert_eq!(g[0], own[0], "a finer size is never raised");
        for h in &g[1] {
            assert!((h - (4.0 + SLOPE * 10.0)).abs() < 1e-12, "h = {h}");
        }
        assert_eq!(g[2], vec![3.0]);
    }

    #[test]
    fn the_grading_is_the_least_over_every_source_of_its_size_plus_slope_times_distance() {
        // Scattered points with sizes over five orders of magnitude, against the brute force.
        let mut rng = test_support::didactic::Rng(0x6772_6164_6564);
        let mut next = || 0.5 * (rng.unit() + 1.0);
        let mut curves = Vec::new();
        let mut own = Vec::new();
        for _ in 0..12 {
            let pts: Vec<[f64; 3]> = (0..40)
                .map(|_| [1.0e3 * next(), 1.0e3 * next(), 1.0e2 * next()])
                .collect();
            own.push(
                (0..40)
                    .map(|_| match next() {
                        u if u < 0.5 => f64::INFINITY,
                        u => 10f64.powf(5.0 * u - 2.0),
                    })
                    .collect::<Vec<f64>>(),
            );
            curves.push(curve(vec![0], pts));
        }
        let g = graded_at(&curves, &own);
        let all: Vec<([f64; 3], f64)> = (curves.iter().zip(&own))
            .flat_map(|(c, h)| c.points.iter().copied().zip(h.iter().copied()))
            .collect();
        for (c, gc) in curves.iter().zip(&g) {
            for (p, h) in c.points.iter().zip(gc) {
                let brute = (all.iter())
                    .map(|(q, hq)| hq + SLOPE * geom::predicates::dist(p, q))
                    .fold(f64::INFINITY, f64::min);
                assert_eq!(*h, brute);
            }
        }
    }

    #[test]
    fn a_curve_takes_the_finest_curvature_size_of_its_smooth_patches_and_none_from_flat_ones() {
        let flat = TriMesh::new(
            vec![[150.0, 0.0, 0.0], [1150.0, 0.0, 0.0], [150.0, 600.0, 0.0]],
            vec![[0, 1, 2]],
        );
        let patches = [patch("tube", half_cylinder()), patch("plane", flat)];
        // The straight border the two patches share, along the cylinder's foot.
        let foot = vec![[150.0, 0.0, 0.0], [150.0, 300.0, 0.0], [150.0, 600.0, 0.0]];
        let curves = [
            curve(vec![0, 1], foot.clone()),
            curve(vec![1], foot),
            curve(vec![0], vec![[0.0, 0.0, 150.0], [0.0, 600.0, 150.0]]),
        ];
        let smooth = ["tube".to_string(), "plane".to_string()];
        let sizes = curvature_sizes(&curves, &patches, &smooth, &[]).0;
        // Radius 150 m: about 0.35 × 150 m, as the tube's own surface mesh refines.
        for h in sizes[0].iter().chain(&sizes[2]) {
            assert!(*h > 40.0 && *h < 80.0, "h = {h}");
        }
        // The plane asks nothing, but a curve where the tube's is gets the tube's sizes.
        assert_eq!(sizes[1], sizes[0]);
        // A support as read (not smoothed) asks nothing of its curves.
        let as_read = curvature_sizes(&curves, &patches, &["plane".to_string()], &[]).0;
        assert!(
            as_read[0]
                .iter()
                .chain(&as_read[2])
                .all(|h| *h == f64::INFINITY)
        );
        assert!((curvature_sizes(&curves, &patches, &[], &[]).0.iter()).all(Vec::is_empty));
    }
}
