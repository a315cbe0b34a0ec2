//! Which triangles of a mesh meet: across each edge, and at each vertex. Pure index work, in
//! index order, so every walk over them is the same on every machine.

use crate::TriMesh;

/// The triangles at each vertex of `mesh`, ascending (corners that are not its vertices left
/// out).
pub fn stars(mesh: &TriMesh) -> Vec<Vec<u32>> {
    let mut star = vec![Vec::new(); mesh.vertices.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for &v in tri {
            if let Some(s) = star.get_mut(v as usize) {
                s.push(t as u32);
            }
        }
    }
    star
}

/// No triangle across an edge (see [`across_edges`]).
pub const NONE: u32 = u32::MAX;

/// Per triangle, per edge `k` (from corner `k` to corner `k + 1`), the triangle across it when
/// exactly two triangles share the edge, else [`NONE`].
pub fn across_edges(mesh: &TriMesh) -> Vec<[u32; 3]> {
    let mut uses: Vec<([u32; 2], u32, u8)> = Vec::with_capacity(3 * mesh.triangles.len());
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            uses.push(([a.min(b), a.max(b)], t as u32, k as u8));
        }
    }
    uses.sort_unstable();
    let mut out = vec![[NONE; 3]; mesh.triangles.len()];
    for run in uses.chunk_by(|x, y| x.0 == y.0) {
        if let [x, y] = run
            && x.1 != y.1
        {
            out[x.1 as usize][x.2 as usize] = y.1;
            out[y.1 as usize][y.2 as usize] = x.1;
        }
    }
    out
}
