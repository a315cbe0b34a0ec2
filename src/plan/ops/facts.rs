//! `mesh_facts`: the report's figures of the final mesh (`report::MeshFacts`), derived after the
//! build from the `mesh` node's output rather than run as a node (see `engine::derive`): the
//! report is not a build output, so its figures are in neither the lock file nor the report's
//! own list of steps, but they are cached by the mesh's hash like any output, so a build whose
//! mesh did not change neither reads the mesh nor measures its tets again.

use crate::report::{FACTS_VERSION, MeshFacts};
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::mesh::VolumeMesh;

/// The figures of the volume mesh (the only input) of model `model` (named in the pictures).
pub struct MeshFactsOp {
    pub model: String,
}

impl Operation for MeshFactsOp {
    fn kind(&self) -> &'static str {
        "mesh_facts"
    }
    fn version(&self) -> u32 {
        FACTS_VERSION
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        p.set("model.name", self.model.as_str()).expect("string");
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let mesh: VolumeMesh = inputs
            .first()
            .ok_or("mesh_facts needs the mesh")?
            .decode()?;
        let facts = MeshFacts::of(&mesh, &self.model);
        Ok(Output::new(Artifact::encode(&facts)?).count("tets", facts.tets as u64))
    }
}
