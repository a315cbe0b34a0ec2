//! `export`: writes the build's output files. Inputs: the import nodes (their validation
//! reports), then every `discretize:<curve>` node, then (when the model has a box) `mesh`.
//! Output: a `FileSet` the engine writes atomically under the recipe's output directory: the
//! mesh in every recipe format, the seed's Tables 1 and 2 (`<model>.quality.txt`, `.json`), the
//! curve discretization (`<model>.curves.vtu`) and the import validation (`validation.json`).
//! The mesh is decoded once and dropped before the files are packed into the artifact.

use super::{CurveNodes, SurfaceData};
use crate::engine::{Artifact, FileSet, OpError, Operation, Output, Params, RunContext};
use crate::mesh::VolumeMesh;
use crate::stages::export::curves::write_curves_vtu;
use crate::stages::export::{Format, export};
use crate::stages::quality;
use std::collections::BTreeMap;

pub struct ExportOp {
    pub model: String,
    pub formats: Vec<String>,
    pub n_imports: usize,
    pub n_curves: usize,
    /// Whether the last input is the `mesh` node.
    pub with_mesh: bool,
}

impl Operation for ExportOp {
    fn kind(&self) -> &'static str {
        "export"
    }
    fn version(&self) -> u32 {
        2
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        p.set("model.name", self.model.as_str()).expect("string");
        p.set("output.formats", self.formats.clone())
            .expect("strings");
        p
    }
    fn emits_files(&self) -> bool {
        true
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        if inputs.len() != self.n_imports + self.n_curves + usize::from(self.with_mesh) {
            return Err("export needs the import, curve and mesh nodes".into());
        }
        let mut reports = serde_json::Map::new();
        for a in &inputs[..self.n_imports] {
            let s: SurfaceData = a.decode()?;
            let v: serde_json::Value =
                serde_json::from_str(&s.report_json).unwrap_or(serde_json::Value::Null);
            reports.insert(s.name, v);
        }
        let mut curves = Vec::new();
        for a in &inputs[self.n_imports..self.n_imports + self.n_curves] {
            let c: CurveNodes = a.decode()?;
            curves.push((c.name, c.nodes));
        }
        let mut files = BTreeMap::new();
        let validation = serde_json::to_string_pretty(&serde_json::Value::Object(reports))
            .map_err(|e| OpError::from(e.to_string()))?;
        files.insert("validation.json".to_string(), validation.into_bytes());
        files.insert(
            format!("{}.curves.vtu", self.model),
            write_curves_vtu(&curves),
        );
        if self.with_mesh {
            let mesh: VolumeMesh = inputs[inputs.len() - 1].decode()?;
            for f in &self.formats {
                let format = Format::from_name(f)
                    .ok_or_else(|| OpError::from(format!("unknown output format `{f}`")))?;
                for (name, bytes) in export(&mesh, &self.model, format).map_err(OpError::from)? {
                    files.insert(name, bytes);
                }
            }
            let q = quality::report(&mesh);
            files.insert(
                format!("{}.quality.txt", self.model),
                q.render().into_bytes(),
            );
            let json =
                serde_json::to_string_pretty(&q).map_err(|e| OpError::from(e.to_string()))?;
            files.insert(format!("{}.quality.json", self.model), json.into_bytes());
        }
        let n = files.len() as u64;
        let nodes: usize = curves.iter().map(|(_, n)| n.len()).sum();
        // Consumed into the artifact (same bytes as `Artifact::encode`), freeing each file as
        // it is copied, so the set and its encoding are never both whole in memory.
        Ok(Output::new(FileSet { files }.into_artifact())
            .count("files", n)
            .count("curve_nodes", nodes as u64))
    }
}
