//! Exact point location in a [`RegionModel`]: which region strictly contains a point.
//!
//! A point is in a region when ray-casting parity puts it inside the outer shell's one-sided
//! patches and outside every cavity's, and it lies on none of the region's patches (dangling
//! ones included). The triangles are gathered once, so many points can be located cheaply.

use super::exact::{
    Loc, Tri, in_coplanar_triangle, may_meet, one_sided, parity, patch_tris, patches_bbox,
};
use super::{PatchIn, Region, RegionModel};
use geom::{BBox, Orientation, orient3d};

struct RegionTris {
    all: Vec<Tri>,
    all_box: BBox,
    outer: Vec<Tri>,
    cavities: Vec<Vec<Tri>>,
}

/// A model's regions with their triangles gathered, for repeated exact point location.
pub struct Locator {
    regions: Vec<RegionTris>,
    bbox: BBox,
}

impl Locator {
    /// `patches` must be the slice the model was found from (indices out of range are ignored).
    pub fn new(model: &RegionModel, patches: &[PatchIn]) -> Locator {
        Locator::from_regions(&model.regions, patches)
    }

    pub(super) fn from_regions(regions: &[Region], patches: &[PatchIn]) -> Locator {
        let regions = regions
            .iter()
            .map(|r| {
                let mut ids: Vec<u32> = r.sides.iter().map(|f| f.patch).collect();
                ids.sort_unstable();
                ids.dedup();
                let all = patch_tris(patches, ids);
                let all_box = BBox::from_points(all.iter().flatten());
                RegionTris {
                    all,
                    all_box,
                    outer: patch_tris(patches, one_sided(&r.outer.face_uses)),
                    cavities: r
                        .cavities
                        .iter()
                        .map(|c| patch_tris(patches, one_sided(&c.face_uses)))
                        .collect(),
                }
            })
            .collect();
        Locator {
            regions,
            bbox: patches_bbox(patches),
        }
    }

    /// Whether `p` is strictly inside region `i`; `None` when no non-degenerate ray was found.
    pub fn contains(&self, i: usize, p: [f64; 3]) -> Option<bool> {
        let r = self.regions.get(i)?;
        if p.iter().any(|c| !c.is_finite()) {
            return Some(false);
        }
        let at = BBox { min: p, max: p };
        if r.all_box.contains(&p)
            && r.all.iter().any(|t| {
                may_meet(&at, t)
                    && orient3d(&t[0], &t[1], &t[2], &p) == Orientation::Zero
                    && in_coplanar_triangle(&p, t)
            })
        {
            return Some(false);
        }
        if parity(&p, &r.outer, &self.bbox)? != Loc::Inside {
            return Some(false);
        }
        for c in &r.cavities {
            if parity(&p, c, &self.bbox)? != Loc::Outside {
                return Some(false);
            }
        }
        Some(true)
    }

    /// The index of the region strictly containing `p`, `None` outside every region or on a
    /// patch bounding or dangling in the region.
    pub fn locate(&self, p: [f64; 3]) -> Option<usize> {
        (0..self.regions.len()).find(|&i| self.contains(i, p) == Some(true))
    }
}
