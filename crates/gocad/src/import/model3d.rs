//! The records of a `GOCAD Model3d` object (the header of an `.ml` file): which TSurfs make the
//! model, which TFACE (patch) belongs to which surface with its three key points, and the
//! REGION / LAYER / SURFACE / FAULT_BLOCK records kept for comparison with the regions the
//! pipeline builds. A record's numbers may continue on the following lines; a list ends at `0`.

use super::ImportError;
use super::lexer::{Tokens, eq_ci, parse_f64, parse_id, parse_signed, text};
use super::parser::GocadObject;
use serde::{Deserialize, Serialize};

/// `TFACE <id> <type> <surface>` followed by three key points.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Model3dFace {
    pub id: u64,
    pub kind: String,
    pub surface: String,
    pub key_points: Vec<[f64; 3]>,
    pub line: usize,
}

/// `REGION <id> <name>` with its signed TFACE ids (`+k`: the side the TFACE normal points to).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Model3dRegion {
    pub id: u64,
    pub name: String,
    pub sides: Vec<i64>,
    pub line: usize,
}

/// Another list record: `LAYER`, `SURFACE`, `FAULT_BLOCK`... with its name and ids.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Model3dRecord {
    pub keyword: String,
    pub name: String,
    pub ids: Vec<i64>,
    pub line: usize,
}

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Model3dInfo {
    pub name: String,
    pub line: usize,
    /// `TSURF <name>` records in order.
    pub tsurfs: Vec<String>,
    pub tfaces: Vec<Model3dFace>,
    pub regions: Vec<Model3dRegion>,
    pub layers: Vec<Model3dRecord>,
    pub other: Vec<Model3dRecord>,
}

#[derive(Default)]
enum Open {
    #[default]
    None,
    Face,
    Region,
    Layer,
    Other,
}

#[derive(Default)]
pub(super) struct Model3dBuilder {
    info: Model3dInfo,
    open: Open,
}

impl Model3dBuilder {
    /// Reads one line of a Model3d object; returns whether it was a Model3d record.
    pub(super) fn record(
        &mut self,
        kw: &[u8],
        line: &[u8],
        n: usize,
        file: &str,
    ) -> Result<bool, ImportError> {
        let mut toks = Tokens::new(line);
        toks.next();
        let starts_numeric = matches!(kw.first(), Some(b'0'..=b'9' | b'-' | b'+' | b'.'));
        if starts_numeric {
            return self.continuation(line, n, file).map(|_| true);
        }
        let word = |t: Option<&[u8]>| t.map(text).unwrap_or_default();
        if eq_ci(kw, "TSURF") {
            self.info.tsurfs.push(text(toks.rest()));
            self.open = Open::None;
        } else if eq_ci(kw, "TFACE") {
            let id = toks
                .next()
                .and_then(parse_id)
                .ok_or_else(|| ImportError::new(file, n, "Model3d TFACE without an id"))?;
            let kind = word(toks.next());
            let surface = text(toks.rest());
            self.info.tfaces.push(Model3dFace {
                id,
                kind,
                surface,
                key_points: Vec::new(),
                line: n,
            });
            self.open = Open::Face;
        } else if eq_ci(kw, "REGION") {
            let id = toks
                .next()
                .and_then(parse_id)
                .ok_or_else(|| ImportError::new(file, n, "REGION without an id"))?;
            let name = text(toks.rest());
            self.info.regions.push(Model3dRegion {
                id,
                name,
                sides: Vec::new(),
                line: n,
            });
            self.open = Open::Region;
        } else if eq_ci(kw, "LAYER")
            || eq_ci(kw, "SURFACE")
            || eq_ci(kw, "FAULT_BLOCK")
            || eq_ci(kw, "MODEL_REGION")
        {
            let rec = Model3dRecord {
                keyword: text(kw),
                name: text(toks.rest()),
                ids: Vec::new(),
                line: n,
            };
            if eq_ci(kw, "LAYER") {
                self.info.layers.push(rec);
                self.open = Open::Layer;
            } else {
                self.info.other.push(rec);
                self.open = Open::Other;
            }
        } else {
            return Ok(false);
        }
        Ok(true)
    }

    fn continuation(&mut self, line: &[u8], n: usize, file: &str) -> Result<(), ImportError> {
        let bad = |t: &[u8]| {
            ImportError::new(
                file,
                n,
                format!("'{}' is not a number in a Model3d record", text(t)),
            )
        };
        match self.open {
            Open::Face => {
                let Some(face) = self.info.tfaces.last_mut() else {
                    return Ok(());
                };
                let mut p = [0.0; 3];
                let mut toks = Tokens::new(line);
                for c in &mut p {
                    let t = toks.next().ok_or_else(|| {
                        ImportError::new(file, n, "a TFACE key point needs 3 coordinates")
                    })?;
                    *c = parse_f64(t).map_err(|_| bad(t))?;
                }
                face.key_points.push(p);
            }
            Open::Region | Open::Layer | Open::Other => {
                let list = match self.open {
                    Open::Region => self.info.regions.last_mut().map(|r| &mut r.sides),
                    Open::Layer => self.info.layers.last_mut().map(|r| &mut r.ids),
                    _ => self.info.other.last_mut().map(|r| &mut r.ids),
                };
                let Some(list) = list else { return Ok(()) };
                for t in Tokens::new(line) {
                    let v = parse_signed(t).ok_or_else(|| bad(t))?;
                    if v == 0 {
                        self.open = Open::None;
                        break;
                    }
                    list.push(v);
                }
            }
            Open::None => {}
        }
        Ok(())
    }

    pub(super) fn finish(mut self, obj: &GocadObject) -> Model3dInfo {
        self.info.name = obj.name.clone();
        self.info.line = obj.line;
        self.info
    }
}
