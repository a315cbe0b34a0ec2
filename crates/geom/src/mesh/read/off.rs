//! OFF reader (Geomview Object File Format, ASCII): an `OFF` header (`COFF`, `NOFF`, ... are
//! accepted, colours and normals after the coordinates ignored), counts `nv nf [ne]`, `nv` vertex
//! lines, `nf` face lines `n i1 .. in [colour]` with 0-based indices. `#` starts a comment.
//! Every triangle gets tag 0.

use super::cursor::Cursor;
use super::{BoundaryMesh, ReadError, fan};

/// The next non-empty, comment-stripped line as tokens, with its start offset.
fn tokens<'a>(c: &mut Cursor<'a>) -> Option<(Vec<&'a str>, usize)> {
    while let Some((line, at)) = c.line() {
        let text = match std::str::from_utf8(line) {
            Ok(t) => t,
            Err(_) => return Some((vec!["\u{fffd}"], at)),
        };
        let text = text.split('#').next().unwrap_or("");
        let toks: Vec<&str> = text.split_ascii_whitespace().collect();
        if !toks.is_empty() {
            return Some((toks, at));
        }
    }
    None
}

fn parse<T: std::str::FromStr>(
    c: &Cursor,
    at: usize,
    tok: Option<&&str>,
    what: &str,
) -> Result<T, ReadError> {
    let t = tok.ok_or_else(|| c.err_at(at, format!("missing {what}")))?;
    t.parse()
        .map_err(|_| c.err_at(at, format!("expected {what}, found '{t}'")))
}

pub fn read_off(bytes: &[u8], label: &str) -> Result<BoundaryMesh, ReadError> {
    let mut c = Cursor::new(bytes, label);
    let (head, at) = tokens(&mut c).ok_or_else(|| c.err("empty file: expected an OFF header"))?;
    if !head[0].ends_with("OFF") {
        return Err(c.err_at(at, format!("expected an OFF header, found '{}'", head[0])));
    }
    let (counts, at) = if head.len() > 1 {
        (head[1..].to_vec(), at)
    } else {
        tokens(&mut c)
            .ok_or_else(|| c.err("unexpected end of file: expected the vertex and face counts"))?
    };
    let nv: usize = parse(&c, at, counts.first(), "the vertex count")?;
    let nf: usize = parse(&c, at, counts.get(1), "the face count")?;
    let mut out = BoundaryMesh::default();
    // Counts are untrusted: cap the reservation by what the file could hold.
    out.vertices.reserve(nv.min(bytes.len() / 6));
    for i in 0..nv {
        let (t, at) = tokens(&mut c).ok_or_else(|| {
            c.err(format!(
                "unexpected end of file: expected vertex {i} of {nv}"
            ))
        })?;
        let mut p = [0.0; 3];
        for (k, v) in p.iter_mut().enumerate() {
            let x: f64 = parse(
                &c,
                at,
                t.get(k),
                &format!("coordinate {} of vertex {i}", ["x", "y", "z"][k]),
            )?;
            if !x.is_finite() {
                return Err(c.err_at(at, format!("vertex {i} has a non-finite coordinate")));
            }
            *v = x;
        }
        out.vertices.push(p);
    }
    out.triangles.reserve(nf.min(bytes.len() / 8));
    let mut poly = Vec::new();
    for f in 0..nf {
        let (t, at) = tokens(&mut c)
            .ok_or_else(|| c.err(format!("unexpected end of file: expected face {f} of {nf}")))?;
        let n: usize = parse(&c, at, t.first(), &format!("the vertex count of face {f}"))?;
        if n < 3 {
            return Err(c.err_at(
                at,
                format!("face {f} has {n} vertices; at least 3 are needed"),
            ));
        }
        if t.len() < n + 1 {
            return Err(c.err_at(
                at,
                format!("face {f} announces {n} vertices but lists {}", t.len() - 1),
            ));
        }
        poly.clear();
        for k in 0..n {
            let i: i64 = parse(
                &c,
                at,
                t.get(k + 1),
                &format!("vertex index {k} of face {f}"),
            )?;
            if i < 0 || i as usize >= nv {
                return Err(c.err_at(
                    at,
                    format!("face {f} refers to vertex {i}, but there are {nv} vertices (0-based)"),
                ));
            }
            poly.push(i as u32);
        }
        fan(&poly, 0, &mut out);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quad_with_colour_is_fan_triangulated_and_comments_are_skipped() {
        let src = b"OFF # cube face\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n\n# the face\n4 0 1 2 3 255 0 0\n";
        let m = read_off(src, "q.off").unwrap();
        assert_eq!(m.vertices.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.triangle_tag, vec![0, 0]);
    }

    #[test]
    fn counts_on_the_header_line_are_accepted() {
        let m = read_off(b"OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 2 1 0\n", "h.off").unwrap();
        assert_eq!(m.triangles, vec![[2, 1, 0]]);
    }

    #[test]
    fn a_face_pointing_at_a_missing_vertex_names_the_line() {
        let e = read_off(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "bad.off").unwrap_err();
        assert_eq!((e.file.as_str(), e.line), ("bad.off", 6));
        assert!(e.message.contains("vertex 7"), "{e}");
    }

    #[test]
    fn a_truncated_file_says_which_vertex_is_missing() {
        let e = read_off(b"OFF\n3 1 0\n0 0 0\n1 0 0\n", "t.off").unwrap_err();
        assert!(e.message.contains("vertex 2 of 3"), "{e}");
    }

    #[test]
    fn a_nan_coordinate_is_refused_with_its_line() {
        let e = read_off(b"OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "n.off").unwrap_err();
        assert_eq!(e.line, 4, "{e}");
    }

    #[test]
    fn a_missing_header_is_refused() {
        let e = read_off(b"PLY\n", "p.off").unwrap_err();
        assert!(
            e.to_string().starts_with("p.off:1: expected an OFF header"),
            "{e}"
        );
    }
}
