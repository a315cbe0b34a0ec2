//! How a region's progress bar (`geom::progress`: a fixed length, cut into one share per phase)
//! is shared among the phases of `mesh_region`, so that it moves about evenly in time.
//!
//! The shares are weights in microseconds per item, from the phases' times on the didactic
//! model's refinement (d) (regions of 9k to 48k nodes, 0.07 to 0.65 s each, one thread): the
//! Delaunay insertion of the input vertices took 3.3-3.9 µs per vertex, their recovery about
//! 0.8, refinement 6-6.5 µs per node it inserted, the layout 0.2 µs per node, optimization 2-5.6
//! µs per node (its inner shares are in `optimize`) and the statistics with the exact
//! verification 1-1.5 µs per node.
//!
//! What is known when: the nodes refinement will insert are estimated once the region's
//! conforming Delaunay mesh and its size field exist ([`new_nodes`]), which cuts the bar after
//! the conforming mesh. The share of the checks and of the conforming mesh is fixed before, from
//! a rougher guess out of the boundary alone ([`guessed_new_nodes`]): bulk regions add 1-3 nodes
//! per input vertex, thin layers next to none, and the insertion is 7 % of a bulk region's time
//! but half of a thin layer's. The advancing front (alone, or after Delaunay gave way) took about
//! 90 % of a bulk region's time on the refinement (b) meshed by the front, its optimization and
//! checks the rest (in a thin layer, 40 % and 60 %), which fixes its share. Where a phase has no
//! count of its own (the layout, the set-up of the optimizer's complex, the verification) the
//! bar stands still during it, then moves on.
//!
//! These numbers only decide how evenly the bar moves: a wrong estimate makes a share pass
//! faster or slower than its time, never a different mesh.

use geom::predicates::{cross, dist, dot, sub};

use super::RegionInput;

/// The input checks of the Delaunay method (shape, segments).
pub const CHECKS: f64 = 0.01;
/// The checks of the advancing front (every pair of triangles, exactly).
pub const FRONT_CHECKS: f64 = 0.05;

const INSERT_PER_VERTEX: f64 = 4.0;
const RECOVER_PER_VERTEX: f64 = 0.8;
const REFINE_PER_NODE: f64 = 6.0;
const LAYOUT_PER_NODE: f64 = 0.2;
const OPTIMIZE_PER_NODE: f64 = 4.0;
const FINISH_PER_NODE: f64 = 1.3;
/// Refinement's new nodes per input vertex and per boundary edge length of the region's
/// thickness, guessed before they can be estimated.
const GUESSED_NEW_PER_THICKNESS: f64 = 0.3;
/// The advancing front's time per node.
const FRONT_PER_NODE: f64 = 30.0;

/// The nodes refinement will insert in a region of `n_input` vertices whose conforming mesh
/// measures `per_size3` (`∫ h⁻³ dV`, `delaunay::refine::estimate`): about one per `h³` of
/// volume, less about a third of one per input vertex, whose neighbourhood the boundary already
/// spaces (which makes all the difference in a thin layer). Fitted on the 24 regions of the
/// didactic model and its refinements (b) and (d), from 0 to 36k new nodes: within 11 % of the
/// count on each region that adds more than a thousand.
pub fn new_nodes(per_size3: f64, n_input: usize) -> f64 {
    1.12 * (per_size3 - 0.36 * n_input as f64).max(0.0)
}

/// The nodes refinement will insert, guessed from the boundary alone: in proportion to the input
/// vertices and to the region's thickness in boundary edge lengths (`2 V / (A h)`, volume `V`,
/// boundary area `A`, mean boundary edge `h`: a slab's thickness over `h`). On the 30 regions of
/// the didactic model and its refinements, thicknesses of 0.2 to 0.8 edges (the reservoir) added
/// 0 to 0.24 nodes per input vertex, thicknesses of 2.8 to 12.8 added 1.0 to 3.0: within 30 %
/// of the count where it is more than a thousand.
pub fn guessed_new_nodes(input: &RegionInput) -> f64 {
    let pts = &input.vertices;
    let (mut area, mut edges) = (0.0, 0.0);
    for t in &input.boundary {
        let [a, b, c] = t.map(|i| pts[i as usize]);
        area += 0.5 * norm(&cross(&sub(&b, &a), &sub(&c, &a)));
        edges += dist(&a, &b) + dist(&b, &c) + dist(&c, &a);
    }
    let h = edges / (3 * input.boundary.len()).max(1) as f64;
    let thickness = 2.0 * enclosed_volume(input) / (area * h);
    let guess = GUESSED_NEW_PER_THICKNESS * thickness * pts.len() as f64;
    if guess.is_finite() {
        guess.max(0.0)
    } else {
        0.0
    }
}

/// The volume the boundary encloses (the signed volumes of its outward triangles seen from one
/// vertex; the embedded ones bound nothing).
pub fn enclosed_volume(input: &RegionInput) -> f64 {
    let pts = &input.vertices;
    let Some(o) = pts.first() else { return 0.0 };
    let sum: f64 = (input.boundary.iter())
        .map(|t| {
            let [a, b, c] = t.map(|i| sub(&pts[i as usize], o));
            dot(&a, &cross(&b, &c))
        })
        .sum();
    sum / 6.0
}

fn norm(v: &[f64; 3]) -> f64 {
    dot(v, v).sqrt()
}

/// The share of the conforming Delaunay mesh (insertion, recovery) in what follows the checks,
/// and of the insertion in it, for a region of `n_input` vertices to which refinement is guessed
/// to add `new_nodes`.
pub fn conforming_share(n_input: usize, new_nodes: f64, optimize: bool) -> (f64, f64) {
    let (n, e) = (n_input.max(1) as f64, new_nodes);
    let conforming = n * (INSERT_PER_VERTEX + RECOVER_PER_VERTEX);
    let rest = e * REFINE_PER_NODE + (n + e) * later_per_node(optimize);
    (
        conforming / (conforming + rest),
        INSERT_PER_VERTEX / (INSERT_PER_VERTEX + RECOVER_PER_VERTEX),
    )
}

/// Weights of refinement, layout, optimization and the last checks, from the input vertices
/// `n_input` and the nodes refinement is estimated to add.
pub fn after_conforming(n_input: usize, new_nodes: f64, optimize: bool) -> [f64; 4] {
    let nodes = n_input as f64 + new_nodes;
    [
        new_nodes * REFINE_PER_NODE,
        nodes * LAYOUT_PER_NODE,
        if optimize {
            nodes * OPTIMIZE_PER_NODE
        } else {
            0.0
        },
        nodes * FINISH_PER_NODE,
    ]
}

/// Weights of the advancing front, optimization and the last checks.
pub fn front(optimize: bool) -> [f64; 3] {
    [
        FRONT_PER_NODE,
        if optimize { OPTIMIZE_PER_NODE } else { 0.0 },
        FINISH_PER_NODE,
    ]
}

fn later_per_node(optimize: bool) -> f64 {
    LAYOUT_PER_NODE + FINISH_PER_NODE + if optimize { OPTIMIZE_PER_NODE } else { 0.0 }
}
