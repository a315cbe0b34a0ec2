//! `model`: the topological model. Every surface (imports and box sides) is split along all its
//! intersection curves, cut into patches, the patches outside the box are trimmed away, and the
//! regions are found by face-uses, faults being the surfaces allowed to dangle. Inputs: the box,
//! then the surfaces (`n_surfaces`, in name order), then the intersections.

use super::SurfaceData;
use crate::engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use crate::geom::{BBox, TriMesh};
use crate::stages::intersect::{Intersection, split};
use crate::stages::{patches, regions};
use serde::{Deserialize, Serialize};

/// One patch of the model, with its support triangulation.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ModelPatch {
    /// Stable name `surface#k`.
    pub name: String,
    pub surface: String,
    pub mesh: TriMesh,
}

/// The output of `model`.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ModelData {
    pub patches: Vec<ModelPatch>,
    pub regions: regions::RegionModel,
}

pub struct ModelOp {
    pub n_surfaces: usize,
    /// Surfaces that may end inside the model (the recipe's faults).
    pub faults: Vec<String>,
    /// Region names by point, from the recipe's `[regions]`.
    pub names: Vec<(String, [f64; 3])>,
}

impl Operation for ModelOp {
    fn kind(&self) -> &'static str {
        "model"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        p.set("surfaces.faults", self.faults.clone())
            .expect("strings");
        for (name, at) in &self.names {
            p.set(&format!("regions.{name}.point"), *at)
                .expect("validated finite");
        }
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let (bbox, rest) = inputs.split_first().ok_or("model needs the box")?;
        let bbox: BBox = bbox.decode()?;
        if rest.len() < self.n_surfaces {
            return Err("model needs its surfaces".into());
        }
        let surfaces: Vec<SurfaceData> = rest[..self.n_surfaces]
            .iter()
            .map(|a| a.decode())
            .collect::<Result<_, _>>()?;
        let intersections: Vec<Intersection> = rest[self.n_surfaces..]
            .iter()
            .map(|a| a.decode())
            .collect::<Result<_, _>>()?;
        let named: Vec<(&str, &TriMesh)> = surfaces
            .iter()
            .map(|s| (s.name.as_str(), &s.mesh))
            .collect();
        let split =
            split::split_model(&named, &intersections).map_err(|e| OpError::from(e.to_string()))?;
        let mut kept = Vec::new();
        let mut trimmed = 0u64;
        for (s, sp) in surfaces.iter().zip(&split) {
            for p in patches::patches(&s.name, sp) {
                if patches::inside_box(&p, &bbox) {
                    kept.push(ModelPatch {
                        name: p.name,
                        surface: s.name.clone(),
                        mesh: p.mesh,
                    });
                } else {
                    trimmed += 1;
                }
            }
        }
        let input: Vec<regions::PatchIn> = kept
            .iter()
            .map(|p| regions::PatchIn {
                name: p.name.clone(),
                surface: p.surface.clone(),
                mesh: p.mesh.clone(),
            })
            .collect();
        let opts = regions::RegionOptions::with_faults(self.faults.iter().cloned());
        let model = regions::find_regions_with(&input, &self.names, &opts)
            .map_err(|e| OpError::from(e.to_string()))?;
        let out = Output::new(Artifact::encode(&ModelData {
            patches: kept,
            regions: model.clone(),
        })?)
        .count("patches", input.len() as u64)
        .count("trimmed_patches", trimmed)
        .count("regions", model.regions.len() as u64)
        .count("dangling_patches", model.dangling.len() as u64);
        let names: Vec<&str> = model.regions.iter().map(|r| r.name.as_str()).collect();
        Ok(out.note(format!("regions: {}", names.join(", "))))
    }
}
