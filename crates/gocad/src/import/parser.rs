//! The gOcad record parser: every object of a file, raw (coordinates as written), with vertex
//! references resolved to indices.
//!
//! It decides object boundaries (`GOCAD <Type>` ... `END`, a missing END ends at the next `GOCAD`
//! line or at the end of the file), group nesting (`BEGIN_MEMBERS`/`END_MEMBERS`), header names
//! (`name:`, `name=`, `HEADER: {`), the coordinate-system block, property declarations, the
//! geometry records of TSurf objects (VRTX, PVRTX, ATOM, PATOM, TRGL, TFACE, BSTONE, BORDER) and
//! of PLine objects (the same vertex records, SEG, ILINE), read in `records`, and those of Well
//! objects, read in `well_records`; then which vertex every record's id means.
//! Objects of other types keep their header and a count of their records; their geometry is not
//! parsed. Line numbers are 1-based and stored as u32 (files beyond 4 G lines saturate).
//!
//! A TSurf error fails the file, as it always has. An error in a PLine or a Well is kept in its
//! object ([`GocadObject::geometry_error`]) instead: importing a file's surfaces must not start to
//! fail because of a line or well the recipe does not import; importing that line or well does.
//! Lines keep no property values: a PVRTX is read for its id and coordinates only, so a line
//! whose PVRTX carry fewer values than PROPERTIES declares (real files do) still imports.

use super::ImportError;
use super::lexer::{Lines, Tokens, eq_ci, parse_id, quoted_tokens, text, trim};
use super::model3d::{Model3dBuilder, Model3dInfo};
use super::records::{parse_line_record, parse_surface_record};
use super::well_records::{self, WellRecords};
use serde::{Deserialize, Serialize};

/// The `GOCAD_ORIGINAL_COORDINATE_SYSTEM` block of an object (defaults when absent).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CoordinateSystem {
    pub name: Option<String>,
    /// `AXIS_UNIT` values as written (quotes removed) and the line they are on.
    pub axis_units: Option<([String; 3], usize)>,
    /// `ZPOSITIVE` value as written and its line.
    pub zpositive: Option<(String, usize)>,
}

/// A TFACE of a TSurf object or an ILINE of a PLine object.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RawPart {
    pub line: usize,
}

/// One `GOCAD <Type>` object.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GocadObject {
    /// `TSurf`, `PLine` or `Well` for any spelling of them (`Tsurf`, `PLINE`); other types as
    /// written (`VSet`, `SGrid`...).
    pub kind: String,
    pub name: String,
    /// Line of the `GOCAD` signature.
    pub line: usize,
    /// Line of the closing `END`, `None` when it is missing.
    pub end_line: Option<usize>,
    /// Name of the enclosing group, if any (innermost).
    pub group: Option<String>,
    pub crs: CoordinateSystem,
    pub geological_type: Option<String>,
    pub geological_feature: Option<String>,
    /// `PROPERTIES` names and their `ESIZES` (1 each when ESIZES is absent).
    pub property_names: Vec<String>,
    pub property_sizes: Vec<usize>,
    /// Vertices in file order (VRTX and PVRTX; ATOMs are aliases, not vertices).
    pub vertices: Vec<[f64; 3]>,
    pub vertex_ids: Vec<u64>,
    pub vertex_lines: Vec<u32>,
    /// Flat property values: vertex `v` holds `properties[v*stride .. (v+1)*stride]`.
    pub property_stride: usize,
    pub properties: Vec<f64>,
    /// ATOM/PATOM records: (id, index of the vertex it repeats, line).
    pub atoms: Vec<(u64, u32, u32)>,
    /// Triangles as vertex indices (aliases resolved), their lines and their part.
    pub triangles: Vec<[u32; 3]>,
    pub triangle_lines: Vec<u32>,
    pub triangle_part: Vec<u32>,
    /// TFACEs of a TSurf, ILINEs of a PLine (one implicit part when triangles or segments come
    /// before any TFACE or ILINE).
    pub parts: Vec<RawPart>,
    pub bstones: Vec<u32>,
    pub borders: Vec<[u32; 2]>,
    /// SEG records of a PLine as vertex indices (aliases resolved), their lines and their part.
    pub segments: Vec<[u32; 2]>,
    pub segment_lines: Vec<u32>,
    pub segment_part: Vec<u32>,
    /// The path and marker records of a Well object, as written.
    pub well: Option<WellRecords>,
    /// The first error in the geometry of a PLine or Well object. The file still parses, so that
    /// importing its other objects does not depend on this one; importing this one returns it.
    pub geometry_error: Option<ImportError>,
    /// Geometry records of objects whose geometry is not parsed (VSet, SGrid...).
    pub record_count: usize,
}

impl GocadObject {
    pub fn is_surface(&self) -> bool {
        self.kind == "TSurf"
    }
    pub fn is_line(&self) -> bool {
        self.kind == "PLine"
    }
    pub fn is_well(&self) -> bool {
        self.kind == "Well"
    }
}

/// Every object of a file, plus the Model3d records when the file is a Model3d.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GocadFile {
    pub objects: Vec<GocadObject>,
    pub model3d: Option<Model3dInfo>,
}

#[derive(Clone, Copy, PartialEq)]
enum Mode {
    Body,
    Header,
    Crs,
    /// Inside a `{ ... }` block that carries nothing we use (PROPERTY_CLASS_HEADER).
    Skip,
    /// Inside a Well's `WELL_CURVE` ... `END_CURVE` block (a log: nothing we use).
    Curve,
}

/// An object being read: raw ids until `finish` resolves them.
pub(super) struct Builder {
    pub(super) obj: GocadObject,
    pub(super) raw_atoms: Vec<(u64, u64, u32)>,
    pub(super) raw_triangles: Vec<[u64; 3]>,
    pub(super) raw_bstones: Vec<(u64, u32)>,
    pub(super) raw_borders: Vec<(u64, u64, u32)>,
    pub(super) raw_segments: Vec<[u64; 2]>,
    model: Option<Model3dBuilder>,
    is_group: bool,
}

impl Builder {
    fn new(kind: &[u8], line: usize, group: Option<String>) -> Self {
        let kind = ["TSurf", "PLine", "Well"]
            .into_iter()
            .find(|k| eq_ci(kind, k))
            .map_or_else(|| text(kind), str::to_string);
        let is_group = kind.ends_with("Group");
        let model = if kind.eq_ignore_ascii_case("Model3d") {
            Some(Model3dBuilder::default())
        } else {
            None
        };
        let well = (kind == "Well").then(WellRecords::default);
        Builder {
            obj: GocadObject {
                kind,
                line,
                group,
                well,
                ..Default::default()
            },
            raw_atoms: Vec::new(),
            raw_triangles: Vec::new(),
            raw_bstones: Vec::new(),
            raw_borders: Vec::new(),
            raw_segments: Vec::new(),
            model,
            is_group,
        }
    }
}

const ID_NONE: u32 = u32::MAX;

/// Most property values a vertex may carry (Galapagos-style files have a few hundred); bounds the
/// memory a hostile ESIZES line can claim.
const MAX_STRIDE: usize = 4096;

/// Maps gOcad vertex ids to vertex indices: a dense table when ids are compact, else a sorted list.
enum IdMap {
    Dense(Vec<u32>),
    Sorted(Vec<(u64, u32)>),
}

impl IdMap {
    fn get(&self, id: u64) -> Option<u32> {
        match self {
            IdMap::Dense(t) => usize::try_from(id)
                .ok()
                .and_then(|i| t.get(i))
                .copied()
                .filter(|&v| v != ID_NONE),
            IdMap::Sorted(s) => s.binary_search_by_key(&id, |e| e.0).ok().map(|k| s[k].1),
        }
    }
}

pub(super) fn line32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// Parses every object of a gOcad file. `file_label` names the file in errors.
pub fn parse_gocad(bytes: &[u8], file_label: &str) -> Result<GocadFile, ImportError> {
    let err = |line: usize, msg: String| ImportError::new(file_label, line, msg);
    let mut file = GocadFile::default();
    let mut cur: Option<Builder> = None;
    let mut groups: Vec<String> = Vec::new();
    let mut mode = Mode::Body;

    for line in Lines::new(bytes) {
        let n = line.number;
        let t = trim(line.text);
        if t.is_empty() || t[0] == b'#' {
            continue;
        }
        let mut toks = Tokens::new(t);
        let Some(kw) = toks.next() else { continue };

        // A GOCAD signature always starts a new object, whatever block was left open.
        if eq_ci(kw, "GOCAD") {
            if let Some(b) = cur.take() {
                finish(b, None, &mut file, file_label)?;
            }
            let kind = toks.next().unwrap_or(b"");
            if kind.is_empty() {
                return Err(err(n, "GOCAD signature without an object type".into()));
            }
            cur = Some(Builder::new(kind, n, groups.last().cloned()));
            mode = Mode::Body;
            continue;
        }
        match mode {
            Mode::Header => {
                if t.starts_with(b"}") {
                    mode = Mode::Body;
                } else if let Some(b) = cur.as_mut() {
                    header_entry(t, &mut b.obj);
                    if t.ends_with(b"}") {
                        mode = Mode::Body;
                    }
                }
                continue;
            }
            Mode::Skip => {
                if t.contains(&b'}') {
                    mode = Mode::Body;
                }
                continue;
            }
            Mode::Crs => {
                if let Some(b) = cur.as_mut() {
                    if eq_ci(kw, "END_ORIGINAL_COORDINATE_SYSTEM") {
                        mode = Mode::Body;
                    } else if eq_ci(kw, "AXIS_UNIT") {
                        let q = quoted_tokens(toks.rest(), 3);
                        let u = |k: usize| q.get(k).cloned().unwrap_or_default();
                        b.obj.crs.axis_units = Some(([u(0), u(1), u(2)], n));
                    } else if eq_ci(kw, "ZPOSITIVE") {
                        b.obj.crs.zpositive = Some((text(toks.rest()), n));
                    } else if eq_ci(kw, "NAME") {
                        b.obj.crs.name = Some(text(toks.rest()));
                    }
                } else if eq_ci(kw, "END_ORIGINAL_COORDINATE_SYSTEM") {
                    mode = Mode::Body;
                }
                continue;
            }
            Mode::Curve => {
                if eq_ci(kw, "END_CURVE") {
                    mode = Mode::Body;
                    continue;
                }
                if !eq_ci(kw, "END") {
                    continue;
                }
                // An END inside a log block closes the block and the object.
                mode = Mode::Body;
            }
            Mode::Body => {}
        }

        if eq_ci(kw, "END_MEMBERS") {
            if let Some(b) = cur.take() {
                finish(b, None, &mut file, file_label)?;
            }
            groups.pop();
            continue;
        }
        let Some(b) = cur.as_mut() else {
            // Text outside any object (a group's END, stray words): nothing to read.
            continue;
        };
        if b.obj.is_surface() && parse_surface_record(kw, &mut toks, n, b, file_label)? {
            continue;
        }
        if (b.obj.is_line() || b.obj.is_well()) && deferred(b, kw, &mut toks, n, file_label) {
            continue;
        }
        if let Some(m) = b.model.as_mut()
            && m.record(kw, t, n, file_label)?
        {
            continue;
        }
        match kw {
            _ if eq_ci(kw, "END") => {
                if let Some(b) = cur.take() {
                    finish(b, Some(n), &mut file, file_label)?;
                }
            }
            _ if eq_ci(kw, "HEADER") || eq_ci(kw, "HEADER:") || kw.starts_with(b"HEADER{") => {
                let after_open = t.iter().position(|&c| c == b'{').map(|p| &t[p + 1..]);
                match after_open {
                    Some(rest) if rest.contains(&b'}') => {
                        let inner =
                            &rest[..rest.iter().position(|&c| c == b'}').unwrap_or(rest.len())];
                        for entry in inner.split(|&c| c == b';') {
                            header_entry(trim(entry), &mut b.obj);
                        }
                    }
                    Some(_) => mode = Mode::Header,
                    None => {}
                }
            }
            _ if eq_ci(kw, "GOCAD_ORIGINAL_COORDINATE_SYSTEM") => mode = Mode::Crs,
            _ if eq_ci(kw, "BEGIN_MEMBERS") && b.is_group => {
                let name = if b.obj.name.is_empty() {
                    b.obj.kind.clone()
                } else {
                    b.obj.name.clone()
                };
                groups.push(name);
                cur = None;
            }
            _ if eq_ci(kw, "PROPERTIES") => {
                b.obj.property_names = quoted_tokens(toks.rest(), MAX_STRIDE + 1);
                if b.obj.property_names.len() > MAX_STRIDE {
                    return Err(err(n, format!("more than {MAX_STRIDE} PROPERTIES")));
                }
            }
            _ if eq_ci(kw, "ESIZES") => {
                let mut sizes = Vec::new();
                for tok in toks.by_ref() {
                    match parse_id(tok) {
                        Some(s) if s <= 1 << 16 => sizes.push(s as usize),
                        _ => {
                            return Err(err(
                                n,
                                format!("ESIZES entry '{}' is not a size", text(tok)),
                            ));
                        }
                    }
                }
                if sizes.iter().sum::<usize>() > MAX_STRIDE {
                    return Err(err(
                        n,
                        format!("ESIZES declare more than {MAX_STRIDE} values per vertex"),
                    ));
                }
                b.obj.property_sizes = sizes;
            }
            _ if eq_ci(kw, "GEOLOGICAL_TYPE") => b.obj.geological_type = Some(text(toks.rest())),
            _ if eq_ci(kw, "GEOLOGICAL_FEATURE") => {
                b.obj.geological_feature = Some(text(toks.rest()))
            }
            _ if eq_ci(kw, "WELL_CURVE") && !t.ends_with(b"{") => mode = Mode::Curve,
            _ if t.ends_with(b"{") => mode = Mode::Skip,
            _ if is_geometry_keyword(kw) => b.obj.record_count += 1,
            _ => {}
        }
    }
    if let Some(b) = cur.take() {
        finish(b, None, &mut file, file_label)?;
    }
    Ok(file)
}

fn is_geometry_keyword(kw: &[u8]) -> bool {
    matches!(
        kw,
        b"VRTX" | b"PVRTX" | b"ATOM" | b"PATOM" | b"SEG" | b"TRGL" | b"TETRA" | b"ILINE"
    )
}

/// One `key: value` (or `key=value`) line of a HEADER block.
fn header_entry(t: &[u8], obj: &mut GocadObject) {
    let Some(p) = t.iter().position(|&c| c == b':' || c == b'=') else {
        return;
    };
    let key = trim(&t[..p]);
    if !eq_ci(key, "name") {
        return;
    }
    let mut v = trim(&t[p + 1..]);
    if let Some(s) = v.strip_suffix(b"}") {
        v = trim(s);
    }
    if v.len() >= 2 && v[0] == b'"' && v[v.len() - 1] == b'"' {
        v = &v[1..v.len() - 1];
    }
    obj.name = text(v);
}

/// Reads a PLine or Well record into `b`; returns whether `kw` was one. An error is kept in the
/// object (the first one) rather than returned, and the record counts as read.
fn deferred(b: &mut Builder, kw: &[u8], toks: &mut Tokens<'_>, n: usize, file: &str) -> bool {
    let read = if b.obj.is_line() {
        parse_line_record(kw, toks, n, b, file)
    } else {
        well_records::record(&mut b.obj, kw, toks, n, file)
    };
    read.unwrap_or_else(|e| {
        b.obj.geometry_error.get_or_insert(e);
        true
    })
}

/// Closes an object: resolves ids, checks references, appends it to the file.
fn finish(
    mut b: Builder,
    end: Option<usize>,
    file: &mut GocadFile,
    label: &str,
) -> Result<(), ImportError> {
    b.obj.end_line = end;
    if let Some(m) = b.model.take() {
        file.model3d = Some(m.finish(&b.obj));
    }
    if b.is_group {
        return Ok(());
    }
    if b.obj.is_surface() {
        if b.obj.property_sizes.is_empty() {
            b.obj.property_sizes = vec![1; b.obj.property_names.len()];
        }
        resolve(&mut b, label)?;
    } else if b.obj.is_line()
        && let Err(e) = resolve(&mut b, label)
    {
        b.obj.geometry_error.get_or_insert(e);
    }
    file.objects.push(b.obj);
    Ok(())
}

fn resolve(b: &mut Builder, label: &str) -> Result<(), ImportError> {
    let o = &mut b.obj;
    let nv = o.vertices.len();
    if nv >= ID_NONE as usize {
        return Err(ImportError::new(
            label,
            o.line,
            "more than 4 294 967 294 vertices in one object",
        ));
    }
    let count = nv + b.raw_atoms.len();
    let max_id = o
        .vertex_ids
        .iter()
        .chain(b.raw_atoms.iter().map(|a| &a.0))
        .copied()
        .max()
        .unwrap_or(0);
    let dense = max_id <= (2 * count as u64).saturating_add(1024);
    let name = |id: u64, line: u32, what: &str| {
        ImportError::new(
            label,
            line as usize,
            format!("duplicate vertex id {id}: {what} repeats an id already defined"),
        )
    };
    let mut map = if dense {
        let mut t = vec![ID_NONE; max_id as usize + 1];
        for (i, (&id, &line)) in o.vertex_ids.iter().zip(&o.vertex_lines).enumerate() {
            let slot = &mut t[id as usize];
            if *slot != ID_NONE {
                return Err(name(id, line, "this vertex"));
            }
            *slot = i as u32;
        }
        IdMap::Dense(t)
    } else {
        let mut s: Vec<(u64, u32)> = o
            .vertex_ids
            .iter()
            .enumerate()
            .map(|(i, &id)| (id, i as u32))
            .collect();
        s.sort_unstable();
        if let Some(w) = s.windows(2).find(|w| w[0].0 == w[1].0) {
            let later = w[0].1.max(w[1].1);
            return Err(name(w[0].0, o.vertex_lines[later as usize], "this vertex"));
        }
        IdMap::Sorted(s)
    };
    // Aliases in file order; an ATOM may repeat an earlier ATOM.
    for &(aid, target, line) in &b.raw_atoms {
        let Some(idx) = map.get(target) else {
            return Err(ImportError::new(
                label,
                line as usize,
                format!("ATOM {aid} repeats vertex {target}, which is not defined before it"),
            ));
        };
        if map.get(aid).is_some() {
            return Err(name(aid, line, "this ATOM"));
        }
        match &mut map {
            IdMap::Dense(t) => t[aid as usize] = idx,
            IdMap::Sorted(s) => {
                let pos = s.partition_point(|e| e.0 < aid);
                s.insert(pos, (aid, idx));
            }
        }
        o.atoms.push((aid, idx, line));
    }
    let missing = |what: &str, id: u64, line: u32| {
        ImportError::new(
            label,
            line as usize,
            format!("{what} points at vertex {id}, which is not defined"),
        )
    };
    o.triangles.reserve_exact(b.raw_triangles.len());
    for (tri, &line) in b.raw_triangles.iter().zip(&o.triangle_lines) {
        let mut out = [0u32; 3];
        for k in 0..3 {
            out[k] = map
                .get(tri[k])
                .ok_or_else(|| missing("TRGL", tri[k], line))?;
        }
        o.triangles.push(out);
    }
    for &(v, line) in &b.raw_bstones {
        o.bstones
            .push(map.get(v).ok_or_else(|| missing("BSTONE", v, line))?);
    }
    for &(v0, v1, line) in &b.raw_borders {
        let a = map.get(v0).ok_or_else(|| missing("BORDER", v0, line))?;
        let c = map.get(v1).ok_or_else(|| missing("BORDER", v1, line))?;
        o.borders.push([a, c]);
    }
    o.segments.reserve_exact(b.raw_segments.len());
    for (&[v0, v1], &line) in b.raw_segments.iter().zip(&o.segment_lines) {
        let a = map.get(v0).ok_or_else(|| missing("SEG", v0, line))?;
        let c = map.get(v1).ok_or_else(|| missing("SEG", v1, line))?;
        o.segments.push([a, c]);
    }
    Ok(())
}
