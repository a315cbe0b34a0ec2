//! Broad phase of the pairwise checks (triangles crossing, segments meeting): every pair of
//! overlapping boxes, each judged once by the caller's exact test, in parallel.
//!
//! A box can only rule a pair out (closed boxes of closed simplices that do not overlap cannot
//! meet), so the pairs judged are exactly the overlapping ones and the exact test decides. Boxes
//! are f64, as the coordinates are: the min and max of a simplex's corners is its box exactly.
//!
//! Where box sizes are even (triangulated surfaces, the usual case) a uniform grid of cells about
//! twice the mean box size finds the pairs: each box is listed in the cells it covers, and a pair
//! is judged only in the cell holding the low corner of the two boxes' overlap, so once. A few
//! boxes much larger than the cells are compared with every box instead; when there are many, an
//! R-tree traversed against itself takes over. The findings are sorted by pair, so what the
//! caller reports comes out the same for any thread count.

use crate::BBox;
use rayon::prelude::*;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};

/// Most cells one box may cover before it is compared with every box instead.
const MAX_CELLS_PER_BOX: u64 = 512;
/// Most such large boxes before the R-tree replaces the grid.
const MAX_BIG_BOXES: usize = 64;
/// Cells per axis (21 bits each, so a cell's three coordinates pack into one `u64`).
const CELLS_PER_AXIS: u64 = 1 << 21;

/// Every pair `(i, j)`, `i < j`, of overlapping boxes (closed: touching counts) for which
/// `judge(i, j)` finds something, with what it found, sorted by `(i, j)`. Each overlapping pair
/// is judged exactly once.
pub fn overlapping_pairs<T: Send>(
    boxes: &[BBox],
    judge: impl Fn(u32, u32) -> Option<T> + Sync,
) -> Vec<(u32, u32, T)> {
    let judge_pair = |i: u32, j: u32| {
        let (i, j) = (i.min(j), i.max(j));
        judge(i, j).map(|found| (i, j, found))
    };
    let mut hits = match grid_pairs(boxes, &judge_pair) {
        Some(hits) => hits,
        None => rtree_pairs(boxes, &judge_pair),
    };
    hits.par_sort_unstable_by_key(|h| (h.0, h.1));
    hits
}

/// A uniform grid over the boxes: the cell of a point on each axis, monotone in the coordinate.
struct Grid {
    lo: [f64; 3],
    cell: f64,
}

impl Grid {
    /// Cells about twice the mean box size (the largest extent of each box), never so small that
    /// the boxes' span needs more cells per axis than a key holds.
    fn new(boxes: &[BBox]) -> Self {
        let all = boxes.iter().fold(BBox::empty(), |a, b| a.union(b));
        let largest = |b: &BBox| b.extent().into_iter().fold(0.0, f64::max);
        let mean = boxes.iter().map(largest).sum::<f64>() / boxes.len().max(1) as f64;
        let span = largest(&all);
        let mut cell = 2.0 * mean;
        if !(cell.is_finite() && cell > 0.0) {
            cell = if span > 0.0 { span } else { 1.0 };
        }
        let cell = cell.max(span / (CELLS_PER_AXIS / 2) as f64);
        Grid { lo: all.min, cell }
    }

    /// The cell holding `p` (`p - lo` is never negative, so the saturating cast is the floor).
    fn cell_of(&self, p: &[f64; 3]) -> [u64; 3] {
        [0, 1, 2].map(|k| (((p[k] - self.lo[k]) / self.cell) as u64).min(CELLS_PER_AXIS - 1))
    }

    fn key(c: [u64; 3]) -> u64 {
        (c[0] << 42) | (c[1] << 21) | c[2]
    }
}

/// The boxes listed by cell, and the boxes too large to list.
struct Registry {
    /// `(cell key, box)`, sorted.
    entries: Vec<(u64, u32)>,
    big: Vec<u32>,
}

/// The boxes listed by cell; `None` when too many are too large to list.
fn register(grid: &Grid, boxes: &[BBox]) -> Option<Registry> {
    let mut entries = Vec::with_capacity(boxes.len() * 2);
    let mut big = Vec::new();
    for (i, b) in boxes.iter().enumerate() {
        let (c0, c1) = (grid.cell_of(&b.min), grid.cell_of(&b.max));
        let n: u64 = (0..3).map(|k| c1[k] - c0[k] + 1).product();
        if n > MAX_CELLS_PER_BOX {
            big.push(i as u32);
            if big.len() > MAX_BIG_BOXES {
                return None;
            }
            continue;
        }
        for x in c0[0]..=c1[0] {
            for y in c0[1]..=c1[1] {
                for z in c0[2]..=c1[2] {
                    entries.push((Grid::key([x, y, z]), i as u32));
                }
            }
        }
    }
    entries.par_sort_unstable();
    Some(Registry { entries, big })
}

/// The grid's findings, or `None` when the boxes are too uneven for a grid.
fn grid_pairs<T: Send>(
    boxes: &[BBox],
    judge: &(impl Fn(u32, u32) -> Option<(u32, u32, T)> + Sync),
) -> Option<Vec<(u32, u32, T)>> {
    if boxes.len() < 2 {
        return Some(Vec::new());
    }
    let grid = Grid::new(boxes);
    let Registry { entries, big } = register(&grid, boxes)?;
    let low: Vec<[u64; 3]> = boxes.iter().map(|b| grid.cell_of(&b.min)).collect();
    let mut starts: Vec<usize> = (0..entries.len())
        .filter(|&i| i == 0 || entries[i - 1].0 != entries[i].0)
        .collect();
    starts.push(entries.len());
    let mut hits: Vec<_> = starts
        .par_windows(2)
        .with_min_len(256)
        .flat_map_iter(|w| cell_pairs(&entries[w[0]..w[1]], boxes, &low, judge))
        .collect();
    hits.extend(big_pairs(boxes, &big, judge));
    Some(hits)
}

/// The findings of one cell (its entries, boxes in increasing order): the pairs of its boxes
/// that overlap with the low corner of the overlap in this cell. The cell of that corner is the
/// component-wise maximum of the two boxes' low cells (the cell map is monotone).
fn cell_pairs<T: Send>(
    cell: &[(u64, u32)],
    boxes: &[BBox],
    low: &[[u64; 3]],
    judge: &(impl Fn(u32, u32) -> Option<(u32, u32, T)> + Sync),
) -> Vec<(u32, u32, T)> {
    let here = cell[0].0;
    let mut hits = Vec::new();
    for (s, &(_, a)) in cell.iter().enumerate() {
        for &(_, b) in &cell[s + 1..] {
            let (ca, cb) = (low[a as usize], low[b as usize]);
            let corner = Grid::key([0, 1, 2].map(|k| ca[k].max(cb[k])));
            if corner == here && boxes[a as usize].overlaps(&boxes[b as usize]) {
                hits.extend(judge(a, b));
            }
        }
    }
    hits
}

/// The large boxes against every box, each pair of large boxes once.
fn big_pairs<T: Send>(
    boxes: &[BBox],
    big: &[u32],
    judge: &(impl Fn(u32, u32) -> Option<(u32, u32, T)> + Sync),
) -> Vec<(u32, u32, T)> {
    let mut hits = Vec::new();
    for (bi, &i) in big.iter().enumerate() {
        let earlier = &big[..bi];
        let found: Vec<_> = (0..boxes.len() as u32)
            .into_par_iter()
            .filter(|&j| j != i && !earlier.contains(&j))
            .filter(|&j| boxes[i as usize].overlaps(&boxes[j as usize]))
            .filter_map(|j| judge(i, j))
            .collect();
        hits.extend(found);
    }
    hits
}

/// The pairs an R-tree of the boxes finds against itself, judged in bounded parallel batches.
fn rtree_pairs<T: Send>(
    boxes: &[BBox],
    judge: &(impl Fn(u32, u32) -> Option<(u32, u32, T)> + Sync),
) -> Vec<(u32, u32, T)> {
    const BATCH: usize = 1 << 18;
    let entries: Vec<GeomWithData<Rectangle<[f64; 3]>, u32>> = (boxes.iter().enumerate())
        .map(|(i, b)| {
            let rect = Rectangle::from_aabb(AABB::from_corners(b.min, b.max));
            GeomWithData::new(rect, i as u32)
        })
        .collect();
    let tree = RTree::bulk_load(entries);
    let judge_batch = |batch: &[(u32, u32)]| -> Vec<(u32, u32, T)> {
        batch
            .par_iter()
            .with_min_len(4096)
            .filter(|&&(i, j)| boxes[i as usize].overlaps(&boxes[j as usize]))
            .filter_map(|&(i, j)| judge(i, j))
            .collect()
    };
    let mut hits = Vec::new();
    let mut batch = Vec::with_capacity(BATCH);
    for (a, b) in tree.intersection_candidates_with_other_tree(&tree) {
        if a.data < b.data {
            batch.push((a.data, b.data));
        }
        if batch.len() == BATCH {
            hits.extend(judge_batch(&batch));
            batch.clear();
        }
    }
    hits.extend(judge_batch(&batch));
    hits
}

#[cfg(test)]
mod tests {
    use super::*;

    fn xorshift(seed: u64) -> impl FnMut() -> f64 {
        let mut x = seed;
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Many small boxes, some flat ones and `large` boxes spanning much of the field.
    fn random_boxes(n: usize, large: usize, seed: u64) -> Vec<BBox> {
        let mut next = xorshift(seed);
        (0..n + large)
            .map(|i| {
                let min = [next() * 40.0, next() * 40.0, next() * 3.0];
                let s = if i >= n { 30.0 } else { 2.0 };
                let flat = if i % 7 == 0 { 0.0 } else { 1.0 };
                let max = [
                    min[0] + s * next(),
                    min[1] + s * next(),
                    min[2] + flat * next(),
                ];
                BBox { min, max }
            })
            .collect()
    }

    /// `small` boxes a hundredth wide and `large` cubes half as wide as the field.
    fn specks_and_cubes(small: usize, large: usize) -> Vec<BBox> {
        let mut next = xorshift(0x9e37_79b9);
        (0..small + large)
            .map(|i| {
                let w = if i < small { 0.01 } else { 50.0 };
                let min = [0, 1, 2].map(|_| next() * 100.0);
                BBox {
                    min,
                    max: min.map(|x| x + w),
                }
            })
            .collect()
    }

    fn all_pairs(boxes: &[BBox]) -> Vec<(u32, u32, ())> {
        let mut want = Vec::new();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                if boxes[i].overlaps(&boxes[j]) {
                    want.push((i as u32, j as u32, ()));
                }
            }
        }
        want
    }

    #[test]
    fn every_overlapping_pair_is_judged_once_and_no_other_in_order() {
        let sets = [
            random_boxes(1500, 0, 1),
            random_boxes(1500, 20, 0xdead_beef),
            specks_and_cubes(3000, 100),
        ];
        for boxes in sets {
            let got = overlapping_pairs(&boxes, |_, _| Some(()));
            let want = all_pairs(&boxes);
            assert!(want.len() > 100, "the boxes do overlap: {}", want.len());
            assert_eq!(got, want);
        }
    }

    #[test]
    fn the_grid_gives_way_to_the_rtree_only_for_many_large_boxes() {
        let keep = |i: u32, j: u32| Some((i, j, ()));
        assert!(grid_pairs(&specks_and_cubes(3000, 30), &keep).is_some());
        assert!(grid_pairs(&specks_and_cubes(3000, 100), &keep).is_none());
    }

    #[test]
    fn boxes_that_only_touch_overlap_and_identical_points_pair_up() {
        let b = |min: [f64; 3], max: [f64; 3]| BBox { min, max };
        let boxes = vec![
            b([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
            b([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
            b([5.0, 5.0, 5.0], [5.0, 5.0, 5.0]),
            b([5.0, 5.0, 5.0], [5.0, 5.0, 5.0]),
        ];
        let got = overlapping_pairs(&boxes, |i, j| Some((i, j)));
        assert_eq!(got, vec![(0, 1, (0, 1)), (2, 3, (2, 3))]);
    }

    #[test]
    fn only_the_pairs_the_judge_keeps_are_returned() {
        let boxes = random_boxes(800, 5, 3);
        let odd = overlapping_pairs(&boxes, |i, j| ((i + j) % 2 == 1).then_some(i + j));
        assert!(!odd.is_empty());
        assert!(
            odd.iter()
                .all(|&(i, j, s)| i < j && s == i + j && s % 2 == 1)
        );
    }
}
