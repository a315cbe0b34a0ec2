//! Background size field of a region (the seed's background octree, here a uniform grid): each
//! cell starts at the mean edge length of the boundary/embedded triangles crossing it and the
//! sizes are propagated inwards growing linearly at rate `growth - 1` per unit distance (a
//! multi-source Dijkstra over the 26-neighbourhood, deterministic), capped by the interior target
//! and by the largest boundary cell — so no interior element is larger than the largest boundary
//! one and neighbouring cells differ smoothly (at most the growth rate, finer than 2:1 balance).
//! The advancing front reads its target size here rather than from the front's own faces, so
//! sizes cannot drift down as the front advances.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use super::SizeField;

type P = [f64; 3];

/// Largest number of background cells (the advancing front's); the cell size grows to respect it.
const MAX_CELLS: usize = 2_000_000;

pub struct Background {
    origin: P,
    cell: f64,
    /// `1 / cell`: cells are found by a product, not a division (a third of every size query).
    per_cell: f64,
    dims: [usize; 3],
    h: Vec<f64>,
}

impl Background {
    /// Build from the triangles that bound or are embedded in the region.
    pub fn new(pts: &[P], tris: &[[u32; 3]], field: &SizeField) -> Self {
        Self::with_max_cells(pts, tris, field, MAX_CELLS)
    }

    /// As `new`, on at most `max_cells` cells.
    pub fn with_max_cells(
        pts: &[P],
        tris: &[[u32; 3]],
        field: &SizeField,
        max_cells: usize,
    ) -> Self {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in pts {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let mut sum = 0.0;
        let mut cap: f64 = 0.0;
        let les: Vec<f64> = tris.iter().map(|t| mean_edge(t, pts)).collect();
        for &le in &les {
            sum += le;
            cap = cap.max(le);
        }
        let avg = if les.is_empty() {
            1.0
        } else {
            sum / les.len() as f64
        };
        let mut cell = if avg.is_finite() && avg > 0.0 {
            avg
        } else {
            1.0
        };
        let ext = [
            (hi[0] - lo[0]).max(0.0),
            (hi[1] - lo[1]).max(0.0),
            (hi[2] - lo[2]).max(0.0),
        ];
        let dims_for =
            |c: f64| ext.map(|e| ((e / c).floor() as usize).saturating_add(1).min(1 << 20));
        let mut dims = dims_for(cell);
        while dims[0].saturating_mul(dims[1]).saturating_mul(dims[2]) > max_cells {
            cell *= 1.5;
            dims = dims_for(cell);
        }
        let goal = field
            .size
            .min(cap)
            .min(field.max_size)
            .max(field.min_size.max(0.0));
        let n = dims[0] * dims[1] * dims[2];
        let mut bg = Background {
            origin: lo,
            cell,
            per_cell: 1.0 / cell,
            dims,
            h: vec![f64::INFINITY; n],
        };
        for (t, &le) in tris.iter().zip(&les) {
            let (a, b) = bbox(t, pts);
            let (ca, cb) = (bg.cell_of(&a), bg.cell_of(&b));
            for x in ca[0]..=cb[0] {
                for y in ca[1]..=cb[1] {
                    for z in ca[2]..=cb[2] {
                        let i = bg.index([x, y, z]);
                        bg.h[i] = bg.h[i].min(
                            le.clamp(field.min_size.max(0.0), field.max_size.max(field.min_size)),
                        );
                    }
                }
            }
        }
        let rate = (field.growth - 1.0).clamp(0.0, 1.0);
        bg.propagate(rate, goal);
        bg
    }

    fn propagate(&mut self, rate: f64, goal: f64) {
        // Heapified at once; the pop order is that of the unique keys (size, cell), however
        // the heap was built.
        let mut heap: BinaryHeap<Reverse<(u64, usize)>> = self
            .h
            .iter()
            .enumerate()
            .filter(|(_, h)| h.is_finite())
            .map(|(i, h)| Reverse((h.to_bits(), i)))
            .collect::<Vec<_>>()
            .into();
        let [nx, ny, nz] = self.dims;
        // The 26 neighbours: offsets per axis and the growth over each step.
        let mut steps: Vec<([i64; 3], f64)> = Vec::with_capacity(26);
        for dx in -1i64..=1 {
            for dy in -1i64..=1 {
                for dz in -1i64..=1 {
                    if (dx, dy, dz) != (0, 0, 0) {
                        let d = ((dx * dx + dy * dy + dz * dz) as f64).sqrt() * self.cell;
                        steps.push(([dx, dy, dz], rate * d));
                    }
                }
            }
        }
        let (sy, sz) = (nx as i64, (nx * ny) as i64);
        while let Some(Reverse((hb, i))) = heap.pop() {
            let h = f64::from_bits(hb);
            if h > self.h[i] {
                continue;
            }
            let (x, y, z) = (i % nx, (i / nx) % ny, i / (nx * ny));
            let inner = x > 0 && y > 0 && z > 0 && x + 1 < nx && y + 1 < ny && z + 1 < nz;
            let cap = goal.max(h);
            for &([dx, dy, dz], grow) in &steps {
                if !inner {
                    let (xx, yy, zz) = (x as i64 + dx, y as i64 + dy, z as i64 + dz);
                    if xx < 0
                        || yy < 0
                        || zz < 0
                        || xx >= nx as i64
                        || yy >= ny as i64
                        || zz >= nz as i64
                    {
                        continue;
                    }
                }
                let j = (i as i64 + dx + sy * dy + sz * dz) as usize;
                let nh = (h + grow).min(cap);
                if nh < self.h[j] {
                    self.h[j] = nh;
                    heap.push(Reverse((nh.to_bits(), j)));
                }
            }
        }
    }

    #[inline]
    fn cell_of(&self, p: &P) -> [usize; 3] {
        let mut c = [0usize; 3];
        for k in 0..3 {
            // `as` truncates towards zero and sends negatives and NaN to 0: the floor, clamped.
            let v = (p[k] - self.origin[k]) * self.per_cell;
            c[k] = (v as usize).min(self.dims[k] - 1);
        }
        c
    }

    #[inline]
    fn index(&self, c: [usize; 3]) -> usize {
        c[0] + self.dims[0] * (c[1] + self.dims[1] * c[2])
    }

    /// Target element size at `p` (the nearest cell's value; points outside clamp to the grid).
    pub fn size_at(&self, p: &P) -> f64 {
        self.h[self.index(self.cell_of(p))]
    }
}

fn mean_edge(t: &[u32; 3], pts: &[P]) -> f64 {
    let [a, b, c] = t.map(|i| pts[i as usize]);
    let d = |x: &P, y: &P| {
        ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
    };
    (d(&a, &b) + d(&b, &c) + d(&c, &a)) / 3.0
}

fn bbox(t: &[u32; 3], pts: &[P]) -> (P, P) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &v in t {
        let p = pts[v as usize];
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_grow_away_from_small_boundary_triangles_up_to_the_cap() {
        let pts = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [10.0, 10.0, 10.0],
            [14.0, 10.0, 10.0],
            [10.0, 14.0, 10.0],
        ];
        let tris = vec![[0, 1, 2], [3, 4, 5]];
        let f = SizeField {
            size: f64::INFINITY,
            min_size: 0.0,
            max_size: f64::INFINITY,
            growth: 1.2,
        };
        let bg = Background::new(&pts, &tris, &f);
        let near = bg.size_at(&[0.2, 0.2, 0.0]);
        let mid = bg.size_at(&[5.0, 5.0, 5.0]);
        assert!(near < 1.2, "{near}");
        assert!(
            mid > near && mid <= 4.0 * (1.0 + 2.0 / 3.0) / 3.0 * 3.0,
            "{mid}"
        );
    }
}
