//! `crossings`: the pairs of surfaces that meet inside the box although `[intersect]` does not
//! pair them. Such a pair is never split along its contact, so the model is not conforming
//! there and the build fails much later (a tet mesher's "boundary triangle intersects embedded
//! triangle") far from the cause; the build says which pair to add instead.
//!
//! Decisions and why:
//! - Every pair not in `[intersect]` whose boxes overlap inside the model's box is intersected
//!   exactly (`model::intersect`); a pair counts when a point of a contact curve lies in the box
//!   (closed: a horizon that reaches a box side it is not paired with counts too). Pairs of two
//!   box sides always meet along the box's edges and are left out.
//! - It reports, it does not fail: a crossing in a part that a trim discards is harmless, and
//!   only the user knows. The CLI prints each pair as a warning and the report lists it.
//! - The node depends on every surface and on the pair list, so it re-runs when either changes
//!   and never otherwise.

use super::{Groups, SurfaceData};
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::BBox;
use geom::mesh::SurfaceKind;
use model::intersect::{SurfaceRef, intersect};
use serde::{Deserialize, Serialize};

/// Two surfaces that meet in the box without being paired, and a point where they do.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Crossing {
    pub a: String,
    pub b: String,
    pub at: [f64; 3],
}

impl Crossing {
    /// The warning a user reads, naming what to add to the recipe.
    pub fn message(&self) -> String {
        format!(
            "surfaces `{}` and `{}` meet at ({:.1}, {:.1}, {:.1}) inside the box, but \
             `[intersect]` does not pair them: the mesh cannot conform there; add \
             `[\"{}\", \"{}\"]` to `pairs` (or trim the part away)",
            self.a, self.b, self.at[0], self.at[1], self.at[2], self.a, self.b
        )
    }
}

pub struct CrossingsOp {
    /// `box` (none for a sealed model) and `surfaces`.
    pub inputs: Groups,
    /// The recipe's pairs, each sorted, the list sorted.
    pub paired: Vec<(String, String)>,
}

impl Operation for CrossingsOp {
    fn kind(&self) -> &'static str {
        "crossings"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        let pairs: Vec<String> = self
            .paired
            .iter()
            .map(|(a, b)| format!("{a}/{b}"))
            .collect();
        Params::new().with("intersect", pairs).expect("strings")
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let bbox: Option<BBox> = match self.inputs.get("box", inputs)?.first() {
            Some(a) => Some(a.decode()?),
            None => None,
        };
        let mut surfaces: Vec<SurfaceData> = self
            .inputs
            .get("surfaces", inputs)?
            .iter()
            .map(|a| a.decode())
            .collect::<Result<_, _>>()?;
        surfaces.sort_by(|x, y| x.name.cmp(&y.name));
        let mut found = Vec::new();
        for (i, s) in surfaces.iter().enumerate() {
            for t in &surfaces[i + 1..] {
                if let Some(c) = self.unpaired_crossing(s, t, bbox.as_ref()) {
                    found.push(c);
                }
            }
        }
        let n = found.len() as u64;
        Ok(Output::new(Artifact::encode(&found)?).count("unpaired", n))
    }
}

impl CrossingsOp {
    fn unpaired_crossing(
        &self,
        s: &SurfaceData,
        t: &SurfaceData,
        bbox: Option<&BBox>,
    ) -> Option<Crossing> {
        let both_box = s.kind == SurfaceKind::Box && t.kind == SurfaceKind::Box;
        let pair = (s.name.clone(), t.name.clone());
        if both_box || self.paired.binary_search(&pair).is_ok() {
            return None;
        }
        let (bs, bt) = (s.mesh.bbox(), t.mesh.bbox());
        let apart = |b: &BBox| !b.overlaps(&bs) || !b.overlaps(&bt);
        if !bs.overlaps(&bt) || bbox.is_some_and(apart) {
            return None;
        }
        let x = intersect(
            SurfaceRef {
                name: &s.name,
                mesh: &s.mesh,
            },
            SurfaceRef {
                name: &t.name,
                mesh: &t.mesh,
            },
        )
        .ok()?;
        let inside = |p: &[f64; 3]| bbox.is_none_or(|b| b.contains(p));
        let at = x
            .curves
            .iter()
            .flat_map(|c| c.points.iter().map(|p| p.xyz))
            .find(|p| inside(p))?;
        Some(Crossing {
            a: s.name.clone(),
            b: t.name.clone(),
            at,
        })
    }
}

/// The crossings a build found (none when its `crossings` node did not finish).
pub fn unpaired_crossings(report: &engine::BuildReport) -> Vec<Crossing> {
    report
        .artifact("crossings")
        .and_then(|a| a.decode().ok())
        .unwrap_or_default()
}
