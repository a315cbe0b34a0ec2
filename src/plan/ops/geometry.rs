//! `box`, `surface:box.<side>` and `intersect:<a>×<b>`: the bounding box, its six planar sides,
//! and the exact intersection of two surfaces.

use super::SurfaceData;
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::BBox;
use geom::mesh::SurfaceKind;
use model::intersect;

/// How the box is given: explicitly, or as the extent of some surfaces plus a margin.
#[derive(Clone, Debug, PartialEq)]
pub enum BoxSpecParams {
    Explicit {
        min: [f64; 3],
        max: [f64; 3],
    },
    /// The inputs of the node are the named surfaces' import nodes, in this order.
    Around {
        surfaces: Vec<String>,
        margin: [f64; 3],
    },
}

/// `box`: the model's bounding box. Output: `BBox`.
pub struct BoxOp(pub BoxSpecParams);

impl Operation for BoxOp {
    fn kind(&self) -> &'static str {
        "box"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        match &self.0 {
            BoxSpecParams::Explicit { min, max } => {
                p.set("box.min", *min).expect("validated finite");
                p.set("box.max", *max).expect("validated finite");
            }
            BoxSpecParams::Around { surfaces, margin } => {
                p.set("box.around", surfaces.clone()).expect("strings");
                p.set("box.margin", *margin).expect("validated finite");
            }
        }
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let bbox = match &self.0 {
            BoxSpecParams::Explicit { min, max } => BBox {
                min: *min,
                max: *max,
            },
            BoxSpecParams::Around { margin, .. } => {
                let mut b = BBox::empty();
                for a in inputs {
                    let s: SurfaceData = a.decode()?;
                    b = b.union(&s.mesh.bbox());
                }
                if b.is_empty() {
                    return Err("the box's surfaces have no vertices".into());
                }
                BBox {
                    min: [
                        b.min[0] - margin[0],
                        b.min[1] - margin[1],
                        b.min[2] - margin[2],
                    ],
                    max: [
                        b.max[0] + margin[0],
                        b.max[1] + margin[1],
                        b.max[2] + margin[2],
                    ],
                }
            }
        };
        if (0..3)
            .any(|k| bbox.min[k].is_nan() || bbox.max[k].is_nan() || bbox.min[k] >= bbox.max[k])
        {
            return Err(format!(
                "the box is empty or flat: min {:?}, max {:?}",
                bbox.min, bbox.max
            )
            .into());
        }
        Ok(Output::new(Artifact::encode(&bbox)?).count("volume_m3", bbox.volume().round() as u64))
    }
}

/// `surface:box.<side>`: one planar side of the box as a surface.
pub struct BoxSideOp {
    pub side: String,
}

impl Operation for BoxSideOp {
    fn kind(&self) -> &'static str {
        "box_side"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        Params::new()
            .with("side", self.side.as_str())
            .expect("string")
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let bbox: BBox = inputs.first().ok_or("box side needs the box")?.decode()?;
        let (name, mesh) = intersect::box_sides(&bbox)
            .into_iter()
            .find(|(n, _)| *n == self.side)
            .ok_or_else(|| OpError::from(format!("no box side named `{}`", self.side)))?;
        let data = SurfaceData {
            name,
            kind: SurfaceKind::Box,
            triangle_part: vec![0; mesh.triangles.len()],
            mesh,
            bstones: Vec::new(),
            report_json: String::new(),
            report_text: String::new(),
            findings: 0,
        };
        Ok(Output::new(Artifact::encode(&data)?)
            .count("triangles", data.mesh.triangles.len() as u64))
    }
}

/// `intersect:<a>×<b>`: the intersection curves of two surfaces (inputs: the two surfaces, in
/// name order). Output: `model::intersect::Intersection`.
pub struct IntersectOp {
    pub a: String,
    pub b: String,
}

impl Operation for IntersectOp {
    fn kind(&self) -> &'static str {
        "intersect"
    }
    /// Read only by `model` and `crossings` when they re-run.
    fn lazy_output(&self) -> bool {
        true
    }
    fn version(&self) -> u32 {
        // 2: triangles the two surfaces hold in common are listed, not an error.
        // 3: unless the two also cross elsewhere at under a degree (one part drawn twice).
        3
    }
    fn params(&self) -> Params {
        Params::new()
            .with("intersect.pair", vec![self.a.clone(), self.b.clone()])
            .expect("strings")
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let [sa, sb] = inputs else {
            return Err("intersect needs exactly two surfaces".into());
        };
        let sa: SurfaceData = sa.decode()?;
        let sb: SurfaceData = sb.decode()?;
        let x = intersect::intersect(
            intersect::SurfaceRef {
                name: &sa.name,
                mesh: &sa.mesh,
            },
            intersect::SurfaceRef {
                name: &sb.name,
                mesh: &sb.mesh,
            },
        )
        .map_err(|e| OpError::from(e.to_string()))?;
        let points: usize = x.curves.iter().map(|c| c.points.len()).sum();
        Ok(Output::new(Artifact::encode(&x)?)
            .count("curves", x.curves.len() as u64)
            .count("points", points as u64))
    }
}
