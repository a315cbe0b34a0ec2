//! Regions meshed flat along their layer: `[mesh.regions] R = { layers = n, aspect = s }`.
//!
//! Isotropic elements across a thin layer are many: `n` across a 35 m reservoir are 12 m wide
//! all over it. With an aspect the region is meshed in a space stretched across the layer by
//! `s` (`tet_mesh::stretch`), so its elements are about `s` times as wide as they are thick, and
//! the patches facing across the layer (its top and base: within 45° of its normal on average)
//! are meshed `s` times coarser than the count across asks, up to the region's own size. Its
//! sides (faults, the box: the strips across the layer) are meshed in the same stretched space
//! when only regions with an aspect bound them, so the tets along them are isotropic there too;
//! a side shared with an isotropic region stays isotropic. The curves keep the count's size:
//! their nodes set the elements across the layer at its edges. The layer's normal is measured
//! on the model (the dominant direction of its boundary's normals), so it is in the keys.
//!
//! A solver sees these elements as a flow with a vertical permeability `s²` times below the
//! horizontal one sees isotropic ones: stretched by `√(kh / kv)` the equations of such a layer are
//! isotropic, and so are its elements.

use super::ModelData;
use crate::recipe::Recipe;
use geom::TriMesh;
use tet_mesh::stretch::{Stretch, layer_normal};

/// A patch faces across a layer when its normals lie within 45° of the layer's on average.
const ACROSS_COS: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// A region meshed stretched across its layer.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// The layer's unit normal, measured on the model.
    pub normal: [f64; 3],
    /// `aspect`, as written.
    pub aspect: f64,
}

impl Layer {
    /// The stretch about `origin` (the region's first vertex keeps coordinates small).
    pub fn stretch(&self, origin: [f64; 3]) -> Stretch {
        Stretch {
            axis: self.normal,
            factor: self.aspect,
            origin,
        }
    }
}

/// The `aspect` of region `name`, when it asks for one above 1.
pub fn aspect_of(recipe: &Recipe, name: &str) -> Option<f64> {
    let a = recipe.mesh.regions.get(name)?.aspect?;
    (a > 1.0).then_some(a)
}

/// Per region of `model` (in its order), its layer when the recipe gives it an aspect.
pub fn layers(recipe: &Recipe, model: &ModelData) -> Vec<Option<Layer>> {
    (model.regions.regions.iter())
        .map(|r| {
            let aspect = aspect_of(recipe, &r.name)?;
            let mut patches: Vec<u32> = r.sides.iter().map(|f| f.patch).collect();
            patches.dedup();
            let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
            for p in patches {
                let mesh = &model.patches[p as usize].mesh;
                let base = vertices.len() as u32;
                vertices.extend(&mesh.vertices);
                triangles.extend(mesh.triangles.iter().map(|t| t.map(|i| i + base)));
            }
            let normal = layer_normal(&vertices, &triangles)?;
            Some(Layer { normal, aspect })
        })
        .collect()
}

/// Per patch of `model`, the layer whose stretched space it is meshed in: a side of a region with
/// an aspect (not facing across its layer) that only regions with an aspect bound (the box's
/// sides, a fault between two such layers), meshed in the first one's space (model order). A
/// side shared with a region meshed isotropically stays isotropic: flat triangles on its
/// boundary would leave that region's mesher no room.
pub fn side_layers(model: &ModelData, layers: &[Option<Layer>]) -> Vec<Option<Layer>> {
    let mut out: Vec<Option<Layer>> = vec![None; model.patches.len()];
    let mut shared = vec![false; model.patches.len()];
    for (r, layer) in model.regions.regions.iter().zip(layers) {
        for f in &r.sides {
            let p = f.patch as usize;
            match layer {
                None => shared[p] = true,
                Some(l) if out[p].is_none() && !faces_across(&model.patches[p].mesh, &l.normal) => {
                    out[p] = Some(l.clone());
                }
                Some(_) => {}
            }
        }
    }
    for (o, s) in out.iter_mut().zip(shared) {
        if s {
            *o = None;
        }
    }
    out
}

/// Whether the patch `p` of `model` is meshed coarser for `layer`: it faces across it, or it is
/// a side meshed in a stretched space (`sides`, from [`side_layers`]).
pub fn widened(model: &ModelData, p: usize, layer: &Layer, sides: &[Option<Layer>]) -> bool {
    sides[p].is_some() || faces_across(&model.patches[p].mesh, &layer.normal)
}

/// Whether `mesh` faces across the layer of unit normal `normal` (its top or base, not a side).
pub fn faces_across(mesh: &TriMesh, normal: &[f64; 3]) -> bool {
    let normals = mesh.unit_normals();
    let (mut along, mut area) = (0.0, 0.0);
    for (t, n) in normals.iter().enumerate() {
        let a = geom::trimesh::triangle_area(mesh.corners(t));
        along += a * (0..3).map(|k| n[k] * normal[k]).sum::<f64>().abs();
        area += a;
    }
    area > 0.0 && along >= ACROSS_COS * area
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_gently_dipping_sheet_faces_across_a_flat_layer_and_a_steep_fault_does_not() {
        let sheet = |dz: f64| {
            TriMesh::new(
                vec![
                    [0.0, 0.0, 0.0],
                    [100.0, 0.0, dz],
                    [100.0, 100.0, dz],
                    [0.0, 100.0, 0.0],
                ],
                vec![[0, 1, 2], [0, 2, 3]],
            )
        };
        let up = [0.0, 0.0, 1.0];
        assert!(faces_across(&sheet(10.0), &up));
        assert!(faces_across(&sheet(90.0), &up));
        assert!(!faces_across(&sheet(110.0), &up));
        assert!(!faces_across(&sheet(173.0), &up));
    }
}
