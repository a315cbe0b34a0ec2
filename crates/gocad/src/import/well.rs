//! From parsed Well objects to [`WellPath`]s: the well head, the path stations in the recipe's
//! frame with their measured depths, and the markers placed on the path.
//!
//! The gOcad Well format has no public specification. The subset read (`well_records`) is the one
//! on which the public readers agree — RINGMesh's `.wl` reader (from the Nancy group gOcad comes from),
//! AuScope geomodel-2-3dweb's and GA earthsci's borehole readers, and a Python gOcad reader —
//! checked against the one real Well file published with them (AuScope's `wl2Test.wl`):
//! - a PATH station's `z` is absolute, in the object's ZPOSITIVE convention, and its `dx dy` are
//!   offsets from WREF; so the station is `(WREF.x + dx, WREF.y + dy, z)`, then the object's
//!   transform (axis units, `ZPOSITIVE Depth` → z := -z) applies to it as to any vertex. WREF is
//!   the head and need not be a station (`wl2Test.wl` has WREF at sea level and its first station
//!   at the kelly bushing, 94 m above);
//! - `TVSS_PATH` is read as PATH, as those readers read it;
//! - measured depths are in `PATH_ZM_UNIT` (the z axis unit when absent) and only grow along the
//!   path; a VRTX path has none written, so they are its length from the first station;
//! - a marker's position is the linear interpolation, in measured depth, between the two
//!   stations around it; a marker outside the stations' measured depths is an error rather than
//!   an extrapolation.

use super::frame::{Frame, unit_scale};
use super::parser::{GocadObject, parse_gocad};
use super::pick::{WELL, every, pick, quoted_name};
use super::well_records::{RawMarker, RawStation, StationRecord, WellRecords};
use super::{ImportError, ImportOptions};
use serde::{Deserialize, Serialize};

/// A marker placed on its well's path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Marker {
    pub name: String,
    /// Measured depth, in the target units.
    pub md: f64,
    /// Position on the path, in the recipe's frame.
    pub xyz: [f64; 3],
    /// Line of the MRKR record.
    pub line: usize,
}

/// A well path ready for meshing, in the recipe's frame (z up whatever the file's ZPOSITIVE).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WellPath {
    pub name: String,
    pub file: String,
    /// The well head (WREF).
    pub head: [f64; 3],
    /// Path stations in order of measured depth.
    pub stations: Vec<[f64; 3]>,
    /// Measured depth of each station, in the target units; never decreasing.
    pub measured_depth: Vec<f64>,
    /// 1-based line of each station's record.
    pub station_lines: Vec<u32>,
    pub markers: Vec<Marker>,
}

/// Imports the one Well of a file the options name (by name, by position, or the only one).
pub fn import_well(
    bytes: &[u8],
    file_label: &str,
    opts: &ImportOptions,
) -> Result<WellPath, ImportError> {
    let mut file = parse_gocad(bytes, file_label)?;
    let idx = pick(&file, file_label, opts, &WELL)?;
    convert(file.objects.swap_remove(idx), file_label, opts)
}

/// Imports every Well of a file (a `.wl`, a well group), in file order. Objects of other types
/// fail the import unless `opts.skip_other_types`; `opts.object` is ignored.
pub fn import_wells(
    bytes: &[u8],
    file_label: &str,
    opts: &ImportOptions,
) -> Result<Vec<WellPath>, ImportError> {
    let file = parse_gocad(bytes, file_label)?;
    every(&file, file_label, opts, &WELL)?;
    file.objects
        .into_iter()
        .filter(|o| WELL.holds(o))
        .map(|o| convert(o, file_label, opts))
        .collect()
}

fn convert(mut o: GocadObject, label: &str, opts: &ImportOptions) -> Result<WellPath, ImportError> {
    if let Some(e) = o.geometry_error.take() {
        return Err(e);
    }
    let w = o.well.take().unwrap_or_default();
    let (wref, wref_line) = check_records(&o, &w, label)?;
    let frame = Frame::of(&o, label, opts.target_units)?;
    let zm_scale = match &w.zm_unit {
        Some((unit, line)) => unit_scale(unit, "PATH_ZM_UNIT", *line, label, opts.target_units)?,
        None => frame.z_scale(),
    };
    let head = frame.place(wref, wref_line, label)?;
    let mut stations = Vec::with_capacity(w.stations.len());
    for s in &w.stations {
        stations.push(frame.place(absolute(s, wref), s.line, label)?);
    }
    let (md, md_written) = measured_depths(&w.stations, &stations, zm_scale, label)?;
    let path = Path {
        stations,
        md,
        md_written,
        lines: w.stations.iter().map(|s| s.line).collect(),
        zm_scale,
    };
    let markers = w
        .markers
        .iter()
        .map(|m| path.place(m, label))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(WellPath {
        name: o.name,
        file: label.to_string(),
        head,
        measured_depth: path.md,
        station_lines: path
            .lines
            .iter()
            .map(|&l| u32::try_from(l).unwrap_or(u32::MAX))
            .collect(),
        stations: path.stations,
        markers,
    })
}

/// The checks that need the whole object: a head, stations of one kind, growing measured depth.
fn check_records(
    o: &GocadObject,
    w: &WellRecords,
    label: &str,
) -> Result<([f64; 3], usize), ImportError> {
    let name = quoted_name(o);
    let Some(wref) = w.wref else {
        return Err(ImportError::new(
            label,
            o.line,
            format!(
                "Well object{name} has no WREF record: the well head, from which PATH offsets \
                 are measured, is missing; add `WREF x y z`"
            ),
        ));
    };
    let Some(first) = w.stations.first() else {
        return Err(ImportError::new(
            label,
            o.line,
            format!(
                "Well object{name} has no path station (PATH, TVSS_PATH or VRTX record); a path \
                 kept only in an external file (WP_CATALOG_FILE, binary curves) is not read"
            ),
        ));
    };
    let is_path = |s: &RawStation| matches!(s.record, StationRecord::Path { .. });
    if let Some(other) = w.stations.iter().find(|s| is_path(s) != is_path(first)) {
        let (this, that) = if is_path(other) {
            ("PATH", "VRTX")
        } else {
            ("VRTX", "PATH")
        };
        return Err(ImportError::new(
            label,
            other.line,
            format!(
                "a {this} station in a path given by {that} records (from line {}); give the \
                 path one way only",
                first.line
            ),
        ));
    }
    for pair in w.stations.windows(2) {
        if let (StationRecord::Path { md: a, .. }, StationRecord::Path { md: b, .. }) =
            (pair[0].record, pair[1].record)
            && b < a
        {
            return Err(ImportError::new(
                label,
                pair[1].line,
                format!(
                    "this station's measured depth {b} is less than the previous station's {a} \
                     (line {}): measured depth only grows along a well, so the stations are out \
                     of order or a value is mistyped",
                    pair[0].line
                ),
            ));
        }
    }
    Ok(wref)
}

/// A station's coordinates as written: a PATH's offsets added to the head.
fn absolute(s: &RawStation, wref: [f64; 3]) -> [f64; 3] {
    match s.record {
        StationRecord::Path { z, dx, dy, .. } => [wref[0] + dx, wref[1] + dy, z],
        StationRecord::Vertex(p) => p,
    }
}

/// Measured depth of each station in the target units and as written: a PATH station's as
/// written, a VRTX station's the length along the path from the first station.
fn measured_depths(
    raw: &[RawStation],
    placed: &[[f64; 3]],
    zm_scale: f64,
    label: &str,
) -> Result<(Vec<f64>, Vec<f64>), ImportError> {
    let mut md = Vec::with_capacity(raw.len());
    let mut written = Vec::with_capacity(raw.len());
    for (i, s) in raw.iter().enumerate() {
        let (d, w) = match s.record {
            StationRecord::Path { md, .. } => (md * zm_scale, md),
            StationRecord::Vertex(_) if i == 0 => (0.0, 0.0),
            StationRecord::Vertex(_) => {
                let d = md[i - 1] + distance(placed[i - 1], placed[i]);
                (d, d / zm_scale)
            }
        };
        if !d.is_finite() {
            return Err(ImportError::new(
                label,
                s.line,
                "measured depth overflows after unit scaling",
            ));
        }
        md.push(d);
        written.push(w);
    }
    Ok((md, written))
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

/// A path being built: stations in the frame and their measured depths.
struct Path {
    stations: Vec<[f64; 3]>,
    md: Vec<f64>,
    /// Measured depths in the file's unit, for messages.
    md_written: Vec<f64>,
    lines: Vec<usize>,
    /// Scale of the written measured depths into the target units.
    zm_scale: f64,
}

impl Path {
    /// Places a marker by linear interpolation in measured depth.
    fn place(&self, m: &RawMarker, label: &str) -> Result<Marker, ImportError> {
        let d = m.md * self.zm_scale;
        let last = self.md.len() - 1;
        if !(d >= self.md[0] && d <= self.md[last]) {
            return Err(ImportError::new(
                label,
                m.line,
                format!(
                    "marker '{}' at measured depth {} lies beyond the path, whose stations span \
                     measured depths {} to {} (lines {} to {}); the marker's depth is wrong or \
                     the path stops short of it",
                    m.name,
                    m.md,
                    self.md_written[0],
                    self.md_written[last],
                    self.lines[0],
                    self.lines[last]
                ),
            ));
        }
        Ok(Marker {
            name: m.name.clone(),
            md: d,
            xyz: self.at(d),
            line: m.line,
        })
    }

    /// The point at measured depth `d`, which lies within the stations' measured depths.
    fn at(&self, d: f64) -> [f64; 3] {
        let i = self.md.partition_point(|&v| v <= d).saturating_sub(1);
        let (Some(a), Some(b)) = (self.stations.get(i), self.stations.get(i + 1)) else {
            return self.stations[i];
        };
        let t = (d - self.md[i]) / (self.md[i + 1] - self.md[i]);
        [
            a[0] + t * (b[0] - a[0]),
            a[1] + t * (b[1] - a[1]),
            a[2] + t * (b[2] - a[2]),
        ]
    }
}
