//! The geometry records TSurf and PLine objects share or own: the vertex records (VRTX, PVRTX,
//! ATOM, PATOM, read by one function for both types), TRGL, TFACE, BSTONE and BORDER for
//! surfaces, SEG and ILINE for lines. Vertex ids stay raw here; the parser resolves them when the
//! object ends. A surface's PVRTX must carry the property values PROPERTIES/ESIZES declare; a
//! line's are not read, since a line keeps no property.

use super::lexer::{NumberError, Tokens, parse_f64, parse_id, text};
use super::parser::{Builder, GocadObject, RawPart, line32};
use super::{ImportError, MAX_COORDINATE, beyond_earth};

/// The vertex index a record names: a non-negative integer token.
fn vertex_id(tok: Option<&[u8]>, what: &str, n: usize, file: &str) -> Result<u64, ImportError> {
    match tok {
        Some(t) => parse_id(t).ok_or_else(|| {
            ImportError::new(
                file,
                n,
                format!(
                    "{what} '{}' is not a vertex id (a non-negative integer)",
                    text(t)
                ),
            )
        }),
        None => Err(ImportError::new(file, n, format!("{what} is missing"))),
    }
}

/// Reads one TSurf geometry record; returns whether `kw` was one.
#[inline]
pub(super) fn parse_surface_record(
    kw: &[u8],
    toks: &mut Tokens<'_>,
    n: usize,
    b: &mut Builder,
    file: &str,
) -> Result<bool, ImportError> {
    if parse_vertex_record(kw, toks, n, b, file, true)? {
        return Ok(true);
    }
    let id = |tok: Option<&[u8]>, what: &str| vertex_id(tok, what, n, file);
    match kw {
        b"TRGL" => {
            let a = id(toks.next(), "TRGL corner")?;
            let bb = id(toks.next(), "TRGL corner")?;
            let c = id(toks.next(), "TRGL corner")?;
            b.raw_triangles.push([a, bb, c]);
            b.obj.triangle_lines.push(line32(n));
            if b.obj.parts.is_empty() {
                b.obj.parts.push(RawPart { line: b.obj.line });
            }
            b.obj.triangle_part.push((b.obj.parts.len() - 1) as u32);
        }
        b"TFACE" => b.obj.parts.push(RawPart { line: n }),
        b"BSTONE" => {
            let v = id(toks.next(), "BSTONE vertex")?;
            b.raw_bstones.push((v, line32(n)));
        }
        b"BORDER" => {
            let _border_id = id(toks.next(), "BORDER id")?;
            let v0 = id(toks.next(), "BORDER vertex")?;
            let v1 = id(toks.next(), "BORDER vertex")?;
            b.raw_borders.push((v0, v1, line32(n)));
        }
        _ => return Ok(false),
    }
    Ok(true)
}

/// Reads one PLine geometry record (vertices without their property values, SEG, ILINE);
/// returns whether `kw` was one.
pub(super) fn parse_line_record(
    kw: &[u8],
    toks: &mut Tokens<'_>,
    n: usize,
    b: &mut Builder,
    file: &str,
) -> Result<bool, ImportError> {
    if parse_vertex_record(kw, toks, n, b, file, false)? {
        return Ok(true);
    }
    match kw {
        b"SEG" => {
            let a = vertex_id(toks.next(), "SEG end", n, file)?;
            let c = vertex_id(toks.next(), "SEG end", n, file)?;
            b.raw_segments.push([a, c]);
            b.obj.segment_lines.push(line32(n));
            if b.obj.parts.is_empty() {
                b.obj.parts.push(RawPart { line: b.obj.line });
            }
            b.obj.segment_part.push((b.obj.parts.len() - 1) as u32);
        }
        b"ILINE" => b.obj.parts.push(RawPart { line: n }),
        _ => return Ok(false),
    }
    Ok(true)
}

/// Reads a VRTX, PVRTX, ATOM or PATOM record, the vertex records TSurf and PLine share; returns
/// whether `kw` was one. `with_properties`: a PVRTX's property values are read and checked
/// against PROPERTIES/ESIZES (surfaces); otherwise they are not read (lines).
#[inline]
fn parse_vertex_record(
    kw: &[u8],
    toks: &mut Tokens<'_>,
    n: usize,
    b: &mut Builder,
    file: &str,
    with_properties: bool,
) -> Result<bool, ImportError> {
    let err = |msg: String| ImportError::new(file, n, msg);
    let id = |tok: Option<&[u8]>, what: &str| vertex_id(tok, what, n, file);
    match kw {
        b"VRTX" | b"PVRTX" => {
            let kwname = if kw == b"VRTX" { "VRTX" } else { "PVRTX" };
            let vid = id(
                toks.next(),
                if kw == b"VRTX" { "VRTX id" } else { "PVRTX id" },
            )?;
            let mut xyz = [0.0; 3];
            for (k, c) in xyz.iter_mut().enumerate() {
                let axis = ["x", "y", "z"][k];
                let tok = toks
                    .next()
                    .ok_or_else(|| err(format!("{kwname} {vid} has no {axis} coordinate")))?;
                *c = parse_f64(tok).map_err(|e| match e {
                    NumberError::NotFinite => err(format!(
                        "{kwname} {vid}: {axis} coordinate '{}' is infinite or NaN",
                        text(tok)
                    )),
                    NumberError::NotNumeric => err(format!(
                        "{kwname} {vid}: {axis} coordinate '{}' is not a number",
                        text(tok)
                    )),
                })?;
                if c.abs() > MAX_COORDINATE {
                    return Err(err(beyond_earth(
                        &format!("{kwname} {vid}: {axis} coordinate"),
                        *c,
                    )));
                }
            }
            let o = &mut b.obj;
            if with_properties {
                read_properties(kw == b"PVRTX", vid, toks, o, &err)?;
            }
            o.vertices.push(xyz);
            o.vertex_ids.push(vid);
            o.vertex_lines.push(line32(n));
        }
        b"ATOM" | b"PATOM" => {
            let aid = id(toks.next(), "ATOM id")?;
            let target = id(toks.next(), "ATOM target")?;
            b.raw_atoms.push((aid, target, line32(n)));
        }
        _ => return Ok(false),
    }
    Ok(true)
}

/// Appends a vertex's property values: a PVRTX's as written, NaN for a VRTX.
#[inline]
fn read_properties(
    pvrtx: bool,
    vid: u64,
    toks: &mut Tokens<'_>,
    o: &mut GocadObject,
    err: &dyn Fn(String) -> ImportError,
) -> Result<(), ImportError> {
    if o.vertices.is_empty() && o.property_stride == 0 {
        o.property_stride = declared_stride(o);
    }
    let stride = o.property_stride;
    if !pvrtx {
        o.properties.extend(std::iter::repeat_n(f64::NAN, stride));
        return Ok(());
    }
    for k in 0..stride {
        let tok = toks.next().ok_or_else(|| {
            err(format!(
                "PVRTX {vid} has {k} property values; PROPERTIES/ESIZES declare {stride}"
            ))
        })?;
        let v = parse_f64(tok).map_err(|_| {
            err(format!(
                "PVRTX {vid}: property value '{}' is not a finite number",
                text(tok)
            ))
        })?;
        o.properties.push(v);
    }
    Ok(())
}

/// Number of property values a PVRTX carries: the ESIZES sum, else one per name.
fn declared_stride(o: &GocadObject) -> usize {
    if o.property_sizes.is_empty() {
        o.property_names.len()
    } else {
        o.property_sizes.iter().sum()
    }
}
