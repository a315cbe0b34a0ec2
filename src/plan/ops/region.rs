//! `tet_mesh:<r>` and `mesh`: one region filled with tetrahedra from the FE meshes of the patches
//! that bound it (sides known from the model, carried as parameters), and the final volume mesh
//! welded from all regions with every patch's triangles in its surface's group, the wells' edges
//! as line groups and the wells' crossings of the surfaces as named points.
//!
//! A crossing's name is `<well>:<surface>` (`:2`, `:3`, ... when the well crosses the same
//! surface again, in path order): the surface, not the patch, because the analyst knows the
//! horizons and faults of the recipe, not the pieces the model cut them into. Its node is found
//! by exact coordinates, as the wells' edges are: the cut put the crossing into the patch's
//! surface mesh bit for bit and welding keeps coordinates, so a crossing that is not a node of
//! the mesh is a broken invariant, reported by well and surface.

use super::aspect::Layer;
use super::wells::{RegionWells, WellCutData};
use super::{Groups, PatchMesh};
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::mesh::{LineGroup, NamedPoint, RegionGroup, VolumeMesh};
use geom::point_key;
use model::regions::{FaceUse, Side};
use model::{
    FaceToFace, VolumeAssembly, assemble_volume, drop_pinched_faces, edge_clash, embed_polylines,
    face_to_face, patch_crossing, region_input,
};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use tet_mesh::stretch::{mesh_region_stretched, stretched_quality};
use tet_mesh::{Method, SizeField, TetMeshOptions, mesh_region_with_progress};

/// The output of `tet_mesh:<r>`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RegionMesh {
    pub name: String,
    /// The boundary nodes first (as welded from the patch meshes), then the interior nodes.
    pub nodes: Vec<[f64; 3]>,
    /// Positive tets.
    pub tets: Vec<[u32; 4]>,
    /// Per well crossing the region (by name), its edges: the chains of tet edges its pieces
    /// became.
    pub wells: Vec<(String, Vec<[u32; 2]>)>,
}

/// `tet_mesh:<r>`: inputs are `surface_mesh:<p>` for every patch in `patches`, then
/// `wells_in:<r>` when the recipe has wells, then the refinements.
pub struct TetMeshOp {
    pub name: String,
    /// The distinct patches bounding the region, in model order.
    pub patches: Vec<String>,
    /// Per patch, whether its surface is smoothed (`smooth`): for the advice of an error only.
    pub smoothed: Vec<bool>,
    /// Face-uses, `patch` indexing `patches`; a dangling patch appears with both sides.
    pub sides: Vec<FaceUse>,
    /// Recipe path of the size rule (`mesh.regions.<r>` or `mesh`).
    pub size_path: String,
    pub size: SizeField,
    /// `tet_method` at `size_path`; in the key only when it is not the default, so recipes that
    /// do not name it keep their keys.
    pub method: Method,
    /// How many `refine:<k>` inputs follow the patch meshes (features within reach).
    pub refinements: usize,
    /// Whether `wells_in:<r>` follows the patch meshes.
    pub wells: bool,
    /// With an `aspect`, the layer it is meshed stretched across (in the key only then).
    pub layer: Option<Layer>,
}

/// The surface of the patch named `patch` (`<surface>#<k>`).
fn surface_of(patch: &str) -> &str {
    patch.rsplit_once('#').map_or(patch, |(s, _)| s)
}

impl TetMeshOp {
    /// The names of the two patches `f` is about.
    fn patch_names(&self, f: &FaceToFace) -> [&str; 2] {
        f.patches
            .map(|p| self.patches.get(p as usize).map_or("?", String::as_str))
    }

    /// Says in recipe terms that two of the region's patches lie on each other.
    fn face_to_face_error(&self, f: &FaceToFace) -> String {
        let [a, b] = self.patch_names(f);
        let smoothed = (f.patches.iter()).any(|&p| self.smoothed.get(p as usize) == Some(&true));
        let [x, y, z] = f.at;
        let [sa, sb] = [a, b].map(surface_of);
        let cause = if smoothed {
            "two surfaces that touch in the files can cross once `smooth` refines them between \
             the files' vertices: smooth neither of the two surfaces, or part them in the data"
        } else {
            "the two surfaces touch over an area there in the files (or come closer than their \
             meshes can part): part them in the data there"
        };
        let cause = format!(
            "{cause}, or, where one is drawn along the other over a patch, drop that patch: a \
             `[[trim]]` with `surface = \"{sa}\"` and `discard = {{ nearest = [{x:.1}, {y:.1}, \
             {z:.1}] }}` drops `{a}` (with `surface = \"{sb}\"`, `{b}`), and `discard = {{ \
             within = d }}` (d the gap) drops every patch of the surface that lies within d of \
             another surface all over{}",
            if smoothed {
                String::new()
            } else {
                self.refine_advice(a, b)
            }
        );
        format!(
            "region `{}`: patches `{a}` and `{b}` lie on each other at ({x:.1}, {y:.1}, {z:.1}) \
             (their meshes share a triangle), so the region has no thickness there; {cause}",
            self.name
        )
    }
}

impl TetMeshOp {
    /// Says in recipe terms that two of the region's patches bound it from one side of an edge.
    fn edge_clash_error(&self, c: &FaceToFace) -> String {
        let [a, b] = self.patch_names(c);
        let [x, y, z] = c.at;
        let cause = if surface_of(a) == surface_of(b) {
            format!("`{}` folds onto itself along a line there", surface_of(a))
        } else {
            "the two surfaces cross or meet along a line there".to_string()
        };
        format!(
            "region `{}`: patches `{a}` and `{b}` both bound it from the same side of an edge at \
             ({x:.1}, {y:.1}, {z:.1}) (their meshes run the edge the same way), so the region \
             touches itself along it: {cause}, with nothing between; part the surfaces there in \
             the data, or trim one of them",
            self.name
        )
    }
}

impl TetMeshOp {
    /// Says in recipe terms that the meshes of two of the region's patches cross.
    fn crossing_error(&self, c: &FaceToFace) -> String {
        let [a, b] = self.patch_names(c);
        let [x, y, z] = c.at;
        format!(
            "region `{}`: the meshes of patches `{a}` and `{b}` cross at ({x:.1}, {y:.1}, \
             {z:.1}): the two surfaces meet at a small angle there (or cross in the files), and \
             their meshes, each within its tolerance of its own surface, {CROSSING}; part the \
             surfaces there in the data{}",
            self.name,
            self.refine_advice(a, b)
        )
    }

    /// Where patches `a` and `b` of two surfaces come together, the `[[mesh.refine]]` entry that
    /// lets their meshes part: a tenth of the region's size along the curves where the surfaces
    /// meet, growing back over twice that size. Nothing for two patches of one surface.
    fn refine_advice(&self, a: &str, b: &str) -> String {
        let (sa, sb) = (surface_of(a), surface_of(b));
        if sa == sb {
            return String::new();
        }
        let size = self.size.size;
        format!(
            "; or, where they meet at a small angle (an onlap, a pinch-out), refine where they \
             meet so that their meshes part: {}",
            AdvisedRefinement {
                curve: format!("{sa}/{sb}"),
                size: size / 10.0,
                distance: 2.0 * size,
            }
            .advice()
        )
    }
}

/// The `[[mesh.refine]]` entry a region's error advises where the meshes of two surfaces cross:
/// the curves where they meet (a curve selector), the size there and the distance it grows back
/// over. The build adds it and tries again ([`AdvisedRefinement::of_crossing`] reads it back).
#[derive(Clone, Debug, PartialEq)]
pub struct AdvisedRefinement {
    pub curve: String,
    pub size: f64,
    pub distance: f64,
}

impl AdvisedRefinement {
    const CURVE: &str = "`[[mesh.refine]]` with `curve = \"";
    const SIZE: &str = "\"`, `size = ";
    const DISTANCE: &str = "` and `distance = ";

    /// As the error words it (sizes to three significant digits).
    fn advice(&self) -> String {
        format!(
            "{}{}{}{}{}{}`",
            Self::CURVE,
            self.curve,
            Self::SIZE,
            three_digits(self.size),
            Self::DISTANCE,
            three_digits(self.distance)
        )
    }

    /// The refinement a region's error advises because the meshes of two of its patches cross,
    /// if it is such an error.
    pub fn of_crossing(error: &str) -> Option<Self> {
        if !error.contains(CROSSING) {
            return None;
        }
        let rest = &error[error.find(Self::CURVE)? + Self::CURVE.len()..];
        let (curve, rest) = rest.split_once(Self::SIZE)?;
        let (size, rest) = rest.split_once(Self::DISTANCE)?;
        let distance = &rest[..rest.find('`')?];
        Some(AdvisedRefinement {
            curve: curve.to_string(),
            size: size.parse().ok()?,
            distance: distance.parse().ok()?,
        })
    }
}

/// What names an error about the meshes of two patches crossing.
const CROSSING: &str = "pass through each other";

/// `x` to three significant digits, written without trailing zeros.
fn three_digits(x: f64) -> String {
    if !x.is_finite() || x == 0.0 {
        return format!("{x}");
    }
    let scale = 10f64.powi(2 - x.abs().log10().floor() as i32);
    format!("{}", (x * scale).round() / scale)
}

impl Operation for TetMeshOp {
    fn kind(&self) -> &'static str {
        "tet_mesh"
    }
    /// A region mesh is read only by `mesh` when it re-runs.
    fn lazy_output(&self) -> bool {
        true
    }
    fn version(&self) -> u32 {
        // 6: Delaunay meshing with local recovery (the front as hole filler and fallback).
        // 7: floating-point location walks; flips and contractions up to 0.8 in thin layers.
        // 8: refinement drops points whose tet is gone; tets and nodes laid out along a Hilbert
        //    curve (16 bits per axis) before optimization.
        // 9: the optimizer flips before it relaxes (no relaxation or smoothing before the
        //    rounds) except in thin layers; layers without free nodes close with 3-2 and 4-4
        //    flips for the average; a bad tet's edges removed longest first; refinement
        //    proposals made as tets are created.
        // 10: cavities grow breadth first (their tets, hence slots, come in another order).
        // 11: the size field by two raster sweeps; the layout sorts the nodes and buckets the
        //     tets by their highest node.
        // 12: missing boundary triangles recovered by flips (2-3, edge removal) before any hole.
        // 13: holes whose front gets stuck are widened round the stuck place and filled again.
        // 14: the wells' edges in the output.
        // 15: recovery holes filled by their own Delaunay tetrahedralization or a cone first.
        // 16: hole pieces with embedded triangles filled apart, each with its own.
        // 17: a hole's embedded triangles peeled off by a tet each before the cone.
        // 18: at most 16 apexes tried per peeled triangle.
        // 19: background size cells hold the size at their centre, not the least in them.
        // 20: the optimizer inserts nodes for tets below shape 0.5 (was 0.35).
        // 21: the front on a recovery hole smaller than the region has a budget of its own.
        // 22: holes widened over half the region (not all of it) get no front of their own.
        // 23: the optimizer's insertions share tries set by its first round's list.
        // 24: no front on the whole region after Delaunay gave way where the boundary is pinched.
        // 25: the recovery of a pinched region stops widening its holes past a bound of work.
        // 26: widened holes are tried again once grown by half, while under half the region.
        // 27: the check of the tets' volume allows the sums' rounding (thin regions).
        // 28: a front that keeps back-tracking near its end is closed by the Delaunay method.
        // 29: closing is tried again after twice as many back-tracks, and widens at most 512 faces.
        // 30: a closing try that fails leaves the front as it was.
        // 31: the front on the whole region after Delaunay gave way has a budget of its own.
        // 32: a region's fronts may spend half as much whatever its size.
        // 33: a thin layer's flips and contractions act on tets up to shape 0.6, not 0.8.
        // 34: a region round a pinch keeps the pinched triangle as a face inside it.
        // 35: a missing triangle's coplanar wrong diagonal is flipped whatever holds the quad's
        //     other half (a chequerboard's gap, not only a neighbouring triangle).
        35
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        p.set("region", self.name.as_str()).expect("string");
        let sides: Vec<String> = self
            .sides
            .iter()
            .map(|f| {
                let side = if f.side == Side::Front {
                    "front"
                } else {
                    "back"
                };
                format!("{}:{side}", self.patches[f.patch as usize])
            })
            .collect();
        p.set("sides", sides).expect("strings");
        let path = &self.size_path;
        p.set(&format!("{path}.size"), self.size.size)
            .expect("validated finite");
        p.set(&format!("{path}.min_size"), self.size.min_size)
            .expect("validated finite");
        p.set(&format!("{path}.max_size"), self.size.max_size)
            .expect("validated finite");
        p.set(&format!("{path}.growth"), self.size.growth)
            .expect("validated finite");
        if self.method != Method::default() {
            p.set(&format!("{path}.tet_method"), self.method.name())
                .expect("string");
        }
        if let Some(l) = &self.layer {
            let at = format!("mesh.regions.{}", self.name);
            p.set(&format!("{at}.aspect"), l.aspect)
                .expect("validated finite");
            p.set(&format!("{at}.aspect_normal"), l.normal.to_vec())
                .expect("finite");
        }
        p
    }
    fn run(&self, ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let (inputs, refine) = super::refine::split_refinements(inputs, self.refinements)?;
        let (inputs, wells) = match (self.wells, inputs.split_last()) {
            (true, Some((w, rest))) => (rest, w.decode::<RegionWells>()?),
            _ => (inputs, RegionWells::default()),
        };
        let meshes: Vec<PatchMesh> = inputs
            .iter()
            .map(|a| a.decode())
            .collect::<Result<_, _>>()?;
        if meshes.len() != self.patches.len() {
            return Err(format!("tet_mesh:{} needs the meshes of its patches", self.name).into());
        }
        let get = |p: u32| meshes.get(p as usize).map(|m| &m.mesh);
        let mut input = region_input(&self.name, &self.sides, &get)
            .map_err(|e| OpError::from(e.to_string()))?;
        let pinched = drop_pinched_faces(&mut input);
        let pieces: Vec<Vec<[f64; 3]>> = wells.wells.iter().flat_map(|(_, p)| p.clone()).collect();
        let ranges = embed_polylines(&mut input, &pieces);
        let opts = TetMeshOptions {
            method: self.method,
            ..TetMeshOptions::default()
        };
        let size = SizeField {
            refine: refine.into_iter().chain(wells.refine.clone()).collect(),
            ..self.size.clone()
        };
        let progress = |done, total| ctx.progress(done, total);
        // Two patches lying on each other or crossing fail the mesher's input check; only then
        // is it worth finding which, to say so in recipe terms.
        let meshed = match (&self.layer, input.vertices.first()) {
            (Some(l), Some(&origin)) => {
                mesh_region_stretched(&input, &size, &opts, &l.stretch(origin), &progress)
            }
            _ => mesh_region_with_progress(&input, &size, &opts, &progress),
        };
        let out = meshed.map_err(|e| {
            let said = (face_to_face(&self.sides, &get).map(|f| self.face_to_face_error(&f)))
                .or_else(|| edge_clash(&self.sides, &get).map(|c| self.edge_clash_error(&c)))
                .or_else(|| patch_crossing(&self.sides, &get).map(|c| self.crossing_error(&c)));
            OpError::from(said.unwrap_or_else(|| e.to_string()))
        })?;
        let well_edges = well_edges(&wells, &ranges, &out.lines);
        let (nn, nt) = (out.nodes.len() as u64, out.tets.len() as u64);
        let flat = (self.layer.as_ref().zip(input.vertices.first())).map(|(l, &origin)| {
            let (ratio, angle) = stretched_quality(&out.nodes, &out.tets, &l.stretch(origin));
            format!(
                "region `{}` is meshed {} times as wide along its layer as across it (`aspect`): \
                 stretched by that across the layer its tets reach a mean ratio of {ratio:.3} and \
                 a dihedral angle of {angle:.1}°; the quality tables measure them as they are, flat",
                self.name, l.aspect
            )
        });
        let out = Output::new(Artifact::encode(&RegionMesh {
            name: self.name.clone(),
            nodes: out.nodes,
            tets: out.tets,
            wells: well_edges,
        })?)
        .count("nodes", nn)
        .count("tets", nt);
        let out = match flat {
            Some(note) => out.note(note),
            None => out,
        };
        Ok(match pinched.first() {
            Some(&[x, y, z]) => out
                .count("pinched_triangles", pinched.len() as u64)
                .note(format!(
                    "region `{}` closes to nothing across {} triangle(s) where two of its patches' \
                 meshes are one and the same, first at ({x:.1}, {y:.1}, {z:.1}): its sides come \
                 closer there than their meshes can part, so the regions beyond them meet \
                 directly",
                    self.name,
                    pinched.len()
                )),
            None => out,
        })
    }
}

/// Per well, the tet edges its pieces became: `ranges` are the pieces' segments in the input's
/// lines (pieces in the order of `wells`), `chains` the nodes each segment became.
fn well_edges(
    wells: &RegionWells,
    ranges: &[std::ops::Range<usize>],
    chains: &[Vec<u32>],
) -> Vec<(String, Vec<[u32; 2]>)> {
    let mut ranges = ranges.iter();
    let mut out = Vec::with_capacity(wells.wells.len());
    for (name, pieces) in &wells.wells {
        let mut edges = Vec::new();
        for r in ranges.by_ref().take(pieces.len()) {
            for c in &chains[r.clone()] {
                edges.extend(c.windows(2).map(|w| [w[0], w[1]]));
            }
        }
        out.push((name.clone(), edges));
    }
    out
}

/// `mesh`: the regions' tets welded with the patches' triangles.
pub struct AssembleOp {
    /// Each region's group: name and the recipe's attributes.
    pub regions: Vec<RegionGroup>,
    /// The recipe's `[groups]`, in name order: each name and its patches' names, in model order.
    pub face_sets: Vec<(String, Vec<String>)>,
    /// The wells given a cross-section area, in name order.
    pub well_areas: Vec<(String, f64)>,
    /// `regions` (every `tet_mesh:<r>`, in the order of `regions`), `patches` (every
    /// `surface_mesh:<p>`, in model order) and, only when the recipe has wells, `wells` (every
    /// `well_cut:<w>`, in name order).
    pub inputs: Groups,
}

impl Operation for AssembleOp {
    fn kind(&self) -> &'static str {
        "mesh"
    }
    /// The volume mesh is read only by `export` when it re-runs and by the report's figures when
    /// they are not cached.
    fn lazy_output(&self) -> bool {
        true
    }
    fn version(&self) -> u32 {
        // 2: the wells' line elements.
        // 3: the wells' crossings of the surfaces as named points.
        // 4: the recipe's named face sets.
        // 5: the wells' stretches lying on a surface, among their edges.
        // 6: the wells' cross-section areas.
        6
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        for r in &self.regions {
            if let Some(m) = r.material {
                p.set(&format!("regions.{}.material", r.name), m)
                    .expect("int");
            }
            let props: BTreeMap<String, f64> = r.properties.clone();
            for (k, v) in props {
                p.set(&format!("regions.{}.{k}", r.name), v)
                    .expect("validated finite");
            }
        }
        for (name, patches) in &self.face_sets {
            p.set(&format!("groups.{name}"), patches.clone())
                .expect("strings");
        }
        for (name, area) in &self.well_areas {
            p.set(&format!("wells.{name}.area"), *area)
                .expect("validated finite");
        }
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let regions: Vec<RegionMesh> = self.inputs.decode("regions", inputs)?;
        if regions.len() != self.regions.len() {
            return Err("mesh needs one tet mesh per region".into());
        }
        let patches: Vec<PatchMesh> = self.inputs.decode("patches", inputs)?;
        let face_sets = face_set_patches(&self.face_sets, &patches)?;
        let parts = VolumeAssembly {
            regions: self
                .regions
                .iter()
                .zip(&regions)
                .map(|(g, r)| (g.clone(), r.nodes.as_slice(), r.tets.as_slice()))
                .collect(),
            patches: patches
                .iter()
                .map(|p| (p.surface.as_str(), p.kind, &p.mesh))
                .collect(),
            face_sets,
        };
        let mut mesh: VolumeMesh =
            assemble_volume(&parts).map_err(|e| OpError::from(e.to_string()))?;
        if self.inputs.len("wells") > 0 {
            let cuts: Vec<WellCutData> = self.inputs.decode("wells", inputs)?;
            mesh.lines = well_lines(&mesh.nodes, &regions, &cuts)?;
            for g in &mut mesh.lines {
                g.area = (self.well_areas.iter())
                    .find(|(w, _)| *w == g.name)
                    .map(|(_, a)| *a);
            }
            mesh.points = well_points(&mesh.nodes, &cuts)?;
        }
        let (nn, nt, nf) = (
            mesh.nodes.len() as u64,
            mesh.tets.len() as u64,
            mesh.triangles.len() as u64,
        );
        Ok(Output::new(Artifact::encode(&mesh)?)
            .count("nodes", nn)
            .count("tets", nt)
            .count("triangles", nf))
    }
}

/// The face sets with their patches as indices into `patches` (found by name).
fn face_set_patches(
    sets: &[(String, Vec<String>)],
    patches: &[PatchMesh],
) -> Result<Vec<(String, Vec<usize>)>, OpError> {
    let index: BTreeMap<&str, usize> = (patches.iter().enumerate())
        .map(|(i, p)| (p.name.as_str(), i))
        .collect();
    let find = |set: &str, p: &String| {
        index.get(p.as_str()).copied().ok_or_else(|| {
            OpError::from(format!(
                "mesh: group `{set}` names patch `{p}`, which has no mesh"
            ))
        })
    };
    (sets.iter())
        .map(|(name, ps)| {
            Ok((
                name.clone(),
                ps.iter().map(|p| find(name, p)).collect::<Result<_, _>>()?,
            ))
        })
        .collect()
}

/// The wells' crossings of the surfaces as named points of the welded mesh (nodes found by
/// exact coordinates), `<well>:<surface>` then `:2`, `:3`, ... for the same well crossing the
/// same surface again in path order; sorted by name.
fn well_points(nodes: &[[f64; 3]], cuts: &[WellCutData]) -> Result<Vec<NamedPoint>, OpError> {
    let ids: BTreeMap<[u64; 3], u32> = (nodes.iter().enumerate())
        .map(|(i, p)| (point_key(p), i as u32))
        .collect();
    let mut points = Vec::new();
    for cut in cuts {
        let mut seen: BTreeMap<&str, usize> = BTreeMap::new();
        for m in &cut.markers {
            let k = seen.entry(m.surface.as_str()).or_default();
            *k += 1;
            let name = match *k {
                1 => format!("{}:{}", cut.name, m.surface),
                k => format!("{}:{}:{k}", cut.name, m.surface),
            };
            let node = ids.get(&point_key(&m.point)).copied().ok_or_else(|| {
                OpError::from(format!(
                    "mesh: well `{}` crosses surface `{}` (patch `{}`) at ({}, {}, {}), which is \
                     not a node of the mesh",
                    cut.name, m.surface, m.patch, m.point[0], m.point[1], m.point[2]
                ))
            })?;
            points.push(NamedPoint { name, node });
        }
    }
    points.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(points)
}

/// The wells' edges in the welded mesh's numbering (nodes joined by exact coordinates), one
/// group per well in name order, its edges in region order then path order, then those of its
/// stretches lying on a surface (edges of that surface's mesh) in path order.
fn well_lines(
    nodes: &[[f64; 3]],
    regions: &[RegionMesh],
    cuts: &[WellCutData],
) -> Result<Vec<LineGroup>, OpError> {
    if regions.iter().all(|r| r.wells.is_empty()) && cuts.iter().all(|c| c.runs.is_empty()) {
        return Ok(Vec::new());
    }
    let key = point_key;
    let ids: BTreeMap<[u64; 3], u32> = (nodes.iter().enumerate())
        .map(|(i, p)| (key(p), i as u32))
        .collect();
    let mut groups: BTreeMap<&str, Vec<[u32; 2]>> = BTreeMap::new();
    for r in regions {
        let global = |v: u32| {
            let p = r.nodes.get(v as usize);
            p.and_then(|p| ids.get(&key(p))).copied().ok_or_else(|| {
                OpError::from(format!(
                    "mesh: a well edge of region `{}` ends at node {v}, which is not in the mesh",
                    r.name
                ))
            })
        };
        for (name, edges) in &r.wells {
            let g = groups.entry(name).or_default();
            for e in edges {
                g.push([global(e[0])?, global(e[1])?]);
            }
        }
    }
    for cut in cuts {
        for (patch, points) in &cut.runs {
            let node = |p: &[f64; 3]| {
                ids.get(&key(p)).copied().ok_or_else(|| {
                    OpError::from(format!(
                        "mesh: well `{}` runs along patch `{patch}` through ({}, {}, {}), which is \
                         not a node of the mesh",
                        cut.name, p[0], p[1], p[2]
                    ))
                })
            };
            let g = groups.entry(&cut.name).or_default();
            for w in points.windows(2) {
                g.push([node(&w[0])?, node(&w[1])?]);
            }
        }
    }
    Ok(groups
        .into_iter()
        .map(|(name, lines)| LineGroup {
            area: None,
            name: name.to_string(),
            lines,
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::ops::WellMarker;

    fn marker(surface: &str, point: [f64; 3]) -> WellMarker {
        WellMarker {
            patch: format!("{surface}#0"),
            surface: surface.into(),
            point,
            md: 0.0,
        }
    }

    fn cut(name: &str, markers: Vec<WellMarker>) -> WellCutData {
        WellCutData {
            name: name.into(),
            size: 1.0,
            markers,
            pieces: Vec::new(),
            runs: Vec::new(),
            pins: Vec::new(),
        }
    }

    #[test]
    fn a_well_crossing_a_surface_again_numbers_the_later_crossings_in_path_order() {
        let nodes = [
            [0.0, 0.0, 0.0],
            [0.0, 0.0, -1.0],
            [0.0, 0.0, -2.0],
            [1.0; 3],
        ];
        let cuts = [
            cut(
                "W2",
                vec![
                    marker("H1", [0.0, 0.0, -2.0]),
                    marker("F1", [1.0; 3]),
                    marker("H1", [0.0, 0.0, -1.0]),
                ],
            ),
            // -0.0 is the node at 0.0.
            cut("W1", vec![marker("H1", [-0.0, 0.0, 0.0])]),
        ];
        let points = well_points(&nodes, &cuts).unwrap();
        let got: Vec<(&str, u32)> = points.iter().map(|p| (p.name.as_str(), p.node)).collect();
        assert_eq!(
            got,
            [("W1:H1", 0), ("W2:F1", 3), ("W2:H1", 2), ("W2:H1:2", 1)]
        );
    }

    #[test]
    fn a_run_through_a_point_that_is_not_a_node_is_an_error_naming_the_well_and_the_patch() {
        let mut c = cut("W1", Vec::new());
        c.runs = vec![("H1#2".into(), vec![[0.0; 3], [0.5, 0.0, 0.0]])];
        let e = well_lines(&[[0.0; 3]], &[], &[c]).unwrap_err().to_string();
        assert!(e.contains("well `W1`") && e.contains("patch `H1#2`"), "{e}");
    }

    #[test]
    fn a_crossing_that_is_not_a_node_is_an_error_naming_the_well_and_the_surface() {
        let cuts = [cut("W1", vec![marker("H2", [0.5, 0.0, 0.0])])];
        let e = well_points(&[[0.0; 3]], &cuts).unwrap_err().to_string();
        assert!(e.contains("well `W1`") && e.contains("surface `H2`"), "{e}");
    }

    /// A region bounded by `H1#3`, `H2#4` and `F1#1`, each smoothed or not.
    fn op(smoothed: Vec<bool>) -> TetMeshOp {
        TetMeshOp {
            name: "r".into(),
            patches: vec!["H1#3".into(), "H2#4".into(), "F1#1".into()],
            smoothed,
            sides: Vec::new(),
            size_path: "mesh".into(),
            size: SizeField::default(),
            method: Method::default(),
            refinements: 0,
            wells: false,
            layer: None,
        }
    }

    #[test]
    fn patches_lying_on_each_other_are_put_down_to_smoothing_only_when_a_surface_is_smoothed() {
        let f = FaceToFace {
            patches: [0, 1],
            at: [1.0, 2.0, 3.0],
        };
        let plain = op(vec![false, false, true]).face_to_face_error(&f);
        assert!(plain.contains("`H1#3` and `H2#4` lie on each other at (1.0, 2.0, 3.0)"));
        // The place the command line looks up the nearest input triangle of.
        assert_eq!(
            crate::cli::culprit::failure_place(&plain),
            Some([1.0, 2.0, 3.0])
        );
        assert!(!plain.contains("smooth"), "{plain}");
        assert!(plain.contains("part them in the data"), "{plain}");
        assert!(plain.contains("`discard = { within = d }`"), "{plain}");
        // Either patch can be dropped by the place the message gives.
        assert!(
            plain.contains(
                "`surface = \"H1\"` and `discard = { nearest = [1.0, 2.0, 3.0] }` drops `H1#3` \
                 (with `surface = \"H2\"`, `H2#4`)"
            ),
            "{plain}"
        );
        let smoothed = op(vec![false, true, false]).face_to_face_error(&f);
        assert!(smoothed.contains("smooth neither"), "{smoothed}");
    }

    #[test]
    fn patches_whose_meshes_cross_are_named_with_the_refinement_that_parts_them() {
        let f = FaceToFace {
            patches: [0, 1],
            at: [1.0, 2.0, 3.0],
        };
        let mut op = op(vec![false, false, false]);
        op.size.size = 250.0;
        let crossing = op.crossing_error(&f);
        assert!(
            crossing.contains("patches `H1#3` and `H2#4` cross at (1.0, 2.0, 3.0)"),
            "{crossing}"
        );
        assert_eq!(
            crate::cli::culprit::failure_place(&crossing),
            Some([1.0, 2.0, 3.0])
        );
        let advice = "`[[mesh.refine]]` with `curve = \"H1/H2\"`, `size = 25` and `distance = 500`";
        assert!(crossing.contains(advice), "{crossing}");
        // The build reads the advice back from a crossing, and only from a crossing.
        let advised = AdvisedRefinement {
            curve: "H1/H2".into(),
            size: 25.0,
            distance: 500.0,
        };
        assert_eq!(AdvisedRefinement::of_crossing(&crossing), Some(advised));
        assert_eq!(
            AdvisedRefinement::of_crossing(&op.face_to_face_error(&f)),
            None
        );
        // The same advice for two patches lying on each other, unless smoothing is to blame.
        assert!(op.face_to_face_error(&f).contains(advice));
        op.smoothed = vec![true, false, false];
        assert!(!op.face_to_face_error(&f).contains("mesh.refine"));
        // Two patches of one surface meet along no curve of two surfaces.
        op.patches = vec!["H1#3".into(), "H1#4".into()];
        assert!(!op.crossing_error(&f).contains("mesh.refine"));
        assert_eq!(three_digits(1153.0 / 10.0), "115");
        assert_eq!(three_digits(0.123456), "0.123");
    }

    #[test]
    fn patches_bounding_a_region_from_one_side_of_an_edge_are_named_with_the_place() {
        let f = FaceToFace {
            patches: [0, 1],
            at: [1.0, 2.0, 3.0],
        };
        let clash = op(vec![false, false, false]).edge_clash_error(&f);
        assert!(
            clash.contains(
                "`H1#3` and `H2#4` both bound it from the same side of an edge at (1.0, 2.0, 3.0)"
            ),
            "{clash}"
        );
        assert_eq!(
            crate::cli::culprit::failure_place(&clash),
            Some([1.0, 2.0, 3.0])
        );
        assert!(clash.contains("the two surfaces cross or meet"), "{clash}");
        let op = TetMeshOp {
            patches: vec!["HK1#1.29".into(), "HK1#1.32".into()],
            ..op(vec![false, false])
        };
        let folded = op.edge_clash_error(&f);
        assert!(
            folded.contains("`HK1` folds onto itself along a line"),
            "{folded}"
        );
    }
}
