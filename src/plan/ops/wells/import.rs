//! `well:<w>`: the well path read from its file (a gOcad Well, or a PLine read as one path), in
//! the recipe's frame, with the file's own markers; a station repeating the one before it is
//! dropped.

use crate::recipe::WellFormat;
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use gocad::import::{self, Marker, ObjectRef, Units};
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
        // 2: values beyond ±1e12 (no-data markers, damaged numbers) are refused.
        // 3: names and other text from a line are cut at 4096 bytes (a damaged giant line).
        3
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
                let md = model::wells::lengths_along(&stations);
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
