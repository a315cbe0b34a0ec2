//! Quality optimization after the front closes: smoothing of interior nodes. Each move is
//! accepted only when every tetrahedron around the node stays positive (exact `orient3d`) and the
//! worst mean ratio of the ball improves, so optimization can never invert or flatten a tet.
//! Nodes are visited in index order (Gauss-Seidel), single-threaded: the result is deterministic.

use crate::geom::predicates::{Orientation, orient3d};

use super::quality::mean_ratio;

type P = [f64; 3];

const PASSES: usize = 3;

pub fn optimize(nodes: &mut [P], tets: &mut [[u32; 4]], n_input: usize) {
    let mut ball: Vec<Vec<u32>> = vec![Vec::new(); nodes.len()];
    for (i, t) in tets.iter().enumerate() {
        for &v in t {
            ball[v as usize].push(i as u32);
        }
    }
    for _ in 0..PASSES {
        for (v, b) in ball.iter().enumerate().skip(n_input) {
            if b.is_empty() {
                continue;
            }
            smooth_node(v, b, nodes, tets);
        }
    }
}

fn worst(v: usize, p: &P, ball: &[u32], nodes: &[P], tets: &[[u32; 4]]) -> Option<f64> {
    let mut w = f64::INFINITY;
    for &t in ball {
        let q = tets[t as usize].map(|i| {
            if i as usize == v {
                *p
            } else {
                nodes[i as usize]
            }
        });
        if orient3d(&q[0], &q[1], &q[2], &q[3]) != Orientation::Positive {
            return None;
        }
        w = w.min(mean_ratio(&q[0], &q[1], &q[2], &q[3]));
    }
    Some(w)
}

fn smooth_node(v: usize, ball: &[u32], nodes: &mut [P], tets: &[[u32; 4]]) {
    let cur = nodes[v];
    let Some(q0) = worst(v, &cur, ball, nodes, tets) else {
        return;
    };
    // Target: mean of the centroids of the ball's tets weighted towards the node's neighbours.
    let mut sum = [0.0; 3];
    let mut n = 0.0;
    for &t in ball {
        for &w in &tets[t as usize] {
            if w as usize != v {
                let p = nodes[w as usize];
                for k in 0..3 {
                    sum[k] += p[k];
                }
                n += 1.0;
            }
        }
    }
    let target = [sum[0] / n, sum[1] / n, sum[2] / n];
    for step in [1.0, 0.5, 0.25] {
        let p = [
            cur[0] + (target[0] - cur[0]) * step,
            cur[1] + (target[1] - cur[1]) * step,
            cur[2] + (target[2] - cur[2]) * step,
        ];
        if let Some(q) = worst(v, &p, ball, nodes, tets)
            && q > q0
        {
            nodes[v] = p;
            return;
        }
    }
}
