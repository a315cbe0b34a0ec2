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
//! A fold is judged from the support under the triangle's centroid as found from each of its
//! corners' facets and by a global search: on a crumpled support a local search can land on
//! different facets from different starts, and `verify` starts from one corner.

use super::cdt::{CavityEdge, Cdt, FREE, NONE};
use super::support::Support;
use geom::predicates::{cross, dot, sub};

/// Rounds of repair; each splits every triangle still folded.
const MAX_ROUNDS: usize = 8;

/// Splits folded triangles until none is left or `MAX_ROUNDS` pass; returns the points added.
/// `stri` (the support triangle under each vertex, `u32::MAX` where unknown) is kept current.
pub fn repair_folds(
    cdt: &mut Cdt,
    p3: &mut Vec<[f64; 3]>,
    support: &Support,
    stri: &mut Vec<u32>,
) -> usize {
    let mut added = 0;
    for _ in 0..MAX_ROUNDS {
        let folded: Vec<[u32; 3]> = cdt
            .live_triangles()
            .filter(|&t| cdt.inside[t as usize] && folds(cdt, p3, support, stri, t))
            .map(|t| cdt.tri[t as usize])
            .collect();
        if folded.is_empty() {
            break;
        }
        for verts in folded {
            // An earlier repair this round may have taken the triangle.
            if unfold_by_flip(cdt, p3, support, stri, verts) {
                continue;
            }
            let Some(t) = find(cdt, verts) else { continue };
            if split(cdt, p3, support, stri, t) {
                added += 1;
            }
        }
    }
    added
}

/// Whether the flat 3D triangle `t` faces away from the support under its centroid (its normal
/// 90° or more from the support's there: the condition `verify` refuses).
fn folds(cdt: &Cdt, p3: &[[f64; 3]], support: &Support, stri: &[u32], t: u32) -> bool {
    let v = cdt.tri[t as usize];
    if v.iter().any(|&x| x < 3) {
        return false;
    }
    let [a, b, c] = v.map(|x| p3[x as usize]);
    let g = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
    let n = cross(&sub(&b, &a), &sub(&c, &a));
    // The support under the centroid as found from each corner's facet, and globally: on a
    // crumpled support these can differ, and `verify` looks from one of them.
    let hints = v.map(|x| stri.get(x as usize).copied().unwrap_or(u32::MAX));
    let faces_away = |on: Option<crate::support::OnSupport>| {
        on.is_some_and(|on| {
            let ns = support.normals[on.tri as usize];
            // A support triangle of zero area has no normal (`[0; 3]`) and says nothing.
            ns != [0.0; 3] && !(dot(&n, &ns) > 0.0)
        })
    };
    hints
        .iter()
        .filter(|&&h| h != u32::MAX)
        .any(|&h| faces_away(support.project_from(h, &g)))
        || faces_away(support.project(&g))
}

/// Flips an edge of the folded triangle `verts` (free, inside, and convex in the plane) when
/// neither triangle the flip makes folds; returns whether one was flipped. Where the fold is a
/// diagonal drawn the wrong way across a sharp bend of the support (the base of a spike of a
/// chart), the other diagonal follows the bend, and no split point, however many, is needed.
fn unfold_by_flip(
    cdt: &mut Cdt,
    p3: &[[f64; 3]],
    support: &Support,
    stri: &[u32],
    verts: [u32; 3],
) -> bool {
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
        if !folds(cdt, p3, support, stri, a) && !folds(cdt, p3, support, stri, b) {
            return true;
        }
        let back = cdt
            .slot_of(a, b)
            .expect("a flip leaves its two triangles neighbours");
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
