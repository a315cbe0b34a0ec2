//! `import:<surface>`: reads one gOcad file's bytes into a validated, optionally repaired surface.
//! Its artifact carries the validation report of what was found; what repair left (the repaired
//! surface validated again) is in its counts, `findings_remaining` and one per kind left, so
//! that what is reported does not change the artifact the later stages' keys are made of.

use super::SurfaceData;
use engine::{Artifact, OpError, Operation, Output, Params, RunContext};
use geom::Tolerances;
use geom::mesh::SurfaceKind;
use gocad::{import, validate};
use std::collections::BTreeMap;

/// What to do when validation finds problems (the recipe's `on_invalid`).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum OnInvalid {
    /// Repair what is safe, keep the report.
    Repair,
    /// Fail the node with the report.
    Stop,
}

/// The count of validation findings left after repair, and (suffixed `.<kind>`) of each kind
/// left: counts of an import that found something.
pub const FINDINGS_REMAINING: &str = "findings_remaining";

/// What validation found on import of the surface whose node has `counts` and whose report is
/// `report_json`, and what repair left (from the counts), each by kind name.
pub fn findings_by_kind(
    report_json: &str,
    counts: &BTreeMap<String, u64>,
) -> (BTreeMap<String, u64>, BTreeMap<String, u64>) {
    let report: serde_json::Value = serde_json::from_str(report_json).unwrap_or_default();
    let found = report["counts"]
        .as_object()
        .map(|m| {
            m.iter()
                .filter_map(|(k, v)| Some((k.clone(), v.as_u64()?)))
                .collect()
        })
        .unwrap_or_default();
    let prefix = format!("{FINDINGS_REMAINING}.");
    let remaining = counts
        .iter()
        .filter_map(|(k, &n)| Some((k.strip_prefix(&prefix)?.to_string(), n)))
        .collect();
    (found, remaining)
}

pub struct ImportOp {
    pub surface: String,
    pub kind: SurfaceKind,
    /// The file as the recipe names it (for messages).
    pub file_label: String,
    pub object: Option<import::ObjectRef>,
    pub skip_other_types: bool,
    /// The recipe's units: every file's coordinates are converted from its `AXIS_UNIT` into them.
    pub target_units: import::Units,
    pub on_invalid: OnInvalid,
    pub tolerances: Tolerances,
}

impl Operation for ImportOp {
    fn kind(&self) -> &'static str {
        "import"
    }
    fn version(&self) -> u32 {
        // 3: coordinates beyond ±1e12 (no-data markers, damaged numbers) are refused.
        // 4: validation's exact contact test also sees a triangle that merging collapsed onto a
        //    line as a coplanar overlap.
        // 5: names and other text from a line are cut at 4096 bytes (a damaged giant line).
        5
    }
    fn params(&self) -> Params {
        let mut p = Params::new();
        let key = |k: &str| format!("surfaces.{}.{k}", self.surface);
        p.set(&key("kind"), format!("{:?}", self.kind).to_lowercase())
            .expect("finite");
        p.set(&key("file"), self.file_label.as_str())
            .expect("finite");
        // A name keys as the string it always did (none as ""), a position as an integer.
        match &self.object {
            Some(import::ObjectRef::Position(k)) => p.set(&key("object"), *k),
            Some(import::ObjectRef::Name(n)) => p.set(&key("object"), n.as_str()),
            None => p.set(&key("object"), ""),
        }
        .expect("finite");
        p.set(&key("skip_other_types"), self.skip_other_types)
            .expect("finite");
        p.set(
            &key("on_invalid"),
            if self.on_invalid == OnInvalid::Repair {
                "repair"
            } else {
                "stop"
            },
        )
        .expect("finite");
        p.set("model.units", format!("{:?}", self.target_units))
            .expect("string");
        for (k, v) in self.tolerances.fields() {
            p.set(&format!("tolerances.{k}"), v)
                .expect("validated finite");
        }
        p
    }
    fn run(&self, _ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError> {
        let bytes = inputs.first().ok_or("import needs its file")?.bytes()?;
        let opts = import::ImportOptions {
            object: self.object.clone(),
            skip_other_types: self.skip_other_types,
            target_units: Some(self.target_units),
        };
        let imported = import::import_surface(bytes, &self.file_label, &opts)
            .map_err(|e| OpError::from(e.to_string()))?;
        let report = validate::validate(&imported, &self.tolerances);
        let findings = report.findings.len() as u64;
        let (surface, remaining) = if report.is_clean() {
            (imported, None)
        } else if self.on_invalid == OnInvalid::Stop {
            return Err(OpError::from(format!(
                "surface `{}` ({}) is invalid and the recipe says on_invalid = \"stop\":\n{}",
                self.surface,
                self.file_label,
                report.render_text()
            )));
        } else {
            let (fixed, _log) = validate::repair(&imported, &report, &self.tolerances);
            // What repair left, found on the surface the later stages get.
            let remaining = validate::validate(&fixed, &self.tolerances).counts();
            (fixed, Some(remaining))
        };
        let data = SurfaceData {
            name: self.surface.clone(),
            kind: self.kind,
            mesh: surface.mesh,
            triangle_part: surface.triangle_part,
            bstones: surface.bstones,
            report_json: report.to_json().to_string(),
            report_text: if report.is_clean() {
                String::new()
            } else {
                report.render_text()
            },
            findings,
        };
        let mut out = Output::new(Artifact::encode(&data)?)
            .count("vertices", data.mesh.vertices.len() as u64)
            .count("triangles", data.mesh.triangles.len() as u64)
            .count("parts", surface.parts.len() as u64)
            .count("findings", findings);
        let remaining = remaining.unwrap_or_default();
        if findings > 0 {
            out = out.count(FINDINGS_REMAINING, remaining.values().sum());
            for (kind, &n) in remaining.iter().filter(|(_, n)| **n > 0) {
                out = out.count(&format!("{FINDINGS_REMAINING}.{kind}"), n);
            }
            out.notes.push(format!(
                "{} (see validation.json)",
                validate::repair_summary(&report.counts(), &remaining)
            ));
        }
        Ok(out)
    }
}
