//! Wavefront OBJ reader: `v x y z [w]` vertices and `f` faces (`i`, `i/t`, `i/t/n`, `i//n`;
//! 1-based, negative = relative to the vertices read so far; polygons fan-triangulated). `g` and
//! `o` statements start a group: each distinct group name gets a tag (1, 2, ... in order of first
//! use) and its name in `tag_names`; faces before any group get tag 0. Other statements
//! (`vn`, `vt`, `usemtl`, `s`, `l`, ...) are skipped.

use super::cursor::Cursor;
use super::{BoundaryMesh, ReadError, fan};
use std::collections::BTreeMap;

pub fn read_obj(bytes: &[u8], label: &str) -> Result<BoundaryMesh, ReadError> {
    let mut c = Cursor::new(bytes, label);
    let mut out = BoundaryMesh::default();
    let mut tag_of: BTreeMap<String, i32> = BTreeMap::new();
    let mut tag = 0i32;
    // Faces are checked once every vertex is known (forward references are tolerated).
    let mut faces: Vec<(Vec<i64>, i32, usize)> = Vec::new();
    while let Some((line, at)) = c.line() {
        let Ok(text) = std::str::from_utf8(line) else {
            return Err(c.err_at(at, "line is not UTF-8 text"));
        };
        let text = text.split('#').next().unwrap_or("");
        let mut it = text.split_ascii_whitespace();
        let Some(kw) = it.next() else { continue };
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
                out.vertices.push(p);
            }
            "f" => {
                let mut poly = Vec::new();
                for t in it {
                    let first = t.split('/').next().unwrap_or("");
                    let i: i64 = first
                        .parse()
                        .map_err(|_| c.err_at(at, format!("bad vertex reference '{t}' in face")))?;
                    let abs = match i {
                        0 => {
                            return Err(
                                c.err_at(at, "vertex index 0 in face (OBJ indices start at 1)")
                            );
                        }
                        i if i < 0 => out.vertices.len() as i64 + i + 1,
                        i => i,
                    };
                    if abs < 1 {
                        return Err(c.err_at(
                            at,
                            format!("relative vertex index {i} reaches before the first vertex ({} read so far)", out.vertices.len()),
                        ));
                    }
                    poly.push(abs);
                }
                if poly.len() < 3 {
                    return Err(c.err_at(
                        at,
                        format!("face has {} vertices; at least 3 are needed", poly.len()),
                    ));
                }
                faces.push((poly, tag, at));
            }
            "g" | "o" => {
                let name: Vec<&str> = it.collect();
                let name = name.join(" ");
                if name.is_empty() {
                    tag = 0;
                } else {
                    let next = tag_of.len() as i32 + 1;
                    tag = *tag_of.entry(name.clone()).or_insert(next);
                    out.tag_names.insert(tag, name);
                }
            }
            _ => {}
        }
    }
    let nv = out.vertices.len() as i64;
    let mut poly = Vec::new();
    for (f, t, at) in faces {
        poly.clear();
        for i in f {
            if i > nv {
                return Err(c.err_at(
                    at,
                    format!("face refers to vertex {i}, but the file has {nv} vertices"),
                ));
            }
            poly.push((i - 1) as u32);
        }
        fan(&poly, t, &mut out);
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
}
