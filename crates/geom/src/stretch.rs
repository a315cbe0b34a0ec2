//! An affine stretch along one direction: the space in which a layer is meshed flat along it.
//! Affine, so it keeps incidences, planes and orientations; the meshers using it restore the
//! points they were given bit for bit and map only the points they make back.

/// A stretch by `factor` along the unit vector `axis`, about `origin`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stretch {
    pub axis: [f64; 3],
    pub factor: f64,
    pub origin: [f64; 3],
}

impl Stretch {
    fn scaled(&self, p: &[f64; 3], by: f64) -> [f64; 3] {
        let d = [0, 1, 2].map(|k| p[k] - self.origin[k]);
        let along: f64 = (0..3).map(|k| d[k] * self.axis[k]).sum();
        [0, 1, 2].map(|k| p[k] + (by - 1.0) * along * self.axis[k])
    }

    /// The point in the stretched space.
    pub fn apply(&self, p: &[f64; 3]) -> [f64; 3] {
        self.scaled(p, self.factor)
    }

    /// The point back in the model.
    pub fn undo(&self, p: &[f64; 3]) -> [f64; 3] {
        self.scaled(p, 1.0 / self.factor)
    }

    /// The unit normal in the stretched space of a plane whose unit normal is `n` in the model
    /// (normals take the inverse transpose: the part along the axis shrinks by `factor`).
    pub fn normal(&self, n: &[f64; 3]) -> [f64; 3] {
        let along: f64 = (0..3).map(|k| n[k] * self.axis[k]).sum();
        let m = [0, 1, 2].map(|k| n[k] + (1.0 / self.factor - 1.0) * along * self.axis[k]);
        let len = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        if len > 0.0 { m.map(|x| x / len) } else { m }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stretch_undone_returns_the_point_and_keeps_the_orthogonal_part() {
        let s = Stretch {
            axis: [0.0, 0.6, 0.8],
            factor: 4.0,
            origin: [500_000.0, 7_000_000.0, -1000.0],
        };
        let p = [500_123.5, 7_000_456.25, -1234.5];
        let q = s.apply(&p);
        let back = s.undo(&q);
        for k in 0..3 {
            assert!((back[k] - p[k]).abs() < 1e-6, "{back:?}");
        }
        // Along the axis the offset from the origin is four times as long, across it the same.
        let along = |x: &[f64; 3]| {
            (0..3)
                .map(|k| (x[k] - s.origin[k]) * s.axis[k])
                .sum::<f64>()
        };
        assert!((along(&q) - 4.0 * along(&p)).abs() < 1e-6);
        assert!((q[0] - p[0]).abs() < 1e-9);
    }

    #[test]
    fn a_normal_stays_normal_to_its_plane_in_the_stretched_space() {
        let s = Stretch {
            axis: [0.0, 0.6, 0.8],
            factor: 4.0,
            origin: [10.0, 20.0, 30.0],
        };
        // The plane through o spanned by u and v, with unit normal n.
        let (o, u, v): ([f64; 3], [f64; 3], [f64; 3]) =
            ([1.0, 2.0, 3.0], [1.0, 0.5, 0.0], [0.0, 1.0, 2.0]);
        let c = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let l = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        let m = s.normal(&c.map(|x| x / l));
        let at = |w: [f64; 3]| s.apply(&[0, 1, 2].map(|k| o[k] + w[k]));
        let (q0, qu, qv) = (s.apply(&o), at(u), at(v));
        for q in [qu, qv] {
            let d: f64 = (0..3).map(|k| (q[k] - q0[k]) * m[k]).sum();
            assert!(d.abs() < 1e-9, "{d}");
        }
        assert!(((0..3).map(|k| m[k] * m[k]).sum::<f64>() - 1.0).abs() < 1e-12);
    }
}
