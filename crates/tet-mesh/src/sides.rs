//! Which side of a candidate tetrahedron's four face planes each nearby front node lies on,
//! decided once per node and candidate by the exact `orient3d` and shared by every front face
//! around the node. The validity test of a candidate reads these signs for three things: a front
//! face strictly outside one plane is skipped, a node on no plane's outer side is inside the
//! closed tet, and the signs against a new face's plane are the first step of the exact
//! triangle-triangle test.

use geom::predicates::Orientation;

use super::exact::orient3d;

type P = [f64; 3];

/// Per-node signs for the current candidate, valid while the node's stamp equals the current
/// generation (so nothing is cleared between candidates).
#[derive(Default)]
pub struct SideCache {
    stamp: Vec<u32>,
    sign: Vec<[i8; 4]>,
    generation: u32,
}

impl SideCache {
    /// Forget every cached sign (a new candidate) and make room for `n` nodes.
    pub fn start(&mut self, n: usize) {
        if self.stamp.len() < n {
            self.stamp.resize(n, 0);
            self.sign.resize(n, [0; 4]);
        }
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.generation = 1;
        }
    }

    /// Signs of node `w` against the outward planes `planes` of the positive tet `tet`: +1 strictly
    /// outside, 0 on the plane, -1 strictly inside. A vertex of the tet is 0 on the three planes
    /// through it and -1 on the fourth, by construction (no predicate needed).
    pub fn of(&mut self, w: u32, tet: &[u32; 4], planes: &[[u32; 3]; 4], pts: &[P]) -> [i8; 4] {
        if tet.contains(&w) {
            return planes.map(|f| if f.contains(&w) { 0 } else { -1 });
        }
        let i = w as usize;
        if self.stamp[i] == self.generation {
            return self.sign[i];
        }
        let p = &pts[i];
        let s = planes.map(|f| {
            orient3d(
                &pts[f[0] as usize],
                &pts[f[1] as usize],
                &pts[f[2] as usize],
                p,
            )
            .sign() as i8
        });
        self.stamp[i] = self.generation;
        self.sign[i] = s;
        s
    }
}

/// The `Orientation` of a sign from `SideCache::of`.
#[inline]
pub fn orientation_of(s: i8) -> Orientation {
    match s {
        1 => Orientation::Positive,
        -1 => Orientation::Negative,
        _ => Orientation::Zero,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::verify::outward_faces;

    #[test]
    fn signs_against_a_tets_planes_match_the_predicate_and_are_fresh_for_each_candidate() {
        let mut pts: Vec<P> = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.2, 0.2, 0.2],  // inside
            [2.0, 2.0, 2.0],  // outside the slanted face only
            [0.5, 0.5, 0.0],  // on the base plane and the slanted one
            [0.0, 0.0, -1.0], // below the base, on two side planes
            [0.3, 0.3, 0.6],  // just outside the slanted face
        ];
        let tet = [0, 1, 2, 3];
        let planes = outward_faces(tet);
        let mut cache = SideCache::default();
        cache.start(pts.len());
        assert_eq!(cache.of(4, &tet, &planes, &pts), [-1, -1, -1, -1]);
        assert_eq!(cache.of(5, &tet, &planes, &pts), [-1, -1, 1, -1]);
        assert_eq!(cache.of(6, &tet, &planes, &pts), [0, -1, 0, -1]);
        assert_eq!(cache.of(7, &tet, &planes, &pts), [1, 0, -1, 0]);
        assert_eq!(cache.of(8, &tet, &planes, &pts), [-1, -1, 1, -1]);
        // A tet vertex: on the three planes through it, inside the fourth.
        assert_eq!(cache.of(3, &tet, &planes, &pts), [-1, 0, 0, 0]);
        for w in 4..9u32 {
            let s = cache.of(w, &tet, &planes, &pts);
            for (k, f) in planes.iter().enumerate() {
                let o = orient3d(
                    &pts[f[0] as usize],
                    &pts[f[1] as usize],
                    &pts[f[2] as usize],
                    &pts[w as usize],
                );
                assert_eq!(orientation_of(s[k]), o, "node {w} plane {k}");
            }
        }
        // A new candidate (another tet over the same nodes) must not see the old signs.
        pts.push([0.0, 0.0, 2.0]);
        let tet2 = [0, 1, 2, 9];
        let planes2 = outward_faces(tet2);
        cache.start(pts.len());
        assert_eq!(cache.of(8, &tet2, &planes2, &pts)[2], -1);
    }
}
