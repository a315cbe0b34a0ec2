//! `wells_in:<r>`: every well's pieces in one region, with the size near them, for its tet mesh;
//! `curve_pins`: every well's crossings of the model's curves, for their discretizations.

use super::cut::WellCutData;
use super::samples;
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::refine::Refinement;
use model::discretize::Pin;
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

/// The output of `curve_pins`: per curve crossed by a well (by name), the points its
/// discretization must hold, in the order the cuts give them, once each.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CurvePins {
    pub curves: Vec<(String, Vec<Pin>)>,
}

impl CurvePins {
    /// The pins of curve `name`.
    pub fn of(&self, name: &str) -> &[Pin] {
        (self.curves.binary_search_by(|(c, _)| c.as_str().cmp(name)))
            .map_or(&[], |i| self.curves[i].1.as_slice())
    }
}

/// `curve_pins`: inputs every `well_cut:<w>`, in well-name order. One node gathers them, so a
/// well crossing no curve re-runs it alone and leaves every curve's discretization cached.
pub struct CurvePinsOp;

impl Operation for CurvePinsOp {
    fn kind(&self) -> &'static str {
        "curve_pins"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        Params::new()
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let mut by_curve: std::collections::BTreeMap<String, Vec<Pin>> = Default::default();
        for a in inputs {
            let cut: WellCutData = a.decode()?;
            for (curve, pin) in cut.pins {
                let pins = by_curve.entry(curve).or_default();
                if !pins.iter().any(|p| p.point == pin.point) {
                    pins.push(pin);
                }
            }
        }
        let n = by_curve.values().map(Vec::len).sum::<usize>() as u64;
        let curves = by_curve.into_iter().collect();
        Ok(Output::new(Artifact::encode(&CurvePins { curves })?).count("pins", n))
    }
}
