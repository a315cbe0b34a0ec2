//! Real data: RINGMesh's sealed Model3d files (../shared). Their surfaces already meet along
//! shared edges (a horizon ending on a fault shares the fault's vertices), so every contact is
//! degenerate: curves along edges, through vertices, surfaces sharing vertices. Splitting such
//! a conforming model along all its intersections must give it back unchanged: no new vertex,
//! the same triangles, every curve piece an existing edge.

use crate::intersect_support;

use geom::TriMesh;
use gocad::import::{ImportOptions, import_surfaces};
use intersect_support::assert_sound;
use model::intersect::split::split_model;
use model::intersect::{Intersection, SurfaceRef, intersect};
use std::path::PathBuf;
use test_support::paths;

fn data_dir() -> Option<PathBuf> {
    paths::shared("data/gocad/ringmesh__RINGMesh/tests/data")
}

fn sealed_model_splits_into_itself(file: &str) {
    let Some(dir) = data_dir() else { return };
    let bytes = std::fs::read(dir.join(file)).expect("read");
    let opts = ImportOptions {
        skip_other_types: true,
        ..Default::default()
    };
    let surfaces: Vec<(String, TriMesh)> = import_surfaces(&bytes, file, &opts)
        .unwrap_or_else(|e| panic!("{e}"))
        .into_iter()
        .map(|s| (s.name, s.mesh))
        .collect();
    let mut xs: Vec<Intersection> = Vec::new();
    for i in 0..surfaces.len() {
        for j in i + 1..surfaces.len() {
            let (a, b) = (&surfaces[i], &surfaces[j]);
            let x = intersect(
                SurfaceRef {
                    name: &a.0,
                    mesh: &a.1,
                },
                SurfaceRef {
                    name: &b.0,
                    mesh: &b.1,
                },
            )
            .unwrap_or_else(|e| panic!("{file}: {e}"));
            if !x.curves.is_empty() {
                xs.push(x);
            }
        }
    }
    assert!(
        xs.len() >= surfaces.len() / 2,
        "{file}: {} contacts",
        xs.len()
    );
    let refs: Vec<(&str, &TriMesh)> = surfaces.iter().map(|(n, m)| (n.as_str(), m)).collect();
    let split = split_model(&refs, &xs).unwrap_or_else(|e| panic!("{file}: {e}"));
    for ((name, mesh), s) in refs.iter().zip(&split) {
        assert_sound(mesh, s);
        assert_eq!(
            s.mesh.vertices.len(),
            mesh.vertices.len(),
            "{file}: {name} gains no vertex"
        );
        let sorted = |m: &TriMesh| {
            let mut t: Vec<[u32; 3]> = m
                .triangles
                .iter()
                .map(|t| {
                    let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
                    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
                })
                .collect();
            t.sort_unstable();
            t
        };
        assert_eq!(
            sorted(&s.mesh),
            sorted(mesh),
            "{file}: {name} keeps its triangles"
        );
    }
}

#[test]
fn model_a1_splits_into_itself() {
    sealed_model_splits_into_itself("modelA1.ml");
}

#[test]
fn model_a2_splits_into_itself() {
    sealed_model_splits_into_itself("modelA2.ml");
}

#[test]
fn model_a5_splits_into_itself() {
    sealed_model_splits_into_itself("modelA5.ml");
}

#[test]
fn model_a4_splits_into_itself() {
    sealed_model_splits_into_itself("modelA4.ml");
}

#[test]
fn cloudspin_splits_into_itself() {
    sealed_model_splits_into_itself("CloudSpin_fixed.ml");
}
