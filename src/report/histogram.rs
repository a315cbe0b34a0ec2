//! Quality histograms: tet mean ratio per region and triangle `c/c*` per surface group, with the
//! measures of `export::quality` (never re-derived here), binned on fixed edges so that two
//! builds can be compared bin by bin, and drawn as small SVG bar charts.
//!
//! Bins: mean ratio on [0, 1] in 20 bins (1.0 = regular tet; the last bin includes 1.0 and the
//! values rounding puts just above it);
//! `c/c*` on [1, 2] in 20 bins plus an "above" count for values ≥ 2 (1.0 = equilateral). A value
//! below the first edge (rounding) goes to the first bin; NaN values are counted as invalid.

use super::input::{tet_points, tri_points};
use super::palette::Rgb;
use super::text::{coord, count, esc, num};
use export::quality::triangle_ratio;
use geom::mesh::VolumeMesh;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// Number of bins of every histogram.
pub const BINS: usize = 20;

/// Counts of one measure over one group of elements.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Histogram {
    pub name: String,
    /// Lower edge of the first bin.
    pub lo: f64,
    /// Upper edge of the last bin.
    pub hi: f64,
    /// `BINS` equal bins between `lo` and `hi`.
    pub counts: Vec<usize>,
    /// Values ≥ `hi` (not in any bin; always 0 for the mean ratio, whose last bin holds 1.0 and
    /// the rounding errors above it).
    pub above: usize,
    /// NaN values.
    pub invalid: usize,
}

impl Histogram {
    fn new(name: &str, lo: f64, hi: f64) -> Self {
        Histogram {
            name: name.to_string(),
            lo,
            hi,
            counts: vec![0; BINS],
            above: 0,
            invalid: 0,
        }
    }

    /// Adds one value; `closed` puts `hi` and anything above it in the last bin (for a measure
    /// bounded by `hi`, where a larger value is a rounding error: a mean ratio of 1 + 1e-16).
    fn add(&mut self, v: f64, closed: bool) {
        if v.is_nan() {
            self.invalid += 1;
        } else if v >= self.hi && !closed {
            self.above += 1;
        } else {
            let b = ((v - self.lo) / (self.hi - self.lo) * BINS as f64).floor();
            // Float-to-int casts saturate: +inf lands in the last bin.
            let b = if b > 0.0 {
                (b as usize).min(BINS - 1)
            } else {
                0
            };
            self.counts[b] += 1;
        }
    }

    /// Elements counted (valid or not).
    pub fn total(&self) -> usize {
        self.counts.iter().sum::<usize>() + self.above + self.invalid
    }
}

/// Mean ratio histograms, one per region (index order), from the tets' measures
/// (`export::quality::tet_measures`, measured once for the quality tables and these). Tets with
/// an out-of-range region or node are left out.
pub fn mean_ratio_from(mesh: &VolumeMesh, measures: &[(f64, f64)]) -> Vec<Histogram> {
    let mut h: Vec<Histogram> = mesh
        .regions
        .iter()
        .map(|r| Histogram::new(&r.name, 0.0, 1.0))
        .collect();
    for (i, (t, &r)) in mesh.tets.iter().zip(&mesh.tet_region).enumerate() {
        if let (Some(h), Some(_), Some(m)) =
            (h.get_mut(r as usize), tet_points(mesh, t), measures.get(i))
        {
            h.add(m.0, true);
        }
    }
    h
}

/// `c/c*` histograms, one per surface group (index order).
pub fn c_ratio(mesh: &VolumeMesh) -> Vec<Histogram> {
    let mut h: Vec<Histogram> = mesh
        .surface_groups
        .iter()
        .map(|g| Histogram::new(&g.name, 1.0, 2.0))
        .collect();
    for (t, &g) in mesh.triangles.iter().zip(&mesh.triangle_group) {
        if let (Some(h), Some([a, b, c])) = (h.get_mut(g as usize), tri_points(mesh, t)) {
            h.add(triangle_ratio(&a, &b, &c), false);
        }
    }
    h
}

const W: f64 = 300.0;
const H: f64 = 130.0;
const PLOT: (f64, f64, f64, f64) = (34.0, 22.0, 290.0, 106.0); // left, top, right, bottom

/// A bar chart of `h` in colour `colour`: bar heights are percentages of the group's elements,
/// the axis tops at the largest bin; dashed lines mark `marks` (the seed's thresholds).
pub fn svg(h: &Histogram, colour: Rgb, measure: &str, marks: &[f64]) -> String {
    let (l, t, r, b) = PLOT;
    let n = h.total();
    let mut s = String::new();
    let _ = write!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {W} {H}\" width=\"{W}\" height=\"{H}\" role=\"img\" font-family=\"sans-serif\" font-size=\"10\"><title>{} of {}</title>",
        esc(measure),
        esc(&h.name)
    );
    let _ = write!(
        s,
        "<text x=\"{l}\" y=\"13\" font-weight=\"bold\">{}</text><text x=\"{r}\" y=\"13\" text-anchor=\"end\">{} elements</text>",
        esc(&h.name),
        count(n)
    );
    let nbars = BINS + usize::from(h.above > 0);
    let bw = (r - l) / nbars as f64;
    let values: Vec<usize> = h
        .counts
        .iter()
        .copied()
        .chain((h.above > 0).then_some(h.above))
        .collect();
    let top = values.iter().copied().max().unwrap_or(0);
    let pct_top = if n > 0 {
        100.0 * top as f64 / n as f64
    } else {
        0.0
    };
    if top > 0 {
        for (i, &v) in values.iter().enumerate() {
            if v == 0 {
                continue;
            }
            let hgt = (b - t) * v as f64 / top as f64;
            let fill = if i >= BINS {
                "#888888".to_string()
            } else {
                colour.hex()
            };
            let _ = write!(
                s,
                "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{fill}\"><title>{}</title></rect>",
                coord(l + i as f64 * bw + 0.5),
                coord(b - hgt),
                coord((bw - 1.0).max(0.5)),
                coord(hgt.max(0.5)),
                bin_label(h, i, v, n)
            );
        }
    } else {
        let _ = write!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" fill=\"#888\">no elements</text>",
            coord(0.5 * (l + r)),
            coord(0.5 * (t + b))
        );
    }
    // Axes, threshold marks and labels.
    let _ = write!(
        s,
        "<path d=\"M{l} {t}V{b}H{r}\" fill=\"none\" stroke=\"#444\" stroke-width=\"0.8\"/>"
    );
    let x_of = |v: f64| l + (v - h.lo) / (h.hi - h.lo) * BINS as f64 * bw;
    for &m in marks {
        let x = coord(x_of(m));
        let _ = write!(
            s,
            "<line x1=\"{x}\" y1=\"{t}\" x2=\"{x}\" y2=\"{b}\" stroke=\"#c00\" stroke-width=\"0.8\" stroke-dasharray=\"3 2\"/>"
        );
    }
    for v in [h.lo, 0.5 * (h.lo + h.hi), h.hi] {
        let _ = write!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            coord(x_of(v)),
            b + 12.0,
            num(v, 1)
        );
    }
    if h.above > 0 {
        let _ = write!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">&gt;</text>",
            coord(r - 0.5 * bw),
            b + 12.0
        );
    }
    let _ = write!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}%</text><text x=\"{}\" y=\"{b}\" text-anchor=\"end\">0</text>",
        l - 3.0,
        t + 8.0,
        num(pct_top, 1),
        l - 3.0
    );
    let _ = write!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" fill=\"#555\">{}</text>",
        coord(0.5 * (l + r)),
        H - 1.0,
        esc(measure)
    );
    s.push_str("</svg>");
    s
}

/// Tooltip of bar `i`: its range, count and percentage.
fn bin_label(h: &Histogram, i: usize, v: usize, n: usize) -> String {
    let pct = if n > 0 {
        100.0 * v as f64 / n as f64
    } else {
        0.0
    };
    let range = if i >= BINS {
        format!("≥ {}", num(h.hi, 2))
    } else {
        let w = (h.hi - h.lo) / BINS as f64;
        format!(
            "{} – {}",
            num(h.lo + i as f64 * w, 2),
            num(h.lo + (i + 1) as f64 * w, 2)
        )
    };
    format!("{range}: {} ({}%)", count(v), num(pct, 2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_fall_in_the_bin_of_their_range_and_the_closed_end_stays_in() {
        let mut h = Histogram::new("r", 0.0, 1.0);
        for v in [
            0.0,
            0.049,
            0.05,
            0.5,
            1.0,
            f64::NAN,
            -1e-9,
            1.0 + 1e-15,
            f64::INFINITY,
        ] {
            h.add(v, true);
        }
        assert_eq!(h.counts[0], 3);
        assert_eq!(h.counts[1], 1);
        assert_eq!(h.counts[10], 1);
        assert_eq!(h.counts[19], 3);
        assert_eq!((h.above, h.invalid, h.total()), (0, 1, 9));
    }

    #[test]
    fn values_at_or_above_an_open_end_are_counted_above() {
        let mut h = Histogram::new("s", 1.0, 2.0);
        for v in [1.0, 1.99, 2.0, 1e300, f64::INFINITY] {
            h.add(v, false);
        }
        assert_eq!((h.counts[0], h.counts[19], h.above), (1, 1, 3));
    }

    #[test]
    fn an_empty_histogram_draws_a_note_instead_of_bars() {
        let h = Histogram::new("empty <region>", 0.0, 1.0);
        let s = svg(&h, Rgb(1, 2, 3), "mean ratio", &[0.3]);
        assert!(s.contains("no elements"));
        assert!(s.contains("empty &lt;region&gt;"));
        assert!(!s.contains("<rect"));
    }
}
