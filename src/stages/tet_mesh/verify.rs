//! Exact verification of a region's tetrahedral mesh against its input: the last gate before a
//! mesh leaves `mesh_region`, and usable on any mesh (e.g. one read back from a file).
//! Orientation is decided by `orient3d`; face conformity is combinatorial; only the volume
//! balance is a float comparison (relative 1e-9), as specified.

use crate::geom::predicates::{Orientation, orient3d, signed_volume};

use super::check::{enclosed_volume, reference_point};
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

/// Sorted faces; the count of a face is the length of its run.
struct FaceCounts(Vec<[u32; 3]>);

impl FaceCounts {
    fn get(&self, f: &[u32; 3]) -> u32 {
        let lo = self.0.partition_point(|x| x < f);
        let hi = lo + self.0[lo..].partition_point(|x| x == f);
        (hi - lo) as u32
    }
}

/// Every tet positive (exact), each boundary triangle the outward face of exactly one tet and of
/// none reversed, each embedded triangle a face of exactly two tets (one per side), every other
/// face shared by exactly two tets with opposite orientations, and the tets' total volume equal
/// to the enclosed volume (relative 1e-9).
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
    // Every tet's outward faces (canonical rotation), sorted: a face's count is the length of its
    // run. A sorted Vec takes 12 bytes per face where a hash map took several times that.
    let mut faces: Vec<[u32; 3]> = Vec::with_capacity(out.tets.len() * 4);
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
        for f in outward_faces(*t) {
            faces.push(canon(f));
        }
    }
    faces.sort_unstable();
    let faces = FaceCounts(faces);
    let mut expected_single: Vec<[u32; 3]> = Vec::with_capacity(input.boundary.len());
    for (i, t) in input.boundary.iter().enumerate() {
        let c = canon(*t);
        let got = faces.get(&c);
        let rev = faces.get(&canon([t[0], t[2], t[1]]));
        if got != 1 || rev != 0 {
            return Err(TetMeshError::new(
                name,
                format!(
                    "boundary triangle {i} {t:?} is the face of {got} tets on the inner side and {rev} outside (expected 1 and 0)"
                ),
                Some(input.vertices[t[0] as usize]),
            ));
        }
        expected_single.push(c);
    }
    expected_single.sort_unstable();
    for (i, t) in input.embedded.iter().enumerate() {
        let got = faces.get(&canon(*t));
        let rev = faces.get(&canon([t[0], t[2], t[1]]));
        if got != 1 || rev != 1 {
            return Err(TetMeshError::new(
                name,
                format!(
                    "embedded triangle {i} {t:?} is the face of {got} + {rev} tets (expected one on each side)"
                ),
                Some(input.vertices[t[0] as usize]),
            ));
        }
    }
    // Every face other than the boundary ones: exactly one tet on each side.
    for (ti, t) in out.tets.iter().enumerate() {
        for f in outward_faces(*t) {
            let c = canon(f);
            let n = faces.get(&c);
            if n != 1 {
                return Err(TetMeshError::new(
                    name,
                    format!("face {f:?} of tet {ti} is an outward face of {n} tets (overlap)"),
                    Some(nodes[f[0] as usize]),
                ));
            }
            if expected_single.binary_search(&c).is_ok() {
                continue;
            }
            let r = faces.get(&canon([f[0], f[2], f[1]]));
            if r != 1 {
                return Err(TetMeshError::new(
                    name,
                    format!(
                        "face {f:?} of tet {ti} has {r} tets on its other side (hole or overlap in the mesh)"
                    ),
                    Some(nodes[f[0] as usize]),
                ));
            }
        }
    }
    let o = reference_point(&input.vertices);
    let expect = enclosed_volume(&input.vertices, &input.boundary);
    let mut total = 0.0;
    for t in &out.tets {
        let [a, b, c, d] = t.map(|i| nodes[i as usize]);
        let [a, b, c, d] = [a, b, c, d].map(|p| [p[0] - o[0], p[1] - o[1], p[2] - o[2]]);
        total += signed_volume(&a, &b, &c, &d);
    }
    // Written so that a NaN volume fails too.
    let balanced = (total - expect).abs() <= 1e-9 * expect.abs();
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
    Ok(())
}
