//! The recovery holes: which tets may meet a missing constraint triangle, which side of the
//! boundary each kept tet lies on (flooded from the constraint triangles' oriented sides, never
//! across a constrained face), and the holes' inner part, grown until its surface is a manifold
//! and filled piece by piece: without new nodes, from one node in the piece's kernel, or by the
//! advancing front. A piece that only the front could fill is first widened by the inner tets
//! round it, since the front's sized nodes rarely fit in a thin recovery hole.

use std::collections::HashMap;

use super::super::super::advance::advance_front;
use super::super::super::check::check_input;
use super::super::super::work::FrontWork;
use super::super::super::{RegionInput, SizeField, TetMeshError};
use super::super::tri::{NONE, P, Tri};
use super::{Holders, MAX_GROWTH, Side, kernel, meets, peel, same_turn, sorted, star};

/// The holes' inner surface: its boundary triangles, and the embedded triangles inside it.
type HoleSurface = (Vec<[u32; 3]>, Vec<[u32; 3]>);

/// Each tet's starting side: a hole where it may meet a missing triangle, else unknown.
pub(super) fn hole_tets(
    tri: &Tri,
    all: &[([u32; 3], bool)],
    missing: &[usize],
    vtet: &[u32],
) -> Vec<Side> {
    let mut side = vec![Side::Unknown; tri.t.len()];
    if !missing.is_empty() {
        // Per missing triangle, every tet meeting it, reached through tets meeting it (whether
        // or not an earlier triangle already took them).
        let mut seen = vec![u32::MAX; tri.t.len()];
        let mut stack = Vec::new();
        for (round, &k) in missing.iter().enumerate() {
            let round = round as u32;
            let f = all[k].0;
            let mut visit = |t: u32, stack: &mut Vec<u32>, side: &mut [Side]| {
                if seen[t as usize] != round {
                    seen[t as usize] = round;
                    if meets(tri, t, f) {
                        side[t as usize] = Side::Hole;
                        stack.push(t);
                    }
                }
            };
            for &v in &f {
                for t in star(tri, v, vtet[v as usize]) {
                    visit(t, &mut stack, &mut side);
                }
            }
            while let Some(t) = stack.pop() {
                for i in 0..4 {
                    let a = tri.t[t as usize].adj[i];
                    if a != NONE {
                        visit(a >> 2, &mut stack, &mut side);
                    }
                }
            }
        }
    }
    side
}

/// Constrains the faces holding constraint triangles and seeds the flood's sides from them.
pub(super) fn seed_sides(
    tri: &mut Tri,
    side: &mut [Side],
    all: &[([u32; 3], bool)],
    holders: &[Holders],
    n: usize,
    name: &str,
) -> Result<(), TetMeshError> {
    for (k, hs) in holders.iter().enumerate() {
        for (t, i) in hs.iter() {
            tri.constrain(t, i);
            let (f, embedded) = all[k];
            let s = if embedded || same_turn(tri.face(t, i), f) {
                Side::In
            } else {
                Side::Out
            };
            seed(side, t, s, tri, name)?;
        }
    }
    let n32 = n as u32;
    for t in tri.live_tets() {
        if tri.t[t as usize].v.iter().any(|&v| v >= n32) {
            seed(side, t, Side::Out, tri, name)?;
        }
    }
    Ok(())
}

/// Floods the sides across unconstrained faces; tets no flood reaches join the holes.
pub(super) fn flood(tri: &Tri, side: &mut [Side], name: &str) -> Result<(), TetMeshError> {
    let mut stack: Vec<u32> = tri
        .live_tets()
        .filter(|&t| matches!(side[t as usize], Side::In | Side::Out))
        .collect();
    while let Some(t) = stack.pop() {
        let s = side[t as usize];
        for i in 0..4 {
            if tri.t[t as usize].cons & (1 << i) != 0 {
                continue;
            }
            let a = tri.t[t as usize].adj[i];
            if a == NONE {
                continue;
            }
            let u = (a >> 2) as usize;
            match side[u] {
                Side::Unknown => {
                    side[u] = s;
                    stack.push(u as u32);
                }
                Side::Hole => {}
                o if o != s => {
                    let f = tri.face(t, i);
                    return Err(TetMeshError::new(
                        name,
                        "inside and outside meet across a face that is not on the boundary",
                        Some(tri.pts[f[0] as usize]),
                    ));
                }
                _ => {}
            }
        }
    }
    // Tets no flood reached are walled in by holes (e.g. behind box sides whose cospherical
    // squares the tetrahedralization split the other way): they join the holes, whose inner part
    // the front meshes whatever side they were on.
    for (t, s) in side.iter_mut().enumerate() {
        if *s == Side::Unknown && tri.alive(t as u32) {
            *s = Side::Hole;
        }
    }
    Ok(())
}

/// The holes' inner surface, once the holes have grown round every edge where it pinched.
pub(super) fn unpinched_hole_surface(
    tri: &Tri,
    side: &mut [Side],
    all: &[([u32; 3], bool)],
    holders: &[Holders],
    vtet: &[u32],
    name: &str,
) -> Result<HoleSurface, TetMeshError> {
    // Where the hole's inner part pinches along an edge (hole and kept tets alternate round
    // it), the kept tets round that edge join the hole, until its surface is a manifold.
    let mut grown = 0;
    loop {
        let (sub_b, sub_e) = hole_surface(tri, side, all, holders);
        let pinched = pinched_edges(&sub_b);
        if pinched.is_empty() {
            return Ok((sub_b, sub_e));
        }
        grown += 1;
        if grown > MAX_GROWTH {
            let [u, _] = pinched[0];
            return Err(TetMeshError::new(
                name,
                "a recovery hole stays pinched along an edge",
                Some(tri.pts[u as usize]),
            ));
        }
        for [u, v] in pinched {
            for t in star(tri, u, vtet[u as usize]) {
                if side[t as usize] == Side::In && tri.t[t as usize].v.contains(&v) {
                    side[t as usize] = Side::Hole;
                }
            }
        }
    }
}

/// Widens the holes round `at`, where their front got stuck: every inner tet at a vertex of the
/// holes' surface `sub_b` near `at` (within twice the nearest one's distance) joins them, so
/// that the wall of kept tets that pinned the front there is gone. Returns how many tets joined.
pub(super) fn widen_hole(tri: &Tri, side: &mut [Side], sub_b: &[[u32; 3]], at: [f64; 3]) -> usize {
    let d2 = |v: u32| {
        let p = &tri.pts[v as usize];
        (0..3).map(|k| (p[k] - at[k]).powi(2)).sum::<f64>()
    };
    let near = sub_b
        .iter()
        .flatten()
        .map(|&v| d2(v))
        .fold(f64::INFINITY, f64::min);
    if !near.is_finite() {
        return 0;
    }
    // Where every tet at the nearest wall vertices has joined already, the next ring out.
    for reach in [4.0, 16.0, 64.0] {
        let wall: Vec<u32> = sub_b
            .iter()
            .flatten()
            .copied()
            .filter(|&v| d2(v) <= reach * near)
            .collect();
        let joined = widen_around(tri, side, wall).len();
        if joined > 0 {
            return joined;
        }
    }
    0
}

/// Why the holes could not be filled, with the hole that failed.
pub(super) type HoleError = (TetMeshError, Vec<[u32; 3]>);

/// A hole's own tets and new nodes (numbered after its vertices).
pub(super) type Filled = (Vec<P>, Vec<[u32; 4]>);

/// How holes are filled: the region's name and size field, its embedded segments (which no
/// cone's node may come near), and a tetrahedralization of a hole without new nodes.
pub(super) struct Filler<'a, D: Fn(&RegionInput) -> Option<Filled>> {
    pub name: &'a str,
    pub size: &'a SizeField,
    pub segments: &'a [[P; 2]],
    /// What the fronts filling the holes may spend, all together.
    pub work: &'a FrontWork,
    pub delaunay: D,
}

/// The tets filling the holes, in `tri`'s numbering (new nodes appended). Each hole (a
/// connected piece of the surface; all of them at once where embedded triangles lie inside or
/// a piece is a cavity shell) is
/// tried in turn by `delaunay`, which adds no node, then as a cone from one node in its kernel
/// (`kernel`), then, with `front`, by the front. An error comes with the hole that failed.
pub(super) fn mesh_holes<D: Fn(&RegionInput) -> Option<Filled>>(
    tri: &mut Tri,
    sub_b: &[[u32; 3]],
    sub_e: &[[u32; 3]],
    front: bool,
    fill: &Filler<'_, D>,
) -> Result<Vec<[u32; 4]>, HoleError> {
    // Pieces are filled apart only when each is a solid (not a cavity shell inside another)
    // and each embedded triangle has its corners on one piece only.
    let whole = || vec![(sub_b.to_vec(), sub_e.to_vec())];
    let pieces = match connected_pieces(sub_b) {
        p if p.iter().all(|q| enclosed_volume(&tri.pts, q) > 0.0) => {
            embedded_by_piece(p, sub_e).unwrap_or_else(whole)
        }
        _ => whole(),
    };
    // On an error no node added for the holes before it stays.
    let n = tri.pts.len();
    let mut out = Vec::new();
    for (piece, embedded) in pieces {
        match mesh_hole(tri, &piece, &embedded, front, fill) {
            Ok(tets) => out.extend(tets),
            Err(e) => {
                tri.pts.truncate(n);
                return Err((e, piece));
            }
        }
    }
    Ok(out)
}

/// One hole's tets (see [`mesh_holes`]).
fn mesh_hole<D: Fn(&RegionInput) -> Option<Filled>>(
    tri: &mut Tri,
    sub_b: &[[u32; 3]],
    sub_e: &[[u32; 3]],
    front: bool,
    fill: &Filler<'_, D>,
) -> Result<Vec<[u32; 4]>, TetMeshError> {
    let name = fill.name;
    let (sub, back) = compact_input(name, &tri.pts, sub_b, sub_e);
    check_input(&sub).map_err(|e| {
        TetMeshError::new(
            name,
            format!("a recovery hole is not valid: {}", e.message),
            e.at,
        )
    })?;
    // Without embedded triangles: the hole's own Delaunay mesh, else the cone.
    let plain = |h: &RegionInput| -> Option<Filled> {
        (fill.delaunay)(h).or_else(|| {
            let cone = kernel::cone(&h.vertices, &h.boundary, fill.segments)
                .filter(|_| h.embedded.is_empty())?;
            Some((vec![cone.0], cone.1))
        })
    };
    let (nodes, tets) = match plain(&sub).or_else(|| peel::peel(&sub, &plain)) {
        Some(filled) => filled,
        None if !front => {
            return Err(TetMeshError::new(
                name,
                "a recovery hole is not star-shaped",
                Some(centre(&sub.vertices)),
            ));
        }
        None => {
            // The hole's front has a budget of its own (within the region's): one that cannot
            // close its hole gives way to a wider hole, or to the front on the whole region.
            let own = fill.work.for_hole(sub.boundary.len() + sub.embedded.len());
            let raw = advance_front(&sub, fill.size, &own);
            fill.work.spend(own.spent());
            let raw = raw?;
            (raw.nodes[sub.vertices.len()..].to_vec(), raw.tets)
        }
    };
    // The new nodes follow the hole's vertices.
    let mut map = back;
    for p in nodes {
        map.push(tri.pts.len() as u32);
        tri.pts.push(p);
    }
    Ok(tets.iter().map(|t| t.map(|v| map[v as usize])).collect())
}

fn centre(pts: &[P]) -> P {
    let mut c = [0.0; 3];
    for p in pts {
        for k in 0..3 {
            c[k] += p[k] / pts.len() as f64;
        }
    }
    c
}

/// The volume a closed surface encloses, positive when its right-hand normals point out (float:
/// it only tells a solid piece from a cavity shell, whose volume is negative).
fn enclosed_volume(pts: &[P], tris: &[[u32; 3]]) -> f64 {
    let o = pts[tris[0][0] as usize];
    tris.iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| pts[v as usize]);
            geom::predicates::signed_volume(&o, &a, &b, &c)
        })
        .sum()
}

/// The pieces of a closed surface that share no edge, each in its input order, the pieces in
/// the order of their first triangle.
pub fn connected_pieces(tris: &[[u32; 3]]) -> Vec<Vec<[u32; 3]>> {
    let mut by_edge: Vec<([u32; 2], usize)> = tris
        .iter()
        .enumerate()
        .flat_map(|(k, t)| (0..3).map(move |e| (sorted2(t[e], t[(e + 1) % 3]), k)))
        .collect();
    by_edge.sort_unstable();
    let mut piece = vec![usize::MAX; tris.len()];
    let mut count = 0;
    for start in 0..tris.len() {
        if piece[start] != usize::MAX {
            continue;
        }
        piece[start] = count;
        let mut stack = vec![start];
        while let Some(k) = stack.pop() {
            for e in 0..3 {
                let key = sorted2(tris[k][e], tris[k][(e + 1) % 3]);
                let first = by_edge.partition_point(|&(x, _)| x < key);
                for &(_, j) in by_edge[first..].iter().take_while(|&&(x, _)| x == key) {
                    if piece[j] == usize::MAX {
                        piece[j] = count;
                        stack.push(j);
                    }
                }
            }
        }
        count += 1;
    }
    let mut out = vec![Vec::new(); count];
    for (k, t) in tris.iter().enumerate() {
        out[piece[k]].push(*t);
    }
    out
}

/// A hole piece: its surface and the embedded triangles inside it.
type Piece = (Vec<[u32; 3]>, Vec<[u32; 3]>);

/// Each piece with the embedded triangles whose corners all lie on it; `None` when all the
/// corners of one lie on no single piece, or on two (pieces touching at an edge of it): such
/// holes are filled together.
fn embedded_by_piece(pieces: Vec<Vec<[u32; 3]>>, embedded: &[[u32; 3]]) -> Option<Vec<Piece>> {
    let mut pieces_at: HashMap<u32, Vec<usize>> = HashMap::new();
    for (k, piece) in pieces.iter().enumerate() {
        for &v in piece.iter().flatten() {
            let at = pieces_at.entry(v).or_default();
            if !at.contains(&k) {
                at.push(k);
            }
        }
    }
    let mut out: Vec<_> = pieces.into_iter().map(|p| (p, Vec::new())).collect();
    for t in embedded {
        let at = |v: &u32| pieces_at.get(v).map_or(&[][..], Vec::as_slice);
        let mut holding = at(&t[0])
            .iter()
            .filter(|k| t[1..].iter().all(|v| at(v).contains(k)));
        match (holding.next(), holding.next()) {
            (Some(&k), None) => out[k].1.push(*t),
            _ => return None,
        }
    }
    Some(out)
}

fn sorted2(a: u32, b: u32) -> [u32; 2] {
    [a.min(b), a.max(b)]
}

/// Widens the holes by every inner tet at one of the vertices `wall` (a failed hole's, or the
/// last ring's); returns the tets that joined.
pub(super) fn widen_around(tri: &Tri, side: &mut [Side], mut wall: Vec<u32>) -> Vec<u32> {
    wall.sort_unstable();
    wall.dedup();
    let joining: Vec<u32> = tri
        .live_tets()
        .filter(|&t| {
            side[t as usize] == Side::In
                && tri.t[t as usize]
                    .v
                    .iter()
                    .any(|v| wall.binary_search(v).is_ok())
        })
        .collect();
    for &t in &joining {
        side[t as usize] = Side::Hole;
    }
    joining
}

/// The faces holes share with inner tets (by sorted vertices), each with the inner tet's side.
pub(super) fn hole_walls(tri: &Tri, side: &[Side], live: &[u32]) -> HashMap<[u32; 3], u32> {
    let mut surface: HashMap<[u32; 3], u32> = HashMap::new();
    for &t in live {
        if side[t as usize] != Side::Hole {
            continue;
        }
        for i in 0..4 {
            let a = tri.t[t as usize].adj[i];
            if a != NONE && side[(a >> 2) as usize] == Side::In {
                surface.insert(sorted(tri.face(t, i)), a);
            }
        }
    }
    surface
}

fn seed(side: &mut [Side], t: u32, s: Side, tri: &Tri, name: &str) -> Result<(), TetMeshError> {
    match side[t as usize] {
        Side::Unknown => side[t as usize] = s,
        Side::Hole => {}
        o if o != s => {
            return Err(TetMeshError::new(
                name,
                "a tet lies on both sides of the boundary",
                Some(tri.pts[tri.t[t as usize].v[0] as usize]),
            ));
        }
        _ => {}
    }
    Ok(())
}

/// The inner part of the holes: the faces from hole tets to kept inner tets, the boundary
/// triangles inside or on the holes, and the embedded triangles inside them (those with a hole on
/// one side only bound it).
fn hole_surface(
    tri: &Tri,
    side: &[Side],
    all: &[([u32; 3], bool)],
    holders: &[Holders],
) -> HoleSurface {
    let mut sub_b: Vec<[u32; 3]> = Vec::new();
    let mut sub_e: Vec<[u32; 3]> = Vec::new();
    for t in tri.live_tets() {
        if side[t as usize] != Side::Hole {
            continue;
        }
        for i in 0..4 {
            let a = tri.t[t as usize].adj[i];
            if a == NONE || tri.t[t as usize].cons & (1 << i) != 0 {
                continue;
            }
            if side[(a >> 2) as usize] == Side::In {
                sub_b.push(tri.face(t, i));
            }
        }
    }
    for (k, &(f, embedded)) in all.iter().enumerate() {
        let hs = &holders[k];
        if hs.is_empty() {
            if embedded {
                sub_e.push(f);
            } else {
                sub_b.push(f);
            }
            continue;
        }
        let in_hole: Vec<(u32, usize)> = hs
            .iter()
            .filter(|(t, _)| side[*t as usize] == Side::Hole)
            .collect();
        if embedded {
            match in_hole.len() {
                2 => sub_e.push(f),
                1 => sub_b.push(tri.face(in_hole[0].0, in_hole[0].1)),
                _ => {}
            }
        } else if in_hole.iter().any(|&(t, i)| same_turn(tri.face(t, i), f)) {
            sub_b.push(f);
        }
    }
    (sub_b, sub_e)
}

/// Edges that two faces of `tris` traverse in the same direction.
fn pinched_edges(tris: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let mut directed: Vec<[u32; 2]> = tris
        .iter()
        .flat_map(|t| [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]])
        .collect();
    directed.sort_unstable();
    let mut out: Vec<[u32; 2]> = directed
        .windows(2)
        .filter(|w| w[0] == w[1])
        .map(|w| w[0])
        .collect();
    out.dedup();
    out
}

/// The sub-problem over only the vertices it uses; `back[local] = global`.
fn compact_input(
    name: &str,
    pts: &[P],
    boundary: &[[u32; 3]],
    embedded: &[[u32; 3]],
) -> (RegionInput, Vec<u32>) {
    let mut local: HashMap<u32, u32> = HashMap::new();
    let mut back: Vec<u32> = Vec::new();
    let mut map = |v: u32| {
        *local.entry(v).or_insert_with(|| {
            back.push(v);
            (back.len() - 1) as u32
        })
    };
    let b: Vec<[u32; 3]> = boundary.iter().map(|t| t.map(&mut map)).collect();
    let e: Vec<[u32; 3]> = embedded.iter().map(|t| t.map(&mut map)).collect();
    let vertices = back.iter().map(|&v| pts[v as usize]).collect();
    (
        RegionInput {
            name: name.to_string(),
            vertices,
            boundary: b,
            embedded: e,
            lines: Vec::new(),
        },
        back,
    )
}

#[cfg(test)]
mod tests {
    use super::{connected_pieces, embedded_by_piece};

    #[test]
    fn a_solid_encloses_a_positive_volume_and_a_cavity_shell_a_negative_one() {
        let (pts, mut faces) = test_support::shapes::cuboid([0.0; 3], [2.0; 3]);
        assert!((super::enclosed_volume(&pts, &faces) - 8.0).abs() < 1e-12);
        for f in &mut faces {
            f.swap(1, 2);
        }
        assert!((super::enclosed_volume(&pts, &faces) + 8.0).abs() < 1e-12);
    }

    #[test]
    fn holes_sharing_only_a_vertex_are_separate_pieces_in_input_order() {
        // Two tetrahedra's surfaces meeting at vertex 0, the second listed first.
        let a = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]];
        let b = [[0, 4, 5], [0, 6, 4], [0, 5, 6], [4, 6, 5]];
        let tris: Vec<[u32; 3]> = b.iter().chain(&a).copied().collect();
        let pieces = connected_pieces(&tris);
        assert_eq!(pieces, vec![b.to_vec(), a.to_vec()]);
    }

    /// Two tetrahedra's surfaces, apart (vertices 0..4 and 4..8), as pieces.
    fn two_pieces() -> Vec<Vec<[u32; 3]>> {
        let a = vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]];
        let b = vec![[4, 5, 6], [4, 7, 5], [4, 6, 7], [5, 7, 6]];
        vec![a, b]
    }

    #[test]
    fn an_embedded_triangle_goes_with_the_piece_its_corners_lie_on() {
        let split = embedded_by_piece(two_pieces(), &[[4, 5, 7], [0, 1, 3]]).expect("apart");
        assert_eq!(split[0].1, vec![[0, 1, 3]]);
        assert_eq!(split[1].1, vec![[4, 5, 7]]);
        assert_eq!(split[1].0, two_pieces()[1]);
    }

    #[test]
    fn an_embedded_triangle_on_no_single_piece_keeps_the_holes_together_and_a_touch_does_not() {
        assert!(embedded_by_piece(two_pieces(), &[[0, 1, 4]]).is_none());
        assert!(embedded_by_piece(two_pieces(), &[[0, 1, 9]]).is_none());
        let touching = || vec![vec![[0, 1, 2], [0, 2, 3]], vec![[0, 4, 5], [0, 5, 6]]];
        assert_eq!(embedded_by_piece(touching(), &[]).map(|s| s.len()), Some(2));
        let split = embedded_by_piece(touching(), &[[0, 5, 6]]).expect("one piece holds it");
        assert_eq!(split[1].1, vec![[0, 5, 6]]);
    }
}
