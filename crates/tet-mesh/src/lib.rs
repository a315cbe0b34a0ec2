//! Stage `tet_mesh`: fill one region with tetrahedra that conform exactly to its boundary
//! triangles, to the dangling (embedded) fault triangles inside it and to embedded segments
//! (well paths), each of which becomes a chain of tet edges.
//!
//! Two methods share the input checks, the size field, the optimizer and the exact verification.
//!
//! **Delaunay (the default, `delaunay`).** The Delaunay tetrahedralization of the boundary and
//! embedded vertices; the boundary triangles that are not Delaunay faces are recovered locally
//! (the tets that may meet them are removed and the hole's inner part is meshed by the front);
//! interior nodes come from Delaunay refinement against the size field, whose cavities never cross
//! a boundary or embedded face. It is 5-6x faster than the front at the same quality. When recovery meets something it cannot settle, the
//! region falls back to the front and the stats say why.
//!
//! **Advancing front (`advance`, the seed's method).** Conformity is by construction: the front
//! starts as the boundary triangles (embedded ones twice, once per side), every tetrahedron is
//! built on a front face, and no node is ever inserted on a boundary face. Each candidate
//! tetrahedron is accepted only after exact tests (`exact`): positive `orient3d`, none of its new
//! faces improperly intersects a front face, and no front node lies in it. When a face has no
//! valid apex the mesher back-tracks (deletes the tetrahedra around it, restores the front and
//! re-meshes the cavity), iteratively, never recursively.
//!
//! **Embedded segments (well paths, `RegionInput::lines`).** Checked exactly like the triangles
//! (`lines`, `inside`: a segment meets other input only in shared end vertices, and lies inside
//! the region); the Delaunay method inserts their vertices with the boundary's, divides them to
//! the size field, makes each piece an edge by flips or by nodes on the segment, and protects the
//! pieces from then on (`delaunay`); the optimizer keeps them and their nodes fixed; `verify`
//! checks each chain (`TetMeshOutput::lines`). The advancing front does not embed segments: a
//! region with segments that the Delaunay method cannot mesh is an error saying so.
//!
//! Afterwards `optimize` raises the worst qualities: optimization-based smoothing of interior
//! nodes (`smooth`), 2-3 flips and edge removal (`flips`) and node insertion for bad tets nothing
//! else fixes (`slivers`), over a tet complex with adjacency (`complex`); every change keeps every
//! tetrahedron positive (exact), every boundary and embedded face a face and every piece of a
//! segment an edge. `verify` checks the result exactly before `mesh_region` returns it, so a
//! partial or overlapping mesh is an error, never a result.
//!
//! Submodules: `exact` (the predicates, with exact shortcuts for repeated and axis-coplanar
//! points; triangles and segments meet by `geom::contact`), `quality` (measures), `check` (input
//! validation, on the pairs `geom::broad_phase` proposes), `lines` and `inside` (the segments' checks and the check of their chains),
//! `delaunay` (kernel, insertion order, recovery, refinement), `front` (front faces, their spatial
//! grid, and grids of front nodes and of all nodes), `advance` (the front loop and back-tracking), `sides` (exact
//! sides of nearby front nodes against a candidate's planes), `work` (what the fronts of a region
//! may spend before they give up), `optimize` (the optimization
//! driver) with `complex`, `smooth`, `flips` and `slivers`, `verify` (exact output check),
//! `progress` (how the phases share a progress bar, for [`mesh_region_with_progress`]).
//!
//! **Progress.** [`mesh_region_with_progress`] reports to a plain `&dyn Fn(done, total)`
//! (`geom::progress`), so the crate knows nothing of who watches (the build engine, a command
//! line). Each phase counts what it has (input vertices inserted, refinement's nodes of those
//! estimated, the front's volume, the optimizer's lists), on a share of the bar set from
//! measured times; reporting is throttled and only reads, so the mesh is the same bit for bit.

mod advance;
mod check;
mod closing;
mod complex;
mod delaunay;
pub mod exact;
mod flips;
mod front;
mod inside;
mod lines;
mod optimize;
mod pinch;
mod progress;
pub mod quality;
mod sides;
mod sizing;
mod slivers;
mod smooth;
pub mod stretch;
mod verify;
mod work;

pub use check::check_input;
pub use verify::verify;

use geom::progress::{Meter, Span};

/// One region to fill.
#[derive(Clone, Debug, Default)]
pub struct RegionInput {
    pub name: String,
    pub vertices: Vec<[f64; 3]>,
    /// Closed boundary triangles (one or more closed shells: an outer shell and cavity shells),
    /// oriented so their right-hand normal points OUT of the region (the caller orients them).
    pub boundary: Vec<[u32; 3]>,
    /// Embedded (dangling) triangles inside the region: must appear as faces, with tets on both sides.
    pub embedded: Vec<[u32; 3]>,
    /// Embedded line segments (well paths) between two vertices: each becomes a chain of tet
    /// edges. A segment meets the boundary, an embedded triangle or another segment only at its
    /// end vertices (then vertices of those triangles or segments); segments sharing ends form
    /// polylines, which may end inside the region.
    pub lines: Vec<[u32; 2]>,
}

/// Target element size inside the region. The front's own face sizes (from the boundary) drive
/// the local size; `size` is the interior target the mesh may grow towards at rate `growth` per
/// layer, always clamped to `[min_size, max_size]`.
#[derive(Clone, Debug)]
pub struct SizeField {
    pub size: f64,
    pub min_size: f64,
    pub max_size: f64,
    pub growth: f64,
    /// Finer sizes near features (each growing no faster than `growth` allows).
    pub refine: Vec<geom::refine::Refinement>,
}

impl Default for SizeField {
    fn default() -> Self {
        SizeField {
            size: f64::INFINITY,
            min_size: 0.0,
            max_size: f64::INFINITY,
            growth: 1.2,
            refine: Vec::new(),
        }
    }
}

/// Options of the mesher.
#[derive(Clone, Debug)]
pub struct TetMeshOptions {
    /// Run the quality optimization (smoothing) after the front closes. Default true.
    pub optimize: bool,
    /// Seed for any randomness (the mesher currently uses none; kept for the cache key). Default 0.
    pub seed: u64,
    /// How the region is filled. Default `Delaunay` (falling back to the front).
    pub method: Method,
}

/// Meshing method of a region (in a recipe: `tet_method = "delaunay"` or `"front"`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Delaunay tetrahedralization, local boundary recovery, Delaunay refinement; the advancing
    /// front fills recovery holes, and meshes the whole region when recovery fails.
    #[default]
    Delaunay,
    /// Advancing front only.
    Front,
}

impl Method {
    /// Every method with its name in recipes (`tet_method`) and on the command line.
    pub const NAMES: [(&'static str, Method); 2] =
        [("delaunay", Method::Delaunay), ("front", Method::Front)];

    pub fn name(self) -> &'static str {
        match self {
            Method::Delaunay => "delaunay",
            Method::Front => "front",
        }
    }

    /// The method named `s`, if any.
    pub fn from_name(s: &str) -> Option<Method> {
        Method::NAMES.iter().find(|(n, _)| *n == s).map(|&(_, m)| m)
    }
}

impl Default for TetMeshOptions {
    fn default() -> Self {
        TetMeshOptions {
            optimize: true,
            seed: 0,
            method: Method::default(),
        }
    }
}

/// Figures about one meshed region.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TetMeshStats {
    pub tets: usize,
    pub nodes: usize,
    /// Interior nodes added by the mesher (`nodes - input vertices`).
    pub new_nodes: usize,
    /// How many times the front got stuck and tetrahedra were deleted and re-meshed.
    pub backtracks: usize,
    pub min_mean_ratio: f64,
    pub avg_mean_ratio: f64,
    pub min_dihedral_deg: f64,
    /// Boundary or embedded triangles that were not Delaunay faces and were recovered through a
    /// hole re-meshed by the front (Delaunay method).
    pub recovered_faces: usize,
    /// Boundary or embedded triangles that were not Delaunay faces and were recovered by flips
    /// (Delaunay method).
    pub flipped_faces: usize,
    /// Why the Delaunay method gave way to the advancing front on the whole region, if it did.
    pub fallback: Option<String>,
    /// Nodes on the embedded segments (all new, kept fixed by the optimizer).
    pub line_nodes: usize,
    /// Of those, the nodes inserted to recover pieces of segments that were not edges.
    pub line_splits: usize,
    /// Pieces of segments that were not edges and flips made edges.
    pub line_flips: usize,
}

/// The tetrahedral mesh of one region.
#[derive(Clone, Debug)]
pub struct TetMeshOutput {
    /// Input vertices first (same indices), then the new interior nodes.
    pub nodes: Vec<[f64; 3]>,
    /// Positively oriented: `det[b-a, c-a, d-a] > 0`.
    pub tets: Vec<[u32; 4]>,
    /// Per input segment (`RegionInput::lines`, same order): the nodes it became, from its first
    /// vertex to its second; consecutive nodes are tet edges, the inner ones new nodes on it.
    pub lines: Vec<Vec<u32>>,
    pub stats: TetMeshStats,
}

/// The Delaunay method's error `why`, saying that the front was not tried on the whole region for
/// the pinch `p`.
fn pinched(mut why: TetMeshError, p: &pinch::Pinch) -> TetMeshError {
    why.message = format!(
        "{}; the advancing front was not tried on the whole region: its boundary is pinched near \
         ({}, {}, {}), where surfaces come {:.3} apart with triangles {:.3} wide round them, a gap \
         the front cannot close (part the surfaces there, or mesh them finer)",
        why.message, p.at[0], p.at[1], p.at[2], p.gap, p.width
    );
    why
}

/// Why a region could not be meshed (or a mesh is not valid): names the region and the place.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("region '{region}': {message}{}", geom::at_suffix(.at))]
pub struct TetMeshError {
    pub region: String,
    pub message: String,
    pub at: Option<[f64; 3]>,
    /// Whether an advancing front got stuck or spent its work: the region's error then says
    /// whether its boundary is pinched ([`explained`]).
    front: bool,
}

impl TetMeshError {
    pub(crate) fn new(region: &str, message: impl Into<String>, at: Option<[f64; 3]>) -> Self {
        TetMeshError {
            region: region.to_string(),
            message: message.into(),
            at,
            front: false,
        }
    }

    /// This error, as one of an advancing front that could not close.
    pub(crate) fn of_the_front(self) -> Self {
        TetMeshError {
            front: true,
            ..self
        }
    }
}

/// The region's error `why`, with the likely cause when a front could not close: the pinch of
/// the boundary (measured now if it was not yet: this is a failure's path), or, where there is
/// none, that the front's sides met badly, which a coarser interior often avoids.
fn explained(mut why: TetMeshError, input: &RegionInput, work: &work::FrontWork) -> TetMeshError {
    if !why.front {
        return why;
    }
    why.message = match work.pinch(input) {
        Some(p) => format!(
            "{}; its boundary is pinched near ({}, {}, {}), where surfaces come {:.3} apart with \
             triangles {:.3} wide round them, a gap the front cannot close (part the surfaces \
             there, or mesh them finer)",
            why.message, p.at[0], p.at[1], p.at[2], p.gap, p.width
        ),
        None => format!(
            "{}; its boundary is not pinched (no two of its surfaces come closer than a \
             twentieth of their triangles' width): the front could not close where its sides \
             met, which a coarser interior often avoids (a larger `growth` in `[mesh]`, at some \
             cost in the tets' quality)",
            why.message
        ),
    };
    why
}

/// Mesh one region: check the input, mesh it (Delaunay with local recovery, the front as its
/// fallback, or the front alone), optimize, compute statistics and verify exactly. Never returns a
/// mesh that fails `verify`.
pub fn mesh_region(
    input: &RegionInput,
    size: &SizeField,
    opts: &TetMeshOptions,
) -> Result<TetMeshOutput, TetMeshError> {
    mesh_region_with_progress(input, size, opts, &|_, _| {})
}

/// [`mesh_region`], telling `progress(done, total)` how far it got, for a progress bar: `total`
/// is fixed, `done` never decreases, a mesh returned was last reported as `done == total`, and
/// there are at most a few hundred calls (`geom::progress`; how the phases share the bar is in
/// this crate's `progress` module). The mesh is the same, bit for bit.
pub fn mesh_region_with_progress(
    input: &RegionInput,
    size: &SizeField,
    opts: &TetMeshOptions,
    progress: &dyn Fn(u64, u64),
) -> Result<TetMeshOutput, TetMeshError> {
    let meter = Meter::new(progress);
    let bar = meter.whole();
    let mut fallback = None;
    let (mut mesh, figures, tail) = match opts.method {
        Method::Delaunay => {
            check::check_shape(input)?;
            check::check_embedded_inside(input)?;
            lines::check_lines(input)?;
            bar.reach(progress::CHECKS);
            let rest = bar.part(progress::CHECKS, 1.0);
            let work = work::FrontWork::for_region(input);
            match delaunay::mesh(input, size, rest, opts.optimize, &work) {
                Ok(done) => done,
                Err(why) => {
                    // The Delaunay path tests intersections only where a triangle is not one
                    // of its faces: an input it could not take is tested in full before the
                    // front, which relies on it, meshes it.
                    check::check_intersections(input)?;
                    if !input.lines.is_empty() {
                        return Err(no_front_for_lines(input, Some(&why)));
                    }
                    // The front meshes the region with what the recovery's fronts left of the
                    // region's budget; none left, or the recovery's own front failed on the
                    // whole region already, the recovery's failure is the region's.
                    if work.exhausted(0) || work.failed_on_whole_region() {
                        return Err(explained(why, input, &work));
                    }
                    // Nor where the boundary is pinched: the front cannot close the gap.
                    if let Some(p) = work.pinch(input) {
                        return Err(pinched(why, &p));
                    }
                    let [front, optimize, finish] =
                        meter.rest().split(progress::front(opts.optimize));
                    // If the front fails too, its error says why both did. It has a budget of its
                    // own (`work::FrontWork::for_fallback`), far above what a front it rescues
                    // spends, far below what a failing one did.
                    let own = work.for_fallback();
                    let m = advance::advance_front_reporting(input, size, front, &own);
                    work.spend(own.spent());
                    let m = m.map_err(|mut e| {
                        e.message =
                            format!("{} (after Delaunay gave way: {})", e.message, why.message);
                        explained(e, input, &work)
                    })?;
                    fallback = Some(why.to_string());
                    (m, delaunay::Figures::default(), Tail { optimize, finish })
                }
            }
        }
        Method::Front => {
            check_input(input)?;
            lines::check_lines(input)?;
            if !input.lines.is_empty() {
                return Err(no_front_for_lines(input, None));
            }
            bar.reach(progress::FRONT_CHECKS);
            let [front, optimize, finish] = bar
                .part(progress::FRONT_CHECKS, 1.0)
                .split(progress::front(opts.optimize));
            let work = work::FrontWork::for_region(input);
            let m = advance::advance_front_reporting(input, size, front, &work)
                .map_err(|e| explained(e, input, &work))?;
            (m, Default::default(), Tail { optimize, finish })
        }
    };
    // Nodes on segments follow the input vertices and stay fixed, as those do.
    let n_fixed = input.vertices.len() + figures.line_nodes;
    let mut mean_ratios = None;
    if opts.optimize {
        let protected = input.boundary.iter().chain(&input.embedded).copied();
        let line_edges = figures
            .chains
            .iter()
            .flat_map(|c| c.windows(2).map(|w| [w[0], w[1]]));
        let (nodes, tets, measured) = optimize::optimize(
            std::mem::take(&mut mesh.nodes),
            std::mem::take(&mut mesh.tets),
            n_fixed,
            protected,
            line_edges,
            tail.optimize,
        );
        mesh.nodes = nodes;
        mesh.tets = tets;
        mean_ratios = Some(measured);
    }
    tail.optimize.done();
    let (nodes, tets, map) = compact(mesh.nodes, mesh.tets, input.vertices.len());
    let lines = (figures.chains.iter())
        .map(|c| c.iter().map(|&v| map[v as usize]).collect())
        .collect();
    let mut out = TetMeshOutput {
        nodes,
        tets,
        lines,
        stats: TetMeshStats::default(),
    };
    out.stats = measured_stats(
        &out,
        input.vertices.len(),
        mesh.backtracks,
        mean_ratios.as_deref(),
    );
    drop(mean_ratios);
    out.stats.recovered_faces = figures.missing_faces;
    out.stats.flipped_faces = figures.flipped_faces;
    out.stats.line_nodes = figures.line_nodes;
    out.stats.line_splits = figures.line_splits;
    out.stats.line_flips = figures.line_flips;
    out.stats.fallback = fallback;
    // The statistics were about a third of this share, the exact verification the rest.
    tail.finish.reach(0.3);
    verify(input, &out)?;
    meter.finish();
    Ok(out)
}

/// The shares of a region's progress bar left once its mesh is made.
pub(crate) struct Tail<'m> {
    pub optimize: Span<'m>,
    pub finish: Span<'m>,
}

/// The error for segments the Delaunay method could not embed (`why`), or that the front was
/// asked to: the advancing front does not embed segments.
fn no_front_for_lines(input: &RegionInput, why: Option<&TetMeshError>) -> TetMeshError {
    let n = input.lines.len();
    let reason = match why {
        Some(e) => format!("the Delaunay method failed ({}), and ", e.message),
        None => String::new(),
    };
    TetMeshError::new(
        &input.name,
        format!(
            "the well cannot be embedded in this region: {reason}the advancing front cannot \
             embed its {n} line segments"
        ),
        why.and_then(|e| e.at)
            .or_else(|| input.vertices.get(input.lines[0][0] as usize).copied()),
    )
}

/// Drop interior nodes no tetrahedron uses (left behind by back-tracking), keeping input
/// vertices at their indices and the others in creation order; with the map from old ids.
fn compact(
    nodes: Vec<[f64; 3]>,
    mut tets: Vec<[u32; 4]>,
    n_input: usize,
) -> (Vec<[f64; 3]>, Vec<[u32; 4]>, Vec<u32>) {
    let mut used = vec![false; nodes.len()];
    for t in &tets {
        for &v in t {
            used[v as usize] = true;
        }
    }
    let mut map = vec![u32::MAX; nodes.len()];
    let mut out = Vec::with_capacity(nodes.len());
    for (i, p) in nodes.into_iter().enumerate() {
        if i < n_input || used[i] {
            map[i] = out.len() as u32;
            out.push(p);
        }
    }
    for t in &mut tets {
        for v in t.iter_mut() {
            *v = map[*v as usize];
        }
    }
    (out, tets, map)
}

/// Quality statistics of a mesh.
pub fn stats_of(out: &TetMeshOutput, n_input: usize, backtracks: usize) -> TetMeshStats {
    measured_stats(out, n_input, backtracks, None)
}

/// [`stats_of`], with each tet's mean ratio given when the optimizer has kept them current
/// (measuring every tet's mean ratio again was 1.3 % of a large region's time, by profile).
fn measured_stats(
    out: &TetMeshOutput,
    n_input: usize,
    backtracks: usize,
    mean_ratios: Option<&[f64]>,
) -> TetMeshStats {
    let mut s = TetMeshStats {
        tets: out.tets.len(),
        nodes: out.nodes.len(),
        new_nodes: out.nodes.len().saturating_sub(n_input),
        backtracks,
        min_mean_ratio: f64::INFINITY,
        min_dihedral_deg: f64::INFINITY,
        ..Default::default()
    };
    let mut sum_q = 0.0;
    let mut max_cos = f64::NEG_INFINITY;
    for (k, t) in out.tets.iter().enumerate() {
        let [a, b, c, d] = t.map(|i| out.nodes[i as usize]);
        let q = match mean_ratios {
            Some(m) => m[k],
            None => quality::mean_ratio(&a, &b, &c, &d),
        };
        s.min_mean_ratio = s.min_mean_ratio.min(q);
        max_cos = max_cos.max(quality::largest_dihedral_cosine(&a, &b, &c, &d));
        sum_q += q;
    }
    if !out.tets.is_empty() {
        s.avg_mean_ratio = sum_q / out.tets.len() as f64;
        s.min_dihedral_deg = quality::dihedral_deg(max_cos);
    } else {
        s.min_mean_ratio = 0.0;
        s.min_dihedral_deg = 0.0;
    }
    s
}

#[cfg(test)]
mod tests {
    use super::pinch::tests::slab;
    use super::*;

    /// The error of a front on `input` that has next to no work to spend.
    fn front_out_of_work(input: &RegionInput) -> TetMeshError {
        let work = work::FrontWork::with(5_000, 0);
        advance::advance_front(input, &SizeField::default(), &work).expect_err("no work")
    }

    #[test]
    fn a_front_that_could_not_close_says_whether_the_boundary_is_pinched() {
        let cube = slab(1.0);
        let e = explained(
            front_out_of_work(&cube),
            &cube,
            &work::FrontWork::for_region(&cube),
        );
        assert!(e.message.contains("its boundary is not pinched"), "{e}");
        assert!(e.message.contains("`growth`"), "{e}");
        // 0.03 thick under edges of 1: a gap no front closes.
        let thin = slab(0.01);
        let e = explained(
            front_out_of_work(&thin),
            &thin,
            &work::FrontWork::for_region(&thin),
        );
        assert!(e.message.contains("its boundary is pinched near ("), "{e}");
        assert!(!e.message.contains("not pinched"), "{e}");
    }

    #[test]
    fn an_error_that_is_not_a_front_s_is_left_as_it_is() {
        let cube = slab(1.0);
        let e = TetMeshError::new("cube", "a boundary vertex is not used", None);
        let same = explained(e.clone(), &cube, &work::FrontWork::for_region(&cube));
        assert_eq!(same, e);
    }
}
