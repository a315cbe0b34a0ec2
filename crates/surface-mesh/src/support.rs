//! The support surface as the mesher sees it: its triangles, their flattening, and two R-trees
//! (rstar) over them — one in 3D to project a point onto the support (closest point, with its
//! barycentric coordinates, hence its parameter), one in 2D to map a parameter point back onto
//! the support through the support triangle that contains it (exact `orient2d` containment).
//! A node built by `to_3d` lies on the support up to the rounding of one barycentric combination.

use super::param::{Param, ParamError, flatten};
use geom::closest::closest_on_triangle;
use geom::predicates::{dot, sub};
use geom::{Orientation, TriMesh, orient2d};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, PointDistance, RTree, RTreeObject};

/// A support triangle in 3D for nearest queries (coordinates relative to `Support::origin`).
struct Tri3 {
    p: [[f64; 3]; 3],
    id: u32,
}

impl RTreeObject for Tri3 {
    type Envelope = AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        let mut lo = self.p[0];
        let mut hi = self.p[0];
        for q in &self.p[1..] {
            for k in 0..3 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        AABB::from_corners(lo, hi)
    }
}

impl PointDistance for Tri3 {
    fn distance_2(&self, x: &[f64; 3]) -> f64 {
        let (q, _) = closest_on_triangle(x, &self.p[0], &self.p[1], &self.p[2]);
        let d = sub(&q, x);
        dot(&d, &d)
    }
}

pub struct Support {
    pub mesh: TriMesh,
    pub param: Param,
    origin: [f64; 3],
    tree3: RTree<Tri3>,
    tree2: RTree<GeomWithData<Rectangle<[f64; 2]>, u32>>,
    /// Unit normal of each support triangle (for fold checks).
    pub normals: Vec<[f64; 3]>,
    /// Edge neighbours of each support triangle (`u32::MAX` on the border): for local walks.
    adj: Vec<[u32; 3]>,
}

/// Where a point lands on the support.
#[derive(Copy, Clone, Debug)]
pub struct OnSupport {
    pub tri: u32,
    pub xyz: [f64; 3],
    pub uv: [f64; 2],
    pub dist: f64,
}

impl Support {
    pub fn new(mesh: &TriMesh) -> Result<Support, ParamError> {
        let param = flatten(mesh)?;
        let origin = super::param::centre(mesh);
        let rel = |p: &[f64; 3]| sub(p, &origin);
        let tris3: Vec<Tri3> = mesh
            .triangles
            .iter()
            .enumerate()
            .map(|(i, t)| Tri3 {
                p: [
                    rel(&mesh.vertices[t[0] as usize]),
                    rel(&mesh.vertices[t[1] as usize]),
                    rel(&mesh.vertices[t[2] as usize]),
                ],
                id: i as u32,
            })
            .collect();
        let tris2: Vec<_> = mesh
            .triangles
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let a = param.uv[t[0] as usize];
                let b = param.uv[t[1] as usize];
                let c = param.uv[t[2] as usize];
                let lo = [a[0].min(b[0]).min(c[0]), a[1].min(b[1]).min(c[1])];
                let hi = [a[0].max(b[0]).max(c[0]), a[1].max(b[1]).max(c[1])];
                GeomWithData::new(Rectangle::from_corners(lo, hi), i as u32)
            })
            .collect();
        let normals = mesh.unit_normals();
        let mut edges: std::collections::BTreeMap<(u32, u32), u32> =
            std::collections::BTreeMap::new();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for i in 0..3 {
                edges.insert((tri[i], tri[(i + 1) % 3]), t as u32);
            }
        }
        // adj[t][i]: across the edge opposite corner i, i.e. (tri[i+1], tri[i+2]).
        let adj = mesh
            .triangles
            .iter()
            .map(|tri| {
                [0, 1, 2].map(|i| {
                    let (a, b) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                    edges.get(&(b, a)).copied().unwrap_or(u32::MAX)
                })
            })
            .collect();
        Ok(Support {
            adj,
            mesh: mesh.clone(),
            param,
            origin,
            tree3: RTree::bulk_load(tris3),
            tree2: RTree::bulk_load(tris2),
            normals,
        })
    }

    /// The closest support point to `x`, with its parameter.
    pub fn project(&self, x: &[f64; 3]) -> Option<OnSupport> {
        let xr = sub(x, &self.origin);
        let t = self.tree3.nearest_neighbor(xr)?;
        let (q, w) = closest_on_triangle(&xr, &t.p[0], &t.p[1], &t.p[2]);
        let d = sub(&q, &xr);
        let tri = self.mesh.triangles[t.id as usize];
        let uv = self.combine2(tri, w);
        let xyz = self.combine3(tri, w);
        Some(OnSupport {
            tri: t.id,
            xyz,
            uv,
            dist: dot(&d, &d).sqrt(),
        })
    }

    /// A closest point found by walking from support triangle `hint` across edges while the
    /// distance decreases: a local closest point, cheap for small moves (smoothing). Falls back
    /// to the global `project` if the walk runs long.
    pub fn project_from(&self, hint: u32, x: &[f64; 3]) -> Option<OnSupport> {
        if hint as usize >= self.mesh.triangles.len() {
            return self.project(x);
        }
        let xr = sub(x, &self.origin);
        let rel = |v: u32| sub(&self.mesh.vertices[v as usize], &self.origin);
        let eval = |t: u32| {
            let tri = self.mesh.triangles[t as usize];
            let (q, w) = closest_on_triangle(&xr, &rel(tri[0]), &rel(tri[1]), &rel(tri[2]));
            let d = sub(&q, &xr);
            (dot(&d, &d), w)
        };
        let mut t = hint;
        let (mut d2, mut w) = eval(t);
        for _ in 0..64 {
            let mut best: Option<(u32, f64, [f64; 3])> = None;
            for i in 0..3 {
                if w[i] > 0.0 {
                    continue;
                }
                let n = self.adj[t as usize][i];
                if n == u32::MAX {
                    continue;
                }
                let (dn, wn) = eval(n);
                if dn < d2 && best.is_none_or(|b| dn < b.1) {
                    best = Some((n, dn, wn));
                }
            }
            let Some((n, dn, wn)) = best else {
                let tri = self.mesh.triangles[t as usize];
                return Some(OnSupport {
                    tri: t,
                    xyz: self.combine3(tri, w),
                    uv: self.combine2(tri, w),
                    dist: d2.sqrt(),
                });
            };
            t = n;
            d2 = dn;
            w = wn;
        }
        self.project(x)
    }

    /// The closest support point, trying a walk from `hint` first and keeping it when it lands
    /// on the support to rounding (then it is the closest point, distance ~0); otherwise the
    /// global R-tree search.
    pub fn project_hinted(&self, hint: u32, x: &[f64; 3]) -> Option<OnSupport> {
        let eps = 1e-12 * (1.0 + x[0].abs().max(x[1].abs()).max(x[2].abs()));
        match self.project_from(hint, x) {
            Some(on) if on.dist <= eps => Some(on),
            _ => self.project(x),
        }
    }

    fn combine2(&self, t: [u32; 3], w: [f64; 3]) -> [f64; 2] {
        let a = self.param.uv[t[0] as usize];
        let b = self.param.uv[t[1] as usize];
        let c = self.param.uv[t[2] as usize];
        [
            w[0] * a[0] + w[1] * b[0] + w[2] * c[0],
            w[0] * a[1] + w[1] * b[1] + w[2] * c[1],
        ]
    }

    fn combine3(&self, t: [u32; 3], w: [f64; 3]) -> [f64; 3] {
        let a = &self.mesh.vertices[t[0] as usize];
        let b = &self.mesh.vertices[t[1] as usize];
        let c = &self.mesh.vertices[t[2] as usize];
        // Relative to the first corner, so UTM-sized coordinates keep their precision.
        let mut out = [0.0; 3];
        for k in 0..3 {
            out[k] = a[k] + w[1] * (b[k] - a[k]) + w[2] * (c[k] - a[k]);
        }
        out
    }

    /// The support point with parameter `uv`, if `uv` lies in the flattened support.
    pub fn to_3d(&self, uv: &[f64; 2]) -> Option<(u32, [f64; 3])> {
        let env = AABB::from_point(*uv);
        let mut best: Option<u32> = None;
        for it in self.tree2.locate_in_envelope_intersecting(env) {
            let t = self.mesh.triangles[it.data as usize];
            let a = &self.param.uv[t[0] as usize];
            let b = &self.param.uv[t[1] as usize];
            let c = &self.param.uv[t[2] as usize];
            if orient2d(a, b, uv) != Orientation::Negative
                && orient2d(b, c, uv) != Orientation::Negative
                && orient2d(c, a, uv) != Orientation::Negative
                && best.is_none_or(|x| it.data < x)
            {
                best = Some(it.data);
            }
        }
        let id = best?;
        let t = self.mesh.triangles[id as usize];
        let a = self.param.uv[t[0] as usize];
        let b = self.param.uv[t[1] as usize];
        let c = self.param.uv[t[2] as usize];
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        let w1 = ((uv[0] - a[0]) * (c[1] - a[1]) - (uv[1] - a[1]) * (c[0] - a[0])) / area;
        let w2 = ((b[0] - a[0]) * (uv[1] - a[1]) - (b[1] - a[1]) * (uv[0] - a[0])) / area;
        let w1 = w1.clamp(0.0, 1.0);
        let w2 = w2.clamp(0.0, 1.0 - w1);
        Some((id, self.combine3(t, [1.0 - w1 - w2, w1, w2])))
    }

    /// The local metric of the flattening at `uv`: the upper-triangular factor L of the first
    /// fundamental form M = JᵀJ = LᵀL of the support triangle containing `uv`, so that
    /// |L·d| is the 3D length of a small parameter step d. None outside the support.
    pub fn metric_at(&self, uv: &[f64; 2]) -> Option<[[f64; 2]; 2]> {
        let (id, _) = self.to_3d(uv)?;
        let t = self.mesh.triangles[id as usize];
        let a = self.param.uv[t[0] as usize];
        let b = self.param.uv[t[1] as usize];
        let c = self.param.uv[t[2] as usize];
        let e = [[b[0] - a[0], c[0] - a[0]], [b[1] - a[1], c[1] - a[1]]];
        let det = e[0][0] * e[1][1] - e[0][1] * e[1][0];
        if !(det.abs() > 0.0) {
            return None;
        }
        let inv = [
            [e[1][1] / det, -e[0][1] / det],
            [-e[1][0] / det, e[0][0] / det],
        ];
        let pa = &self.mesh.vertices[t[0] as usize];
        let f1 = sub(&self.mesh.vertices[t[1] as usize], pa);
        let f2 = sub(&self.mesh.vertices[t[2] as usize], pa);
        // J = F · E⁻¹ (3 × 2), columns j1, j2.
        let j1 = [0, 1, 2].map(|k| f1[k] * inv[0][0] + f2[k] * inv[1][0]);
        let j2 = [0, 1, 2].map(|k| f1[k] * inv[0][1] + f2[k] * inv[1][1]);
        let m11 = dot(&j1, &j1);
        let m12 = dot(&j1, &j2);
        let m22 = dot(&j2, &j2);
        let l11 = m11.sqrt();
        if !(l11 > 0.0) {
            return None;
        }
        let l12 = m12 / l11;
        let l22 = (m22 - l12 * l12).max(0.0).sqrt();
        if !(l22 > 0.0) {
            return None;
        }
        Some([[l11, l12], [0.0, l22]])
    }

    /// The origin used for relative coordinates (bounding-box centre).
    pub fn origin_of(mesh: &TriMesh) -> [f64; 3] {
        super::param::centre(mesh)
    }
}
