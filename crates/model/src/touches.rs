//! Where two surfaces touch at isolated points (a dome's apex exactly on the horizon above: the
//! intersection's `touches`, points on no curve). Each such point lies on one patch of each
//! surface, and is handed to both patches' surface meshes as a fixed node: the FE surfaces then
//! touch where the surfaces do, and the apex, a feature point of the dome, is kept instead of
//! cut off by a chord. A point on a patch's border (on a curve) is left to the curve.

use crate::regions::PatchIn;
use crate::wells::inside_patch;

/// Per touch point, every patch whose support holds it away from the border, as (patch index,
/// point), in patch order then point order.
pub fn touch_points(patches: &[PatchIn], points: &[[f64; 3]]) -> Vec<(u32, [f64; 3])> {
    let mut out = Vec::new();
    for (i, patch) in patches.iter().enumerate() {
        for p in points {
            if inside_patch(p, patch) && !out.contains(&(i as u32, *p)) {
                out.push((i as u32, *p));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom::TriMesh;

    fn square(name: &str, z: f64) -> PatchIn {
        let v = vec![[0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z]];
        PatchIn {
            name: name.into(),
            surface: name.into(),
            mesh: TriMesh::new(v, vec![[0, 1, 2], [0, 2, 3]]),
            chart_of: None,
        }
    }

    #[test]
    fn a_touch_inside_a_patch_or_on_its_inner_edge_is_its_point_and_one_on_its_border_is_not() {
        let patches = [square("a", 0.0), square("b", 1.0)];
        let points = [
            [0.25, 0.5, 0.0],
            [0.5, 0.5, 0.0],
            [1.0, 0.5, 0.0],
            [0.5, 0.5, 0.5],
        ];
        assert_eq!(
            touch_points(&patches, &points),
            [(0, [0.25, 0.5, 0.0]), (0, [0.5, 0.5, 0.0])],
            "inside, on the diagonal; not on the border, nor off the plane"
        );
    }
}
