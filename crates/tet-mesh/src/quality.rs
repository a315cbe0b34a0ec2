//! Shape measures of a tetrahedron, used to rank candidate apexes, to steer optimization and to
//! report. These are float *measures*: validity (is a tet inverted) is never decided from them —
//! that is `orient3d`'s job.

use geom::predicates::{cross, dot, signed_volume, sub};

type P = [f64; 3];

/// The signed volume and the sum of the six squared edge lengths, the two ingredients of the
/// mean ratio.
#[inline]
fn volume_and_edges(a: &P, b: &P, c: &P, d: &P) -> (f64, f64) {
    let l2 = len2(&sub(b, a))
        + len2(&sub(c, a))
        + len2(&sub(d, a))
        + len2(&sub(c, b))
        + len2(&sub(d, b))
        + len2(&sub(d, c));
    (signed_volume(a, b, c, d), l2)
}

/// Normalised mean ratio: `12·(3V)^(2/3) / Σ l²`, 1 for the regular tetrahedron, ≤ 0 for a flat or
/// inverted one (negative volumes give a negative value so rankings stay monotone).
pub fn mean_ratio(a: &P, b: &P, c: &P, d: &P) -> f64 {
    let (v, l2) = volume_and_edges(a, b, c, d);
    if l2 <= 0.0 {
        return 0.0;
    }
    let c = cbrt((3.0 * v.abs()) * (3.0 * v.abs()));
    let m = 12.0 * c / l2;
    if v < 0.0 { -m } else { m }
}

/// The cube of [`mean_ratio`] (signed like the volume), without a root: `1728·(3V)² / (Σ l²)³`.
/// Monotone in the mean ratio, so comparisons against cubed bars need no root at all.
#[inline]
pub fn mean_ratio_cubed(a: &P, b: &P, c: &P, d: &P) -> f64 {
    let (v, l2) = volume_and_edges(a, b, c, d);
    if l2 <= 0.0 {
        return 0.0;
    }
    let t = 3.0 * v;
    let m = 1728.0 * (t * t) / (l2 * l2 * l2);
    if v < 0.0 { -m } else { m }
}

/// Cube root of `x ≥ 0`, to a few ulps: a bit-level first guess (within about 3 %) and three
/// Halley steps (cubic convergence). The standard library's correctly rounded `cbrt` was 4-8 %
/// of a whole meshing run; the measures need no last-ulp rounding. Zero, subnormal, infinite
/// or NaN arguments go to the standard `cbrt`.
#[inline]
pub fn cbrt(x: f64) -> f64 {
    if !x.is_normal() || x < 0.0 {
        return x.cbrt();
    }
    let mut y = f64::from_bits(x.to_bits() / 3 + 0x2A9F_7893_782D_A1CE);
    for _ in 0..3 {
        let y3 = y * y * y;
        y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
    }
    y
}

/// Scale that maps the sine of a 10° dihedral angle to a mean ratio of 0.3, so that
/// [`shape`] treats the two bars of the seed's Table 2 (mean ratio ≥ 0.3, min dihedral ≥ 10°) alike.
pub const SINE_SCALE: f64 = 0.3 / 0.173_648_177_666_930_35;

/// The smallest sine of the six dihedral angles of `abcd` (0 for a flat tet, negative for an
/// inverted one). Small both for a tiny angle and for one near 180°. Uses
/// `sin θ_e = 3·V·|e| / (2·A_f·A_g)` for the edge `e` shared by the faces `f` and `g`.
pub fn min_sine(a: &P, b: &P, c: &P, d: &P) -> f64 {
    let v = signed_volume(a, b, c, d);
    let p = [a, b, c, d];
    // Twice the area of the face opposite node i.
    let area2 = |x: &P, y: &P, z: &P| len2(&cross(&sub(y, x), &sub(z, x))).sqrt();
    let ar = [
        area2(b, c, d),
        area2(a, c, d),
        area2(a, b, d),
        area2(a, b, c),
    ];
    let mut m = f64::INFINITY;
    for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
        // The edge ij is shared by the faces opposite the two other nodes k and l.
        let (k, l) = match (i, j) {
            (0, 1) => (2, 3),
            (0, 2) => (1, 3),
            (0, 3) => (1, 2),
            (1, 2) => (0, 3),
            (1, 3) => (0, 2),
            _ => (0, 1),
        };
        let e = len2(&sub(p[j], p[i])).sqrt();
        let den = ar[k] * ar[l];
        if den <= 0.0 {
            return 0.0;
        }
        // areas are doubled: sin = 3 V e / (2 A_k A_l) = 6 V e / (ar_k ar_l)
        m = m.min(6.0 * v * e / den);
    }
    if m.is_finite() { m } else { 0.0 }
}

/// Above a mean ratio of 0.7 the scaled dihedral sine never binds in [`shape`] (sampled on
/// 800k random and perturbed regular tets: it binds up to 0.62, and at 0.7 it exceeds the mean
/// ratio by 8 %), so the six dihedral sines are not computed there. The cube of 0.7.
const SINE_NEVER_BINDS_CUBED: f64 = 0.343;

/// The optimizer's objective: the mean ratio, capped by the scaled smallest dihedral sine, so a
/// tet is "good" only when both of Table 2's measures are (1 ≈ regular; ≤ 0 flat or inverted).
#[inline]
pub fn shape(a: &P, b: &P, c: &P, d: &P) -> f64 {
    shape_above(a, b, c, d, f64::NEG_INFINITY)
}

/// [`shape`] when the mean ratio exceeds `floor`; otherwise `-∞` without computing the sines
/// or any root (the shape is at most the mean ratio, so it is at most `floor` too). For searches
/// that only need the tets better than a bar.
#[inline]
pub fn shape_above(a: &P, b: &P, c: &P, d: &P, floor: f64) -> f64 {
    // The mean ratio's cube decides which measure binds, so the root is taken only when the
    // mean ratio is the result (same value as `mean_ratio(..).min(..)`, to a few ulps).
    let q3 = mean_ratio_cubed(a, b, c, d);
    if q3 <= floor * floor * floor {
        return f64::NEG_INFINITY;
    }
    if q3 <= 0.0 {
        return if q3 < 0.0 { -cbrt(-q3) } else { 0.0 };
    }
    if q3 >= SINE_NEVER_BINDS_CUBED {
        return cbrt(q3);
    }
    let s = SINE_SCALE * min_sine(a, b, c, d);
    if s <= 0.0 || s * s * s < q3 {
        return s;
    }
    cbrt(q3)
}

/// [`shape`] and [`mean_ratio`] together, sharing one volume and edge pass.
#[inline]
pub fn shape_and_mean_ratio(a: &P, b: &P, c: &P, d: &P) -> (f64, f64) {
    let q3 = mean_ratio_cubed(a, b, c, d);
    if q3 <= 0.0 {
        let m = if q3 < 0.0 { -cbrt(-q3) } else { 0.0 };
        return (m, m);
    }
    let m = cbrt(q3);
    if q3 >= SINE_NEVER_BINDS_CUBED {
        return (m, m);
    }
    let s = SINE_SCALE * min_sine(a, b, c, d);
    if s <= 0.0 || s * s * s < q3 {
        (s, m)
    } else {
        (m, m)
    }
}

#[inline]
fn len2(v: &P) -> f64 {
    dot(v, v)
}

/// The smallest of the six dihedral angles of `abcd`, in degrees.
pub fn min_dihedral_deg(a: &P, b: &P, c: &P, d: &P) -> f64 {
    dihedral_deg(largest_dihedral_cosine(a, b, c, d))
}

/// The angle whose cosine is `cos`, in degrees (at most 180).
pub fn dihedral_deg(cos: f64) -> f64 {
    cos.acos().to_degrees().min(180.0)
}

/// The cosine of the smallest dihedral angle of `abcd` (the angle falls as its cosine rises):
/// the smallest angle of many tets is the arc cosine of their largest, taken once.
pub fn largest_dihedral_cosine(a: &P, b: &P, c: &P, d: &P) -> f64 {
    // Outward-ish face normals (unnormalised): opposite d, c, b, a.
    let p = [a, b, c, d];
    let faces = [[0usize, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]];
    let mut n = [[0.0f64; 3]; 4];
    for (i, f) in faces.iter().enumerate() {
        let opp = 6 - f[0] - f[1] - f[2];
        let mut v = cross(&sub(p[f[1]], p[f[0]]), &sub(p[f[2]], p[f[0]]));
        // make it point away from the opposite vertex
        if dot(&v, &sub(p[opp], p[f[0]])) > 0.0 {
            v = [-v[0], -v[1], -v[2]];
        }
        let l = len2(&v).sqrt();
        n[i] = if l > 0.0 {
            let inv = 1.0 / l;
            [v[0] * inv, v[1] * inv, v[2] * inv]
        } else {
            [0.0; 3]
        };
    }
    let mut max_cos = f64::NEG_INFINITY;
    for i in 0..4 {
        for j in i + 1..4 {
            max_cos = max_cos.max((-dot(&n[i], &n[j])).clamp(-1.0, 1.0));
        }
    }
    max_cos
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_regular_tetrahedron_has_mean_ratio_one_and_dihedral_about_70_5() {
        let a = [1.0, 1.0, 1.0];
        let b = [1.0, -1.0, -1.0];
        let c = [-1.0, 1.0, -1.0];
        let d = [-1.0, -1.0, 1.0];
        let q = mean_ratio(&a, &b, &c, &d).abs();
        assert!((q - 1.0).abs() < 1e-12, "{q}");
        assert!((min_dihedral_deg(&a, &b, &c, &d) - 70.528779).abs() < 1e-4);
    }

    #[test]
    fn the_shape_above_a_floor_is_the_shape_or_minus_infinity_when_the_mean_ratio_is_below() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut r = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..20_000 {
            let p: [P; 4] = std::array::from_fn(|_| [r(), r(), r() * 0.3]);
            let floor = r() - 0.1;
            let (sh, mr) = (
                shape(&p[0], &p[1], &p[2], &p[3]),
                mean_ratio(&p[0], &p[1], &p[2], &p[3]),
            );
            let got = shape_above(&p[0], &p[1], &p[2], &p[3], floor);
            if mr > floor * (1.0 + 1e-12) + 1e-12 {
                assert_eq!(got, sh, "{p:?} floor {floor}");
            } else if got != sh {
                assert_eq!(got, f64::NEG_INFINITY);
                assert!(sh <= floor + 1e-12, "{sh} > {floor}");
            }
        }
    }

    #[test]
    fn the_smallest_dihedral_sine_matches_the_smallest_dihedral_angle() {
        let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.3, 0.9, 0.0]);
        for d in [
            [0.4, 0.3, 0.6],
            [0.4, 0.3, 0.05],
            [2.0, 0.2, 0.3],
            [0.35, 0.35, 1e-3],
        ] {
            let deg = min_dihedral_deg(&a, &b, &c, &d);
            let s = min_sine(&a, &b, &c, &d);
            // The smallest sine is that of the smallest angle or of the largest (near 180°).
            assert!(s <= deg.to_radians().sin() + 1e-12, "{d:?}: {s} vs {deg}");
            assert!(s > 0.0);
        }
        let (p, q, r, w) = (
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        );
        // This regular tet is negatively oriented: the sign follows the orientation. Its
        // dihedral angles are all acos(1/3), whose sine is sqrt(8)/3.
        let regular = 8f64.sqrt() / 3.0;
        let s = min_sine(&p, &q, &r, &w);
        assert!((s + regular).abs() < 1e-12, "{s}");
        let s = min_sine(&q, &p, &r, &w);
        assert!((s - regular).abs() < 1e-12, "{s}");
        // A 10° dihedral scores 0.3, the mean-ratio bar.
        assert!((SINE_SCALE * 10f64.to_radians().sin() - 0.3).abs() < 1e-12);
        // A sliver (four nearly coplanar nodes on a square) scores low by both.
        let sl = shape(
            &[0.0, 0.0, 0.0],
            &[1.0, 0.0, 0.02],
            &[1.0, 1.0, 0.0],
            &[0.0, 1.0, 0.02],
        );
        assert!(sl.abs() < 0.1, "{sl}");
    }

    #[test]
    fn the_fast_cube_root_agrees_with_the_standard_one_to_a_few_ulps() {
        let mut x = 1e-300;
        while x < 1e300 {
            for f in [1.0, 1.37, 2.0, 2.9, 7.77] {
                let v = x * f;
                let (got, want) = (cbrt(v), v.cbrt());
                assert!(
                    (got - want).abs() <= 4.0 * f64::EPSILON * want,
                    "{v}: {got} vs {want}"
                );
            }
            x *= 10.0;
        }
        assert_eq!(cbrt(0.0), 0.0);
        assert_eq!(cbrt(27.0), 3.0);
        assert!(cbrt(f64::NAN).is_nan());
        assert_eq!(cbrt(f64::INFINITY), f64::INFINITY);
    }

    #[test]
    fn the_shape_is_the_smaller_of_the_mean_ratio_and_the_scaled_dihedral_sine() {
        let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.3, 0.9, 0.0]);
        for d in [
            [0.4, 0.3, 0.6],
            [0.4, 0.3, 0.05],
            [2.0, 0.2, 0.3],
            [0.35, 0.35, 1e-3],
            [0.4, 0.3, -0.6],
            [0.5, 0.5, 0.0],
        ] {
            let want = {
                let q = mean_ratio(&a, &b, &c, &d);
                if q <= 0.0 {
                    q
                } else {
                    q.min(SINE_SCALE * min_sine(&a, &b, &c, &d))
                }
            };
            let got = shape(&a, &b, &c, &d);
            assert!((got - want).abs() <= 1e-14, "{d:?}: {got} vs {want}");
            let q3 = mean_ratio_cubed(&a, &b, &c, &d);
            let q = mean_ratio(&a, &b, &c, &d);
            assert!((q3 - q * q * q).abs() <= 1e-14, "{d:?}: {q3} vs {q}");
        }
    }

    #[test]
    fn a_flat_tetrahedron_has_mean_ratio_zero() {
        let q = mean_ratio(
            &[0.0; 3],
            &[1.0, 0.0, 0.0],
            &[0.0, 1.0, 0.0],
            &[1.0, 1.0, 0.0],
        );
        assert_eq!(q, 0.0);
    }

    #[test]
    fn above_a_mean_ratio_of_0_7_skipping_the_dihedral_sines_changes_no_shape() {
        // Perturbed regular tets (a fixed linear congruential sequence): wherever the mean ratio
        // is at least 0.7, the scaled smallest sine is above it, so `shape` is the mean ratio.
        let mut x: u64 = 12345;
        let mut next = || {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let reg = [
            [1.0, -1.0, -1.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ];
        let mut checked = 0;
        for k in 0..200_000 {
            let amp = 1.6 * (k % 100) as f64 / 100.0;
            let t: Vec<P> = reg
                .iter()
                .map(|p| {
                    [
                        p[0] + amp * next(),
                        p[1] + amp * next(),
                        p[2] + amp * next(),
                    ]
                })
                .collect();
            let q = mean_ratio(&t[0], &t[1], &t[2], &t[3]);
            if q < 0.7 {
                continue;
            }
            checked += 1;
            let sine = SINE_SCALE * min_sine(&t[0], &t[1], &t[2], &t[3]);
            assert!(sine > q, "sine {sine} below mean ratio {q} for {t:?}");
            let sh = shape(&t[0], &t[1], &t[2], &t[3]);
            assert!((sh - q).abs() <= 1e-12, "{sh} vs {q}");
        }
        assert!(checked > 10_000, "{checked}");
    }
}
