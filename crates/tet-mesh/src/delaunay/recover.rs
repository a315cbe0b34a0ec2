//! From boundary points to a conforming mesh of the region: the Delaunay tetrahedralization of
//! the boundary and embedded vertices, then boundary recovery without a single node on a boundary
//! face. Most boundary triangles of a good surface mesh are Delaunay faces already; most missing
//! ones are made faces by flips (`flips`). Each still missing one is recovered locally: every
//! tet that may meet its interior (exact, conservative tests) is removed, and the part of those
//! holes inside the region (bounded by the missing triangles, the boundary triangles inside the
//! holes and the faces towards the kept inner tets) is filled, hole by hole (`holes`): by the
//! hole's own conforming Delaunay mesh (this same recovery, two levels deep), else by a cone
//! from a node in its kernel (`kernel`), else the hole takes the inner tets round it and is
//! tried again. What is left goes to the advancing front, which never inserts a node on a face;
//! where the front gets stuck against the walls of kept tets, the hole is widened there and
//! meshed again, unless the region is pinched (`pinch`) and its fronts have spent more than one
//! that closes a hole there does: the front cannot close the gap, and widening only fails again
//! at more cost. Kept tets are classified inside or outside by flooding from the boundary
//! triangles' oriented sides, never across a boundary face. Any inconsistency is an error, and
//! the caller falls back to the advancing front on the whole region.

mod flips;
mod holes;
pub use holes::connected_pieces;
mod kernel;
mod peel;
mod segments;

use std::collections::HashSet;

use geom::predicates::Orientation;
use geom::progress::Span;

use super::super::check::check_intersections;
use super::super::exact::orient3d;
use super::super::front::{FaceMap, WordSet};
use super::super::work::FrontWork;
use super::super::{RegionInput, SizeField, TetMeshError};
use super::flip::coplanar;
use super::tri::{FACE, Limits, NONE, P, Tri};
use geom::spatial_order::brio;
use holes::{
    Filler, flood, hole_tets, hole_walls, mesh_holes, seed_sides, unpinched_hole_surface,
    widen_around, widen_hole,
};
pub use segments::recover_segments;

/// Boundary-conforming mesh of a region: `tri` holds only inner tets, the boundary faces on its
/// hull and the embedded faces as constraints; `pts[n_input..n_input + 4]` are the unused corners
/// of the enclosing tet.
pub struct Conforming {
    pub tri: Tri,
    pub n_input: usize,
    /// Boundary triangles that were not Delaunay faces and went through a hole.
    pub missing: usize,
    /// Boundary triangles that were not Delaunay faces and flips made faces.
    pub flipped: usize,
}

/// Recovery gives up when more than `MAX_MISSING` constraint triangles, and more than one in
/// `MAX_MISSING_SHARE`, are missing. Surface meshes from Gmsh and from our mesher miss none or a
/// handful; a structured grid on a box side (cospherical squares) misses about half, and the holes
/// then span the region: the front meshes it directly and faster.
const MAX_MISSING: usize = 500;
const MAX_MISSING_SHARE: usize = 50;
/// Growth (numerator, denominator) of widened holes' faces between two tries to fill them
/// (`worth_a_try`). On the example with a horizon jittered by 35 or 50 m, recoveries tried
/// every ring of widening, holes of up to 29,000 faces, 16 times each: 1 to 9 s of a region's
/// tries without the front, and up to 7 s more with it; every widened hole that any recovery
/// filled in the test suite, the geology corpus and RINGMesh modelA4 was filled within 5 rings.
const TRY_GROWTH: (usize, usize) = (3, 2);
/// Rounds of hole growth before recovery gives up.
const MAX_GROWTH: usize = 8;
/// Times a hole is widened round the place where the front got stuck before recovery gives up.
const MAX_WIDENING: usize = 16;
/// Front work (`work` units) past which the recovery of a pinched region (`pinch`) gives up
/// widening its holes. On the example with a horizon jittered by up to 35 or 50 m, the geology
/// corpus, RINGMesh modelA4 and CloudSpin, the pinched regions whose recovery closed its holes
/// spent at most 6.4 million units on their fronts; those that failed spent 134 to 534 million,
/// 10 to 35 s, widening hole after hole to fail where the front could not close the gap.
/// Regions that are not pinched keep the whole budget (modelA4's and CloudSpin's heaviest
/// recoveries that succeed spend 61 and 159 million).
const PINCHED_FRONT_WORK: u64 = 32_000_000;
/// The share of the region's triangles (numerator, denominator) below which the holes widened
/// without the front get a front of their own (`worth_a_front`).
const MAX_WIDENED_SHARE: (usize, usize) = (1, 2);
/// Holes inside holes: a hole is first tetrahedralized as a region of its own (its vertices'
/// Delaunay tetrahedralization, recovered), down to this depth, before the front meshes it.
const MAX_DEPTH: u32 = 2;

/// The (tet, face) pairs that hold a constraint triangle, `4 t + i` each: at most two.
#[derive(Clone, Copy)]
struct Holders([u32; 2]);

impl Holders {
    fn push(&mut self, t: u32, i: usize) {
        let slot = if self.0[0] == NONE { 0 } else { 1 };
        self.0[slot] = 4 * t + i as u32;
    }

    fn is_empty(&self) -> bool {
        self.0[0] == NONE
    }

    fn iter(&self) -> impl Iterator<Item = (u32, usize)> {
        self.0
            .into_iter()
            .filter(|&x| x != NONE)
            .map(|x| (x >> 2, (x & 3) as usize))
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    Unknown,
    In,
    Out,
    Hole,
}

fn sorted(f: [u32; 3]) -> [u32; 3] {
    let mut k = f;
    k.sort_unstable();
    k
}

/// Same cyclic orientation.
fn same_turn(f: [u32; 3], g: [u32; 3]) -> bool {
    f == g || f == [g[1], g[2], g[0]] || f == [g[2], g[0], g[1]]
}

/// `bar`: the shares of the region's progress bar of the insertion and of the recovery; `work`:
/// what the fronts filling recovery holes may spend, all together.
pub fn conforming(
    input: &RegionInput,
    size: &SizeField,
    bar: [Span<'_>; 2],
    work: &FrontWork,
) -> Result<Conforming, TetMeshError> {
    let segments: Vec<[P; 2]> = (input.lines.iter())
        .map(|l| l.map(|v| input.vertices[v as usize]))
        .collect();
    conforming_at(input, size, bar, &segments, work, 0)
}

/// [`conforming`] of a region (`depth` 0) or of a recovery hole inside one (`depth` > 0: the
/// holes' own holes never go to the front); `segments` are the region's embedded segments.
fn conforming_at(
    input: &RegionInput,
    size: &SizeField,
    bar: [Span<'_>; 2],
    segments: &[[P; 2]],
    work: &FrontWork,
    depth: u32,
) -> Result<Conforming, TetMeshError> {
    let [inserting, recovering] = bar;
    let name = input.name.as_str();
    let n = input.vertices.len();
    let mut tri = enclosing_tet(input);
    insert_boundary_vertices(&mut tri, input, inserting)?;

    // Which constraint triangles are faces.
    let (all, cons_index) = constraints(input);
    let mut holders = find_holders(&tri, &cons_index, all.len(), n);
    let mut missing: Vec<usize> = (0..all.len()).filter(|&k| holders[k].is_empty()).collect();
    let mut vtet = vertex_tets(&tri);
    if !missing.is_empty() && flip_diagonals(&mut tri, &all, &missing, &mut vtet) > 0 {
        holders = find_holders(&tri, &cons_index, all.len(), n);
        missing = (0..all.len()).filter(|&k| holders[k].is_empty()).collect();
    }
    check_missing(input, &tri, &all, &missing)?;
    let before_flips = missing.len();
    if !missing.is_empty() {
        let kept = flips::Kept::new(&all, &cons_index);
        if flips::recover_by_flips(&mut tri, &all, &missing, &kept, &mut vtet) > 0 {
            holders = find_holders(&tri, &cons_index, all.len(), n);
            missing = (0..all.len()).filter(|&k| holders[k].is_empty()).collect();
        }
    }

    // Half way: the holes follow (none in most regions).
    recovering.reach(0.5);

    // Remove every tet that may meet a missing triangle.
    let mut side = hole_tets(&tri, &all, &missing, &vtet);
    // Flood the kept tets from the constraint sides and the enclosing tet's corners.
    seed_sides(&mut tri, &mut side, &all, &holders, n, name)?;
    flood(&tri, &mut side, name)?;

    // The holes' inner part, filled.
    let extra: Vec<[u32; 4]> = if side.contains(&Side::Hole) {
        fill_holes(
            &mut tri, &mut side, &all, &holders, &vtet, input, size, segments, work, depth,
        )?
    } else {
        Vec::new()
    };
    // Keep the inner tets in place: the faces the holes share with them are noted, every other
    // tet goes, and the front's tets are linked in (no rebuild of the whole adjacency).
    let live: Vec<u32> = tri.live_tets().collect();
    let surface = hole_walls(&tri, &side, &live);
    drop((vtet, holders, cons_index));
    for &t in &live {
        if side[t as usize] != Side::In {
            tri.kill(t);
        }
    }
    drop(side);
    let embedded: HashSet<[u32; 3]> = input.embedded.iter().map(|&t| sorted(t)).collect();
    tri.link_in(&extra, &surface, &embedded);
    recovering.done();
    Ok(Conforming {
        tri,
        n_input: n,
        missing: missing.len(),
        flipped: before_flips - missing.len(),
    })
}

/// The tets filling the holes: first without the front, each hole that neither its own
/// Delaunay tetrahedralization nor a cone fills taking the inner tets round it
/// ([`without_front`]); then the front, once on the holes so widened (where they took the whole
/// region, as in a closed body, this is the front's mesh of it inside this method, which still
/// recovers the segments), else on the holes as they were. Where the front gets stuck, the hole
/// is widened round the stuck place (the inner tets there join it, in rings of growing radius)
/// and meshed again once it has grown by half (`worth_a_try`): the walls of kept tets that
/// pinned the front there are gone. A hole's own holes (`depth` > 0) never go to the front.
#[allow(clippy::too_many_arguments)]
fn fill_holes(
    tri: &mut Tri,
    side: &mut [Side],
    all: &[([u32; 3], bool)],
    holders: &[Holders],
    vtet: &[u32],
    input: &RegionInput,
    size: &SizeField,
    segments: &[[P; 2]],
    work: &FrontWork,
    depth: u32,
) -> Result<Vec<[u32; 4]>, TetMeshError> {
    let name = input.name.as_str();
    // Only the region itself (`depth` 0) is asked for its pinch: `work` is the region's.
    let give_up = || depth == 0 && gives_up(work.spent(), || work.pinch(input).is_some());
    let fill = Filler {
        name,
        size,
        segments,
        work,
        delaunay: |sub: &RegionInput| {
            (depth < MAX_DEPTH)
                .then(|| {
                    let bars = [Span::none(), Span::none()];
                    conforming_at(sub, size, bars, segments, work, depth + 1).ok()
                })
                .flatten()
                .map(|c| inner_tets(&c))
        },
    };
    let before = side.to_vec();
    // A hole's own holes are not widened: each level would multiply the tries.
    let widenings = if depth == 0 { MAX_WIDENING } else { 0 };
    match without_front(tri, side, all, holders, vtet, &fill, widenings) {
        Ok(tets) => return Ok(tets),
        Err(e) if depth > 0 => return Err(e),
        Err(_) => {}
    }
    // Once the fronts have spent the region's work (`work`), the last front's error is the
    // answer: another widening would only fail at once.
    if let Ok((sub_b, sub_e)) = unpinched_hole_surface(tri, side, all, holders, vtet, name)
        && worth_a_front(&sub_b, &sub_e, all)
    {
        match mesh_holes(tri, &sub_b, &sub_e, true, &fill) {
            Ok(tets) => return Ok(tets),
            Err((e, hole)) => {
                if is_whole_region(&hole, &sub_e, all) {
                    work.whole_region_failed();
                }
                if work.exhausted(0) || give_up() {
                    return Err(e);
                }
            }
        }
    }
    side.copy_from_slice(&before);
    let mut widened = 0;
    let mut tried = 0;
    let mut at = None;
    loop {
        let (sub_b, sub_e) = unpinched_hole_surface(tri, side, all, holders, vtet, name)?;
        let faces = sub_b.len() + sub_e.len();
        let mut failed = None;
        if widened == MAX_WIDENING || worth_a_try(faces, tried, all.len()) {
            match mesh_holes(tri, &sub_b, &sub_e, true, &fill) {
                Ok(tets) => return Ok(tets),
                Err((e, _)) if widened < MAX_WIDENING && !work.exhausted(0) && !give_up() => {
                    let Some(p) = e.at else { return Err(e) };
                    (at, tried, failed) = (Some(p), faces, Some(e));
                }
                Err((e, _)) => return Err(e),
            }
        }
        widened += 1;
        // Nothing left to take round the stuck place: the last try's error, or a last try.
        if at.is_none_or(|p| widen_hole(tri, side, &sub_b, p) == 0) {
            match failed {
                Some(e) => return Err(e),
                None => widened = MAX_WIDENING,
            }
        }
    }
}

/// Whether holes widened to `faces` faces are tried again, the last try having been on `tried`
/// faces (none yet: 0), in a region of `region` triangles: once they have grown by
/// [`TRY_GROWTH`], while they are under [`MAX_WIDENED_SHARE`] of the region. A try costs about
/// what its holes' size does, so the tries up to a given size cost a few times the last one,
/// where a try at each ring of widening cost the sum of every ring's size. Holes wider than that
/// share get no front of their own (`worth_a_front`): they are tried only when they can widen
/// no further (the whole region, in a closed body) or after the last ring.
fn worth_a_try(faces: usize, tried: usize, region: usize) -> bool {
    tried == 0
        || (faces * TRY_GROWTH.1 >= tried * TRY_GROWTH.0
            && faces * MAX_WIDENED_SHARE.1 < region * MAX_WIDENED_SHARE.0)
}

/// Whether the recovery of a region whose fronts have spent `spent` units gives up widening its
/// holes: past [`PINCHED_FRONT_WORK`], when `pinched` says the region is pinched (asked only
/// then: measuring costs a twentieth to a fifth of a region's meshing).
fn gives_up(spent: u64, pinched: impl FnOnce() -> bool) -> bool {
    spent > PINCHED_FRONT_WORK && pinched()
}

/// Whether the holes as widened without the front (`boundary`, with `embedded` inside) are worth
/// a front of their own before the holes as they were: when they are the whole region (a closed
/// body, where this front still recovers the segments) or less than [`MAX_WIDENED_SHARE`] of its
/// triangles. Holes widened over most of the region but not all of it cost the front about what
/// the whole region does, with walls of kept tets left to pin it: on RINGMesh modelA4 a front on
/// 10,360 of a region's 13,836 triangles failed in 7.5 s, where fronts on the holes as they were
/// then closed them in 2.7 s; on a jittered horizon one on 14,145 of 19,381 failed in 9.2 s, and
/// the front on the whole region, which follows the recovery, meshed it in 4.8 s.
fn worth_a_front(boundary: &[[u32; 3]], embedded: &[[u32; 3]], all: &[([u32; 3], bool)]) -> bool {
    let faces = boundary.len() + embedded.len();
    faces * MAX_WIDENED_SHARE.1 < all.len() * MAX_WIDENED_SHARE.0
        || is_whole_region(boundary, embedded, all)
}

/// Whether a hole (`boundary`, with `embedded` inside) is made of exactly the region's own
/// triangles `all` (compared as vertex sets, each once): the front that failed on it failed on
/// the whole region.
fn is_whole_region(boundary: &[[u32; 3]], embedded: &[[u32; 3]], all: &[([u32; 3], bool)]) -> bool {
    if boundary.len() + embedded.len() != all.len() {
        return false;
    }
    let sorted = |t: &[u32; 3]| {
        let mut t = *t;
        t.sort_unstable();
        t
    };
    let mut hole: Vec<[u32; 3]> = boundary.iter().chain(embedded).map(sorted).collect();
    let mut region: Vec<[u32; 3]> = all.iter().map(|(t, _)| sorted(t)).collect();
    hole.sort_unstable();
    region.sort_unstable();
    hole == region
}

/// The holes filled without the front, each that cannot be taking the inner tets round it, ring
/// by ring, at most `widenings` rings, and tried again once grown by half (`worth_a_try`); the
/// error is the last hole's.
fn without_front<D: Fn(&RegionInput) -> Option<holes::Filled>>(
    tri: &mut Tri,
    side: &mut [Side],
    all: &[([u32; 3], bool)],
    holders: &[Holders],
    vtet: &[u32],
    fill: &Filler<'_, D>,
    widenings: usize,
) -> Result<Vec<[u32; 4]>, TetMeshError> {
    let mut widened = 0;
    let mut tried = 0;
    // The vertices whose inner tets join the holes next: the failed hole's after a try, the
    // last ring's after a widening not tried.
    let mut wall = Vec::new();
    loop {
        let (sub_b, sub_e) = unpinched_hole_surface(tri, side, all, holders, vtet, fill.name)?;
        let faces = sub_b.len() + sub_e.len();
        let mut failed = None;
        if widened == widenings || worth_a_try(faces, tried, all.len()) {
            match mesh_holes(tri, &sub_b, &sub_e, false, fill) {
                Ok(tets) => return Ok(tets),
                Err((e, _)) if widened == widenings => return Err(e),
                Err((e, hole)) => {
                    (tried, failed) = (faces, Some(e));
                    wall = hole.into_iter().flatten().collect();
                }
            }
        }
        widened += 1;
        let ring = widen_around(tri, side, std::mem::take(&mut wall));
        if ring.is_empty() {
            // Nothing left to take: the last try's error, or a last try.
            match failed {
                Some(e) => return Err(e),
                None => widened = widenings,
            }
        }
        wall = ring.iter().flat_map(|&t| tri.t[t as usize].v).collect();
    }
}

/// The tets filling `input` without the front: its vertices' Delaunay tetrahedralization, its
/// triangles recovered, its holes filled by their own Delaunay meshes, cones or peeling (a front
/// given no work gives way at once), with the nodes those added; `None` where that fails.
pub fn without_any_front(input: &RegionInput, size: &SizeField) -> Option<holes::Filled> {
    let bars = [Span::none(), Span::none()];
    let c = conforming(input, size, bars, &FrontWork::with(0, 0)).ok()?;
    Some(inner_tets(&c))
}

/// The inner tets of a conforming mesh in its input's numbering, the nodes its holes added
/// numbered after the input's (no inner tet uses an enclosing corner), and those nodes.
fn inner_tets(c: &Conforming) -> holes::Filled {
    let n = c.n_input as u32;
    let map = |v: u32| if v < n { v } else { v - 4 };
    let tets = c
        .tri
        .live_tets()
        .map(|t| c.tri.t[t as usize].v.map(map))
        .collect();
    (c.tri.pts[c.n_input + 4..].to_vec(), tets)
}

/// A tetrahedralization of only the enclosing tet, far around the input's bounding box.
fn enclosing_tet(input: &RegionInput) -> Tri {
    let n = input.vertices.len();
    let mut pts = input.vertices.clone();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &pts {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let c = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
    let ext = (0..3)
        .map(|k| hi[k] - lo[k])
        .fold(0.0f64, f64::max)
        .max(1.0);
    let s = 1.0e3 * ext;
    for d in [[1., 1., 1.], [1., -1., -1.], [-1., 1., -1.], [-1., -1., 1.]] {
        pts.push([c[0] + s * d[0], c[1] + s * d[1], c[2] + s * d[2]]);
    }
    let n32 = n as u32;
    let mut st = [n32, n32 + 1, n32 + 2, n32 + 3];
    if orient3d(&pts[n], &pts[n + 1], &pts[n + 2], &pts[n + 3]) != Orientation::Positive {
        st.swap(0, 1);
    }
    Tri::new(pts, st)
}

/// Inserts the boundary, embedded and segment vertices (in `brio` order); one that fails is the
/// error.
fn insert_boundary_vertices(
    tri: &mut Tri,
    input: &RegionInput,
    bar: Span<'_>,
) -> Result<(), TetMeshError> {
    let n = input.vertices.len();
    let mut used = vec![false; n];
    for t in input.boundary.iter().chain(&input.embedded) {
        for &v in t {
            used[v as usize] = true;
        }
    }
    for &v in input.lines.iter().flatten() {
        used[v as usize] = true;
    }
    let ids: Vec<u32> = (0..n as u32).filter(|&v| used[v as usize]).collect();
    // A Delaunay tetrahedralization of boundary points (the enclosing tet's included) has 7 to
    // 7.7 tets per point on our regions, thin layers the most: room for 8, so that no
    // reallocation doubles the array at its peak, and no more (it is most of a thin region's).
    tri.reserve(8 * ids.len() + 64);
    for (k, v) in brio(&ids, &input.vertices).into_iter().enumerate() {
        bar.step(k, ids.len());
        let p = input.vertices[v as usize];
        tri.insert_vertex(v, NONE, &Limits::default())
            .map_err(|r| {
                TetMeshError::new(
                    &input.name,
                    format!("boundary vertex {v} could not be inserted ({r:?})"),
                    Some(p),
                )
            })?;
    }
    Ok(())
}

/// The constraint triangles (boundary, then embedded flagged `true`) and their index.
fn constraints(input: &RegionInput) -> (Vec<([u32; 3], bool)>, FaceMap<u32>) {
    // Looked up once per tet face, never iterated: the front's fast word hash.
    let mut cons_index: FaceMap<u32> = FaceMap::with_capacity_and_hasher(
        input.boundary.len() + input.embedded.len(),
        Default::default(),
    );
    let all: Vec<([u32; 3], bool)> = input
        .boundary
        .iter()
        .map(|&t| (t, false))
        .chain(input.embedded.iter().map(|&t| (t, true)))
        .collect();
    for (k, (t, _)) in all.iter().enumerate() {
        cons_index.insert(sorted(*t), k as u32);
    }
    (all, cons_index)
}

/// Whether recovery may go on with the missing triangles (input checked, not too many).
fn check_missing(
    input: &RegionInput,
    tri: &Tri,
    all: &[([u32; 3], bool)],
    missing: &[usize],
) -> Result<(), TetMeshError> {
    // Triangles that are all faces of the tetrahedralization cannot meet improperly (see
    // `check::check_shape`); otherwise the input is checked in full before any recovery, so an
    // intersection is reported as such.
    if !missing.is_empty() {
        check_intersections(input)?;
    }
    if missing.len() > MAX_MISSING && missing.len() * MAX_MISSING_SHARE > all.len() {
        let at = tri.pts[all[missing[0]].0[0] as usize];
        return Err(TetMeshError::new(
            &input.name,
            format!(
                "{} of the {} boundary and embedded triangles are not Delaunay faces (a structured, \
                 cospherical boundary?): too many to recover locally",
                missing.len(),
                all.len()
            ),
            Some(at),
        ));
    }
    Ok(())
}

/// Per constraint (index into the list `cons_index` maps to): the (tet, face) pairs holding it.
///
/// Each face is looked up once, from its tet of smaller slot, which notes both sides (in slot
/// order, as a scan of every tet's faces would); faces on an enclosing corner (ids from
/// `n_input` on) are no constraint and are not looked up.
fn find_holders(tri: &Tri, cons_index: &FaceMap<u32>, n: usize, n_input: usize) -> Vec<Holders> {
    let mut holders = vec![Holders([NONE; 2]); n];
    for t in tri.live_tets() {
        let rec = &tri.t[t as usize];
        for i in 0..4 {
            let other = rec.adj[i];
            if other != NONE && other >> 2 < t {
                continue;
            }
            let f = tri.face(t, i);
            if f.iter().any(|&v| v as usize >= n_input) {
                continue;
            }
            if let Some(&k) = cons_index.get(&sorted(f)) {
                holders[k as usize].push(t, i);
                if other != NONE {
                    holders[k as usize].push(other >> 2, (other & 3) as usize);
                }
            }
        }
    }
    holders
}

/// One tet of each vertex (`NONE` for vertices in no tet).
fn vertex_tets(tri: &Tri) -> Vec<u32> {
    let mut vtet = vec![NONE; tri.pts.len()];
    for t in tri.live_tets() {
        for &v in &tri.t[t as usize].v {
            vtet[v as usize] = t;
        }
    }
    vtet
}

/// For each missing constraint triangle `uvw` whose edge `uv` the tetrahedralization crosses in
/// the triangle's plane by an edge `wz` (a coplanar quad `u w v z` holding the other diagonal),
/// flip `wz` to `uv` (`flip44`, where `wz` has four tets round it). The quad's other half may
/// be a neighbouring constraint triangle (a structured grid with its diagonals one way) or no
/// constraint at all (a chequerboard of triangles touching at corners, whose gaps are the other
/// halves): `z` is sought among the vertices round `w` in the triangle's plane, so either is
/// found. An edge of a constraint triangle is never flipped away. Returns the number of flips;
/// `vtet` is kept current.
fn flip_diagonals(
    tri: &mut Tri,
    all: &[([u32; 3], bool)],
    missing: &[usize],
    vtet: &mut [u32],
) -> usize {
    // Constraint edges, sorted: an edge of a constraint triangle is never flipped away.
    let mut edges: Vec<[u32; 2]> = (all.iter())
        .flat_map(|(t, _)| (0..3).map(move |e| sorted_pair(t[e], t[(e + 1) % 3])))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let mut flips = 0;
    // (vertex round `w`, a tet holding the edge to it): a failed `flip44` changes no tet.
    let mut near: Vec<(u32, u32)> = Vec::new();
    for &k in missing {
        let t = all[k].0;
        for e in 0..3 {
            let (u, v, w) = (t[e], t[(e + 1) % 3], t[(e + 2) % 3]);
            if vtet[w as usize] == NONE {
                continue;
            }
            // The vertices round `w`, each once; those in the triangle's plane are tried.
            near.clear();
            for s in star(tri, w, vtet[w as usize]) {
                for &z in &tri.t[s as usize].v {
                    if ![u, v, w].contains(&z) && !near.iter().any(|&(x, _)| x == z) {
                        near.push((z, s));
                    }
                }
                if near.len() > MAX_NEAR {
                    break;
                }
            }
            for &(z, start) in &near {
                if edges.binary_search(&sorted_pair(w, z)).is_ok() || !coplanar(tri, [u, v, w, z]) {
                    continue;
                }
                if let Some(new) = tri.flip44(w, z, start, u, v) {
                    flips += 1;
                    for &n in &new {
                        for &x in &tri.t[n as usize].v {
                            vtet[x as usize] = n;
                        }
                    }
                    break;
                }
            }
        }
    }
    flips
}

/// The most vertices round a constraint triangle's vertex that [`flip_diagonals`] looks at.
const MAX_NEAR: usize = 256;

fn sorted_pair(a: u32, b: u32) -> [u32; 2] {
    [a.min(b), a.max(b)]
}

/// Star sizes up to which [`Star`] scans its list for a tet already met.
const STAR_SCAN: usize = 64;

/// Tets around vertex `v`, starting from one of them, in breadth-first order.
fn star(tri: &Tri, v: u32, start: u32) -> Star<'_> {
    Star {
        tri,
        v,
        out: vec![start],
        seen: WordSet::default(),
        k: 0,
    }
}

/// The tets round a vertex, met breadth-first and handed out as met: a search for one tet of
/// the star stops there. A vertex's star holds a few dozen tets, where a scan of the list is
/// fastest; a hole's own Delaunay mesh can give a hull vertex thousands, where scanning, and
/// gathering the whole star to find one tet, made the recovery of each edge quadratic.
struct Star<'a> {
    tri: &'a Tri,
    v: u32,
    out: Vec<u32>,
    seen: WordSet<u32>,
    k: usize,
}

impl Iterator for Star<'_> {
    type Item = u32;

    fn next(&mut self) -> Option<u32> {
        let t = *self.out.get(self.k)?;
        self.k += 1;
        let tet = &self.tri.t[t as usize];
        for (i, &w) in tet.v.iter().enumerate() {
            let a = tet.adj[i];
            if w == self.v || a == NONE {
                continue;
            }
            let new = if self.out.len() < STAR_SCAN {
                !self.out.contains(&(a >> 2))
            } else {
                if self.seen.is_empty() {
                    self.seen.extend(&self.out);
                }
                self.seen.insert(a >> 2)
            };
            if new {
                self.out.push(a >> 2);
            }
        }
        Some(t)
    }
}

/// Whether the closed tet `t` may meet the open triangle `f` (conservative: `false` only when a
/// plane separates them, decided exactly). Closed, so that where `f` lies in the plane of tet
/// faces that triangulate the same piece of plane differently (coplanar boundary points, as on
/// a box side), the tets on both sides of that plane are taken.
fn meets(tri: &Tri, t: u32, f: [u32; 3]) -> bool {
    let tv = tri.t[t as usize].v;
    let p = |v: u32| &tri.pts[v as usize];
    let o = |a: u32, b: u32, c: u32, d: u32| orient3d(p(a), p(b), p(c), p(d)).sign();
    // The triangle's plane: the tet strictly on one side.
    let s: Vec<i32> = tv.iter().map(|&w| o(f[0], f[1], f[2], w)).collect();
    if s.iter().all(|&x| x > 0) || s.iter().all(|&x| x < 0) {
        return false;
    }
    // A tet face's plane: the open triangle strictly outside.
    for fi in FACE {
        let g = [tv[fi[0]], tv[fi[1]], tv[fi[2]]];
        let sf: Vec<i32> = f.iter().map(|&x| o(g[0], g[1], g[2], x)).collect();
        if sf.iter().all(|&x| x >= 0) && sf.iter().any(|&x| x > 0) {
            return false;
        }
    }
    // Planes through an edge of the triangle and a tet vertex: the open triangle strictly on its
    // third vertex's side, the tet on the other closed side.
    for e in 0..3 {
        let (a, b, c) = (f[e], f[(e + 1) % 3], f[(e + 2) % 3]);
        for &w in &tv {
            if w == a || w == b {
                continue;
            }
            let sc = o(a, b, w, c);
            if sc != 0 && tv.iter().all(|&x| o(a, b, w, x) * sc <= 0) {
                return false;
            }
        }
    }
    // Planes through an edge of the tet and a triangle vertex: the rest of the tet strictly on
    // one side, the open triangle strictly on the other.
    for i in 0..4 {
        for j in i + 1..4 {
            let (a, b) = (tv[i], tv[j]);
            let rest: Vec<u32> = (0..4)
                .filter(|&k| k != i && k != j)
                .map(|k| tv[k])
                .collect();
            for &x in &f {
                if x == a || x == b {
                    continue;
                }
                let s0 = o(a, b, x, rest[0]);
                let s1 = o(a, b, x, rest[1]);
                if s0 == 0 || s0 != s1 {
                    continue;
                }
                let sy: Vec<i32> = f.iter().map(|&y| o(a, b, x, y) * s0).collect();
                if sy.iter().all(|&y| y <= 0) && sy.iter().any(|&y| y < 0) {
                    return false;
                }
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::{
        PINCHED_FRONT_WORK, RegionInput, STAR_SCAN, Span, enclosing_tet, gives_up,
        insert_boundary_vertices, is_whole_region, star, vertex_tets, worth_a_front, worth_a_try,
    };

    #[test]
    fn a_hole_is_the_whole_region_only_when_it_is_made_of_exactly_the_regions_triangles() {
        let all = [([0, 1, 2], false), ([0, 2, 3], false), ([1, 2, 4], true)];
        // The same triangles, turned and in another order: the whole region.
        assert!(is_whole_region(&[[3, 0, 2], [2, 1, 0]], &[[4, 2, 1]], &all));
        // One triangle swapped for a face of a kept tet, one missing, one repeated: not.
        assert!(!is_whole_region(
            &[[0, 1, 2], [0, 2, 5]],
            &[[1, 2, 4]],
            &all
        ));
        assert!(!is_whole_region(&[[0, 1, 2]], &[[1, 2, 4]], &all));
        assert!(!is_whole_region(
            &[[0, 1, 2], [0, 1, 2]],
            &[[1, 2, 4]],
            &all
        ));
    }

    #[test]
    fn the_recovery_gives_up_on_a_pinched_region_once_its_fronts_spent_what_a_closing_one_does() {
        let measured = std::cell::Cell::new(0);
        let pinched = |is: bool| {
            let m = &measured;
            move || {
                m.set(m.get() + 1);
                is
            }
        };
        // Below the bound the pinch is not even measured.
        assert!(!gives_up(PINCHED_FRONT_WORK, pinched(true)));
        assert_eq!(measured.get(), 0);
        assert!(gives_up(PINCHED_FRONT_WORK + 1, pinched(true)));
        // A region that is not pinched goes on widening, whatever its fronts spent.
        assert!(!gives_up(u64::MAX, pinched(false)));
        assert_eq!(measured.get(), 2);
    }

    #[test]
    fn widened_holes_get_a_front_of_their_own_when_small_or_the_whole_region_but_not_between() {
        let all: Vec<([u32; 3], bool)> = (0..8).map(|k| ([k, k + 1, k + 2], false)).collect();
        let own: Vec<[u32; 3]> = all.iter().map(|(t, _)| *t).collect();
        let kept = |n: u32| (0..n).map(|k| [k, k + 1, 20 + k]).collect::<Vec<_>>();
        // Three of eight triangles: small enough.
        assert!(worth_a_front(&kept(3), &[], &all));
        // Four, five or seven of eight, but not the region's own: most of it, with walls.
        assert!(!worth_a_front(&kept(4), &[], &all));
        assert!(!worth_a_front(&kept(5), &[], &all));
        assert!(!worth_a_front(&kept(7), &[], &all));
        // Eight that are not the region's own triangles: still not.
        assert!(!worth_a_front(&kept(8), &[], &all));
        // The region's own triangles: its front, which still recovers the segments.
        assert!(worth_a_front(&own, &[], &all));
        // Half of them as embedded triangles count the same.
        assert!(!worth_a_front(&kept(2), &kept(2), &all));
    }

    #[test]
    fn a_star_hands_out_every_tet_at_its_vertex_once_however_many_there_are() {
        // A 7 x 7 x 7 lattice, slightly sheared so no five points are cospherical.
        let mut vertices = Vec::new();
        for i in 0..7 {
            for j in 0..7 {
                for k in 0..7 {
                    let (x, y, z) = (i as f64, j as f64, k as f64);
                    vertices.push([x + 0.013 * y * y, y + 0.007 * z * x, z + 0.011 * x * y]);
                }
            }
        }
        let input = RegionInput {
            boundary: (0..341).map(|v| [v, v + 1, v + 2]).collect(),
            vertices,
            ..RegionInput::default()
        };
        let mut tri = enclosing_tet(&input);
        insert_boundary_vertices(&mut tri, &input, Span::none()).unwrap();
        let vtet = vertex_tets(&tri);
        // Inner lattice points have a few dozen tets; the enclosing tet's corners, past
        // `STAR_SCAN`, take the set instead of the scan.
        let corner = input.vertices.len() as u32;
        let mut big = false;
        for v in (0..corner).chain(corner..corner + 4) {
            let mut expected: Vec<u32> = tri
                .live_tets()
                .filter(|&t| tri.t[t as usize].v.contains(&v))
                .collect();
            let mut got: Vec<u32> = star(&tri, v, vtet[v as usize]).collect();
            assert_eq!(got[0], vtet[v as usize]);
            big |= got.len() > STAR_SCAN;
            got.sort_unstable();
            expected.sort_unstable();
            assert_eq!(got, expected, "the star of vertex {v}");
        }
        assert!(big, "some star is past the scan's size");
        // A search stops at the first tet that answers: no further tet is visited.
        let mut it = star(&tri, corner, vtet[corner as usize]);
        assert_eq!(it.next(), Some(vtet[corner as usize]));
        assert!(it.k == 1);
    }

    #[test]
    fn widened_holes_are_tried_again_once_half_as_wide_again_and_only_under_half_the_region() {
        // The first try is always made.
        assert!(worth_a_try(10, 0, 1000));
        // Then only once the holes have grown by half.
        assert!(!worth_a_try(149, 100, 1000));
        assert!(worth_a_try(150, 100, 1000));
        // Holes over half the region wait for the last ring, however much they grew.
        assert!(worth_a_try(499, 100, 1000));
        assert!(!worth_a_try(500, 100, 1000));
    }
}
