//! Stage `quality`: the seed's Table 1 (surface triangles, per surface group) and Table 2 (tets,
//! per region) for a finished mesh, as typed rows (serialisable for the JSON report) and as
//! aligned text. Statistics follow `tools/check_mesh.py` exactly: population standard deviation,
//! percentages as `100 · count / n`, strict comparisons (`> 1.15`, `< 0.3`).
//!
//! Rows are in group/region index order with an "all" row last, so the output is deterministic.
//! An empty group keeps its row with zero counts and NaN statistics (rendered as "-", JSON null).

pub mod bound;
pub mod layout;
pub mod measures;

pub use measures::{PAPER_MEAN_RATIO_SCALE, tet_mean_ratio, tet_min_dihedral_deg, triangle_ratio};

use geom::mesh::VolumeMesh;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// One row of the seed's Table 1: triangle shape `c/c*` over a surface group.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TriQuality {
    pub name: String,
    pub nodes: usize,
    pub triangles: usize,
    pub avg: f64,
    pub sd: f64,
    pub max: f64,
    pub pct_gt_1_15: f64,
    pub pct_gt_1_5: f64,
}

/// One row of the seed's Table 2: normalised tet mean ratio over a region (regular tet = 1.0;
/// multiply `avg`/`min` by [`PAPER_MEAN_RATIO_SCALE`] for the paper's 0.79 scale, given here as
/// `avg_paper` and `min_paper`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TetQuality {
    pub name: String,
    pub nodes: usize,
    pub elements: usize,
    pub avg: f64,
    pub sd: f64,
    pub min: f64,
    pub pct_lt_0_3: f64,
    pub pct_lt_0_2: f64,
    pub pct_lt_0_1: f64,
    pub min_dihedral_deg: f64,
    /// The centroid of the region's tet with that angle (the first in tet order), so that a
    /// bad tet can be found and explained; `None` for an empty region.
    #[serde(default)]
    pub min_dihedral_at: Option<[f64; 3]>,
    /// The sharpest angle (degrees) the region's surface triangles leave its tets round an
    /// edge, which its smallest dihedral angle cannot exceed ([`bound`]), and where; `None`
    /// where no two surface triangles meet at an edge of its tets.
    #[serde(default)]
    pub min_dihedral_bound_deg: Option<f64>,
    #[serde(default)]
    pub min_dihedral_bound_at: Option<[f64; 3]>,
    pub avg_paper: f64,
    pub min_paper: f64,
}

/// avg, population sd, min, max of `x` (NaN for empty input).
fn moments(x: &[f64]) -> (f64, f64, f64, f64) {
    if x.is_empty() {
        return (f64::NAN, f64::NAN, f64::NAN, f64::NAN);
    }
    let n = x.len() as f64;
    let avg = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - avg) * (v - avg)).sum::<f64>() / n;
    let min = x.iter().copied().fold(f64::INFINITY, f64::min);
    let max = x.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (avg, var.sqrt(), min, max)
}

fn pct(x: &[f64], pred: impl Fn(f64) -> bool) -> f64 {
    if x.is_empty() {
        return f64::NAN;
    }
    100.0 * x.iter().filter(|&&v| pred(v)).count() as f64 / x.len() as f64
}

fn count_nodes<'a>(n_nodes: usize, elems: impl Iterator<Item = &'a [u32]>) -> usize {
    let mut seen = vec![false; n_nodes];
    let mut count = 0;
    for e in elems {
        for &v in e {
            if let Some(s) = seen.get_mut(v as usize)
                && !*s
            {
                *s = true;
                count += 1;
            }
        }
    }
    count
}

pub(crate) fn node(mesh: &VolumeMesh, v: u32) -> [f64; 3] {
    mesh.nodes.get(v as usize).copied().unwrap_or([f64::NAN; 3])
}

fn tri_row(mesh: &VolumeMesh, name: &str, sel: &[usize]) -> TriQuality {
    let q: Vec<f64> = sel
        .iter()
        .map(|&t| {
            let [a, b, c] = mesh.triangles[t];
            triangle_ratio(&node(mesh, a), &node(mesh, b), &node(mesh, c))
        })
        .collect();
    let (avg, sd, _, max) = moments(&q);
    TriQuality {
        name: name.to_string(),
        nodes: count_nodes(
            mesh.nodes.len(),
            sel.iter().map(|&t| &mesh.triangles[t][..]),
        ),
        triangles: sel.len(),
        avg,
        sd,
        max,
        pct_gt_1_15: pct(&q, |v| v > 1.15),
        pct_gt_1_5: pct(&q, |v| v > 1.5),
    }
}

/// Tets measured per parallel task (a few hundred microseconds' work).
const MEASURE_CHUNK: usize = 8192;

/// Each tet's mean ratio and smallest dihedral angle, measured once for all of Table 2's rows
/// and the report's histograms (in parallel: each tet's pair depends on it alone, and they are
/// collected in tet order).
pub fn tet_measures(mesh: &VolumeMesh) -> Vec<(f64, f64)> {
    use rayon::prelude::*;
    mesh.tets
        .par_iter()
        .with_min_len(MEASURE_CHUNK)
        .map(|tet| {
            let [a, b, c, d] = tet.map(|v| node(mesh, v));
            (
                tet_mean_ratio(&a, &b, &c, &d),
                tet_min_dihedral_deg(&a, &b, &c, &d),
            )
        })
        .collect()
}

fn tet_row(
    mesh: &VolumeMesh,
    measures: &[(f64, f64)],
    name: &str,
    sel: &[usize],
    bound: Option<bound::Bound>,
) -> TetQuality {
    let mut q = Vec::with_capacity(sel.len());
    let (mut dmin, mut worst) = (f64::INFINITY, None);
    for &t in sel {
        let (ratio, dihedral) = measures[t];
        q.push(ratio);
        if dihedral < dmin || worst.is_none() {
            (dmin, worst) = (dihedral, Some(t));
        }
    }
    let (avg, sd, min, _) = moments(&q);
    TetQuality {
        name: name.to_string(),
        nodes: count_nodes(mesh.nodes.len(), sel.iter().map(|&t| &mesh.tets[t][..])),
        elements: sel.len(),
        avg,
        sd,
        min,
        pct_lt_0_3: pct(&q, |v| v < 0.3),
        pct_lt_0_2: pct(&q, |v| v < 0.2),
        pct_lt_0_1: pct(&q, |v| v < 0.1),
        min_dihedral_deg: if sel.is_empty() { f64::NAN } else { dmin },
        min_dihedral_at: worst.map(|t| centroid(mesh, t)),
        min_dihedral_bound_deg: bound.map(|b| b.deg),
        min_dihedral_bound_at: bound.map(|b| b.at),
        avg_paper: PAPER_MEAN_RATIO_SCALE * avg,
        min_paper: PAPER_MEAN_RATIO_SCALE * min,
    }
}

/// The centroid of tet `t` of `mesh`.
fn centroid(mesh: &VolumeMesh, t: usize) -> [f64; 3] {
    let corners = mesh.tets[t].map(|v| node(mesh, v));
    [0, 1, 2].map(|k| corners.iter().map(|c| c[k]).sum::<f64>() / 4.0)
}

/// Splits element indices by their group tag; tags beyond `n_groups` are ignored here (the
/// `validate` stage reports them).
fn by_group(tags: &[u32], n_groups: usize) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new(); n_groups];
    for (i, &g) in tags.iter().enumerate() {
        if let Some(v) = out.get_mut(g as usize) {
            v.push(i);
        }
    }
    out
}

/// Table 1: one row per surface group (index order), then "all".
pub fn table1(mesh: &VolumeMesh) -> Vec<TriQuality> {
    let n = mesh.triangles.len().min(mesh.triangle_group.len());
    let groups = by_group(&mesh.triangle_group[..n], mesh.surface_groups.len());
    let mut rows: Vec<TriQuality> = mesh
        .surface_groups
        .iter()
        .zip(&groups)
        .map(|(g, sel)| tri_row(mesh, &g.name, sel))
        .collect();
    let all: Vec<usize> = (0..mesh.triangles.len()).collect();
    rows.push(tri_row(mesh, "all", &all));
    rows
}

/// Table 2: one row per region (index order), then "all".
pub fn table2(mesh: &VolumeMesh) -> Vec<TetQuality> {
    table2_with(mesh, &tet_measures(mesh))
}

/// [`table2`] from the tets' `measures` ([`tet_measures`]).
fn table2_with(mesh: &VolumeMesh, measures: &[(f64, f64)]) -> Vec<TetQuality> {
    let n = mesh.tets.len().min(mesh.tet_region.len());
    let groups = by_group(&mesh.tet_region[..n], mesh.regions.len());
    let bounds = bound::dihedral_bounds(mesh);
    let mut rows: Vec<TetQuality> = (mesh.regions.iter().zip(&groups).zip(&bounds))
        .map(|((r, sel), &b)| tet_row(mesh, measures, &r.name, sel, b))
        .collect();
    let all: Vec<usize> = (0..mesh.tets.len()).collect();
    let mut sharpest = None;
    for &b in bounds.iter().flatten() {
        bound::keep_sharper(&mut sharpest, b);
    }
    rows.push(tet_row(mesh, measures, "all", &all, sharpest));
    rows
}

/// Both tables, as the build's JSON report and printed summary carry them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct QualityReport {
    pub table1: Vec<TriQuality>,
    pub table2: Vec<TetQuality>,
}

/// Computes both tables (side by side: neither depends on the other).
pub fn report(mesh: &VolumeMesh) -> QualityReport {
    report_and_measures(mesh).0
}

/// [`report`], and the tets' measures it was made from ([`tet_measures`], measured beside
/// Table 1) for other uses of them.
pub fn report_and_measures(mesh: &VolumeMesh) -> (QualityReport, Vec<(f64, f64)>) {
    let (table1, measures) = rayon::join(|| table1(mesh), || tet_measures(mesh));
    let table2 = table2_with(mesh, &measures);
    (QualityReport { table1, table2 }, measures)
}

impl QualityReport {
    /// Both tables as aligned text, Table 1 first, separated by a blank line.
    pub fn render(&self) -> String {
        format!(
            "{}\n{}",
            render_table1(&self.table1),
            render_table2(&self.table2)
        )
    }
}

fn f(v: f64, digits: usize) -> String {
    if v.is_nan() {
        "-".to_string()
    } else {
        format!("{v:.digits$}")
    }
}

/// A table as aligned text: the title, then right-aligned columns, the first left-aligned.
pub fn render_text(table: &layout::Table) -> String {
    let cells = |row: &[layout::Cell]| -> Vec<String> {
        row.iter()
            .map(|c| match c {
                layout::Cell::Name(s) => s.clone(),
                layout::Cell::Count(n) => n.to_string(),
                layout::Cell::Number { value, digits } => f(*value, *digits),
            })
            .collect()
    };
    let header: Vec<String> = table.columns.iter().map(|h| h.to_string()).collect();
    let body: Vec<Vec<String>> = table.rows.iter().map(|r| cells(r)).collect();
    let mut width: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for r in &body {
        for (w, c) in width.iter_mut().zip(r) {
            *w = (*w).max(c.chars().count());
        }
    }
    let mut out = format!("{}\n", table.title);
    for r in std::iter::once(&header).chain(&body) {
        let mut s = String::new();
        for (i, (c, w)) in r.iter().zip(&width).enumerate() {
            if i == 0 {
                let _ = write!(s, "{c:<w$}");
            } else {
                let _ = write!(s, "  {c:>w$}");
            }
        }
        out.push_str(s.trim_end());
        out.push('\n');
    }
    out
}

/// Table 1 as aligned text (c/c*: 1.0 ideal; percentages of triangles above 1.15 and 1.5).
pub fn render_table1(rows: &[TriQuality]) -> String {
    render_text(&layout::table1(rows))
}

/// Table 2 as aligned text (mean ratio normalised to 1.0, with the paper's 0.79 scale alongside).
pub fn render_table2(rows: &[TetQuality]) -> String {
    render_text(&layout::table2(rows))
}
