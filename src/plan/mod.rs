//! `plan`: lowers a validated recipe into the build graph (`lower`), and defines the operations
//! that adapt the pipeline stages to the engine (`ops`), converting recipe values into stage
//! inputs on the way (`convert`; trim selectors are resolved to surface names in `lower`).
//!
//! The static part comes from the recipe: one file node and one `import` node per surface, the
//! `box` node and one `surface` node per box side, one `intersect` node per pair, then `model`
//! (split, patches, trims, regions, topology) when a box or `[model] sealed = true` closes the
//! regions, or else `curves` (the imports' free borders and the intersection curves). The dynamic
//! part is added by the expander of `model` (or of `curves`) once its output is known: one
//! `curve:<name>` and one `discretize:<name>` node per curve, and, for a model, one
//! `patch:<p>` and `surface_mesh:<p>` per patch, one `tet_mesh:<r>` per region, `mesh`, and the
//! `export` node.
//!
//! Decisions: node names are the stable entity names (`import:H1`, `intersect:F1/H1`,
//! `discretize:F1/H1`), so the lock file, `explain` and `--json` speak the recipe's language.
//! Parameters are named by their recipe path (`mesh.curves."F1/H1".size`) so a changed value is
//! reported where the user wrote it. Every operation gets exactly the recipe values it uses, so an
//! edit re-runs only the operations that read the edited value.

mod convert;
mod lower;
pub mod ops;

pub use convert::{output_format, subdivision, tet_method, trim_action};
pub use lower::{PlanError, curve_subdivision, lower};
