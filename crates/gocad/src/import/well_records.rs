//! The records of a `GOCAD Well` object the importer keeps, as written: the well head, the path
//! stations, the markers, and the unit of measured depth. [`super::well`] turns them into a path.
//!
//! What is read, and why (the format has no public specification; this subset is what the public
//! readers of it agree on, see [`super::well`]):
//! - `WREF x y z`: the well head, the origin of the PATH offsets.
//! - `PATH zm z dx dy` and `TVSS_PATH zm z dx dy`: a station at measured depth `zm`, at height `z`
//!   (in the object's ZPOSITIVE convention) and horizontal offset `(dx, dy)` from WREF.
//! - `VRTX x y z` (or `VRTX id x y z`): a station given by its coordinates.
//! - `MRKR name flag zm`: a marker at measured depth `zm`; the lines that describe it (UNIT,
//!   FEATURE, NO_FEATURE, DIP, DIPDEG, NORM, MREF) carry nothing the mesh needs and are passed.
//! - `PATH_ZM_UNIT unit`: the unit of every measured depth.
//! - `ZPOSITIVE` written in the body, outside the coordinate-system block, as older writers do.
//!
//! Refused with an error naming the line, because reading them would mean guessing: `STATION`
//! (a deviation survey: the path depends on an integration method the file does not name),
//! `TVD_PATH` (the public readers disagree on its datum) and `PATH_CURVE_X/Y/Z` (a path stored
//! in log curves, which are not read). Logs (`WELL_CURVE` blocks), zones, KB and DATUM are
//! skipped by the parser.

use super::lexer::{NumberError, Tokens, eq_ci, parse_f64, parse_id, quoted_tokens, text};
use super::parser::GocadObject;
use super::{ImportError, MAX_COORDINATE, beyond_earth};
use serde::{Deserialize, Serialize};

/// A path station as written.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum StationRecord {
    /// `PATH` or `TVSS_PATH`: measured depth, z, and the offsets from WREF.
    Path { md: f64, z: f64, dx: f64, dy: f64 },
    /// `VRTX`: the station's coordinates.
    Vertex([f64; 3]),
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RawStation {
    pub record: StationRecord,
    pub line: usize,
}

/// `MRKR name flag md` as written.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RawMarker {
    pub name: String,
    pub md: f64,
    pub line: usize,
}

/// The records of one Well object.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct WellRecords {
    /// `WREF` coordinates and line.
    pub wref: Option<([f64; 3], usize)>,
    /// `PATH_ZM_UNIT` value as written and its line.
    pub zm_unit: Option<(String, usize)>,
    /// Path stations in file order.
    pub stations: Vec<RawStation>,
    /// Markers in file order.
    pub markers: Vec<RawMarker>,
}

/// Reads one record of a Well object; returns whether `kw` was a Well record.
pub(super) fn record(
    obj: &mut GocadObject,
    kw: &[u8],
    toks: &mut Tokens<'_>,
    n: usize,
    file: &str,
) -> Result<bool, ImportError> {
    let Some(w) = obj.well.as_mut() else {
        return Ok(false);
    };
    let err = |msg: String| ImportError::new(file, n, msg);
    match kw {
        _ if eq_ci(kw, "WREF") => {
            if let Some((_, first)) = w.wref {
                return Err(err(format!(
                    "a second WREF: the well head is already given on line {first}; a Well has \
                     one head, so remove one of them"
                )));
            }
            w.wref = Some((numbers::<3>(toks, "WREF", "x y z", n, file)?, n));
        }
        _ if eq_ci(kw, "PATH") || eq_ci(kw, "TVSS_PATH") => {
            let name = if eq_ci(kw, "PATH") {
                "PATH"
            } else {
                "TVSS_PATH"
            };
            let [md, z, dx, dy] = numbers::<4>(toks, name, "zm z dx dy", n, file)?;
            let record = StationRecord::Path { md, z, dx, dy };
            w.stations.push(RawStation { record, line: n });
        }
        _ if eq_ci(kw, "VRTX") => {
            let record = StationRecord::Vertex(station_vertex(toks, n, file)?);
            w.stations.push(RawStation { record, line: n });
        }
        _ if eq_ci(kw, "MRKR") => w.markers.push(marker(toks, n, file)?),
        _ if eq_ci(kw, "PATH_ZM_UNIT") => w.zm_unit = Some((text(toks.rest()), n)),
        _ if eq_ci(kw, "ZPOSITIVE") => body_zpositive(obj, toks, n, file)?,
        _ if eq_ci(kw, "STATION") => {
            return Err(err(
                "STATION (a deviation survey: measured depth, inclination, azimuth) is not read: \
                 the path it implies depends on an integration method the file does not name; \
                 export the well with PATH or VRTX stations"
                    .into(),
            ));
        }
        _ if eq_ci(kw, "TVD_PATH") => {
            return Err(err(
                "TVD_PATH is not read: the depth it gives is measured from a datum the readers \
                 of this format disagree on; export the well with PATH or VRTX stations"
                    .into(),
            ));
        }
        _ if kw.len() > 11 && eq_ci(&kw[..11], "PATH_CURVE_") => {
            return Err(err(format!(
                "{}: this well's path is stored in log curves, which are not read; export the \
                 well with PATH or VRTX stations",
                text(kw)
            )));
        }
        _ => return Ok(false),
    }
    Ok(true)
}

/// `N` finite numbers following a keyword.
fn numbers<const N: usize>(
    toks: &mut Tokens<'_>,
    kw: &str,
    layout: &str,
    n: usize,
    file: &str,
) -> Result<[f64; N], ImportError> {
    let mut out = [0.0; N];
    for (k, v) in out.iter_mut().enumerate() {
        let tok = toks.next().ok_or_else(|| {
            ImportError::new(
                file,
                n,
                format!("{kw} has {k} numbers where {N} are expected: {kw} {layout}"),
            )
        })?;
        *v = number(tok, kw, n, file)?;
    }
    Ok(out)
}

fn number(tok: &[u8], kw: &str, n: usize, file: &str) -> Result<f64, ImportError> {
    parse_f64(tok)
        .map_err(|e| {
            let what = match e {
                NumberError::NotFinite => "is infinite or NaN",
                NumberError::NotNumeric => "is not a number",
            };
            ImportError::new(file, n, format!("{kw}: '{}' {what}", text(tok)))
        })
        .and_then(|v| {
            if v.abs() > MAX_COORDINATE {
                return Err(ImportError::new(
                    file,
                    n,
                    beyond_earth(&format!("{kw}: a value"), v),
                ));
            }
            Ok(v)
        })
}

/// `VRTX x y z`, or `VRTX id x y z` where the first of four tokens is an integer id.
fn station_vertex(toks: &mut Tokens<'_>, n: usize, file: &str) -> Result<[f64; 3], ImportError> {
    let words: Vec<&[u8]> = toks.collect();
    let xyz = match words.as_slice() {
        [id, x, y, z, ..] if parse_id(id).is_some() => [x, y, z],
        [x, y, z, ..] => [x, y, z],
        _ => {
            return Err(ImportError::new(
                file,
                n,
                format!(
                    "VRTX has {} numbers where a well station needs 3: VRTX x y z",
                    words.len()
                ),
            ));
        }
    };
    let mut p = [0.0; 3];
    for (c, tok) in p.iter_mut().zip(xyz) {
        *c = number(tok, "VRTX", n, file)?;
    }
    Ok(p)
}

/// `MRKR name flag md` (the name may be quoted).
fn marker(toks: &mut Tokens<'_>, n: usize, file: &str) -> Result<RawMarker, ImportError> {
    let words = quoted_tokens(toks.rest(), 3);
    let [name, _flag, md, ..] = words.as_slice() else {
        return Err(ImportError::new(
            file,
            n,
            "MRKR needs a name, a flag and a measured depth: MRKR <name> <flag> <zm>",
        ));
    };
    Ok(RawMarker {
        name: name.clone(),
        md: number(md.as_bytes(), "MRKR", n, file)?,
        line: n,
    })
}

/// A `ZPOSITIVE` in the body of a Well: it counts as the coordinate system's unless that one
/// says otherwise.
fn body_zpositive(
    obj: &mut GocadObject,
    toks: &mut Tokens<'_>,
    n: usize,
    file: &str,
) -> Result<(), ImportError> {
    let value = text(toks.rest());
    match &obj.crs.zpositive {
        None => obj.crs.zpositive = Some((value, n)),
        Some((v, _)) if v.eq_ignore_ascii_case(&value) => {}
        Some((v, line)) => {
            return Err(ImportError::new(
                file,
                n,
                format!(
                    "ZPOSITIVE {value} contradicts the coordinate system's ZPOSITIVE {v} (line \
                     {line}); keep the one that is true"
                ),
            ));
        }
    }
    Ok(())
}
