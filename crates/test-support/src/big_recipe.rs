//! Recipes with tens of thousands of entries, written in memory: what a generated recipe (one
//! region per fault block, one curve rule per fault trace) looks like. The recipe checker must
//! stay near-linear in their size; the tests check that the answers stay right at that scale and
//! `benches/recipe_check.rs` measures the time.

/// A small valid recipe: three surfaces and a 10 × 10 × 10 box. Every big recipe starts with
/// it; the recipe-error tests extend or edit it.
pub const HEAD: &str = r#"[model]
name = "t"

[surfaces]
top = { file = "data/top.ts", kind = "horizon" }
base = { file = "data/base.ts", kind = "horizon" }
f1 = { file = "data/f1.ts", kind = "fault" }

[box]
min = [0.0, 0.0, -10.0]
max = [10.0, 10.0, 0.0]

[mesh]
size = 1.0
"#;

/// The 1-based line of the first entry after the head and one table header.
pub const FIRST_ENTRY_LINE: usize = 17;

/// `n` regions `r0…`, each at its own point inside the box.
pub fn regions(n: usize) -> String {
    let mut s = format!("{HEAD}\n[regions]\n");
    for i in 0..n {
        let (x, y) = region_xy(i);
        s.push_str(&format!("r{i} = {{ point = [{x}, {y}, -5.0] }}\n"));
    }
    s
}

/// The point of region `r{i}` in [`regions`].
pub fn region_xy(i: usize) -> (f64, f64) {
    (
        0.5 + (i % 1000) as f64 * 0.008,
        0.5 + (i / 1000) as f64 * 0.008,
    )
}

/// `n` curve rules, one per component `#k` of the curves between `top` and `f1`.
pub fn curve_rules(n: usize) -> String {
    let mut s = format!("{HEAD}\n[mesh.curves]\n");
    for k in 0..n {
        s.push_str(&format!("\"top/f1#{k}\" = {{ size = 2.0 }}\n"));
    }
    s
}

/// `n` distinct region names, each written twice in a row: `n` duplicate-key errors.
pub fn repeated_region_names(n: usize) -> String {
    let mut s = format!("{HEAD}\n[regions]\n");
    for i in 0..n {
        let (x, y) = region_xy(i);
        let line = format!("r{i} = {{ point = [{x}, {y}, -5.0] }}\n");
        s.push_str(&line);
        s.push_str(&line);
    }
    s
}
