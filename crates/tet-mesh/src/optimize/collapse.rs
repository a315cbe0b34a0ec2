//! Edge contraction: a free (interior, non-input) node `v` that sits too close to a neighbour
//! `w` — the short edge of a bad tet, typical where the front closed between layers of
//! different sizes — is removed by moving it onto `w`. The tets around the edge `vw` disappear
//! and every other tet of `v`'s ball gets `w` instead of `v`.
//!
//! Validity is decided exactly: the new tets are the cone from `w` over the faces of `v`'s link
//! that do not contain `w`; they tile the old ball exactly once when every one is positive by
//! `orient3d` (the same cone/degree argument as for insertion), so positivity is the whole test.
//! Only faces containing `v` vanish, and `v` is not an input vertex, so no boundary or embedded
//! face is ever touched. A contraction is made only when the worst quality of the new tets beats
//! that of the old ball.

use super::super::complex::Complex;

/// The worst quality must rise by at least this much.
const GAIN: f64 = 1e-6;
/// Balls larger than this are not contracted (keeps each attempt cheap).
const MAX_BALL: usize = 64;

/// Try to contract a free node of the tet in slot `t` onto one of its neighbours (any node it
/// shares a tet with), shortest edge first. True when one was contracted.
pub fn collapse_for(cx: &mut Complex, t: u32) -> bool {
    if !cx.alive[t as usize] {
        return false;
    }
    let tv = cx.tets[t as usize];
    let mut edges: Vec<(f64, u32, u32)> = Vec::new();
    for v in tv {
        if (v as usize) < cx.n_fixed {
            continue;
        }
        let p = cx.nodes[v as usize];
        let mut around: Vec<u32> = cx.node_tets[v as usize]
            .iter()
            .flat_map(|&u| cx.tets[u as usize])
            .filter(|&w| w != v)
            .collect();
        around.sort_unstable();
        around.dedup();
        for w in around {
            let q = cx.nodes[w as usize];
            let l = (0..3).map(|m| (p[m] - q[m]).powi(2)).sum::<f64>();
            edges.push((l, v, w));
        }
    }
    edges.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    edges.into_iter().any(|(_, v, w)| collapse(cx, v, w))
}

/// Contract the free node `v` onto its neighbour `w` if valid and better.
pub fn collapse(cx: &mut Complex, v: u32, w: u32) -> bool {
    if (v as usize) < cx.n_fixed || v == w {
        return false;
    }
    let ball = cx.node_tets[v as usize].clone();
    if ball.len() > MAX_BALL || !ball.iter().any(|&t| cx.tets[t as usize].contains(&w)) {
        return false;
    }
    let mut old = f64::INFINITY;
    let mut new_tets = Vec::with_capacity(ball.len());
    for &t in &ball {
        let tv = cx.tets[t as usize];
        old = old.min(cx.shape[t as usize]);
        if !tv.contains(&w) {
            new_tets.push(tv.map(|x| if x == v { w } else { x }));
        }
    }
    let mut new = f64::INFINITY;
    for &n in &new_tets {
        new = new.min(cx.quality(n));
        if new <= old + GAIN {
            return false;
        }
    }
    if !new_tets.iter().all(|&n| cx.positive(n)) {
        return false;
    }
    for t in ball {
        cx.remove_tet(t);
    }
    for n in new_tets {
        cx.add_tet(n);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An octahedron around a free node, with a second free node crowding it: contracting the
    /// crowding node leaves the eight good tets of the octahedron.
    #[test]
    fn a_free_node_crowding_its_neighbour_is_contracted_and_every_tet_stays_positive() {
        let (mut nodes, mut tets) = test_support::shapes::octahedron_ball([0.0; 3]);
        // Split the tet [2, 0, 4, 6] by a node 7 close to node 6 inside it.
        nodes.push([0.1, 0.1, 0.08]);
        let split = tets.remove(0);
        let [a, b, c, d] = split;
        tets.extend([[7, b, c, d], [a, 7, c, d], [a, b, 7, d], [a, b, c, 7]]);
        let mut cx = Complex::new(nodes, tets.clone(), 6, std::iter::empty());
        assert!(tets.iter().all(|&t| cx.positive(t)));
        let worst = tets.iter().map(|&t| cx.quality(t)).fold(1.0, f64::min);
        // Node 6 is free too (index 6 >= n_fixed), but contracting 7 onto 6 is the better move.
        assert!(collapse(&mut cx, 7, 6));
        let (nodes, tets) = cx.into_parts();
        assert_eq!(tets.len(), 8);
        let cx = Complex::new(nodes, tets.clone(), 6, std::iter::empty());
        assert!(tets.iter().all(|&t| cx.positive(t)));
        assert!(tets.iter().all(|t| !t.contains(&7)));
        let after = tets.iter().map(|&t| cx.quality(t)).fold(1.0, f64::min);
        assert!(after > worst + 0.1, "{worst} -> {after}");
    }

    #[test]
    fn an_input_vertex_is_never_contracted() {
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let mut cx = Complex::new(nodes, vec![[0, 1, 2, 3]], 4, std::iter::empty());
        assert!(!collapse(&mut cx, 0, 1));
        assert!(!collapse_for(&mut cx, 0));
    }
}
