//! Where a region's boundary is pinched: a vertex lies far closer to a part of the boundary that
//! is not its neighbour than the triangles round it are wide (two horizons that nearly touch, a
//! fold pressed nearly flat).
//!
//! The advancing front builds tets of about the local size and cannot close a gap twenty times
//! thinner than the faces on either side of it: it back-tracks there until its work runs out. The
//! Delaunay method can (its flat tets are left to the optimizer), so only the front's run on the
//! whole region, after the Delaunay method gave way, is skipped where the boundary is pinched,
//! and the region's error then says where; and the recovery stops widening its holes for the
//! front once its fronts have spent more than one closing a hole of a pinched region does.
//!
//! Each vertex is compared with every triangle within [`PINCH_RATIO`] of its mean edge length,
//! but those that touch its neighbours (so the edges and faces round a sharp edge or corner do
//! not count as gaps). The distances are measured in floating point: they decide only whether
//! the front is tried, never a mesh's topology.

use geom::BBox;
use geom::broad_phase::overlapping_pairs;
use geom::closest::closest_on_triangle;
use geom::predicates::dist;

use super::RegionInput;

/// A gap below this share of the mean edge length round its vertex is a pinch. On the example
/// with a horizon jittered by up to 35 or 50 m, the one region the front meshed after the Delaunay
/// method gave way had no gap below 0.15 of its edges; the five where it failed, after 47 to 67 s
/// each, had gaps of 0.0019 to 0.037 of theirs.
pub const PINCH_RATIO: f64 = 0.05;

/// The narrowest gap of a pinched boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pinch {
    /// The vertex at the gap.
    pub at: [f64; 3],
    /// The distance from it to the nearest triangle that is not its neighbour.
    pub gap: f64,
    /// The mean length of the edges round it.
    pub width: f64,
}

/// The narrowest gap of `input`'s boundary and embedded triangles below [`PINCH_RATIO`] of its
/// width (ties to the lowest vertex, then the lowest triangle), or `None`.
pub fn narrowest(input: &RegionInput) -> Option<Pinch> {
    let pts = &input.vertices;
    let tris: Vec<[u32; 3]> = input
        .boundary
        .iter()
        .chain(&input.embedded)
        .copied()
        .collect();
    let ring = Ring::of(pts.len(), &tris);
    let width = ring.widths(pts);
    // The vertices' boxes first (each its reach), then the triangles': a pair (vertex, triangle)
    // is judged once, as `i < j`.
    let n = pts.len() as u32;
    let mut boxes: Vec<BBox> = (0..pts.len())
        .map(|v| reach(&pts[v], PINCH_RATIO * width[v]))
        .collect();
    boxes.extend(
        tris.iter()
            .map(|t| BBox::from_points(t.iter().map(|&i| &pts[i as usize]))),
    );
    let found = overlapping_pairs(&boxes, |i, j| {
        if i >= n || j < n || width[i as usize] <= 0.0 {
            return None;
        }
        let t = tris[(j - n) as usize];
        if t.iter().any(|&w| ring.near(i, w)) {
            return None;
        }
        let p = &pts[i as usize];
        let [a, b, c] = t.map(|w| &pts[w as usize]);
        let gap = dist(p, &closest_on_triangle(p, a, b, c).0);
        (gap < PINCH_RATIO * width[i as usize]).then_some(gap)
    });
    // The pairs come sorted: of the narrowest, the first is that of the lowest vertex.
    let ratio = |&(v, _, gap): &(u32, u32, f64)| gap / width[v as usize];
    let mut narrowest: Option<&(u32, u32, f64)> = None;
    for f in &found {
        if narrowest.is_none_or(|b| ratio(f) < ratio(b)) {
            narrowest = Some(f);
        }
    }
    let &(v, _, gap) = narrowest?;
    Some(Pinch {
        at: pts[v as usize],
        gap,
        width: width[v as usize],
    })
}

/// The box of the points within `r` of `p`.
fn reach(p: &[f64; 3], r: f64) -> BBox {
    BBox {
        min: [p[0] - r, p[1] - r, p[2] - r],
        max: [p[0] + r, p[1] + r, p[2] + r],
    }
}

/// Each vertex's neighbours (the vertices it shares a triangle with, and itself), sorted.
struct Ring {
    start: Vec<usize>,
    next: Vec<u32>,
}

impl Ring {
    fn of(n: usize, tris: &[[u32; 3]]) -> Ring {
        let mut pairs: Vec<(u32, u32)> = (0..n as u32).map(|v| (v, v)).collect();
        for t in tris {
            for a in 0..3 {
                for b in 0..3 {
                    if a != b {
                        pairs.push((t[a], t[b]));
                    }
                }
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        let mut start = vec![0; n + 1];
        for &(v, _) in &pairs {
            start[v as usize + 1] += 1;
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        Ring {
            start,
            next: pairs.into_iter().map(|(_, w)| w).collect(),
        }
    }

    fn of_vertex(&self, v: u32) -> &[u32] {
        &self.next[self.start[v as usize]..self.start[v as usize + 1]]
    }

    /// Whether `w` is `v` or one of its neighbours.
    fn near(&self, v: u32, w: u32) -> bool {
        self.of_vertex(v).binary_search(&w).is_ok()
    }

    /// Each vertex's mean edge length (0 for a vertex on no triangle).
    fn widths(&self, pts: &[[f64; 3]]) -> Vec<f64> {
        (0..pts.len() as u32)
            .map(|v| {
                // The ring holds the vertex itself, at distance 0.
                let ring = self.of_vertex(v);
                let sum: f64 = (ring.iter())
                    .map(|&w| dist(&pts[v as usize], &pts[w as usize]))
                    .sum();
                if ring.len() > 1 {
                    sum / (ring.len() - 1) as f64
                } else {
                    0.0
                }
            })
            .collect()
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The cube [0,3]^3 gridded 3 × 3 per side, its z scaled by `squash`: a slab 3 × 3 × 3
    /// `squash` with edges of 1 on its top and bottom.
    pub(crate) fn slab(squash: f64) -> RegionInput {
        let (mut vertices, boundary) = test_support::shapes::gridded_cube(3, 3.0);
        for v in &mut vertices {
            v[2] *= squash;
        }
        RegionInput {
            name: "slab".into(),
            vertices,
            boundary,
            ..RegionInput::default()
        }
    }

    #[test]
    fn a_cube_and_a_thin_slab_are_not_pinched() {
        assert_eq!(narrowest(&slab(1.0)), None);
        // 0.3 thick under edges of 1 to 1.4: thin, but a front closes it.
        assert_eq!(narrowest(&slab(0.1)), None);
    }

    #[test]
    fn a_slab_far_thinner_than_its_edges_is_pinched_between_top_and_bottom() {
        let p = narrowest(&slab(0.01)).expect("pinched");
        assert!(p.gap > 0.0 && p.gap <= 0.03 + 1e-12, "{p:?}");
        assert!(p.gap < PINCH_RATIO * p.width, "{p:?}");
        // From a vertex of the top or of the bottom, across the slab.
        assert!([0.0, 0.03].contains(&p.at[2]), "{p:?}");
    }

    #[test]
    fn one_vertex_pressed_nearly_onto_the_opposite_side_is_the_pinch() {
        let mut input = slab(1.0);
        // An inner vertex of the top (z = 3) pressed down to 0.002 over the bottom.
        let v = (input.vertices.iter())
            .position(|p| p[2] == 3.0 && p[0] == 1.0 && p[1] == 1.0)
            .expect("an inner top vertex");
        input.vertices[v][2] = 0.002;
        let p = narrowest(&input).expect("pinched");
        assert_eq!(p.at, [1.0, 1.0, 0.002]);
        assert!((p.gap - 0.002).abs() < 1e-12, "{p:?}");
    }
}
