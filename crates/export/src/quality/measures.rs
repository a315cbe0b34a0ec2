//! Element quality measures of the seed paper (section 5) as defined in DESIGN.md §7, with the
//! exact formulas of `tools/check_mesh.py` so that our tables and the independent checker agree:
//!
//! * triangle `c/c*`: `c` = (mean of the squared edge lengths) / area, `c*` = its equilateral value
//!   `4/√3`; 1.0 is ideal, larger is worse, a degenerate triangle gives a huge value;
//! * tet mean ratio normalised so the regular tet is 1.0: `12·(3|V|)^(2/3) / Σ l²`;
//! * minimum dihedral angle in degrees (the regular tet has arccos(1/3) ≈ 70.53°).
//!
//! These are measures, never decisions: plain floating point is right here.

use geom::predicates::{cross, dot, signed_volume, sub};

/// The seed's Table 2 quotes 0.79 for the regular tet (its mean ratio is not normalised):
/// multiply our normalised value by this to compare with the paper's figures.
pub const PAPER_MEAN_RATIO_SCALE: f64 = 0.79;

fn norm2(v: &[f64; 3]) -> f64 {
    dot(v, v)
}

/// Triangle shape measure `c/c*` (1.0 for the equilateral triangle, ≥ 1 otherwise).
pub fn triangle_ratio(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> f64 {
    let area = 0.5 * norm2(&cross(&sub(b, a), &sub(c, a))).sqrt();
    let s2 = (norm2(&sub(b, a)) + norm2(&sub(c, b)) + norm2(&sub(a, c))) / 3.0;
    let c_ratio = s2 / area.max(1e-300);
    let c_star = 1.0 / (3f64.sqrt() / 4.0);
    c_ratio / c_star
}

/// Tet mean ratio normalised to 1.0 for the regular tet, 0 for a flat one; independent of the
/// vertex order (uses |V|).
pub fn tet_mean_ratio(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    let vol = signed_volume(a, b, c, d);
    let l2 = norm2(&sub(b, a))
        + norm2(&sub(c, a))
        + norm2(&sub(d, a))
        + norm2(&sub(c, b))
        + norm2(&sub(d, b))
        + norm2(&sub(d, c));
    let k = (3.0 * vol.abs()).cbrt();
    12.0 * k * k / l2.max(1e-300)
}

/// Smallest interior dihedral angle of the tet, in degrees, whatever its vertex order.
///
/// At each edge `ij` the angle between the two faces through it is the angle between the
/// components of `k - i` and `l - i` orthogonal to the edge (`k`, `l` the other two corners),
/// taken with `atan2` so that flat and needle tets give 0 without a NaN.
///
/// `atan2` is the cost of a large mesh's Table 2, so it is taken only at the edges that can hold
/// the smallest angle: those whose cosine is within `COS_SLACK` (1e-9) of the largest. A cosine is
/// off by a few units in the last place, far inside the slack, so the result is the smallest of
/// all six `atan2`s bit for bit.
pub fn tet_min_dihedral_deg(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    let p = [a, b, c, d];
    // (sine, cosine) of each angle, both scaled by the same positive factor.
    let mut sc = [(0.0f64, 0.0f64); 6];
    for (slot, &(i, j, k, l)) in sc.iter_mut().zip(TET_EDGES.iter()) {
        let e = sub(p[j], p[i]);
        let ee = norm2(&e);
        if ee.is_nan() || ee <= 0.0 {
            // A zero-length edge: the tet is degenerate.
            return 0.0;
        }
        let u0 = sub(p[k], p[i]);
        let v0 = sub(p[l], p[i]);
        let su = dot(&u0, &e) / ee;
        let sv = dot(&v0, &e) / ee;
        let u = [u0[0] - su * e[0], u0[1] - su * e[1], u0[2] - su * e[2]];
        let v = [v0[0] - sv * e[0], v0[1] - sv * e[1], v0[2] - sv * e[2]];
        *slot = (norm2(&cross(&u, &v)).sqrt(), dot(&u, &v));
    }
    let cosines = sc.map(|(s, c)| {
        let r = (s * s + c * c).sqrt();
        if r > 0.0 { c / r } else { 1.0 }
    });
    let largest = cosines.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mut best = 180.0f64;
    for (&(s, c), &cosine) in sc.iter().zip(&cosines) {
        // A NaN angle is passed over, as `f64::min` would.
        if cosine >= largest - COS_SLACK {
            best = best.min(s.atan2(c).to_degrees());
        }
    }
    best
}

/// A tet's six edges `ij`, each with the two other corners `k`, `l`.
pub(crate) const TET_EDGES: [(usize, usize, usize, usize); 6] = [
    (0, 1, 2, 3),
    (0, 2, 1, 3),
    (0, 3, 1, 2),
    (1, 2, 0, 3),
    (1, 3, 0, 2),
    (2, 3, 0, 1),
];

/// How far below the largest cosine an edge's may be and still be measured (see
/// [`tet_min_dihedral_deg`]).
const COS_SLACK: f64 = 1e-9;

#[cfg(test)]
mod tests {
    use super::*;

    fn regular() -> [[f64; 3]; 4] {
        [
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ]
    }

    #[test]
    fn the_regular_tet_has_mean_ratio_one_and_dihedral_arccos_one_third() {
        let [a, b, c, d] = regular();
        assert!((tet_mean_ratio(&a, &b, &c, &d) - 1.0).abs() < 1e-12);
        assert!((tet_mean_ratio(&b, &a, &c, &d) - 1.0).abs() < 1e-12);
        let want = (1.0f64 / 3.0).acos().to_degrees();
        assert!((tet_min_dihedral_deg(&a, &b, &c, &d) - want).abs() < 1e-9);
        assert!((want - 70.528_779_365_509_3).abs() < 1e-9);
    }

    #[test]
    fn the_unit_corner_tet_has_a_45_degree_dihedral_and_known_mean_ratio() {
        let o = [0.0; 3];
        let (x, y, z) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        assert!((tet_min_dihedral_deg(&o, &x, &y, &z) - 54.735_610_317_245_35).abs() < 1e-9);
        // Σl² = 3 + 3·2 = 9, V = 1/6: 12·(1/2)^(2/3)/9
        let want = 12.0 * 0.5f64.powf(2.0 / 3.0) / 9.0;
        assert!((tet_mean_ratio(&o, &x, &y, &z) - want).abs() < 1e-12);
        // Kuhn tet of a unit cube: dihedral angles 45, 60, 90
        let k = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 1.0, 1.0],
        ];
        assert!((tet_min_dihedral_deg(&k[0], &k[1], &k[2], &k[3]) - 45.0).abs() < 1e-9);
    }

    #[test]
    fn a_flat_tet_has_zero_mean_ratio_and_zero_dihedral() {
        let (a, b, c, d) = (
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        );
        assert_eq!(tet_mean_ratio(&a, &b, &c, &d), 0.0);
        assert!(tet_min_dihedral_deg(&a, &b, &c, &d) < 1e-9);
        assert_eq!(tet_min_dihedral_deg(&a, &a, &c, &d), 0.0);
    }

    /// Every edge's angle by `atan2`, the smallest kept: the definition the fast path must match.
    fn every_edge_by_atan2(p: [[f64; 3]; 4]) -> f64 {
        let mut best = 180.0f64;
        for (i, j, k, l) in TET_EDGES {
            let e = sub(&p[j], &p[i]);
            let ee = norm2(&e);
            let (u0, v0) = (sub(&p[k], &p[i]), sub(&p[l], &p[i]));
            let (su, sv) = (dot(&u0, &e) / ee, dot(&v0, &e) / ee);
            let u = [0, 1, 2].map(|m| u0[m] - su * e[m]);
            let v = [0, 1, 2].map(|m| v0[m] - sv * e[m]);
            best = best.min(norm2(&cross(&u, &v)).sqrt().atan2(dot(&u, &v)).to_degrees());
        }
        best
    }

    #[test]
    fn the_smallest_dihedral_is_the_smallest_of_the_six_atan2s_bit_for_bit() {
        let mut rng = test_support::didactic::Rng(7);
        let mut p = |scale: f64| [0; 3].map(|_| 500_000.0 + scale * rng.unit());
        for n in 0..20_000 {
            // Well-shaped, slivers (a corner near the opposite face), needles and caps, at UTM
            // coordinates.
            let mut t = [p(100.0), p(100.0), p(100.0), p(100.0)];
            match n % 4 {
                1 => {
                    t[3] = [0, 1, 2]
                        .map(|m| (t[0][m] + t[1][m] + t[2][m]) / 3.0 + 1e-3 * (n % 7) as f64)
                }
                2 => t[1] = [0, 1, 2].map(|m| t[0][m] + 1e-4 * (t[1][m] - 500_000.0)),
                3 => t[2] = [0, 1, 2].map(|m| 0.5 * (t[0][m] + t[1][m])),
                _ => {}
            }
            let [a, b, c, d] = t;
            let got = tet_min_dihedral_deg(&a, &b, &c, &d);
            let want = every_edge_by_atan2(t);
            assert_eq!(got.to_bits(), want.to_bits(), "tet {n}: {t:?}");
        }
    }

    #[test]
    fn the_equilateral_triangle_scores_one_and_the_right_isoceles_two_over_root_three() {
        let h = 3f64.sqrt() / 2.0;
        let q = triangle_ratio(&[0.0, 0.0, 5.0], &[1.0, 0.0, 5.0], &[0.5, h, 5.0]);
        assert!((q - 1.0).abs() < 1e-12);
        // legs 1, 1: s² = 4/3, area 1/2 → c = 8/3, c* = 4/√3 → 2/√3
        let r = triangle_ratio(&[0.0; 3], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0]);
        assert!((r - 2.0 / 3f64.sqrt()).abs() < 1e-12);
        assert!(triangle_ratio(&[0.0; 3], &[1.0, 0.0, 0.0], &[2.0, 0.0, 0.0]) > 1e100);
    }
}
