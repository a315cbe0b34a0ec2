//! Self-intersection search: `geom::broad_phase` proposes the pairs of triangles whose boxes
//! overlap and `geom::contact` decides each exactly, by the canonical vertices the two share
//! (coincident vertices are one vertex here, so triangles meeting at a duplicated vertex touch
//! properly). The pairs come back sorted, so the findings do not depend on the thread count.

use super::checks::TriStatus;
use geom::BBox;
use geom::broad_phase::overlapping_pairs;
use geom::contact::{Contact, Tri, triangle_contact};

/// How two `Ok` triangles meet, by the canonical vertices they share. A vertex `u` shares with
/// `t` is taken at `t`'s position (the two may differ by up to the merge distance), so the two
/// agree on where the shared vertex is.
pub fn judge(v: &[[f64; 3]], canon: &[u32], t: &[u32; 3], u: &[u32; 3]) -> Contact {
    let ct = t.map(|i| canon[i as usize]);
    let cu = u.map(|i| canon[i as usize]);
    let tp = t.map(|i| &v[i as usize]);
    let up = [0, 1, 2].map(|j| match ct.iter().position(|&c| c == cu[j]) {
        Some(i) => tp[i],
        None => &v[u[j] as usize],
    });
    triangle_contact(&Tri { ids: ct, pts: tp }, &Tri { ids: cu, pts: up })
}

/// All intersecting pairs `(t, u, contact)` of `Ok` triangles with `t < u`, sorted.
pub fn find(
    v: &[[f64; 3]],
    tris: &[[u32; 3]],
    canon: &[u32],
    status: &[TriStatus],
) -> Vec<(u32, u32, Contact)> {
    let ok: Vec<u32> = (0..tris.len() as u32)
        .filter(|&t| status[t as usize] == TriStatus::Ok)
        .collect();
    let boxes: Vec<BBox> = (ok.iter())
        .map(|&t| BBox::from_points(tris[t as usize].map(|i| &v[i as usize])))
        .collect();
    let found = overlapping_pairs(&boxes, |i, j| {
        let (t, u) = (
            &tris[ok[i as usize] as usize],
            &tris[ok[j as usize] as usize],
        );
        let c = judge(v, canon, t, u);
        (c != Contact::None).then_some(c)
    });
    // `ok` is increasing, so the pairs stay sorted.
    (found.into_iter())
        .map(|(i, j, c)| (ok[i as usize], ok[j as usize], c))
        .collect()
}
