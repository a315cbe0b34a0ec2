//! Cutting the surface along its chords: where chords of different intersections cross or
//! end on one another inside a triangle, which further points lie on each chord, the chord
//! pieces between those points, and the triangles that replace every touched triangle.

use super::super::key::Location;
use super::super::locate::{project, projection_axis};
use super::super::polygon::improve;
use super::points::Surface;
use super::{
    Chord, SplitError, along_edge_xyz, arrangement, crossing_xyz, find_mesh, on_open_segment,
    symbolic, tri_of, triangulate,
};
use geom::TriMesh;
use std::collections::BTreeMap;

/// The chord pieces inside each original triangle, as sorted vertex pairs.
type Pieces = BTreeMap<u32, Vec<[u32; 2]>>;

/// The runs of `chords` (sorted by triangle) in one triangle: (triangle, start, end).
fn triangle_runs(chords: &[Chord]) -> Vec<(u32, usize, usize)> {
    let mut runs = Vec::new();
    let mut start = 0;
    while start < chords.len() {
        let t = chords[start].t;
        let end = start + chords[start..].iter().take_while(|c| c.t == t).count();
        runs.push((t, start, end));
        start = end;
    }
    runs
}

/// The points on each original edge (by sorted corners) and inside each original face.
pub(super) struct Places {
    on_edge: BTreeMap<(u32, u32), Vec<u32>>,
    in_face: BTreeMap<u32, Vec<u32>>,
}

impl Places {
    /// The points on the edge between corners `a` and `b`, if any.
    fn edge(&self, a: u32, b: u32) -> Option<&Vec<u32>> {
        self.on_edge.get(&(a.min(b), a.max(b)))
    }
}

/// The curves being cut into the surface: its vertices so far, the chords, the points on each.
pub(super) struct Cut<'a> {
    pub(super) surface: Surface<'a>,
    /// The other surface of each intersection.
    pub(super) partner: Vec<&'a str>,
    pub(super) vertices: Vec<[f64; 3]>,
    /// Where each curve point's (and crossing's) vertex lies on the surface.
    pub(super) loc: BTreeMap<u32, Location>,
    pub(super) chords: Vec<Chord>,
    /// Points lying inside each chord (index into `chords`), unsorted.
    pub(super) on_chord: Vec<Vec<u32>>,
    /// Vertices created where chords of two intersections cross.
    pub(super) crossings: Vec<u32>,
}

impl Cut<'_> {
    /// Where chords of different intersections cross or end on one another inside a triangle.
    pub(super) fn cross_chords(&mut self) -> Result<(), SplitError> {
        let mut crossing_at: BTreeMap<Vec<(String, u32)>, u32> = BTreeMap::new();
        for (t, start, end) in triangle_runs(&self.chords) {
            let corners = tri_of(self.surface.mesh, t).ok_or_else(|| self.surface.bad(t))?;
            let multi = self.chords[start..end]
                .iter()
                .any(|c| c.other != self.chords[start].other);
            if multi {
                let Some((axis, _)) = projection_axis(&corners) else {
                    return Err(self.surface.unsupported(
                        t,
                        corners[0],
                        "a curve touches this zero-area triangle",
                    ));
                };
                self.t_junctions(t, start, end);
                self.crossings_in(t, start, end, axis, &mut crossing_at);
            }
        }
        Ok(())
    }

    /// The T-junctions among chords `start..end` of triangle `t`, known from provenance.
    fn t_junctions(&mut self, t: u32, start: usize, end: usize) {
        // An end of chord j inside the face lies on chord i when its point on j's surface (a
        // vertex, or an edge) lies in the plane of i's other face, or when chord i runs along an
        // edge of its other surface and that point is on an edge coplanar with it.
        let others = self.surface.others;
        for i in start..end {
            let ci = &self.chords[i];
            let Some(im) = find_mesh(others, self.partner[ci.other]) else {
                continue;
            };
            let Some(plane) = tri_of(im, ci.other_face) else {
                continue;
            };
            let ie = symbolic::partner_edge(ci.ends);
            let meets = |q: &TriMesh, at: Location| match (ie, at) {
                (Some(e), Location::Edge(a, b)) => symbolic::edges_coplanar(q, (a, b), im, e),
                _ => symbolic::lies_in_plane(q, at, &plane),
            };
            let vertices = &self.vertices;
            let (p0, p1) = (vertices[ci.v[0] as usize], vertices[ci.v[1] as usize]);
            let d = [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]];
            let along = |w: u32| {
                let x = vertices[w as usize];
                (x[0] - p0[0]) * d[0] + (x[1] - p0[1]) * d[1] + (x[2] - p0[2]) * d[2]
            };
            for cj in &self.chords[start..end] {
                let Some(q) =
                    find_mesh(others, self.partner[cj.other]).filter(|_| cj.other != ci.other)
                else {
                    continue;
                };
                for (&w, &at) in cj.v.iter().zip(&cj.ends) {
                    if !ci.v.contains(&w)
                        && self.loc.get(&w) == Some(&Location::Face(t))
                        && meets(q, at)
                        && along(w) > 0.0
                        && along(w) < along(ci.v[1])
                    {
                        self.on_chord[i].push(w);
                    }
                }
            }
        }
    }

    /// The crossings of chords `start..end` of triangle `t`, pairwise (projected along `axis`).
    fn crossings_in(
        &mut self,
        t: u32,
        start: usize,
        end: usize,
        axis: usize,
        crossing_at: &mut BTreeMap<Vec<(String, u32)>, u32>,
    ) {
        for i in start..end {
            for j in i + 1..end {
                let (ci, cj) = (&self.chords[i], &self.chords[j]);
                if ci.other == cj.other
                    || ci.v.iter().any(|v| cj.v.contains(v))
                    || self.on_chord[i].iter().any(|v| cj.v.contains(v))
                    || self.on_chord[j].iter().any(|v| ci.v.contains(v))
                {
                    continue;
                }
                let p = |v: u32| project(&self.vertices[v as usize], axis);
                match arrangement::crossing(p(ci.v[0]), p(ci.v[1]), p(cj.v[0]), p(cj.v[1])) {
                    // A touch is found later, as a point lying on a chord.
                    None | Some(false) => {}
                    Some(true) => {
                        let v = self.crossing_vertex(t, (i, j), (start, end), axis, crossing_at);
                        for k in [i, j] {
                            if !self.chords[k].v.contains(&v) {
                                self.on_chord[k].push(v);
                            }
                        }
                    }
                }
            }
        }
    }

    /// The vertex where chords `i` and `j` of `t` cross: the one of the same three faces, else
    /// the corner or chord end of `t` (chords `run`) whose coordinates it rounds to bit for bit
    /// (a crossing that close to a border point is that point: no float can tell them apart,
    /// and the other surfaces, building the same bits, weld to it too), else new.
    fn crossing_vertex(
        &mut self,
        t: u32,
        (i, j): (usize, usize),
        run: (usize, usize),
        axis: usize,
        crossing_at: &mut BTreeMap<Vec<(String, u32)>, u32>,
    ) -> u32 {
        let (ci, cj) = (&self.chords[i], &self.chords[j]);
        let s = &self.surface;
        let mut key = vec![
            (s.name.to_string(), t),
            (self.partner[ci.other].to_string(), ci.other_face),
            (self.partner[cj.other].to_string(), cj.other_face),
        ];
        key.sort();
        if let Some(&v) = crossing_at.get(&key) {
            return v;
        }
        let xyz = along_edge_xyz(ci, cj, &self.partner, s.others).unwrap_or_else(|| {
            crossing_xyz(
                &key,
                s.name,
                s.mesh,
                s.others,
                [ci.v, cj.v].map(|s| s.map(|v| self.vertices[v as usize])),
                axis,
            )
        });
        let tri = s.mesh.triangles[t as usize];
        let same = tri
            .into_iter()
            .chain(self.chords[run.0..run.1].iter().flat_map(|c| c.v))
            .find(|&w| self.vertices[w as usize] == xyz);
        if let Some(w) = same {
            crossing_at.insert(key, w);
            return w;
        }
        self.vertices.push(xyz);
        let v = self.vertices.len() as u32 - 1;
        crossing_at.insert(key, v);
        self.crossings.push(v);
        self.loc.insert(v, Location::Face(t));
        v
    }

    /// The points on each original edge, and inside each original face.
    pub(super) fn places(&self) -> Places {
        let mut on_edge: BTreeMap<(u32, u32), Vec<u32>> = BTreeMap::new();
        let mut in_face: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
        for (&v, &l) in &self.loc {
            match l {
                Location::Edge(i, j) => on_edge.entry((i, j)).or_default().push(v),
                Location::Face(t) => in_face.entry(t).or_default().push(v),
                Location::Vertex(_) => {}
            }
        }
        Places { on_edge, in_face }
    }

    /// The further points lying inside each chord, triangle by triangle.
    pub(super) fn points_on_chords(&mut self, places: &Places) -> Result<(), SplitError> {
        // The triangle's border points between its ends when it runs along an edge, else any
        // point of the triangle lying exactly on it.
        for (t, start, end) in triangle_runs(&self.chords) {
            self.points_on_chords_in(t, start, end, places)?;
        }
        Ok(())
    }

    /// As [`Self::points_on_chords`], for chords `start..end` of triangle `t`.
    fn points_on_chords_in(
        &mut self,
        t: u32,
        start: usize,
        end: usize,
        places: &Places,
    ) -> Result<(), SplitError> {
        let mesh = self.surface.mesh;
        let tri = mesh.triangles[t as usize];
        let corners = tri_of(mesh, t).ok_or_else(|| self.surface.bad(t))?;
        let Some((axis, _)) = projection_axis(&corners) else {
            return Err(self.surface.unsupported(
                t,
                corners[0],
                "a curve runs inside this zero-area triangle",
            ));
        };
        let loc = &self.loc;
        let sides = |v: u32| -> u8 {
            (0..3usize)
                .filter(|&k| {
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    v == a || v == b || loc.get(&v) == Some(&Location::Edge(a.min(b), a.max(b)))
                })
                .fold(0, |m, k| m | (1 << k))
        };
        let edge_of = |k: usize| places.edge(tri[k], tri[(k + 1) % 3]);
        let mut local: Vec<u32> = tri.to_vec();
        for k in 0..3 {
            local.extend(edge_of(k).into_iter().flatten());
        }
        local.extend(places.in_face.get(&t).into_iter().flatten());
        let vertices = &self.vertices;
        for (c, xs) in self.chords[start..end]
            .iter()
            .zip(&mut self.on_chord[start..end])
        {
            let common = sides(c.v[0]) & sides(c.v[1]);
            if let Some(k) = (0..3).find(|&k| common & (1 << k) != 0) {
                let (p, q) = (vertices[c.v[0] as usize], vertices[c.v[1] as usize]);
                let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
                let along = |v: u32| {
                    let x = vertices[v as usize];
                    (x[0] - p[0]) * d[0] + (x[1] - p[1]) * d[1] + (x[2] - p[2]) * d[2]
                };
                let len2 = along(c.v[1]);
                xs.extend(
                    edge_of(k)
                        .into_iter()
                        .flatten()
                        .filter(|&&w| along(w) > 0.0 && along(w) < len2),
                );
                continue;
            }
            let p = |v: u32| project(&vertices[v as usize], axis);
            let (p0, p1) = (p(c.v[0]), p(c.v[1]));
            for &w in &local {
                if !c.v.contains(&w) && on_open_segment(p0, p1, p(w)) {
                    xs.push(w);
                }
            }
        }
        Ok(())
    }

    /// The chord pieces between the points on each chord, per triangle and as sorted curve edges.
    pub(super) fn pieces(&mut self) -> (Pieces, Vec<[u32; 2]>) {
        let mut pieces: Pieces = BTreeMap::new();
        let mut curve_edges = Vec::new();
        let vertices = &self.vertices;
        for (c, xs) in self.chords.iter().zip(&mut self.on_chord) {
            let (p, q) = (vertices[c.v[0] as usize], vertices[c.v[1] as usize]);
            let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
            let along = |v: u32| {
                let x = vertices[v as usize];
                (x[0] - p[0]) * d[0] + (x[1] - p[1]) * d[1] + (x[2] - p[2]) * d[2]
            };
            xs.sort_by(|a, b| along(*a).total_cmp(&along(*b)).then(a.cmp(b)));
            xs.dedup();
            let chain: Vec<u32> = std::iter::once(c.v[0])
                .chain(xs.iter().copied())
                .chain(std::iter::once(c.v[1]))
                .collect();
            for w in chain.windows(2) {
                let e = [w[0].min(w[1]), w[0].max(w[1])];
                curve_edges.push(e);
                pieces.entry(c.t).or_default().push(e);
            }
        }
        curve_edges.sort_unstable();
        curve_edges.dedup();
        (pieces, curve_edges)
    }

    /// The new triangles and their parents: untouched ones kept, touched ones re-triangulated.
    pub(super) fn retriangulate(
        &self,
        places: &Places,
        pieces: &Pieces,
    ) -> Result<(Vec<[u32; 3]>, Vec<u32>), SplitError> {
        let mesh = self.surface.mesh;
        let mut triangles = Vec::with_capacity(mesh.triangles.len());
        let mut parent = Vec::with_capacity(mesh.triangles.len());
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let t = t as u32;
            let touched = pieces.contains_key(&t)
                || places.in_face.contains_key(&t)
                || (0..3).any(|k| places.edge(tri[k], tri[(k + 1) % 3]).is_some());
            if !touched {
                triangles.push(*tri);
                parent.push(t);
                continue;
            }
            for tr in self.split_triangle(t, *tri, places, pieces)? {
                triangles.push(tr);
                parent.push(t);
            }
        }
        Ok((triangles, parent))
    }

    /// The triangles replacing touched triangle `t`: constrained triangulation, or zero-area fan.
    fn split_triangle(
        &self,
        t: u32,
        tri: [u32; 3],
        places: &Places,
        pieces: &Pieces,
    ) -> Result<Vec<[u32; 3]>, SplitError> {
        let vertices = &self.vertices;
        let boundary = self.boundary_cycle(tri, places);
        let corners = [0, 1, 2].map(|k| vertices[tri[k] as usize]);
        let Some((axis, sign)) = projection_axis(&corners) else {
            // A zero-area triangle (skipped by `intersect`) with curve points on its edges:
            // fanned, so that its neighbours stay conforming.
            let fan = match pieces.contains_key(&t) || places.in_face.contains_key(&t) {
                true => None,
                false => triangulate::fan(&boundary),
            };
            return fan.ok_or_else(|| {
                self.surface.unsupported(
                    t,
                    corners[0],
                    "a curve runs inside this zero-area triangle",
                )
            });
        };
        let pt = |v: u32| project(&vertices[v as usize], axis);
        let err = |(what, v): triangulate::Refusal| {
            self.surface.unsupported(t, vertices[v as usize], what)
        };
        let segs = inner_pieces(&boundary, pieces.get(&t));
        let mut inner: Vec<u32> = segs
            .iter()
            .flatten()
            .copied()
            .filter(|v| !boundary.contains(v))
            .chain(places.in_face.get(&t).into_iter().flatten().copied())
            .collect();
        inner.sort_unstable();
        inner.dedup();
        let mut ct = triangulate::Ct::new(&boundary, &pt, sign).map_err(err)?;
        for v in inner {
            ct.insert_point(v).map_err(err)?;
        }
        for s in &segs {
            ct.insert_segment(s[0], s[1]).map_err(err)?;
        }
        let (mut local, locked) = ct.finish();
        improve(&mut local, &locked, &pt, sign);
        Ok(local)
    }

    /// The boundary cycle of `tri` in its own orientation, with the points on its edges in order.
    fn boundary_cycle(&self, tri: [u32; 3], places: &Places) -> Vec<u32> {
        let vertices = &self.vertices;
        let mut boundary = Vec::new();
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            boundary.push(a);
            if let Some(list) = places.edge(a, b) {
                let (pa, pb) = (vertices[a as usize], vertices[b as usize]);
                let d = [pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]];
                let mut along: Vec<(f64, u32)> = list
                    .iter()
                    .map(|&v| {
                        let p = vertices[v as usize];
                        (
                            (p[0] - pa[0]) * d[0] + (p[1] - pa[1]) * d[1] + (p[2] - pa[2]) * d[2],
                            v,
                        )
                    })
                    .collect();
                along.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
                boundary.extend(along.into_iter().map(|(_, v)| v));
            }
        }
        boundary
    }
}

/// The chord pieces of a triangle that are not pieces of its `boundary` cycle, sorted, unique.
fn inner_pieces(boundary: &[u32], pieces: Option<&Vec<[u32; 2]>>) -> Vec<[u32; 2]> {
    let m = boundary.len();
    // The first position of each boundary vertex, for lookups by binary search.
    let mut first: Vec<(u32, usize)> = boundary.iter().enumerate().map(|(i, &v)| (v, i)).collect();
    first.sort_unstable();
    first.dedup_by_key(|x| x.0);
    let position = |v: u32| {
        first
            .binary_search_by_key(&v, |x| x.0)
            .ok()
            .map(|k| first[k].1)
    };
    let mut segs: Vec<[u32; 2]> = pieces
        .map(|c| {
            c.iter()
                .copied()
                .filter(|s| {
                    let i = position(s[0]);
                    let j = position(s[1]);
                    match (i, j) {
                        (Some(i), Some(j)) => (i + 1) % m != j && (j + 1) % m != i,
                        _ => true,
                    }
                })
                .collect()
        })
        .unwrap_or_default();
    segs.sort_unstable();
    segs.dedup();
    segs
}
