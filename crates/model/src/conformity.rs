//! Whether surfaces that meet share their vertices: a sealed model's surfaces (a gOcad Model3d)
//! meet along contacts whose vertices both hold bit for bit. A border vertex of one surface
//! lying a hair from a vertex of another, but not at its coordinates, is a non-conformal
//! contact (a file written with too few digits, a surface moved by a rounding): the model is
//! still built, the intersections making it conformal, but the user is told where, since the
//! data and the model then differ there. Distances here are measures for a report; nothing in
//! the model depends on them.

use geom::TriMesh;
use geom::predicates::dist;
use rstar::RTree;
use rstar::primitives::GeomWithData;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A place where a vertex of surface `a` lies `distance` from a vertex of surface `b` (`a < b`
/// by name; one of the two on its surface's border) without being at its coordinates.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NearMiss {
    pub a: String,
    pub b: String,
    /// The first of the two vertices in coordinate order.
    pub at: [f64; 3],
    pub distance: f64,
}

/// Every border vertex (on an edge of one triangle) of each surface that lies within `within`
/// of a vertex of another surface at other coordinates; by surface pair, then place.
pub fn near_misses(surfaces: &[(&str, &TriMesh)], within: f64) -> Vec<NearMiss> {
    if within.is_nan() || within <= 0.0 {
        return Vec::new();
    }
    let points: Vec<GeomWithData<[f64; 3], u32>> = (surfaces.iter().enumerate())
        .flat_map(|(i, (_, m))| {
            m.vertices
                .iter()
                .map(move |p| GeomWithData::new(*p, i as u32))
        })
        .filter(|p| p.geom().iter().all(|x| x.is_finite()))
        .collect();
    let tree = RTree::bulk_load(points);
    let mut found: BTreeMap<(usize, usize, [u64; 3], [u64; 3]), NearMiss> = BTreeMap::new();
    for (i, (name, mesh)) in surfaces.iter().enumerate() {
        for v in border_vertices(mesh) {
            let p = mesh.vertices[v];
            for q in tree.locate_within_distance(p, within * within) {
                let (j, q) = (q.data as usize, *q.geom());
                if j == i || q == p {
                    continue;
                }
                // Each pair of vertices once, whichever of the two is on a border.
                let (lo, hi) = if p.map(f64::to_bits) < q.map(f64::to_bits) {
                    (p, q)
                } else {
                    (q, p)
                };
                let key = (
                    i.min(j),
                    i.max(j),
                    lo.map(f64::to_bits),
                    hi.map(f64::to_bits),
                );
                let (a, b) = (name.to_string(), surfaces[j].0.to_string());
                found.entry(key).or_insert_with(|| NearMiss {
                    a: a.clone().min(b.clone()),
                    b: a.max(b),
                    at: lo,
                    distance: dist(&p, &q),
                });
            }
        }
    }
    let mut out: Vec<NearMiss> = found.into_values().collect();
    out.sort_by(|x, y| {
        (x.a.cmp(&y.a))
            .then(x.b.cmp(&y.b))
            .then(x.at.map(f64::to_bits).cmp(&y.at.map(f64::to_bits)))
    });
    out
}

/// The vertices on an edge that one triangle uses, ascending.
fn border_vertices(mesh: &TriMesh) -> Vec<usize> {
    let mut out: Vec<usize> = (mesh.border_edges().into_iter())
        .flat_map(|(a, b)| [a as usize, b as usize])
        .filter(|&v| v < mesh.vertices.len())
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square at height `z`, x from `x0`, two triangles.
    fn square(x0: f64, z: f64) -> TriMesh {
        let v = vec![
            [x0, 0.0, z],
            [x0 + 1.0, 0.0, z],
            [x0 + 1.0, 1.0, z],
            [x0, 1.0, z],
        ];
        TriMesh::new(v, vec![[0, 1, 2], [0, 2, 3]])
    }

    #[test]
    fn squares_sharing_an_edge_exactly_are_conformal_and_one_an_ulp_off_is_named_both_ways() {
        let (a, b) = (square(0.0, 0.0), square(1.0, 0.0));
        assert!(near_misses(&[("a", &a), ("b", &b)], 1e-6).is_empty());
        let mut off = b.clone();
        off.vertices[0][0] = f64::from_bits(1.0f64.to_bits() + 1);
        let got = near_misses(&[("b", &off), ("a", &a)], 1e-6);
        assert_eq!(got.len(), 1, "one pair of vertices: {got:?}");
        assert!(
            got.iter()
                .all(|m| (m.a.as_str(), m.b.as_str()) == ("a", "b"))
        );
        assert!(got.iter().all(|m| m.distance > 0.0 && m.distance < 1e-15));
        let same = near_misses(&[("a", &a), ("b", &off)], 1e-6);
        assert_eq!(got, same, "the order of the surfaces does not matter");
        assert!(near_misses(&[("a", &a), ("b", &off)], 0.0).is_empty());
        let far = square(1.5, 0.0);
        assert!(near_misses(&[("a", &a), ("b", &far)], 1e-6).is_empty());
    }
}
