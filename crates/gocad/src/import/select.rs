//! From parsed objects to [`ImportedSurface`]s: which object the recipe means, the coordinate
//! transform (per-axis unit scale, `ZPOSITIVE Depth` → z := -z), property columns, and the
//! matching of Model3d TFACE records to the parts of their TSurf.

use super::parser::{GocadFile, GocadObject, parse_gocad};
use super::{ImportError, ImportOptions, ImportedSurface, ObjectRef, PartInfo, SourceMap, Units};
use geom::TriMesh;

/// Imports the one surface of a file the options name.
pub fn import_surface(
    bytes: &[u8],
    file_label: &str,
    opts: &ImportOptions,
) -> Result<ImportedSurface, ImportError> {
    let mut file = parse_gocad(bytes, file_label)?;
    let idx = select(&file, file_label, opts)?;
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
    if !file.objects.iter().any(|o| o.is_surface()) {
        return Err(no_surface(&file, file_label));
    }
    if !opts.skip_other_types
        && let Some(o) = file.objects.iter().find(|o| !o.is_surface())
    {
        return Err(other_type(o, file_label));
    }
    let model = file.model3d.take();
    let mut out = Vec::new();
    for o in file.objects.into_iter().filter(|o| o.is_surface()) {
        out.push(convert(o, model.as_ref(), file_label, opts)?);
    }
    Ok(out)
}

fn no_surface(file: &GocadFile, label: &str) -> ImportError {
    match file.objects.first() {
        None => ImportError::new(label, 0, "the file holds no GOCAD object"),
        Some(o) => ImportError::new(
            label,
            o.line,
            format!(
                "the file holds no GOCAD TSurf object (its first object is a GOCAD {})",
                o.kind
            ),
        ),
    }
}

fn other_type(o: &GocadObject, label: &str) -> ImportError {
    let name = if o.name.is_empty() {
        String::new()
    } else {
        format!(" '{}'", o.name)
    };
    ImportError::new(
        label,
        o.line,
        format!(
            "object{name} is a GOCAD {} where a TSurf surface is expected (set skip_other_types to ignore it)",
            o.kind
        ),
    )
}

/// How an object is listed in messages: `#2 'name' (line 134)`, its position counted from 1.
fn listed(file: &GocadFile, o: &GocadObject) -> String {
    let k = file
        .objects
        .iter()
        .position(|x| std::ptr::eq(x, o))
        .map_or(0, |i| i + 1);
    format!("#{k} '{}' (line {})", o.name, o.line)
}

/// The TSurf objects of the file, listed.
fn surfaces_listed(file: &GocadFile) -> String {
    file.objects
        .iter()
        .filter(|o| o.is_surface())
        .map(|o| listed(file, o))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Index of the object the options select.
fn select(file: &GocadFile, label: &str, opts: &ImportOptions) -> Result<usize, ImportError> {
    let index_of = |o: &GocadObject| {
        file.objects
            .iter()
            .position(|x| std::ptr::eq(x, o))
            .unwrap_or(0)
    };
    match &opts.object {
        Some(ObjectRef::Position(k)) => {
            let at = (*k as usize)
                .checked_sub(1)
                .and_then(|i| file.objects.get(i));
            return match at {
                Some(o) if o.is_surface() => Ok(index_of(o)),
                Some(o) => Err(other_type(o, label)),
                None => Err(ImportError::new(
                    label,
                    0,
                    format!(
                        "there is no object #{k}: the file holds {} GOCAD object{}, counted \
                         from 1 (TSurf objects: {})",
                        file.objects.len(),
                        if file.objects.len() == 1 { "" } else { "s" },
                        surfaces_listed(file)
                    ),
                )),
            };
        }
        Some(ObjectRef::Name(want)) => {
            let named: Vec<&GocadObject> =
                file.objects.iter().filter(|o| &o.name == want).collect();
            return match named.as_slice() {
                [one] if one.is_surface() => Ok(index_of(one)),
                [one] => Err(other_type(one, label)),
                [] => Err(ImportError::new(
                    label,
                    0,
                    format!(
                        "no object named '{want}'; TSurf objects here: {}",
                        surfaces_listed(file)
                    ),
                )),
                [first, ..] => Err(ImportError::new(
                    label,
                    first.line,
                    format!(
                        "{} objects are named '{want}': {}; the name cannot tell them apart, so \
                         select one by its position in the file, e.g. `object = {}`",
                        named.len(),
                        named
                            .iter()
                            .map(|o| listed(file, o))
                            .collect::<Vec<_>>()
                            .join(", "),
                        index_of(first) + 1
                    ),
                )),
            };
        }
        None => {}
    }
    if !opts.skip_other_types
        && let Some(o) = file.objects.iter().find(|o| !o.is_surface())
    {
        return Err(other_type(o, label));
    }
    let surfaces: Vec<&GocadObject> = file.objects.iter().filter(|o| o.is_surface()).collect();
    match surfaces.as_slice() {
        [one] => Ok(index_of(one)),
        [] => Err(no_surface(file, label)),
        many => {
            let mut names: Vec<&str> = many.iter().map(|o| o.name.as_str()).collect();
            names.sort_unstable();
            names.dedup();
            let k = index_of(many[0]) + 1;
            let how = if names.len() == many.len() {
                format!(
                    "name one with `object = \"{}\"`, or select it by its position in the file, \
                     e.g. `object = {k}`",
                    many[0].name
                )
            } else {
                format!(
                    "some share a name, so select one by its position in the file, e.g. \
                     `object = {k}`"
                )
            };
            Err(ImportError::new(
                label,
                many[1].line,
                format!(
                    "the file holds {} TSurf objects ({}); {how}",
                    many.len(),
                    surfaces_listed(file)
                ),
            ))
        }
    }
}

/// Per-axis scale from the object's AXIS_UNIT into the target units.
fn axis_scale(
    o: &GocadObject,
    label: &str,
    target: Option<Units>,
) -> Result<[f64; 3], ImportError> {
    let Some(target) = target else {
        return Ok([1.0; 3]);
    };
    let Some((units, line)) = &o.crs.axis_units else {
        return Ok([Units::Metre.metres() / target.metres(); 3]);
    };
    let mut s = [1.0; 3];
    for k in 0..3 {
        let u = Units::parse(&units[k]).ok_or_else(|| {
            ImportError::new(
                label,
                *line,
                format!(
                    "AXIS_UNIT '{}' is not a length unit this importer knows (m, km, ft)",
                    units[k]
                ),
            )
        })?;
        s[k] = u.metres() / target.metres();
    }
    Ok(s)
}

fn z_is_depth(o: &GocadObject, label: &str) -> Result<bool, ImportError> {
    match &o.crs.zpositive {
        None => Ok(false),
        Some((v, line)) => match v.to_ascii_lowercase().as_str() {
            "depth" => Ok(true),
            "elevation" => Ok(false),
            _ => Err(ImportError::new(
                label,
                *line,
                format!("ZPOSITIVE must be Elevation or Depth, found '{v}'"),
            )),
        },
    }
}

fn convert(
    mut o: GocadObject,
    model: Option<&super::Model3dInfo>,
    label: &str,
    opts: &ImportOptions,
) -> Result<ImportedSurface, ImportError> {
    if o.triangles.is_empty() {
        let name = if o.name.is_empty() {
            String::new()
        } else {
            format!(" '{}'", o.name)
        };
        return Err(ImportError::new(
            label,
            o.line,
            format!("TSurf object{name} has no triangles"),
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
    let scale = axis_scale(&o, label, opts.target_units)?;
    let zsign = if z_is_depth(&o, label)? { -1.0 } else { 1.0 };
    let mut vertices = std::mem::take(&mut o.vertices);
    for (i, p) in vertices.iter_mut().enumerate() {
        let q = [p[0] * scale[0], p[1] * scale[1], zsign * p[2] * scale[2]];
        if q.iter().any(|c| !c.is_finite()) {
            let line = o.vertex_lines.get(i).copied().unwrap_or(0) as usize;
            return Err(ImportError::new(
                label,
                line,
                "coordinate overflows after unit scaling",
            ));
        }
        *p = q;
    }
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
