//! Draws shaded 3D triangles as an SVG picture: an oblique axonometric (parallel) view from the
//! south-west and above, the painter's algorithm (far faces first), flat shading quantised to a
//! few light levels, and a bounded size.
//!
//! Decisions made here are about pictures only, never about the model: depth order and shading
//! are floating-point measures; whether a face looks at the viewer (back-face culling) is the
//! exact `orient2d` of its projected corners (a projected triangle turning counter-clockwise in
//! the (right, up) screen frame faces the viewer, because right × up = towards the viewer).
//!
//! Size bound (the rule quoted in every caption): when more than `cap` faces would be drawn, the
//! corners are snapped to a square grid of `cell` units (vertex clustering in the picture): a
//! face whose snapped corners collapse is dropped (its neighbours, snapped alike, cover it
//! without a gap), and of faces with the same snapped corners only the nearest is kept (it hides
//! the others exactly). `cell` starts at one unit (of a picture at most 960 units wide and 640
//! high) and grows by a quarter until at most `cap` faces remain.
//!
//! Lines (the wells) are drawn after every face, dark and named at their heads: they lie inside
//! the model, so painted in depth order they would be hidden by the surfaces around them, which
//! is the opposite of what a picture of where the wells go is for. They are not under the size
//! bound (a well is a few thousand points at most); consecutive points that fall on the same
//! tenth of a picture unit are written once.

use super::palette::Rgb;
use super::text::{coord, esc};
use geom::BBox;
use geom::predicates::{Orientation, cross, dot, orient2d, sub};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// Picture width in SVG units.
pub const WIDTH: f64 = 960.0;
/// Largest picture height in SVG units.
pub const MAX_HEIGHT: f64 = 640.0;
const MARGIN: f64 = 16.0;
/// Number of light levels of the flat shading.
const LEVELS: u8 = 8;

/// A parallel projection: `right` and `up` span the screen, `toward` points at the viewer.
#[derive(Copy, Clone, Debug)]
pub struct Camera {
    pub right: [f64; 3],
    pub up: [f64; 3],
    pub toward: [f64; 3],
}

impl Camera {
    /// The oblique view used by every picture: from azimuth 35° west of south, 30° above the
    /// horizon (x east, y north, z up).
    pub fn oblique() -> Camera {
        let (a, e) = (35f64.to_radians(), 30f64.to_radians());
        let toward = [-a.sin() * e.cos(), -a.cos() * e.cos(), e.sin()];
        let right = [a.cos(), -a.sin(), 0.0];
        let up = cross(&toward, &right);
        Camera { right, up, toward }
    }

    /// Screen coordinates (right, up) of a point.
    pub fn project(&self, p: &[f64; 3]) -> [f64; 2] {
        [dot(&self.right, p), dot(&self.up, p)]
    }

    /// Larger is nearer the viewer.
    pub fn depth(&self, p: &[f64; 3]) -> f64 {
        dot(&self.toward, p)
    }
}

/// A triangle to draw, with the index of its colour in the picture's colour list.
#[derive(Copy, Clone, Debug)]
pub struct Face {
    pub pts: [[f64; 3]; 3],
    pub colour: u32,
}

/// A named set of 3D polylines drawn over the faces (a well), its name written at `head`.
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    pub name: String,
    pub parts: Vec<Vec<[f64; 3]>>,
    pub head: Option<[f64; 3]>,
}

/// How a picture is drawn.
#[derive(Clone, Debug)]
pub struct Style<'a> {
    /// Prefix of the CSS classes (unique per picture in one HTML page).
    pub id: &'a str,
    /// Colours, indexed by [`Face::colour`].
    pub colours: &'a [Rgb],
    /// Draw only faces that look at the viewer.
    pub cull_back: bool,
    /// Stroke of the triangle edges: `None` strokes each face with its own fill (no seams).
    pub edges: Option<&'a str>,
    /// Most faces drawn.
    pub cap: usize,
    /// Title inside the SVG (for screen readers and standalone viewing).
    pub title: &'a str,
    /// Drawn over the faces, in order.
    pub lines: &'a [Line],
}

/// A drawn picture and the figures its caption quotes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Picture {
    pub svg: String,
    /// Faces that would be drawn without the size bound (after culling).
    pub visible: usize,
    /// Faces drawn.
    pub drawn: usize,
    /// Cell size of the size bound (0 when every visible face is drawn).
    pub cell: f64,
}

struct Flat {
    p: [[f64; 2]; 3],
    depth: f64,
    colour: u32,
    level: u8,
}

fn finite3(p: &[[f64; 3]; 3]) -> bool {
    p.iter().all(|q| q.iter().all(|c| c.is_finite()))
}

/// Light level in `0..LEVELS` from the face normal (two-sided: a face lit from behind is lit).
fn level(cam: &Camera, p: &[[f64; 3]; 3]) -> u8 {
    let n = cross(&sub(&p[1], &p[0]), &sub(&p[2], &p[0]));
    let len = dot(&n, &n).sqrt();
    if len == 0.0 || !len.is_finite() {
        return LEVELS / 2;
    }
    // Light from the viewer's upper left.
    let l: [f64; 3] =
        std::array::from_fn(|k| 0.75 * cam.toward[k] + 0.55 * cam.up[k] - 0.35 * cam.right[k]);
    let ll = dot(&l, &l).sqrt();
    let i = (dot(&n, &l) / (len * ll)).abs();
    ((i * (LEVELS - 1) as f64).round() as u8).min(LEVELS - 1)
}

fn shade_of(level: u8) -> f64 {
    0.5 + 0.5 * level as f64 / (LEVELS - 1) as f64
}

/// Screen frame: maps projected coordinates into the picture, fitting `frame`'s eight corners.
struct Fit {
    min: [f64; 2],
    scale: f64,
    width: f64,
    height: f64,
}

impl Fit {
    fn new(cam: &Camera, frame: &BBox) -> Fit {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for i in 0..8 {
            let c = [
                if i & 1 == 0 {
                    frame.min[0]
                } else {
                    frame.max[0]
                },
                if i & 2 == 0 {
                    frame.min[1]
                } else {
                    frame.max[1]
                },
                if i & 4 == 0 {
                    frame.min[2]
                } else {
                    frame.max[2]
                },
            ];
            let q = cam.project(&c);
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        let (dx, dy) = (hi[0] - lo[0], hi[1] - lo[1]);
        if !(dx.is_finite() && dy.is_finite()) || dx <= 0.0 && dy <= 0.0 {
            return Fit {
                min: [0.0; 2],
                scale: 0.0,
                width: 2.0 * MARGIN,
                height: 2.0 * MARGIN,
            };
        }
        let sx = if dx > 0.0 {
            (WIDTH - 2.0 * MARGIN) / dx
        } else {
            f64::INFINITY
        };
        let sy = if dy > 0.0 {
            (MAX_HEIGHT - 2.0 * MARGIN) / dy
        } else {
            f64::INFINITY
        };
        let scale = sx.min(sy);
        Fit {
            min: [lo[0], hi[1]],
            scale,
            width: (dx * scale + 2.0 * MARGIN).ceil().min(WIDTH),
            height: (dy * scale + 2.0 * MARGIN).ceil().min(MAX_HEIGHT),
        }
    }
    /// Picture coordinates (y down).
    fn map(&self, q: [f64; 2]) -> [f64; 2] {
        [
            MARGIN + (q[0] - self.min[0]) * self.scale,
            MARGIN + (self.min[1] - q[1]) * self.scale,
        ]
    }
}

/// Draws `faces` framed on `frame` (normally the whole mesh's box, so pictures line up).
pub fn draw(faces: &[Face], frame: &BBox, style: &Style) -> Picture {
    let cam = Camera::oblique();
    let fit = Fit::new(&cam, frame);
    let mut flat: Vec<Flat> = Vec::with_capacity(faces.len());
    for f in faces {
        if !finite3(&f.pts) {
            continue;
        }
        let q = f.pts.map(|p| cam.project(&p));
        if style.cull_back && orient2d(&q[0], &q[1], &q[2]) != Orientation::Positive {
            continue;
        }
        let c: [f64; 3] = std::array::from_fn(|k| (f.pts[0][k] + f.pts[1][k] + f.pts[2][k]) / 3.0);
        flat.push(Flat {
            p: q.map(|q| fit.map(q)),
            depth: cam.depth(&c),
            colour: f.colour,
            level: level(&cam, &f.pts),
        });
    }
    // Far first; ties by input order (the sort is stable), so the bytes are deterministic.
    flat.sort_by(|a, b| a.depth.total_cmp(&b.depth));
    let visible = flat.len();
    let (keep, cell) = bound(&flat, fit.width, fit.height, style.cap);
    let svg = write_svg(&flat, &keep, cell, (&cam, &fit), style);
    Picture {
        svg,
        visible,
        drawn: keep.iter().filter(|&&k| k).count(),
        cell,
    }
}

/// Grid coordinates of a picture point snapped to a grid of `cell` units.
fn snap(p: [f64; 2], cell: f64) -> [i64; 2] {
    // Float-to-int casts saturate, so no input can overflow here.
    [(p[0] / cell).round() as i64, (p[1] / cell).round() as i64]
}

/// Which faces to draw under the size bound (see the module doc), and the cell size used.
fn bound(flat: &[Flat], width: f64, height: f64, cap: usize) -> (Vec<bool>, f64) {
    if flat.len() <= cap {
        return (vec![true; flat.len()], 0.0);
    }
    let mut cell = 1.0f64;
    loop {
        // (sorted snapped corners, nearest first) of every face that does not collapse.
        let mut keys: Vec<([[i64; 2]; 3], std::cmp::Reverse<usize>)> = flat
            .iter()
            .enumerate()
            .filter_map(|(i, f)| {
                let mut k = f.p.map(|q| snap(q, cell));
                k.sort_unstable();
                (k[0] != k[1] && k[1] != k[2]).then_some((k, std::cmp::Reverse(i)))
            })
            .collect();
        keys.sort_unstable();
        keys.dedup_by(|b, a| a.0 == b.0);
        if keys.len() <= cap || cell >= width.max(height) {
            let mut keep = vec![false; flat.len()];
            for (_, std::cmp::Reverse(i)) in keys {
                keep[i] = true;
            }
            return (keep, cell);
        }
        cell *= 1.25;
    }
}

fn write_svg(
    flat: &[Flat],
    keep: &[bool],
    cell: f64,
    (cam, fit): (&Camera, &Fit),
    style: &Style,
) -> String {
    let (width, height) = (fit.width, fit.height);
    let id = style.id;
    let mut used: Vec<(u32, u8)> = flat
        .iter()
        .zip(keep)
        .filter(|(_, k)| **k)
        .map(|(f, _)| (f.colour, f.level))
        .collect();
    used.sort_unstable();
    used.dedup();
    let mut s = String::with_capacity(64 * used.len() + 48 * keep.len() + 512);
    let _ = write!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {} {}\" width=\"{}\" height=\"{}\" role=\"img\"><title>{}</title><style>",
        width,
        height,
        width,
        height,
        esc(style.title)
    );
    let _ = write!(
        s,
        ".{id} path{{stroke-width:{};stroke-linejoin:round}}",
        if style.edges.is_some() { "0.35" } else { "0.6" }
    );
    for (c, l) in &used {
        let base = style
            .colours
            .get(*c as usize)
            .copied()
            .unwrap_or(Rgb(128, 128, 128));
        let fill = base.shade(shade_of(*l)).hex();
        let stroke = style
            .edges
            .map(str::to_string)
            .unwrap_or_else(|| fill.clone());
        let _ = write!(s, ".{id}{c}_{l}{{fill:{fill};stroke:{stroke}}}");
    }
    let _ = write!(s, "</style><g class=\"{id}\">");
    for (f, _) in flat.iter().zip(keep).filter(|(_, k)| **k) {
        // Under the size bound the corners are drawn snapped, so neighbours stay watertight.
        let p = if cell > 0.0 {
            f.p.map(|q| snap(q, cell).map(|v| v as f64 * cell))
        } else {
            f.p
        };
        let _ = write!(
            s,
            "<path class=\"{id}{}_{}\" d=\"M{} {} {} {} {} {}z\"/>",
            f.colour,
            f.level,
            coord(p[0][0]),
            coord(p[0][1]),
            coord(p[1][0]),
            coord(p[1][1]),
            coord(p[2][0]),
            coord(p[2][1])
        );
    }
    s.push_str("</g>");
    if !style.lines.is_empty() {
        s.push_str(&lines_svg(cam, fit, style));
    }
    axes(&mut s, height);
    s.push_str("</svg>");
    s
}

/// The lines of `style` over the faces: one `<polyline>` per part with the line's name as its
/// `<title>`, then every name at its head in dark text on a white halo.
fn lines_svg(cam: &Camera, fit: &Fit, style: &Style) -> String {
    let id = style.id;
    let mut s = format!(
        "<g class=\"{id}-wells\" fill=\"none\" stroke=\"#111\" stroke-width=\"2\" stroke-linejoin=\"round\" stroke-linecap=\"round\">"
    );
    let mut labels = String::new();
    for line in style.lines {
        let name = esc(&line.name);
        for part in &line.parts {
            let mut points: Vec<String> = Vec::with_capacity(part.len());
            let mut last = String::new();
            for p in part.iter().filter(|p| p.iter().all(|c| c.is_finite())) {
                let q = fit.map(cam.project(p));
                let xy = format!("{},{}", coord(q[0]), coord(q[1]));
                if xy != last {
                    points.push(xy.clone());
                    last = xy;
                }
            }
            if points.len() < 2 {
                continue;
            }
            let _ = write!(
                s,
                "<polyline points=\"{}\"><title>{name}</title></polyline>",
                points.join(" ")
            );
        }
        if let Some(h) = line.head.filter(|h| h.iter().all(|c| c.is_finite())) {
            let q = fit.map(cam.project(&h));
            let _ = write!(
                labels,
                "<text x=\"{}\" y=\"{}\">{name}</text>",
                coord(q[0] + 4.0),
                coord(q[1] - 5.0)
            );
        }
    }
    s.push_str("</g>");
    if !labels.is_empty() {
        let _ = write!(
            s,
            "<g class=\"{id}-names\" font-size=\"12\" font-weight=\"600\" font-family=\"sans-serif\" fill=\"#111\" stroke=\"#fff\" stroke-width=\"3\" stroke-linejoin=\"round\" paint-order=\"stroke\">{labels}</g>"
        );
    }
    s
}

/// A small x/y/z tripod in the lower left corner, so the view can be read.
fn axes(s: &mut String, height: f64) {
    let cam = Camera::oblique();
    let o = [MARGIN + 22.0, height - MARGIN - 8.0];
    s.push_str(
        "<g stroke=\"#333\" stroke-width=\"1.2\" font-size=\"11\" font-family=\"sans-serif\">",
    );
    for (name, dir) in [
        ("x", [1.0, 0.0, 0.0]),
        ("y", [0.0, 1.0, 0.0]),
        ("z", [0.0, 0.0, 1.0]),
    ] {
        let q = cam.project(&dir);
        let e = [o[0] + 20.0 * q[0], o[1] - 20.0 * q[1]];
        let t = [o[0] + 27.0 * q[0] - 3.0, o[1] - 27.0 * q[1] + 4.0];
        let _ = write!(
            s,
            "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/><text x=\"{}\" y=\"{}\" stroke=\"none\" fill=\"#333\">{name}</text>",
            coord(o[0]),
            coord(o[1]),
            coord(e[0]),
            coord(e[1]),
            coord(t[0]),
            coord(t[1])
        );
    }
    s.push_str("</g>");
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(z: f64, colour: u32) -> Face {
        Face {
            pts: [[0.0, 0.0, z], [1.0, 0.0, z], [0.0, 1.0, z]],
            colour,
        }
    }

    fn frame() -> BBox {
        BBox {
            min: [0.0; 3],
            max: [1.0; 3],
        }
    }

    fn style(cap: usize, cull: bool) -> Style<'static> {
        Style {
            id: "t",
            colours: &[Rgb(255, 0, 0), Rgb(0, 0, 255)],
            cull_back: cull,
            edges: None,
            cap,
            title: "test",
            lines: &[],
        }
    }

    #[test]
    fn the_camera_frame_is_orthonormal_and_right_handed() {
        let c = Camera::oblique();
        for v in [c.right, c.up, c.toward] {
            assert!((dot(&v, &v) - 1.0).abs() < 1e-12);
        }
        assert!(dot(&c.right, &c.up).abs() < 1e-12);
        let w = cross(&c.right, &c.up);
        assert!((dot(&w, &c.toward) - 1.0).abs() < 1e-12);
        // Seen from above: the top of a column is nearer than its foot.
        assert!(c.depth(&[0.0, 0.0, 1.0]) > c.depth(&[0.0, 0.0, 0.0]));
    }

    #[test]
    fn far_faces_are_painted_before_near_ones() {
        let p = draw(&[tri(1.0, 1), tri(0.0, 0)], &frame(), &style(10, false));
        let low = p.svg.find("class=\"t0_").unwrap();
        let high = p.svg.find("class=\"t1_").unwrap();
        assert!(
            low < high,
            "the lower triangle (farther from a viewer above) comes first"
        );
        assert_eq!((p.visible, p.drawn, p.cell), (2, 2, 0.0));
    }

    #[test]
    fn back_faces_are_culled_only_when_asked() {
        let up = tri(0.0, 0);
        let mut down = tri(0.5, 1);
        down.pts.swap(1, 2);
        let p = draw(&[up, down], &frame(), &style(10, true));
        assert_eq!(p.visible, 1);
        assert!(p.svg.contains("class=\"t0_"));
        assert!(!p.svg.contains("class=\"t1_"));
        let q = draw(&[up, down], &frame(), &style(10, false));
        assert_eq!(q.visible, 2);
    }

    #[test]
    fn the_size_bound_keeps_at_most_cap_faces_of_a_fine_surface() {
        // A plane of 100 × 100 squares (20 000 triangles), capped at 2 000.
        let n = 100;
        let mut faces = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let (x, y, h) = (i as f64 / n as f64, j as f64 / n as f64, 1.0 / n as f64);
                faces.push(Face {
                    pts: [[x, y, 0.0], [x + h, y, 0.0], [x + h, y + h, 0.0]],
                    colour: 0,
                });
                faces.push(Face {
                    pts: [[x, y, 0.0], [x + h, y + h, 0.0], [x, y + h, 0.0]],
                    colour: 1,
                });
            }
        }
        let p = draw(&faces, &frame(), &style(2000, false));
        assert_eq!(p.visible, 20_000);
        assert!(p.drawn <= 2000 && p.drawn > 200, "drawn {}", p.drawn);
        assert!(p.cell >= 2.0);
        assert_eq!(p.svg.matches("<path").count(), p.drawn);
    }

    #[test]
    fn of_faces_that_coincide_in_the_picture_the_nearest_is_kept() {
        let cam = Camera::oblique();
        let far = tri(0.0, 0);
        let mut near = far;
        near.colour = 1;
        for q in &mut near.pts {
            for (c, t) in q.iter_mut().zip(cam.toward) {
                *c += 0.5 * t;
            }
        }
        let p = draw(&[near, far], &frame(), &style(1, false));
        assert_eq!((p.visible, p.drawn), (2, 1));
        assert!(p.svg.contains("class=\"t1_"));
        assert!(!p.svg.contains("class=\"t0_"));
    }

    #[test]
    fn faces_with_non_finite_corners_are_skipped() {
        let mut bad = tri(0.0, 0);
        bad.pts[1][0] = f64::NAN;
        let p = draw(&[bad], &frame(), &style(10, false));
        assert_eq!(p.visible, 0);
        assert!(p.svg.starts_with("<svg") && p.svg.ends_with("</svg>"));
    }
}
