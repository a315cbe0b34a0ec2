//! Support re-triangulation: the same mesher regenerates an imported surface's triangulation at a
//! given size before intersection, preserving its shape (the new nodes lie on the old support)
//! and its borders (border vertices where the border turns by more than
//! `Tolerances::kink_angle_deg` are kept bit for bit; the border between them is resampled at
//! about `size` by arc length, on the old border edges). It meshes one piece that flattens, as
//! any patch; `model::remesh` cuts a surface of any shape (closed, a tube, creased, of several
//! TFACEs) into such pieces first.

use super::{PatchInput, SurfaceMeshError, SurfaceSize, dist, mesh_patch, param};
use geom::predicates::{dot, sub};
use geom::{Tolerances, TriMesh};

/// Regenerates a support triangulation at `size`, preserving its shape and borders: border
/// vertices where the border turns by more than `Tolerances::kink_angle_deg` are kept bit for bit,
/// the border between them is resampled at about `size` (new border nodes lie on the old border
/// edges), and the inside is meshed by `mesh_patch` on the old support.
pub fn retriangulate(support: &TriMesh, size: f64) -> Result<TriMesh, SurfaceMeshError> {
    retriangulate_keeping(support, size, &[], Tolerances::default().kink_angle_deg)
}

/// [`retriangulate`], keeping the support vertices `keep` (a file's corner marks) bit for bit
/// too: on the border as corners, inside as fixed nodes; a border turn above `kink_angle_deg`
/// (the recipe's `Tolerances::kink_angle_deg`) is a corner.
pub fn retriangulate_keeping(
    support: &TriMesh,
    size: f64,
    keep: &[u32],
    kink_angle_deg: f64,
) -> Result<TriMesh, SurfaceMeshError> {
    let name = "support retriangulation".to_string();
    let fail = |message: String, at: Option<[f64; 3]>| SurfaceMeshError {
        patch: name.clone(),
        message,
        at,
    };
    if !(size > 0.0 && size.is_finite()) {
        return Err(fail(format!("invalid size {size}"), None));
    }
    let loops = param::border_loops(support).map_err(|e| fail(e.message, e.at))?;
    let kink = kink_angle_deg.to_radians().cos();
    let mut keep: Vec<u32> = keep.to_vec();
    keep.sort_unstable();
    keep.dedup();
    let mut out_loops = Vec::new();
    for l in &loops {
        let pts: Vec<[f64; 3]> = l.iter().map(|&v| support.vertices[v as usize]).collect();
        let kept: Vec<bool> = l.iter().map(|v| keep.binary_search(v).is_ok()).collect();
        out_loops.push(resample_loop(&pts, &kept, size, kink));
    }
    let on_border: std::collections::BTreeSet<u32> = loops.iter().flatten().copied().collect();
    let points = (keep.iter())
        .filter(|v| !on_border.contains(v))
        .filter_map(|&v| support.vertices.get(v as usize).copied())
        .collect();
    let input = PatchInput {
        name: name.clone(),
        support: support.clone(),
        loops: out_loops,
        constraints: vec![],
        points,
        facets: Vec::new(),
    };
    let out = mesh_patch(
        &input,
        &SurfaceSize {
            size,
            min_size: 0.0,
            max_size: size,
            growth: 1.3,
        },
    )?;
    Ok(TriMesh::new(out.nodes, out.triangles))
}

/// Keeps the corners (turn cosine below `kink_cos`, or `kept`) of a closed border polyline and
/// resamples the pieces between them at about `size` by arc length.
fn resample_loop(pts: &[[f64; 3]], kept: &[bool], size: f64, kink_cos: f64) -> Vec<[f64; 3]> {
    let n = pts.len();
    let mut corners: Vec<usize> = (0..n)
        .filter(|&i| {
            if kept[i] {
                return true;
            }
            let a = sub(&pts[i], &pts[(i + n - 1) % n]);
            let b = sub(&pts[(i + 1) % n], &pts[i]);
            let la = dot(&a, &a).sqrt();
            let lb = dot(&b, &b).sqrt();
            la > 0.0 && lb > 0.0 && dot(&a, &b) / (la * lb) < kink_cos
        })
        .collect();
    if corners.is_empty() {
        corners.push(0);
    }
    let mut out = Vec::new();
    for (k, &c0) in corners.iter().enumerate() {
        let c1 = corners[(k + 1) % corners.len()];
        // The piece c0 -> c1 (wrapping; the whole loop when there is one corner).
        let mut piece = vec![pts[c0]];
        let mut i = c0;
        loop {
            i = (i + 1) % n;
            piece.push(pts[i]);
            if i == c1 {
                break;
            }
        }
        let mut cum = vec![0.0];
        for w in piece.windows(2) {
            let l = dist(&w[0], &w[1]);
            cum.push(cum[cum.len() - 1] + l);
        }
        let len = cum[cum.len() - 1];
        let min_seg = if corners.len() == 1 { 3 } else { 1 };
        let segs = ((len / size).round() as usize).max(min_seg);
        out.push(pts[c0]);
        let mut j = 0;
        for s in 1..segs {
            let target = len * s as f64 / segs as f64;
            while j + 2 < cum.len() && cum[j + 1] < target {
                j += 1;
            }
            let span = cum[j + 1] - cum[j];
            let u = if span > 0.0 {
                ((target - cum[j]) / span).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (a, b) = (piece[j], piece[j + 1]);
            out.push([
                a[0] + u * (b[0] - a[0]),
                a[1] + u * (b[1] - a[1]),
                a[2] + u * (b[2] - a[2]),
            ]);
        }
    }
    out
}
