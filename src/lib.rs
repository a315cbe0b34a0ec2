//! georecipe: a declarative model-recipe compiler for subsurface finite-element meshing.
//!
//! A TOML recipe is parsed and validated (`recipe`), lowered into a DAG of operations (`plan`),
//! and executed by a content-hashed, cached, parallel build engine (`engine`) that knows nothing
//! about meshes. The operations are the pipeline stages (`stages`), pure functions of typed inputs
//! built on exact geometry (`geom`) and the FE mesh types they exchange (`mesh`). The command line
//! (`cli`) is the only place besides the engine's store that touches the filesystem.
//! See ARCHITECTURE.md for the module map, the data flow and the invariants.

pub mod cli;
pub mod engine;
pub mod geom;
pub mod mesh;
pub mod plan;
pub mod recipe;
pub mod stages;
