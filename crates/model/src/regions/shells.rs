//! From linked triangle face-uses to patch face-uses and shells, and the free-border report.
//!
//! Every triangle of a patch must put its front in one shell and its back in one shell (maybe the
//! same: a dangling patch); otherwise the patch is not consistently oriented or another surface
//! crosses it without a curve, and that is reported. Free border edges of a surface that may not
//! dangle are reported as the polyline where the surface stops short.

use super::radial::{Links, fu};
use super::weld::{P3, Soup, fmt_point};
use super::{FaceUse, PatchIn, RegionError, RegionOptions, Side};
use std::collections::BTreeMap;

pub(super) struct Shells {
    /// `shell_of[p] = [shell of the front, shell of the back]`.
    pub shell_of: Vec<[u32; 2]>,
    /// Face-uses of each shell, sorted.
    pub shells: Vec<Vec<FaceUse>>,
}

impl Shells {
    pub fn build(
        soup: &Soup,
        patches: &[PatchIn],
        mut links: Links,
    ) -> Result<Shells, RegionError> {
        let mut root_shell: BTreeMap<usize, u32> = BTreeMap::new();
        let mut shell_of = Vec::with_capacity(patches.len());
        let mut shells: Vec<Vec<FaceUse>> = Vec::new();
        for (p, patch) in patches.iter().enumerate() {
            let range = soup.patch_tris(p);
            let mut pair = [0u32; 2];
            for (si, side) in [Side::Front, Side::Back].into_iter().enumerate() {
                let front = side == Side::Front;
                let root = links.uf.find(fu(range.start, front));
                for t in range.clone() {
                    if links.uf.find(fu(t, front)) != root {
                        return Err(split_patch(soup, patch, range.clone(), t));
                    }
                }
                let next = shells.len() as u32;
                let s = *root_shell.entry(root).or_insert_with(|| {
                    shells.push(Vec::new());
                    next
                });
                shells[s as usize].push(FaceUse {
                    patch: p as u32,
                    side,
                });
                pair[si] = s;
            }
            shell_of.push(pair);
        }
        Ok(Shells { shell_of, shells })
    }

    /// Whether both sides of patch `p` lie in one shell.
    pub fn is_dangling(&self, p: usize) -> bool {
        self.shell_of[p][0] == self.shell_of[p][1]
    }
}

/// Why a patch's triangles do not put one side in one shell: a pair of triangles traversing an
/// edge the same way (inconsistent orientation), or else a crossing or a disconnection.
fn split_patch(
    soup: &Soup,
    patch: &PatchIn,
    range: std::ops::Range<usize>,
    t: usize,
) -> RegionError {
    let mut directed: Vec<(u32, u32, usize)> = Vec::new();
    for u in range {
        let tri = soup.tris[u];
        for k in 0..3 {
            directed.push((tri[k], tri[(k + 1) % 3], u));
        }
    }
    directed.sort_unstable();
    if let Some(w) = directed
        .windows(2)
        .find(|w| w[0].0 == w[1].0 && w[0].1 == w[1].1)
    {
        let (a, b) = (soup.points[w[0].0 as usize], soup.points[w[0].1 as usize]);
        return RegionError::new(
            format!(
                "patch `{}` of surface `{}` is not consistently oriented: two of its triangles run along the edge \
                 from {} to {} in the same direction",
                patch.name,
                patch.surface,
                fmt_point(&a),
                fmt_point(&b)
            ),
            Some(&patch.surface),
            Some(a),
        );
    }
    let at = soup.corners(t)[0];
    RegionError::new(
        format!(
            "patch `{}` of surface `{}` does not bound one volume per side near {}: it is not connected, or \
             another surface crosses it without a shared curve",
            patch.name,
            patch.surface,
            fmt_point(&at)
        ),
        Some(&patch.surface),
        Some(at),
    )
}

/// Reports the free borders of surfaces that may not dangle (sorted by surface name).
pub(super) fn check_free_borders(
    soup: &Soup,
    patches: &[PatchIn],
    free_edges: &[(u32, u32, u32)],
    opts: &RegionOptions,
) -> Result<(), RegionError> {
    let mut by_surface: BTreeMap<&str, Vec<(u32, u32)>> = BTreeMap::new();
    for &(u, v, t) in free_edges {
        let surface = patches[soup.tri_patch[t as usize] as usize]
            .surface
            .as_str();
        if !opts.may_dangle(surface) {
            by_surface.entry(surface).or_default().push((u, v));
        }
    }
    let Some((surface, edges)) = by_surface.into_iter().next() else {
        return Ok(());
    };
    let chains = chain(soup, &edges);
    let first = &chains[0];
    let (a, b) = (
        soup.points[first[0] as usize],
        soup.points[first[first.len() - 1] as usize],
    );
    let more = if chains.len() > 1 {
        format!(" ({} more free border pieces)", chains.len() - 1)
    } else {
        String::new()
    };
    let what = if first.len() > 2 && first[0] == first[first.len() - 1] {
        format!("a free border loop through {}", fmt_point(&a))
    } else {
        format!("free border from {} to {}", fmt_point(&a), fmt_point(&b))
    };
    let cause = if first.len() > 2 && first[0] == first[first.len() - 1] {
        "a hole in the surface, or a piece of it that ends inside the model, lets the volumes on \
         its two sides meet; close the hole in the data (or let the surface that fills it cut \
         this one), or, where it ends inside a region on purpose as a fault does, give it \
         `kind = \"fault\"`"
    } else {
        "it ends short of the box or of the surface it should end on, so the volumes on its two \
         sides meet past its border; extend it there in the data (the intersection trims what \
         reaches past), or, where it ends inside a region on purpose as a fault does, give it \
         `kind = \"fault\"`"
    };
    Err(RegionError::new(
        format!("surface `{surface}` stops short: {what} does not close any region{more}: {cause}"),
        Some(surface),
        Some(a),
    ))
}

fn lex(a: &P3, b: &P3) -> std::cmp::Ordering {
    a[0].total_cmp(&b[0])
        .then(a[1].total_cmp(&b[1]))
        .then(a[2].total_cmp(&b[2]))
}

/// Chains edges into polylines (vertex lists), each started at its lexicographically smallest
/// end (or smallest vertex for a loop); chains in order of their start.
fn chain(soup: &Soup, edges: &[(u32, u32)]) -> Vec<Vec<u32>> {
    let mut adj: BTreeMap<u32, Vec<(u32, usize)>> = BTreeMap::new();
    for (e, &(u, v)) in edges.iter().enumerate() {
        adj.entry(u).or_default().push((v, e));
        adj.entry(v).or_default().push((u, e));
    }
    let mut used = vec![false; edges.len()];
    let mut starts: Vec<u32> = adj.keys().copied().collect();
    let pt = |v: u32| soup.points[v as usize];
    // Ends (odd degree) first, then the rest, each group by coordinates.
    starts.sort_by(|&a, &b| {
        let (da, db) = (
            adj[&a].len().is_multiple_of(2),
            adj[&b].len().is_multiple_of(2),
        );
        da.cmp(&db).then_with(|| lex(&pt(a), &pt(b)))
    });
    let mut chains = Vec::new();
    for s in starts {
        let mut cur = s;
        let mut line = vec![s];
        while let Some(&(next, e)) = adj[&cur].iter().find(|(_, e)| !used[*e]) {
            used[e] = true;
            line.push(next);
            cur = next;
        }
        if line.len() > 1 {
            chains.push(line);
        }
    }
    chains.sort_by(|a, b| lex(&pt(a[0]), &pt(b[0])));
    chains
}
