//! Triangle shape measures (floating point, for decisions about *quality*, never about topology).
//! The seed's c/c*: (mean of squared edge lengths) / area, divided by its equilateral value, so
//! 1.0 is ideal and larger is worse. `shape` is its inverse in (0, 1], convenient to maximize.

use geom::predicates::{cross, dot, sub};

/// c/c* of triangle `abc` in 3D (infinity for a degenerate triangle).
pub fn c_ratio(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> f64 {
    let s = shape(a, b, c);
    if s > 0.0 { 1.0 / s } else { f64::INFINITY }
}

/// 4·√3·area / (sum of squared edge lengths): 1 for equilateral, 0 for degenerate.
pub fn shape(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> f64 {
    let ab = sub(b, a);
    let ac = sub(c, a);
    let bc = sub(c, b);
    let n = cross(&ab, &ac);
    let area = 0.5 * dot(&n, &n).sqrt();
    let s = dot(&ab, &ab) + dot(&ac, &ac) + dot(&bc, &bc);
    if s > 0.0 {
        4.0 * 3f64.sqrt() * area / s
    } else {
        0.0
    }
}

/// Circumradius of triangle `abc` in 3D (infinity when degenerate).
pub fn circumradius(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> f64 {
    let ab = sub(b, a);
    let ac = sub(c, a);
    let bc = sub(c, b);
    let n = cross(&ab, &ac);
    let a2 = dot(&n, &n).sqrt();
    if a2 > 0.0 {
        dot(&ab, &ab).sqrt() * dot(&ac, &ac).sqrt() * dot(&bc, &bc).sqrt() / (2.0 * a2)
    } else {
        f64::INFINITY
    }
}

/// Summary of c/c* over a triangle mesh: (count, mean, standard deviation, max, share > 1.15,
/// share > 1.5), shares in percent.
#[derive(Clone, Debug, PartialEq)]
pub struct QualityStats {
    pub triangles: usize,
    pub mean: f64,
    pub sd: f64,
    pub max: f64,
    pub pct_above_1_15: f64,
    pub pct_above_1_5: f64,
}

pub fn stats(nodes: &[[f64; 3]], triangles: &[[u32; 3]]) -> QualityStats {
    let q: Vec<f64> = triangles
        .iter()
        .map(|t| {
            let p = |i: usize| nodes.get(t[i] as usize).copied().unwrap_or([f64::NAN; 3]);
            c_ratio(&p(0), &p(1), &p(2))
        })
        .collect();
    let n = q.len().max(1) as f64;
    let mean = q.iter().sum::<f64>() / n;
    let sd = (q.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n).sqrt();
    QualityStats {
        triangles: q.len(),
        mean,
        sd,
        max: q.iter().copied().fold(0.0, f64::max),
        pct_above_1_15: 100.0 * q.iter().filter(|&&x| x > 1.15).count() as f64 / n,
        pct_above_1_5: 100.0 * q.iter().filter(|&&x| x > 1.5).count() as f64 / n,
    }
}
