//! Peak memory and speed of the tetrahedral mesher alone, on one closed boundary (.off) and an
//! optional file of embedded triangles (.off, vertices matched by exact coordinates): the bar is
//! at most 300 bytes per tet at peak. Embedded vertices inside the region are added.
//! Two figures, both over what was held before `mesh_region` (reading the input does not count):
//! - the peak resident set (Linux `clear_refs` resets it just before), which includes memory the
//!   allocator keeps after a free. A 48-triangle cube is meshed first, so that the mesher's code
//!   is paged in and the allocator set up before the measure: doing that on the region itself
//!   added about 0.45 MB, 85 B/tet on a 5,000-tet region (set `COLD` to measure that way);
//! - the heap peak (a counting allocator): the mesher's own data at its largest.
//!
//! One thread.
//!
//! usage: [COLD=1] cargo run --release --example tet_memory -- BOUNDARY.off [EMBEDDED.off] [front]

use std::alloc::{GlobalAlloc, Layout, System};
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::time::Instant;

use geom::mesh::read::read_by_extension;
use tet_mesh::{Method, RegionInput, SizeField, TetMeshOptions, mesh_region};

/// Counts the live heap bytes and their peak: the mesher's own data at its largest, without what the
/// allocator keeps resident after a free or page rounding (which the resident-set figure includes).
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let live = LIVE.fetch_add(layout.size(), Relaxed) + layout.size();
            PEAK.fetch_max(live, Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Relaxed);
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            if new_size >= layout.size() {
                let live =
                    LIVE.fetch_add(new_size - layout.size(), Relaxed) + new_size - layout.size();
                PEAK.fetch_max(live, Relaxed);
            } else {
                LIVE.fetch_sub(layout.size() - new_size, Relaxed);
            }
        }
        p
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

fn status_kb(key: &str) -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with(key))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// A cube whose sides are `n` by `n` squares, each split in two, oriented outward: meshing it
/// first pages in the mesher's code (recovery, front, refinement, optimizer, verification)
/// without leaving freed memory behind worth counting.
fn grid_cube(n: u32) -> RegionInput {
    let mut vertices = Vec::new();
    let mut index = HashMap::new();
    let mut boundary = Vec::new();
    let mut at = |p: [u32; 3], vertices: &mut Vec<[f64; 3]>| {
        *index.entry(p).or_insert_with(|| {
            vertices.push(p.map(|c| c as f64 / n as f64));
            (vertices.len() - 1) as u32
        })
    };
    for axis in 0..3 {
        for side in [0, n] {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            for i in 0..n {
                for j in 0..n {
                    let corner = |di: u32, dj: u32| {
                        let mut p = [0; 3];
                        p[axis] = side;
                        p[u] = i + di;
                        p[v] = j + dj;
                        p
                    };
                    let q = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)]
                        .map(|p| at(p, &mut vertices));
                    // (u, v, axis) is right-handed: the normal of q points along +axis.
                    let mut tris = [[q[0], q[1], q[2]], [q[0], q[2], q[3]]];
                    if side == 0 {
                        tris.iter_mut().for_each(|t| t.swap(1, 2));
                    }
                    boundary.extend(tris);
                }
            }
        }
    }
    RegionInput {
        name: "warm-up cube".into(),
        vertices,
        boundary,
        embedded: vec![],
        lines: Vec::new(),
    }
}

fn read(path: &str) -> geom::mesh::read::BoundaryMesh {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    read_by_extension(path, &bytes).unwrap_or_else(|e| panic!("{e}"))
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(boundary) = args.first() else {
        eprintln!("usage: tet_memory BOUNDARY.off [EMBEDDED.off] [front]");
        std::process::exit(2);
    };
    let b = read(boundary);
    let mut input = RegionInput {
        name: boundary.clone(),
        vertices: b.vertices,
        boundary: b.triangles,
        embedded: vec![],
        lines: Vec::new(),
    };
    // One closed shell: orient it outward by the sign of its enclosed volume.
    let vol: f64 = input
        .boundary
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| input.vertices[i as usize]);
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum();
    if vol < 0.0 {
        input.boundary.iter_mut().for_each(|t| t.swap(1, 2));
    }
    if let Some(e) = args.get(1).filter(|a| a.ends_with(".off")) {
        let e = read(e);
        // Fault vertices inside the region are not boundary vertices: they are added.
        let mut index: HashMap<[u64; 3], u32> = input
            .vertices
            .iter()
            .enumerate()
            .map(|(i, p)| (p.map(f64::to_bits), i as u32))
            .collect();
        for t in &e.triangles {
            let f = t.map(|i| {
                let p = e.vertices[i as usize];
                *index.entry(p.map(f64::to_bits)).or_insert_with(|| {
                    input.vertices.push(p);
                    (input.vertices.len() - 1) as u32
                })
            });
            input.embedded.push(f);
        }
    }
    let method = if args.iter().any(|a| a == "front") {
        Method::Front
    } else {
        Method::Delaunay
    };
    let opts = TetMeshOptions {
        method,
        ..TetMeshOptions::default()
    };
    if std::env::var_os("COLD").is_none() {
        mesh_region(&grid_cube(2), &SizeField::default(), &opts)
            .unwrap_or_else(|e| panic!("the warm-up cube: {e}"));
    }
    let before = status_kb("VmRSS:").unwrap_or(0);
    let heap_before = LIVE.load(Relaxed);
    PEAK.store(heap_before, Relaxed);
    let reset = std::fs::write("/proc/self/clear_refs", "5").is_ok();
    let t0 = Instant::now();
    let out = mesh_region(&input, &SizeField::default(), &opts).unwrap_or_else(|e| panic!("{e}"));
    let secs = t0.elapsed().as_secs_f64();
    let peak = status_kb("VmHWM:").unwrap_or(0);
    let heap_peak = PEAK.load(Relaxed) - heap_before;
    let tets = out.tets.len();
    let extra = peak.saturating_sub(before) * 1024;
    println!(
        "{boundary}: {tets} tets in {secs:.3} s ({:.0} tets/s, {method:?}{}), peak {} MB over {} MB before: {:.0} B/tet{}, heap peak {:.0} B/tet; MR avg {:.4} min {:.3}, min dihedral {:.1}",
        tets as f64 / secs,
        out.stats
            .fallback
            .as_deref()
            .map(|f| format!(", fell back: {f}"))
            .unwrap_or_default(),
        peak / 1024,
        before / 1024,
        extra as f64 / tets as f64,
        if reset {
            ""
        } else {
            " (peak not reset: includes reading)"
        },
        heap_peak as f64 / tets as f64,
        out.stats.avg_mean_ratio,
        out.stats.min_mean_ratio,
        out.stats.min_dihedral_deg
    );
}
