//! The input triangle nearest to where a meshing node failed. A surface or tet mesh error names
//! the coordinates where it failed, in the model's terms; a geomodeller edits the surface files,
//! so the command line adds the file line of the closest triangle of the recipe's surfaces.
//!
//! Only failures pay for it: the surfaces are imported again (as their `import` nodes do, in the
//! model's units) the first time a failure needs them, and each gets an R-tree (rstar) of its
//! triangles, so a failure costs a logarithmic search, not a scan of the model, however many
//! meshes fail. A surface whose file cannot be read or imported is left out; its own node says
//! why. Of triangles equally near, the first in the recipe's surface order and the file's
//! triangle order is named, so the note is the same on every run.

use crate::recipe::Recipe;
use gocad::import::{ImportOptions, ImportedSurface, import_surface};
use rstar::{AABB, PointDistance, RTree, RTreeObject};

/// The last `at (x, y, z)` or `near (x, y, z)` of an error message: where the stage failed.
pub fn failure_place(error: &str) -> Option<[f64; 3]> {
    let start = ["at (", "near ("]
        .iter()
        .filter_map(|w| error.rfind(w).map(|i| i + w.len()))
        .max()?;
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

/// An input triangle in a surface's R-tree: its corners and its number in the surface.
struct Tri {
    p: [[f64; 3]; 3],
    index: u32,
}

impl RTreeObject for Tri {
    type Envelope = AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        let lo = [0, 1, 2].map(|k| self.p.iter().map(|q| q[k]).fold(f64::INFINITY, f64::min));
        let hi = [0, 1, 2].map(|k| {
            self.p
                .iter()
                .map(|q| q[k])
                .fold(f64::NEG_INFINITY, f64::max)
        });
        AABB::from_corners(lo, hi)
    }
}

impl PointDistance for Tri {
    fn distance_2(&self, at: &[f64; 3]) -> f64 {
        let [a, b, c] = &self.p;
        model::trims::triangle_distance(at, a, b, c).powi(2)
    }
}

/// A surface of the recipe, imported, with its name and its triangles indexed.
pub struct Indexed {
    name: String,
    surface: ImportedSurface,
    tree: RTree<Tri>,
}

impl Indexed {
    fn new(name: String, surface: ImportedSurface) -> Indexed {
        let v = &surface.mesh.vertices;
        let tris = (surface.mesh.triangles.iter().enumerate())
            .map(|(i, t)| Tri {
                p: t.map(|k| v[k as usize]),
                index: i as u32,
            })
            .collect();
        Indexed {
            name,
            tree: RTree::bulk_load(tris),
            surface,
        }
    }

    /// The nearest triangle to `at` and its squared distance; the lowest number among ties.
    fn nearest(&self, at: [f64; 3]) -> Option<(f64, u32)> {
        let mut near = self.tree.nearest_neighbor_iter_with_distance_2(at);
        let (first, d2) = near.next()?;
        let tied = near.take_while(|&(_, e2)| e2 == d2).map(|(t, _)| t.index);
        Some((d2, tied.fold(first.index, u32::min)))
    }
}

/// The recipe's surfaces, imported and indexed, with their names.
pub fn import_all(recipe: &Recipe) -> Vec<Indexed> {
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
            Some(Indexed::new(name.clone(), s))
        })
        .collect()
}

/// `file:line` of the input triangle nearest to `at`, its surface and how far it is (in `units`),
/// as a sentence; among the surface `only` when given (the surface of a failed patch: its
/// neighbours along a curve are as near). `None` when no such surface has a triangle.
pub fn nearest_triangle(
    surfaces: &[Indexed],
    only: Option<&str>,
    at: [f64; 3],
    units: &str,
) -> Option<String> {
    let mut best: Option<(f64, &Indexed, u32)> = None;
    for s in surfaces.iter().filter(|s| only.is_none_or(|o| o == s.name)) {
        if let Some((d2, t)) = s.nearest(at)
            && best.is_none_or(|(bd2, ..)| d2 < bd2)
        {
            best = Some((d2, s, t));
        }
    }
    let (d2, s, t) = best?;
    Some(format!(
        "the nearest input triangle is {}:{} (surface `{}`), {:.3} {units} from there",
        s.surface.source.file,
        s.surface.source.triangle_line(t),
        s.name,
        d2.sqrt()
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
        let split =
            "splitting `H1`: triangle 12 near (1.5, 2, 3): two curve points are at one place";
        assert_eq!(failure_place(split), Some([1.5, 2.0, 3.0]));
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
        let h1 = &surfaces.iter().find(|s| s.name == "H1").unwrap().surface;
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

    /// The nearest triangle by looking at every one: what the index must agree with.
    fn scanned(surfaces: &[Indexed], at: [f64; 3]) -> (f64, usize, u32) {
        let mut best = (f64::INFINITY, 0, 0);
        for (k, s) in surfaces.iter().enumerate() {
            let v = &s.surface.mesh.vertices;
            for (t, tri) in s.surface.mesh.triangles.iter().enumerate() {
                let [a, b, c] = tri.map(|i| v[i as usize]);
                let d = model::trims::triangle_distance(&at, &a, &b, &c).powi(2);
                if d < best.0 {
                    best = (d, k, t as u32);
                }
            }
        }
        best
    }

    #[test]
    fn the_indexed_search_names_the_triangle_a_scan_of_every_triangle_names() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("recipes");
        let recipe = crate::cli::load::load(&dir.join("didactic.toml"))
            .unwrap_or_else(|e| panic!("the example loads: {}", e.0));
        let surfaces = import_all(&recipe);
        // Points over the box and beyond it, on a lattice that falls on no symmetry of the data.
        for i in 0..7 {
            for j in 0..7 {
                for k in 0..5 {
                    let at = [
                        499_000.0 + 1_123.7 * i as f64,
                        6_999_000.0 + 1_049.3 * j as f64,
                        -2_600.0 + 610.9 * k as f64,
                    ];
                    let (d2, k, t) = scanned(&surfaces, at);
                    let s = &surfaces[k];
                    let said = nearest_triangle(&surfaces, None, at, "m").expect("a triangle");
                    let line = s.surface.source.triangle_line(t);
                    let want = format!(":{line} (surface `{}`), {:.3} m", s.name, d2.sqrt());
                    assert!(said.contains(&want), "{at:?}: {said} (scan: {want})");
                }
            }
        }
    }
}
