//! Delaunay meshing of a region: the Delaunay tetrahedralization of the boundary and embedded
//! vertices (`tri`, inserted in `order`), local boundary recovery (`recover`: 4-4 flips where a
//! cocircular quad took the other diagonal (`flip`), then 2-3 flips and edge removals, then holes
//! filled by their own Delaunay mesh, a cone, or the advancing front),
//! then interior nodes by Delaunay refinement against the background size field (`refine`). No
//! node is ever placed on a boundary or embedded face: recovery removes and re-meshes tets
//! instead of splitting faces, and refinement cavities never cross a constraint. It is the fast
//! path of `mesh_region`; when recovery meets something it cannot settle, the caller falls back to
//! the advancing front on the whole region.
//!
//! What each part decides:
//! * `tri`, the kernel: Bowyer-Watson with adjacency and constraint faces. Each tet slot is one
//!   40-byte record (vertices, neighbours, flood stamp, constraint bits), so a cavity's flood pays
//!   one cache miss per tet; cavities grow breadth first, each level's neighbour records and
//!   apexes requested together so their misses overlap; cavities never cross a constraint and are
//!   shrunk until star-shaped; `insphere` and `orient3d` are exact.
//! * `order`, insertion order and memory layout: a Hilbert curve whose keys are read by a
//!   tabulated 96-state automaton (equal to Skilling's transform) and sorted by LSD radix passes,
//!   in a deterministic BRIO; before optimization the refined mesh is laid out again (free nodes
//!   in curve order, tets bucketed by their highest node).
//! * `recover`: each missing boundary or embedded triangle is first made a face by flips where it
//!   can be (`recover/flips`); each still missing takes every tet that may meet it (exact
//!   separating-plane tests) into a hole; kept tets are classified by flooding from the triangles'
//!   oriented sides; the holes' inner part, grown until its surface is a manifold, is filled hole
//!   by hole without new nodes where it can be, else from one node in its kernel, else by the
//!   front. More than 500 missing triangles that are also 2 % of them (a structured cospherical
//!   grid) send the region to the front at once.
//! * `recover/segments`: embedded segments (wells), once the triangles are faces: divided to the
//!   size field, each piece made an edge by flips or split at a node on it, then protected as a
//!   constraint edge (`tri/edges`) that no later cavity removes.
//! * `refine`: circumcenters, or the ideal apex over a boundary face, inserted in Hilbert-ordered
//!   rounds with spacing and height limits from the size field (height over constraint faces and
//!   distance to constraint edges); new tets propose as they are created; a point whose tet an
//!   insertion destroyed since is dropped.
//!
//! The segments' nodes come right after the input vertices in the output (the optimizer keeps
//! every node below a bound fixed: nodes on a segment stay where they are).

mod flip;
mod order;
mod recover;
mod refine;
mod tri;

use geom::progress::Span;

use super::advance::RawMesh;
use super::progress;
use super::sizing::Background;
use super::work::FrontWork;
use super::{RegionInput, SizeField, Tail, TetMeshError};

pub use recover::connected_pieces;

/// New nodes, and tets on the given vertices and those nodes (numbered after them).
pub type Filled = (Vec<[f64; 3]>, Vec<[u32; 4]>);

/// The tets filling the closed surfaces `input` bounds without any front (see
/// `recover::without_any_front`).
pub fn fill_without_front(input: &RegionInput, size: &SizeField) -> Option<Filled> {
    recover::without_any_front(input, size)
}

/// Cells of the background size field. The field grows smoothly (at most the growth rate per
/// unit length), so a coarser grid than the front's loses nothing, and its set-up (then a
/// Dijkstra over the cells) was 8 % of a million-tet region at the front's two million cells.
const SIZE_CELLS: usize = 250_000;
/// Fewer cells for small regions: about four per boundary triangle (a thin layer with few tets
/// per boundary triangle would otherwise spend more on the grid than on its tets).
const MIN_SIZE_CELLS: usize = 4096;

/// Figures of one Delaunay meshing.
#[derive(Clone, Debug, Default)]
pub struct Figures {
    /// Boundary and embedded triangles recovered through holes.
    pub missing_faces: usize,
    /// Boundary and embedded triangles recovered by flips.
    pub flipped_faces: usize,
    /// Per input segment, its chain of nodes (output numbering); the chains' inner nodes are
    /// the nodes right after the input vertices.
    pub chains: Vec<Vec<u32>>,
    /// Nodes on segments: placed to the size field, and split to recover missing pieces.
    pub line_nodes: usize,
    pub line_splits: usize,
    /// Pieces of segments made edges by flips.
    pub line_flips: usize,
}

/// The region's mesh before optimization; `bar` is its share of the region's progress bar
/// (`progress`), which it cuts once it can estimate how many nodes refinement inserts, and
/// returns the shares left for the optimizer (`optimize`: whether it runs) and the last checks.
pub fn mesh<'m>(
    input: &RegionInput,
    size: &SizeField,
    bar: Span<'m>,
    optimize: bool,
    work: &FrontWork,
) -> Result<(RawMesh, Figures, Tail<'m>), TetMeshError> {
    let guess = progress::guessed_new_nodes(input);
    let (conforming, inserting) = progress::conforming_share(input.vertices.len(), guess, optimize);
    let [conforming, rest] = bar.split([conforming, 1.0 - conforming]);
    let bars = conforming.split([inserting, 1.0 - inserting]);
    let conf = recover::conforming(input, size, bars, work)?;
    let mut tri = conf.tri;
    let mut all = input.boundary.clone();
    all.extend_from_slice(&input.embedded);
    let cells = (4 * all.len()).clamp(MIN_SIZE_CELLS, SIZE_CELLS);
    let bg = Background::with_max_cells(&input.vertices, &all, size, cells);
    let new_nodes = progress::new_nodes(refine::estimate(&tri, &bg), conf.n_input);
    let weights = progress::after_conforming(conf.n_input, new_nodes, optimize);
    let [refining, layout, optimizing, finishing] = rest.split(weights);
    let lines = if input.lines.is_empty() {
        None
    } else {
        Some(recover::recover_segments(&mut tri, input, &bg)?)
    };
    refine::refine(&mut tri, &bg, refining, new_nodes);
    refining.done();
    // Drop the enclosing tet's four corners: ids after them shift down by four.
    let n = conf.n_input;
    let map = |v: u32| if (v as usize) < n { v } else { v - 4 };
    let mut nodes = std::mem::take(&mut tri.pts);
    nodes.drain(n..n + 4);
    let mut tets: Vec<[u32; 4]> = tri
        .live_tets()
        .map(|t| tri.t[t as usize].v.map(map))
        .collect();
    drop(tri);
    let mut figures = Figures {
        missing_faces: conf.missing,
        flipped_faces: conf.flipped,
        ..Figures::default()
    };
    let mut fixed = n;
    if let Some(r) = lines {
        figures.chains = r
            .chains
            .iter()
            .map(|c| c.iter().map(|&v| map(v)).collect())
            .collect();
        fixed += chain_nodes_first(&mut nodes, &mut tets, &mut figures.chains, n);
        (figures.line_nodes, figures.line_splits) = (r.placed + r.split, r.split);
        figures.line_flips = r.flipped;
    }
    order::spatial_layout(&mut nodes, &mut tets, fixed);
    layout.done();
    Ok((
        RawMesh {
            nodes,
            tets,
            backtracks: 0,
        },
        figures,
        Tail {
            optimize: optimizing,
            finish: finishing,
        },
    ))
}

/// Renumbers the chains' inner nodes to follow the `n` input vertices (in chain order), the
/// other new nodes after them in their order; returns how many the chains hold.
fn chain_nodes_first(
    nodes: &mut Vec<[f64; 3]>,
    tets: &mut [[u32; 4]],
    chains: &mut [Vec<u32>],
    n: usize,
) -> usize {
    let mut map: Vec<u32> = vec![u32::MAX; nodes.len()];
    let mut next = n as u32;
    for c in chains.iter() {
        for &v in &c[1..c.len() - 1] {
            if map[v as usize] == u32::MAX {
                map[v as usize] = next;
                next += 1;
            }
        }
    }
    let on_chains = next as usize - n;
    for (v, m) in map.iter_mut().enumerate() {
        if v < n {
            *m = v as u32;
        } else if *m == u32::MAX {
            *m = next;
            next += 1;
        }
    }
    let mut moved = vec![[0.0; 3]; nodes.len()];
    for (v, p) in nodes.iter().enumerate() {
        moved[map[v] as usize] = *p;
    }
    *nodes = moved;
    for t in tets.iter_mut() {
        *t = t.map(|v| map[v as usize]);
    }
    for c in chains.iter_mut() {
        for v in c.iter_mut() {
            *v = map[*v as usize];
        }
    }
    on_chains
}
