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
use geom::predicates::{cross, dot, sub};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};

/// Triangles cast per region, at most.
pub const MAX_SAMPLES: usize = 4096;

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
    let walls = walls(patches, sides);
    if walls.is_empty() {
        return None;
    }
    let tree = RTree::bulk_load(
        walls
            .iter()
            .enumerate()
            .map(|(i, w)| {
                let (lo, hi) = bounds(&w.corners);
                Boxed::new(Rectangle::from_corners(lo, hi), i as u32)
            })
            .collect(),
    );
    let (lo, hi) = walls
        .iter()
        .map(|w| bounds(&w.corners))
        .reduce(|(a, b), (c, d)| (min3(a, c), max3(b, d)))?;
    let diag = sub(&hi, &lo).iter().map(|x| x * x).sum::<f64>().sqrt();
    let step = walls.len().div_ceil(MAX_SAMPLES).max(1);
    let mut samples: Vec<(f64, f64)> = (0..walls.len())
        .step_by(step)
        .filter_map(|i| across(&walls, &tree, i, diag).map(|t| (t, walls[i].area)))
        .collect();
    weighted_median(&mut samples)
}

/// The region's boundary triangles with inward normals (dangling patches left out).
fn walls(patches: &[PatchIn], sides: &[FaceUse]) -> Vec<Wall> {
    let both = |p: u32| sides.iter().filter(|f| f.patch == p).count() > 1;
    let mut out = Vec::new();
    for f in sides.iter().filter(|f| !both(f.patch)) {
        let Some(patch) = patches.get(f.patch as usize) else {
            continue;
        };
        let m = &patch.mesh;
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

/// Distance from wall `i`'s centroid along its inward normal to the nearest other wall, looking
/// out to ever longer reaches (so thin layers cost few candidates) up to twice `diag`.
fn across(walls: &[Wall], tree: &RTree<Boxed>, i: usize, diag: f64) -> Option<f64> {
    let w = &walls[i];
    let o = [0, 1, 2].map(|k| (w.corners[0][k] + w.corners[1][k] + w.corners[2][k]) / 3.0);
    let d = w.inward;
    let near = 1e-9 * diag;
    let mut reach = diag / 64.0;
    loop {
        let end = [0, 1, 2].map(|k| o[k] + d[k] * reach);
        let env = AABB::from_corners(min3(o, end), max3(o, end));
        let hit = tree
            .locate_in_envelope_intersecting(env)
            .filter(|b| b.data as usize != i)
            .filter_map(|b| ray_hits(&o, &d, &walls[b.data as usize].corners))
            .filter(|&t| t > near && t <= reach)
            .reduce(f64::min);
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
    use geom::TriMesh;

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
