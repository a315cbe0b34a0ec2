//! georecipe: a declarative model-recipe compiler for subsurface finite-element meshing.
//!
//! A TOML recipe is parsed and validated (`recipe`), lowered into a DAG of operations (`plan`),
//! and executed by the content-hashed, cached, parallel build engine (the `engine` crate), which
//! knows nothing about meshes. The operations adapt the pipeline stages, which live in crates of
//! their own below this one (`gocad`, `model`, `surface_mesh`, `tet_mesh`, `export`, on `geom`),
//! and never see the recipe: the plan converts recipe values into their inputs. The command line
//! (`cli`) is the only place besides the engine that touches the filesystem; `report` writes the
//! build's report. See ARCHITECTURE.md for the crate map, the data flow and the invariants.

pub mod cli;
pub mod plan;
pub mod recipe;
pub mod report;
