//! The model's curves and their end points as msh entities, recovered from the surface pieces so
//! that each surface lists the curves bounding it (`gmsh.model.getBoundary` of a surface returns
//! them, and of a curve its end points).
//!
//! An edge of the surface triangles is a curve edge where the pieces meet or a piece ends: it is
//! used by triangles of two or more pieces, or by other than two triangles (a free border, a
//! non-manifold fan). Curve edges used by the same set of pieces form curves, cut at *corners*:
//! nodes where other than two curve edges meet, or two edges of different piece sets. A chain
//! with no corner is a closed curve; its smallest node becomes its corner, and the curve both
//! starts and ends there, as Gmsh writes a closed curve. A piece is bounded by the curves it
//! lies on one side of; a curve it lies on both sides of (where a dangling fault meets a
//! horizon inside the piece) is embedded in it, which msh 4.1 has no record for, so the piece
//! does not list it. Everything is ordered by node indices,
//! never by hash order, so the entities are a function of the mesh.

use geom::mesh::VolumeMesh;
use std::collections::BTreeMap;

/// The curves and corners of a mesh's surface pieces.
pub(super) struct Curves {
    /// Per curve, its nodes in order; a closed curve repeats its first node at the end.
    pub(super) chains: Vec<Vec<u32>>,
    /// Per curve, the indices into `corners` of its first and last node.
    pub(super) ends: Vec<[usize; 2]>,
    /// Per corner, its node, ascending for the corners that end open curves, then those of the
    /// closed curves in curve order.
    pub(super) corners: Vec<u32>,
    /// Per piece, its bounding curves as (curve index, whether the curve runs the way the
    /// piece's triangles turn), ascending.
    pub(super) bounds: Vec<Vec<(usize, bool)>>,
    /// Per curve, the surface groups of the pieces meeting or ending there, ascending.
    pub(super) groups: Vec<Vec<usize>>,
}

impl Curves {
    /// The curves' 1D physical groups: per name, its curves, in name order. A curve is named
    /// after the surface groups meeting there, `A/B` (names sorted), or `A:border` where the
    /// pieces of one group end (a dangling fault's free edge).
    pub(super) fn named(&self, mesh: &VolumeMesh) -> BTreeMap<String, Vec<usize>> {
        let mut out: BTreeMap<String, Vec<usize>> = BTreeMap::new();
        for (c, groups) in self.groups.iter().enumerate() {
            let mut names: Vec<&str> = (groups.iter())
                .map(|&g| mesh.surface_groups[g].name.as_str())
                .collect();
            names.sort_unstable();
            let name = match names.as_slice() {
                [one] => format!("{one}:border"),
                many => many.join("/"),
            };
            out.entry(name).or_default().push(c);
        }
        out
    }
}

/// One use of an edge: the piece of the triangle that has it, and whether that triangle runs
/// along it from its lower node to its higher.
type EdgeUse = (usize, bool);

/// The curves of the pieces `tris_by_piece` (triangle indices of `mesh`, per piece).
pub(super) fn curves(mesh: &VolumeMesh, tris_by_piece: &[Vec<usize>]) -> Curves {
    let uses = edge_uses(mesh, tris_by_piece);
    // The curve edges, ascending, each with the index of its set of pieces.
    let mut sets: BTreeMap<Vec<usize>, usize> = BTreeMap::new();
    let mut edges: Vec<([u32; 2], usize)> = Vec::new();
    for (&e, u) in &uses {
        let mut pieces: Vec<usize> = u.iter().map(|&(p, _)| p).collect();
        pieces.dedup();
        if pieces.len() >= 2 || u.len() != 2 {
            let next = sets.len();
            edges.push((e, *sets.entry(pieces).or_insert(next)));
        }
    }
    let mut set_pieces = vec![Vec::new(); sets.len()];
    for (pieces, k) in sets {
        set_pieces[k] = pieces;
    }
    let chains = Chains::new(&edges).walk();
    let mut bounds = vec![Vec::new(); tris_by_piece.len()];
    let mut groups = Vec::with_capacity(chains.chains.len());
    for (c, (nodes, _)) in chains.chains.iter().enumerate() {
        let set = edges[chains.first_edge[c]].1;
        let (a, b) = (nodes[0], nodes[1]);
        let key = [a.min(b), a.max(b)];
        for &p in &set_pieces[set] {
            // A curve the piece lies on both sides of (a dangling fault's trace across a
            // horizon) is embedded in it, not part of its boundary.
            let mut of_p = uses[&key].iter().filter(|u| u.0 == p);
            if let (Some(u), None) = (of_p.next(), of_p.next()) {
                bounds[p].push((c, u.1 == (a < b)));
            }
        }
        let mut g: Vec<usize> = (set_pieces[set].iter())
            .map(|&p| mesh.triangle_group[tris_by_piece[p][0]] as usize)
            .collect();
        g.sort_unstable();
        g.dedup();
        groups.push(g);
    }
    Curves {
        groups,
        ends: chains.chains.iter().map(|(_, ends)| *ends).collect(),
        chains: chains.chains.into_iter().map(|(nodes, _)| nodes).collect(),
        corners: chains.corners,
        bounds,
    }
}

/// Every edge of the pieces' triangles (lower node first) with its uses, in piece order.
fn edge_uses(mesh: &VolumeMesh, tris_by_piece: &[Vec<usize>]) -> BTreeMap<[u32; 2], Vec<EdgeUse>> {
    let mut uses: BTreeMap<[u32; 2], Vec<EdgeUse>> = BTreeMap::new();
    for (p, tris) in tris_by_piece.iter().enumerate() {
        for &t in tris {
            let [a, b, c] = mesh.triangles[t];
            for (u, v) in [(a, b), (b, c), (c, a)] {
                uses.entry([u.min(v), u.max(v)])
                    .or_default()
                    .push((p, u < v));
            }
        }
    }
    uses
}

/// The walk of the curve edges into chains.
struct Chains<'a> {
    edges: &'a [([u32; 2], usize)],
    /// Per node with curve edges, the indices of its edges, ascending.
    at: BTreeMap<u32, Vec<usize>>,
    used: Vec<bool>,
    /// Node → corner index.
    corner_of: BTreeMap<u32, usize>,
    corners: Vec<u32>,
    /// Per chain, its nodes and the corner indices at its ends.
    chains: Vec<(Vec<u32>, [usize; 2])>,
    /// Per chain, the index of its first edge.
    first_edge: Vec<usize>,
}

impl<'a> Chains<'a> {
    fn new(edges: &'a [([u32; 2], usize)]) -> Chains<'a> {
        let mut at: BTreeMap<u32, Vec<usize>> = BTreeMap::new();
        for (i, (e, _)) in edges.iter().enumerate() {
            at.entry(e[0]).or_default().push(i);
            at.entry(e[1]).or_default().push(i);
        }
        let mut corners = Vec::new();
        let mut corner_of = BTreeMap::new();
        for (&v, es) in &at {
            if es.len() != 2 || edges[es[0]].1 != edges[es[1]].1 {
                corner_of.insert(v, corners.len());
                corners.push(v);
            }
        }
        Chains {
            edges,
            at,
            used: vec![false; edges.len()],
            corner_of,
            corners,
            chains: Vec::new(),
            first_edge: Vec::new(),
        }
    }

    /// Open chains from every corner (ascending, its edges in order), then the closed ones.
    fn walk(mut self) -> Chains<'a> {
        for k in 0..self.corners.len() {
            let v = self.corners[k];
            for i in self.at[&v].clone() {
                if !self.used[i] {
                    self.follow(v, i);
                }
            }
        }
        for i in 0..self.edges.len() {
            if !self.used[i] {
                let v = self.edges[i].0[0];
                self.corner_of.insert(v, self.corners.len());
                self.corners.push(v);
                self.follow(v, i);
            }
        }
        self
    }

    /// The chain leaving `start` by edge `first`, up to the next corner.
    fn follow(&mut self, start: u32, first: usize) {
        let mut nodes = vec![start];
        let (mut v, mut e) = (start, first);
        loop {
            self.used[e] = true;
            let [a, b] = self.edges[e].0;
            v = if a == v { b } else { a };
            nodes.push(v);
            if self.corner_of.contains_key(&v) {
                break;
            }
            match self.at[&v].iter().find(|&&i| !self.used[i]) {
                Some(&next) => e = next,
                None => break,
            }
        }
        let ends = [self.corner_of[&start], self.corner_of[&v]];
        self.chains.push((nodes, ends));
        self.first_edge.push(first);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom::mesh::{SurfaceGroup, SurfaceKind, VolumeMesh};

    /// Two squares side by side in z = 0, each two triangles turning counterclockwise: nodes
    /// 0 1 2 / 3 4 5 in two rows.
    fn two_squares() -> VolumeMesh {
        VolumeMesh {
            nodes: (0..6)
                .map(|i| [(i % 3) as f64, (i / 3) as f64, 0.0])
                .collect(),
            triangles: vec![[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]],
            triangle_group: vec![0, 0, 1, 1],
            surface_groups: ["L", "R"]
                .map(|name| SurfaceGroup {
                    name: name.into(),
                    kind: SurfaceKind::Box,
                })
                .to_vec(),
            ..Default::default()
        }
    }

    #[test]
    fn two_pieces_meet_along_one_curve_and_each_ends_along_its_own() {
        let c = curves(&two_squares(), &[vec![0, 1], vec![2, 3]]);
        // Corners where the shared edge 1-4 meets the free borders.
        assert_eq!(c.corners, vec![1, 4]);
        assert_eq!(
            c.chains,
            vec![vec![1, 0, 3, 4], vec![1, 2, 5, 4], vec![1, 4]]
        );
        // The left square's triangle 0 1 4 runs 0→1 (against the first curve, 1→0) and 1→4
        // (along the shared one); the right square's 1 2 5 runs 1→2 and its 1 5 4 runs 4→1.
        assert_eq!(c.bounds[0], vec![(0, false), (2, true)]);
        assert_eq!(c.bounds[1], vec![(1, true), (2, false)]);
        assert_eq!(c.ends, vec![[0, 1], [0, 1], [0, 1]]);
        let named: Vec<(String, Vec<usize>)> = c.named(&two_squares()).into_iter().collect();
        let name = |n: &str, cs: Vec<usize>| (n.to_string(), cs);
        assert_eq!(
            named,
            [
                name("L/R", vec![2]),
                name("L:border", vec![0]),
                name("R:border", vec![1])
            ]
        );
    }

    #[test]
    fn a_piece_with_no_neighbour_is_bounded_by_one_closed_curve_at_its_smallest_node() {
        let mut mesh = two_squares();
        mesh.triangle_group = vec![0; 4];
        let c = curves(&mesh, &[vec![0, 1, 2, 3]]);
        assert_eq!(c.corners, vec![0]);
        assert_eq!(c.chains, vec![vec![0, 1, 2, 5, 4, 3, 0]]);
        assert_eq!(c.ends, vec![[0, 0]]);
        assert_eq!(c.bounds, vec![vec![(0, true)]]);
    }

    #[test]
    fn a_curve_a_piece_lies_on_both_sides_of_is_embedded_in_it_not_its_boundary() {
        // Both squares one piece, and a fin (group R) standing on their shared edge 1-4.
        let mut mesh = two_squares();
        mesh.nodes.push([1.0, 0.5, 1.0]);
        mesh.triangles.push([1, 4, 6]);
        mesh.triangle_group = vec![0, 0, 0, 0, 1];
        let c = curves(&mesh, &[vec![0, 1, 2, 3], vec![4]]);
        let shared = c.chains.iter().position(|ch| ch == &vec![1, 4]).unwrap();
        assert!(
            c.bounds[0].iter().all(|&(k, _)| k != shared),
            "{:?}",
            c.bounds[0]
        );
        assert!(c.bounds[1].contains(&(shared, true)), "{:?}", c.bounds[1]);
    }

    #[test]
    fn a_closed_surface_has_no_curve() {
        let mesh = VolumeMesh {
            nodes: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
            triangle_group: vec![0; 4],
            ..Default::default()
        };
        let c = curves(&mesh, &[vec![0, 1, 2, 3]]);
        assert!(c.chains.is_empty() && c.corners.is_empty());
    }
}
