//! `model`: the topological model. Each surface first drops the triangles it holds in common
//! with a surface named before it (`model::intersect::shared`; its intersections are made again
//! without them). Every surface (imports and box sides) is split along all its
//! intersection curves, cut into patches, the patches outside the box are trimmed away, the
//! patches of a surface split only by what the trims discarded are joined again
//! (`model::rejoin`), and the
//! regions are found by face-uses, faults being the surfaces allowed to dangle; then the model's
//! vertices, named curves and patch boundaries are derived (the `model` crate). Inputs: the box
//! (when `has_box`; a sealed model may have none), then the surfaces (`n_surfaces`, in name order), then the intersections. The expander attached
//! to this node (`plan::ops::expand`) adds the per-curve, per-patch and per-region nodes.

use super::{Groups, SurfaceData};
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::mesh::SurfaceKind;
use geom::{BBox, Tolerances, TriMesh};
use model::conformity::{NearMiss, near_misses};
use model::curvature::curvature_sizes;
use model::intersect::{Intersection, shared, split};
use model::rejoin::rejoin;
use model::thickness::region_thickness;
use model::tips::tip_sizes;
use model::touches::touch_points;
use model::trims::{TrimPatch, TrimSpec, apply_trims, describe};
use model::width::{juxtaposition_strips, narrow_sizes, strip_sizes};
use model::{ModelTopology, build_topology};
use model::{patches, regions};
use serde::{Deserialize, Serialize};

/// One patch of the model, with its support triangulation.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ModelPatch {
    /// Stable name `surface#k`.
    pub name: String,
    pub surface: String,
    pub kind: SurfaceKind,
    pub mesh: TriMesh,
    /// The part (TFACE) of its surface its first triangle lies in, so that the model can be
    /// counted as its source file draws it (`geology`).
    #[serde(default)]
    pub part: u32,
    /// The triangles of `mesh` that stand for another direction than their own (pieces of caps
    /// and needles of the imported surface, `geom::facets`), with that unit normal, ascending.
    #[serde(default)]
    pub facets: Vec<(u32, [f64; 3])>,
}

/// The output of `model`.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ModelData {
    pub patches: Vec<ModelPatch>,
    pub regions: regions::RegionModel,
    /// Vertices, curves and patch boundaries (patch indices as in `patches`).
    pub topology: ModelTopology,
    /// Per region (same order), its thickness (`model::thickness`); 0 where no ray crosses it.
    #[serde(default)]
    pub thickness: Vec<f64>,
    /// Where two surfaces touch at an isolated point: (patch index, point), one per patch
    /// holding it (`model::touches`); each becomes a node of that patch's mesh.
    #[serde(default)]
    pub touches: Vec<(u32, [f64; 3])>,
    /// Where the imported surfaces almost share a vertex (`model::conformity`), for a warning.
    #[serde(default)]
    pub near_misses: Vec<NearMiss>,
}

pub struct ModelOp {
    /// `box` (one node; none for a sealed model, `[model] sealed = true`, where the bounding box
    /// of all surfaces stands in for it: it sets the trims' tolerance and, as it contains every
    /// patch, discards none as outside), `surfaces` and `intersections`.
    pub inputs: Groups,
    /// Surfaces that may end inside the model (the recipe's faults).
    pub faults: Vec<String>,
    /// Surfaces with `smooth`: their patches' curvature bounds their curves' sizes.
    pub smoothed: Vec<String>,
    /// Region names by point, from the recipe's `[regions]`.
    pub names: Vec<(String, [f64; 3])>,
    /// The recipe location (`file:line:col`) of each of `names`, same order, for error
    /// messages; like the trims' locations, not in the key.
    pub names_at: Vec<String>,
    pub tolerances: Tolerances,
    /// `[mesh] min_size`: a juxtaposition strip narrower than it asks for less refinement.
    pub min_size: f64,
    /// The recipe's `[[trim]]` entries, in order, each with its recipe location (`file:line:col`)
    /// for error messages.
    pub trims: Vec<(TrimSpec, String)>,
    /// The recipe location (`file:line:col`) of `[box]`, for error messages (not in the key).
    pub box_at: Option<String>,
}

impl Operation for ModelOp {
    fn kind(&self) -> &'static str {
        "model"
    }
    fn version(&self) -> u32 {
        // 12: curves' clearances count the parts of curves apart along the curves (a sliver's
        //     lips, a curve coming back along itself), not only curves sharing no end.
        // 13: a crossing of two curves that rounds onto a corner or curve end of its face is
        //     that vertex.
        // 14: the points where surfaces touch, per patch holding them.
        // 15: where the imported surfaces almost share a vertex.
        // 16: curves' curvature sizes on smoothed surfaces.
        // 17: those sizes graded over every curve by distance.
        // 18: no chart keeps a lobe behind a sliver of a neck.
        // 19: no chart's border crosses itself on its plane where the charts can be mended.
        // 20: each patch records the part (TFACE) it lies in.
        // 21: charts peeled from an overlap merge on past one that cannot.
        // 22: curves inside one surface carry the sizes their narrow patches ask for.
        // 23: triangles held in common with a surface named first are dropped; the curves at a
        //     patch's sharp corner carry the distance to the nearer first point past it.
        // 24: untwisting and unpinching charts alternate until untwisting moves nothing.
        // 25: a chart that meets its patch's border along a wedge joins a chart beside it.
        // 26: the curves of juxtaposition strips carry the sizes their width asks for.
        // 27: a strip narrower than `min_size` asks for less the narrower it is.
        // 28: three or more sheets of one surface meeting at an edge are patches of their own.
        // 29: two surfaces enclosing more than `MAX_LENSES` regions alone fail the model.
        // 30: a cap on a smooth stretch of surface stands for the triangle across its longest
        //     edge in creases and charts.
        // 31: curves are cut only at kinks that turn over the longer edge's reach; patches
        //     record which triangles stand for another direction (caps and needles).
        // 32: a triangle moved to mend a chart's crossing takes the few triangles that would
        //     leave its new chart touching itself at its corner.
        // 33: a chart that a curve cuts into a strip along it joins the chart beside it.
        // 34: patches of one surface split only by a discarded surface's trace are one.
        34
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        p.set("box", self.inputs.len("box") == 1).expect("bool");
        for (k, v) in self.tolerances.fields() {
            p.set(&format!("tolerances.{k}"), v)
                .expect("validated finite");
        }
        p.set("mesh.min_size", self.min_size)
            .expect("validated finite");
        p.set("surfaces.faults", self.faults.clone())
            .expect("strings");
        if !self.smoothed.is_empty() {
            p.set("surfaces.smooth", self.smoothed.clone())
                .expect("strings");
        }
        for (name, at) in &self.names {
            p.set(&format!("regions.{name}.point"), *at)
                .expect("validated finite");
        }
        let trims: Vec<String> = self
            .trims
            .iter()
            .enumerate()
            .map(|(k, (t, _))| describe(k, t))
            .collect();
        p.set("trim", trims).expect("strings");
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let bbox: Option<BBox> = self.inputs.decode("box", inputs)?.pop();
        let surfaces: Vec<SurfaceData> = self.inputs.decode("surfaces", inputs)?;
        let intersections: Vec<Intersection> = self.inputs.decode("intersections", inputs)?;
        let bbox = match bbox {
            Some(b) => {
                self.check_box_meets(&b, &surfaces, &intersections)?;
                b
            }
            None => surfaces_bbox(&surfaces)?,
        };
        self.check_points(&bbox)?;
        let (surfaces, intersections, shared) = unshare(surfaces, intersections)?;
        let named: Vec<(&str, &TriMesh)> = surfaces
            .iter()
            .map(|s| (s.name.as_str(), &s.mesh))
            .collect();
        let split =
            split::split_model(&named, &intersections).map_err(|e| OpError::from(e.to_string()))?;
        let normals: Vec<Vec<[f64; 3]>> = surfaces
            .iter()
            .map(|s| geom::facets::facet_normals(&s.mesh, &self.tolerances))
            .collect();
        let own: Vec<Vec<[f64; 3]>> = surfaces.iter().map(|s| s.mesh.unit_normals()).collect();
        let all: Vec<(usize, patches::Patch)> = split
            .iter()
            .enumerate()
            .flat_map(|(i, sp)| {
                let s = &surfaces[i];
                patches::patches_at_creases(
                    &s.name,
                    sp,
                    &normals[i],
                    self.tolerances.crease_angle_deg,
                )
                .into_iter()
                .map(move |p| (i, p))
            })
            .collect();
        let trim_in: Vec<TrimPatch> = all
            .iter()
            .map(|(i, p)| TrimPatch {
                name: &p.name,
                surface: &surfaces[*i].name,
                mesh: &p.mesh,
            })
            .collect();
        let split_named: Vec<(&str, &TriMesh)> = surfaces
            .iter()
            .zip(&split)
            .map(|(s, sp)| (s.name.as_str(), &sp.mesh))
            .collect();
        let specs: Vec<TrimSpec> = self.trims.iter().map(|(t, _)| t.clone()).collect();
        let outcome = apply_trims(&trim_in, &split_named, &specs, &bbox, &self.tolerances)
            .map_err(|e| {
                let place = e
                    .trim
                    .and_then(|k| self.trims.get(k))
                    .map(|(_, at)| format!("{at}: "))
                    .unwrap_or_default();
                OpError::from(format!("{place}{e}"))
            })?;
        let trimmed = outcome.discarded.len() as u64;
        let chart_deg = self.tolerances.chart_angle_deg;
        let mut charting: Vec<patches::Charting> = surfaces
            .iter()
            .zip(&normals)
            .map(|(s, n)| patches::Charting::new(&s.mesh, n, chart_deg))
            .collect();
        let creases: Vec<_> = (split.iter().zip(&normals))
            .map(|(sp, n)| patches::creased(sp, n, self.tolerances.crease_angle_deg))
            .collect();
        let (rejoined, joined) = rejoin(
            (all.into_iter().zip(&outcome.keep))
                .filter_map(|(p, k)| k.then_some(p))
                .collect(),
            &split,
            &|i, pair| creases[i](pair),
        );
        let mut kept: Vec<ModelPatch> = Vec::new();
        let mut input: Vec<regions::PatchIn> = Vec::new();
        for (i, p) in rejoined {
            let whole = p.name.clone();
            let part = p
                .triangles
                .first()
                .and_then(|&t| split[i].parent.get(t as usize))
                .and_then(|&o| surfaces[i].triangle_part.get(o as usize))
                .copied()
                .unwrap_or(0);
            let charts = charting[i].cut(p, &split[i]);
            let cut = charts.len() > 1;
            for c in charts {
                let facets = standing_for(&c.triangles, &split[i].parent, &normals[i], &own[i]);
                input.push(regions::PatchIn {
                    name: c.name.clone(),
                    surface: surfaces[i].name.clone(),
                    mesh: c.mesh.clone(),
                    chart_of: cut.then(|| whole.clone()),
                });
                kept.push(ModelPatch {
                    name: c.name,
                    surface: surfaces[i].name.clone(),
                    kind: surfaces[i].kind,
                    mesh: c.mesh,
                    part,
                    facets,
                });
            }
        }
        let opts = regions::RegionOptions::with_faults(self.faults.iter().cloned());
        let model = regions::find_regions_with(&input, &self.names, &opts)
            .map_err(|e| self.region_error(e))?;
        let mut topology =
            build_topology(&input, &self.tolerances).map_err(|e| OpError::from(e.to_string()))?;
        let region_patches: Vec<Vec<u32>> = (model.regions.iter())
            .map(|r| {
                let mut ps: Vec<u32> = r.sides.iter().map(|s| s.patch).collect();
                ps.dedup();
                ps
            })
            .collect();
        let strips =
            juxtaposition_strips(&topology.curves, &topology.patches, &input, &region_patches);
        let strip = strip_sizes(
            &topology.curves,
            &topology.patches,
            &input,
            &strips,
            self.min_size,
        );
        let mut narrow = narrow_sizes(&topology.curves, &topology.patches, &input);
        for (n, s) in narrow.iter_mut().zip(strip) {
            n.extend(s);
        }
        let tips = tip_sizes(&topology.curves, &topology.patches);
        for (n, t) in narrow.iter_mut().zip(tips) {
            n.extend(t);
        }
        let (bends, narrow) = curvature_sizes(&topology.curves, &input, &self.smoothed, &narrow);
        for ((c, b), n) in topology.curves.iter_mut().zip(bends).zip(narrow) {
            c.curvature_size = b;
            c.narrow_size = n;
        }
        let thickness = model
            .regions
            .iter()
            .map(|r| region_thickness(&input, &r.sides).unwrap_or(0.0))
            .collect();
        let touch_xyz: Vec<[f64; 3]> = (intersections.iter())
            .flat_map(|x| x.touches.iter().map(|t| t.xyz))
            .collect();
        let touches = touch_points(&input, &touch_xyz);
        let e = bbox.extent();
        let diagonal = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
        let near_misses = near_misses(&named, self.tolerances.conformity_rel * diagonal);
        let n_curves = topology.curves.len() as u64;
        let n_vertices = topology.vertices.len() as u64;
        let out = Output::new(Artifact::encode(&ModelData {
            patches: kept,
            regions: model.clone(),
            topology,
            thickness,
            touches,
            near_misses,
        })?)
        .count("vertices", n_vertices)
        .count("curves", n_curves)
        .count("patches", input.len() as u64)
        .count("trimmed_patches", trimmed)
        .count("rejoined_patches", joined as u64)
        .count("regions", model.regions.len() as u64)
        .count("dangling_patches", model.dangling.len() as u64);
        let names: Vec<&str> = model.regions.iter().map(|r| r.name.as_str()).collect();
        let out = out.note(format!("regions: {}", names.join(", ")));
        Ok(shared.into_iter().fold(out, |o, n| o.note(n)))
    }
}

/// The model's surfaces and intersections once [`unshare`] has run, and its notes.
type Unshared = (Vec<SurfaceData>, Vec<Intersection>, Vec<String>);

/// The surfaces without the triangles each holds in common with a surface whose name sorts
/// first (`model::intersect::shared`), with the intersections made again for them, and a note
/// for each surface that dropped some (where it and the first are one interface).
fn unshare(
    surfaces: Vec<SurfaceData>,
    intersections: Vec<Intersection>,
) -> Result<Unshared, OpError> {
    let named: Vec<(&str, &TriMesh)> = surfaces
        .iter()
        .map(|s| (s.name.as_str(), &s.mesh))
        .collect();
    let Some(u) =
        shared::unshare(&named, &intersections).map_err(|e| OpError::from(e.to_string()))?
    else {
        return Ok((surfaces, intersections, Vec::new()));
    };
    let mut notes = Vec::new();
    let surfaces = (surfaces.into_iter().zip(u.meshes))
        .map(|(s, m)| match m {
            None => s,
            Some((mesh, kept)) => {
                let with: Vec<&str> = (intersections.iter())
                    .filter(|x| x.b == s.name && !x.shared.is_empty())
                    .map(|x| x.a.as_str())
                    .collect();
                let n = s.mesh.triangles.len() - kept.len();
                // Each common triangle stays with the surface it shares it with.
                let owner = match with.as_slice() {
                    [one] => format!("`{one}`'s"),
                    _ => "theirs".to_string(),
                };
                notes.push(format!(
                    "`{}` is one with `{}` over {n} triangle(s) (the same points): kept as \
                     {owner}, and `{}` ends where they part",
                    s.name,
                    with.join("`, `"),
                    s.name
                ));
                let triangle_part = (kept.iter())
                    .filter_map(|&t| s.triangle_part.get(t as usize).copied())
                    .collect();
                SurfaceData {
                    mesh,
                    triangle_part,
                    ..s
                }
            }
        })
        .collect();
    Ok((surfaces, u.intersections, notes))
}

/// `[a, b, c]`, each coordinate as the shortest round-trip float.
fn fmt_point(p: &[f64; 3]) -> String {
    format!("[{}, {}, {}]", p[0], p[1], p[2])
}

/// `[min]..[max]`.
fn fmt_box(b: &BBox) -> String {
    format!("{}..{}", fmt_point(&b.min), fmt_point(&b.max))
}

impl ModelOp {
    /// That the box meets the imported surfaces: some surface's bounding box meets it, and no
    /// surface named in `[intersect]` lies entirely outside it. Either is a box written in other
    /// coordinates than the surfaces (units, a local origin, depth), which otherwise fails later
    /// as curves or regions that are missing, far from the cause.
    fn check_box_meets(
        &self,
        bbox: &BBox,
        surfaces: &[SurfaceData],
        intersections: &[Intersection],
    ) -> Result<(), OpError> {
        let place = self
            .box_at
            .as_ref()
            .map(|at| format!("{at}: "))
            .unwrap_or_default();
        let imported: Vec<(&str, BBox)> = surfaces
            .iter()
            .filter(|s| s.kind != SurfaceKind::Box)
            .map(|s| (s.name.as_str(), BBox::from_points(&s.mesh.vertices)))
            .filter(|(_, b)| !b.is_empty())
            .collect();
        if imported.is_empty() {
            return Ok(());
        }
        if !imported.iter().any(|(_, b)| b.overlaps(bbox)) {
            let spans: Vec<String> = imported
                .iter()
                .map(|(n, b)| format!("`{n}` spans {}", fmt_box(b)))
                .collect();
            return Err(OpError::from(format!(
                "{place}the box {} meets no imported surface: {}; help: the box and the surfaces \
                 are probably in different coordinates (units, a local origin or UTM, elevation \
                 or depth): give `[box]` corners that cover the surfaces, or write `around = \
                 [{}]` with a `margin`",
                fmt_box(bbox),
                spans.join(", "),
                imported
                    .iter()
                    .map(|(n, _)| format!("\"{n}\""))
                    .collect::<Vec<_>>()
                    .join(", "),
            )));
        }
        let mut listed: Vec<&str> = intersections
            .iter()
            .flat_map(|x| [x.a.as_str(), x.b.as_str()])
            .collect();
        listed.sort_unstable();
        listed.dedup();
        for (name, b) in &imported {
            if !listed.contains(name) || b.overlaps(bbox) {
                continue;
            }
            let axes: Vec<String> = (0..3)
                .filter(|&i| b.max[i] < bbox.min[i] || b.min[i] > bbox.max[i])
                .map(|i| {
                    format!(
                        "{} {}..{} against the box's {}..{}",
                        ["x", "y", "z"][i],
                        b.min[i],
                        b.max[i],
                        bbox.min[i],
                        bbox.max[i]
                    )
                })
                .collect();
            return Err(OpError::from(format!(
                "{place}the surface `{name}`, listed in `[intersect]`, lies entirely outside the \
                 box {}: it spans {} ({}), so it meets nothing and none of it is meshed; help: \
                 widen `[box]` to cover it, or, if it is not part of this model, remove `{name}` \
                 from `[intersect]`",
                fmt_box(bbox),
                fmt_box(b),
                axes.join(", "),
            )));
        }
        Ok(())
    }

    /// The recipe location of the region named at `p`, with `": "`, or nothing.
    fn region_place(&self, p: &[f64; 3]) -> String {
        self.names
            .iter()
            .zip(&self.names_at)
            .find(|((_, q), _)| q == p)
            .map(|(_, at)| format!("{at}: "))
            .unwrap_or_default()
    }

    /// Every region point strictly inside `bbox` (the box when it is given around surfaces, or
    /// the surfaces' extent of a sealed model, are known only now; an explicit box was checked
    /// with the recipe). A point outside is in no region.
    fn check_points(&self, bbox: &BBox) -> Result<(), OpError> {
        let fmt = fmt_point;
        for (name, p) in &self.names {
            let Some(i) = (0..3).find(|&i| !(bbox.min[i] < p[i] && p[i] < bbox.max[i])) else {
                continue;
            };
            let axis = ["x", "y", "z"][i];
            let box_of = if self.inputs.len("box") == 1 {
                "the box"
            } else {
                "the extent of the surfaces (the sealed model)"
            };
            return Err(OpError::from(format!(
                "{}region `{name}`: the point {} is outside {box_of} {}..{}: {axis} = {} is not \
                 strictly between {} and {}; help: a region's point must be strictly inside the \
                 model: check the coordinate for a typo or other units, then move the point into \
                 its region or widen `[box]`",
                self.region_place(p),
                fmt(p),
                fmt(&bbox.min),
                fmt(&bbox.max),
                p[i],
                bbox.min[i],
                bbox.max[i],
            )));
        }
        Ok(())
    }

    /// A region error with the recipe location of the `[regions]` entry it is about, and what
    /// to do about a point in no region.
    fn region_error(&self, e: regions::RegionError) -> OpError {
        let place = e.at.map(|p| self.region_place(&p)).unwrap_or_default();
        let help = if e.message.contains("strictly inside no region") {
            "; help: the point is inside the model's extent but in no region: it lies on a surface, or in \
             a gap the trims opened or a surface does not close; move it off the surfaces, \
             into the region it names"
        } else {
            ""
        };
        OpError::from(format!("{place}{e}{help}"))
    }
}

/// The bounding box of every vertex of `surfaces`: the stand-in for the box of a sealed model.
fn surfaces_bbox(surfaces: &[SurfaceData]) -> Result<BBox, OpError> {
    let b = BBox::from_points(surfaces.iter().flat_map(|s| s.mesh.vertices.iter()));
    if b.is_empty() {
        return Err("a sealed model needs at least one surface with vertices".into());
    }
    Ok(b)
}

impl ModelData {
    /// The model as users see it, for `--json` and the report: every curve (its surfaces and
    /// patches), every patch (its surface and curves) and every region (its patches with sides;
    /// a dangling patch is listed with both), all by name.
    pub fn summary(&self) -> serde_json::Value {
        use serde_json::json;
        let topo = &self.topology;
        let patch_name = |p: u32| self.patches[p as usize].name.clone();
        let curves: Vec<_> = topo
            .curves
            .iter()
            .map(|c| {
                json!({
                    "name": c.name,
                    "surfaces": c.surfaces,
                    "patches": c.patches.iter().map(|&p| patch_name(p)).collect::<Vec<_>>(),
                    "closed": c.closed,
                    "points": c.points.len(),
                })
            })
            .collect();
        let patches: Vec<_> = self
            .patches
            .iter()
            .zip(&topo.patches)
            .enumerate()
            .map(|(i, (p, b))| {
                let curve_name = |c: u32| topo.curves[c as usize].name.clone();
                json!({
                    "name": p.name,
                    "surface": p.surface,
                    "support_triangles": p.mesh.triangles.len(),
                    "dangling": self.regions.dangling.contains(&(i as u32)),
                    "loops": b.loops.iter().map(|l| l.iter().map(|u| curve_name(u.curve)).collect::<Vec<_>>()).collect::<Vec<_>>(),
                    "constraints": b.constraints.iter().map(|&c| curve_name(c)).collect::<Vec<_>>(),
                })
            })
            .collect();
        let regions: Vec<_> = self
            .regions
            .regions
            .iter()
            .zip(self.thickness.iter().chain(std::iter::repeat(&0.0)))
            .map(|(r, t)| {
                json!({
                    "name": r.name,
                    "thickness": t,
                    "sides": r.sides.iter().map(|f| format!("{}:{}", patch_name(f.patch), if f.side == regions::Side::Front { "front" } else { "back" })).collect::<Vec<_>>(),
                    "cavities": r.cavities.len(),
                    "interior_point": r.interior_point,
                })
            })
            .collect();
        json!({
            "vertices": topo.vertices.len(),
            "curves": curves,
            "patches": patches,
            "regions": regions,
            "geology": super::geology::counts(self),
        })
    }
}

/// Of a patch whose triangles are `triangles` of a split surface (`parent`: each one's triangle
/// of the imported surface), those whose imported triangle stands for another direction than its
/// own (`facets` against `own`), by their index in the patch, with that direction.
fn standing_for(
    triangles: &[u32],
    parent: &[u32],
    facets: &[[f64; 3]],
    own: &[[f64; 3]],
) -> Vec<(u32, [f64; 3])> {
    (triangles.iter().enumerate())
        .filter_map(|(k, &t)| {
            let p = *parent.get(t as usize)? as usize;
            let n = *facets.get(p)?;
            (own.get(p) != Some(&n)).then_some((k as u32, n))
        })
        .collect()
}
