//! The two sides of the surface triangles, shared by every writer that names them (Exodus and
//! Abaqus side sets, msh physical groups and volume boundaries, the VTU's fault side cells,
//! TetGen's front and back tets of each face).
//!
//! A triangle's front is the side its right-hand normal `(b-a)×(c-a)` points to (exact
//! `orient3d`); the mesh keeps every patch triangle oriented like its surface, so that is the
//! surface's front as the model names it. [`face_uses`] finds the tets that have a triangle as a
//! face and on which side each lies; a face is also named by its TETRA4 side, as Exodus numbers
//! them (Exodus II manual): side 1 = nodes 1 2 4, side 2 = 2 3 4, side 3 = 1 4 3, side 4 =
//! 1 3 2, each ordered so its right-hand normal points out of a positive tet.
//!
//! [`fault_sides`] numbers the faults' `<fault>:front` and `<fault>:back` groups after the
//! surface groups, one id scheme for every format: the `k`-th fault group (in group order, empty
//! ones counted) of `n` groups has `front` = `n + 2k + 1` and `back` = `n + 2k + 2`.

use geom::mesh::{SurfaceGroup, SurfaceKind, VolumeMesh};
use geom::predicates::{Orientation, orient3d};
use rayon::prelude::*;
use std::collections::HashMap;

/// The TETRA4 sides as 0-based local node indices, side 1 first.
pub(crate) const TETRA4_SIDES: [[usize; 3]; 4] = [[0, 1, 3], [1, 2, 3], [0, 3, 2], [0, 2, 1]];

/// One tet that has a given triangle as a face.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct FaceUse {
    /// The tet's index in the mesh.
    pub(crate) tet: u32,
    /// The tet's 1-based element number.
    pub(crate) elem: u32,
    /// The face's 1-based TETRA4 side number in that tet.
    pub(crate) side: u32,
    /// Whether the tet lies on the triangle's front.
    pub(crate) front: bool,
}

/// For every triangle of `mesh`, the tets that have it as a face (two for an interior face, one
/// on the boundary, none for a triangle that is no tet face), lowest element number first;
/// `number` gives each tet's element number.
pub(crate) fn face_uses(mesh: &VolumeMesh, number: &[u32]) -> Vec<Vec<FaceUse>> {
    // Looked up only, never iterated: the output does not depend on the map's order.
    let mut by_key: HashMap<[u32; 3], Vec<usize>> = HashMap::new();
    for (i, t) in mesh.triangles.iter().enumerate() {
        by_key.entry(sorted(*t)).or_default().push(i);
    }
    // Most tets have no node on a triangle: their faces are not looked up at all.
    let mut on_triangle = vec![false; mesh.nodes.len()];
    for &v in mesh.triangles.iter().flatten() {
        if let Some(x) = on_triangle.get_mut(v as usize) {
            *x = true;
        }
    }
    let on = |v: u32| on_triangle.get(v as usize).copied().unwrap_or(false);
    // The tets in chunks on the build's threads, each chunk's finds in tet order, gathered in
    // chunk order: the same lists, in the same order, for any number of threads.
    let found: Vec<Vec<(usize, FaceUse)>> = (0..mesh.tets.len().div_ceil(TETS_PER_CHUNK))
        .into_par_iter()
        .map(|chunk| {
            let mut out = Vec::new();
            let start = chunk * TETS_PER_CHUNK;
            let tets = mesh.tets.iter().enumerate().skip(start);
            for (t, &tet) in tets.take(TETS_PER_CHUNK) {
                for (s, local) in TETRA4_SIDES.iter().enumerate() {
                    let face = local.map(|k| tet[k]);
                    if !face.iter().all(|&v| on(v)) {
                        continue;
                    }
                    let Some(tris) = by_key.get(&sorted(face)) else {
                        continue;
                    };
                    let apex = tet[6 - local.iter().sum::<usize>()];
                    for &i in tris {
                        out.push((
                            i,
                            FaceUse {
                                tet: t as u32,
                                elem: number[t],
                                side: s as u32 + 1,
                                front: in_front(mesh, mesh.triangles[i], apex),
                            },
                        ));
                    }
                }
            }
            out
        })
        .collect();
    let mut uses = vec![Vec::new(); mesh.triangles.len()];
    for (i, u) in found.into_iter().flatten() {
        uses[i].push(u);
    }
    for u in &mut uses {
        u.sort_by_key(|f| f.elem);
    }
    uses
}

/// Tets per parallel chunk of [`face_uses`]: large enough that a chunk's work outweighs its
/// scheduling.
const TETS_PER_CHUNK: usize = 1 << 16;

/// Fails, naming the first triangle's group and corners, when a triangle is no tet face:
/// Exodus and Abaqus name only element faces.
pub(crate) fn every_triangle_a_face(
    mesh: &VolumeMesh,
    uses: &[Vec<FaceUse>],
) -> Result<(), String> {
    match uses.iter().position(Vec::is_empty) {
        Some(i) => Err(orphan(mesh, i)),
        None => Ok(()),
    }
}

/// The use on the triangle's front (`front`) or back, of the lowest element number.
pub(crate) fn on_side(uses: &[FaceUse], front: bool) -> Option<FaceUse> {
    uses.iter().find(|f| f.front == front).copied()
}

fn sorted(mut f: [u32; 3]) -> [u32; 3] {
    f.sort_unstable();
    f
}

/// Whether node `apex` lies on the side of triangle `tri` its right-hand normal points to.
fn in_front(mesh: &VolumeMesh, tri: [u32; 3], apex: u32) -> bool {
    let p = |v: u32| &mesh.nodes[v as usize];
    orient3d(p(tri[0]), p(tri[1]), p(tri[2]), p(apex)) == Orientation::Positive
}

fn orphan(mesh: &VolumeMesh, i: usize) -> String {
    let group = mesh
        .triangle_group
        .get(i)
        .and_then(|&g| mesh.surface_groups.get(g as usize))
        .map_or("?", |g| g.name.as_str());
    let corners = mesh.triangles[i].map(|v| mesh.nodes[v as usize]);
    format!(
        "surface '{group}' triangle {i} {corners:?} is not a face of any tet: no side set can name it"
    )
}

/// The ids of one fault's two side groups.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct FaultSides {
    /// The fault's surface group index.
    pub(crate) group: usize,
    /// The id of `<fault>:front`.
    pub(crate) front: usize,
    /// The id of `<fault>:back`.
    pub(crate) back: usize,
}

impl FaultSides {
    /// The side's id.
    pub(crate) fn id(&self, front: bool) -> usize {
        if front { self.front } else { self.back }
    }
}

/// Every fault group's side ids, in group order.
pub(crate) fn fault_sides(mesh: &VolumeMesh) -> Vec<FaultSides> {
    fault_sides_of(&mesh.surface_groups)
}

/// Every fault's side ids among `groups`, in group order.
pub(crate) fn fault_sides_of(groups: &[SurfaceGroup]) -> Vec<FaultSides> {
    let n = groups.len();
    (0..n)
        .filter(|&g| groups[g].kind == SurfaceKind::Fault)
        .enumerate()
        .map(|(k, group)| FaultSides {
            group,
            front: n + 2 * k + 1,
            back: n + 2 * k + 2,
        })
        .collect()
}

/// `<fault>:front` or `<fault>:back`, the model's names for a surface's sides.
pub(crate) fn side_name(fault: &str, front: bool) -> String {
    format!("{fault}:{}", if front { "front" } else { "back" })
}
