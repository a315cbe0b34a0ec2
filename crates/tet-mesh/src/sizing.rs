//! Background size field of a region (the seed's background octree, here a uniform grid): each
//! cell stores the size at its centre, starting from the boundary/embedded triangles crossing it
//! (each one's mean edge length, grown at the rate below over the distance from the triangle's
//! bounding box to the centre), and the sizes are propagated inwards growing linearly at rate `growth - 1` per unit distance (along
//! shortest paths through the 26-neighbourhood, found by two raster sweeps), capped by the
//! interior target and by the largest boundary cell — so no interior element is larger than the largest boundary
//! one and neighbouring cells differ smoothly (at most the growth rate, finer than 2:1 balance).
//! The advancing front reads its target size here rather than from the front's own faces, so
//! sizes cannot drift down as the front advances. A cell holds the size at its centre, not the
//! least size anywhere in it: with the least, one sliver a few centimetres across in a cell of
//! a hundred metres set the whole cell to centimetres, and the mesher filled it with centimetre
//! tets (millions, for minutes). Near a small triangle the front's own faces keep sizes small.

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
        let rate = (field.growth - 1.0).clamp(0.0, 1.0);
        for (t, &le) in tris.iter().zip(&les) {
            let (a, b) = bbox(t, pts);
            let (ca, cb) = (bg.cell_of(&a), bg.cell_of(&b));
            let h = le.clamp(field.min_size.max(0.0), field.max_size.max(field.min_size));
            for x in ca[0]..=cb[0] {
                for y in ca[1]..=cb[1] {
                    for z in ca[2]..=cb[2] {
                        let i = bg.index([x, y, z]);
                        let d = box_distance(&bg.centre([x, y, z]), &a, &b);
                        bg.h[i] = bg.h[i].min(h + rate * d);
                    }
                }
            }
        }
        bg.propagate(rate, goal);
        for r in &field.refine {
            bg.bound_by(r, r.slope.clamp(0.0, rate));
        }
        bg
    }

    /// Lowers every cell to the size `r` asks for there: `r.size` at the cells holding its
    /// points (those inside the grid), growing by `slope` per unit of distance, the same
    /// distance transform as `propagate`.
    fn bound_by(&mut self, r: &geom::refine::Refinement, slope: f64) {
        let mut f = vec![f64::INFINITY; self.h.len()];
        let inside = |p: &P| {
            (0..3).all(|k| {
                p[k] >= self.origin[k] && p[k] <= self.origin[k] + self.dims[k] as f64 * self.cell
            })
        };
        for p in r.points.iter().filter(|p| inside(p)) {
            let i = self.index(self.cell_of(p));
            f[i] = f[i].min(r.size);
        }
        self.sweeps(&mut f, slope);
        for (h, g) in self.h.iter_mut().zip(&f) {
            *h = h.min(*g);
        }
    }

    /// The field the seeds grow into: at each cell the least, over the seeded cells `s`, of
    /// `h_s + rate * d(s, cell)` capped at `max(goal, h_s)`, where `d` is the shortest path
    /// through the 26-neighbourhood (steps of 1, √2 and √3 cells). A seed at or above `goal`
    /// stays flat, so its term is the constant `h_s`; one below grows to `goal`. So the field is
    /// the least of one constant and a distance transform of the seeds below `goal`, which two
    /// raster sweeps compute exactly: a shortest path's steps all point into one octant, so
    /// it can take its steps that go forward in raster order first and the others after, through
    /// cells between its ends (inside the grid). The sweeps replace a Dijkstra whose heap was 3 %
    /// of a million-tet region's time.
    fn propagate(&mut self, rate: f64, goal: f64) {
        let mut flat = f64::INFINITY;
        for h in &mut self.h {
            if *h >= goal && h.is_finite() {
                flat = flat.min(*h);
                *h = f64::INFINITY;
            } else if *h < goal {
                flat = flat.min(goal);
            }
        }
        let mut h = std::mem::take(&mut self.h);
        self.sweeps(&mut h, rate);
        self.h = h;
        for h in &mut self.h {
            *h = h.min(flat);
        }
    }

    /// Two raster sweeps: each cell of `h` becomes the least over all cells `s` of
    /// `h_s + rate * d(s, cell)` (see `propagate`).
    fn sweeps(&self, h: &mut [f64], rate: f64) {
        let [nx, ny, nz] = self.dims;
        // The 13 neighbours that come before a cell in raster order (x fastest), with the growth
        // over each step; the sweep back uses the opposite 13.
        let mut steps: Vec<([i64; 3], f64)> = Vec::with_capacity(13);
        for dz in -1i64..=1 {
            for dy in -1i64..=1 {
                for dx in -1i64..=1 {
                    if (dz, dy, dx) < (0, 0, 0) {
                        let d = ((dx * dx + dy * dy + dz * dz) as f64).sqrt() * self.cell;
                        steps.push(([dx, dy, dz], rate * d));
                    }
                }
            }
        }
        let (sy, sz) = (nx as i64, (nx * ny) as i64);
        let dims = [nx as i64, ny as i64, nz as i64];
        let sweep = |h: &mut [f64], i: usize, sign: i64| {
            let c = [
                (i % nx) as i64,
                ((i / nx) % ny) as i64,
                (i / (nx * ny)) as i64,
            ];
            let inner = (0..3).all(|k| c[k] > 0 && c[k] + 1 < dims[k]);
            let mut v = h[i];
            for &(d, grow) in &steps {
                let d = d.map(|x| x * sign);
                if !inner && (0..3).any(|k| c[k] + d[k] < 0 || c[k] + d[k] >= dims[k]) {
                    continue;
                }
                let j = (i as i64 + d[0] + sy * d[1] + sz * d[2]) as usize;
                v = v.min(h[j] + grow);
            }
            h[i] = v;
        };
        let n = h.len();
        for i in 0..n {
            sweep(h, i, 1);
        }
        for i in (0..n).rev() {
            sweep(h, i, -1);
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

    /// The centre of cell `c`: the point whose size the cell stores.
    fn centre(&self, c: [usize; 3]) -> P {
        [0, 1, 2].map(|k| self.origin[k] + (c[k] as f64 + 0.5) * self.cell)
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

/// Distance from `p` to the box `[lo, hi]` (0 inside).
fn box_distance(p: &P, lo: &P, hi: &P) -> f64 {
    let g = [0, 1, 2].map(|k| (lo[k] - p[k]).max(p[k] - hi[k]).max(0.0));
    (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt()
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

    /// The field by Dijkstra's algorithm from every seed, each path capped as `propagate` says.
    fn dijkstra_field(
        seeds: &[f64],
        dims: [usize; 3],
        cell: f64,
        rate: f64,
        goal: f64,
    ) -> Vec<f64> {
        let mut h = seeds.to_vec();
        let mut done = vec![false; h.len()];
        let [nx, ny, nz] = dims;
        loop {
            // The smallest open cell (a linear scan: the grids here are small).
            let Some(i) = (0..h.len())
                .filter(|&i| !done[i] && h[i].is_finite())
                .min_by(|&a, &b| h[a].total_cmp(&h[b]))
            else {
                return h;
            };
            done[i] = true;
            let c = [i % nx, (i / nx) % ny, i / (nx * ny)].map(|x| x as i64);
            for dz in -1i64..=1 {
                for dy in -1i64..=1 {
                    for dx in -1i64..=1 {
                        let d = [c[0] + dx, c[1] + dy, c[2] + dz];
                        if d.iter()
                            .zip([nx, ny, nz])
                            .any(|(&x, n)| x < 0 || x >= n as i64)
                        {
                            continue;
                        }
                        let j = d[0] as usize + nx * (d[1] as usize + ny * d[2] as usize);
                        let step = ((dx * dx + dy * dy + dz * dz) as f64).sqrt() * cell;
                        let nh = (h[i] + rate * step).min(goal.max(h[i]));
                        if nh < h[j] {
                            h[j] = nh;
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn the_two_sweeps_give_the_shortest_path_field_of_the_26_neighbourhood() {
        // Seeds below and above the goal, scattered by a fixed generator over odd-shaped grids.
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for dims in [[7, 5, 4], [1, 9, 3], [6, 1, 1], [4, 4, 4]] {
            let n = dims[0] * dims[1] * dims[2];
            for _ in 0..20 {
                let mut seeds = vec![f64::INFINITY; n];
                for _ in 0..1 + next() % 4 {
                    seeds[(next() % n as u64) as usize] = 0.5 + (next() % 1000) as f64 / 250.0;
                }
                let (cell, rate, goal) = (0.7, 0.3, 2.5);
                let mut bg = Background {
                    origin: [0.0; 3],
                    cell,
                    per_cell: 1.0 / cell,
                    dims,
                    h: seeds.clone(),
                };
                bg.propagate(rate, goal);
                let want = dijkstra_field(&seeds, dims, cell, rate, goal);
                for (i, (got, want)) in bg.h.iter().zip(&want).enumerate() {
                    assert!(
                        (got - want).abs() <= 1e-12 * want,
                        "cell {i} of {dims:?}: {got} against {want}"
                    );
                }
            }
        }
    }

    /// The field of the triangles `pts[0..3]` and `pts[3..6]`, growing at 1.2 without a cap.
    fn two_triangles(pts: &[P]) -> Background {
        let f = SizeField {
            size: f64::INFINITY,
            min_size: 0.0,
            max_size: f64::INFINITY,
            growth: 1.2,
            refine: Vec::new(),
        };
        Background::new(pts, &[[0, 1, 2], [3, 4, 5]], &f)
    }

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
        let bg = two_triangles(&pts);
        let near = bg.size_at(&[0.2, 0.2, 0.0]);
        let mid = bg.size_at(&[5.0, 5.0, 5.0]);
        // The small triangle's size (1.14) grown over the way to its cell's centre (1.54).
        assert!((near - (1.138 + 0.2 * 1.54)).abs() < 0.01, "{near}");
        assert!(
            mid > near && mid <= 4.0 * (1.0 + 2.0 / 3.0) / 3.0 * 3.0,
            "{mid}"
        );
    }

    #[test]
    fn a_tiny_boundary_triangle_sets_the_size_at_its_cells_centre_not_across_the_cell() {
        // A 1 cm triangle in a grid of 100 m cells (the big triangle's): its cell stores the
        // size grown from 1 cm to the cell's centre, not 1 cm, which would fill the whole
        // cell with centimetre tets.
        let pts = vec![
            [0.0, 0.0, 0.0],
            [0.01, 0.0, 0.0],
            [0.0, 0.01, 0.0],
            [0.0, 0.0, 300.0],
            [100.0, 0.0, 300.0],
            [0.0, 100.0, 300.0],
        ];
        let bg = two_triangles(&pts);
        let cell = bg.cell;
        let centre = 0.2 * (3.0f64).sqrt() * cell / 2.0;
        let at = bg.size_at(&[0.001, 0.001, 0.0]);
        assert!((at - (0.01 / 3.0 * (2.0 + 2f64.sqrt()) + centre)).abs() < 0.02 * centre);
        // Still far below the big triangle's size: the small one is honoured around it.
        assert!(at < 0.25 * cell, "{at} in cells of {cell}");
    }

    #[test]
    fn a_refinement_point_lowers_the_sizes_around_it_growing_no_faster_than_the_mesh() {
        let pts = vec![
            [0.0, 0.0, 0.0],
            [40.0, 0.0, 0.0],
            [0.0, 40.0, 0.0],
            [40.0, 40.0, 40.0],
        ];
        let tris = vec![[0, 1, 2], [1, 3, 2], [0, 3, 1], [0, 2, 3]];
        let point = geom::refine::Refinement {
            points: vec![[10.0, 10.0, 10.0]],
            size: 1.0,
            slope: 5.0,
        };
        let plain = SizeField {
            size: 30.0,
            min_size: 0.1,
            max_size: 100.0,
            growth: 1.2,
            refine: Vec::new(),
        };
        let refined = SizeField {
            refine: vec![point],
            ..plain.clone()
        };
        let (a, b) = (
            Background::new(&pts, &tris, &plain),
            Background::new(&pts, &tris, &refined),
        );
        let at = [10.0, 10.0, 10.0];
        assert!(
            b.size_at(&at) < 1.0 + 0.2 * 2.0 * b.cell,
            "{}",
            b.size_at(&at)
        );
        assert!(a.size_at(&at) > 5.0, "{}", a.size_at(&at));
        // 8 units away the size grew at most by the mesh's 0.2 per unit (plus a cell), far less
        // than the 5 per unit the refinement asked for.
        let off = [18.0, 10.0, 10.0];
        assert!(
            b.size_at(&off) <= 1.0 + 0.2 * (8.0 + 2.0 * b.cell),
            "{}",
            b.size_at(&off)
        );
    }
}
