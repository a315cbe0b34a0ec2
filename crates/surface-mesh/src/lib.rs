//! Stage `surface_mesh`: the finite-element triangle mesh of one patch (seed §2.2 and §5). It uses
//! exactly the given curve nodes, lies on the patch's support surface, and has well-shaped
//! triangles; the same mesher regenerates poor imported supports (`retriangulate`).
//!
//! Method (the brief's option B, chosen because it needs no height-field assumption and lets every
//! topological decision be an exact 2D predicate):
//! 1. `param`: flatten the support triangulation — projection onto its mean plane when that is
//!    exactly fold-free, mended where it turns a few triangles over (`relax`), else a Tutte
//!    embedding — and index it with R-trees (`support`).
//! 2. `input`: number the given loop and constraint nodes and the given points (isolated nodes,
//!    where wells cross the patch); map each to the plane by projecting it onto the support (it
//!    must lie within `Tolerances::support_distance_rel` × its segment length, or for a point its
//!    local size); check exactly that loops and constraints do not cross (`segments`) and that no
//!    point lies on them (`points`).
//! 3. `cdt`: constrained Delaunay triangulation of those nodes and segments; inside = odd number of
//!    loop crossings from outside (so loops may come in either orientation and any order; the
//!    output is oriented like the support regardless). The points are inserted last, as vertices
//!    with no segment; each must land in an inside triangle.
//! 4. `refine` (geometric pass): frontal Delaunay point insertion with sizes from `size` (graded
//!    from the boundary discretization and the points, bounded by the support's curvature)
//!    measured in 3D, placed in the flattening's local metric; new points are mapped onto the
//!    support through it. The given points are vertices from the start: new points keep the
//!    same distance from them as from any other vertex (`refine`'s spacing rule).
//! 5. `smooth` (topological pass + smoothing): 3D quality flips and smoothing towards the
//!    neighbours' mean or the fan's equilateral apexes, with pull-back onto the support, guarded
//!    by exact orientation tests in the plane. Given nodes, points included, never move.
//!
//! Sizes grade at most `MAX_SURFACE_GROWTH` (1.15) per element on a surface, whatever growth the
//! recipe allows for volumes: the seed's Table 1 judges surface triangles, and grading is what
//! costs them quality (see the constant).
//! 6. `verify`: exact topological and geometric validity; `mesh_patch` never returns a mesh that
//!    fails it.
//!
//! Progress (`geom::progress`, [`mesh_patch_with_progress`]): the bar is shared as the phases'
//! times were on the didactic model's refinement (d) patches (`BAR_SHARES`); refinement reports
//! the points it inserted of those `refine::expected_points` expects, smoothing its rounds.
//!
//! Distance to the support: every generated node is a barycentric combination of one support
//! triangle's corners, so it lies on the support up to rounding; `mesh_patch` checks it against
//! `Tolerances::default().support_distance_rel` (1e-6) × the node's mean edge length.

#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::needless_range_loop)]

mod cdt;
mod input;
mod order;
mod param;
mod points;
pub mod quality;
mod refine;
mod refine_support;
mod relax;
mod retriangulate;
mod segments;
mod size;
mod smooth;
mod sparse;
mod stretched;
mod support;
mod tutte;
mod unfold;
mod verify;

pub use stretched::mesh_patch_stretched;

use cdt::{CONSTRAINT, Cdt, CdtError, LOOP, NONE};
use geom::predicates::dist;
use geom::progress::{Meter, Span};
use geom::refine::Refinement;
use geom::{Tolerances, TriMesh};
use input::{GivenNodes, given_nodes};
use size::SizeField;
use support::Support;

pub use param::{projected_border_conflict, projects_one_to_one};
pub use refine_support::{MAX_LEVELS, MAX_PASSES, Smoothed, SupportSmoothing, refine_smooth};
pub use retriangulate::{retriangulate, retriangulate_keeping};
pub use size::CurvatureSizes;

/// One patch to mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchInput {
    pub name: String,
    /// The patch's support triangulation (may be coarse, irregular, not a height field).
    pub support: TriMesh,
    /// Closed boundary loops: node coordinates exactly as discretized (first node NOT repeated at
    /// the end). Outer loop and holes in any order and either orientation: inside is decided by
    /// the parity of loop crossings, exactly. Loops may touch at a node (the patch is pinched
    /// there): the node is given once and meshed with one fan per side.
    pub loops: Vec<Vec<[f64; 3]>>,
    /// Internal constraint polylines (open), each node exactly as given; must appear as mesh edges.
    pub constraints: Vec<Vec<[f64; 3]>>,
    /// Isolated points strictly inside the patch (where wells cross it), each exactly as given;
    /// each becomes a mesh node, bit-identical, with no edge imposed on it. A point bit-identical
    /// to a loop or constraint node, or to an earlier point, is that node. A point must lie on the
    /// support (within `Tolerances::support_distance_rel` × its local size, the target size
    /// clamped to [`min_size`, `max_size`]) and strictly inside the patch: a point outside it, or
    /// on a loop or constraint segment away from its nodes (exactly in the flattening, or within
    /// that tolerance in 3D), is an error naming the point.
    pub points: Vec<[f64; 3]>,
    /// Support triangles that stand for another direction than their own, with that unit normal
    /// (caps and needles, as `geom::facets` decides on the imported surface): the support's
    /// curvature is measured on these normals, so a cap's wall asks for no small elements.
    /// Empty: every triangle stands for itself.
    pub facets: Vec<(u32, [f64; 3])>,
}

/// Element sizes (model units): target `size`, clamped to [`min_size`, `max_size`], growing away
/// from the boundary discretization by at most `growth` (≥ 1) per unit length, and never faster
/// than [`MAX_SURFACE_GROWTH`] on a surface.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceSize {
    pub size: f64,
    pub min_size: f64,
    pub max_size: f64,
    pub growth: f64,
}

/// The mesh of one patch.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceMeshOutput {
    /// The given loop nodes (loop after loop, in order, a node where loops touch at its first
    /// visit only), then the constraint nodes not already given (in order), then the points not
    /// already given (in order), all bit-identical; then the generated interior nodes.
    pub nodes: Vec<[f64; 3]>,
    /// Oriented like the support.
    pub triangles: Vec<[u32; 3]>,
}

/// A patch that cannot be meshed: its name, what went wrong, and where.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("surface mesh of patch '{patch}': {message}{}", geom::at_suffix(.at))]
pub struct SurfaceMeshError {
    pub patch: String,
    pub message: String,
    pub at: Option<[f64; 3]>,
}

/// The fastest size growth a surface mesh uses (ratio per element), whatever `SurfaceSize::growth`
/// allows (the recipe's `mesh.growth`, 1.3 by default, is meant for volumes). A triangle spanning
/// a size change of g per element is distorted by about g² in c/c*: on the seed's didactic
/// refinements (25-100 m reservoir curves, 200 m elsewhere) the mean c/c* of all surface
/// triangles is 1.044 at 1.3, 1.033 at 1.2 and 1.028 at 1.15 (Gmsh's frontal-Delaunay on a
/// graded square: 1.048 at 1.3, 1.030 at 1.15); the seed's Table 1 asks for 1.03 at (d).
pub const MAX_SURFACE_GROWTH: f64 = 1.15;

/// The most points the sizes may ask a patch's refinement to add, as `refine::expected_points`
/// estimates them before it starts: about four million triangles, tens of seconds of meshing,
/// and far past what a finite-element model needs on one surface (the didactic model at 10.8
/// million tets has patches of under 100,000 points). Sizes asking for more are a slip (a size
/// in the wrong unit, a digit too few) or a mesh no one can use; the patch fails at once saying
/// so. Where the size is a thousandth of the border's (the example at `size = 0.05`), each size
/// query also meets every border node within reach, so such a refinement runs for many minutes.
/// (The recipe's sizes are checked earlier, against the whole model: `plan::ops::budget`.)
pub const MAX_PATCH_POINTS: f64 = 2.0e6;

/// Smoothing/flip rounds after refinement.
const SMOOTH_ROUNDS: usize = 4;

/// Shares of a patch's progress bar: the checks and the triangulation of the given nodes,
/// refinement (its size field included), smoothing, fold repair and output, verification. The
/// didactic model's refinement (d) patches of 1,400 to 5,300 new points spent 5-8 %, 45-65 %,
/// 18-27 %, 7-10 % and 14-17 % of their times there.
const BAR_SHARES: [f64; 5] = [0.06, 0.55, 0.18, 0.05, 0.16];

/// Meshes one patch (see the module doc) with the default `Tolerances`. The result has passed
/// `verify`.
pub fn mesh_patch(
    input: &PatchInput,
    size: &SurfaceSize,
) -> Result<SurfaceMeshOutput, SurfaceMeshError> {
    mesh_patch_with(input, size, &Tolerances::default())
}

/// `mesh_patch` with the recipe's tolerances: `support_distance_rel` bounds how far a given node
/// may lie from the support and is the bound `verify` applies to every node.
pub fn mesh_patch_with(
    input: &PatchInput,
    size: &SurfaceSize,
    tolerances: &Tolerances,
) -> Result<SurfaceMeshOutput, SurfaceMeshError> {
    mesh_patch_refined(input, size, tolerances, &[])
}

/// `mesh_patch_with`, with elements no larger than `refine` asks for near its features (growing
/// from them no faster than the surface's own growth).
pub fn mesh_patch_refined(
    input: &PatchInput,
    size: &SurfaceSize,
    tolerances: &Tolerances,
    refine: &[Refinement],
) -> Result<SurfaceMeshOutput, SurfaceMeshError> {
    mesh_patch_with_progress(input, size, tolerances, refine, &|_, _| {})
}

/// [`mesh_patch_refined`], telling `progress(done, total)` how far it got, for a progress bar:
/// `total` is fixed, `done` never decreases, a mesh returned was last reported as
/// `done == total`, and there are at most a few hundred calls (`geom::progress`). The mesh is
/// the same, bit for bit.
pub fn mesh_patch_with_progress(
    input: &PatchInput,
    size: &SurfaceSize,
    tolerances: &Tolerances,
    refine: &[Refinement],
    progress: &dyn Fn(u64, u64),
) -> Result<SurfaceMeshOutput, SurfaceMeshError> {
    let meter = Meter::new(progress);
    let [triangulating, refining, smoothing, repairing, verifying] =
        meter.whole().split(BAR_SHARES);
    check_sizes(input, size)?;
    let given = given_nodes(input)?;
    let support = Support::new(&input.support)
        .map_err(|e| fail(input, format!("support: {}", e.message), e.at))?;
    let tol = tolerances.support_distance_rel;
    if !(tol > 0.0 && tol.is_finite()) {
        return Err(fail(
            input,
            format!("invalid tolerance support_distance_rel = {tol} (need a positive number)"),
            None,
        ));
    }
    let hloc = given_sizes(input, &given, point_size(size))?;
    let uv = flatten_given(input, &given, &support, tol, &hloc)?;
    let segs: Vec<(u32, u32)> = given
        .loop_segments()
        .chain(given.constraint_segments())
        .collect();
    check_given_crossings(input, &given, &support, &uv, &segs)?;
    let hloc = points::check_points(input, &given, &uv, &segs, tol, &hloc)?;
    let (mut cdt, mut p3) = triangulate_given(input, &given, &uv, &segs)?;
    triangulating.done();
    let sizing = Sizing {
        size,
        refine,
        bar: [refining, smoothing],
    };
    refine_and_smooth(input, &sizing, &given, &hloc, &support, &mut cdt, &mut p3)?;
    let out = output(input, &given, &cdt, &p3)?;
    repairing.done();
    verify::verify_with(input, &out, tol, &support)?;
    verifying.done();
    meter.finish();
    Ok(out)
}

/// The error for `input` with `message`, located at `at`.
fn fail(input: &PatchInput, message: String, at: Option<[f64; 3]>) -> SurfaceMeshError {
    SurfaceMeshError {
        patch: input.name.clone(),
        message,
        at,
    }
}

/// Whether the requested sizes are usable: size > 0, 0 <= min <= max, max > 0, finite growth >= 1.
fn check_sizes(input: &PatchInput, size: &SurfaceSize) -> Result<(), SurfaceMeshError> {
    let SurfaceSize {
        size: target,
        min_size,
        max_size,
        growth,
    } = *size;
    let sizes_ok = target > 0.0
        && target.is_finite()
        && min_size >= 0.0
        && max_size >= min_size
        && max_size > 0.0
        && growth >= 1.0
        && growth.is_finite();
    if !sizes_ok {
        return Err(fail(
            input,
            format!(
                "invalid sizes: size {target}, min {min_size}, max {max_size}, growth {growth} (need size > 0, 0 <= min <= max, growth >= 1)"
            ),
            None,
        ));
    }
    Ok(())
}

/// The local size of a given point: the target size clamped to [min, max] (a point has no
/// segment to measure).
fn point_size(size: &SurfaceSize) -> f64 {
    size.size.max(size.min_size).min(size.max_size)
}

/// Local sizes of the given nodes (mean adjacent given segment length; `hpoint` for a point that
/// no loop or constraint passes through); no segment may be empty.
fn given_sizes(
    input: &PatchInput,
    given: &GivenNodes,
    hpoint: f64,
) -> Result<Vec<f64>, SurfaceMeshError> {
    let ng = given.nodes.len();
    let mut hsum = vec![0.0f64; ng];
    let mut hcnt = vec![0u32; ng];
    for (a, b) in given.loop_segments().chain(given.constraint_segments()) {
        let l = dist(&given.nodes[a as usize], &given.nodes[b as usize]);
        if !(l > 0.0) {
            return Err(fail(
                input,
                "zero-length segment".into(),
                Some(given.nodes[a as usize]),
            ));
        }
        for v in [a, b] {
            hsum[v as usize] += l;
            hcnt[v as usize] += 1;
        }
    }
    Ok((0..ng)
        .map(|i| {
            if i < given.first_point {
                hsum[i] / hcnt[i].max(1) as f64
            } else {
                hpoint
            }
        })
        .collect())
}

/// Maps the given nodes (points included) into the plane: each must lie within `tol` × its local
/// size of the support.
fn flatten_given(
    input: &PatchInput,
    given: &GivenNodes,
    support: &Support,
    tol: f64,
    hloc: &[f64],
) -> Result<Vec<[f64; 2]>, SurfaceMeshError> {
    let mut uv = Vec::with_capacity(given.nodes.len());
    for (i, p) in given.nodes.iter().enumerate() {
        let on = support
            .project(p)
            .ok_or_else(|| fail(input, "empty support".into(), Some(*p)))?;
        if on.dist > tol * hloc[i] {
            let what = match given.point_of(i) {
                Some(k) => format!("point {k}"),
                None => "a given node".to_string(),
            };
            return Err(fail(
                input,
                format!(
                    "{what} is {:.3e} off the support (allowed {:.3e})",
                    on.dist,
                    tol * hloc[i]
                ),
                Some(*p),
            ));
        }
        uv.push(on.uv);
    }
    Ok(uv)
}

/// Whether the given segments stay apart in the plane (exact); the error is located at the
/// first crossing, mapped back onto the support.
fn check_given_crossings(
    input: &PatchInput,
    given: &GivenNodes,
    support: &Support,
    uv: &[[f64; 2]],
    segs: &[(u32, u32)],
) -> Result<(), SurfaceMeshError> {
    let segs2: Vec<([f64; 2], [f64; 2])> = segs
        .iter()
        .map(|&(a, b)| (uv[a as usize], uv[b as usize]))
        .collect();
    if let Some((i, j)) = segments::first_crossing(&segs2) {
        let at = crossing_point(&segs2[i], &segs2[j])
            .and_then(|x| support.to_3d(&x).map(|r| r.1))
            .unwrap_or(given.nodes[segs[i].0 as usize]);
        return Err(fail(
            input,
            "the boundary loops or constraints intersect themselves or each other".into(),
            Some(at),
        ));
    }
    Ok(())
}

/// Constrained Delaunay triangulation of the given nodes and segments, inside labelled; returns
/// it with its vertices in 3D (the super triangle's three first, as zeros). The points are
/// inserted last, each into the labelled triangulation: one that lands in an outside triangle
/// lies outside the patch (exact: inside and outside triangles meet only across loop edges, and
/// `check_points` has refused points on those).
fn triangulate_given(
    input: &PatchInput,
    given: &GivenNodes,
    uv: &[[f64; 2]],
    segs: &[(u32, u32)],
) -> Result<(Cdt, Vec<[f64; 3]>), SurfaceMeshError> {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in uv {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let mut cdt = Cdt::new(lo, hi);
    let mut p3: Vec<[f64; 3]> = vec![[0.0; 3]; 3];
    p3.extend_from_slice(&given.nodes[..given.first_point]);
    order::insert_all(&mut cdt, &uv[..given.first_point]).map_err(|(i, e)| {
        let why = match e {
            CdtError::Duplicate(_) => "two given nodes land on the same point of the support",
            _ => "a given node could not be placed",
        };
        fail(input, why.into(), Some(given.nodes[i]))
    })?;
    let nloop = given.loop_segments().count();
    for (k, &(a, b)) in segs.iter().enumerate() {
        let kind = if k < nloop { LOOP } else { CONSTRAINT };
        cdt.insert_segment(a + 3, b + 3, kind).map_err(|e| {
            let at = match e {
                CdtError::VertexOnSegment { vertex, .. } => p3.get(vertex as usize).copied(),
                CdtError::Crossing { c, .. } => p3.get(c as usize).copied(),
                _ => None,
            };
            fail(
                input,
                "a boundary or constraint segment touches another node or segment".into(),
                at.or(Some(given.nodes[a as usize])),
            )
        })?;
    }
    cdt.label_inside();
    check_inside(input, given, &cdt, &p3)?;
    insert_points(input, given, uv, &mut cdt, &mut p3)?;
    Ok((cdt, p3))
}

/// Inserts the points (given nodes from `first_point` on) into the labelled triangulation; each
/// must land in an inside triangle.
fn insert_points(
    input: &PatchInput,
    given: &GivenNodes,
    uv: &[[f64; 2]],
    cdt: &mut Cdt,
    p3: &mut Vec<[f64; 3]>,
) -> Result<(), SurfaceMeshError> {
    for i in given.first_point..given.nodes.len() {
        let k = given.point_of(i).unwrap_or(i - given.first_point);
        let p = given.nodes[i];
        let t = cdt.locate(&uv[i], NONE);
        if !t.is_some_and(|t| cdt.inside[t as usize]) {
            return Err(fail(
                input,
                format!("point {k} lies outside the patch"),
                Some(p),
            ));
        }
        let start = t.unwrap_or(NONE);
        match cdt.insert(uv[i], start, &mut |_: &Cdt, _: &[(u32, u32, u8)]| true) {
            Ok(v) => {
                debug_assert_eq!(v as usize, i + 3);
                p3.push(p);
            }
            Err(CdtError::Duplicate(v)) => {
                return Err(fail(
                    input,
                    format!(
                        "point {k} lands on the same place of the support as node {}",
                        v.saturating_sub(3)
                    ),
                    Some(p),
                ));
            }
            Err(_) => {
                return Err(fail(
                    input,
                    format!("point {k} could not be placed"),
                    Some(p),
                ));
            }
        }
    }
    Ok(())
}

/// Whether the constraint edges run inside the patch and the loops enclose some area.
fn check_inside(
    input: &PatchInput,
    given: &GivenNodes,
    cdt: &Cdt,
    p3: &[[f64; 3]],
) -> Result<(), SurfaceMeshError> {
    for t in cdt.live_triangles() {
        for i in 0..3 {
            if cdt.fix[t as usize][i] == CONSTRAINT && !cdt.inside[t as usize] {
                let v = cdt.tri[t as usize][cdt::next(i)];
                return Err(fail(
                    input,
                    "a constraint runs outside the patch".into(),
                    p3.get(v as usize).copied(),
                ));
            }
        }
    }
    if !cdt.live_triangles().any(|t| cdt.inside[t as usize]) {
        return Err(fail(
            input,
            "the loops enclose no area".into(),
            given.nodes.first().copied(),
        ));
    }
    Ok(())
}

/// Why a patch whose sizes ask for about `points` over its `area` (elements of `target` inside,
/// `finest` at the finest) is not meshed.
fn over_budget(points: f64, area: f64, target: f64, finest: f64) -> String {
    format!(
        "its sizes ask for about {} million points over its {:.3} km² (elements of {} inside, \
         {} at the finest), over the {} million a patch may take: raise the size (a size in \
         the wrong unit, or a digit too few?)",
        sig(points / 1e6),
        area / 1e6,
        sig(target),
        sig(finest),
        MAX_PATCH_POINTS / 1e6
    )
}

/// `x` to three significant digits, as a plain number.
fn sig(x: f64) -> String {
    if !x.is_normal() {
        return format!("{x}");
    }
    let digits = (2 - x.abs().log10().floor() as i32).clamp(0, 12) as usize;
    format!("{x:.digits$}")
}

/// Sizes and refinement: inserts points up to the size field (bounded by a point budget from
/// the area and the smallest size), then flips and smooths.
/// The sizes a patch is meshed at: the recipe's, and the refinements near features; with the
/// shares of the progress bar that refinement and smoothing fill.
struct Sizing<'a> {
    size: &'a SurfaceSize,
    refine: &'a [Refinement],
    bar: [Span<'a>; 2],
}

fn refine_and_smooth(
    input: &PatchInput,
    sizing: &Sizing<'_>,
    given: &GivenNodes,
    hloc: &[f64],
    support: &Support,
    cdt: &mut Cdt,
    p3: &mut Vec<[f64; 3]>,
) -> Result<(), SurfaceMeshError> {
    let [refining, smoothing] = sizing.bar;
    let SurfaceSize {
        size: target,
        min_size,
        max_size,
        growth,
    } = *sizing.size;
    let snodes: Vec<([f64; 3], f64)> = given
        .nodes
        .iter()
        .copied()
        .zip(hloc.iter().copied())
        .collect();
    let origin = support::Support::origin_of(&input.support);
    let mut normals = support.normals.clone();
    for &(t, n) in &input.facets {
        if let Some(x) = normals.get_mut(t as usize) {
            *x = n;
        }
    }
    let curvature = size::curvature_nodes(&input.support, &normals, target);
    let field = SizeField::new(
        &snodes,
        &curvature,
        origin,
        target,
        min_size,
        max_size,
        growth.min(MAX_SURFACE_GROWTH),
    )
    .with_refinements(sizing.refine);
    let area: f64 = cdt
        .live_triangles()
        .filter(|&t| cdt.inside[t as usize])
        .map(|t| {
            let v = cdt.tri[t as usize];
            geom::trimesh::triangle_area([
                &p3[v[0] as usize],
                &p3[v[1] as usize],
                &p3[v[2] as usize],
            ])
        })
        .sum();
    let hfloor = min_size
        .max(hloc.iter().copied().fold(f64::INFINITY, f64::min))
        .min(target)
        .max(f64::MIN_POSITIVE);
    let max_points = (8.0 * area / (hfloor * hfloor)).min(5.0e7) as usize + 10_000;
    let expected = refine::expected_points(cdt, p3, &field);
    if expected > MAX_PATCH_POINTS {
        return Err(fail(
            input,
            over_budget(expected, area, target, hfloor),
            None,
        ));
    }
    let stri = {
        let mut r = refine::Refiner::new(cdt, p3, support, &field);
        r.run(max_points, refining, expected)
            .map_err(|m| fail(input, m, given.nodes.first().copied()))?;
        std::mem::take(&mut r.stri)
    };
    let first_free = (3 + given.nodes.len()) as u32;
    let mut s = smooth::Smoother {
        cdt,
        p3,
        support,
        first_free,
        stri,
    };
    refining.done();
    s.run(SMOOTH_ROUNDS, smoothing);
    let mut stri = std::mem::take(&mut s.stri);
    unfold::repair_folds(cdt, p3, support, &mut stri, first_free);
    Ok(())
}

/// Output: the CDT's vertices minus the super triangle, inside triangles in slot order, unused
/// generated nodes dropped.
fn output(
    input: &PatchInput,
    given: &GivenNodes,
    cdt: &Cdt,
    p3: &[[f64; 3]],
) -> Result<SurfaceMeshOutput, SurfaceMeshError> {
    let nodes: Vec<[f64; 3]> = p3[3..].to_vec();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    for t in cdt.live_triangles().filter(|&t| cdt.inside[t as usize]) {
        let v = cdt.tri[t as usize];
        if v.iter().any(|&x| x < 3) {
            return Err(fail(
                input,
                "the loops are not closed around the patch".into(),
                given.nodes.first().copied(),
            ));
        }
        triangles.push(v.map(|x| x - 3));
    }
    Ok(compact(
        SurfaceMeshOutput { nodes, triangles },
        given.nodes.len(),
    ))
}

/// Drops generated nodes that no triangle uses (points inserted then cut off by nothing should
/// not exist, but a refused cavity can leave none either; this keeps numbering dense).
fn compact(mut out: SurfaceMeshOutput, ng: usize) -> SurfaceMeshOutput {
    let mut used = vec![false; out.nodes.len()];
    for t in &out.triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    let mut map = vec![u32::MAX; out.nodes.len()];
    let mut nodes = Vec::with_capacity(out.nodes.len());
    for (i, p) in out.nodes.iter().enumerate() {
        if i < ng || used[i] {
            map[i] = nodes.len() as u32;
            nodes.push(*p);
        }
    }
    for t in &mut out.triangles {
        *t = t.map(|v| map[v as usize]);
    }
    out.nodes = nodes;
    out
}

fn crossing_point(s: &([f64; 2], [f64; 2]), t: &([f64; 2], [f64; 2])) -> Option<[f64; 2]> {
    let r = [s.1[0] - s.0[0], s.1[1] - s.0[1]];
    let q = [t.1[0] - t.0[0], t.1[1] - t.0[1]];
    let den = r[0] * q[1] - r[1] * q[0];
    if den == 0.0 {
        return Some(t.0);
    }
    let w = [t.0[0] - s.0[0], t.0[1] - s.0[1]];
    let u = (w[0] * q[1] - w[1] * q[0]) / den;
    Some([s.0[0] + u * r[0], s.0[1] + u * r[1]])
}

/// How the support is flattened for meshing: `"plane"` (projection onto its mean plane, exactly
/// fold-free), `"relaxed"` (that projection, mended where it turns a few triangles over) or
/// `"tutte"` (Tutte embedding, for supports that fold over every plane).
pub fn flattening_method(support: &TriMesh) -> Result<&'static str, SurfaceMeshError> {
    param::flatten(support)
        .map(|p| p.method)
        .map_err(|e| SurfaceMeshError {
            patch: "support".into(),
            message: e.message,
            at: e.at,
        })
}

/// Checks a patch mesh (see `verify.rs`): exact topology, orientation, no fold or overlap, and
/// every node within `tol_rel` × its mean edge length of the support.
pub fn verify(
    input: &PatchInput,
    out: &SurfaceMeshOutput,
    tol_rel: f64,
) -> Result<(), SurfaceMeshError> {
    let support = Support::new(&input.support).map_err(|e| SurfaceMeshError {
        patch: input.name.clone(),
        message: format!("support: {}", e.message),
        at: e.at,
    })?;
    verify::verify_with(input, out, tol_rel, &support)
}
