//! `well_cut:<w>`: the well cut by the model (`model::wells`), in the well's terms: its
//! crossings as markers with their measured depths, its pieces by region name, resampled to its
//! size, restricted to the recipe's `regions` when it names them; errors name the well, its file
//! and the line of the segment.

use super::import::WellData;
use crate::plan::ops::ModelData;
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use model::discretize::Pin;
use model::regions::{Locator, PatchIn};
use model::wells::{CurveIndex, WellCut, WellError, cut_well, lengths_along, resample};
use serde::{Deserialize, Serialize};

/// Where a well crosses a patch: a node of that patch's mesh and a marker of the well.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WellMarker {
    pub patch: String,
    pub surface: String,
    pub point: [f64; 3],
    /// Measured depth, interpolated between the stations around it.
    pub md: f64,
}

/// The output of `well_cut:<w>`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WellCutData {
    pub name: String,
    /// The element size along and around the well.
    pub size: f64,
    /// In path order.
    pub markers: Vec<WellMarker>,
    /// In path order: the region's name and the piece, resampled (its ends kept bit for bit).
    pub pieces: Vec<(String, Vec<[f64; 3]>)>,
    /// In path order: the patch's name and the stretch lying on it, resampled (its ends kept
    /// bit for bit); its segments become edges of that patch's surface mesh.
    pub runs: Vec<(String, Vec<[f64; 3]>)>,
    /// Where the well crosses a model curve: the curve's name and the point its discretization
    /// must hold; by curve name, then along the curve, once each.
    pub pins: Vec<(String, Pin)>,
}

/// `well_cut:<w>`: inputs `model`, `well:<w>`.
pub struct WellCutOp {
    pub name: String,
    /// Recipe path of the edge length (`wells.<w>.size` or `mesh.size`) and its value.
    pub size_path: String,
    pub size: f64,
    /// The regions the well is embedded in; `None`: every region it crosses.
    pub regions: Option<Vec<String>>,
}

impl Operation for WellCutOp {
    fn kind(&self) -> &'static str {
        "well_cut"
    }
    fn version(&self) -> u32 {
        // 2: the stretches lying on a patch (runs), no longer refused.
        // 3: crossings on a curve, pins of its discretization, no longer refused.
        3
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        p.set("well", self.name.as_str()).expect("string");
        p.set(&self.size_path, self.size).expect("validated finite");
        if let Some(r) = &self.regions {
            p.set(&format!("wells.{}.regions", self.name), r.clone())
                .expect("strings");
        }
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let [model, well] = inputs else {
            return Err("well_cut needs the model and the well".into());
        };
        let model = model.decode_shared::<ModelData>()?;
        let well: WellData = well.decode()?;
        let patches: Vec<PatchIn> = model
            .patches
            .iter()
            .map(|p| PatchIn {
                name: p.name.clone(),
                surface: p.surface.clone(),
                mesh: p.mesh.clone(),
                chart_of: None,
            })
            .collect();
        let locator = Locator::new(&model.regions, &patches);
        let curves = CurveIndex::new(
            (model.topology.curves.iter())
                .map(|c| c.points.clone())
                .collect(),
        );
        let cut = cut_well(&well.stations, &patches, &curves, &locator)
            .map_err(|e| OpError::from(describe(&well, &e)))?;
        if cut.pieces.is_empty() && cut.runs.is_empty() {
            return Err(format!(
                "well `{}` ({}) has no part inside the model: its path from ({}) to ({}) lies outside every region; check the file's coordinates and units against the [box]",
                well.name,
                well.file,
                fmt_point(&well.stations[0]),
                fmt_point(well.stations.last().expect("two stations")),
            )
            .into());
        }
        let cut = self.within_regions(cut, &model);
        if cut.pieces.is_empty() && cut.runs.is_empty() {
            return Err(format!(
                "well `{}` ({}) crosses none of the regions its `regions` names ({})",
                well.name,
                well.file,
                self.regions.as_deref().unwrap_or_default().join(", ")
            )
            .into());
        }
        let md = MeasuredDepth::new(&well);
        let mut markers: Vec<WellMarker> = cut
            .crossings
            .iter()
            .map(|c| {
                let p = &model.patches[c.patch as usize];
                WellMarker {
                    patch: p.name.clone(),
                    surface: p.surface.clone(),
                    point: c.point,
                    md: md.at(c.along),
                }
            })
            .collect();
        // On a curve the well meets every patch there at one point: one marker per surface.
        let mut seen = std::collections::BTreeSet::new();
        markers.retain(|m| seen.insert((m.surface.clone(), m.point.map(f64::to_bits))));
        let mut pins: Vec<(String, Pin)> = (cut.crossings.iter())
            .filter_map(|c| {
                let pin = c.curve?;
                let curve = &model.topology.curves[pin.curve as usize];
                let pin = Pin {
                    segment: pin.segment,
                    point: c.point,
                };
                Some((curve.name.clone(), pin))
            })
            .collect();
        pins.sort_by(|a, b| {
            (a.0.cmp(&b.0)).then(a.1.segment.cmp(&b.1.segment)).then(
                a.1.point
                    .map(f64::to_bits)
                    .cmp(&b.1.point.map(f64::to_bits)),
            )
        });
        pins.dedup_by(|a, b| a.0 == b.0 && a.1.point == b.1.point);
        let pieces: Vec<(String, Vec<[f64; 3]>)> = cut
            .pieces
            .iter()
            .map(|p| {
                let region = model.regions.regions[p.region as usize].name.clone();
                (region, resample(&p.points, self.size))
            })
            .collect();
        let runs: Vec<(String, Vec<[f64; 3]>)> = (cut.runs.iter())
            .map(|r| {
                let patch = model.patches[r.patch as usize].name.clone();
                (patch, resample(&r.points, self.size))
            })
            .collect();
        let (nm, np, nr) = (markers.len() as u64, pieces.len() as u64, runs.len() as u64);
        let segments: usize = (pieces.iter().chain(&runs)).map(|(_, p)| p.len() - 1).sum();
        let mut out = Output::new(Artifact::encode(&WellCutData {
            name: self.name.clone(),
            size: self.size,
            markers,
            pieces,
            runs,
            pins,
        })?)
        .count("markers", nm)
        .count("pieces", np);
        if nr > 0 {
            out = out.count("runs", nr);
        }
        Ok(out.count("segments", segments as u64))
    }
}

impl WellCutOp {
    /// The cut restricted to the recipe's regions: their pieces, the runs on their boundaries
    /// that join one of them, and the crossings that end a piece or such a run.
    fn within_regions(&self, cut: WellCut, model: &ModelData) -> WellCut {
        let Some(keep) = &self.regions else {
            return cut;
        };
        let name = |r: u32| model.regions.regions[r as usize].name.as_str();
        let pieces: Vec<_> = (cut.pieces.into_iter())
            .filter(|p| keep.iter().any(|k| k == name(p.region)))
            .collect();
        let ends = |points: &[[f64; 3]]| [points[0], points[points.len() - 1]];
        let piece_ends: Vec<[f64; 3]> = pieces.iter().flat_map(|p| ends(&p.points)).collect();
        let runs: Vec<_> = (cut.runs.into_iter())
            .filter(|r| ends(&r.points).iter().any(|e| piece_ends.contains(e)))
            .collect();
        let all_ends: Vec<[f64; 3]> = (runs.iter().flat_map(|r| ends(&r.points)))
            .chain(piece_ends)
            .collect();
        let crossings = (cut.crossings.into_iter())
            .filter(|c| all_ends.contains(&c.point))
            .collect();
        WellCut {
            crossings,
            pieces,
            runs,
        }
    }
}

fn fmt_point(p: &[f64; 3]) -> String {
    format!("{}, {}, {}", p[0], p[1], p[2])
}

/// A cut error in the well's terms: its name, file and the line of the segment's first station.
fn describe(well: &WellData, e: &WellError) -> String {
    let line = e
        .segment
        .and_then(|i| well.station_lines.get(i))
        .filter(|&&l| l > 0);
    let place = match line {
        Some(l) => format!("{}:{l}", well.file),
        None => well.file.clone(),
    };
    format!(
        "well `{}` ({place}): {e}; move the path off the surface or its curve, or leave the well out",
        well.name
    )
}

/// Measured depth along the path, from the length along it.
struct MeasuredDepth<'a> {
    along: Vec<f64>,
    md: &'a [f64],
}

impl<'a> MeasuredDepth<'a> {
    fn new(w: &'a WellData) -> Self {
        MeasuredDepth {
            along: lengths_along(&w.stations),
            md: &w.measured_depth,
        }
    }

    fn at(&self, s: f64) -> f64 {
        let i = self
            .along
            .partition_point(|&a| a <= s)
            .clamp(1, self.along.len() - 1);
        let (a0, a1) = (self.along[i - 1], self.along[i]);
        let (m0, m1) = (self.md[i - 1], self.md[i]);
        if a1 > a0 {
            m0 + (s - a0) / (a1 - a0) * (m1 - m0)
        } else {
            m0
        }
    }
}
