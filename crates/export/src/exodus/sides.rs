//! Which tet faces a surface triangle is: Exodus names a face by (element, side) with the
//! TETRA4 side numbering of the Exodus II manual: side 1 = nodes 1 2 4, side 2 = 2 3 4,
//! side 3 = 1 4 3, side 4 = 1 3 2 (each ordered so its right-hand normal points out of a
//! positive tet). Each use also records whether the tet lies on the triangle's front, the side
//! its right-hand normal `(b-a)×(c-a)` points to (exact `orient3d`); the mesh keeps every patch
//! triangle oriented like its surface, so that is the surface's front as the model names it.

use geom::mesh::VolumeMesh;
use geom::predicates::{Orientation, orient3d};
use std::collections::HashMap;

/// The TETRA4 sides as 0-based local node indices, side 1 first.
pub(crate) const TETRA4_SIDES: [[usize; 3]; 4] = [[0, 1, 3], [1, 2, 3], [0, 3, 2], [0, 2, 1]];

/// One tet that has a given triangle as a face.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct FaceUse {
    /// The tet's 1-based element number.
    pub(crate) elem: u32,
    /// The face's 1-based TETRA4 side number in that tet.
    pub(crate) side: u32,
    /// Whether the tet lies on the triangle's front.
    pub(crate) front: bool,
}

/// For every triangle of `mesh`, the tets that have it as a face (two for an interior face, one
/// on the boundary), lowest element number first. Fails, naming the triangle's group and
/// corners, when no tet has it: Exodus and Abaqus name only element faces.
pub(crate) fn face_uses(mesh: &VolumeMesh, number: &[u32]) -> Result<Vec<Vec<FaceUse>>, String> {
    let mut by_key: HashMap<[u32; 3], Vec<usize>> = HashMap::new();
    for (i, t) in mesh.triangles.iter().enumerate() {
        by_key.entry(sorted(*t)).or_default().push(i);
    }
    let mut uses = vec![Vec::new(); mesh.triangles.len()];
    for (t, tet) in mesh.tets.iter().enumerate() {
        for (s, local) in TETRA4_SIDES.iter().enumerate() {
            let Some(tris) = by_key.get(&sorted(local.map(|k| tet[k]))) else {
                continue;
            };
            let apex = tet[6 - local.iter().sum::<usize>()];
            for &i in tris {
                uses[i].push(FaceUse {
                    elem: number[t],
                    side: s as u32 + 1,
                    front: in_front(mesh, mesh.triangles[i], apex),
                });
            }
        }
    }
    for (i, u) in uses.iter_mut().enumerate() {
        if u.is_empty() {
            return Err(orphan(mesh, i));
        }
        u.sort_by_key(|f| f.elem);
    }
    Ok(uses)
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
