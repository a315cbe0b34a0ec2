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
}
