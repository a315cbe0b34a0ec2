//! `plan`: lowers a validated recipe into the build graph, and defines the operations that wrap
//! the pipeline stages for the engine.
//!
//! The static part comes from the recipe: one file node and one `import` node per surface, the
//! `box` node and one `surface` node per box side, one `intersect` node per pair, then `model`
//! (split, patches, trim to the box, regions; only with a box) and `curves` (the curves that
//! drive the expansion). The dynamic part is expanded after `curves` has run: one `curve:<name>`
//! node per curve (extracting that curve, so an unchanged curve cuts off early), one
//! `discretize:<name>` node per curve, and the `export` node that needs them all.
//!
//! Decisions: node names are the stable entity names (`import:H1`, `intersect:F1×H1`,
//! `discretize:F1/H1`), so the lock file, `explain` and `--json` speak the recipe's language.
//! Parameters are named by their recipe path (`mesh.curves."F1/H1".size`) so a changed value is
//! reported where the user wrote it. Every operation gets exactly the recipe values it uses, so an
//! edit re-runs only the operations that read the edited value.

mod lower;
pub mod ops;

pub use lower::{PlanError, curve_subdivision, lower};
