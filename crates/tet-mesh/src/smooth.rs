//! Optimization-based smoothing of one free node: maximise the worst mean ratio of the tets
//! around it. The objective is non-smooth (a minimum), so each step climbs the gradient of the
//! worst tet (or of the near-worst ones together) with a backtracking line search, after a first
//! try towards the centroid of the node's neighbours. A move is accepted only when every tet of
//! the ball stays positive by the exact `orient3d` and the worst quality strictly rises.

use geom::predicates::{Orientation, orient3d};

use super::complex::{Complex, P};
use super::quality::{mean_ratio, shape, shape_and_mean_ratio};

/// Gradient steps per call.
const ITERATIONS: usize = 12;
/// Laplacian relaxation never takes a ball's worst shape below this (or below where it was).
const RELAX_FLOOR: f64 = 0.35;
/// Tets within this much of the worst share the ascent direction.
const NEAR_WORST: f64 = 0.02;

/// The corners of tet `t` with node `v` moved to `p`.
#[inline]
fn placed(cx: &Complex, t: [u32; 4], v: u32, p: &P) -> [P; 4] {
    t.map(|i| if i == v { *p } else { cx.nodes[i as usize] })
}

/// Quality of `t` with node `v` placed at `p`, and its gradient with respect to `p`.
fn quality_and_gradient(cx: &Complex, t: [u32; 4], v: u32, p: &P) -> (f64, P) {
    let x = placed(cx, t, v, p);
    let q = mean_ratio(&x[0], &x[1], &x[2], &x[3]);
    let k = t.iter().position(|&i| i == v).unwrap_or(0);
    // The face opposite `k`, ordered so that its right-hand normal points towards node k.
    let f = match k {
        0 => [1, 3, 2],
        1 => [0, 2, 3],
        2 => [0, 3, 1],
        _ => [0, 1, 2],
    };
    let (a, b, c) = (x[f[0]], x[f[1]], x[f[2]]);
    let u = sub(&b, &a);
    let w = sub(&c, &a);
    let n = [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ];
    let vol6 = dot(&n, &sub(p, &a));
    let mut gl = [0.0; 3];
    let mut l2 = 0.0;
    for (i, y) in x.iter().enumerate() {
        for z in &x[i + 1..] {
            let e = sub(y, z);
            l2 += dot(&e, &e);
        }
        if i != k {
            let e = sub(p, y);
            for m in 0..3 {
                gl[m] += 2.0 * e[m];
            }
        }
    }
    if vol6 <= 0.0 || l2 <= 0.0 || q <= 0.0 {
        return (q, [0.0; 3]);
    }
    // q = c V^(2/3) / L  =>  grad q = q (2/3 grad V / V - grad L / L), grad V / V = n / vol6.
    let g = [0, 1, 2].map(|m| q * (2.0 / 3.0 * n[m] / vol6 - gl[m] / l2));
    (q, g)
}

/// The gradient of the optimizer's shape measure (`quality::shape`) of `t` with `v` at `p`, whose
/// value there is `q`: the analytic mean-ratio gradient where the mean ratio is the binding
/// measure, else forward differences of the dihedral-sine term (steps of `1e-6 · scale`).
fn shape_gradient(cx: &Complex, t: [u32; 4], v: u32, p: &P, scale: f64, q: f64) -> P {
    let at = |p: &P| {
        let x = placed(cx, t, v, p);
        shape(&x[0], &x[1], &x[2], &x[3])
    };
    let (mr, g) = quality_and_gradient(cx, t, v, p);
    if mr <= q || q <= 0.0 {
        return g;
    }
    let h = 1e-6 * scale;
    if h.is_nan() || h <= 0.0 {
        return [0.0; 3];
    }
    [0, 1, 2].map(|m| {
        let mut y = *p;
        y[m] += h;
        (at(&y) - q) / h
    })
}

#[inline]
fn sub(a: &P, b: &P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
fn dot(a: &P, b: &P) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Worst quality of the ball of `v` with `v` at `p`; None if a tet is not positive (exact).
pub fn worst_at(cx: &Complex, v: u32, p: &P) -> Option<f64> {
    worst_above(cx, v, p, 0.0)
}

/// Worst quality of the ball of `v` with `v` at `p` when it is above `floor >= 0` and every tet
/// is positive (exact); None otherwise, as soon as one tet is at or below `floor`.
fn worst_above(cx: &Complex, v: u32, p: &P, floor: f64) -> Option<f64> {
    let mut w = f64::INFINITY;
    for &t in &cx.node_tets[v as usize] {
        let x = placed(cx, cx.tets[t as usize], v, p);
        w = w.min(shape(&x[0], &x[1], &x[2], &x[3]));
        if w <= floor {
            return None;
        }
    }
    for &t in &cx.node_tets[v as usize] {
        let x = placed(cx, cx.tets[t as usize], v, p);
        if orient3d(&x[0], &x[1], &x[2], &x[3]) != Orientation::Positive {
            return None;
        }
    }
    Some(w)
}

/// What a relaxation move must reach (see [`relax_node`]): a worst shape above `s0`, or a worst
/// mean ratio at least `w_keep`, a worst shape at least `s_floor` and a mean mean ratio above `m0`.
struct Bar {
    s0: f64,
    w_keep: f64,
    s_floor: f64,
    m0: f64,
}

/// Whether the ball of `v` with `v` at `p` passes `bar` with every tet positive (exact). Each
/// tet's (shape, mean ratio) is left in `measures`, in ball order, for
/// [`Complex::move_node_measured`]. The worsts only fall as tets are measured, so the ball is
/// given up at the first tet that makes both ways out of reach.
fn ball_passes(cx: &Complex, v: u32, p: &P, bar: &Bar, measures: &mut Vec<(f64, f64)>) -> bool {
    let ball = &cx.node_tets[v as usize];
    let mut s = 0.0;
    let mut w = f64::INFINITY;
    let mut sw = f64::INFINITY;
    measures.clear();
    for &t in ball {
        let x = placed(cx, cx.tets[t as usize], v, p);
        let (sh, q) = shape_and_mean_ratio(&x[0], &x[1], &x[2], &x[3]);
        if sh <= 0.0 {
            return false;
        }
        measures.push((sh, q));
        sw = sw.min(sh);
        s += q;
        w = w.min(q);
        if sw <= bar.s0 && (w < bar.w_keep || sw < bar.s_floor) {
            return false;
        }
    }
    if sw <= bar.s0 && s / ball.len() as f64 <= bar.m0 {
        return false;
    }
    ball.iter().all(|&t| {
        let x = placed(cx, cx.tets[t as usize], v, p);
        orient3d(&x[0], &x[1], &x[2], &x[3]) == Orientation::Positive
    })
}

/// The ball of `v` where it stands, from the complex's cached measures.
fn ball_now(cx: &Complex, v: u32) -> Option<(f64, f64, f64)> {
    let ball = &cx.node_tets[v as usize];
    let mut s = 0.0;
    let mut w = f64::INFINITY;
    let mut sw = f64::INFINITY;
    for &t in ball {
        sw = sw.min(cx.shape[t as usize]);
        let q = cx.mean_ratio[t as usize];
        s += q;
        w = w.min(q);
    }
    (sw > 0.0).then_some((sw, w, s / ball.len() as f64))
}

/// Laplacian step for the free node `v`: towards the centroid of its neighbours, accepted when
/// the ball's worst shape rises, or when its mean mean ratio rises while its worst mean ratio
/// stays at least `keep` (a good ball may trade a little of its worst for a better average) and
/// its worst shape stays above the optimizer's bar (or where it was). True when moved.
/// `measures` is scratch space.
pub fn relax_node(cx: &mut Complex, v: u32, keep: f64, measures: &mut Vec<(f64, f64)>) -> bool {
    if (v as usize) < cx.n_fixed || cx.node_tets[v as usize].is_empty() {
        return false;
    }
    let cur = cx.nodes[v as usize];
    let Some((s0, w0, m0)) = ball_now(cx, v) else {
        return false;
    };
    let mut sum = [0.0; 3];
    let mut n = 0.0;
    for &t in &cx.node_tets[v as usize] {
        for &w in &cx.tets[t as usize] {
            if w != v {
                let p = cx.nodes[w as usize];
                for m in 0..3 {
                    sum[m] += p[m];
                }
                n += 1.0;
            }
        }
    }
    let centre = sum.map(|s| s / n);
    let bar = Bar {
        s0,
        w_keep: keep.min(w0),
        s_floor: RELAX_FLOOR.min(s0),
        m0,
    };
    for step in [1.0, 0.5, 0.25] {
        let p = [0, 1, 2].map(|m| cur[m] + (centre[m] - cur[m]) * step);
        if ball_passes(cx, v, &p, &bar, measures) {
            cx.move_node_measured(v, p, measures);
            return true;
        }
    }
    false
}

/// Move the free node `v` to raise the worst quality of its ball. Returns the new worst
/// quality when the node moved.
pub fn smooth_node(cx: &mut Complex, v: u32) -> Option<f64> {
    if (v as usize) < cx.n_fixed || cx.node_tets[v as usize].is_empty() {
        return None;
    }
    let start = cx.nodes[v as usize];
    let mut cur = start;
    let mut best = worst_at(cx, v, &cur)?;
    let q0 = best;
    // Scale of the ball: mean distance to the neighbours.
    let mut sum = [0.0; 3];
    let mut scale = 0.0;
    let mut n = 0.0;
    for &t in &cx.node_tets[v as usize] {
        for &w in &cx.tets[t as usize] {
            if w != v {
                let p = cx.nodes[w as usize];
                for m in 0..3 {
                    sum[m] += p[m];
                }
                scale += dot(&sub(&p, &cur), &sub(&p, &cur)).sqrt();
                n += 1.0;
            }
        }
    }
    let centre = sum.map(|s| s / n);
    scale /= n;
    for step in [1.0, 0.5, 0.25] {
        let p = [0, 1, 2].map(|m| cur[m] + (centre[m] - cur[m]) * step);
        if let Some(q) = worst_above(cx, v, &p, best) {
            best = q;
            cur = p;
            break;
        }
    }
    let mut alpha = 0.1 * scale;
    for _ in 0..ITERATIONS {
        let mut dir = [0.0; 3];
        for &t in &cx.node_tets[v as usize] {
            let tv = cx.tets[t as usize];
            let x = placed(cx, tv, v, &cur);
            let q = shape(&x[0], &x[1], &x[2], &x[3]);
            if q <= best + NEAR_WORST {
                let g = shape_gradient(cx, tv, v, &cur, scale, q);
                let gn = dot(&g, &g).sqrt();
                if gn > 0.0 {
                    for m in 0..3 {
                        dir[m] += g[m] / gn;
                    }
                }
            }
        }
        let dn = dot(&dir, &dir).sqrt();
        if dn <= 0.0 || !dn.is_finite() {
            break;
        }
        let dir = dir.map(|d| d / dn);
        let mut moved = false;
        let mut a = alpha;
        for _ in 0..6 {
            let p = [0, 1, 2].map(|m| cur[m] + dir[m] * a);
            if let Some(q) = worst_above(cx, v, &p, best) {
                best = q;
                cur = p;
                moved = true;
                break;
            }
            a *= 0.5;
        }
        if !moved {
            break;
        }
        alpha = (a * 2.0).min(0.2 * scale);
    }
    if best > q0 && cur != start {
        cx.move_node(v, cur);
        Some(best)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gradient_of_the_mean_ratio_matches_finite_differences() {
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.1, 0.0],
            [0.3, 0.9, 0.1],
            [0.4, 0.3, 0.6],
        ];
        let cx = Complex::new(nodes.clone(), vec![[0, 1, 2, 3]], 0, std::iter::empty());
        for v in 0..4u32 {
            let p = nodes[v as usize];
            let (q, g) = quality_and_gradient(&cx, [0, 1, 2, 3], v, &p);
            assert!(q > 0.0);
            for m in 0..3 {
                let h = 1e-6;
                let mut pp = p;
                pp[m] += h;
                let (q1, _) = quality_and_gradient(&cx, [0, 1, 2, 3], v, &pp);
                let fd = (q1 - q) / h;
                assert!(
                    (fd - g[m]).abs() < 1e-4,
                    "node {v} axis {m}: {fd} vs {}",
                    g[m]
                );
            }
        }
    }

    #[test]
    fn a_badly_placed_free_node_moves_to_a_better_ball_and_fixed_nodes_never_move() {
        // An octahedron around node 6, pushed towards one corner.
        let (nodes, tets) = test_support::shapes::octahedron_ball([0.6, 0.1, 0.05]);
        let c = 6;
        let mut cx = Complex::new(nodes, tets.clone(), 6, std::iter::empty());
        for &t in &tets {
            assert!(cx.positive(t), "{t:?}");
        }
        let before = worst_at(&cx, c, &cx.nodes[c as usize]).unwrap();
        let after = smooth_node(&mut cx, c).expect("moves");
        assert!(after > before + 0.2, "{before} -> {after}");
        assert!(tets.iter().all(|&t| cx.positive(t)));
        assert_eq!(smooth_node(&mut cx, 0), None);
    }
}
