//! Fold repair: a triangle that is valid in the parameter plane but whose flat 3D triangle faces
//! away from the support is split at its centre in the plane until none is left.
//!
//! The flattening maps the support's fan round a vertex into less than a full turn, but in 3D
//! that fan may turn more than 360° (a saddle at a boundary vertex: the tip of a horizon sliver
//! between two faults turns 360.2°). A coarse mesh may then hold a triangle whose angle at that
//! vertex is below 180° in the plane and above 180° on the support: its flat 3D triangle folds
//! back over its neighbours. More triangles round the vertex bring every angle below 180°, so
//! the repair inserts the folded triangle's centre in the plane (mapped onto the support, like
//! any point), with no size or spacing rule: the fold is a defect, not a size question. First,
//! though, flipping one of its edges is tried: a diagonal drawn the wrong way across a sharp bend
//! of a crumpled support unfolds that way without a point.
//!
//! A fold is judged exactly as `verify` judges it: from the support under the triangle's
//! centroid, found by a local search from its first corner's facet, that facet found as `verify`
//! finds it (the same search over the nodes the output keeps, in its order). On a crumpled
//! support, searches from different facets land on different ones, and a repair that judged
//! from the facets refinement had placed the vertices on left folds that `verify` then refused.

use super::cdt::{CavityEdge, Cdt, FREE, NONE};
use super::support::Support;
use super::verify;

/// Rounds of repair; each splits every triangle still folded.
const MAX_ROUNDS: usize = 8;

/// Splits folded triangles until none is left or `MAX_ROUNDS` pass; returns the points added.
/// `stri` (the support triangle under each vertex, `u32::MAX` where unknown) is kept current.
/// The vertices from 3 to `first_free` are the given nodes.
pub fn repair_folds(
    cdt: &mut Cdt,
    p3: &mut Vec<[f64; 3]>,
    support: &Support,
    stri: &mut Vec<u32>,
    first_free: u32,
) -> usize {
    let mut added = 0;
    for _ in 0..MAX_ROUNDS {
        let facets = verify_facets(cdt, p3, support, first_free);
        let folded: Vec<[u32; 3]> = {
            let judge = Judge {
                support,
                stri,
                facets: &facets,
            };
            cdt.live_triangles()
                .filter(|&t| cdt.inside[t as usize] && judge.folds(cdt, p3, t))
                .map(|t| cdt.tri[t as usize])
                .collect()
        };
        if folded.is_empty() {
            break;
        }
        for verts in folded {
            let judge = Judge {
                support,
                stri,
                facets: &facets,
            };
            if unfold_by_flip(cdt, p3, &judge, verts) {
                continue;
            }
            // An earlier repair this round may have taken the triangle.
            let Some(t) = find(cdt, verts) else { continue };
            if split(cdt, p3, support, stri, t) {
                added += 1;
            }
        }
    }
    added
}

/// Per vertex, the support facet `verify` finds for its node (`u32::MAX` for the super
/// triangle's vertices and for vertices no inside triangle uses, which the output drops unless
/// given): the same search from the same facets in the same order (`verify::node_facets`).
fn verify_facets(cdt: &Cdt, p3: &[[f64; 3]], support: &Support, first_free: u32) -> Vec<u32> {
    let mut used = vec![false; p3.len()];
    for t in cdt.live_triangles().filter(|&t| cdt.inside[t as usize]) {
        for v in cdt.tri[t as usize] {
            used[v as usize] = true;
        }
    }
    let kept: Vec<usize> = (3..p3.len())
        .filter(|&v| v < first_free as usize || used[v])
        .collect();
    let nodes: Vec<[f64; 3]> = kept.iter().map(|&v| p3[v]).collect();
    let mut out = vec![u32::MAX; p3.len()];
    for (v, on) in kept.into_iter().zip(verify::node_facets(support, &nodes)) {
        out[v] = on.map_or(u32::MAX, |on| on.tri);
    }
    out
}

/// How a fold is judged in one round of repair.
struct Judge<'a> {
    support: &'a Support,
    /// The support triangle under each vertex as refinement placed it (for vertices added
    /// since `facets` was found).
    stri: &'a [u32],
    /// The support facet `verify` finds for each vertex's node.
    facets: &'a [u32],
}

impl Judge<'_> {
    /// Whether the flat 3D triangle `t` faces away from the support under its centroid (its
    /// normal 90° or more from the support's there), as `verify` judges it: from the facet found
    /// for its first corner's node. A vertex added this round has none yet; it is judged from
    /// the facet refinement placed the vertex on. A support triangle of zero area has no normal
    /// and says nothing.
    fn folds(&self, cdt: &Cdt, p3: &[[f64; 3]], t: u32) -> bool {
        let v = cdt.tri[t as usize];
        if v.iter().any(|&x| x < 3) {
            return false;
        }
        let of = |list: &[u32], x: u32| list.get(x as usize).copied().unwrap_or(u32::MAX);
        let from = match of(self.facets, v[0]) {
            u32::MAX => of(self.stri, v[0]),
            f => f,
        };
        let corners = v.map(|x| &p3[x as usize]);
        verify::faces_away(self.support, corners, from).is_some_and(|(away, _)| away)
    }
}

/// Flips an edge of the folded triangle `verts` (free, inside, and convex in the plane) when
/// neither triangle the flip makes folds; returns whether one was flipped. Where the fold is a
/// diagonal drawn the wrong way across a sharp bend of the support (the base of a spike of a
/// chart), the other diagonal follows the bend, and no split point, however many, is needed.
fn unfold_by_flip(cdt: &mut Cdt, p3: &[[f64; 3]], judge: &Judge<'_>, verts: [u32; 3]) -> bool {
    for corner in verts {
        // A flip undone leaves the triangle in another slot: find it again each time.
        let Some(t) = find(cdt, verts) else {
            return false;
        };
        let Some(i) = cdt.index_in(t, corner) else {
            continue;
        };
        let n = cdt.nbr[t as usize][i];
        if cdt.fix[t as usize][i] != FREE
            || n == NONE
            || !cdt.inside[n as usize]
            || !cdt.flippable(t, i)
        {
            continue;
        }
        let (a, b) = cdt.flip(t, i);
        if !judge.folds(cdt, p3, a) && !judge.folds(cdt, p3, b) {
            return true;
        }
        // A flip leaves its two triangles neighbours; were it not so, the flip stands and
        // `verify` judges the mesh as it is.
        let Some(back) = cdt.slot_of(a, b) else {
            return false;
        };
        cdt.flip(a, back);
    }
    false
}

/// The live inside triangle with vertices `verts` (in this order, in any rotation), if still there.
fn find(cdt: &Cdt, verts: [u32; 3]) -> Option<u32> {
    let mut fan = Vec::new();
    cdt.fan(verts[0], &mut fan);
    let rotations = [0, 1, 2].map(|r| [verts[r], verts[(r + 1) % 3], verts[(r + 2) % 3]]);
    fan.into_iter()
        .find(|&t| cdt.alive[t as usize] && rotations.contains(&cdt.tri[t as usize]))
}

/// Inserts the centre of `t` in the plane, mapped onto the support.
fn split(
    cdt: &mut Cdt,
    p3: &mut Vec<[f64; 3]>,
    support: &Support,
    stri: &mut Vec<u32>,
    t: u32,
) -> bool {
    let v = cdt.tri[t as usize];
    let [a, b, c] = v.map(|x| cdt.pts[x as usize]);
    let x2 = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
    let Some((sid, x3)) = support.to_3d(&x2) else {
        return false;
    };
    let mut any = |_: &Cdt, _: &[CavityEdge]| true;
    let Ok(nv) = cdt.insert(x2, t, &mut any) else {
        return false;
    };
    let nv = nv as usize;
    if p3.len() <= nv {
        p3.resize(nv + 1, [0.0; 3]);
    }
    p3[nv] = x3;
    if stri.len() <= nv {
        stri.resize(nv + 1, u32::MAX);
    }
    stri[nv] = sid;
    true
}
