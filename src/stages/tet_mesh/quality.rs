//! Shape measures of a tetrahedron, used to rank candidate apexes, to steer optimization and to
//! report. These are float *measures*: validity (is a tet inverted) is never decided from them —
//! that is `orient3d`'s job.

use crate::geom::predicates::{cross, dot, signed_volume, sub};

type P = [f64; 3];

/// Normalised mean ratio: `12·(3V)^(2/3) / Σ l²`, 1 for the regular tetrahedron, ≤ 0 for a flat or
/// inverted one (negative volumes give a negative value so rankings stay monotone).
pub fn mean_ratio(a: &P, b: &P, c: &P, d: &P) -> f64 {
    let v = signed_volume(a, b, c, d);
    let l2 = len2(&sub(b, a))
        + len2(&sub(c, a))
        + len2(&sub(d, a))
        + len2(&sub(c, b))
        + len2(&sub(d, b))
        + len2(&sub(d, c));
    if l2 <= 0.0 {
        return 0.0;
    }
    let m = 12.0 * (3.0 * v.abs()).powf(2.0 / 3.0) / l2;
    if v < 0.0 { -m } else { m }
}

#[inline]
fn len2(v: &P) -> f64 {
    dot(v, v)
}

/// The smallest of the six dihedral angles of `abcd`, in degrees.
pub fn min_dihedral_deg(a: &P, b: &P, c: &P, d: &P) -> f64 {
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
            [v[0] / l, v[1] / l, v[2] / l]
        } else {
            [0.0; 3]
        };
    }
    let mut min = 180.0f64;
    for i in 0..4 {
        for j in i + 1..4 {
            let cosang = -dot(&n[i], &n[j]);
            let ang = cosang.clamp(-1.0, 1.0).acos().to_degrees();
            min = min.min(ang);
        }
    }
    min
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
    fn a_flat_tetrahedron_has_mean_ratio_zero() {
        let q = mean_ratio(
            &[0.0; 3],
            &[1.0, 0.0, 0.0],
            &[0.0, 1.0, 0.0],
            &[1.0, 1.0, 0.0],
        );
        assert_eq!(q, 0.0);
    }
}
