//! One triangle soup for all patches: vertices welded by exact coordinates (bit patterns, with
//! -0.0 and 0.0 the same point), triangles checked for indices in range, finite coordinates and
//! non-zero area (exactly), each remembering its patch.

use super::{PatchIn, RegionError};
use geom::{Orientation, orient2d};
use std::collections::BTreeMap;

pub(super) type P3 = [f64; 3];

pub(super) struct Soup {
    pub points: Vec<P3>,
    /// Welded corner indices.
    pub tris: Vec<[u32; 3]>,
    pub tri_patch: Vec<u32>,
    /// Triangles of patch `p` are `patch_start[p]..patch_start[p + 1]`.
    pub patch_start: Vec<usize>,
}

fn key(p: &P3) -> [u64; 3] {
    // Adding 0.0 turns -0.0 into 0.0 so that both weld to one vertex.
    [
        (p[0] + 0.0).to_bits(),
        (p[1] + 0.0).to_bits(),
        (p[2] + 0.0).to_bits(),
    ]
}

/// Whether three points are collinear (exact): every coordinate projection is degenerate.
pub(super) fn collinear(a: &P3, b: &P3, c: &P3) -> bool {
    (0..3).all(|k| {
        orient2d(&drop_axis(a, k), &drop_axis(b, k), &drop_axis(c, k)) == Orientation::Zero
    })
}

/// The point projected along axis `k` onto the other two coordinates.
pub(super) fn drop_axis(p: &P3, k: usize) -> [f64; 2] {
    match k {
        0 => [p[1], p[2]],
        1 => [p[0], p[2]],
        _ => [p[0], p[1]],
    }
}

pub(super) fn fmt_point(p: &P3) -> String {
    format!("({}, {}, {})", p[0], p[1], p[2])
}

/// The welded id of every vertex of every patch, in patch then vertex order: vertices with the
/// same [`key`] share an id, and ids are numbered in order of first appearance (a sort instead
/// of a map: the same result, faster on large models).
fn weld_ids(patches: &[PatchIn]) -> Vec<u32> {
    let mut all: Vec<([u64; 3], u32)> = Vec::new();
    for p in patches {
        for v in &p.mesh.vertices {
            all.push((key(v), all.len() as u32));
        }
    }
    all.sort_unstable();
    // The first appearance of each point, for every vertex.
    let mut rep = vec![0u32; all.len()];
    for run in all.chunk_by(|a, b| a.0 == b.0) {
        for x in run {
            rep[x.1 as usize] = run[0].1;
        }
    }
    let mut ids = vec![0u32; rep.len()];
    let mut next = 0u32;
    for g in 0..rep.len() {
        if rep[g] as usize == g {
            ids[g] = next;
            next += 1;
        } else {
            ids[g] = ids[rep[g] as usize];
        }
    }
    ids
}

impl Soup {
    pub fn build(patches: &[PatchIn]) -> Result<Soup, RegionError> {
        let mut seen_names: BTreeMap<&str, usize> = BTreeMap::new();
        let ids = weld_ids(patches);
        let mut global = 0usize;
        let mut soup = Soup {
            points: Vec::new(),
            tris: Vec::new(),
            tri_patch: Vec::new(),
            patch_start: vec![0],
        };
        if u32::try_from(patches.len()).is_err() {
            return Err(RegionError::new(
                "too many patches (more than 2^32)",
                None,
                None,
            ));
        }
        for (pi, patch) in patches.iter().enumerate() {
            let sname = Some(patch.surface.as_str());
            if let Some(prev) = seen_names.insert(&patch.name, pi) {
                return Err(RegionError::new(
                    format!(
                        "patches {prev} and {pi} are both named `{}`; patch names must be unique",
                        patch.name
                    ),
                    sname,
                    None,
                ));
            }
            if patch.mesh.triangles.is_empty() {
                return Err(RegionError::new(
                    format!(
                        "patch `{}` of surface `{}` has no triangles",
                        patch.name, patch.surface
                    ),
                    sname,
                    None,
                ));
            }
            let mut local: Vec<u32> = Vec::with_capacity(patch.mesh.vertices.len());
            for p in &patch.mesh.vertices {
                if p.iter().any(|c| !c.is_finite()) {
                    return Err(RegionError::new(
                        format!(
                            "patch `{}` of surface `{}` has a non-finite vertex {}",
                            patch.name,
                            patch.surface,
                            fmt_point(p)
                        ),
                        sname,
                        None,
                    ));
                }
                let id = ids[global];
                global += 1;
                if id as usize == soup.points.len() {
                    soup.points.push(*p);
                }
                local.push(id);
            }
            for (ti, t) in patch.mesh.triangles.iter().enumerate() {
                let mut w = [0u32; 3];
                for k in 0..3 {
                    w[k] = *local.get(t[k] as usize).ok_or_else(|| {
                        RegionError::new(
                            format!(
                                "patch `{}` of surface `{}`: triangle {ti} points to vertex {} but the patch has {} vertices",
                                patch.name,
                                patch.surface,
                                t[k],
                                local.len()
                            ),
                            sname,
                            None,
                        )
                    })?;
                }
                let [a, b, c] = w.map(|i| soup.points[i as usize]);
                if w[0] == w[1] || w[1] == w[2] || w[0] == w[2] || collinear(&a, &b, &c) {
                    return Err(RegionError::new(
                        format!(
                            "patch `{}` of surface `{}`: triangle {ti} {} {} {} has zero area",
                            patch.name,
                            patch.surface,
                            fmt_point(&a),
                            fmt_point(&b),
                            fmt_point(&c)
                        ),
                        sname,
                        Some(a),
                    ));
                }
                soup.tris.push(w);
                soup.tri_patch.push(pi as u32);
            }
            soup.patch_start.push(soup.tris.len());
        }
        if u32::try_from(soup.tris.len() * 2).is_err() {
            return Err(RegionError::new(
                "too many triangles (more than 2^31)",
                None,
                None,
            ));
        }
        Ok(soup)
    }

    pub fn corners(&self, t: usize) -> [P3; 3] {
        self.tris[t].map(|i| self.points[i as usize])
    }

    pub fn patch_tris(&self, p: usize) -> std::ops::Range<usize> {
        self.patch_start[p]..self.patch_start[p + 1]
    }
}
