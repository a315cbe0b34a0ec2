//! How thick a region is: the typical distance across it, measured from the model, so that a
//! recipe can ask for a number of elements across a layer (`layers`) instead of a size, and the
//! report can say when a region is thinner than the elements it is meshed with.
//!
//! Decisions and why:
//! - Thickness at a boundary triangle is the distance from its centroid, along its inward normal,
//!   to the first boundary triangle of the same region the ray meets: across a layer that is the
//!   distance from its top to its bottom, whatever the dip; in a sphere, its diameter.
//! - The region's thickness is the area-weighted median of those distances: a layer's top and
//!   bottom outweigh its sides (box sides, faults), whose rays run along the layer, so the figure
//!   is the layer's thickness and not its length. Patches the region has on both sides (a
//!   dangling fault inside it) do not bound it and are left out.
//! - At most [`MAX_SAMPLES`] triangles are cast, taken evenly through the region's triangles:
//!   the median of thousands of samples is stable and the cost stays bounded on dense supports.
//! - It is a measure steering sizes, not a decision on geometry: floats, a Möller–Trumbore ray
//!   test, rays that meet nothing (a grazing ray through a seam) are left out.

use crate::regions::{FaceUse, PatchIn, Side};
use geom::TriMesh;
use geom::predicates::{cross, dot, sub};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};

/// Triangles cast per region, at most.
pub const MAX_SAMPLES: usize = 4096;

/// Two walls face each other across a region where their inward normals are more than 150°
/// apart (the cosine of the angle between them is under minus this): a layer's top and base
/// closing at under 30°, a lens's two sides; not a layer's top and the box side or fault it
/// ends on, nor the two sides of a 60° corner, which elements of one size fill well.
pub const OPPOSITE: f64 = 0.866;

type Boxed = GeomWithData<Rectangle<[f64; 3]>, u32>;

/// One boundary triangle of a region, facing into it.
struct Wall {
    corners: [[f64; 3]; 3],
    /// Unit normal pointing into the region.
    inward: [f64; 3],
    area: f64,
}

/// The thickness of the region bounded by `sides` (face-uses of `patches`), as the module doc
/// defines it; `None` when no ray meets the far side (an empty or open region).
pub fn region_thickness(patches: &[PatchIn], sides: &[FaceUse]) -> Option<f64> {
    let meshes: Vec<&TriMesh> = patches.iter().map(|p| &p.mesh).collect();
    let inside = Inside::new(&meshes, sides)?;
    let walls = &inside.walls;
    let step = walls.len().div_ceil(MAX_SAMPLES).max(1);
    let mut samples: Vec<(f64, f64)> = (0..walls.len())
        .step_by(step)
        .filter_map(|i| {
            inside
                .across(i, &centroid(&walls[i]))
                .map(|t| (t, walls[i].area))
        })
        .collect();
    weighted_median(&mut samples)
}

/// Where the region bounded by `sides` (face-uses of the patches whose meshes are `meshes`) is
/// thinner than `thin`: points on its walls, each with the distance across the region there and
/// the area of wall it stands for, so
/// that sizes can follow the local thickness where a layer thins (a pinch-out, a wedge) rather
/// than its median. A wall is looked at first at its centroid and near its corners; one thinner
/// than `thin` at any of them is then sampled on a grid at `spacing(thickness)` (its thinnest
/// probe's), the grid widened evenly over all such walls so that there are at most about
/// `max_points` casts. In wall order, deterministic.
pub fn thin_places(
    meshes: &[&TriMesh],
    sides: &[FaceUse],
    thin: f64,
    spacing: &dyn Fn(f64) -> f64,
    max_points: usize,
) -> Vec<([f64; 3], f64, f64)> {
    let Some(inside) = Inside::new(meshes, sides) else {
        return Vec::new();
    };
    let walls = &inside.walls;
    // Pass 1: the thinnest of each wall's probes, for the walls thinner than `thin` somewhere.
    let thin_walls: Vec<(usize, f64)> = (0..walls.len())
        .filter_map(|i| {
            let c = centroid(&walls[i]);
            let probes = std::iter::once(c).chain(walls[i].corners.iter().map(|v| pulled(v, &c)));
            let t = (probes.filter_map(|p| inside.across_to_opposite(i, &p)))
                .fold(f64::INFINITY, f64::min);
            (t < thin).then_some((i, t))
        })
        .collect();
    // Pass 2: a grid on each at its spacing, all widened alike to stay within `max_points`.
    let steps = |i: usize, h: f64| (longest_edge(&walls[i].corners) / h).ceil().max(1.0);
    let count = |widen: f64| -> f64 {
        (thin_walls.iter())
            .map(|&(i, t)| {
                let k = steps(i, spacing(t) * widen);
                (k + 1.0) * (k + 2.0) / 2.0
            })
            .sum()
    };
    let widen = (count(1.0) / max_points.max(1) as f64).sqrt().max(1.0);
    let mut out = Vec::new();
    for &(i, t) in &thin_walls {
        let k = steps(i, spacing(t) * widen) as usize;
        let share = walls[i].area / ((k + 1) * (k + 2) / 2) as f64;
        let [a, b, c] = walls[i].corners;
        let mid = centroid(&walls[i]);
        for u in 0..=k {
            for v in 0..=k - u {
                let (wu, wv) = (u as f64 / k as f64, v as f64 / k as f64);
                let p = [0, 1, 2].map(|d| a[d] + wu * (b[d] - a[d]) + wv * (c[d] - a[d]));
                let p = pulled(&p, &mid);
                if let Some(t) = inside.across_to_opposite(i, &p).filter(|&t| t < thin) {
                    out.push((p, t, share));
                }
            }
        }
    }
    out
}

/// Walls looked at round a point by [`thickness_near`].
const NEAR_WALLS: usize = 8;

/// The distance across the region bounded by `sides` (face-uses of the patches whose meshes are
/// `meshes`) near the point `at` in it, so that a bad element there can be put down to a thin
/// part of the region: of the walls nearest `at` (at most `NEAR_WALLS`, by their points
/// nearest it, ties by index), the first whose cast from that point along its inward normal
/// meets a wall facing it ([`OPPOSITE`]) gives it. Only the nearest counts: a wall's point
/// farther off measures the region elsewhere. `None` when no such ray meets one.
pub fn thickness_near(meshes: &[&TriMesh], sides: &[FaceUse], at: [f64; 3]) -> Option<f64> {
    let inside = Inside::new(meshes, sides)?;
    let mut near: Vec<(f64, usize, [f64; 3])> = (inside.tree.nearest_neighbor_iter(at))
        .take(NEAR_WALLS)
        .map(|b| {
            let i = b.data as usize;
            let [a, b, c] = &inside.walls[i].corners;
            let (p, _) = geom::closest::closest_on_triangle(&at, a, b, c);
            (geom::predicates::dist(&p, &at), i, p)
        })
        .collect();
    near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    near.into_iter().find_map(|(_, i, p)| {
        // Off the wall's edges, but barely: a support's walls can be hundreds of metres wide.
        let c = centroid(&inside.walls[i]);
        let p = [0, 1, 2].map(|k| p[k] + 1e-3 * (c[k] - p[k]));
        inside.across_to_opposite(i, &p)
    })
}

/// `p` moved a hundredth of the way towards `to`: a ray from a wall's corner or edge would run
/// along the wall beside it.
fn pulled(p: &[f64; 3], to: &[f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| p[k] + 0.01 * (to[k] - p[k]))
}

fn longest_edge(c: &[[f64; 3]; 3]) -> f64 {
    [(0, 1), (1, 2), (2, 0)]
        .iter()
        .map(|&(i, j)| geom::predicates::dist(&c[i], &c[j]))
        .fold(0.0, f64::max)
}

/// A region's walls, indexed for ray casts.
struct Inside {
    walls: Vec<Wall>,
    tree: RTree<Boxed>,
    diag: f64,
}

impl Inside {
    /// The walls of the region bounded by `sides` (face-uses of the patches whose meshes are
    /// `meshes`); `None` without any.
    fn new(meshes: &[&TriMesh], sides: &[FaceUse]) -> Option<Inside> {
        let walls = walls(meshes, sides);
        let (lo, hi) = walls
            .iter()
            .map(|w| bounds(&w.corners))
            .reduce(|(a, b), (c, d)| (min3(a, c), max3(b, d)))?;
        let tree = RTree::bulk_load(
            (walls.iter().enumerate())
                .map(|(i, w)| {
                    let (lo, hi) = bounds(&w.corners);
                    Boxed::new(Rectangle::from_corners(lo, hi), i as u32)
                })
                .collect(),
        );
        let diag = sub(&hi, &lo).iter().map(|x| x * x).sum::<f64>().sqrt();
        Some(Inside { walls, tree, diag })
    }

    /// The distance across the region from point `o` of wall `i`, along its inward normal.
    fn across(&self, i: usize, o: &[f64; 3]) -> Option<f64> {
        across(&self.walls, &self.tree, i, o, self.diag).map(|(t, _)| t)
    }

    /// As [`Inside::across`], only where the wall met faces wall `i` ([`OPPOSITE`]): near a
    /// layer's edge, a ray from the box side or fault along the layer meets its top or base
    /// at a short distance that is not its thickness.
    fn across_to_opposite(&self, i: usize, o: &[f64; 3]) -> Option<f64> {
        let (t, j) = across(&self.walls, &self.tree, i, o, self.diag)?;
        (dot(&self.walls[i].inward, &self.walls[j].inward) < -OPPOSITE).then_some(t)
    }
}

/// The region's boundary triangles with inward normals (dangling patches left out).
fn walls(meshes: &[&TriMesh], sides: &[FaceUse]) -> Vec<Wall> {
    let both = |p: u32| sides.iter().filter(|f| f.patch == p).count() > 1;
    let mut out = Vec::new();
    for f in sides.iter().filter(|f| !both(f.patch)) {
        let Some(m) = meshes.get(f.patch as usize) else {
            continue;
        };
        for t in &m.triangles {
            let corners = t.map(|v| m.vertices[v as usize]);
            let n = cross(
                &sub(&corners[1], &corners[0]),
                &sub(&corners[2], &corners[0]),
            );
            let len = dot(&n, &n).sqrt();
            if len == 0.0 || !len.is_finite() {
                continue;
            }
            let s = if f.side == Side::Front { 1.0 } else { -1.0 } / len;
            out.push(Wall {
                corners,
                inward: n.map(|x| x * s),
                area: 0.5 * len,
            });
        }
    }
    out
}

fn centroid(w: &Wall) -> [f64; 3] {
    [0, 1, 2].map(|k| (w.corners[0][k] + w.corners[1][k] + w.corners[2][k]) / 3.0)
}

/// Distance from point `o` of wall `i` along its inward normal to the nearest other wall, and
/// that wall, looking out to ever longer reaches (so thin layers cost few candidates) up to twice `diag`.
fn across(
    walls: &[Wall],
    tree: &RTree<Boxed>,
    i: usize,
    o: &[f64; 3],
    diag: f64,
) -> Option<(f64, usize)> {
    let o = *o;
    let d = walls[i].inward;
    let near = 1e-9 * diag;
    let mut reach = diag / 64.0;
    loop {
        let end = [0, 1, 2].map(|k| o[k] + d[k] * reach);
        let env = AABB::from_corners(min3(o, end), max3(o, end));
        let hit = tree
            .locate_in_envelope_intersecting(env)
            .map(|b| b.data as usize)
            .filter(|&j| j != i)
            .filter_map(|j| Some((ray_hits(&o, &d, &walls[j].corners)?, j)))
            .filter(|&(t, _)| t > near && t <= reach)
            .reduce(|a, b| {
                if b.0 < a.0 || (b.0 == a.0 && b.1 < a.1) {
                    b
                } else {
                    a
                }
            });
        if hit.is_some() || reach > 2.0 * diag {
            return hit;
        }
        reach *= 4.0;
    }
}

/// Möller–Trumbore: the ray parameter where `o + t d` meets triangle `c`, if it does.
fn ray_hits(o: &[f64; 3], d: &[f64; 3], c: &[[f64; 3]; 3]) -> Option<f64> {
    let (e1, e2) = (sub(&c[1], &c[0]), sub(&c[2], &c[0]));
    let p = cross(d, &e2);
    let det = dot(&e1, &p);
    if det.abs() < 1e-300 {
        return None;
    }
    let s = sub(o, &c[0]);
    let u = dot(&s, &p) / det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = cross(&s, &e1);
    let v = dot(d, &q) / det;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    Some(dot(&e2, &q) / det)
}

/// The value at half the total weight of `(value, weight)` pairs (sorted in place).
fn weighted_median(samples: &mut [(f64, f64)]) -> Option<f64> {
    samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = samples.iter().map(|s| s.1).sum();
    let mut acc = 0.0;
    for &(t, w) in samples.iter() {
        acc += w;
        if acc >= 0.5 * total {
            return Some(t);
        }
    }
    samples.last().map(|s| s.0)
}

fn bounds(c: &[[f64; 3]; 3]) -> ([f64; 3], [f64; 3]) {
    (min3(min3(c[0], c[1]), c[2]), max3(max3(c[0], c[1]), c[2]))
}

fn min3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| a[k].min(b[k]))
}

fn max3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| a[k].max(b[k]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed box `[0,a]×[0,b]×[0,c]`, two triangles per side, normals outwards.
    fn cuboid(a: f64, b: f64, c: f64) -> PatchIn {
        let (v, triangles) = test_support::shapes::cuboid([0.0; 3], [a, b, c]);
        PatchIn {
            name: "c#1".into(),
            surface: "c".into(),
            mesh: TriMesh {
                vertices: v,
                triangles,
            },
            chart_of: None,
        }
    }

    fn inside(p: u32) -> Vec<FaceUse> {
        vec![FaceUse {
            patch: p,
            side: Side::Back,
        }]
    }

    #[test]
    fn a_flat_slab_is_as_thick_as_it_is_high_whichever_way_it_is_measured() {
        for (a, b, c, want) in [
            (1000.0, 800.0, 35.0, 35.0),
            (35.0, 1000.0, 800.0, 35.0),
            (900.0, 40.0, 1200.0, 40.0),
        ] {
            let t = region_thickness(&[cuboid(a, b, c)], &inside(0)).expect("a thickness");
            assert!((t - want).abs() < 1e-6, "{a}x{b}x{c}: {t}");
        }
    }

    /// A closed wedge: the slab `[0,a]×[0,b]` between z = 0 and z = h0 + slope·x (the cuboid's
    /// top corners lifted).
    fn wedge(a: f64, b: f64, h0: f64, slope: f64) -> TriMesh {
        let (mut vertices, triangles) = test_support::shapes::cuboid([0.0; 3], [a, b, 1.0]);
        for v in vertices.iter_mut().filter(|v| v[2] == 1.0) {
            v[2] = h0 + slope * v[0];
        }
        TriMesh {
            vertices,
            triangles,
        }
    }

    #[test]
    fn a_wedge_is_thin_where_it_thins_and_sampled_there_within_the_budget() {
        let m = wedge(1000.0, 500.0, 2.0, 0.05);
        let spacing = |t: f64| t;
        let places = thin_places(&[&m], &inside(0), 20.0, &spacing, 100_000);
        assert!(!places.is_empty());
        // Thin below 20 m: x under 360 m; the distance across is the local height (within the
        // tilt of the top, under 0.13 %).
        for (p, t, _) in &places {
            assert!(p[0] < 361.0, "{p:?} {t}");
            let h = 2.0 + 0.05 * p[0];
            assert!((t - h).abs() < 0.01 * h, "{p:?}: {t} vs {h}");
        }
        // The areas add up to the thin walls' (top and base, x under 360 m), give or take the
        // triangles' share beyond it: at least that, at most the whole walls.
        let area: f64 = places.iter().map(|(.., a)| a).sum();
        assert!(
            area > 2.0 * 360.0 * 500.0 * 0.9 && area < 2.0 * 1000.0 * 500.0 * 1.01,
            "{area}"
        );
        // Dense where thin (spacing = thickness), near the tip most of all.
        let near_tip = places.iter().filter(|(p, ..)| p[0] < 50.0).count();
        assert!(near_tip > 100, "{near_tip}");
        let capped = thin_places(&[&m], &inside(0), 20.0, &spacing, 500);
        assert!(
            capped.len() <= 2 * 500 && capped.len() * 4 < places.len(),
            "{}",
            capped.len()
        );
        // A slab thicker than `thin` everywhere has no thin place.
        let slab = wedge(1000.0, 500.0, 30.0, 0.0);
        assert!(thin_places(&[&slab], &inside(0), 20.0, &spacing, 1000).is_empty());
    }

    #[test]
    fn the_thickness_near_a_point_of_a_wedge_is_its_height_there() {
        let m = wedge(1000.0, 500.0, 2.0, 0.05);
        for (x, z) in [(100.0, 1.0), (800.0, 10.0), (5.0, 0.5)] {
            let t = thickness_near(&[&m], &inside(0), [x, 250.0, z]).expect("a thickness");
            let h = 2.0 + 0.05 * x;
            assert!((t - h).abs() < 0.02 * h, "at x = {x}: {t} vs {h}");
        }
        // Seen from outside, nothing faces the walls.
        let outside = vec![FaceUse {
            patch: 0,
            side: Side::Front,
        }];
        assert_eq!(thickness_near(&[&m], &outside, [100.0, 250.0, 1.0]), None);
    }

    #[test]
    fn a_region_seen_from_outside_or_with_no_walls_has_no_thickness() {
        let outside = vec![FaceUse {
            patch: 0,
            side: Side::Front,
        }];
        assert_eq!(region_thickness(&[cuboid(10.0, 10.0, 1.0)], &outside), None);
        assert_eq!(region_thickness(&[], &[]), None);
    }

    #[test]
    fn a_patch_the_region_has_on_both_sides_does_not_bound_it() {
        let mut sides = inside(0);
        sides.extend([
            FaceUse {
                patch: 1,
                side: Side::Front,
            },
            FaceUse {
                patch: 1,
                side: Side::Back,
            },
        ]);
        let fault = cuboid(1.0, 1.0, 1.0);
        let t = region_thickness(&[cuboid(1000.0, 1000.0, 50.0), fault], &sides);
        assert!((t.unwrap() - 50.0).abs() < 1e-6);
    }
}
