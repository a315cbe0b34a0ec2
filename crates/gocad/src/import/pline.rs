//! From parsed PLine objects to [`Polyline`]s: the same object selection (`pick`) and coordinate
//! transform (`frame`) as surfaces, one part per ILINE. A PLine's vertex records are the TSurf
//! ones, read by the same code, so ids, ATOM aliases, units and `ZPOSITIVE Depth` mean exactly
//! what they mean for a surface. Property values are not kept: a line constrains geometry only.

use super::frame::Frame;
use super::parser::{GocadObject, parse_gocad};
use super::pick::{LINE, every, pick, quoted_name};
use super::{ImportError, ImportOptions, SourceMap};
use serde::{Deserialize, Serialize};

/// One ILINE of a line.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LinePart {
    /// `ILINE <k>`, 1-based in file order.
    pub name: String,
    /// Line of the ILINE keyword (the object's first line when segments come before any ILINE).
    pub line: usize,
    pub segment_count: usize,
}

/// A line ready for meshing: coordinates in the recipe's frame, one part per ILINE.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Polyline {
    pub name: String,
    /// Vertices (z flipped for `ZPOSITIVE Depth`, scaled to the target units); ATOM/PATOM
    /// aliases are resolved to the vertex they repeat.
    pub vertices: Vec<[f64; 3]>,
    /// SEG records as pairs of vertex indices, in file order.
    pub segments: Vec<[u32; 2]>,
    /// Part (index into `parts`) of each segment.
    pub segment_part: Vec<u32>,
    pub parts: Vec<LinePart>,
    /// gOcad id and line of each vertex (`triangle_lines` is empty).
    pub source: SourceMap,
    /// 1-based line of each segment's SEG record.
    pub segment_lines: Vec<u32>,
}

/// Imports the one PLine of a file the options name (by name, by position, or the only one).
pub fn import_line(
    bytes: &[u8],
    file_label: &str,
    opts: &ImportOptions,
) -> Result<Polyline, ImportError> {
    let mut file = parse_gocad(bytes, file_label)?;
    let idx = pick(&file, file_label, opts, &LINE)?;
    convert(file.objects.swap_remove(idx), file_label, opts)
}

/// Imports every PLine of a file (a `.pl`, a group), in file order. Objects of other types fail
/// the import unless `opts.skip_other_types`; `opts.object` is ignored.
pub fn import_lines(
    bytes: &[u8],
    file_label: &str,
    opts: &ImportOptions,
) -> Result<Vec<Polyline>, ImportError> {
    let file = parse_gocad(bytes, file_label)?;
    every(&file, file_label, opts, &LINE)?;
    file.objects
        .into_iter()
        .filter(|o| LINE.holds(o))
        .map(|o| convert(o, file_label, opts))
        .collect()
}

fn convert(mut o: GocadObject, label: &str, opts: &ImportOptions) -> Result<Polyline, ImportError> {
    if let Some(e) = o.geometry_error.take() {
        return Err(e);
    }
    if o.segments.is_empty() {
        return Err(ImportError::new(
            label,
            o.line,
            format!(
                "PLine object{} has no segments (no SEG record)",
                quoted_name(&o)
            ),
        ));
    }
    let mut parts: Vec<LinePart> = o
        .parts
        .iter()
        .enumerate()
        .map(|(k, p)| LinePart {
            name: format!("ILINE {}", k + 1),
            line: p.line,
            segment_count: 0,
        })
        .collect();
    for &p in &o.segment_part {
        if let Some(part) = parts.get_mut(p as usize) {
            part.segment_count += 1;
        }
    }
    let frame = Frame::of(&o, label, opts.target_units)?;
    let mut vertices = std::mem::take(&mut o.vertices);
    frame.place_all(&mut vertices, &o.vertex_lines, label)?;
    Ok(Polyline {
        name: o.name,
        vertices,
        segments: o.segments,
        segment_part: o.segment_part,
        parts,
        source: SourceMap {
            file: label.to_string(),
            vertex_ids: o.vertex_ids,
            vertex_lines: o.vertex_lines,
            triangle_lines: Vec::new(),
        },
        segment_lines: o.segment_lines,
    })
}
