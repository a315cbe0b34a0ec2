//! `curves`, `curve:<name>` and `discretize:<name>`: the model's curves, one extraction node per
//! curve (so that a curve whose polyline did not change cuts its dependents off early), and the
//! per-curve 1D discretization. The expander attached to `curves` creates the per-curve nodes
//! and the export node once the curves are known.
//!
//! A recipe with neither a box nor `[model] sealed = true` has no closed model: its curves are
//! the intersection curves of the recipe's pairs and the free borders of every imported surface.

use super::sizes::SizeChoice;
use super::wells::CurvePins;
use super::{ExportOp, Groups, SurfaceData, Wiring};
use crate::plan::lower::curve_subdivision;
use crate::recipe::{self, Recipe};
use engine::{
    Artifact, Expander, Expansion, NodeId, OpError, Operation, Output, Params, RunContext,
};
use geom::Tolerances;
use model::discretize::{Grading, SizeAt, Subdivision, discretize_pinned};
use model::features::SizeNear;
use model::{intersect, topology};
use rstar::RTree;
use rstar::primitives::GeomWithData;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// One named curve of the model.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModelCurve {
    /// Stable name: `a/b` (or `a/b#k`) for an intersection, `s#k` for a free border of `s`.
    pub name: String,
    /// The surfaces that meet along the curve, sorted.
    pub surfaces: Vec<String>,
    pub polyline: Vec<[f64; 3]>,
    pub closed: bool,
    /// Per point of `polyline`, its room in the model (`model::Curve::clearance`); empty for
    /// curves found without a model.
    #[serde(default)]
    pub clearance: Vec<f64>,
    /// Per point of `polyline`, the size its patches' curvature asks for
    /// (`model::Curve::curvature_size`); empty for curves found without a model.
    #[serde(default)]
    pub curvature_size: Vec<f64>,
    /// Places `[x, y, z, size]` where a patch along it is narrow (`model::Curve::narrow_size`).
    #[serde(default)]
    pub narrow_size: Vec<[f64; 4]>,
}

/// The output of `curves`: every curve, sorted by name.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CurveSet {
    pub curves: Vec<ModelCurve>,
}

/// `curves`: the free borders of the imported surfaces and the intersection curves.
pub struct CurvesOp {
    /// `surfaces` (the imports) and `intersections`.
    pub inputs: Groups,
    pub tolerances: Tolerances,
}

impl Operation for CurvesOp {
    fn kind(&self) -> &'static str {
        "curves"
    }
    fn version(&self) -> u32 {
        // 2: curves carry curvature sizes (none without a model).
        // 3: and narrow sizes (none without a model).
        // 4: borders are cut only at kinks that turn over the longer edge's reach.
        4
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        for (k, v) in self.tolerances.fields() {
            p.set(&format!("tolerances.{k}"), v)
                .expect("validated finite");
        }
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let mut curves = Vec::new();
        for a in self.inputs.get("surfaces", inputs)? {
            let s: SurfaceData = a.decode()?;
            let topo = topology::SurfaceTopology::build(&s.mesh, &s.bstones, &self.tolerances);
            let mut borders: Vec<(Vec<[f64; 3]>, bool)> = topo
                .curves()
                .iter()
                .map(|c| {
                    let pts: Vec<[f64; 3]> = c
                        .vertices
                        .iter()
                        .map(|&v| s.mesh.vertices[v as usize])
                        .collect();
                    (canonical_direction(pts, c.closed), c.closed)
                })
                .collect();
            borders.sort_by(|x, y| cmp_points(&smallest_point(&x.0), &smallest_point(&y.0)));
            for (k, (polyline, closed)) in borders.into_iter().enumerate() {
                curves.push(ModelCurve {
                    name: format!("{}#{}", s.name, k + 1),
                    surfaces: vec![s.name.clone()],
                    polyline,
                    closed,
                    clearance: Vec::new(),
                    curvature_size: Vec::new(),
                    narrow_size: Vec::new(),
                });
            }
        }
        for a in self.inputs.get("intersections", inputs)? {
            let x: intersect::Intersection = a.decode()?;
            let many = x.curves.len() > 1;
            for (k, c) in x.curves.iter().enumerate() {
                let base = format!("{}/{}", x.a, x.b);
                let mut polyline: Vec<[f64; 3]> = c.points.iter().map(|p| p.xyz).collect();
                if c.closed && polyline.first() != polyline.last() {
                    polyline.push(polyline[0]);
                }
                curves.push(ModelCurve {
                    name: if many {
                        format!("{base}#{}", k + 1)
                    } else {
                        base
                    },
                    surfaces: vec![x.a.clone(), x.b.clone()],
                    polyline,
                    closed: c.closed,
                    clearance: Vec::new(),
                    curvature_size: Vec::new(),
                    narrow_size: Vec::new(),
                });
            }
        }
        curves.sort_by(|a, b| a.name.cmp(&b.name));
        let n = curves.len() as u64;
        Ok(Output::new(Artifact::encode(&CurveSet { curves })?).count("curves", n))
    }
}

/// Open curves start at their lexicographically smaller end, so the direction (and "from the
/// start" gradings) does not depend on how the curve was found.
fn canonical_direction(mut pts: Vec<[f64; 3]>, closed: bool) -> Vec<[f64; 3]> {
    if !closed && pts.len() > 1 && cmp_points(&pts[pts.len() - 1], &pts[0]).is_lt() {
        pts.reverse();
    }
    pts
}

/// A total order on points that every machine agrees on (lexicographic, `f64::total_cmp`).
fn cmp_points(a: &[f64; 3], b: &[f64; 3]) -> std::cmp::Ordering {
    (0..3)
        .map(|k| a[k].total_cmp(&b[k]))
        .find(|o| o.is_ne())
        .unwrap_or(std::cmp::Ordering::Equal)
}

/// The curve's smallest point in that order: its canonical geometric key.
fn smallest_point(pts: &[[f64; 3]]) -> [f64; 3] {
    pts.iter().copied().min_by(cmp_points).unwrap_or([0.0; 3])
}

/// `curve:<name>`: extracts one curve from the curve set, or from the model when there is one.
pub struct CurveExtractOp {
    pub name: String,
    /// The input is `model` (a `ModelData`), not `curves`.
    pub from_model: bool,
    /// Where the curve was in its input's list when the node was added: looked at first, so
    /// that extracting every curve is not quadratic in their number (a fault of thousands of
    /// triangles touching at corners has tens of thousands). Only a hint: the name decides, and
    /// it is no parameter.
    pub at: usize,
}

impl Operation for CurveExtractOp {
    fn kind(&self) -> &'static str {
        "curve"
    }
    /// Read only by its `discretize` when that re-runs.
    fn lazy_output(&self) -> bool {
        true
    }
    fn version(&self) -> u32 {
        // 3: the curvature sizes along the curve.
        // 4: the narrow sizes along it.
        4
    }
    fn params(&self) -> Params {
        Params::new()
            .with("curve", self.name.as_str())
            .expect("string")
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let input = inputs.first().ok_or("curve needs the curve set")?;
        let missing = || OpError::from(format!("the model has no curve `{}`", self.name));
        // The model or curve set is decoded once for all curves (shared): one decode each made
        // the extraction quadratic in the number of curves.
        let c = if self.from_model {
            let model = input.decode_shared::<super::ModelData>()?;
            let c = named(&model.topology.curves, self.at, |c| &c.name, &self.name)
                .ok_or_else(missing)?;
            ModelCurve {
                name: c.name.clone(),
                surfaces: c.surfaces.clone(),
                polyline: c.points.clone(),
                closed: c.closed,
                clearance: c.clearance.clone(),
                curvature_size: c.curvature_size.clone(),
                narrow_size: c.narrow_size.clone(),
            }
        } else {
            let set = input.decode_shared::<CurveSet>()?;
            let found = named(&set.curves, self.at, |c| &c.name, &self.name);
            found.cloned().ok_or_else(missing)?
        };
        let n = c.polyline.len() as u64;
        Ok(Output::new(Artifact::encode(&c)?).count("points", n))
    }
}

/// The item of `list` called `name`: the one at `at` when it is, else the first so called.
fn named<'a, T>(
    list: &'a [T],
    at: usize,
    name_of: impl Fn(&T) -> &String,
    name: &str,
) -> Option<&'a T> {
    (list.get(at).filter(|c| name_of(c) == name))
        .or_else(|| list.iter().find(|c| name_of(c) == name))
}

/// The output of `discretize:<name>`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CurveNodes {
    pub name: String,
    pub nodes: Vec<[f64; 3]>,
}

/// `discretize:<name>`: the curve's FE nodes under the rule the recipe gives it.
pub struct DiscretizeOp {
    pub name: String,
    /// Recipe path of the rule that applies (`mesh.curves."F1/H1"` or `mesh.size`).
    pub rule_path: String,
    pub rule: Subdivision,
    /// The fewest segments the curve may have (1: no constraint): a patch loop of two curves
    /// needs two on each, a loop of one closed curve three, so that every loop has three nodes.
    pub min_segments: u32,
    /// How many `refine:<k>` inputs follow the curve (features within reach), and the steepest
    /// growth of their sizes along it (the surfaces' own).
    pub refinements: usize,
    pub max_slope: f64,
    /// Whether `curve_pins` follows the curve (the recipe has wells): the points where wells
    /// cross the curve are then nodes of it.
    pub pinned: bool,
    /// The global `min_size`: the patches' curvature asks for no less, as their meshes do not.
    pub min_size: f64,
    /// The longest segment a count of elements across a region it bounds allows (`layers`),
    /// where that is finer than the rule (`sizes::curve_caps`): the rule yields to it.
    pub cap: Option<SizeChoice>,
    /// The segment length each end (first point, last point) starts from where finer sizes
    /// meet it (`sizes::curve_end_sizes`), growing by `max_slope` with the distance from it.
    pub ends: [Option<f64>; 2],
}

impl Operation for DiscretizeOp {
    fn kind(&self) -> &'static str {
        "discretize"
    }
    /// Read only by the surface meshes and the export that re-run.
    fn lazy_output(&self) -> bool {
        true
    }
    fn version(&self) -> u32 {
        // 3: no segment longer than the patches' curvature asks for.
        // 4: nor than a narrow patch along the curve is wide.
        // 5: no segment cuts across a bend of the curve sharper than 45°.
        5
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        match &self.rule {
            Subdivision::Count(n) => {
                p.set(&format!("{}.count", self.rule_path), *n)
                    .expect("int");
            }
            Subdivision::Size {
                size,
                ratio,
                grading,
            } => {
                p.set(&format!("{}.size", self.rule_path), *size)
                    .expect("validated finite");
                p.set(&format!("{}.ratio", self.rule_path), *ratio)
                    .expect("validated finite");
                let g = if *grading == Grading::Bump {
                    "bump"
                } else {
                    "geometric"
                };
                p.set(&format!("{}.grading", self.rule_path), g)
                    .expect("string");
            }
        }
        if self.min_segments > 1 {
            // Derived from the model's loops, not written in the recipe.
            p.set("model.min_segments", self.min_segments).expect("int");
        }
        p.set("mesh.min_size", self.min_size)
            .expect("validated finite");
        if self.refinements > 0 || self.ends.iter().any(Option::is_some) {
            p.set("mesh.growth.surface_slope", self.max_slope)
                .expect("validated finite");
        }
        for (end, size) in ["first", "last"].iter().zip(self.ends) {
            if let Some(size) = size {
                // Derived from the sizes of the curves meeting this one.
                p.set(&format!("model.end_size.{end}"), size)
                    .expect("finite");
            }
        }
        if let Some(cap) = &self.cap {
            p.set(&format!("{}.cap", cap.path), cap.size)
                .expect("validated finite");
        }
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let (inputs, refine) = super::refine::split_refinements(inputs, self.refinements)?;
        let c: ModelCurve = inputs
            .first()
            .ok_or("discretize needs its curve")?
            .decode()?;
        let all_pins: CurvePins = match (self.pinned, inputs.get(1)) {
            (true, Some(a)) => a.decode()?,
            (true, None) => return Err("discretize needs the curve pins".into()),
            (false, _) => CurvePins::default(),
        };
        let pins = all_pins.of(&self.name);
        let fail = |e| OpError::from(format!("curve `{}`: {e}", self.name));
        let near = SizeNear::new(&refine, self.max_slope);
        let rule = capped(&self.rule, self.cap.as_ref(), &c.polyline);
        let bends = CurvatureAlong::new(&c, &rule, self.min_size);
        let ends = EndSizes::new(&c.polyline, self.ends, self.max_slope);
        let field = |x: &[f64; 3]| near.at(x).min(bends.at(x)).min(ends.at(x));
        let graded = !near.is_empty() || !bends.is_empty() || !ends.is_empty();
        let size_at: Option<SizeAt<'_>> = graded.then_some(&field);
        let mut nodes =
            discretize_pinned(&c.polyline, &rule, &c.clearance, size_at, pins).map_err(fail)?;
        if nodes.len() < self.min_segments as usize + 1 {
            let count = Subdivision::Count(self.min_segments);
            nodes =
                discretize_pinned(&c.polyline, &count, &c.clearance, None, pins).map_err(fail)?;
        }
        let n = nodes.len() as u64;
        Ok(Output::new(Artifact::encode(&CurveNodes {
            name: self.name.clone(),
            nodes,
        })?)
        .count("nodes", n))
    }
}

/// The sizes a curve's ends start from ([`DiscretizeOp::ends`]), as a field: at a point, the
/// least over the ends of their size plus `slope` times the distance from them.
struct EndSizes {
    ends: Vec<([f64; 3], f64)>,
    slope: f64,
}

impl EndSizes {
    fn new(polyline: &[[f64; 3]], sizes: [Option<f64>; 2], slope: f64) -> EndSizes {
        let points = [polyline.first(), polyline.last()];
        let ends = (points.iter().zip(sizes))
            .filter_map(|(p, s)| Some((**p.as_ref()?, s?)))
            .collect();
        EndSizes { ends, slope }
    }

    fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }

    fn at(&self, x: &[f64; 3]) -> f64 {
        (self.ends.iter())
            .map(|(p, s)| s + self.slope * geom::predicates::dist(p, x))
            .fold(f64::INFINITY, f64::min)
    }
}

/// `rule` with no segment longer than `cap` along `polyline`: a count raised to what the cap
/// needs, a size lowered to it (uniform: a grading from the cap would grow past it).
fn capped(rule: &Subdivision, cap: Option<&SizeChoice>, polyline: &[[f64; 3]]) -> Subdivision {
    let Some(cap) = cap.map(|c| c.size) else {
        return rule.clone();
    };
    match rule {
        Subdivision::Count(n) => {
            let needed = (geom::predicates::polyline_length(polyline) / cap).ceil();
            Subdivision::Count((*n).max(needed.min(f64::from(u32::MAX)) as u32))
        }
        Subdivision::Size { size, ratio, .. } if *size <= cap && *ratio == 1.0 => rule.clone(),
        Subdivision::Size { size, .. } => Subdivision::Size {
            size: size.min(cap),
            ratio: 1.0,
            grading: Grading::Geometric,
        },
    }
}

/// The curvature sizes of a curve's points and the sizes of its narrow places that are below
/// its rule's size (raised to `min_size`), as a size field
/// along it: at a point, the least over them of `h + g · d`, with `g` the steepest growth of a
/// surface mesh (the sizes were graded so on the patches already; between two points this
/// bounds the size by its neighbours').
struct CurvatureAlong {
    points: RTree<GeomWithData<[f64; 3], f64>>,
}

impl CurvatureAlong {
    fn new(c: &ModelCurve, rule: &Subdivision, min_size: f64) -> CurvatureAlong {
        let below = match rule {
            Subdivision::Size { size, .. } => *size,
            Subdivision::Count(_) => 0.0,
        };
        let narrow = (c.narrow_size.iter()).map(|s| ([s[0], s[1], s[2]], s[3]));
        let points = (c
            .polyline
            .iter()
            .copied()
            .zip(c.curvature_size.iter().copied()))
        .chain(narrow)
        .filter(|&(_, h)| h < below)
        .map(|(p, h)| GeomWithData::new(p, h.max(min_size)))
        .collect();
        CurvatureAlong {
            points: RTree::bulk_load(points),
        }
    }

    fn is_empty(&self) -> bool {
        self.points.size() == 0
    }

    fn at(&self, x: &[f64; 3]) -> f64 {
        let g = surface_mesh::MAX_SURFACE_GROWTH - 1.0;
        (self.points.nearest_neighbor(*x)).map_or(f64::INFINITY, |p| {
            p.data + g * geom::predicates::dist(p.geom(), x)
        })
    }
}

/// Attached to `curves`: adds the per-curve nodes and the export node.
pub struct DiscretizeExpander {
    pub recipe: Arc<Recipe>,
}

impl Expander for DiscretizeExpander {
    fn expand(&self, output: &Artifact, x: &mut Expansion) -> Result<(), OpError> {
        let set: CurveSet = output.decode()?;
        let names: Vec<String> = set.curves.iter().map(|c| c.name.clone()).collect();
        let unmatched = self.recipe.check_curve_rules(&names);
        if !unmatched.is_empty() {
            return Err(recipe::render(&unmatched).into());
        }
        let curves_node = x.node("curves").ok_or("no `curves` node")?;
        let mut discretized = Vec::with_capacity(set.curves.len());
        for (at, c) in set.curves.iter().enumerate() {
            discretized.push(add_curve_nodes(
                x,
                &self.recipe,
                (&c.name, at),
                (curves_node, false),
                1,
                CurveSizing::default(),
                None,
            )?);
        }
        let (export_inputs, groups) = Wiring::new()
            .group("curves", discretized)
            .group("mesh", [])
            .finish();
        let export = ExportOp::new(&self.recipe, groups);
        x.add_op("export", Arc::new(export), &export_inputs)
            .map_err(graph_error)?;
        Ok(())
    }
}

/// How the model sizes one curve beyond the recipe's rule for it: the size its patches give it
/// when no rule names it (`fallback`), and the `refine:<k>` nodes within its reach with the
/// steepest growth of their sizes along it. `Default`: neither (curves found without a model).
#[derive(Default)]
pub(super) struct CurveSizing<'a> {
    pub fallback: Option<&'a SizeChoice>,
    /// What a count of elements across a region the curve bounds allows at most
    /// ([`DiscretizeOp::cap`]); a curve without a rule has it in its fallback already.
    pub cap: Option<&'a SizeChoice>,
    /// The sizes its ends start from ([`DiscretizeOp::ends`]).
    pub ends: [Option<f64>; 2],
    pub refine: Vec<NodeId>,
    pub max_slope: f64,
}

/// Adds `curve:<name>` (extracted from `source`: the model, or the curve set) and
/// `discretize:<name>` under the recipe's rule for that curve (without one, at the fallback's
/// size when given, else at the global size) and the refinements near it, with at least
/// `min_segments` segments and the wells' crossings of it (`pins`: the `curve_pins` node, when
/// the recipe has wells) as nodes; returns the discretize node.
pub(super) fn add_curve_nodes(
    x: &mut Expansion,
    recipe: &Recipe,
    (name, at): (&str, usize),
    (source, from_model): (NodeId, bool),
    min_segments: u32,
    sizing: CurveSizing<'_>,
    pins: Option<NodeId>,
) -> Result<NodeId, OpError> {
    let extract = x
        .add_op(
            &format!("curve:{name}"),
            Arc::new(CurveExtractOp {
                name: name.to_string(),
                from_model,
                at,
            }),
            &[source],
        )
        .map_err(graph_error)?;
    let ruled = recipe.mesh.curve_rule(name).is_some();
    let (rule_path, rule) = match sizing.fallback {
        Some(f) if !ruled && !f.is_global() => (
            f.path.clone(),
            Subdivision::Size {
                size: f.size,
                ratio: 1.0,
                grading: Grading::Geometric,
            },
        ),
        _ => curve_subdivision(recipe, name),
    };
    let mut inputs = vec![extract];
    inputs.extend(pins);
    inputs.extend(&sizing.refine);
    x.add_op(
        &format!("discretize:{name}"),
        Arc::new(DiscretizeOp {
            name: name.to_string(),
            rule_path,
            rule,
            min_segments,
            refinements: sizing.refine.len(),
            max_slope: sizing.max_slope,
            pinned: pins.is_some(),
            min_size: recipe.mesh.min_size,
            cap: sizing.cap.filter(|_| ruled).cloned(),
            ends: sizing.ends,
        }),
        &inputs,
    )
    .map_err(graph_error)
}

pub(super) fn graph_error(e: engine::GraphError) -> OpError {
    OpError::from(e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Quiet;
    impl RunContext for Quiet {
        fn progress(&self, _: u64, _: u64) {}
    }

    #[test]
    fn a_curve_is_found_by_its_name_whether_or_not_the_hint_points_at_it() {
        let list: Vec<String> = ["F1/H1", "F2#3", "H1#1"].map(String::from).to_vec();
        let find = |at: usize, name: &str| named(&list, at, |c| c, name).cloned();
        assert_eq!(find(1, "F2#3").as_deref(), Some("F2#3"));
        // A stale or wrong hint, or one past the end: the name still decides.
        assert_eq!(find(0, "H1#1").as_deref(), Some("H1#1"));
        assert_eq!(find(9, "F1/H1").as_deref(), Some("F1/H1"));
        assert_eq!(find(1, "F9"), None);
    }

    #[test]
    fn finding_every_curve_at_its_hint_reads_one_name_each_not_the_list() {
        // A fault of triangles touching at corners has a free-border curve per triangle; a
        // search from the list's start would read half of it per curve (quadratic).
        let list: Vec<String> = (0..20_000).map(|k| format!("F#{k}")).collect();
        let read = std::cell::Cell::new(0usize);
        fn counted<'a>(read: &std::cell::Cell<usize>, c: &'a String) -> &'a String {
            read.set(read.get() + 1);
            c
        }
        for (at, name) in list.iter().enumerate() {
            assert_eq!(named(&list, at, |c| counted(&read, c), name), Some(name));
        }
        assert_eq!(read.get(), list.len());
    }

    /// The nodes of a 100 m straight curve discretized at 250 m with at least `min` segments.
    fn nodes(min: u32) -> Vec<[f64; 3]> {
        pinned_nodes(min, None)
    }

    /// As `nodes`, with `pins` given as the `curve_pins` input.
    fn pinned_nodes(min: u32, pins: Option<CurvePins>) -> Vec<[f64; 3]> {
        discretized(straight(100.0, Vec::new()), min, pins)
    }

    /// A straight curve along x of `length`, with these curvature sizes at its points (one
    /// every 10 m; empty: none).
    fn straight(length: f64, curvature_size: Vec<f64>) -> ModelCurve {
        let n = if curvature_size.is_empty() {
            2
        } else {
            curvature_size.len()
        };
        ModelCurve {
            name: "c".into(),
            surfaces: vec!["s".into()],
            polyline: (0..n)
                .map(|k| [length * k as f64 / (n - 1) as f64, 0.0, 0.0])
                .collect(),
            closed: false,
            clearance: Vec::new(),
            curvature_size,
            narrow_size: Vec::new(),
        }
    }

    /// `curve`'s nodes at 250 m, `min_size` 2.5 m, with at least `min` segments.
    fn discretized(curve: ModelCurve, min: u32, pins: Option<CurvePins>) -> Vec<[f64; 3]> {
        let op = at_250(min, pins.is_some());
        let mut inputs = vec![Artifact::encode(&curve).unwrap()];
        inputs.extend(pins.map(|p| Artifact::encode(&p).unwrap()));
        let out = op.run(&Quiet, &inputs).unwrap();
        out.artifact.decode::<CurveNodes>().unwrap().nodes
    }

    /// The segment lengths of `curve` under `op`.
    fn segments(op: &DiscretizeOp, curve: &ModelCurve) -> Vec<f64> {
        let out = op.run(&Quiet, &[Artifact::encode(curve).unwrap()]).unwrap();
        let nodes = out.artifact.decode::<CurveNodes>().unwrap().nodes;
        nodes.windows(2).map(|w| w[1][0] - w[0][0]).collect()
    }

    /// The op for curve `c` at 250 m, `min_size` 2.5 m, with at least `min` segments.
    fn at_250(min: u32, pinned: bool) -> DiscretizeOp {
        DiscretizeOp {
            name: "c".into(),
            rule_path: "mesh.size".into(),
            rule: Subdivision::Size {
                size: 250.0,
                ratio: 1.0,
                grading: Grading::Geometric,
            },
            min_segments: min,
            refinements: 0,
            max_slope: 0.15,
            pinned,
            min_size: 2.5,
            cap: None,
            ends: [None; 2],
        }
    }

    #[test]
    fn a_layers_cap_shortens_a_rules_segments_and_raises_its_count_and_nothing_else() {
        let cap = SizeChoice {
            path: "mesh.regions.r.layers".into(),
            size: 10.0,
        };
        let line = straight(1000.0, Vec::new());
        let mut op = at_250(1, false);
        op.cap = Some(cap.clone());
        let capped = segments(&op, &line);
        assert_eq!(capped.len(), 100);
        assert!(
            capped.iter().all(|&l| (l - 10.0).abs() < 1e-9),
            "{capped:?}"
        );
        op.rule = Subdivision::Count(4);
        assert_eq!(segments(&op, &line).len(), 100, "a count is raised");
        op.rule = Subdivision::Count(200);
        assert_eq!(segments(&op, &line).len(), 200, "a finer count stays");
        op.rule = Subdivision::Size {
            size: 50.0,
            ratio: 1.3,
            grading: Grading::Geometric,
        };
        let graded = segments(&op, &line);
        assert!(graded.iter().all(|&l| l <= 10.0 + 1e-9), "{graded:?}");
        assert!(op.params().get("mesh.regions.r.layers.cap").is_some());
        op.cap = None;
        assert!(op.params().get("mesh.regions.r.layers.cap").is_none());
    }

    #[test]
    fn a_curve_starts_from_the_size_at_its_ends_and_grows_from_there() {
        let line = straight(1000.0, Vec::new());
        let mut op = at_250(1, false);
        op.ends = [Some(20.0), None];
        let from_first = segments(&op, &line);
        assert!(from_first[0] < 25.0, "{from_first:?}");
        assert!(
            from_first.windows(2).all(|w| w[1] >= w[0] * 0.99),
            "{from_first:?}"
        );
        assert!(from_first[from_first.len() - 1] > 100.0, "{from_first:?}");
        op.ends = [None, Some(20.0)];
        let from_last = segments(&op, &line);
        assert!(from_last[from_last.len() - 1] < 25.0, "{from_last:?}");
        assert_eq!(
            from_first.len(),
            from_last.len(),
            "the same grading either way"
        );
        assert!(op.params().get("model.end_size.last").is_some());
        assert!(op.params().get("model.end_size.first").is_none());
    }

    #[test]
    fn a_curve_is_no_coarser_than_its_patches_curvature_asks_and_no_finer_than_min_size() {
        let segments = |sizes: Vec<f64>| discretized(straight(1000.0, sizes), 1, None).len() - 1;
        assert_eq!(segments(vec![f64::INFINITY; 101]), 4, "the rule's 250 m");
        assert_eq!(segments(vec![50.0; 101]), 20);
        // Raised to min_size at the points (2.5 m; up to 5 m between them, at 0.15 per metre).
        let tiny = segments(vec![0.01; 101]);
        assert!((300..=400).contains(&tiny), "{tiny}");
        // Bent near its start only: fine there, growing away at 0.15 per metre.
        let mut near_start = vec![f64::INFINITY; 101];
        near_start[0] = 20.0;
        let nodes = discretized(straight(1000.0, near_start), 1, None);
        let first = nodes[1][0] - nodes[0][0];
        let last = nodes[nodes.len() - 1][0] - nodes[nodes.len() - 2][0];
        assert!(first < 30.0 && last > 100.0, "{first} {last}: {nodes:?}");
    }

    #[test]
    fn a_wells_crossing_of_the_curve_is_a_node_of_it_and_other_curves_pins_are_not() {
        let pin = |x: f64| model::discretize::Pin {
            segment: 0,
            point: [x, 0.0, 0.0],
        };
        let pins = CurvePins {
            curves: vec![("b".into(), vec![pin(10.0)]), ("c".into(), vec![pin(37.5)])],
        };
        assert_eq!(
            pinned_nodes(1, Some(pins)),
            [[0.0; 3], [37.5, 0.0, 0.0], [100.0, 0.0, 0.0]]
        );
        assert_eq!(pinned_nodes(1, Some(CurvePins::default())), nodes(1));
    }

    #[test]
    fn a_curve_shorter_than_its_size_gets_the_segments_its_loops_need() {
        assert_eq!(nodes(1).len(), 2, "one segment by size alone");
        assert_eq!(nodes(2).len(), 3);
        assert_eq!(
            nodes(3),
            vec![
                [0.0; 3],
                [100.0 / 3.0, 0.0, 0.0],
                [200.0 / 3.0, 0.0, 0.0],
                [100.0, 0.0, 0.0]
            ]
        );
    }

    #[test]
    fn a_minimum_enters_the_key_only_where_it_binds() {
        let op = |min_segments| DiscretizeOp {
            name: "c".into(),
            rule_path: "mesh.size".into(),
            rule: Subdivision::Count(4),
            min_segments,
            refinements: 0,
            max_slope: 0.15,
            pinned: false,
            min_size: 2.5,
            cap: None,
            ends: [None; 2],
        };
        assert!(op(1).params().get("model.min_segments").is_none());
        assert!(op(2).params().get("model.min_segments").is_some());
    }
}
