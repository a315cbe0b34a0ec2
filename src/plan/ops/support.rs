//! `support:<surface>`: an imported surface's support made over as the recipe asks before anything
//! is cut on it: re-triangulated at a size (`retriangulate`), then refined on curves through its
//! vertices with any Taubin passes (`smooth`), so an FE mesh finer than the file's facets follows
//! a smooth surface.
//!
//! Decisions and why:
//! - Only a surface with either key gets this node, and every later stage reads it in place of
//!   `import:<surface>`; other surfaces keep their graph and their keys.
//! - It runs before intersection, so the curves are cut exactly on the support the FE mesh is
//!   made on; borders, TFACE borders, creases and BSTONEs stay where they were (see
//!   `surface_mesh::refine_smooth` and `model::remesh`).
//! - Re-triangulation meshes the surface piece by piece, cut as the model cuts it (TFACEs,
//!   creases, charts), so closed bodies, tubes and folded box TSurfs re-triangulate too.

use super::SurfaceData;
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::{Tolerances, TriMesh};
use surface_mesh::{SupportSmoothing, refine_smooth};

pub struct SupportOp {
    pub surface: String,
    /// The recipe's `retriangulate` size.
    pub retriangulate: Option<f64>,
    /// The recipe's `smooth`.
    pub smooth: Option<SupportSmoothing>,
    pub tolerances: Tolerances,
}

impl Operation for SupportOp {
    fn kind(&self) -> &'static str {
        "support"
    }
    fn version(&self) -> u32 {
        // 2: re-triangulation keeps the corners of the recipe's kink angle, not the default's.
        // 3: the surface mesher inserts the border's nodes in a biased randomized order.
        // 4: the tet mesher's biased randomized order.
        // 5: re-triangulation piece by piece (TFACEs, creases, charts), every tolerance keyed.
        5
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        let key = |k: &str| format!("surfaces.{}.{k}", self.surface);
        if let Some(size) = self.retriangulate {
            p.set(&key("retriangulate"), size)
                .expect("validated finite");
        }
        if let Some(s) = self.smooth {
            p.set(&key("smooth.levels"), s.levels).expect("finite");
            p.set(&key("smooth.passes"), s.passes).expect("finite");
        }
        // Both keep the support's corners (turns above the kink angle); re-triangulation cuts
        // at creases and into charts and meshes within the support distance.
        for (name, value) in self.tolerances.fields() {
            p.set(&format!("tolerances.{name}"), value)
                .expect("validated finite");
        }
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let mut s: SurfaceData = inputs.first().ok_or("support needs its import")?.decode()?;
        let given = s.mesh.triangles.len() as u64;
        if let Some(size) = self.retriangulate {
            self.retriangulated(&mut s, size)?;
        }
        let mut moved = 0.0;
        if let Some(how) = &self.smooth {
            let kink = self.tolerances.kink_angle_deg;
            let out = refine_smooth(&s.mesh, &s.triangle_part, &s.bstones, how, kink)
                .map_err(|e| self.fail("smooth", &e))?;
            s.mesh = out.mesh;
            s.triangle_part = out.parts;
            moved = out.max_moved;
        }
        let n = s.mesh.triangles.len() as u64;
        Ok(Output::new(Artifact::encode(&s)?)
            .count("given_triangles", given)
            .count("support_triangles", n)
            .count("max_moved_mm", (moved * 1000.0).round() as u64))
    }
}

impl SupportOp {
    fn fail(&self, key: &str, why: &str) -> OpError {
        OpError::from(format!("surfaces.{}.{key}: {why}", self.surface))
    }

    /// Replaces `s`'s support by one re-triangulated at `size`, its TFACEs and BSTONEs kept (the
    /// BSTONEs renumbered).
    fn retriangulated(&self, s: &mut SurfaceData, size: f64) -> Result<(), OpError> {
        let out = model::remesh::remesh(
            &self.surface,
            &s.mesh,
            &s.triangle_part,
            &s.bstones,
            size,
            &self.tolerances,
        )
        .map_err(|e| self.fail("retriangulate", &e.to_string()))?;
        s.bstones = renumbered(&s.mesh, &s.bstones, &out.mesh).map_err(|p| {
            self.fail(
                "retriangulate",
                &format!(
                    "the corner (BSTONE) at ({}, {}, {}) was lost; remove `retriangulate`",
                    p[0], p[1], p[2]
                ),
            )
        })?;
        s.triangle_part = out.parts;
        s.mesh = out.mesh;
        Ok(())
    }
}

/// The indices in `new` of the vertices `old_ids` of `old` (kept bit for bit), or the first one
/// missing.
fn renumbered(old: &TriMesh, old_ids: &[u32], new: &TriMesh) -> Result<Vec<u32>, [f64; 3]> {
    let at: std::collections::BTreeMap<[u64; 3], u32> = (new.vertices.iter().enumerate())
        .map(|(i, p)| (p.map(f64::to_bits), i as u32))
        .collect();
    (old_ids.iter())
        .map(|&v| {
            let p = old
                .vertices
                .get(v as usize)
                .copied()
                .unwrap_or([f64::NAN; 3]);
            at.get(&p.map(f64::to_bits)).copied().ok_or(p)
        })
        .collect()
}
