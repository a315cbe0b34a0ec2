//! Two wells for the shipped example with wells (`recipes/didactic_wells.toml`), in the
//! didactic model's frame (local coordinates shifted by the UTM origin):
//!
//! - W1: vertical at local (2600, 1800), from the kelly bushing 25 m above the box top down to
//!   2000 m below it: it crosses the box top, H1 and H2 east of F1. `ZPOSITIVE Elevation`, LF,
//!   measured depths in metres.
//! - W2: deviated from local (300, 2500): vertical to 600 m below the box top, then building 3°
//!   per 30 m to 80° inclination towards the east-north-east, so it enters the reservoir west of
//!   F1, crosses F1 inside the reservoir and leaves through H2 east of it, ending in the
//!   underburden. `ZPOSITIVE Depth`, CRLF, measured depths in feet.
//!
//! Stations every 30 m of measured depth, as `PATH md z dx dy` records (offsets from WREF), and
//! a marker where each well meets the top of the reservoir, as a well log would pick it.

use super::didactic::{ORIGIN_X, ORIGIN_Y, z_top};
use std::fmt::Write as _;

const STEP: f64 = 30.0;
const FOOT: f64 = 0.3048;

struct Well {
    name: &'static str,
    /// Local coordinates, from the head down.
    stations: Vec<[f64; 3]>,
    /// Measured depth of each station, metres.
    md: Vec<f64>,
}

fn vertical() -> Well {
    let (x, y) = (2600.0, 1800.0);
    let mut stations = Vec::new();
    let mut md = Vec::new();
    let mut z = 25.0;
    while z >= -2000.0 {
        stations.push([x, y, z]);
        md.push(25.0 - z);
        z -= STEP;
    }
    Well {
        name: "W1",
        stations,
        md,
    }
}

fn deviated() -> Well {
    let (mut p, mut inc, mut s) = ([300.0, 2500.0, 25.0], 0.0f64, 0.0);
    let mut stations = vec![p];
    let mut md = vec![s];
    while p[0] < 2600.0 && p[2] > -1700.0 {
        if p[2] < -600.0 && inc < 80.0 {
            inc += 3.0;
        }
        let a = inc.to_radians();
        p = [
            p[0] + STEP * a.sin() * 0.97,
            p[1] + STEP * a.sin() * 0.24,
            p[2] - STEP * a.cos(),
        ];
        s += STEP;
        stations.push(p);
        md.push(s);
    }
    Well {
        name: "W2",
        stations,
        md,
    }
}

/// Where a well meets H1, by measured depth (linear between the stations around it).
fn top_reservoir_md(w: &Well) -> f64 {
    let above = |p: &[f64; 3]| p[2] > z_top(p[0], p[1]);
    let i = (1..w.stations.len())
        .find(|&i| !above(&w.stations[i]))
        .expect("the well reaches the reservoir");
    let (a, b) = (&w.stations[i - 1], &w.stations[i]);
    let (da, db) = (a[2] - z_top(a[0], a[1]), b[2] - z_top(b[0], b[1]));
    w.md[i - 1] + da / (da - db) * (w.md[i] - w.md[i - 1])
}

fn write_well(w: &Well, depth_positive: bool, crlf: bool, md_unit_ft: bool) -> String {
    let nl = if crlf { "\r\n" } else { "\n" };
    let mut o = String::new();
    let mut line = |text: &str| {
        o.push_str(text);
        o.push_str(nl);
    };
    line("GOCAD Well 1");
    line("HEADER {");
    line(&format!("name:{}", w.name));
    line("}");
    line("GOCAD_ORIGINAL_COORDINATE_SYSTEM");
    line("NAME Default");
    line("AXIS_NAME \"X\" \"Y\" \"Z\"");
    line("AXIS_UNIT \"m\" \"m\" \"m\"");
    line(if depth_positive {
        "ZPOSITIVE Depth"
    } else {
        "ZPOSITIVE Elevation"
    });
    line("END_ORIGINAL_COORDINATE_SYSTEM");
    let md_scale = if md_unit_ft { 1.0 / FOOT } else { 1.0 };
    line(if md_unit_ft {
        "PATH_ZM_UNIT ft"
    } else {
        "PATH_ZM_UNIT m"
    });
    let head = w.stations[0];
    let zf = |z: f64| if depth_positive { -z } else { z };
    let (hx, hy) = (head[0] + ORIGIN_X, head[1] + ORIGIN_Y);
    line(&format!("WREF {hx:.3} {hy:.3} {:.3}", zf(head[2])));
    let mut buf = String::new();
    for (p, md) in w.stations.iter().zip(&w.md) {
        buf.clear();
        let (dx, dy) = (p[0] - head[0], p[1] - head[1]);
        write!(
            buf,
            "PATH {:.3} {:.3} {dx:.3} {dy:.3}",
            md * md_scale,
            zf(p[2])
        )
        .expect("a String takes any write");
        line(&buf);
    }
    line(&format!(
        "MRKR H1_pick 1 {:.3}",
        top_reservoir_md(w) * md_scale
    ));
    line("END");
    o
}

/// The two wells as gOcad Well text, `(file name, text, stations)`.
pub fn didactic_wells() -> Vec<(&'static str, String, usize)> {
    let (w1, w2) = (vertical(), deviated());
    vec![
        (
            "W1_vertical.wl",
            write_well(&w1, false, false, false),
            w1.stations.len(),
        ),
        (
            "W2_deviated.wl",
            write_well(&w2, true, true, true),
            w2.stations.len(),
        ),
    ]
}
