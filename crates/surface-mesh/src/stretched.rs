//! A patch meshed in a stretched space (`geom::stretch`): the sides of a layer meshed flat
//! along it. Isotropic triangles there are, back in the model, `factor` times as wide along the
//! layer as they are across it, matching the tets the layer is meshed with in the same space.
//! Every given point (loop, constraint and isolated nodes) is restored bit for bit, so the
//! neighbouring meshes still share them; only the generated nodes are mapped back, onto the
//! support the affine map keeps.

use crate::{
    PatchInput, SurfaceMeshError, SurfaceMeshOutput, SurfaceSize, mesh_patch_with_progress,
};
use geom::refine::Refinement;
use geom::stretch::Stretch;
use geom::{Tolerances, TriMesh, point_key};
use std::collections::BTreeMap;

/// [`mesh_patch_with_progress`] in the space `stretch` makes: `size` and `refine` are taken
/// there as they are.
pub fn mesh_patch_stretched(
    input: &PatchInput,
    size: &SurfaceSize,
    tolerances: &Tolerances,
    refine: &[Refinement],
    stretch: &Stretch,
    progress: &dyn Fn(u64, u64),
) -> Result<SurfaceMeshOutput, SurfaceMeshError> {
    let mut given: BTreeMap<[u64; 3], [f64; 3]> = BTreeMap::new();
    let mut map = |p: &[f64; 3]| {
        let q = stretch.apply(p);
        given.entry(point_key(&q)).or_insert(*p);
        q
    };
    let line = |l: &Vec<[f64; 3]>, map: &mut dyn FnMut(&[f64; 3]) -> [f64; 3]| {
        l.iter().map(&mut *map).collect::<Vec<_>>()
    };
    let loops = input.loops.iter().map(|l| line(l, &mut map)).collect();
    let constraints = (input.constraints.iter())
        .map(|l| line(l, &mut map))
        .collect();
    let points = line(&input.points, &mut map);
    let stretched = PatchInput {
        name: input.name.clone(),
        support: TriMesh::new(
            input
                .support
                .vertices
                .iter()
                .map(|p| stretch.apply(p))
                .collect(),
            input.support.triangles.clone(),
        ),
        loops,
        constraints,
        points,
        facets: (input.facets.iter())
            .map(|&(t, n)| (t, stretch.normal(&n)))
            .collect(),
    };
    let refine: Vec<Refinement> = (refine.iter())
        .map(|r| Refinement {
            points: r.points.iter().map(|p| stretch.apply(p)).collect(),
            ..r.clone()
        })
        .collect();
    let mut out = mesh_patch_with_progress(&stretched, size, tolerances, &refine, progress)?;
    for p in &mut out.nodes {
        *p = match given.get(&point_key(p)) {
            Some(original) => *original,
            None => stretch.undo(p),
        };
    }
    Ok(out)
}
