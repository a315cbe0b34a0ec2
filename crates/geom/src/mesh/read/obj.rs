//! Wavefront OBJ reader: `v x y z [w]` vertices and `f` faces (`i`, `i/t`, `i/t/n`, `i//n`;
//! 1-based, negative = relative to the vertices read so far; polygons fan-triangulated). `g` and
//! `o` statements start a group: each distinct group name gets a tag (1, 2, ... in order of first
//! use) and its name in `tag_names`; faces before any group get tag 0. `l` polylines (same
//! vertex references) are what [`read_obj_lines`] returns, as segments. Other statements (`vn`,
//! `vt`, `usemtl`, `s`, ...) are skipped.

use super::cursor::Cursor;
use super::{BoundaryMesh, LineMesh, ReadError, fan};
use std::collections::BTreeMap;

/// An OBJ file's records as read: vertices and groups in `mesh`, faces and polylines as 1-based
/// absolute vertex numbers with their line (checked against the vertex count at the end).
struct Records {
    mesh: BoundaryMesh,
    faces: Vec<(Vec<i64>, i32, usize)>,
    lines: Vec<(Vec<i64>, usize)>,
}

pub fn read_obj(bytes: &[u8], label: &str) -> Result<BoundaryMesh, ReadError> {
    let c = Cursor::new(bytes, label);
    let Records {
        mut mesh, faces, ..
    } = records(bytes, label)?;
    let mut poly = Vec::new();
    for (f, t, at) in faces {
        poly.clear();
        for i in f {
            poly.push(resolve(i, mesh.vertices.len(), &c, at, "face")?);
        }
        fan(&poly, t, &mut mesh);
    }
    Ok(mesh)
}

/// The `l` records of an OBJ file as segments (a polyline of `n` vertices gives `n - 1`).
pub fn read_obj_lines(bytes: &[u8], label: &str) -> Result<LineMesh, ReadError> {
    let c = Cursor::new(bytes, label);
    let Records { mesh, lines, .. } = records(bytes, label)?;
    let mut out = LineMesh {
        vertices: mesh.vertices,
        lines: Vec::new(),
    };
    for (l, at) in lines {
        let vs = (l.into_iter())
            .map(|i| resolve(i, out.vertices.len(), &c, at, "line"))
            .collect::<Result<Vec<u32>, _>>()?;
        out.lines.extend(vs.windows(2).map(|w| [w[0], w[1]]));
    }
    if out.lines.is_empty() {
        return Err(c.err_at(bytes.len(), "the file holds no lines (`l` records)"));
    }
    Ok(out)
}

/// The 0-based index of the 1-based vertex number `i` of a face or line, if the file has it.
fn resolve(i: i64, nv: usize, c: &Cursor, at: usize, what: &str) -> Result<u32, ReadError> {
    if i > nv as i64 {
        return Err(c.err_at(
            at,
            format!("{what} refers to vertex {i}, but the file has {nv} vertices"),
        ));
    }
    Ok((i - 1) as u32)
}

/// The vertex numbers of a face or line record (`i`, `i/t`, `i/t/n`, `i//n`), made absolute.
fn vertex_refs<'a>(
    it: impl Iterator<Item = &'a str>,
    nv: usize,
    c: &Cursor,
    at: usize,
    what: &str,
) -> Result<Vec<i64>, ReadError> {
    let mut poly = Vec::new();
    for t in it {
        let first = t.split('/').next().unwrap_or("");
        let i: i64 = first
            .parse()
            .map_err(|_| c.err_at(at, format!("bad vertex reference '{t}' in {what}")))?;
        let abs = match i {
            0 => {
                return Err(c.err_at(
                    at,
                    format!("vertex index 0 in {what} (OBJ indices start at 1)"),
                ));
            }
            i if i < 0 => nv as i64 + i + 1,
            i => i,
        };
        if abs < 1 {
            return Err(c.err_at(
                at,
                format!(
                    "relative vertex index {i} reaches before the first vertex ({nv} read so far)"
                ),
            ));
        }
        poly.push(abs);
    }
    Ok(poly)
}

fn records(bytes: &[u8], label: &str) -> Result<Records, ReadError> {
    let mut c = Cursor::new(bytes, label);
    let mut out = Records {
        mesh: BoundaryMesh::default(),
        faces: Vec::new(),
        lines: Vec::new(),
    };
    let mut tag_of: BTreeMap<String, i32> = BTreeMap::new();
    let mut tag = 0i32;
    // Faces and lines are checked once every vertex is known (forward references are tolerated).
    while let Some((line, at)) = c.line() {
        let Ok(text) = std::str::from_utf8(line) else {
            return Err(c.err_at(at, "line is not UTF-8 text"));
        };
        let text = text.split('#').next().unwrap_or("");
        let mut it = text.split_ascii_whitespace();
        let Some(kw) = it.next() else { continue };
        let nv = out.mesh.vertices.len();
        match kw {
            "v" => {
                let mut p = [0.0; 3];
                for (k, v) in p.iter_mut().enumerate() {
                    let t = it
                        .next()
                        .ok_or_else(|| c.err_at(at, "vertex has fewer than 3 coordinates"))?;
                    *v = match t.parse::<f64>() {
                        Ok(x) if x.is_finite() => x,
                        _ => {
                            return Err(c.err_at(
                                at,
                                format!("vertex coordinate {k} is not a finite number: '{t}'"),
                            ));
                        }
                    };
                }
                out.mesh.vertices.push(p);
            }
            "f" => {
                let poly = vertex_refs(it, nv, &c, at, "face")?;
                if poly.len() < 3 {
                    return Err(c.err_at(
                        at,
                        format!("face has {} vertices; at least 3 are needed", poly.len()),
                    ));
                }
                out.faces.push((poly, tag, at));
            }
            "l" => {
                let poly = vertex_refs(it, nv, &c, at, "line")?;
                if poly.len() < 2 {
                    return Err(c.err_at(
                        at,
                        format!("line has {} vertices; at least 2 are needed", poly.len()),
                    ));
                }
                out.lines.push((poly, at));
            }
            "g" | "o" => {
                let name: Vec<&str> = it.collect();
                let name = name.join(" ");
                if name.is_empty() {
                    tag = 0;
                } else {
                    let next = tag_of.len() as i32 + 1;
                    tag = *tag_of.entry(name.clone()).or_insert(next);
                    out.mesh.tag_names.insert(tag, name);
                }
            }
            _ => {}
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_become_tags_in_order_of_first_use_and_keep_their_names() {
        let src = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\ng top\nf 2/5/1 4//2 3\ng side\nf -4 -3 -1\ng top\nf 1 2 4\n";
        let m = read_obj(src, "g.obj").unwrap();
        assert_eq!(m.triangle_tag, vec![0, 1, 2, 1]);
        assert_eq!(m.tag_names.get(&1).map(String::as_str), Some("top"));
        assert_eq!(m.tag_names.get(&2).map(String::as_str), Some("side"));
        assert_eq!(m.triangles[2], [0, 1, 3]);
        assert_eq!(m.triangles[1], [1, 3, 2]);
    }

    #[test]
    fn a_pentagon_becomes_three_triangles() {
        let src = b"v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\n";
        let m = read_obj(src, "p.obj").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
    }

    #[test]
    fn a_face_pointing_at_a_missing_vertex_names_the_line() {
        let e = read_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n", "bad.obj").unwrap_err();
        assert_eq!((e.file.as_str(), e.line), ("bad.obj", 5));
        assert!(e.message.contains("vertex 9"), "{e}");
    }

    #[test]
    fn a_relative_index_before_the_first_vertex_is_refused() {
        let e = read_obj(b"v 0 0 0\nf -1 -2 -3\n", "r.obj").unwrap_err();
        assert_eq!(e.line, 2);
    }

    #[test]
    fn a_short_vertex_line_is_refused() {
        let e = read_obj(b"v 0 0\n", "s.obj").unwrap_err();
        assert_eq!(
            e.to_string(),
            "s.obj:1: vertex has fewer than 3 coordinates"
        );
    }

    #[test]
    fn polylines_become_segments_between_consecutive_vertices() {
        let src = b"v 0 0 0\nv 0 0 -1\nv 1 0 -2\nv 5 5 5\nl 1 2 3\nl -1/1 1\nf 1 2 3\n";
        let m = read_obj_lines(src, "w.obj").unwrap();
        assert_eq!(m.lines, vec![[0, 1], [1, 2], [3, 0]]);
        assert_eq!(m.vertices.len(), 4);
        // The faces are the surface reader's, the lines the line reader's.
        assert_eq!(read_obj(src, "w.obj").unwrap().triangles.len(), 1);
    }

    #[test]
    fn a_line_of_one_vertex_or_a_file_without_lines_is_refused() {
        let e = read_obj_lines(b"v 0 0 0\nl 1\n", "one.obj").unwrap_err();
        assert_eq!(
            e.to_string(),
            "one.obj:2: line has 1 vertices; at least 2 are needed"
        );
        let e = read_obj_lines(b"v 0 0 0\nv 1 0 0\n", "none.obj").unwrap_err();
        assert!(e.message.contains("no lines"), "{e}");
        let e = read_obj_lines(b"v 0 0 0\nl 1 3\n", "far.obj").unwrap_err();
        assert!(e.message.contains("line refers to vertex 3"), "{e}");
    }
}
