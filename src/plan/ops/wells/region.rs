//! `wells_in:<r>`: every well's pieces in one region, with the size near them, for its tet mesh.

use super::cut::WellCutData;
use super::samples;
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::refine::Refinement;
use serde::{Deserialize, Serialize};

/// The output of `wells_in:<r>`: every well's pieces in one region.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RegionWells {
    /// By well name; each piece a polyline whose ends are crossings or path ends.
    pub wells: Vec<(String, Vec<Vec<[f64; 3]>>)>,
    /// Per well (same order), its size near its pieces (the points sampled at most half a
    /// size apart); the slope is the tet mesher's to choose.
    pub refine: Vec<Refinement>,
}

/// `wells_in:<r>`: inputs every `well_cut:<w>`, in well-name order.
pub struct RegionWellsOp {
    pub region: String,
}

impl Operation for RegionWellsOp {
    fn kind(&self) -> &'static str {
        "wells_in"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        Params::new()
            .with("region", self.region.as_str())
            .expect("string")
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let mut wells = Vec::new();
        let mut refine = Vec::new();
        for a in inputs {
            let cut: WellCutData = a.decode()?;
            let mine: Vec<Vec<[f64; 3]>> = cut
                .pieces
                .into_iter()
                .filter(|(r, _)| *r == self.region)
                .map(|(_, p)| p)
                .collect();
            if !mine.is_empty() {
                refine.push(Refinement {
                    points: samples(&mine, cut.size),
                    size: cut.size,
                    slope: f64::INFINITY,
                });
                wells.push((cut.name, mine));
            }
        }
        let n = wells.len() as u64;
        Ok(Output::new(Artifact::encode(&RegionWells { wells, refine })?).count("wells", n))
    }
}
