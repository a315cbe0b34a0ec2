//! What an advancing front that cannot close leaves open, filled by the Delaunay method.
//!
//! The front fails where its sides meet: the last gaps between faces built from opposite walls
//! are too thin or too crooked for any apex its rules allow, and back-tracking there re-creates
//! them. Those gaps are small cavities bounded by the front's own faces, well shaped on the
//! whole, which is what the Delaunay method with boundary recovery fills best (its own weakness
//! is the opposite: the thin holes between a curved closed surface and the flat tets that hug
//! it). So the front, before it gives up, hands each connected piece of its open faces to that
//! method (no front inside it: the recursion ends there); the region's exact verification then
//! judges the whole mesh as for any other.

use super::delaunay::{Filled, connected_pieces, fill_without_front};
use super::{RegionInput, SizeField};

type P = [f64; 3];

/// The tets (and new nodes, numbered from `nodes.len()` on) filling the space the front's `open`
/// faces bound (each facing the space still to fill, as the front holds them), piece by piece;
/// else the faces of the pieces that could not be filled.
pub fn fill_open(
    name: &str,
    nodes: &[P],
    open: &[[u32; 3]],
    size: &SizeField,
) -> Result<Filled, Vec<[u32; 3]>> {
    let mut new_nodes = Vec::new();
    let mut tets = Vec::new();
    let mut failed = Vec::new();
    for piece in connected_pieces(open) {
        // Ids of the piece's vertices, in first-use order, and the piece in them, turned to face
        // out of the space (a region's boundary faces out of it).
        let mut ids: Vec<u32> = Vec::new();
        let mut local = std::collections::HashMap::new();
        let mut boundary = Vec::with_capacity(piece.len());
        for f in &piece {
            let [a, b, c] = f.map(|v| {
                *local.entry(v).or_insert_with(|| {
                    ids.push(v);
                    (ids.len() - 1) as u32
                })
            });
            boundary.push([a, c, b]);
        }
        let input = RegionInput {
            name: name.to_string(),
            vertices: ids.iter().map(|&v| nodes[v as usize]).collect(),
            boundary,
            ..RegionInput::default()
        };
        let Some((added, filled)) = fill_without_front(&input, size) else {
            failed.extend(piece);
            continue;
        };
        let first = (nodes.len() + new_nodes.len()) as u32;
        let n = ids.len() as u32;
        let global = |v: u32| {
            if v < n {
                ids[v as usize]
            } else {
                first + v - n
            }
        };
        tets.extend(filled.iter().map(|t| t.map(global)));
        new_nodes.extend(added);
    }
    match failed.is_empty() {
        true => Ok((new_nodes, tets)),
        false => Err(failed),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The faces of the cube [0, 10]³ gridded 3 × 3 per side shifted by `dx` in x, numbered
    /// from `first`, facing into the cube (as a front holds the space it has still to fill).
    fn cube(dx: f64, first: u32) -> (Vec<P>, Vec<[u32; 3]>) {
        let (mut pts, out) = test_support::shapes::gridded_cube(3, 10.0);
        pts.iter_mut().for_each(|p| p[0] += dx);
        let faces = out.iter().map(|t| [t[0], t[2], t[1]].map(|v| v + first));
        (pts, faces.collect())
    }

    fn volume(nodes: &[P], tets: &[[u32; 4]]) -> f64 {
        let sum: f64 = tets
            .iter()
            .map(|t| {
                let [a, b, c, d] = t.map(|v| nodes[v as usize]);
                geom::predicates::signed_volume(&a, &b, &c, &d)
            })
            .sum();
        sum
    }

    #[test]
    fn two_open_cavities_are_filled_each_by_positive_tets_in_the_front_s_numbering() {
        let (mut nodes, mut open) = cube(0.0, 0);
        let (far, faces) = cube(50.0, nodes.len() as u32);
        nodes.extend(far);
        open.extend(faces);
        assert_eq!(connected_pieces(&open).len(), 2);
        let (added, tets) = fill_open("two", &nodes, &open, &SizeField::default()).expect("fills");
        let all: Vec<P> = nodes.iter().chain(&added).copied().collect();
        assert!(
            (volume(&all, &tets) - 2000.0).abs() < 1e-9,
            "{}",
            volume(&all, &tets)
        );
        for t in &tets {
            let [a, b, c, d] = t.map(|v| all[v as usize]);
            assert!(
                geom::predicates::signed_volume(&a, &b, &c, &d) > 0.0,
                "{t:?}"
            );
            // Each tet in one cube: its given corners are all of that cube's faces.
            let mut cubes: Vec<usize> = (t.iter())
                .filter(|&&v| (v as usize) < nodes.len())
                .map(|&v| 2 * v as usize / nodes.len())
                .collect();
            cubes.dedup();
            assert_eq!(cubes.len(), 1, "{t:?}");
        }
    }
}
