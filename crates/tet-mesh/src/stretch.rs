//! Anisotropic meshing of a layer by an affine stretch across it.
//!
//! A layer thin against its extent wants elements flat along it: several across its thickness,
//! wide along it. The mesher itself is isotropic, so the region is meshed in a space stretched
//! along the layer's normal by the aspect `s`: there an isotropic mesh of size `h` is, back in
//! the model, `h` wide and `h / s` thick. The stretch is affine, so it keeps every incidence and
//! every orientation: the boundary triangles stay the region's faces, and a tet positively
//! oriented in the stretched space is so in the model. The input vertices are restored bit for
//! bit (the neighbours' meshes share them) and only the new nodes are mapped back; the result is
//! verified exactly against the unstretched input, as every region mesh is.
//!
//! The direction is one for the region: the dominant eigenvector of its boundary's area-weighted
//! normal tensor, which for a layer is the normal of its top and base. A folded layer whose
//! limbs face different ways gets one compromise direction (its elements are then flat along the
//! mean of its limbs, still valid): the stretch is a global affine map, not a metric field.

pub use geom::stretch::Stretch;

use geom::predicates::{cross, dot, sub};

use crate::{
    RegionInput, SizeField, TetMeshError, TetMeshOptions, TetMeshOutput, measured_stats,
    mesh_region_with_progress, quality, verify,
};

/// The dominant direction of the area-weighted normals of `boundary` (either sign; the one with
/// a non-negative largest component first in x, y, z order), by power iteration from a fixed
/// start (the tensor's largest row): for a layer, its normal. `None` for a boundary with no area.
pub fn layer_normal(vertices: &[[f64; 3]], boundary: &[[u32; 3]]) -> Option<[f64; 3]> {
    let mut m = [[0.0f64; 3]; 3];
    for t in boundary {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        let n = cross(&sub(&b, &a), &sub(&c, &a));
        let len = dot(&n, &n).sqrt();
        if len == 0.0 {
            continue;
        }
        // |n| n̂ n̂ᵀ: area-weighted (twice the area) and blind to the normal's sign.
        for (i, row) in m.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x += n[i] * n[j] / len;
            }
        }
    }
    // Start from the tensor's largest row: it has a share of the dominant direction.
    let norm = |r: &[f64; 3]| r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    let mut x = m
        .iter()
        .copied()
        .fold([0.0; 3], |a, r| if norm(&r) > norm(&a) { r } else { a });
    for _ in 0..200 {
        let y = [0, 1, 2].map(|i| (0..3).map(|j| m[i][j] * x[j]).sum::<f64>());
        let len = (y[0] * y[0] + y[1] * y[1] + y[2] * y[2]).sqrt();
        if len == 0.0 || !len.is_finite() {
            return None;
        }
        x = y.map(|c| c / len);
    }
    let lead = x
        .iter()
        .copied()
        .fold(0.0f64, |a, c| if c.abs() > a.abs() { c } else { a });
    Some(if lead < 0.0 { x.map(|c| -c) } else { x })
}

/// The region meshed in the space `stretch` makes (sizes and refinements taken there as they
/// are), its new nodes mapped back; statistics measured in the model, as for any region.
pub fn mesh_region_stretched(
    input: &RegionInput,
    size: &SizeField,
    opts: &TetMeshOptions,
    stretch: &Stretch,
    progress: &dyn Fn(u64, u64),
) -> Result<TetMeshOutput, TetMeshError> {
    let stretched = RegionInput {
        vertices: input.vertices.iter().map(|p| stretch.apply(p)).collect(),
        ..input.clone()
    };
    let mut sizes = size.clone();
    for r in &mut sizes.refine {
        r.points = r.points.iter().map(|p| stretch.apply(p)).collect();
    }
    let mut out = mesh_region_with_progress(&stretched, &sizes, opts, progress)?;
    let n = input.vertices.len();
    out.nodes[..n].copy_from_slice(&input.vertices);
    for p in &mut out.nodes[n..] {
        *p = stretch.undo(p);
    }
    let kept = out.stats.clone();
    out.stats = measured_stats(&out, n, kept.backtracks, None);
    out.stats.recovered_faces = kept.recovered_faces;
    out.stats.flipped_faces = kept.flipped_faces;
    out.stats.line_nodes = kept.line_nodes;
    out.stats.line_splits = kept.line_splits;
    out.stats.line_flips = kept.line_flips;
    out.stats.fallback = kept.fallback;
    verify(input, &out)?;
    Ok(out)
}

/// The least mean ratio and the least dihedral angle (degrees) of `tets` over `nodes` seen in
/// the space `stretch` makes: how good a layer's flat elements are for what they were made for.
pub fn stretched_quality(nodes: &[[f64; 3]], tets: &[[u32; 4]], stretch: &Stretch) -> (f64, f64) {
    let (mut ratio, mut cos) = (f64::INFINITY, f64::NEG_INFINITY);
    for t in tets {
        let [a, b, c, d] = t.map(|i| stretch.apply(&nodes[i as usize]));
        ratio = ratio.min(quality::mean_ratio(&a, &b, &c, &d));
        cos = cos.max(quality::largest_dihedral_cosine(&a, &b, &c, &d));
    }
    if tets.is_empty() {
        (0.0, 0.0)
    } else {
        (ratio, quality::dihedral_deg(cos))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_layer_normal_of_a_flat_slab_is_its_thin_direction_whichever_way_it_lies() {
        // A box 1000 × 800 × 30, then the same box with its thin side along x.
        for (dims, want) in [
            ([1000.0, 800.0, 30.0], [0.0, 0.0, 1.0]),
            ([30.0, 800.0, 1000.0], [1.0, 0.0, 0.0]),
        ] {
            let (v, t) = box_mesh(dims);
            let n = layer_normal(&v, &t).expect("a normal");
            for k in 0..3 {
                assert!((n[k] - want[k]).abs() < 1e-9, "{n:?} for {dims:?}");
            }
        }
        assert_eq!(layer_normal(&[[0.0; 3]; 3], &[[0, 1, 2]]), None);
    }

    /// The closed surface of an axis-aligned box of sides `d` at UTM-like coordinates.
    fn box_mesh(d: [f64; 3]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        let lo = [500_000.0, 7_000_000.0, -2000.0];
        test_support::shapes::cuboid(lo, [0, 1, 2].map(|k| lo[k] + d[k]))
    }
}
