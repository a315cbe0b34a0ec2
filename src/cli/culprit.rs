//! The input triangle nearest to where a meshing node failed. A surface or tet mesh error names
//! the coordinates where it failed, in the model's terms; a geomodeller edits the surface files,
//! so the command line adds the file line of the closest triangle of the recipe's surfaces.
//!
//! Only failures pay for it: the surfaces are imported again (as their `import` nodes do, in the
//! model's units) the first time a failure needs them, and searched triangle by triangle. A
//! surface whose file cannot be read or imported is left out; its own node says why.

use crate::recipe::Recipe;
use gocad::import::{ImportOptions, ImportedSurface, import_surface};

/// The last `at (x, y, z)` of an error message: where the stage failed.
pub fn failure_place(error: &str) -> Option<[f64; 3]> {
    let start = error.rfind("at (")? + 4;
    let end = start + error[start..].find(')')?;
    let xs: Vec<f64> = error[start..end]
        .split(',')
        .map(|s| s.trim().parse().ok())
        .collect::<Option<_>>()?;
    match xs[..] {
        [x, y, z] if xs.iter().all(|v| v.is_finite()) => Some([x, y, z]),
        _ => None,
    }
}

/// The recipe's surfaces, imported, with their names.
pub fn import_all(recipe: &Recipe) -> Vec<(String, ImportedSurface)> {
    recipe
        .surfaces
        .iter()
        .filter_map(|(name, spec)| {
            let bytes = std::fs::read(&spec.path).ok()?;
            let opts = ImportOptions {
                object: spec.object.clone(),
                skip_other_types: spec.skip_other_types,
                target_units: Some(recipe.model.units),
            };
            let label = spec.file.display().to_string();
            let s = import_surface(&bytes, &label, &opts).ok()?;
            Some((name.clone(), s))
        })
        .collect()
}

/// `file:line` of the input triangle nearest to `at`, its surface and how far it is (in `units`),
/// as a sentence; among the surface `only` when given (the surface of a failed patch: its
/// neighbours along a curve are as near). `None` when no such surface has a triangle.
pub fn nearest_triangle(
    surfaces: &[(String, ImportedSurface)],
    only: Option<&str>,
    at: [f64; 3],
    units: &str,
) -> Option<String> {
    let mut best: Option<(f64, &str, &ImportedSurface, u32)> = None;
    for (name, s) in surfaces.iter().filter(|(n, _)| only.is_none_or(|o| o == n)) {
        let v = &s.mesh.vertices;
        for (t, tri) in s.mesh.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|i| v[i as usize]);
            let d = model::trims::triangle_distance(&at, &a, &b, &c);
            if best.is_none_or(|(bd, ..)| d < bd) {
                best = Some((d, name, s, t as u32));
            }
        }
    }
    let (d, name, s, t) = best?;
    Some(format!(
        "the nearest input triangle is {}:{} (surface `{name}`), {d:.3} {units} from there",
        s.source.file,
        s.source.triangle_line(t)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_place_is_the_last_coordinates_a_message_gives() {
        let e = "region 'r': the front is stuck at face [1, 2, 3] ((1.0, 2.0, 3.0), (4.0, 5.0, \
                 6.0)) (after Delaunay gave way: at (7, 8, 9)) at (500000.5, 7000000.25, -1200)";
        assert_eq!(failure_place(e), Some([500000.5, 7000000.25, -1200.0]));
        assert_eq!(failure_place("no place here"), None);
        assert_eq!(failure_place("at (1, 2)"), None);
        assert_eq!(failure_place("at (1, NaN, 2)"), None);
    }

    #[test]
    fn the_nearest_triangle_is_named_by_its_file_line() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("recipes");
        let recipe = crate::cli::load::load(&dir.join("didactic.toml"))
            .unwrap_or_else(|e| panic!("the example loads: {}", e.0));
        let surfaces = import_all(&recipe);
        assert_eq!(surfaces.len(), 4);
        // A point 2 m above the centroid of one of H1's triangles.
        let (_, h1) = surfaces.iter().find(|(n, _)| n == "H1").unwrap();
        let k = h1.mesh.triangles.len() / 3;
        let [a, b, c] = h1.mesh.triangles[k].map(|i| h1.mesh.vertices[i as usize]);
        let at = [0, 1, 2].map(|m| (a[m] + b[m] + c[m]) / 3.0 + if m == 2 { 2.0 } else { 0.0 });
        let said = nearest_triangle(&surfaces, None, at, "m").expect("a triangle");
        // At most the 2 m above it (less where the triangle dips).
        let d: f64 = said
            .trim_end_matches(" m from there")
            .rsplit(' ')
            .next()
            .and_then(|x| x.parse().ok())
            .expect("a distance");
        assert!(d > 1.9 && d <= 2.0, "{said}");
        // Restricted to another surface, the nearest is elsewhere and farther.
        let other = nearest_triangle(&surfaces, Some("H2"), at, "m").expect("a triangle");
        assert!(other.contains("(surface `H2`)"), "{other}");
        assert_eq!(nearest_triangle(&surfaces, Some("none"), at, "m"), None);
        let line = h1.source.triangle_line(k as u32);
        assert!(
            said.contains(&format!("H1_top_reservoir.ts:{line} (surface `H1`)")),
            "{said}"
        );
        let text = std::fs::read_to_string(dir.join("data/didactic/H1_top_reservoir.ts")).unwrap();
        assert!(text.lines().nth(line - 1).unwrap().starts_with("TRGL"));
    }
}
