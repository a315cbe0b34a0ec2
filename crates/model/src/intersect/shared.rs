//! Triangles two surfaces hold in common: the same three points, bit for bit, in either order
//! of the corners. Stratigraphic models collapse a pinched-out layer this way, drawing its base
//! onto its top vertex for vertex where it has no thickness. Such a pair is not an overlap to
//! refuse but one piece of interface: the surface whose name sorts first keeps it, the other
//! drops it, and the border of what it drops becomes the curve where the two surfaces part.
//! Identity is a comparison of coordinates, exact; nothing is near enough by a distance.

use geom::TriMesh;
use geom::predicates::{cross, dot, sub};
use rayon::prelude::*;

use super::key::PointKey;
use super::{IntersectError, Intersection, SurfaceRef, intersect};

/// The corners of triangle `t` of `m` by their bits (`-0.0` as `0.0`: the same place), sorted
/// (`None` on a bad index).
fn corners(m: &TriMesh, t: u32) -> Option<[[u64; 3]; 3]> {
    let tri = m.triangles.get(t as usize)?;
    let mut c = [[0u64; 3]; 3];
    for k in 0..3 {
        c[k] = m
            .vertices
            .get(tri[k] as usize)?
            .map(|x| (x + 0.0).to_bits());
    }
    c.sort_unstable();
    Some(c)
}

/// Whether triangles `i` of `a` and `j` of `b` have the same three points.
pub fn identical(a: &TriMesh, i: u32, b: &TriMesh, j: u32) -> bool {
    corners(a, i).is_some_and(|c| Some(c) == corners(b, j))
}

/// Two surfaces that hold triangles in common and also cross elsewhere at less than this many
/// degrees draw one part twice with different triangles (the CFM's 1857 rupture over the Mojave
/// segment): their curves would be hundreds of slivers, so that is an error instead.
pub const REDRAWN_DEG: f64 = 1.0;

/// Where two surfaces with triangles in common cross under [`REDRAWN_DEG`]: the first segment
/// (its ends' keys and its pair of triangles) that crosses a triangle rather than running along
/// an edge both hold, with the angle between the triangles' planes. Where a layer collapses onto
/// its top, its base leaves the top along their common edges, and no segment counts.
pub fn redrawn(
    segments: &[(PointKey, PointKey, (u32, u32))],
    a: &TriMesh,
    b: &TriMesh,
) -> Option<(f64, PointKey)> {
    let normal = |m: &TriMesh, t: u32| {
        let p = m.triangles[t as usize].map(|v| m.vertices[v as usize]);
        let n = cross(&sub(&p[1], &p[0]), &sub(&p[2], &p[0]));
        let len = dot(&n, &n).sqrt();
        n.map(|x| x / len)
    };
    let along_edges = |k: &PointKey| matches!(k, PointKey::VertexVertex { .. });
    segments
        .iter()
        .filter(|(k0, k1, _)| !(along_edges(k0) && along_edges(k1)))
        .find_map(|&(k0, _, (i, j))| {
            let c = dot(&normal(a, i), &normal(b, j)).abs().min(1.0);
            let angle = c.acos().to_degrees();
            (angle < REDRAWN_DEG).then_some((angle, k0))
        })
}

/// The triangles of each surface that a surface whose name sorts before it also holds (as the
/// pairs of `intersections` say), by surface in the order of `names`, each list sorted.
pub fn dropped_by_name(names: &[&str], intersections: &[Intersection]) -> Vec<Vec<u32>> {
    names
        .iter()
        .map(|name| {
            let mut d: Vec<u32> = (intersections.iter())
                .filter(|x| x.b == *name)
                .flat_map(|x| x.shared.iter().map(|&(_, j)| j))
                .collect();
            d.sort_unstable();
            d.dedup();
            d
        })
        .collect()
}

/// `mesh` without the triangles `drop` (sorted), and for each triangle kept, its index in
/// `mesh`. The vertices stay as they are, so vertex numbers keep their meaning.
pub fn without(mesh: &TriMesh, drop: &[u32]) -> (TriMesh, Vec<u32>) {
    let kept: Vec<u32> = (0..mesh.triangles.len() as u32)
        .filter(|t| drop.binary_search(t).is_err())
        .collect();
    let triangles = kept.iter().map(|&t| mesh.triangles[t as usize]).collect();
    (TriMesh::new(mesh.vertices.clone(), triangles), kept)
}

/// A model's surfaces without the triangles each shares with a surface whose name sorts first.
pub struct Unshared {
    /// By surface, in the order given: the surface without them and, for each triangle it
    /// keeps, its index before; `None` for a surface that shares nothing.
    pub meshes: Vec<Option<(TriMesh, Vec<u32>)>>,
    /// The intersections, those of a surface that dropped triangles made again without them.
    pub intersections: Vec<Intersection>,
}

/// Drops from each surface the triangles the `intersections` found it shares with a surface
/// whose name sorts first, and intersects again every pair with a surface that dropped some.
/// `None` when no surface shares a triangle, so a model without any is built as before.
pub fn unshare(
    surfaces: &[(&str, &TriMesh)],
    intersections: &[Intersection],
) -> Result<Option<Unshared>, IntersectError> {
    let names: Vec<&str> = surfaces.iter().map(|s| s.0).collect();
    let dropped = dropped_by_name(&names, intersections);
    if dropped.iter().all(|d| d.is_empty()) {
        return Ok(None);
    }
    let meshes: Vec<Option<(TriMesh, Vec<u32>)>> = (surfaces.iter().zip(&dropped))
        .map(|((_, m), d)| (!d.is_empty()).then(|| without(m, d)))
        .collect();
    let mesh_of = |name: &str| -> Option<(&TriMesh, bool)> {
        let k = names.iter().position(|n| *n == name)?;
        Some(match &meshes[k] {
            Some((m, _)) => (m, true),
            None => (surfaces[k].1, false),
        })
    };
    let again: Vec<Result<Intersection, IntersectError>> = intersections
        .par_iter()
        .map(|x| match (mesh_of(&x.a), mesh_of(&x.b)) {
            (Some((a, ra)), Some((b, rb))) if ra || rb => intersect(
                SurfaceRef {
                    name: &x.a,
                    mesh: a,
                },
                SurfaceRef {
                    name: &x.b,
                    mesh: b,
                },
            ),
            _ => Ok(x.clone()),
        })
        .collect();
    Ok(Some(Unshared {
        meshes,
        intersections: again.into_iter().collect::<Result<_, _>>()?,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> TriMesh {
        TriMesh::new(vertices, triangles)
    }

    #[test]
    fn a_triangle_with_the_same_points_in_another_order_is_identical() {
        let p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let a = mesh(p.clone(), vec![[0, 1, 2]]);
        let b = mesh(vec![p[2], p[0], p[1]], vec![[1, 0, 2]]);
        assert!(identical(&a, 0, &b, 0));
        assert!(identical(&b, 0, &a, 0));
    }

    #[test]
    fn a_triangle_one_ulp_away_is_not_identical() {
        let p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let a = mesh(p.clone(), vec![[0, 1, 2]]);
        let mut q = p;
        q[1][0] = f64::from_bits(1f64.to_bits() + 1);
        assert!(!identical(&a, 0, &mesh(q, vec![[0, 1, 2]]), 0));
        assert!(!identical(&a, 0, &a, 7), "a bad index is nothing");
        let z = mesh(
            vec![[-0.0, 0.0, -0.0], [1.0, 0.0, 0.0], [0.0, 1.0, -0.0]],
            vec![[0, 1, 2]],
        );
        assert!(identical(&a, 0, &z, 0), "-0.0 is where 0.0 is");
    }

    #[test]
    fn dropping_triangles_keeps_the_vertices_and_says_where_each_kept_one_was() {
        let p = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
        let m = mesh(p.clone(), vec![[0, 1, 2], [1, 3, 2], [0, 2, 3]]);
        let (w, kept) = without(&m, &[1]);
        assert_eq!(w.vertices, p);
        assert_eq!(w.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(kept, vec![0, 2]);
    }
}
