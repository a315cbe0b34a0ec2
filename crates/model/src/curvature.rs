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

use crate::Curve;
use crate::regions::PatchIn;
use rayon::prelude::*;
use surface_mesh::CurvatureSizes;

/// Per curve, per point of its polyline, the least curvature size of the patches along it that
/// belong to a surface of `smooth` (infinite where none bends enough to ask for one); every
/// curve's list is empty when no patch does.
pub fn curvature_sizes(curves: &[Curve], patches: &[PatchIn], smooth: &[String]) -> Vec<Vec<f64>> {
    if !patches.iter().any(|p| smooth.contains(&p.surface)) {
        return vec![Vec::new(); curves.len()];
    }
    let fields: Vec<Option<CurvatureSizes>> = patches
        .par_iter()
        .map(|p| {
            (smooth.contains(&p.surface))
                .then(|| CurvatureSizes::new(&p.mesh, p.mesh.bbox().diagonal()))
        })
        .collect();
    curves
        .iter()
        .map(|c| {
            let along: Vec<&CurvatureSizes> = (c.patches.iter())
                .filter_map(|&p| fields.get(p as usize)?.as_ref())
                .collect();
            (c.points.iter())
                .map(|x| along.iter().map(|f| f.at(x)).fold(f64::INFINITY, f64::min))
                .collect()
        })
        .collect()
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
        let sizes = curvature_sizes(&curves, &patches, &smooth);
        // Radius 150 m: about 0.35 × 150 m, as the tube's own surface mesh refines.
        for h in sizes[0].iter().chain(&sizes[2]) {
            assert!(*h > 40.0 && *h < 80.0, "h = {h}");
        }
        assert!(sizes[1].iter().all(|h| *h == f64::INFINITY), "{sizes:?}");
        // A support as read (not smoothed) asks nothing of its curves.
        let as_read = curvature_sizes(&curves, &patches, &["plane".to_string()]);
        assert!(
            as_read[0]
                .iter()
                .chain(&as_read[2])
                .all(|h| *h == f64::INFINITY)
        );
        assert!(
            curvature_sizes(&curves, &patches, &[])
                .iter()
                .all(Vec::is_empty)
        );
    }
}
