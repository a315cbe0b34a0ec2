//! From parsed objects to [`ImportedSurface`]s: which TSurf the recipe means (`pick`), the
//! coordinate transform (`frame`), property columns, and the matching of Model3d TFACE records to
//! the parts of their TSurf.

use super::frame::Frame;
use super::parser::{GocadObject, parse_gocad};
use super::pick::{SURFACE, every, pick, quoted_name};
use super::{ImportError, ImportOptions, ImportedSurface, PartInfo, SourceMap};
use geom::TriMesh;

/// Imports the one surface of a file the options name.
pub fn import_surface(
    bytes: &[u8],
    file_label: &str,
    opts: &ImportOptions,
) -> Result<ImportedSurface, ImportError> {
    let mut file = parse_gocad(bytes, file_label)?;
    let idx = pick(&file, file_label, opts, &SURFACE)?;
    let model = file.model3d.take();
    let obj = file.objects.swap_remove(idx);
    convert(obj, model.as_ref(), file_label, opts)
}

/// Imports every surface of a file (a Model3d, a group, a multi-object `.ts`), in file order.
/// Objects of other types fail the import unless `opts.skip_other_types`; `opts.object` is ignored.
pub fn import_surfaces(
    bytes: &[u8],
    file_label: &str,
    opts: &ImportOptions,
) -> Result<Vec<ImportedSurface>, ImportError> {
    let mut file = parse_gocad(bytes, file_label)?;
    every(&file, file_label, opts, &SURFACE)?;
    let model = file.model3d.take();
    let mut out = Vec::new();
    for o in file.objects.into_iter().filter(|o| o.is_surface()) {
        out.push(convert(o, model.as_ref(), file_label, opts)?);
    }
    Ok(out)
}

fn convert(
    mut o: GocadObject,
    model: Option<&super::Model3dInfo>,
    label: &str,
    opts: &ImportOptions,
) -> Result<ImportedSurface, ImportError> {
    if o.triangles.is_empty() {
        return Err(ImportError::new(
            label,
            o.line,
            format!("TSurf object{} has no triangles", quoted_name(&o)),
        ));
    }
    let mut parts: Vec<PartInfo> = o
        .parts
        .iter()
        .enumerate()
        .map(|(k, p)| PartInfo {
            name: format!("TFACE {}", k + 1),
            line: p.line,
            object: o.name.clone(),
            model_tface: None,
            triangle_count: 0,
        })
        .collect();
    for &p in &o.triangle_part {
        if let Some(part) = parts.get_mut(p as usize) {
            part.triangle_count += 1;
        }
    }
    if let Some(model) = model {
        match_model_faces(&o, model, &mut parts);
    }
    let frame = Frame::of(&o, label, opts.target_units)?;
    let mut vertices = std::mem::take(&mut o.vertices);
    frame.place_all(&mut vertices, &o.vertex_lines, label)?;
    let (property_names, properties) = property_columns(&o, vertices.len());
    Ok(ImportedSurface {
        name: o.name,
        mesh: TriMesh::new(vertices, o.triangles),
        triangle_part: o.triangle_part,
        parts,
        bstones: o.bstones,
        borders: o.borders,
        property_names,
        properties,
        source: SourceMap {
            file: label.to_string(),
            vertex_ids: o.vertex_ids,
            vertex_lines: o.vertex_lines,
            triangle_lines: o.triangle_lines,
        },
    })
}

fn property_columns(o: &GocadObject, n: usize) -> (Vec<String>, Vec<Vec<f64>>) {
    let stride = o.property_stride;
    let mut names = Vec::with_capacity(stride);
    for (k, name) in o.property_names.iter().enumerate() {
        let size = o.property_sizes.get(k).copied().unwrap_or(1);
        if size == 1 {
            names.push(name.clone());
        } else {
            names.extend((0..size).map(|c| format!("{name}[{c}]")));
        }
    }
    while names.len() < stride {
        names.push(format!("property{}", names.len()));
    }
    names.truncate(stride);
    let cols = (0..stride)
        .map(|k| {
            (0..n)
                .map(|v| {
                    o.properties
                        .get(v * stride + k)
                        .copied()
                        .unwrap_or(f64::NAN)
                })
                .collect()
        })
        .collect();
    (names, cols)
}

/// Gives each part of `o` the Model3d TFACE record of the same surface whose first key point is
/// one of the part's vertices (exact equality on the coordinates as written, before any
/// transform); records that match no part are assigned in order to the parts left.
fn match_model_faces(o: &GocadObject, model: &super::Model3dInfo, parts: &mut [PartInfo]) {
    let faces: Vec<&super::Model3dFace> = model
        .tfaces
        .iter()
        .filter(|f| f.surface == o.name)
        .collect();
    if faces.is_empty() {
        return;
    }
    let mut part_vertices: Vec<Vec<u32>> = vec![Vec::new(); parts.len()];
    for (t, &p) in o.triangles.iter().zip(&o.triangle_part) {
        if let Some(pv) = part_vertices.get_mut(p as usize) {
            pv.extend_from_slice(t);
        }
    }
    let mut taken = vec![false; parts.len()];
    let mut unmatched = Vec::new();
    for f in &faces {
        let hit = f.key_points.first().and_then(|kp| {
            (0..parts.len()).find(|&p| {
                !taken[p]
                    && part_vertices[p]
                        .iter()
                        .any(|&v| o.vertices.get(v as usize) == Some(kp))
            })
        });
        match hit {
            Some(p) => {
                taken[p] = true;
                parts[p].model_tface = Some((f.id, f.kind.clone()));
                parts[p].name = format!("TFACE {}", f.id);
            }
            None => unmatched.push(f),
        }
    }
    let mut free = (0..parts.len()).filter(|&p| !taken[p]);
    for f in unmatched {
        if let Some(p) = free.next() {
            parts[p].model_tface = Some((f.id, f.kind.clone()));
            parts[p].name = format!("TFACE {}", f.id);
        }
    }
}
