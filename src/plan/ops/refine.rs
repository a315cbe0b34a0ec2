//! `refine:<k>`: the feature of the recipe's `k`-th `[[mesh.refine]]` entry as points on the
//! model (`model::features`), with the size there and its growth. The curves, patches and
//! regions within its reach take it as an input, so editing the entry re-runs those and nothing
//! else, and a model change that moves the feature re-runs it.

use super::ModelData;
use crate::recipe::{CurveSelector, Recipe, RefineTarget};
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::refine::Refinement;
use model::features::{sample_lines, sample_surfaces};

/// What the samples are taken on, resolved against the recipe's surfaces.
#[derive(Clone, Debug)]
pub enum Near {
    /// The patches of these surfaces.
    Surfaces(Vec<String>),
    /// The model curves the selector matches (its text for the key).
    Curves(CurveSelector, String),
    Point([f64; 3]),
}

pub struct RefineOp {
    /// 1-based, as in the node name.
    pub index: usize,
    pub near: Near,
    pub size: f64,
    pub distance: f64,
    pub far: f64,
}

impl RefineOp {
    /// The op for entry `k` (0-based) of `recipe`'s `[[mesh.refine]]`.
    pub fn new(recipe: &Recipe, k: usize) -> Option<RefineOp> {
        let spec = recipe.mesh.refine.get(k)?;
        let near = match &spec.near {
            RefineTarget::Surface(sel) => Near::Surfaces(
                recipe
                    .surface_names()
                    .into_iter()
                    .filter(|n| sel.matches(n))
                    .collect(),
            ),
            RefineTarget::Curve(sel) => Near::Curves(sel.clone(), sel.text.clone()),
            RefineTarget::Point(p) => Near::Point(*p),
        };
        Some(RefineOp {
            index: k + 1,
            near,
            size: spec.size,
            distance: spec.distance,
            far: spec.far,
        })
    }

    /// The growth per unit of distance the entry asks for.
    pub fn slope(&self) -> f64 {
        (self.far - self.size) / self.distance
    }

    /// The box around the feature on `model` (`None`: it names nothing there), without sampling.
    pub fn bounds(&self, model: &ModelData) -> Option<([f64; 3], [f64; 3])> {
        let pts: Vec<[f64; 3]> = match &self.near {
            Near::Surfaces(names) => model
                .patches
                .iter()
                .filter(|p| names.contains(&p.surface))
                .flat_map(|p| p.mesh.vertices.iter().copied())
                .collect(),
            Near::Curves(sel, _) => model
                .topology
                .curves
                .iter()
                .filter(|c| sel.matches(&c.name))
                .flat_map(|c| c.points.iter().copied())
                .collect(),
            Near::Point(p) => vec![*p],
        };
        Refinement {
            points: pts,
            ..Refinement::default()
        }
        .bounds(0.0)
    }

    /// The points of the feature on `model`.
    pub fn samples(&self, model: &ModelData) -> Vec<[f64; 3]> {
        let spacing = 0.5 * self.size;
        match &self.near {
            Near::Surfaces(names) => {
                let meshes: Vec<&geom::TriMesh> = model
                    .patches
                    .iter()
                    .filter(|p| names.contains(&p.surface))
                    .map(|p| &p.mesh)
                    .collect();
                sample_surfaces(&meshes, spacing)
            }
            Near::Curves(sel, _) => {
                let lines: Vec<&[[f64; 3]]> = model
                    .topology
                    .curves
                    .iter()
                    .filter(|c| sel.matches(&c.name))
                    .map(|c| c.points.as_slice())
                    .collect();
                sample_lines(&lines, spacing)
            }
            Near::Point(p) => vec![*p],
        }
    }
}

impl Operation for RefineOp {
    fn kind(&self) -> &'static str {
        "refine"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        let at = format!("mesh.refine[{}]", self.index - 1);
        match &self.near {
            Near::Surfaces(names) => p.set(&format!("{at}.surface"), names.clone()),
            Near::Curves(_, text) => p.set(&format!("{at}.curve"), text.as_str()),
            Near::Point(x) => p.set(&format!("{at}.point"), *x),
        }
        .expect("plain values");
        for (k, v) in [
            ("size", self.size),
            ("distance", self.distance),
            ("far", self.far),
        ] {
            p.set(&format!("{at}.{k}"), v).expect("validated finite");
        }
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let model = inputs
            .first()
            .ok_or("refine needs the model")?
            .decode_shared::<ModelData>()?;
        let points = self.samples(&model);
        if points.is_empty() {
            return Err(OpError::from(format!(
                "`mesh.refine[{}]` names nothing in the model (no patch or curve matches)",
                self.index - 1
            )));
        }
        let n = points.len() as u64;
        let r = Refinement {
            points,
            size: self.size,
            slope: self.slope(),
        };
        Ok(Output::new(Artifact::encode(&r)?).count("points", n))
    }
}

/// `close_curves:<k>` or `thin:<k>`: one refinement the expander found on the model (where
/// curves come close, where a layer thins). Its key is the refinement's own content, so a model
/// edit that leaves the place as it was re-runs nothing that takes it.
pub struct KnownRefinementOp {
    /// The node kind: `close_curves` or `thin`.
    pub kind: &'static str,
    pub refinement: Refinement,
}

impl Operation for KnownRefinementOp {
    fn kind(&self) -> &'static str {
        self.kind
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        let r = &self.refinement;
        let mut h = blake3::Hasher::new();
        for p in &r.points {
            for v in p {
                h.update(&v.to_le_bytes());
            }
        }
        let mut p = Params::new();
        p.set("points", h.finalize().to_hex().as_str())
            .expect("a string");
        p.set("count", r.points.len() as u64).expect("a count");
        p.set("size", r.size).expect("finite");
        p.set("slope", r.slope).expect("finite");
        p
    }
    fn run(&self, _ctx: &dyn RunContext, _inputs: &[Artifact]) -> Result<Output, OpError> {
        let n = self.refinement.points.len() as u64;
        Ok(Output::new(Artifact::encode(&self.refinement)?).count("points", n))
    }
}

/// Splits off the last `n` inputs, the refinements a node takes after its own inputs.
pub fn split_refinements(
    inputs: &[Artifact],
    n: usize,
) -> Result<(&[Artifact], Vec<Refinement>), OpError> {
    let own = inputs
        .len()
        .checked_sub(n)
        .ok_or("fewer inputs than refinements")?;
    let (head, tail) = inputs.split_at(own);
    let refine = tail.iter().map(|a| a.decode()).collect::<Result<_, _>>()?;
    Ok((head, refine))
}

/// A `refine:<k>` node as the expander places it: the box around its feature, its size and
/// the growth it asks for.
pub struct Placed {
    pub node: engine::NodeId,
    bounds: ([f64; 3], [f64; 3]),
    size: f64,
    slope: f64,
}

impl Placed {
    /// `refinement`, the output of `node`, known before the build runs it.
    pub fn known(node: engine::NodeId, refinement: &Refinement) -> Option<Placed> {
        Some(Placed {
            node,
            bounds: refinement.bounds(0.0)?,
            size: refinement.size,
            slope: refinement.slope,
        })
    }
}

/// The recipe's refinements that name something in `model`, with their nodes in `x`.
pub fn place(recipe: &Recipe, model: &ModelData, x: &engine::Expansion) -> Vec<Placed> {
    (0..recipe.mesh.refine.len())
        .filter_map(|k| {
            let op = RefineOp::new(recipe, k)?;
            Some(Placed {
                node: x.node(&format!("refine:{}", k + 1))?,
                bounds: op.bounds(model)?,
                size: op.size,
                slope: op.slope(),
            })
        })
        .collect()
}

/// The nodes of the refinements that ask, somewhere in the box `bounds`, for less than `size`
/// (growing no faster than `max_slope`), in recipe order.
pub fn within_reach(
    placed: &[Placed],
    bounds: Option<([f64; 3], [f64; 3])>,
    size: f64,
    max_slope: f64,
) -> Vec<engine::NodeId> {
    let Some(b) = bounds else {
        return Vec::new();
    };
    placed
        .iter()
        .filter(|p| {
            let r = Refinement {
                size: p.size,
                slope: p.slope.min(max_slope),
                points: Vec::new(),
            };
            let reach = r.reach(size);
            reach > 0.0
                && geom::refine::boxes_meet(
                    (p.bounds.0.map(|v| v - reach), p.bounds.1.map(|v| v + reach)),
                    b,
                )
        })
        .map(|p| p.node)
        .collect()
}

/// The box around `points` (`None` when empty).
pub fn bounds_of<'a>(
    points: impl IntoIterator<Item = &'a [f64; 3]>,
) -> Option<([f64; 3], [f64; 3])> {
    Refinement {
        points: points.into_iter().copied().collect(),
        ..Refinement::default()
    }
    .bounds(0.0)
}
