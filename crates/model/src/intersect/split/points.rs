//! The curve points on the surface being split: the coordinates of each (built canonically
//! where the other surfaces' meshes are known), the vertex each becomes (points at one place
//! merged), and the chords, the curve segments inside each triangle between those vertices.

use super::super::CurvePoint;
use super::super::key::{Location, PointKey};
use super::{Chord, Intersection, Pt, Side, SplitError, arrangement, find_mesh, tri_of};
use geom::TriMesh;
use std::collections::BTreeMap;

/// The surface being split, with the other surfaces' meshes (by name).
pub(super) struct Surface<'a> {
    pub(super) name: &'a str,
    pub(super) mesh: &'a TriMesh,
    pub(super) others: &'a [(&'a str, &'a TriMesh)],
}

/// The new vertices of the surface and where each curve point went, as merged.
pub(super) struct Merged {
    /// Original vertices, then one per place of a new curve point.
    pub(super) vertices: Vec<[f64; 3]>,
    /// For each intersection, the vertex of each of its curve points.
    pub(super) vertex_of_each: Vec<BTreeMap<PointKey, u32>>,
    /// Where each curve point's vertex lies on the surface.
    pub(super) loc: BTreeMap<u32, Location>,
}

/// Vertex `v` of `m`, `None` on a bad index.
fn vert(m: &TriMesh, v: u32) -> Option<[f64; 3]> {
    m.vertices.get(v as usize).copied()
}

impl<'a> Surface<'a> {
    /// A reference to a triangle or vertex the surface does not have.
    pub(super) fn bad(&self, index: u32) -> SplitError {
        SplitError::BadIndex {
            surface: self.name.to_string(),
            index,
        }
    }

    /// A configuration the split does not handle, in triangle `t` near `at`.
    pub(super) fn unsupported(&self, t: u32, at: [f64; 3], what: &str) -> SplitError {
        SplitError::Unsupported {
            surface: self.name.to_string(),
            triangle: t,
            at,
            what: what.to_string(),
        }
    }

    /// Whether every triangle refers to existing vertices (the first that does not is the error).
    pub(super) fn check_triangles(&self) -> Result<(), SplitError> {
        let nv = self.mesh.vertices.len() as u32;
        for (t, tri) in self.mesh.triangles.iter().enumerate() {
            if tri.iter().any(|&v| v >= nv) {
                return Err(self.bad(t as u32));
            }
        }
        Ok(())
    }

    /// The curve points of every intersection on this surface, and each one's other surface.
    pub(super) fn curve_points<'x>(
        &self,
        intersections: &[(&'x Intersection, Side)],
    ) -> Result<(Vec<Pt>, Vec<&'x str>), SplitError> {
        let mut pts: Vec<Pt> = Vec::new();
        let mut partner: Vec<&str> = Vec::new();
        for (ix, &(x, side)) in intersections.iter().enumerate() {
            let (me, them) = if side == Side::A {
                (&x.a, &x.b)
            } else {
                (&x.b, &x.a)
            };
            if me != self.name {
                return Err(SplitError::WrongSurface {
                    surface: self.name.to_string(),
                    a: x.a.clone(),
                    b: x.b.clone(),
                });
            }
            partner.push(them);
            let om = find_mesh(self.others, them);
            for p in x.curves.iter().flat_map(|c| c.points.iter()) {
                let (la, lb) = (p.on_a, p.on_b);
                let (loc, oloc) = if side == Side::A { (la, lb) } else { (lb, la) };
                let xyz = self.canonical_xyz(p, loc, oloc, om)?;
                pts.push(Pt {
                    ix,
                    key: p.key,
                    loc,
                    oloc,
                    xyz,
                });
            }
        }
        Ok((pts, partner))
    }

    /// Coordinates of `p`: an edge crossing a face built from edge and plane, else as given.
    fn canonical_xyz(
        &self,
        p: &CurvePoint,
        loc: Location,
        oloc: Location,
        om: Option<&TriMesh>,
    ) -> Result<[f64; 3], SplitError> {
        let mesh = self.mesh;
        let xyz = match (loc, oloc, om) {
            (Location::Vertex(v), _, _) => vert(mesh, v).ok_or_else(|| self.bad(v))?,
            (Location::Edge(i, j), Location::Face(f), Some(om)) => {
                match (vert(mesh, i), vert(mesh, j), tri_of(om, f)) {
                    (Some(pi), Some(pj), Some(tf)) => {
                        arrangement::edge_plane(pi, pj, tf).unwrap_or(p.xyz)
                    }
                    _ => p.xyz,
                }
            }
            (Location::Face(t), Location::Edge(i, j), Some(om)) => {
                match (vert(om, i), vert(om, j), tri_of(mesh, t)) {
                    (Some(pi), Some(pj), Some(tf)) => {
                        arrangement::edge_plane(pi, pj, tf).unwrap_or(p.xyz)
                    }
                    _ => p.xyz,
                }
            }
            _ => p.xyz,
        };
        Ok(xyz)
    }

    /// The vertex of each curve point: one per place (a vertex, or edge or face and exact bits).
    pub(super) fn merge(&self, pts: &[Pt], n_intersections: usize) -> Result<Merged, SplitError> {
        let mesh = self.mesh;
        let nv = mesh.vertices.len() as u32;
        let place = |p: &Pt| -> (Location, [u64; 3]) {
            match p.loc {
                Location::Vertex(_) => (p.loc, [0; 3]),
                _ => (p.loc, p.xyz.map(f64::to_bits)),
            }
        };
        let mut vertices = mesh.vertices.clone();
        let mut at_place: BTreeMap<(Location, [u64; 3]), u32> = BTreeMap::new();
        let mut order: Vec<&Pt> = pts.iter().collect();
        order.sort_by_key(|p| place(p));
        for p in order {
            let k = place(p);
            if at_place.contains_key(&k) {
                continue;
            }
            let v = match p.loc {
                Location::Vertex(v) if v < nv => v,
                Location::Vertex(v) => return Err(self.bad(v)),
                Location::Edge(i, j) if i >= nv || j >= nv => return Err(self.bad(i.max(j))),
                Location::Face(t) if t as usize >= mesh.triangles.len() => {
                    return Err(self.bad(t));
                }
                _ => {
                    vertices.push(p.xyz);
                    vertices.len() as u32 - 1
                }
            };
            at_place.insert(k, v);
        }
        let mut vertex_of_each: Vec<BTreeMap<PointKey, u32>> =
            vec![BTreeMap::new(); n_intersections];
        let mut loc: BTreeMap<u32, Location> = BTreeMap::new();
        for p in pts {
            if let Some(&v) = at_place.get(&place(p)) {
                vertex_of_each[p.ix].insert(p.key, v);
                loc.insert(v, p.loc);
            }
        }
        Ok(Merged {
            vertices,
            vertex_of_each,
            loc,
        })
    }

    /// The chords, sorted by triangle, one per vertex pair (the other surface's name breaks ties).
    pub(super) fn chords(
        &self,
        intersections: &[(&Intersection, Side)],
        vertex_of_each: &[BTreeMap<PointKey, u32>],
        partner: &[&str],
    ) -> Result<Vec<Chord>, SplitError> {
        let mut chords: Vec<Chord> = Vec::new();
        for (ix, &(x, side)) in intersections.iter().enumerate() {
            for c in &x.curves {
                let n = c.points.len();
                for (s, &(ta, tb)) in c.segments_faces.iter().enumerate() {
                    let (Some(p), Some(q)) = (c.points.get(s), c.points.get((s + 1) % n.max(1)))
                    else {
                        continue;
                    };
                    let map = &vertex_of_each[ix];
                    let (Some(&vp), Some(&vq)) = (map.get(&p.key), map.get(&q.key)) else {
                        continue;
                    };
                    if vp == vq {
                        continue;
                    }
                    let (t, of) = if side == Side::A { (ta, tb) } else { (tb, ta) };
                    if t as usize >= self.mesh.triangles.len() {
                        return Err(self.bad(t));
                    }
                    let oloc = |c: &CurvePoint| if side == Side::A { c.on_b } else { c.on_a };
                    chords.push(Chord {
                        t,
                        v: [vp, vq],
                        other: ix,
                        other_face: of,
                        ends: [oloc(p), oloc(q)],
                    });
                }
            }
        }
        // Ties (one segment in two intersections) are broken by the other surface's name, not
        // by the order the intersections were given in.
        chords.sort_by(|c, d| {
            let k = |c: &Chord| (c.t, c.v[0].min(c.v[1]), c.v[0].max(c.v[1]));
            k(c).cmp(&k(d))
                .then_with(|| partner[c.other].cmp(partner[d.other]))
                .then(c.other_face.cmp(&d.other_face))
        });
        chords.dedup_by_key(|c| (c.t, c.v[0].min(c.v[1]), c.v[0].max(c.v[1])));
        Ok(chords)
    }
}
