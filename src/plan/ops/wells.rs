//! `well:<w>`, `well_cut:<w>` and `wells_in:<r>`: a well path read from its file, cut by the
//! model's patches (its crossings become nodes of those patches' surface meshes, `patch:<p>`
//! gathers them), and each region's pieces of every well for its tet mesh. A well is its own
//! chain of nodes, so editing one re-runs its cut, the patch extractions (cheap; only the
//! patches whose crossings changed mesh again) and the regions whose pieces changed.

use super::ModelData;
use super::patch::PatchCrossing;
use crate::recipe::WellFormat;
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::TriMesh;
use geom::refine::{Refinement, boxes_meet};
use gocad::import::{self, Marker, ObjectRef, Units};
use model::regions::{Locator, PatchIn};
use model::wells::{WellCut, WellError, cut_well, resample};
use serde::{Deserialize, Serialize};

/// The output of `well:<w>`: the path in the recipe's frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WellData {
    pub name: String,
    /// The file as the recipe names it.
    pub file: String,
    /// From the head down, no two consecutive stations equal.
    pub stations: Vec<[f64; 3]>,
    /// 1-based line of each station's record.
    pub station_lines: Vec<u32>,
    /// Measured depth of each station (for a PLine, the length along it).
    pub measured_depth: Vec<f64>,
    /// The file's own markers (a Well's MRKR records).
    pub markers: Vec<Marker>,
}

/// `well:<w>`: reads the well's file.
pub struct WellImportOp {
    pub name: String,
    pub file_label: String,
    pub format: WellFormat,
    pub object: Option<ObjectRef>,
    pub target_units: Units,
}

impl Operation for WellImportOp {
    fn kind(&self) -> &'static str {
        "well"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        let key = |k: &str| format!("wells.{}.{k}", self.name);
        p.set(&key("file"), self.file_label.as_str())
            .expect("string");
        match &self.object {
            Some(ObjectRef::Position(k)) => p.set(&key("object"), *k),
            Some(ObjectRef::Name(n)) => p.set(&key("object"), n.as_str()),
            None => p.set(&key("object"), ""),
        }
        .expect("finite");
        p.set("model.units", format!("{:?}", self.target_units))
            .expect("string");
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let bytes = inputs.first().ok_or("well needs its file")?.bytes()?;
        let opts = import::ImportOptions {
            object: self.object.clone(),
            skip_other_types: true,
            target_units: Some(self.target_units),
        };
        let fail = |e: import::ImportError| OpError::from(format!("well `{}`: {e}", self.name));
        let mut data = match self.format {
            WellFormat::Well => {
                let w = import::import_well(bytes, &self.file_label, &opts).map_err(fail)?;
                WellData {
                    name: self.name.clone(),
                    file: self.file_label.clone(),
                    stations: w.stations,
                    station_lines: w.station_lines,
                    measured_depth: w.measured_depth,
                    markers: w.markers,
                }
            }
            WellFormat::PLine => {
                let l = import::import_line(bytes, &self.file_label, &opts).map_err(fail)?;
                let (stations, station_lines) = l.open_path().map_err(fail)?;
                let mut md = vec![0.0];
                for w in stations.windows(2) {
                    let d = (0..3).map(|k| (w[1][k] - w[0][k]).powi(2)).sum::<f64>();
                    md.push(md[md.len() - 1] + d.sqrt());
                }
                WellData {
                    name: self.name.clone(),
                    file: self.file_label.clone(),
                    stations,
                    station_lines,
                    measured_depth: md,
                    markers: Vec::new(),
                }
            }
        };
        let repeated = drop_repeated_stations(&mut data);
        let mut out = Output::new(Artifact::encode(&data)?)
            .count("stations", data.stations.len() as u64)
            .count("markers", data.markers.len() as u64);
        if repeated > 0 {
            out.notes.push(format!(
                "{repeated} station(s) repeating the one before were dropped"
            ));
        }
        Ok(out)
    }
}

/// Drops each station equal to the one before it (surveys repeat a station at a tie-in);
/// returns how many.
fn drop_repeated_stations(w: &mut WellData) -> usize {
    let n = w.stations.len();
    let (mut stations, mut lines, mut md) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..n {
        if i > 0 && w.stations[i] == w.stations[i - 1] {
            continue;
        }
        stations.push(w.stations[i]);
        lines.push(w.station_lines.get(i).copied().unwrap_or(0));
        md.push(w.measured_depth.get(i).copied().unwrap_or(0.0));
    }
    let dropped = n - stations.len();
    (w.stations, w.station_lines, w.measured_depth) = (stations, lines, md);
    dropped
}

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
        1
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
        let model: ModelData = model.decode()?;
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
        let cut = cut_well(&well.stations, &patches, &locator)
            .map_err(|e| OpError::from(describe(&well, &e)))?;
        if cut.pieces.is_empty() {
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
        if cut.pieces.is_empty() {
            return Err(format!(
                "well `{}` ({}) crosses none of the regions its `regions` names ({})",
                well.name,
                well.file,
                self.regions.as_deref().unwrap_or_default().join(", ")
            )
            .into());
        }
        let md = MeasuredDepth::new(&well);
        let markers: Vec<WellMarker> = cut
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
        let pieces: Vec<(String, Vec<[f64; 3]>)> = cut
            .pieces
            .iter()
            .map(|p| {
                let region = model.regions.regions[p.region as usize].name.clone();
                (region, resample(&p.points, self.size))
            })
            .collect();
        let (nm, np) = (markers.len() as u64, pieces.len() as u64);
        let segments: usize = pieces.iter().map(|(_, p)| p.len() - 1).sum();
        Ok(Output::new(Artifact::encode(&WellCutData {
            name: self.name.clone(),
            size: self.size,
            markers,
            pieces,
        })?)
        .count("markers", nm)
        .count("pieces", np)
        .count("segments", segments as u64))
    }
}

impl WellCutOp {
    /// The cut restricted to the recipe's regions: their pieces, and the crossings that end one.
    fn within_regions(&self, cut: WellCut, model: &ModelData) -> WellCut {
        let Some(keep) = &self.regions else {
            return cut;
        };
        let name = |r: u32| model.regions.regions[r as usize].name.as_str();
        let pieces: Vec<_> = (cut.pieces.into_iter())
            .filter(|p| keep.iter().any(|k| k == name(p.region)))
            .collect();
        let ends: Vec<[f64; 3]> = pieces
            .iter()
            .flat_map(|p| [p.points[0], p.points[p.points.len() - 1]])
            .collect();
        let crossings = (cut.crossings.into_iter())
            .filter(|c| ends.contains(&c.point))
            .collect();
        WellCut { crossings, pieces }
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
        let mut along = vec![0.0];
        for s in w.stations.windows(2) {
            let d = (0..3).map(|k| (s[1][k] - s[0][k]).powi(2)).sum::<f64>();
            along.push(along[along.len() - 1] + d.sqrt());
        }
        MeasuredDepth {
            along,
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

/// Points along the pieces at most half of `size` apart.
fn samples(pieces: &[Vec<[f64; 3]>], size: f64) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for p in pieces {
        for w in p.windows(2) {
            let len = (0..3)
                .map(|k| (w[1][k] - w[0][k]).powi(2))
                .sum::<f64>()
                .sqrt();
            let n = (2.0 * len / size).ceil().max(1.0) as usize;
            out.extend((0..n).map(|i| {
                let t = i as f64 / n as f64;
                [0, 1, 2].map(|k| w[0][k] + t * (w[1][k] - w[0][k]))
            }));
        }
        out.extend(p.last());
    }
    out
}

/// The crossings of the patch `patch` by the wells `cuts`, in well order then path order.
pub fn patch_crossings(patch: &str, cuts: &[WellCutData]) -> Vec<PatchCrossing> {
    cuts.iter()
        .flat_map(|c| c.markers.iter().map(move |m| (m, c)))
        .filter(|(m, _)| m.patch == patch)
        .map(|(m, c)| PatchCrossing {
            point: m.point,
            well: c.name.clone(),
        })
        .collect()
}

/// The sizes near the wells `cuts` that reach the support `support` of a patch meshed at `size`
/// growing at `slope`: one refinement per well finer than the patch with a piece within
/// `(size - well size) / slope` of the support's box.
pub fn wells_within_reach(
    cuts: &[WellCutData],
    support: &TriMesh,
    size: f64,
    slope: f64,
) -> Vec<Refinement> {
    let Some(near) = Refinement {
        points: support.vertices.clone(),
        ..Refinement::default()
    }
    .bounds(0.0) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for c in cuts.iter().filter(|c| c.size < size && slope > 0.0) {
        let pieces: Vec<Vec<[f64; 3]>> = c.pieces.iter().map(|(_, p)| p.clone()).collect();
        let r = Refinement {
            points: samples(&pieces, c.size),
            size: c.size,
            slope,
        };
        let reach = r.reach(size);
        if r.bounds(reach).is_some_and(|b| boxes_meet(b, near)) {
            out.push(r);
        }
    }
    out
}
