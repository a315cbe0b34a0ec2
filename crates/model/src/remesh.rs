//! Re-triangulating one imported surface at a size, whatever its shape: a closed body with no
//! border at all (a lens, a salt body), a tube, a box TSurf folded round the box's edges, a
//! surface of several TFACEs.
//!
//! Decisions and why:
//! - The surface is cut as the model cuts it: at its TFACE borders, at its creases
//!   (`Tolerances::crease_angle_deg`) and into charts where a piece does not face one way
//!   (`Tolerances::chart_angle_deg`). The pieces' borders are found as the model's curves
//!   (`build_topology`, corners where the border turns by more than the kink angle), each curve
//!   is discretized once, and each piece is meshed by the surface mesher on the old support. Met
//!   whole, a closed surface has no border loop to flatten (every closed body of the geology
//!   corpus and every TKC kimberlite failed so), and its creases and TFACE borders, with no
//!   constraint along them, were not kept.
//! - The meshes are welded by exact coordinates: every node two pieces share comes bit for bit
//!   from one curve's discretization, so nothing is merged by distance.
//! - Kept vertices (a file's corner marks) stay bit for bit: a curve end already, else a pin of
//!   the curve through it, else a fixed node of the piece holding it.
//! - One size everywhere, on the curves as inside, with the fewest segments every border loop
//!   needs (three nodes), and a curve's chords within half its clearance from the other curves
//!   of its pieces, as the model's curves are discretized.
//! - Each new triangle keeps the TFACE of the piece it meshes, so the surface's parts survive.

use crate::assemble::{Welder, patch_input};
use crate::discretize::{Grading, Pin, Subdivision, discretize_pinned};
use crate::intersect::split::{SplitSurface, split_model};
use crate::patches::{Charting, Patch, components, creased};
use crate::regions::PatchIn;
use crate::{ModelError, ModelTopology, build_topology, point_key};
use geom::{Tolerances, TriMesh};
use rayon::prelude::*;
use std::collections::BTreeSet;
use surface_mesh::{SurfaceSize, mesh_patch_with};

/// Growth of the sizes inside a piece (the surface mesher grades at most its own rate anyway).
const GROWTH: f64 = 1.3;

/// A surface re-triangulated: its mesh and each triangle's part (TFACE).
pub struct Remeshed {
    pub mesh: TriMesh,
    pub parts: Vec<u32>,
}

/// `mesh` (surface `name`, its triangles' parts `parts`, empty for one part) re-triangulated at
/// `size`, its vertices `keep` kept bit for bit (see the module doc).
pub fn remesh(
    name: &str,
    mesh: &TriMesh,
    parts: &[u32],
    keep: &[u32],
    size: f64,
    tol: &Tolerances,
) -> Result<Remeshed, ModelError> {
    if !(size > 0.0 && size.is_finite()) {
        return Err(ModelError::new(format!("invalid size {size}"), None));
    }
    let split = (split_model(&[(name, mesh)], &[])
        .map_err(|e| ModelError::new(e.to_string(), None))?)
    .pop()
    .ok_or_else(|| ModelError::new(format!("`{name}` did not split"), None))?;
    let pieces = pieces(name, mesh, parts, &split, tol);
    let piece_parts: Vec<u32> = pieces.iter().map(|&(_, _, part)| part).collect();
    let input: Vec<PatchIn> = (pieces.into_iter())
        .map(|(p, chart_of, _)| PatchIn {
            name: p.name,
            surface: name.to_string(),
            mesh: p.mesh,
            chart_of,
        })
        .collect();
    let topo = build_topology(&input, tol)?;
    let kept: Vec<[f64; 3]> = (keep.iter())
        .filter_map(|&v| mesh.vertices.get(v as usize).copied())
        .collect();
    let nodes = curve_nodes(&topo, &kept, size)?;
    let on_curves: BTreeSet<[u64; 3]> = nodes.iter().flatten().map(point_key).collect();
    let meshes: Vec<TriMesh> = (input.par_iter().zip(&topo.patches))
        .map(|(piece, boundary)| {
            let get = |c: u32| nodes.get(c as usize).map(Vec::as_slice);
            let mut pi = patch_input(&piece.name, &piece.mesh, boundary, &get)?;
            pi.points = fixed_inside(&piece.mesh, &kept, &on_curves);
            let sizes = SurfaceSize {
                size,
                min_size: 0.0,
                max_size: size,
                growth: GROWTH,
            };
            let out = mesh_patch_with(&pi, &sizes, tol).map_err(|e| {
                ModelError::new(format!("piece `{}`: {}", piece.name, e.message), e.at)
            })?;
            Ok(TriMesh::new(out.nodes, out.triangles))
        })
        .collect::<Result<_, ModelError>>()?;
    Ok(weld(&meshes, &piece_parts))
}

/// The pieces of `split` (of `mesh`, surface `name`): cut at TFACE borders and creases, then
/// into charts; each with the name of the patch it is a chart of, if it is one, and its part.
fn pieces(
    name: &str,
    mesh: &TriMesh,
    parts: &[u32],
    split: &SplitSurface,
    tol: &Tolerances,
) -> Vec<(Patch, Option<String>, u32)> {
    let normals = geom::facets::facet_normals(mesh, tol);
    let crease = creased(split, &normals, tol.crease_angle_deg);
    let part = |t: u32| {
        let original = split.parent.get(t as usize).copied().unwrap_or(0);
        parts.get(original as usize).copied().unwrap_or(0)
    };
    let cut = |(t, u): (u32, u32)| part(t) != part(u) || crease((t, u));
    let mut charting = Charting::new(mesh, &normals, tol.chart_angle_deg);
    let mut out = Vec::new();
    for patch in components(name, split, cut) {
        let whole = patch.name.clone();
        // Cut at every TFACE border, a patch lies in one part.
        let in_part = patch.triangles.first().map_or(0, |&t| part(t));
        let charts = charting.cut(patch, split);
        let cut_up = charts.len() > 1;
        out.extend((charts.into_iter()).map(|c| (c, cut_up.then(|| whole.clone()), in_part)));
    }
    out
}

/// Each curve of `topo` discretized at `size`, through every point of `kept` on its polyline.
fn curve_nodes(
    topo: &ModelTopology,
    kept: &[[f64; 3]],
    size: f64,
) -> Result<Vec<Vec<[f64; 3]>>, ModelError> {
    let kept: BTreeSet<[u64; 3]> = kept.iter().map(point_key).collect();
    let rule = Subdivision::Size {
        size,
        ratio: 1.0,
        grading: Grading::Geometric,
    };
    (topo.curves.iter().zip(topo.min_segments()))
        .map(|(c, least)| {
            let pins: Vec<Pin> = (c.points.iter().enumerate())
                .filter(|(_, p)| kept.contains(&point_key(p)))
                .map(|(i, p)| Pin {
                    segment: (i.min(c.points.len().saturating_sub(2))) as u32,
                    point: *p,
                })
                .collect();
            let fail = |e| {
                ModelError::new(
                    format!("curve `{}`: {e}", c.name),
                    c.points.first().copied(),
                )
            };
            let nodes =
                discretize_pinned(&c.points, &rule, &c.clearance, None, &pins).map_err(fail)?;
            if nodes.len() > least as usize {
                return Ok(nodes);
            }
            discretize_pinned(
                &c.points,
                &Subdivision::Count(least),
                &c.clearance,
                None,
                &pins,
            )
            .map_err(fail)
        })
        .collect()
}

/// The points of `kept` that are vertices of `piece` and not curve nodes: fixed nodes inside it.
fn fixed_inside(
    piece: &TriMesh,
    kept: &[[f64; 3]],
    on_curves: &BTreeSet<[u64; 3]>,
) -> Vec<[f64; 3]> {
    let here: BTreeSet<[u64; 3]> = piece.vertices.iter().map(point_key).collect();
    (kept.iter())
        .filter(|p| here.contains(&point_key(p)) && !on_curves.contains(&point_key(p)))
        .copied()
        .collect()
}

/// The pieces' meshes welded into one, each triangle with its piece's part.
fn weld(meshes: &[TriMesh], piece_parts: &[u32]) -> Remeshed {
    let mut welder = Welder::default();
    let mut triangles = Vec::new();
    let mut parts = Vec::new();
    for (m, &part) in meshes.iter().zip(piece_parts) {
        let ids: Vec<u32> = m.vertices.iter().map(|p| welder.id(p)).collect();
        for t in &m.triangles {
            triangles.push(t.map(|v| ids[v as usize]));
            parts.push(part);
        }
    }
    Remeshed {
        mesh: TriMesh::new(welder.into_points(), triangles),
        parts,
    }
}
