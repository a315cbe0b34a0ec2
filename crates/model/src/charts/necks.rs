//! Necks: where a chart's boundary comes back to within a sliver of itself, the surface mesh of
//! the chart must put a needle across the gap, whatever the sizes.
//!
//! Seams run along support edges, and a curve crosses support edges at whatever angle it takes,
//! so a seam can pass within centimetres of a curve (an original vertex just beside a salt body's
//! contact with a horizon) and cut off a lobe of the chart behind a neck that narrow: on a
//! smoothed salt diapir, a lobe 6 m wide and 28 m long behind a neck of 8 cm gave a surface
//! triangle with c/c* = 244 and tets of 0.55° on both sides of it. A lobe that a seam bounds
//! belongs as well to the chart across that seam, and moved there the neck is gone.
//!
//! Decisions and why:
//! - A neck is an interior edge of a chart whose two ends lie on the chart's boundary and which
//!   cuts the chart in two; the lobe is the smaller side, found by a flood that does not cross
//!   the edge and gives up beyond `MAX_LOBE` triangles (or half the chart), so the work stays
//!   bounded by the boundary's length.
//! - A neck is a sliver when the lobe's boundary (without the neck) is longer than `DETOUR`
//!   (100) times the neck: a needle of about 1° at the neck, which no surface mesh avoids. Wider
//!   necks are left alone: they occur on every curved chart of needle support triangles, and
//!   moving those lobes made the receiving charts fold in the projection.
//! - The lobe moves only when a seam bounds it (a lobe bounded by the patch's curves alone is the
//!   model's own shape) and each of its triangles faces within the chart angle of the receiving
//!   chart's mean normal, so that chart still flattens. It goes to the chart with which it shares
//!   the longest seam (the lowest on ties). Triangles and edges are visited in index order, so
//!   the result is the same on every machine.

use super::{NONE, across_edges, add, area, edge_length};
use geom::TriMesh;
use geom::predicates::dot;

/// The most triangles a lobe may have.
const MAX_LOBE: usize = 256;
/// A neck is a sliver when the lobe's boundary is longer than this many times the neck: an
/// angle of about 1° across it. Ordinary lobes of charts on curved supports reach 36 (a closed
/// lens's rim of needle support triangles, where moving them folded the receiving chart); the
/// salt diapir's sliver was 817.
const DETOUR: f64 = 100.0;
/// Most rounds: each moves the lobes it finds.
const ROUNDS: usize = 8;

/// Moves every lobe behind a narrow neck to the chart across its seam (see the module doc);
/// `group` is the chart of each of `mesh`'s triangles, `normals` their unit (or zero) normals.
/// Returns how many lobes moved.
pub fn widen_necks(mesh: &TriMesh, normals: &[[f64; 3]], max_deg: f64, group: &mut [u32]) -> usize {
    let across = across_edges(mesh);
    let cos_max = max_deg.to_radians().cos();
    let groups = group.iter().map(|&g| g as usize + 1).max().unwrap_or(0);
    let mut mean = vec![[0.0; 3]; groups];
    for (t, n) in normals.iter().enumerate() {
        add(&mut mean[group[t] as usize], n, area(mesh, t));
    }
    let mut stamp = Stamps(vec![0; mesh.triangles.len()], 0);
    let mut moved = 0;
    for _ in 0..ROUNDS {
        let before = moved;
        let size = sizes(group, groups);
        let rim = rim_vertices(mesh, &across, group);
        for t in 0..mesh.triangles.len() as u32 {
            for k in 0..3 {
                let u = across[t as usize][k];
                let tri = mesh.triangles[t as usize];
                if u == NONE
                    || u < t
                    || group[u as usize] != group[t as usize]
                    || !rim[tri[k] as usize]
                    || !rim[tri[(k + 1) % 3] as usize]
                {
                    continue;
                }
                let g = group[t as usize];
                let budget = MAX_LOBE.min(size[g as usize] / 2);
                let Some(lobe) = lobe_behind(mesh, &across, group, (t, k), budget, &mut stamp)
                else {
                    continue;
                };
                let Some(to) = receiver(mesh, &across, group, &lobe, edge_length(mesh, t, k))
                else {
                    continue;
                };
                if !faces(normals, &mean[to as usize], &lobe, cos_max) {
                    continue;
                }
                for &s in &lobe {
                    let (n, a) = (&normals[s as usize], area(mesh, s as usize));
                    add(&mut mean[group[s as usize] as usize], n, -a);
                    add(&mut mean[to as usize], n, a);
                    group[s as usize] = to;
                }
                moved += 1;
            }
        }
        if moved == before {
            break;
        }
    }
    moved
}

/// Whether each triangle of `lobe` faces within the angle of `cos_max` of the direction of
/// `mean` (a zero normal faces any way; a zero mean, no way).
fn faces(normals: &[[f64; 3]], mean: &[f64; 3], lobe: &[u32], cos_max: f64) -> bool {
    let len = dot(mean, mean).sqrt();
    len > 0.0
        && lobe.iter().all(|&s| {
            let n = &normals[s as usize];
            *n == [0.0; 3] || dot(n, mean) >= cos_max * len
        })
}

/// Marks of visited triangles: a triangle is marked when its entry equals the current round.
struct Stamps(Vec<u32>, u32);

impl Stamps {
    /// Starts a new round: nothing marked.
    fn clear(&mut self) {
        self.1 += 1;
    }
    /// Marks `t`; returns whether it was unmarked.
    fn mark(&mut self, t: u32) -> bool {
        let fresh = self.0[t as usize] != self.1;
        self.0[t as usize] = self.1;
        fresh
    }
}

/// Whether each vertex ends an edge that bounds a chart: a border edge or a seam.
fn rim_vertices(mesh: &TriMesh, across: &[[u32; 3]], group: &[u32]) -> Vec<bool> {
    let mut rim = vec![false; mesh.vertices.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let u = across[t][k];
            if u == NONE || group[u as usize] != group[t] {
                rim[tri[k] as usize] = true;
                rim[tri[(k + 1) % 3] as usize] = true;
            }
        }
    }
    rim
}

/// Triangles per group.
fn sizes(group: &[u32], groups: usize) -> Vec<usize> {
    let mut size = vec![0; groups];
    for &g in group {
        size[g as usize] += 1;
    }
    size
}

/// The smaller side of the chart of `t` cut along `t`'s edge `k`, when the edge cuts it in two
/// and that side has at most `budget` triangles: ascending.
fn lobe_behind(
    mesh: &TriMesh,
    across: &[[u32; 3]],
    group: &[u32],
    (t, k): (u32, usize),
    budget: usize,
    stamp: &mut Stamps,
) -> Option<Vec<u32>> {
    let u = across[t as usize][k];
    let (a, b) = (
        mesh.triangles[t as usize][k],
        mesh.triangles[t as usize][(k + 1) % 3],
    );
    let neck = |s: u32, j: usize| {
        let tri = mesh.triangles[s as usize];
        let (p, q) = (tri[j], tri[(j + 1) % 3]);
        (p == a && q == b) || (p == b && q == a)
    };
    for (from, other) in [(t, u), (u, t)] {
        stamp.clear();
        stamp.mark(from);
        let mut seen = vec![from];
        let mut k = 0;
        let mut cut = true;
        while k < seen.len() && seen.len() <= budget {
            let s = seen[k];
            k += 1;
            for (j, &n) in across[s as usize].iter().enumerate() {
                if n == NONE || group[n as usize] != group[s as usize] || neck(s, j) {
                    continue;
                }
                if n == other {
                    cut = false;
                }
                if stamp.mark(n) {
                    seen.push(n);
                }
            }
            if !cut {
                break;
            }
        }
        if !cut {
            return None;
        }
        if seen.len() <= budget && k == seen.len() {
            seen.sort_unstable();
            return Some(seen);
        }
    }
    None
}

/// The chart a lobe should join: the one sharing the longest seam with it, when a seam bounds it
/// and its boundary (without the neck, of length `neck`) is longer than [`DETOUR`] times the
/// neck.
fn receiver(
    mesh: &TriMesh,
    across: &[[u32; 3]],
    group: &[u32],
    lobe: &[u32],
    neck: f64,
) -> Option<u32> {
    let g = group[lobe[0] as usize];
    let mut rim = 0.0;
    let mut seams: Vec<(u32, f64)> = Vec::new();
    for &s in lobe {
        for (j, &n) in across[s as usize].iter().enumerate() {
            if n != NONE && lobe.binary_search(&n).is_ok() {
                continue;
            }
            let len = edge_length(mesh, s, j);
            if n != NONE && group[n as usize] == g {
                continue; // the neck
            }
            rim += len;
            if n != NONE {
                match seams.iter_mut().find(|(h, _)| *h == group[n as usize]) {
                    Some(e) => e.1 += len,
                    None => seams.push((group[n as usize], len)),
                }
            }
        }
    }
    if rim <= DETOUR * neck {
        return None;
    }
    seams
        .into_iter()
        .max_by(|x, y| x.1.total_cmp(&y.1).then(y.0.cmp(&x.0)))
        .map(|(h, _)| h)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chart (group 0) whose first triangle is a lobe 5 long behind the neck 0–1 of width
    /// `neck`; four triangles of the chart lie on the other side of the neck, and the lobe's edge
    /// 1–2 is a seam with triangle 6, in group 1, as triangle 5 is.
    fn lobe(neck: f64) -> (TriMesh, Vec<u32>) {
        let m = TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [neck, 0.0, 0.0],
                [0.5 * neck, 5.0, 0.0],
                [5.0, 2.5, 0.0],
                [0.5 * neck, -neck, 0.0],
                [0.0, -5.0, 0.0],
                [5.0, -5.0, 0.0],
            ],
            vec![
                [0, 1, 2],
                [1, 0, 4],
                [0, 5, 4],
                [4, 5, 6],
                [1, 4, 6],
                [1, 6, 3],
                [1, 3, 2],
            ],
        );
        (m, vec![0, 0, 0, 0, 0, 1, 1])
    }

    const UP: [[f64; 3]; 7] = [[0.0, 0.0, 1.0]; 7];

    #[test]
    fn a_lobe_behind_a_sliver_of_a_neck_joins_the_chart_across_its_seam() {
        let (m, mut group) = lobe(0.01);
        assert_eq!(widen_necks(&m, &UP, 60.0, &mut group), 1);
        assert_eq!(group, vec![1, 0, 0, 0, 0, 1, 1]);
    }

    #[test]
    fn a_neck_wider_than_a_sliver_is_kept_even_when_the_lobe_is_a_needle() {
        // The lobe's rim is 20 times its neck: a needle of 6°, but not a sliver.
        let (m, mut group) = lobe(0.5);
        assert_eq!(widen_necks(&m, &UP, 60.0, &mut group), 0);
        assert_eq!(group, vec![0, 0, 0, 0, 0, 1, 1]);
    }

    #[test]
    fn a_lobe_bounded_by_the_patch_border_alone_is_the_models_shape_and_stays() {
        let (mut m, _) = lobe(0.01);
        m.triangles.truncate(5);
        let mut group = vec![0; 5];
        assert_eq!(widen_necks(&m, &UP[..5], 60.0, &mut group), 0);
        assert_eq!(group, vec![0; 5]);
    }

    #[test]
    fn a_lobe_facing_away_from_the_chart_across_its_seam_stays() {
        let (m, mut group) = lobe(0.01);
        let mut normals = UP;
        normals[0] = [1.0, 0.0, 0.0];
        assert_eq!(widen_necks(&m, &normals, 60.0, &mut group), 0);
        assert_eq!(group, vec![0, 0, 0, 0, 0, 1, 1]);
    }
}
