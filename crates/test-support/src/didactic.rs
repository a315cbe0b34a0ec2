//! The data of the shipped example `recipes/didactic.toml`: the seed paper's didactic
//! model (Miranda et al. 2015, §6), the same geometry that `../shared/tools/bench_peers.py` builds
//! in Gmsh, shifted to UTM-sized coordinates.
//!
//! - Box: [0, 5000] × [0, 5000] × [-2500, 0] m, shifted by (ORIGIN_X, ORIGIN_Y).
//! - Horizon H1 (top of the reservoir): z = -1200 + 80 sin(x/900) cos(y/1100) (local x, y).
//! - Horizon H2 (base of the reservoir): H1 - 35 m, written with `ZPOSITIVE Depth` and CRLF.
//! - Fault F1: through-going plane, strike along y, dip 70°, through x = 1500 at z = -1200.
//! - Fault F2: dangling rectangle 1600 × 700 m, strike along x, dip 60°, centre (3400, 3300, -1200);
//!   it crosses the reservoir and dies out above and below it.
//!
//! Surfaces are triangulated irregularly, as gOcad exports are: jittered grids of varying spacing
//! with the quad diagonals chosen by a seeded generator, so the output is the same on every machine.

use std::fmt::Write as _;

pub(crate) const ORIGIN_X: f64 = 500_000.0;
pub(crate) const ORIGIN_Y: f64 = 7_000_000.0;

/// A small deterministic generator (SplitMix64): no unseeded randomness anywhere.
pub struct Rng(pub u64);
impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [-1, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

pub(crate) fn z_top(x: f64, y: f64) -> f64 {
    -1200.0 + 80.0 * (x / 900.0).sin() * (y / 1100.0).cos()
}

/// Grid coordinates from `a` to `b` with spacings that vary smoothly between `h` and `1.6 h`.
pub(crate) fn graded_axis(a: f64, b: f64, h: f64, phase: f64) -> Vec<f64> {
    let mut v = vec![a];
    let mut x = a;
    while x < b {
        let t = (x - a) / (b - a);
        let step = h * (1.3 + 0.3 * (6.0 * t + phase).sin());
        x = (x + step).min(b);
        if b - x < 0.3 * h {
            x = b;
        }
        v.push(x);
    }
    v
}

/// A surface given by a parametric map over a jittered, graded (u, v) grid.
pub(crate) struct Surface {
    pub(crate) vertices: Vec<[f64; 3]>,
    pub(crate) triangles: Vec<[usize; 3]>,
    /// Corners of the parameter rectangle (vertex indices), written as BSTONEs.
    pub(crate) corners: Vec<usize>,
}

pub(crate) fn grid_surface(
    us: &[f64],
    vs: &[f64],
    map: impl Fn(f64, f64) -> [f64; 3],
    rng: &mut Rng,
) -> Surface {
    let (nu, nv) = (us.len(), vs.len());
    let mut vertices = Vec::with_capacity(nu * nv);
    for (j, &v) in vs.iter().enumerate() {
        for (i, &u) in us.iter().enumerate() {
            let (mut uu, mut vv) = (u, v);
            // Jitter interior points by at most a fifth of the neighbouring spacings, which keeps
            // every quad convex so that either diagonal gives valid triangles.
            if i > 0 && i + 1 < nu {
                let h = (us[i + 1] - us[i]).min(us[i] - us[i - 1]);
                uu += 0.2 * h * rng.unit();
            }
            if j > 0 && j + 1 < nv {
                let h = (vs[j + 1] - vs[j]).min(vs[j] - vs[j - 1]);
                vv += 0.2 * h * rng.unit();
            }
            vertices.push(map(uu, vv));
        }
    }
    let id = |i: usize, j: usize| j * nu + i;
    let mut triangles = Vec::with_capacity(2 * (nu - 1) * (nv - 1));
    for j in 0..nv - 1 {
        for i in 0..nu - 1 {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if rng.next_u64() & 1 == 0 {
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            } else {
                triangles.push([a, b, d]);
                triangles.push([b, c, d]);
            }
        }
    }
    let corners = vec![id(0, 0), id(nu - 1, 0), id(nu - 1, nv - 1), id(0, nv - 1)];
    Surface {
        vertices,
        triangles,
        corners,
    }
}

pub(crate) struct Style {
    pub(crate) depth_positive: bool,
    pub(crate) crlf: bool,
    pub(crate) property: Option<&'static str>,
}

pub(crate) fn write_tsurf(name: &str, s: &Surface, style: &Style) -> String {
    let mut o = String::new();
    let nl = if style.crlf { "\r\n" } else { "\n" };
    let line = |o: &mut String, text: &str| {
        o.push_str(text);
        o.push_str(nl);
    };
    line(&mut o, "GOCAD TSurf 1");
    line(&mut o, "HEADER {");
    line(&mut o, &format!("name:{name}"));
    line(&mut o, "}");
    line(&mut o, "GOCAD_ORIGINAL_COORDINATE_SYSTEM");
    line(&mut o, "NAME Default");
    line(&mut o, "AXIS_NAME \"X\" \"Y\" \"Z\"");
    line(&mut o, "AXIS_UNIT \"m\" \"m\" \"m\"");
    line(
        &mut o,
        if style.depth_positive {
            "ZPOSITIVE Depth"
        } else {
            "ZPOSITIVE Elevation"
        },
    );
    line(&mut o, "END_ORIGINAL_COORDINATE_SYSTEM");
    if let Some(p) = style.property {
        line(&mut o, &format!("PROPERTIES {p}"));
        line(&mut o, "ESIZES 1");
    }
    line(&mut o, "TFACE");
    let mut buf = String::new();
    for (i, p) in s.vertices.iter().enumerate() {
        buf.clear();
        let z = if style.depth_positive { -p[2] } else { p[2] };
        let (x, y) = (p[0] + ORIGIN_X, p[1] + ORIGIN_Y);
        match style.property {
            // The property is the depth below the box top, a typical gOcad vertex attribute.
            Some(_) => write!(buf, "PVRTX {} {x:.3} {y:.3} {z:.3} {:.3}", i + 1, -p[2]).unwrap(),
            None => write!(buf, "VRTX {} {x:.3} {y:.3} {z:.3}", i + 1).unwrap(),
        }
        line(&mut o, &buf);
    }
    for t in &s.triangles {
        line(
            &mut o,
            &format!("TRGL {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1),
        );
    }
    for c in &s.corners {
        line(&mut o, &format!("BSTONE {}", c + 1));
    }
    line(&mut o, "END");
    o
}

/// How densely to triangulate: `None` gives the shipped data (the file bytes in
/// `recipes/data/didactic`); `Some(n)` scales every surface's grid spacing so that it has about
/// `n` triangles (the model benchmark uses 100 000).
pub type Density = Option<usize>;

/// The spacing `h` of a surface whose default axes are `(a, b)`, scaled to about `target`
/// triangles (the grid is graded, so the count is approximate).
fn scaled(h: f64, target: Density, axes: impl Fn(f64) -> (usize, usize)) -> f64 {
    match target {
        None => h,
        Some(n) => {
            let (nu, nv) = axes(h);
            let triangles = 2.0 * (nu - 1) as f64 * (nv - 1) as f64;
            h * (triangles / n.max(2) as f64).sqrt()
        }
    }
}

/// The four didactic surfaces as gOcad TSurf text, `(file name, text, vertices, triangles)`.
pub fn didactic_files(target: Density) -> Vec<(&'static str, String, usize, usize)> {
    let mut rng = Rng(0x6765_6F72_6563_6970); // "georecip"

    // Horizons: 5400 m squares overhanging the box by 200 m, about 110-180 m triangles.
    let h = scaled(110.0, target, |h| {
        (
            graded_axis(-200.0, 5200.0, h, 0.0).len(),
            graded_axis(-200.0, 5200.0, h, 1.7).len(),
        )
    });
    let hx = graded_axis(-200.0, 5200.0, h, 0.0);
    let hy = graded_axis(-200.0, 5200.0, h, 1.7);
    let h1 = grid_surface(&hx, &hy, |x, y| [x, y, z_top(x, y)], &mut rng);
    let h = scaled(115.0, target, |h| {
        (
            graded_axis(-200.0, 5200.0, h, 2.9).len(),
            graded_axis(-200.0, 5200.0, h, 0.4).len(),
        )
    });
    let hx2 = graded_axis(-200.0, 5200.0, h, 2.9);
    let hy2 = graded_axis(-200.0, 5200.0, h, 0.4);
    let h2 = grid_surface(&hx2, &hy2, |x, y| [x, y, z_top(x, y) - 35.0], &mut rng);

    // F1: through-going plane, strike // y, dip 70° towards +x with depth, 3200 m down dip.
    let dip = 70f64.to_radians();
    let (dx, dz) = (dip.cos(), -dip.sin());
    let h = scaled(120.0, target, |h| {
        (
            graded_axis(-1600.0, 1600.0, h, 0.8).len(),
            graded_axis(-300.0, 5300.0, h, 2.2).len(),
        )
    });
    let su = graded_axis(-1600.0, 1600.0, h, 0.8);
    let sv = graded_axis(-300.0, 5300.0, h, 2.2);
    let f1 = grid_surface(
        &su,
        &sv,
        |u, v| [1500.0 + u * dx, v, -1200.0 + u * dz],
        &mut rng,
    );

    // F2: dangling rectangle, strike // x, dip 60° towards +y with depth.
    let dip2 = 60f64.to_radians();
    let (ey, ez) = (dip2.cos(), -dip2.sin());
    // Both axes scale together: `s` is exactly 1 for the shipped data.
    let s = scaled(1.0, target, |s| {
        (
            graded_axis(-800.0, 800.0, 70.0 * s, 0.3).len(),
            graded_axis(-350.0, 350.0, 60.0 * s, 1.1).len(),
        )
    });
    let (hu, hv) = (70.0 * s, 60.0 * s);
    let tu = graded_axis(-800.0, 800.0, hu, 0.3);
    let tv = graded_axis(-350.0, 350.0, hv, 1.1);
    let f2 = grid_surface(
        &tu,
        &tv,
        |u, v| [3400.0 + u, 3300.0 + v * ey, -1200.0 + v * ez],
        &mut rng,
    );

    let files = [
        (
            "H1_top_reservoir.ts",
            "H1_top_reservoir",
            &h1,
            Style {
                depth_positive: false,
                crlf: false,
                property: None,
            },
        ),
        (
            "H2_base_reservoir.ts",
            "H2_base_reservoir",
            &h2,
            Style {
                depth_positive: true,
                crlf: true,
                property: None,
            },
        ),
        (
            "F1_through.ts",
            "F1_through",
            &f1,
            Style {
                depth_positive: false,
                crlf: false,
                property: Some("depth"),
            },
        ),
        (
            "F2_dangling.ts",
            "F2_dangling",
            &f2,
            Style {
                depth_positive: false,
                crlf: false,
                property: None,
            },
        ),
    ];
    files
        .into_iter()
        .map(|(file, name, s, style)| {
            (
                file,
                write_tsurf(name, s, &style),
                s.vertices.len(),
                s.triangles.len(),
            )
        })
        .collect()
}
