//! Quality optimization after the mesh is built: rounds of flips around the bad tets (`flips`),
//! contraction of free nodes that crowd a bad tet (`collapse`), optimization-based smoothing of
//! their free nodes (`smooth`) and, for what is left, node insertion (`slivers`); then one pass of
//! Laplacian relaxation of every free node and a last smoothing and flip pass. The objective
//! is `quality::shape`: the mean ratio capped by the scaled smallest dihedral sine, so both bars
//! of the seed's Table 2 (mean ratio >= 0.3, dihedral >= 10°) are raised together. Every change
//! keeps every tet positive (exact `orient3d`), never moves an input vertex or a node on an
//! embedded segment (those are all below `n_fixed`: a node may not yet slide along its segment)
//! and never removes a boundary or embedded face or a piece of a segment, so the optimizer
//! cannot break what `advance` or `delaunay` built; `verify` checks the result anyway.
//!
//! Flips come first (in a thin layer, after a first relaxation and smoothing of its few free
//! nodes): a refined Delaunay mesh's bad tets are slivers that a flip removes at once,
//! while smoothing their nodes first moved many nodes for little (on the peer model's L3
//! overburden, relaxing and smoothing before the rounds cost 0.7 s of 2.8 and left a lower
//! average mean ratio, 0.846 against 0.854, than relaxing once after them).
//!
//! Time stays bounded: each pass works on the list of tets below its threshold, an attempt
//! that failed is not repeated until something near it changed (`Memo`, keyed by node stamps),
//! and the insertions of all rounds share a number of tries set by the first round's list.
//! Everything runs in slot order on one thread with sorted work lists: the result is
//! deterministic.
//!
//! Progress (`geom::progress`): the optimizer's share of the bar is cut as its time was on the
//! didactic model's refinement (d) regions ([`BAR_BUILD`] …): building the complex, the rounds
//! (a round a quarter of the one before: the first flip pass was most of them, and the rounds
//! stop when nothing changes), the relaxation of every free node and the last passes; flip
//! passes, insertions and the relaxation report per item of their lists.

mod collapse;

use std::collections::HashMap;
use std::hash::BuildHasherDefault;

use geom::progress::Span;

use super::complex::Complex;
use super::flips::{Scratch, improve_tet, mean_flip_pass};
use super::front::WordHasher;
use super::slivers::insert_node_for;
use super::smooth::{relax_node, smooth_node};
use collapse::collapse_for;

type P = [f64; 3];

/// Rounds of smoothing + flips + insertion.
const ROUNDS: usize = 8;
/// Tets below this shape measure are flip and contraction candidates.
const FLIP_BELOW: f64 = 0.5;
/// In a region whose free nodes are fewer than this share of its nodes (a thin layer, where the
/// boundary makes the mesh), smoothing has little to move: flips and contractions are the remedy,
/// and they act on tets up to `THIN_FLIP_BELOW`. On the peer model's 35 m reservoir at 50 m sizes
/// (free shares 1.4 % and 2.5 %) that raised the average mean ratio from 0.878 to 0.882 and the
/// minimum from 0.50 to 0.56 (against 0.5); the same layer at 25 m sizes (5.6 % and 8 %) gained
/// 0.003 for twice the time, so it is left out. Now that insertion lifts every tet below 0.5,
/// flipping up to 0.6 keeps that: on the peer reservoirs of L1-L3 at growths 1.2 to 1.775 the
/// worst mean ratio is the same as with 0.8 or better (L3 reservoir_E at 1.775: 0.500 against
/// 0.475), the average at most 0.0003 lower, the smallest dihedral within 1.5° (19.3° against
/// 20.8° on L2 reservoir_W, 19.4° against 18.9° on L3 reservoir_E at 1.3), for 6 to 43 % less
/// time (L3 reservoir_E 1.03 s to 0.71 s); at 0.7 the time is a little over 0.6's, at 0.75 as at
/// 0.8, and at 0.5 the worst tet of L3 reservoir_E at growth 1.3 falls from 0.501 to 0.478. On
/// the geology corpus's 40 cases (closed bodies, tubes, wedges, onlaps) every model's worst tet
/// is as with 0.8 but for two mean ratios 0.0001 and 0.0015 lower, at the same dihedrals.
const THIN_FREE_SHARE: f64 = 0.05;
const THIN_FLIP_BELOW: f64 = 0.6;
/// Tets below this shape measure after flipping get an inserted node. Measured on the peer
/// model's twelve L2 and L3 blocks at growth 1.2: at 0.35 their worst mean ratios were
/// 0.36-0.51 (below 0.46 in nine), at 0.5 every block's is at least 0.50, for 0.1 % more tets
/// and no measurable time; at HXT's count the L3 overburden's smallest dihedral went from 12°
/// to 17°, and at 0.55 it took 7 % more tets and half again the time, at 0.6 four times.
const INSERT_BELOW: f64 = 0.5;
/// The rounds' insertions together try at most this many times per tet of the first round's
/// list, plus [`INSERT_TRIES_BASE`]. An attempt that failed is tried again only once something
/// near it changed, so where the rounds can improve the mesh their lists shrink by about half
/// each round: on the didactic model and its refinements the rounds of every region tried at
/// most 2.3 times its first list (3.2 times on a list of 64). Where the boundary forces the bad
/// tets (a thin layer pinched to nothing between jittered horizons), insertions succeed locally
/// and leave as many bad tets as before: a first list of 8,566 became 67,846 tries over eight
/// rounds, 17 s of the region's 18, and raised its worst tet from 0.0157 to 0.0182. The cap does
/// bind on real models: in 23 regions of the test corpus (RINGMesh, geology, SCEC), whose
/// quality checks still pass; what it costs their worst tets is not yet measured.
const INSERT_TRIES_PER_BAD: usize = 3;
const INSERT_TRIES_BASE: usize = 256;
/// Nodes whose ball is worse than this get max-min smoothing; all get Laplacian relaxation.
const SMOOTH_BELOW: f64 = 0.3;
/// Laplacian relaxation may lower a ball's worst quality for a better mean while it stays above.
const RELAX_KEEP: f64 = 0.5;
/// A layer whose free nodes are fewer than this share of its nodes is made by its boundary
/// alone: only the connectivity can still raise its average, and its optimization closes with
/// one pass of 3-2 and 4-4 flips for the average (`flips::mean_flip_pass`; new tets stay above
/// `RELAX_KEEP` or the worst they replace). On the peer model's L1 reservoir (no free node) the
/// average rose from 0.6677 to 0.6684; a second pass found a handful more, at a third more time.
const MEAN_FLIP_FREE_SHARE: f64 = 0.01;
/// Laplacian relaxation passes after the rounds.
const RELAX_PASSES: usize = 1;
/// Shares of the optimizer's progress bar: building the complex, the rounds, the relaxation
/// (once more before the rounds in a thin layer), the last passes. On the didactic model's
/// refinement (d), a 48k-node region spent 60 ms building, 180 ms in rounds, 135 ms relaxing and
/// 3 ms after.
const BAR_BUILD: f64 = 0.16;
const BAR_ROUNDS: f64 = 0.47;
const BAR_RELAX: f64 = 0.36;
const BAR_LAST: f64 = 0.01;
/// Shares of a round: its four flip passes, smoothing, insertion.
const BAR_ROUND: [f64; 6] = [0.6, 0.2, 0.08, 0.04, 0.04, 0.04];

/// Optimize in place. `protected` lists every boundary and embedded triangle, `line_edges` the
/// pieces of embedded segments (whose nodes must be below `n_fixed`); nodes below `n_fixed`
/// never move. Returns the nodes, the tets and each tet's mean ratio. Reports on `bar`.
pub fn optimize(
    nodes: Vec<P>,
    tets: Vec<[u32; 4]>,
    n_fixed: usize,
    protected: impl Iterator<Item = [u32; 3]>,
    line_edges: impl Iterator<Item = [u32; 2]>,
    bar: Span<'_>,
) -> (Vec<P>, Vec<[u32; 4]>, Vec<f64>) {
    let [building, bar] = bar.split([BAR_BUILD, 1.0 - BAR_BUILD]);
    let mut cx = Complex::new(nodes, tets, n_fixed, protected);
    cx.protect_edges(line_edges);
    building.done();
    let free = (cx.nodes.len() - n_fixed) as f64;
    let thin = free < THIN_FREE_SHARE * cx.nodes.len() as f64;
    let flip_below = if thin { THIN_FLIP_BELOW } else { FLIP_BELOW };
    let mut scratch = Scratch::default();
    let mut memo = Memo::default();
    let before = if thin { BAR_RELAX } else { 0.0 };
    let [before, rounds, relaxing, last] = bar.split([before, BAR_ROUNDS, BAR_RELAX, BAR_LAST]);
    if thin {
        // The few free nodes of a thin layer are relaxed and smoothed before the flips too:
        // cheap there, and worth 0.0007 of average on the peer model's L2 reservoir.
        relax_pass(&mut cx, before);
        smooth_pass(&mut cx, SMOOTH_BELOW, &mut memo);
    }
    // The insertion tries left to the rounds, fixed by the first round's list.
    let mut tries: Option<usize> = None;
    let rounds = rounds.split(std::array::from_fn::<f64, ROUNDS, _>(|r| {
        0.25f64.powi(r as i32)
    }));
    for round in rounds {
        let [f0, f1, f2, f3, smoothing, inserting] = round.split(BAR_ROUND);
        let mut changed = false;
        for passing in [f0, f1, f2, f3] {
            let flipped = flip_pass(&mut cx, &mut scratch, &mut memo, flip_below, passing);
            changed |= flipped;
            if !flipped {
                break;
            }
        }
        changed |= smooth_pass(&mut cx, SMOOTH_BELOW, &mut memo);
        smoothing.done();
        let bad = bad_tets(&cx, INSERT_BELOW);
        let tries = tries.get_or_insert(INSERT_TRIES_PER_BAD * bad.len() + INSERT_TRIES_BASE);
        changed |= insert_pass(&mut cx, &mut memo, &bad, tries, inserting);
        if !changed {
            break;
        }
    }
    relax_pass(&mut cx, relaxing);
    smooth_pass(&mut cx, SMOOTH_BELOW, &mut memo);
    flip_pass(&mut cx, &mut scratch, &mut memo, flip_below, last);
    if free < MEAN_FLIP_FREE_SHARE * cx.nodes.len() as f64 {
        let level = average_mean_ratio(&cx);
        mean_flip_pass(&mut cx, level, RELAX_KEEP, &mut scratch);
    }
    cx.into_measured_parts()
}

/// What was tried and failed, keyed by the sorted tet (or node) with the stamp it had then: an
/// attempt is repeated only once something near it changed, so every pass works on a short list.
/// Hash maps with a fixed hasher, looked up only, never iterated: no order reaches the result
/// (ordered maps were a third of a thin layer's flip passes, which look up every tet).
#[derive(Default)]
struct Memo {
    flips: WordMap<[u32; 4], u64>,
    inserts: WordMap<[u32; 4], u64>,
    smooth: WordMap<u32, u64>,
}

type WordMap<K, V> = HashMap<K, V, BuildHasherDefault<WordHasher>>;

impl Memo {
    fn flip_failed(&self, cx: &Complex, t: [u32; 4]) -> bool {
        self.flips.get(&sorted4(t)) == Some(&cx.stamp_of(t))
    }

    fn insert_failed(&self, cx: &Complex, t: [u32; 4]) -> bool {
        self.inserts.get(&sorted4(t)) == Some(&cx.stamp_of(t))
    }
}

fn sorted4(t: [u32; 4]) -> [u32; 4] {
    let mut k = t;
    k.sort_unstable();
    k
}

/// One pass of flips and contractions over the tets below `below`, worst first, reported on
/// `bar`. True when one was made.
fn flip_pass(
    cx: &mut Complex,
    scratch: &mut Scratch,
    memo: &mut Memo,
    below: f64,
    bar: Span<'_>,
) -> bool {
    let mut flipped = false;
    let bad = bad_tets(cx, below);
    for (k, &(_, t)) in bad.iter().enumerate() {
        bar.step(k, bad.len());
        if !cx.alive[t as usize] {
            continue;
        }
        let tv = cx.tets[t as usize];
        if memo.flip_failed(cx, tv) {
            continue;
        }
        if improve_tet(cx, t, scratch) || collapse_for(cx, t) {
            flipped = true;
        } else {
            memo.flips.insert(sorted4(tv), cx.stamp_of(tv));
        }
    }
    flipped
}

/// The average mean ratio of the live tets.
fn average_mean_ratio(cx: &Complex) -> f64 {
    let (mut n, mut sum) = (0usize, 0.0);
    for (m, _) in cx.mean_ratio.iter().zip(&cx.alive).filter(|(_, a)| **a) {
        n += 1;
        sum += m;
    }
    if n == 0 { 0.0 } else { sum / n as f64 }
}

/// Live tets below `below`, worst first (ties by slot).
fn bad_tets(cx: &Complex, below: f64) -> Vec<(f64, u32)> {
    // Counted first and sorted in place: in a thin layer most tets are below, and a list grown
    // by doubling plus a stable sort's buffer were among the largest blocks at its memory peak.
    // The slot breaks ties, so the unstable sort's order is the same on every run.
    let bad = |i: &usize| cx.alive[*i] && cx.shape[*i] < below;
    let mut v = Vec::with_capacity((0..cx.tets.len()).filter(bad).count());
    v.extend(
        (0..cx.tets.len())
            .filter(bad)
            .map(|i| (cx.shape[i], i as u32)),
    );
    v.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    v
}

/// A node insertion for each live tet of `bad` (worst first), but for those whose last insertion
/// failed with nothing near them changed since, while `tries` lasts (each attempt spends one),
/// reported on `bar`. True when a node was inserted.
fn insert_pass(
    cx: &mut Complex,
    memo: &mut Memo,
    bad: &[(f64, u32)],
    tries: &mut usize,
    bar: Span<'_>,
) -> bool {
    let mut inserted = false;
    for (k, &(_, t)) in bad.iter().enumerate() {
        bar.step(k, bad.len());
        if *tries == 0 {
            break;
        }
        if !cx.alive[t as usize] {
            continue;
        }
        let tv = cx.tets[t as usize];
        if memo.insert_failed(cx, tv) {
            continue;
        }
        *tries -= 1;
        if insert_node_for(cx, t) {
            inserted = true;
        } else {
            memo.inserts.insert(sorted4(tv), cx.stamp_of(tv));
        }
    }
    inserted
}

/// Laplacian relaxation of every free node, in index order, reported on `bar`.
fn relax_pass(cx: &mut Complex, bar: Span<'_>) {
    let mut measures = Vec::new();
    let (first, n) = (cx.n_fixed, cx.nodes.len());
    for pass in 0..RELAX_PASSES {
        for v in first..n {
            bar.step(pass * (n - first) + v - first, RELAX_PASSES * (n - first));
            relax_node(cx, v as u32, RELAX_KEEP, &mut measures);
        }
    }
}

/// Max-min smoothing of every free node of a tet below `below` (so of every free node whose
/// ball's worst quality is below it), in index order, skipping nodes whose last smoothing failed
/// and whose ball has not changed since. True when a node moved.
fn smooth_pass(cx: &mut Complex, below: f64, memo: &mut Memo) -> bool {
    let mut todo: Vec<u32> = bad_tets(cx, below)
        .into_iter()
        .flat_map(|(_, t)| cx.tets[t as usize])
        .filter(|&v| v as usize >= cx.n_fixed)
        .collect();
    todo.sort_unstable();
    todo.dedup();
    let mut moved = false;
    for v in todo {
        let stamp = cx.stamps(&[v])[0];
        if memo.smooth.get(&v) == Some(&stamp) {
            continue;
        }
        if smooth_node(cx, v).is_some() {
            moved = true;
        } else {
            memo.smooth.insert(v, stamp);
        }
    }
    moved
}

#[cfg(test)]
mod tests {
    use super::super::{RegionInput, SizeField, TetMeshOutput, advance, stats_of, verify};
    use super::*;

    /// The cube [0,3]^3, each side split into 3x3 quads of two triangles (outward), with a
    /// dangling square at z = 1.5 (two triangles) inside.
    fn cube_with_embedded_square() -> RegionInput {
        let (mut vertices, boundary) = test_support::shapes::gridded_cube(3, 3.0);
        let n = vertices.len() as u32;
        vertices.extend([
            [1.0, 1.0, 1.5],
            [2.0, 1.0, 1.5],
            [2.0, 2.0, 1.5],
            [1.0, 2.0, 1.5],
        ]);
        RegionInput {
            name: "cube".into(),
            vertices,
            boundary,
            embedded: vec![[n, n + 1, n + 2], [n, n + 2, n + 3]],
            lines: Vec::new(),
        }
    }

    #[test]
    fn the_optimizer_keeps_every_protected_face_and_input_vertex_and_never_inverts_a_tet() {
        let input = cube_with_embedded_square();
        let work = crate::work::FrontWork::for_region(&input);
        let raw = advance::advance_front(&input, &SizeField::default(), &work).expect("meshes");
        let n_in = input.vertices.len();
        let before = TetMeshOutput {
            nodes: raw.nodes.clone(),
            tets: raw.tets.clone(),
            lines: Vec::new(),
            stats: Default::default(),
        };
        verify(&input, &before).expect("the raw mesh is valid");
        let protected = input.boundary.iter().chain(&input.embedded).copied();
        let (nodes, tets, _) = optimize(
            raw.nodes,
            raw.tets,
            n_in,
            protected,
            std::iter::empty(),
            Span::none(),
        );
        let after = TetMeshOutput {
            nodes,
            tets,
            lines: Vec::new(),
            stats: Default::default(),
        };
        assert_eq!(&after.nodes[..n_in], &input.vertices[..]);
        // verify: every tet positive (exact), every boundary face once, every embedded face
        // once on each side, no hole or overlap, volume balanced.
        verify(&input, &after).expect("the optimized mesh is valid");
        let (s0, s1) = (stats_of(&before, n_in, 0), stats_of(&after, n_in, 0));
        assert!(s1.min_mean_ratio >= s0.min_mean_ratio, "{s0:?} -> {s1:?}");
        assert!(s1.min_mean_ratio >= 0.3, "{s1:?}");
    }

    /// A slab 3 × 3 × 0.06 (a thin layer whose boundary makes its tets flat), meshed by the
    /// front.
    fn thin_slab() -> Complex {
        let (mut vertices, boundary) = test_support::shapes::gridded_cube(3, 3.0);
        for v in &mut vertices {
            v[2] *= 0.02;
        }
        let input = RegionInput {
            name: "slab".into(),
            vertices,
            boundary,
            ..RegionInput::default()
        };
        let work = crate::work::FrontWork::for_region(&input);
        let raw = advance::advance_front(&input, &SizeField::default(), &work).expect("meshes");
        let n = input.vertices.len();
        let protected = input.boundary.iter().copied();
        Complex::new(raw.nodes, raw.tets, n, protected)
    }

    #[test]
    fn insertions_stop_when_their_tries_are_spent() {
        let mut cx = thin_slab();
        let bad = bad_tets(&cx, INSERT_BELOW);
        assert!(bad.len() > 3, "the slab has flat tets: {}", bad.len());
        let (nodes, tets) = (cx.nodes.clone(), cx.tets.clone());
        // With tries to spare, a node goes in: the empty budget below is what stops it.
        let mut spare = thin_slab();
        let mut many = usize::MAX;
        assert!(insert_pass(
            &mut spare,
            &mut Memo::default(),
            &bad,
            &mut many,
            Span::none()
        ));
        let mut none = 0;
        let inserted = insert_pass(&mut cx, &mut Memo::default(), &bad, &mut none, Span::none());
        assert!(!inserted);
        assert_eq!((&cx.nodes, &cx.tets), (&nodes, &tets), "nothing changed");
        let mut two = 2;
        insert_pass(&mut cx, &mut Memo::default(), &bad, &mut two, Span::none());
        assert_eq!(two, 0, "both tries spent on a list of {}", bad.len());
        assert!(
            cx.nodes.len() <= nodes.len() + 2,
            "at most one node per try"
        );
    }
}
