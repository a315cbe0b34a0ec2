//! Facet normals: the direction each imported triangle stands for, where creases and charts are
//! decided and, carried with each patch, where the surface mesher measures curvature.
//!
//! A cap (a triangle with one angle near 180°, its third corner almost on its longest edge) is a
//! crack filler: its own normal turns with the smallest jitter of that corner, and on real
//! triangulations it stands almost anywhere. On a revolved salt wall, a cap of 171° stood at 89°
//! and 118° to every neighbour. Its edges became creases, the creases a sliver patch of their
//! own whose corners were 3-6°, and the tets on the needle there reached 5.7°.
//!
//! Decisions and why:
//! - A triangle is a cap when its largest angle exceeds [`CAP_DEG`]. On a smooth stretch, where
//!   the proper triangle across its longest edge faces within the crease angle of every proper
//!   triangle at the cap's three corners, its normal is that triangle's: the surface it fills a
//!   crack of turns less than a crease there, so no crease runs along it and no chart ends at it.
//!   The chart angle bounds that angle too, when it is the smaller (creases turned off with
//!   `crease_angle_deg = 179`): the normals steer charts as well, and a lens rim's caps taken
//!   into their neighbours' chart on such a "smooth" stretch folded its surface mesh.
//!   Caps at its corners are not asked: a revolved salt wall's caps come in pairs, each standing
//!   at 118° to the other.
//! - A needle (a triangle with an angle under [`NEEDLE_DEG`]) is taken as a cap: its normal
//!   turns with the least move of its short edge's ends. Where a curve cuts a cap, the split
//!   leaves a needle on the cap's wall (0.4 m by 42 m, largest angle 139°) standing as the cap
//!   did.
//! - Where the surface itself turns sharply (a lens's rim sampled by a few rings, crumpled into
//!   caps between triangles 45-107° apart), a cap keeps its own normal: which side it joins
//!   would move the rim's crease and charts, and a rim so turned folded the surface mesh of a
//!   chart that took its caps in.
//! - A cap that faces away from that triangle by 90° or more keeps its own normal too: it folds
//!   back over the surface, and the charts must see the fold.
//! - Where the triangle across is itself a cap, the walk goes on across that one's longest edge,
//!   at most [`CHAIN`] steps; a cap with no proper triangle within reach, or on the border
//!   there, keeps its own normal.
//! - Normals are measures steering where creases and seams go, not orientation decisions; the
//!   walk and the neighbour are decided by index and exact equality, so the result is the same on
//!   every machine.

use crate::adjacency::{NONE, across_edges, stars};
use crate::predicates::{dot, sub};
use crate::{Tolerances, TriMesh};

/// A triangle whose largest angle exceeds this (degrees) is a cap.
pub const CAP_DEG: f64 = 150.0;
/// A triangle whose smallest angle is below this (degrees) is a needle, and stands for a
/// triangle across as a cap does.
pub const NEEDLE_DEG: f64 = 2.0;
/// Most caps walked across from one cap in search of a proper triangle.
pub const CHAIN: usize = 8;

/// The unit normal that each triangle of `mesh` stands for (see the module doc), with creases
/// and charts at `tol`'s angles; zero where a triangle has none.
pub fn facet_normals(mesh: &TriMesh, tol: &Tolerances) -> Vec<[f64; 3]> {
    let own = mesh.unit_normals();
    let longest: Vec<Option<usize>> = (0..mesh.triangles.len())
        .map(|t| cap_edge(mesh, t))
        .collect();
    if longest.iter().all(Option::is_none) {
        return own;
    }
    let across = across_edges(mesh);
    let star = stars(mesh);
    let smooth_deg = tol.crease_angle_deg.min(tol.chart_angle_deg);
    let cos_crease = smooth_deg.to_radians().cos();
    (0..mesh.triangles.len())
        .map(|t| {
            if longest[t].is_none() {
                return own[t];
            }
            let Some(side) = proper_across(&longest, &across, t) else {
                return own[t];
            };
            let faces_side = |u: usize| dot(&own[u], &own[side]) >= cos_crease;
            let smooth = (mesh.triangles[t].iter())
                .flat_map(|&v| &star[v as usize])
                .all(|&u| longest[u as usize].is_some() || faces_side(u as usize));
            let upright = dot(&own[t], &own[side]) > 0.0;
            if smooth && upright { own[side] } else { own[t] }
        })
        .collect()
}

/// The first proper triangle met walking from cap `t` across caps' longest edges, at most
/// [`CHAIN`] steps.
fn proper_across(longest: &[Option<usize>], across: &[[u32; 3]], t: usize) -> Option<usize> {
    let mut at = t;
    for _ in 0..CHAIN {
        match longest[at] {
            None => return Some(at),
            Some(k) if across[at][k] == NONE => return None,
            Some(k) => at = across[at][k] as usize,
        }
    }
    None
}

/// The longest edge `k` (from corner `k` to corner `k + 1`) of triangle `t` when it is a cap or
/// a needle (never when a corner is not a vertex of `mesh`).
fn cap_edge(mesh: &TriMesh, t: usize) -> Option<usize> {
    let tri = mesh.triangles[t];
    let corners = tri.map(|v| mesh.vertices.get(v as usize));
    let [Some(p0), Some(p1), Some(p2)] = corners else {
        return None;
    };
    let p = |k: usize| [p0, p1, p2][k % 3];
    // The cosine of the angle at corner k + 2, opposite edge k, and the edge's squared length.
    let opposite = |k: usize| {
        let (a, b) = (sub(p(k), p(k + 2)), sub(p(k + 1), p(k + 2)));
        let len = (dot(&a, &a) * dot(&b, &b)).sqrt();
        let e = sub(p(k + 1), p(k));
        ((len > 0.0).then(|| dot(&a, &b) / len), dot(&e, &e))
    };
    let edges = [opposite(0), opposite(1), opposite(2)];
    let (cos_cap, cos_needle) = (CAP_DEG.to_radians().cos(), NEEDLE_DEG.to_radians().cos());
    let sliver = (edges.iter()).any(|(c, _)| c.is_some_and(|c| c < cos_cap || c > cos_needle));
    let longest = (0..3).fold(0, |m, k| if edges[k].1 > edges[m].1 { k } else { m });
    sliver.then_some(longest)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strip: triangle 0 on one side of the edge 0-1, and a cap 0-2-1 (corner 2 lifted `lift`
    /// off the plane, a tenth of a metre from the edge) on the other, then triangles 0-3-2 and
    /// 2-3-1 beyond the cap, their far corner `drop` below the plane.
    fn strip(lift: f64, drop: f64) -> TriMesh {
        TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [10.0, 0.0, 0.0],
                [5.0, -0.1, lift],
                [5.0, -5.0, -drop],
                [5.0, 5.0, 0.0],
            ],
            vec![[0, 1, 4], [0, 2, 1], [0, 3, 2], [2, 3, 1]],
        )
    }

    #[test]
    fn a_cap_on_a_smooth_stretch_stands_for_the_triangle_across_its_longest_edge() {
        let m = strip(0.3, 0.0);
        let own = m.unit_normals();
        assert!(dot(&own[1], &own[0]) < 0.5, "the cap itself stands up");
        let n = facet_normals(&m, &Tolerances::default());
        assert_eq!(n[1], own[0]);
        assert_eq!([n[0], n[2], n[3]], [own[0], own[2], own[3]]);
    }

    #[test]
    fn a_cap_where_the_surface_turns_by_a_crease_keeps_its_own_normal() {
        // The far side bent down by 45° about the cap's long edge: a rim.
        let m = strip(0.3, 5.0);
        assert_eq!(facet_normals(&m, &Tolerances::default()), m.unit_normals());
    }

    #[test]
    fn with_creases_turned_off_a_cap_where_the_surface_turns_past_the_chart_angle_keeps_its_normal()
    {
        // The far side bent down by 70° about the cap's long edge.
        let m = strip(0.3, 13.7);
        let no_creases = Tolerances {
            crease_angle_deg: 179.0,
            ..Tolerances::default()
        };
        assert_eq!(facet_normals(&m, &no_creases), m.unit_normals());
        let gentle = strip(0.3, 1.0);
        assert_ne!(facet_normals(&gentle, &no_creases), gentle.unit_normals());
    }

    #[test]
    fn a_cap_folded_back_over_the_surface_keeps_its_own_normal() {
        let mut m = strip(0.0, 0.0);
        m.vertices[2] = [5.0, 0.1, 0.05];
        let own = m.unit_normals();
        assert!(dot(&own[1], &own[0]) < 0.0, "the cap faces down");
        assert_eq!(facet_normals(&m, &Tolerances::default()), own);
    }

    #[test]
    fn a_chain_of_caps_is_walked_to_the_proper_triangle_beyond() {
        // Triangle 0 proper; cap 1 across its edge 0-1; cap 2 across cap 1's short edge 0-3,
        // which is cap 2's longest.
        let m = TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [10.0, 0.0, 0.0],
                [2.5, -0.15, -0.3],
                [5.0, -0.1, 0.2],
                [5.0, 5.0, 0.0],
            ],
            vec![[0, 1, 4], [1, 0, 3], [3, 0, 2]],
        );
        let own = m.unit_normals();
        assert!(dot(&own[2], &own[0]) < 0.9, "cap 2 leans away");
        assert_eq!(facet_normals(&m, &Tolerances::default()), vec![own[0]; 3]);
    }

    #[test]
    fn a_needle_standing_on_a_smooth_stretch_stands_for_the_triangle_across_its_longest_edge() {
        // Triangle 1 has an angle of 1.7° at corner 0 and stands at 80° to triangle 0, as the
        // piece of a cap's wall a curve cuts off does; its largest angle is no cap's.
        let m = TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [10.0, 0.0, 0.0],
                [10.0, 0.05, 0.3],
                [0.0, 10.0, 0.0],
            ],
            vec![[0, 2, 3], [0, 1, 2]],
        );
        let own = m.unit_normals();
        assert!(dot(&own[1], &own[0]) < 0.2, "the needle stands up");
        assert_eq!(facet_normals(&m, &Tolerances::default()), vec![own[0]; 2]);
    }

    #[test]
    fn a_proper_triangle_keeps_its_own_normal() {
        let m = TriMesh::new(
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.5]],
            vec![[0, 1, 2]],
        );
        assert_eq!(facet_normals(&m, &Tolerances::default()), m.unit_normals());
    }

    #[test]
    fn a_cap_on_the_border_keeps_its_own_normal() {
        let m = TriMesh::new(
            vec![[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [5.0, -0.1, 0.3]],
            vec![[0, 2, 1]],
        );
        assert_eq!(facet_normals(&m, &Tolerances::default()), m.unit_normals());
    }
}
