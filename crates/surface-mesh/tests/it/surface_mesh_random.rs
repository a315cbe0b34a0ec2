//! Property test: random star-shaped loops (with random node spacing) on the wavy horizon, with
//! a random hole and a random dangling trace, always mesh into a mesh that passes `verify`, keeps
//! the given nodes, and has no triangle worse than a fixed bound.

use surface_mesh_common::*;
use test_support::surface_mesh_common;

use proptest::prelude::*;
use std::f64::consts::PI;
use surface_mesh::quality::stats;
use surface_mesh::{PatchInput, SurfaceSize, mesh_patch, verify};

proptest! {
    #![proptest_config(test_support::proptest_config(64))]
    #[test]
    fn random_star_shaped_patches_always_mesh_validly(
        radii in proptest::collection::vec(0.6f64..1.0, 7..14),
        nodes in 30usize..90,
        hole_r in 0.05f64..0.2,
        trace_angle in 0.0f64..(2.0 * PI),
        size in 40.0f64..90.0,
        utm in any::<bool>(),
    ) {
        let off = if utm { UTM } else { [0.0; 3] };
        let g = Grid { nx: 30, ny: 30, u: (0.0, 3000.0), v: (0.0, 3000.0), f: wavy, offset: off };
        let (cx, cy, r0) = (1500.0, 1500.0, 1300.0);
        // Smooth star-shaped radius function from the random control radii.
        let k = radii.len();
        let rad = |a: f64| {
            let s = a / (2.0 * PI) * k as f64;
            let i = s.floor() as usize % k;
            let t = s - s.floor();
            let w = 0.5 - 0.5 * (PI * t).cos();
            r0 * (radii[i] * (1.0 - w) + radii[(i + 1) % k] * w)
        };
        let outer: Vec<[f64; 3]> = (0..nodes)
            .map(|j| {
                let a = 2.0 * PI * j as f64 / nodes as f64;
                g.at(cx + rad(a) * a.cos(), cy + rad(a) * a.sin())
            })
            .collect();
        let hole = g.hole(cx, cy, hole_r * r0, 12);
        let (c, s) = (trace_angle.cos(), trace_angle.sin());
        let r1 = hole_r * r0 + 150.0;
        let trace: Vec<[f64; 3]> = (0..4).map(|j| {
            let r = r1 + 60.0 * j as f64;
            g.at(cx + r * c, cy + r * s)
        }).collect();
        let input = PatchInput { name: "random".into(), support: g.support(), loops: vec![outer, hole], constraints: vec![trace], points: vec![], facets: Vec::new() };
        let sz = SurfaceSize { size, min_size: 5.0, max_size: 400.0, growth: 1.3 };
        let out = mesh_patch(&input, &sz).map_err(|e| TestCaseError::fail(e.to_string()))?;
        verify(&input, &out, 1e-6).map_err(|e| TestCaseError::fail(e.to_string()))?;
        for (i, p) in input.loops.iter().flatten().enumerate() {
            prop_assert_eq!(out.nodes[i].map(f64::to_bits), p.map(f64::to_bits));
        }
        let q = stats(&out.nodes, &out.triangles);
        prop_assert!(q.mean < 1.12, "mean {}", q.mean);
        prop_assert!(q.max < 3.0, "max {}: {:?}", q.max, worst(&out));
    }
}
