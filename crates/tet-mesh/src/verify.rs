//! Exact verification of a region's tetrahedral mesh against its input: the last gate before a
//! mesh leaves `mesh_region`, and usable on any mesh (e.g. one read back from a file).
//! Orientation is decided by `orient3d`; face conformity is combinatorial; only the volume
//! balance is a float comparison (relative 1e-9, beyond a bound on the sums' rounding).

use geom::predicates::{Orientation, orient3d};

use super::check::{Rounded, enclosed_volume_bounded, reference_point};
use super::lines::verify_chains;
use super::{RegionInput, TetMeshError, TetMeshOutput};

/// The four faces of a positive tet `abcd`, each oriented with its normal pointing out of the tet.
#[inline]
pub(crate) fn outward_faces(t: [u32; 4]) -> [[u32; 3]; 4] {
    let [a, b, c, d] = t;
    [[a, c, b], [a, b, d], [b, c, d], [c, a, d]]
}

/// Rotate an oriented triangle so its smallest index comes first (orientation kept).
#[inline]
pub(crate) fn canon(f: [u32; 3]) -> [u32; 3] {
    if f[0] <= f[1] && f[0] <= f[2] {
        f
    } else if f[1] <= f[2] {
        [f[1], f[2], f[0]]
    } else {
        [f[2], f[0], f[1]]
    }
}

/// A tet face keyed by its sorted nodes, with its orientation relative to that order (`odd`)
/// and the tet it bounds.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct Face {
    key: [u32; 3],
    odd: bool,
    tet: u32,
}

/// The sorted nodes of `f` and whether `f` is an odd permutation of them.
#[inline]
fn keyed(f: [u32; 3]) -> ([u32; 3], bool) {
    let c = canon(f);
    if c[1] < c[2] {
        (c, false)
    } else {
        ([c[0], c[2], c[1]], true)
    }
}

/// Every tet's outward faces in sorted order (by their sorted nodes, orientation, tet), one run of
/// equal nodes at a time, to `visit`; the first error stops the scan. A face's bucket is its
/// smallest node: each tet is listed in the buckets of its two smallest nodes (three faces have
/// the smallest, the fourth the next one), and the faces are made and sorted one bucket at a
/// time. That is 8 bytes per tet at once instead of a sorted list of all faces (80): the list
/// was the peak of small regions.
fn for_each_face_run<E>(
    tets: &[[u32; 4]],
    n_nodes: usize,
    mut visit: impl FnMut(&[Face]) -> Result<(), E>,
) -> Result<(), E> {
    let two_smallest = |t: &[u32; 4]| {
        let mut s = *t;
        s.sort_unstable();
        [s[0] as usize, s[1] as usize]
    };
    let mut start = vec![0u32; n_nodes + 1];
    for t in tets {
        for v in two_smallest(t) {
            start[v + 1] += 1;
        }
    }
    for i in 0..n_nodes {
        start[i + 1] += start[i];
    }
    let mut members = vec![0u32; start[n_nodes] as usize];
    let mut next = start.clone();
    for (ti, t) in tets.iter().enumerate() {
        for v in two_smallest(t) {
            members[next[v] as usize] = ti as u32;
            next[v] += 1;
        }
    }
    drop(next);
    // Which of `outward_faces` is opposite each corner.
    const OPPOSITE: [usize; 4] = [2, 3, 1, 0];
    let mut bucket: Vec<Face> = Vec::new();
    for (v, w) in start.windows(2).enumerate() {
        bucket.clear();
        for &ti in &members[w[0] as usize..w[1] as usize] {
            let t = tets[ti as usize];
            let faces = outward_faces(t);
            let low = (1..4).fold(0, |m, i| if t[i] < t[m] { i } else { m });
            let mut push = |f: [u32; 3]| {
                let (key, odd) = keyed(f);
                bucket.push(Face { key, odd, tet: ti });
            };
            if t[low] as usize == v {
                // The three faces through the smallest node.
                (0..4)
                    .filter(|&k| k != OPPOSITE[low])
                    .for_each(|k| push(faces[k]));
            } else {
                // The face without it, whose smallest node is the tet's second smallest.
                push(faces[OPPOSITE[low]]);
            }
        }
        bucket.sort_unstable();
        for run in bucket.chunk_by(|a, b| a.key == b.key) {
            visit(run)?;
        }
    }
    Ok(())
}

/// Every tet positive (exact), each boundary triangle the outward face of exactly one tet and of
/// none reversed, each embedded triangle a face of exactly two tets (one per side), every other
/// face shared by exactly two tets with opposite orientations, the tets' total volume equal
/// to the enclosed volume (relative 1e-9, beyond the sums' rounding), and each embedded segment
/// a chain of tet edges on it (`lines::verify_chains`).
pub fn verify(input: &RegionInput, out: &TetMeshOutput) -> Result<(), TetMeshError> {
    let name = &input.name;
    let n_in = input.vertices.len();
    let nodes = &out.nodes;
    if nodes.len() < n_in {
        return Err(TetMeshError::new(
            name,
            format!(
                "the mesh has {} nodes, fewer than the {n_in} input vertices",
                nodes.len()
            ),
            None,
        ));
    }
    for (i, p) in input.vertices.iter().enumerate() {
        if nodes[i] != *p {
            return Err(TetMeshError::new(
                name,
                format!("input vertex {i} moved to {:?}", nodes[i]),
                Some(*p),
            ));
        }
    }
    if out.tets.is_empty() {
        return Err(TetMeshError::new(name, "the mesh has no tetrahedra", None));
    }
    // One pass over the tets for their orientation and their total volume (taken about a point
    // of the input, so that the products stay small at UTM coordinates).
    let o = reference_point(&input.vertices);
    let mut total = Rounded::default();
    for (ti, t) in out.tets.iter().enumerate() {
        if let Some(&v) = t.iter().find(|&&v| v as usize >= nodes.len()) {
            return Err(TetMeshError::new(
                name,
                format!("tet {ti} {t:?} refers to missing node {v}"),
                None,
            ));
        }
        let [a, b, c, d] = t.map(|i| nodes[i as usize]);
        if orient3d(&a, &b, &c, &d) != Orientation::Positive {
            return Err(TetMeshError::new(
                name,
                format!("tet {ti} {t:?} is inverted or flat"),
                Some(a),
            ));
        }
        let [a, b, c, d] = [a, b, c, d].map(|p| [p[0] - o[0], p[1] - o[1], p[2] - o[2]]);
        total.add(&a, &b, &c, &d);
    }
    // Every tet's outward faces, sorted by their sorted nodes: a face's tets form a run, and the
    // runs are read once alongside the sorted input triangles (bucket by bucket, a linear scan).
    // The boundary and embedded triangles sorted the same way, walked alongside the faces.
    let sorted_input = |tris: &[[u32; 3]]| {
        let mut v: Vec<([u32; 3], usize)> = tris
            .iter()
            .enumerate()
            .map(|(i, t)| (keyed(*t).0, i))
            .collect();
        v.sort_unstable();
        v
    };
    let bnd = sorted_input(&input.boundary);
    let emb = sorted_input(&input.embedded);
    let boundary_error = |i: usize, got: usize, rev: usize| {
        let t = input.boundary[i];
        TetMeshError::new(
            name,
            format!(
                "boundary triangle {i} {t:?} is the face of {got} tets on the inner side and {rev} outside (expected 1 and 0)"
            ),
            Some(input.vertices[t[0] as usize]),
        )
    };
    let embedded_error = |i: usize, got: usize, rev: usize| {
        let t = input.embedded[i];
        TetMeshError::new(
            name,
            format!(
                "embedded triangle {i} {t:?} is the face of {got} + {rev} tets (expected one on each side)"
            ),
            Some(input.vertices[t[0] as usize]),
        )
    };
    let (mut ib, mut ie) = (0, 0);
    for_each_face_run(&out.tets, nodes.len(), |run| {
        let f = run[0];
        if ib < bnd.len() && bnd[ib].0 < f.key {
            return Err(boundary_error(bnd[ib].1, 0, 0));
        }
        if ie < emb.len() && emb[ie].0 < f.key {
            return Err(embedded_error(emb[ie].1, 0, 0));
        }
        // (same orientation as the input triangle, reversed)
        let counts = |t: [u32; 3]| {
            let odd = keyed(t).1;
            let same = run.iter().filter(|x| x.odd == odd).count();
            (same, run.len() - same)
        };
        if ib < bnd.len() && bnd[ib].0 == f.key {
            let i = bnd[ib].1;
            let (got, rev) = counts(input.boundary[i]);
            if got != 1 || rev != 0 {
                return Err(boundary_error(i, got, rev));
            }
            ib += 1;
            return Ok(());
        }
        if ie < emb.len() && emb[ie].0 == f.key {
            let i = emb[ie].1;
            let (got, rev) = counts(input.embedded[i]);
            if got != 1 || rev != 1 {
                return Err(embedded_error(i, got, rev));
            }
            ie += 1;
            return Ok(());
        }
        // Every other face: exactly one tet on each side. (`of`: the face as its tet orients it,
        // for the messages.)
        let of = || {
            outward_faces(out.tets[f.tet as usize])
                .into_iter()
                .find(|g| keyed(*g).0 == f.key)
                .unwrap_or(f.key)
        };
        let same = run.iter().filter(|x| x.odd == f.odd).count();
        if same > 1 {
            let of = of();
            return Err(TetMeshError::new(
                name,
                format!(
                    "face {of:?} of tet {} is an outward face of {same} tets (overlap)",
                    f.tet
                ),
                Some(nodes[of[0] as usize]),
            ));
        }
        if run.len() != 2 {
            let of = of();
            return Err(TetMeshError::new(
                name,
                format!(
                    "face {of:?} of tet {} has {} tets on its other side (hole or overlap in the mesh)",
                    f.tet,
                    run.len() - 1
                ),
                Some(nodes[of[0] as usize]),
            ));
        }
        Ok(())
    })?;
    if ib < bnd.len() {
        return Err(boundary_error(bnd[ib].1, 0, 0));
    }
    if ie < emb.len() {
        return Err(embedded_error(emb[ie].1, 0, 0));
    }
    // The two sums agree exactly in real arithmetic once the faces match as checked above (the
    // tets' interior faces cancel), so they may differ by their rounding only. Written so that a
    // NaN volume fails too.
    let (expect, rounding) = enclosed_volume_bounded(&input.vertices, &input.boundary);
    let (total, rounding) = (total.volume, rounding + total.bound());
    let balanced = (total - expect).abs() <= 1e-9 * expect.abs() + rounding;
    if !balanced {
        return Err(TetMeshError::new(
            name,
            format!(
                "the tets' volume {total} differs from the enclosed volume {expect} (relative {:e})",
                (total - expect) / expect
            ),
            None,
        ));
    }
    if !input.lines.is_empty() || !out.lines.is_empty() {
        verify_chains(input, out)?;
    }
    Ok(())
}
