//! The refined mesh laid out in memory along a Hilbert curve (`spatial_layout`), so the
//! optimizer's passes over neighbouring tets touch neighbouring memory. The insertion orders are
//! `geom::spatial_order`'s.

use geom::spatial_order::hilbert_sort;

type P = [f64; 3];

/// Lay a mesh out in memory along a Hilbert curve: the nodes from `n_fixed` on renumbered in
/// Hilbert order (nodes below `n_fixed` keep their ids), then the tets grouped by their highest
/// node (a counting sort, stable). Tets and nodes near in space are then near in memory, which
/// the optimizer's passes over nodes and balls need: a refined triangulation leaves its tets
/// wherever slots were free. The nodes are a sixth as many keys as the tets: sorting the tets by
/// their centroids instead took 4 % of a level's time, and this saved 3.4 % in alternating runs
/// at L3.
pub fn spatial_layout(nodes: &mut Vec<P>, tets: &mut Vec<[u32; 4]>, n_fixed: usize) {
    let n = nodes.len();
    let mut free: Vec<u32> = (n_fixed as u32..n as u32).collect();
    hilbert_sort(&mut free, nodes);
    let mut map: Vec<u32> = (0..n as u32).collect();
    for (k, &v) in free.iter().enumerate() {
        map[v as usize] = (n_fixed + k) as u32;
    }
    let mut moved = vec![[0.0; 3]; n];
    for (v, p) in nodes.iter().enumerate() {
        moved[map[v] as usize] = *p;
    }
    *nodes = moved;
    drop(free);
    let mut start = vec![0u32; n + 1];
    for t in tets.iter_mut() {
        *t = t.map(|v| map[v as usize]);
        start[*t.iter().max().unwrap_or(&0) as usize + 1] += 1;
    }
    drop(map);
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut sorted = vec![[0u32; 4]; tets.len()];
    for t in tets.iter() {
        let top = *t.iter().max().unwrap_or(&0) as usize;
        sorted[start[top] as usize] = *t;
        start[top] += 1;
    }
    *tets = sorted;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_layout_keeps_fixed_nodes_and_every_tet_and_groups_tets_by_their_highest_node() {
        // A 4x4x4 lattice, the first 10 nodes fixed; "tets" of four scattered nodes each.
        let pts: Vec<P> = (0..64)
            .map(|i| {
                [
                    (i % 4) as f64,
                    (i / 4 % 4) as f64,
                    (i / 16) as f64 + 0.1 * i as f64,
                ]
            })
            .collect();
        let tets: Vec<[u32; 4]> = (0..100u32)
            .map(|k| {
                [
                    k % 64,
                    (k * 7 + 3) % 64,
                    (k * 13 + 5) % 64,
                    (k * 29 + 11) % 64,
                ]
            })
            .filter(|t| (0..4).all(|i| (i + 1..4).all(|j| t[i] != t[j])))
            .collect();
        let (mut nodes, mut laid) = (pts.clone(), tets.clone());
        spatial_layout(&mut nodes, &mut laid, 10);
        assert_eq!(nodes[..10], pts[..10], "fixed nodes keep their ids");
        let mut moved: Vec<P> = nodes.clone();
        let mut original: Vec<P> = pts.clone();
        let by_coords = |a: &P, b: &P| a.partial_cmp(b).unwrap();
        moved.sort_by(by_coords);
        original.sort_by(by_coords);
        assert_eq!(moved, original, "the nodes are a permutation");
        // The same tets, as point quadruples in the same vertex order.
        let as_points = |ns: &[P], ts: &[[u32; 4]]| {
            let mut v: Vec<[P; 4]> = ts.iter().map(|t| t.map(|i| ns[i as usize])).collect();
            v.sort_by(|a, b| a.partial_cmp(b).unwrap());
            v
        };
        assert_eq!(as_points(&nodes, &laid), as_points(&pts, &tets));
        let tops: Vec<u32> = laid.iter().map(|t| *t.iter().max().unwrap()).collect();
        assert!(tops.windows(2).all(|w| w[0] <= w[1]), "{tops:?}");
    }
}
