//! From imported surfaces to the model a mesher can take: exact intersection and splitting
//! (`intersect`), the patches of each split surface (`patches`), which patches the recipe's trims
//! discard (`trims`), the patches a discarded part's trace split, joined again (`rejoin`), the
//! regions the patches bound (`regions`), the half-edge structure of one surface (`topology`),
//! curve subdivision (`discretize`), the room it has (`clearance`) and the sizes the patches'
//! curvature and width ask of it (`curvature`, `width`), how thick each region is
//! (`thickness`), and, at the crate root, the model's topology and the FE assembly along it.
//!
//! The root: the topological model of the conforming, trimmed patches — its vertices and
//! curves, with stable names, and which curves bound (or constrain) which patch.
//!
//! It decides:
//! * which support edges are **curve edges**: an edge used by two or more patches (where surfaces
//!   meet), or by a single triangle of a single patch (a free border, e.g. a fault tip);
//! * where curves end: at **topological vertices**, the points where the set of patches along the
//!   curve changes (three or more surfaces meet: a fault, a horizon and a box side), where a free
//!   border turns by more than `Tolerances::kink_angle_deg` (so discretization never cuts a
//!   corner; a jog that turns back within the edges around it is no corner, see `kinks`), or where
//!   curve edges branch;
//! * the **names**: a curve is named after the surfaces whose patches meet along it, sorted and
//!   joined by `/` (`F1/H1`), with `#k` when several curves share that set (always for a curve of
//!   a single surface: `F2#1`), `k` ranking the curves by their canonical polyline (direction from
//!   the lexicographically smaller end, then point by point, `f64::total_cmp`): never by creation
//!   order, so the same recipe gives the same names on every machine and a mesh size never
//!   renames anything;
//! * for every patch, its boundary as loops of oriented curve uses (following the patch's own
//!   triangle orientation) and its **constraints**: curves with the patch on both sides (a
//!   dangling fault's trace on a horizon), which its surface mesh must contain as edges.
//!
//! Vertices are welded by exact coordinates: splitting copies shared points bit for bit, so the
//! patches of different surfaces meet exactly. Everything is ordered by coordinates or by index,
//! never by hash order. No recursion.

mod assemble;
pub mod charts;
pub mod clearance;
pub mod conformity;
pub mod curvature;
mod curves;
pub mod discretize;
pub mod features;
pub mod intersect;
mod kinks;
pub mod patches;
pub mod regions;
pub mod rejoin;
pub mod remesh;
pub mod thickness;
pub mod tips;
pub mod topology;
pub mod touches;
pub mod trims;
pub mod union_find;
pub mod wells;
pub mod width;

pub use assemble::{
    FaceToFace, VolumeAssembly, assemble_volume, drop_pinched_faces, edge_clash, embed_polylines,
    face_to_face, patch_crossing, patch_input, region_input,
};
pub use curves::build_topology;

use serde::{Deserialize, Serialize};

/// One curve of the model: a support polyline between two topological vertices (or closed).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Curve {
    /// Stable name, e.g. `F1/H1`, `H1/box.ymin#2`, `F2#1`.
    pub name: String,
    /// The surfaces that meet along the curve, sorted (one for a free border).
    pub surfaces: Vec<String>,
    /// Indices of the patches along the curve, ascending.
    pub patches: Vec<u32>,
    /// The polyline, in canonical direction; a closed curve repeats its first point at the end.
    pub points: Vec<[f64; 3]>,
    pub closed: bool,
    /// Per point of `points`, how far it is from the other curves of its patches in their planes
    /// ([`clearance`]): its FE chords keep within half of it.
    #[serde(default)]
    pub clearance: Vec<f64>,
    /// Per point of `points`, the size the curvature of its patches asks for there
    /// ([`curvature`]; infinite where none does): its FE segments are no longer.
    #[serde(default)]
    pub curvature_size: Vec<f64>,
    /// Places `[x, y, z, size]` where a patch along the curve is narrow, with the size its width
    /// asks for there, graded like `curvature_size` ([`width`]): its FE segments are no longer.
    #[serde(default)]
    pub narrow_size: Vec<[f64; 4]>,
}

/// A curve as it appears in a patch's boundary loop.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CurveUse {
    /// Index into [`ModelTopology::curves`].
    pub curve: u32,
    /// True when the loop runs against the curve's direction.
    pub reversed: bool,
}

/// The boundary of one patch.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PatchBoundary {
    /// Closed loops, each a chain of curve uses following the patch's triangle orientation
    /// (outer loop counter-clockwise seen from the front side, holes clockwise).
    pub loops: Vec<Vec<CurveUse>>,
    /// Curves with this patch on both sides (internal constraints), ascending.
    pub constraints: Vec<u32>,
}

impl PatchBoundary {
    /// The curves its loops and constraints use, ascending, once each.
    pub fn curves(&self) -> Vec<u32> {
        let mut v: Vec<u32> = self
            .loops
            .iter()
            .flatten()
            .map(|u| u.curve)
            .chain(self.constraints.iter().copied())
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }
}

/// The model's vertices and curves, and every patch's boundary.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ModelTopology {
    /// Topological vertices, sorted lexicographically.
    pub vertices: Vec<[f64; 3]>,
    /// Sorted by name (surface set, then rank).
    pub curves: Vec<Curve>,
    /// Parallel to the patches given to [`build_topology`].
    pub patches: Vec<PatchBoundary>,
}

impl ModelTopology {
    /// The fewest segments each curve needs so that every patch loop has at least three nodes:
    /// two on each curve of a loop of two, three on a closed curve that is a loop alone (small
    /// patches cut off by creases or intersections are often bounded so).
    pub fn min_segments(&self) -> Vec<u32> {
        let mut min = vec![1u32; self.curves.len()];
        for lp in self.patches.iter().flat_map(|p| &p.loops) {
            let need = match lp.len() {
                1 => 3,
                2 => 2,
                _ => 1,
            };
            for u in lp {
                if let Some(m) = min.get_mut(u.curve as usize) {
                    *m = (*m).max(need);
                }
            }
        }
        min
    }
}

/// Why the model's topology or an FE assembly could not be built: a message naming the patch,
/// curve or region, and a point where it happens.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, thiserror::Error)]
#[error("{message}{}", geom::at_suffix(.at))]
pub struct ModelError {
    pub message: String,
    pub at: Option<[f64; 3]>,
}

impl ModelError {
    pub(crate) fn new(message: impl Into<String>, at: Option<[f64; 3]>) -> Self {
        ModelError {
            message: message.into(),
            at,
        }
    }
}

/// Lexicographic total order on points (`f64::total_cmp`): the order every machine agrees on.
pub(crate) fn cmp_points(a: &[f64; 3], b: &[f64; 3]) -> std::cmp::Ordering {
    (0..3)
        .map(|k| a[k].total_cmp(&b[k]))
        .find(|o| o.is_ne())
        .unwrap_or(std::cmp::Ordering::Equal)
}

/// Exact-coordinate key of a point (`-0.0` folded onto `0.0`), for welding.
pub(crate) fn point_key(p: &[f64; 3]) -> [u64; 3] {
    let k = |x: f64| if x == 0.0 { 0u64 } else { x.to_bits() };
    [k(p[0]), k(p[1]), k(p[2])]
}
