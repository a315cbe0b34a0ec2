//! `export`: writes the build's output files. Inputs: every `discretize:<curve>` node, then
//! (when the model is meshed) `mesh`. Output: a `FileSet` the engine writes atomically under the
//! recipe's output directory: the mesh in every recipe format, the seed's Tables 1 and 2
//! (`<model>.quality.txt`, `.json`) and the curve discretization (`<model>.curves.vtu`). The
//! import validation (`validation.json`) is not here: the command line writes it after every
//! build from the import nodes, so a build that fails after the imports still has it.
//! The files are produced one at a time in path order and appended to the artifact as they
//! come (`FileSetEncoder`: the bytes of the `FileSet` encoding), so the whole set never sits in
//! memory beside its encoding; the decoded mesh is dropped after its last file.
//!
//! An Exodus file records where it came from (its QA and info records): the recipe's file name
//! and the node's own key, recomputed here from what the engine keys it by, so the file names
//! the lock file entry (`[nodes.export] key`) of the build that wrote it. The recipe's file name
//! enters the key only when Exodus is written, so renaming a recipe re-runs no other export.

use super::{CurveNodes, Groups};
use crate::recipe::Recipe;
use engine::artifact::FileSetEncoder;
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use export::curves::write_curves_vtu;
use export::quality;
use export::{Format, Provenance, export_with, file_names};
use geom::mesh::VolumeMesh;
use std::collections::BTreeMap;

pub struct ExportOp {
    pub model: String,
    /// The recipe's file name, recorded by the formats that carry provenance (Exodus).
    pub recipe_file: String,
    /// The formats to write, in recipe order (their names enter the key).
    pub formats: Vec<Format>,
    /// `curves` (their FE nodes) and `mesh` (the volume mesh, or empty for a model that is not
    /// meshed).
    pub inputs: Groups,
}

impl ExportOp {
    /// The export of `recipe`'s model in its `output.formats`, wired as `inputs` says.
    pub fn new(recipe: &Recipe, inputs: Groups) -> ExportOp {
        ExportOp {
            model: recipe.model.name.clone(),
            recipe_file: recipe
                .path
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
            formats: recipe
                .output
                .formats
                .iter()
                .map(|&f| crate::plan::output_format(f))
                .collect(),
            inputs,
        }
    }
}

impl Operation for ExportOp {
    fn kind(&self) -> &'static str {
        "export"
    }
    /// Its files are read only when they differ on disk from what the record says it wrote.
    fn lazy_output(&self) -> bool {
        true
    }
    fn version(&self) -> u32 {
        // 8: msh curve and corner entities bounding the surfaces.
        // 9: Abaqus truss sections of the wells given an area.
        // 10: Table 2 gives the bound each region's boundary sets on its smallest dihedral.
        // 11: and the place of its worst tet.
        11
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        p.set("model.name", self.model.as_str()).expect("string");
        let names: Vec<String> = self.formats.iter().map(|f| f.name().to_string()).collect();
        p.set("output.formats", names).expect("strings");
        if self.records_provenance() {
            p.set("recipe.file", self.recipe_file.as_str())
                .expect("string");
        }
        p
    }
    fn emits_files(&self) -> bool {
        true
    }
    fn run(&self, ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let mut curves = Vec::new();
        for c in self.inputs.decode::<CurveNodes>("curves", inputs)? {
            curves.push((c.name, c.nodes));
        }
        let nodes: usize = curves.iter().map(|(_, n)| n.len()).sum();
        let provenance = self.provenance(inputs);
        // Every file's name and source, known before any is written; a later format writing
        // the same name replaces an earlier one.
        let mut plan: BTreeMap<String, Source> = BTreeMap::new();
        plan.insert(format!("{}.curves.vtu", self.model), Source::Curves);
        let mut mesh = None;
        let mut quality = None;
        if let Some(m) = self.inputs.get("mesh", inputs)?.first() {
            let m: VolumeMesh = m.decode()?;
            for &format in &self.formats {
                // The names depend on the mesh (TetGen's `.edge` is there only with wells).
                for name in file_names(&self.model, format, &m) {
                    plan.insert(name, Source::Mesh(format));
                }
            }
            plan.insert(format!("{}.quality.txt", self.model), Source::QualityTxt);
            plan.insert(format!("{}.quality.json", self.model), Source::QualityJson);
            quality = Some(quality::report(&m));
            mesh = Some(m);
        }
        let last_mesh_file = plan
            .values()
            .rposition(|s| matches!(s, Source::Mesh(_)))
            .unwrap_or(0);
        // Files are produced in path order and appended to the artifact at once, so the peak
        // is the encoding plus the file being written (plus the mesh until its last file).
        let n = plan.len();
        let mut enc = FileSetEncoder::new(n);
        let mut pending: BTreeMap<String, Vec<u8>> = BTreeMap::new();
        for (i, (name, source)) in plan.iter().enumerate() {
            let bytes = match source {
                Source::Curves => write_curves_vtu(&curves),
                Source::QualityTxt | Source::QualityJson => {
                    let q = quality
                        .as_ref()
                        .ok_or_else(|| OpError::from("export: no mesh for the quality tables"))?;
                    if matches!(source, Source::QualityTxt) {
                        q.render().into_bytes()
                    } else {
                        serde_json::to_string_pretty(q)
                            .map_err(|e| OpError::from(e.to_string()))?
                            .into_bytes()
                    }
                }
                Source::Mesh(format) => match pending.remove(name) {
                    Some(b) => b,
                    None => {
                        let m = mesh
                            .as_ref()
                            .ok_or_else(|| OpError::from("export: no mesh to write"))?;
                        let mut this = None;
                        for (file, b) in export_with(m, &self.model, *format, &provenance)
                            .map_err(OpError::from)?
                        {
                            if file == *name {
                                this = Some(b);
                            } else if matches!(plan.get(&file), Some(Source::Mesh(f)) if f == format)
                            {
                                pending.insert(file, b);
                            }
                        }
                        this.ok_or_else(|| {
                            OpError::from(format!("export: {format:?} wrote no file `{name}`"))
                        })?
                    }
                },
            };
            if i == last_mesh_file {
                mesh = None;
            }
            enc.push(name, bytes).map_err(OpError::from)?;
            // One step per file written (each format's files, the curves, the quality tables).
            ctx.progress(i as u64 + 1, n as u64);
        }
        Ok(Output::new(enc.finish().map_err(OpError::from)?)
            .count("files", n as u64)
            .count("curve_nodes", nodes as u64))
    }
}

impl ExportOp {
    /// Whether a format the op writes records the recipe and the key.
    fn records_provenance(&self) -> bool {
        self.formats.contains(&Format::Exodus)
    }

    /// The recipe's file name and this node's key, as the engine computes it from the same
    /// inputs (empty when no format records them).
    fn provenance(&self, inputs: &[Artifact]) -> Provenance {
        if !self.records_provenance() {
            return Provenance::default();
        }
        let hashes: Vec<engine::Hash> = inputs.iter().map(Artifact::hash).collect();
        let key = engine::key::op_key(self.kind(), self.version(), &self.params(), &hashes);
        Provenance {
            recipe: self.recipe_file.clone(),
            key: key.to_hex(),
        }
    }
}

/// Where one output file comes from.
enum Source {
    Curves,
    Mesh(Format),
    QualityTxt,
    QualityJson,
}
