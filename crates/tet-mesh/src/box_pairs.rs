//! Broad phase of the input check: every pair of overlapping boxes, found through a uniform grid.
//! Each box is registered in the cells it covers, and a pair is reported by the one cell that
//! holds the low corner of the two boxes' overlap, so exactly once. The cells are about twice the
//! mean box size (at most four cells per box in all), which on a triangulated surface keeps a
//! few boxes per cell; an R-tree queried once per box did the same job three times slower.

/// A closed box: low and high corners.
pub type Box3 = ([f32; 3], [f32; 3]);

#[inline]
fn overlap(a: &Box3, b: &Box3) -> bool {
    (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
}

struct Grid {
    lo: [f32; 3],
    cell: f32,
    dims: [usize; 3],
}

impl Grid {
    fn new(boxes: &[Box3]) -> Self {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        let mut mean = 0.0f64;
        for b in boxes {
            for k in 0..3 {
                lo[k] = lo[k].min(b.0[k]);
                hi[k] = hi[k].max(b.1[k]);
            }
            mean += (0..3)
                .map(|k| f64::from(b.1[k] - b.0[k]))
                .fold(0.0, f64::max);
        }
        mean /= boxes.len().max(1) as f64;
        let span = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f32, f32::max);
        let mut cell = if mean > 0.0 {
            2.0 * mean as f32
        } else {
            span.max(1.0)
        };
        let most = 4 * boxes.len() + 64;
        loop {
            let dims = [0, 1, 2].map(|k| ((hi[k] - lo[k]) / cell) as usize + 1);
            if dims
                .iter()
                .try_fold(1usize, |n, &d| n.checked_mul(d))
                .is_some_and(|n| n <= most)
            {
                return Grid { lo, cell, dims };
            }
            cell *= 1.5;
        }
    }

    /// The cell of `x` on axis `k` (monotone in `x`).
    #[inline]
    fn at(&self, k: usize, x: f32) -> usize {
        (((x - self.lo[k]) / self.cell) as usize).min(self.dims[k] - 1)
    }

    #[inline]
    fn index(&self, c: [usize; 3]) -> usize {
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }

    /// The cells a box covers, per axis.
    fn span(&self, b: &Box3) -> [(usize, usize); 3] {
        [0, 1, 2].map(|k| (self.at(k, b.0[k]), self.at(k, b.1[k])))
    }
}

/// Call `f(i, j)`, `i < j`, once for every pair of boxes that overlap (closed boxes: touching
/// counts). The order of the calls is fixed by the boxes alone.
pub fn for_each_overlapping_pair(boxes: &[Box3], mut f: impl FnMut(u32, u32)) {
    if boxes.len() < 2 {
        return;
    }
    let grid = Grid::new(boxes);
    let n_cells = grid.dims.iter().product::<usize>();
    // Cells' box lists in one array (counting sort by cell), boxes in index order in each.
    let mut start = vec![0u32; n_cells + 1];
    let each_cell = |b: &Box3, f: &mut dyn FnMut(usize)| {
        let [x, y, z] = grid.span(b);
        for cz in z.0..=z.1 {
            for cy in y.0..=y.1 {
                for cx in x.0..=x.1 {
                    f(grid.index([cx, cy, cz]));
                }
            }
        }
    };
    for b in boxes {
        each_cell(b, &mut |c| start[c + 1] += 1);
    }
    for c in 0..n_cells {
        start[c + 1] += start[c];
    }
    let mut members = vec![0u32; start[n_cells] as usize];
    let mut next = start.clone();
    for (i, b) in boxes.iter().enumerate() {
        each_cell(b, &mut |c| {
            members[next[c] as usize] = i as u32;
            next[c] += 1;
        });
    }
    drop(next);
    for c in 0..n_cells {
        let list = &members[start[c] as usize..start[c + 1] as usize];
        for (s, &i) in list.iter().enumerate() {
            let a = &boxes[i as usize];
            for &j in &list[s + 1..] {
                let b = &boxes[j as usize];
                if !overlap(a, b) {
                    continue;
                }
                let corner = [0, 1, 2].map(|k| grid.at(k, a.0[k].max(b.0[k])));
                if grid.index(corner) == c {
                    f(i, j);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn random_boxes(n: usize, seed: u64) -> Vec<Box3> {
        let mut x = seed;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 40) as f32 / (1u64 << 24) as f32
        };
        (0..n)
            .map(|i| {
                let lo = [next() * 40.0, next() * 40.0, next() * 3.0];
                // Some large boxes and some flat ones among many small ones.
                let s = if i % 50 == 0 { 30.0 } else { 2.0 };
                let flat = if i % 7 == 0 { 0.0 } else { 1.0 };
                (
                    lo,
                    [
                        lo[0] + s * next(),
                        lo[1] + s * next(),
                        lo[2] + flat * next(),
                    ],
                )
            })
            .collect()
    }

    #[test]
    fn every_overlapping_pair_is_reported_once_and_no_other() {
        for seed in [1u64, 0xdead_beef, 42] {
            let boxes = random_boxes(600, seed);
            let mut got = Vec::new();
            for_each_overlapping_pair(&boxes, |i, j| got.push((i, j)));
            let mut want = Vec::new();
            for i in 0..boxes.len() {
                for j in i + 1..boxes.len() {
                    if overlap(&boxes[i], &boxes[j]) {
                        want.push((i as u32, j as u32));
                    }
                }
            }
            let n = got.len();
            got.sort_unstable();
            got.dedup();
            assert_eq!(got.len(), n, "a pair was reported twice");
            assert_eq!(got, want);
            assert!(want.len() > 100, "the boxes do overlap: {}", want.len());
        }
    }

    #[test]
    fn boxes_that_only_touch_overlap_and_identical_points_pair_up() {
        let boxes = vec![
            ([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
            ([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
            ([5.0, 5.0, 5.0], [5.0, 5.0, 5.0]),
            ([5.0, 5.0, 5.0], [5.0, 5.0, 5.0]),
        ];
        let mut got = Vec::new();
        for_each_overlapping_pair(&boxes, |i, j| got.push((i, j)));
        got.sort_unstable();
        assert_eq!(got, vec![(0, 1), (2, 3)]);
    }
}
