//! The layout of the seed's Tables 1 and 2: their titles, column names and each row's cells with
//! the digits each number is shown with. Every renderer (the aligned text of `quality.txt` and
//! the terminal, the HTML report) draws from this one layout, so the tables cannot drift apart.

use super::{TetQuality, TriQuality};

/// One cell: a name (left-aligned), a count, or a number shown with a fixed number of digits.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    Name(String),
    Count(usize),
    Number { value: f64, digits: usize },
}

/// A table ready to render: `rows` are in the order given, the "all" row last.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    pub title: &'static str,
    pub columns: &'static [&'static str],
    pub rows: Vec<Vec<Cell>>,
}

fn num(value: f64, digits: usize) -> Cell {
    Cell::Number { value, digits }
}

/// Table 1: surface triangles, c/c* (1.0 = equilateral).
pub fn table1(rows: &[TriQuality]) -> Table {
    Table {
        title: "Table 1: surface triangles, c/c* (1.0 = equilateral)",
        columns: &[
            "surface",
            "nodes",
            "triangles",
            "c/c* avg",
            "SD",
            "max",
            "% > 1.15",
            "% > 1.5",
        ],
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    Cell::Name(r.name.clone()),
                    Cell::Count(r.nodes),
                    Cell::Count(r.triangles),
                    num(r.avg, 4),
                    num(r.sd, 4),
                    num(r.max, 4),
                    num(r.pct_gt_1_15, 2),
                    num(r.pct_gt_1_5, 2),
                ]
            })
            .collect(),
    }
}

/// Table 2: tets, normalised mean ratio (1.0 = regular) with the seed's ×0.79 scale alongside,
/// the minimum dihedral angle in degrees and the bound the region's boundary sets on it.
pub fn table2(rows: &[TetQuality]) -> Table {
    Table {
        title: "Table 2: tetrahedra, mean ratio (1.0 = regular tet; the seed's scale is x0.79), min dihedral and the boundary's bound on it in degrees",
        columns: &[
            "region",
            "nodes",
            "elements",
            "MR avg",
            "SD",
            "min",
            "% < 0.3",
            "% < 0.2",
            "% < 0.1",
            "min dihedral",
            "bound",
            "avg x0.79",
            "min x0.79",
        ],
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    Cell::Name(r.name.clone()),
                    Cell::Count(r.nodes),
                    Cell::Count(r.elements),
                    num(r.avg, 4),
                    num(r.sd, 4),
                    num(r.min, 4),
                    num(r.pct_lt_0_3, 2),
                    num(r.pct_lt_0_2, 2),
                    num(r.pct_lt_0_1, 2),
                    num(r.min_dihedral_deg, 2),
                    num(r.min_dihedral_bound_deg.unwrap_or(f64::NAN), 2),
                    num(r.avg_paper, 4),
                    num(r.min_paper, 4),
                ]
            })
            .collect(),
    }
}
