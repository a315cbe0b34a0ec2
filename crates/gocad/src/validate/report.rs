//! The validation report: findings with their kind, part, entity ids (mesh indices and gOcad
//! ids), source lines and coordinates; rendered as readable text and as JSON. Findings are kept
//! sorted (kind, then entities), so reports are byte-identical across runs and thread counts.

use crate::import::ImportedSurface;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt::Write;

#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FindingKind {
    UnreferencedVertex,
    DuplicateVertex,
    DegenerateTriangle,
    DuplicateTriangle,
    InconsistentOrientation,
    NonManifoldEdge,
    CoplanarOverlap,
    SelfIntersection,
}

impl FindingKind {
    pub const ALL: [FindingKind; 8] = [
        FindingKind::UnreferencedVertex,
        FindingKind::DuplicateVertex,
        FindingKind::DegenerateTriangle,
        FindingKind::DuplicateTriangle,
        FindingKind::InconsistentOrientation,
        FindingKind::NonManifoldEdge,
        FindingKind::CoplanarOverlap,
        FindingKind::SelfIntersection,
    ];
    /// snake_case name, as in JSON and `counts()`.
    pub fn name(self) -> &'static str {
        match self {
            FindingKind::UnreferencedVertex => "unreferenced_vertex",
            FindingKind::DuplicateVertex => "duplicate_vertex",
            FindingKind::DegenerateTriangle => "degenerate_triangle",
            FindingKind::DuplicateTriangle => "duplicate_triangle",
            FindingKind::InconsistentOrientation => "inconsistent_orientation",
            FindingKind::NonManifoldEdge => "non_manifold_edge",
            FindingKind::CoplanarOverlap => "coplanar_overlap",
            FindingKind::SelfIntersection => "self_intersection",
        }
    }

    /// The kind named `name` (its [`name`](Self::name)).
    pub fn from_name(name: &str) -> Option<FindingKind> {
        FindingKind::ALL.into_iter().find(|k| k.name() == name)
    }

    /// `n` findings of this kind in words: `1 duplicate vertex`, `6 self-intersections`.
    pub fn count_text(self, n: u64) -> String {
        let (one, many) = match self {
            FindingKind::UnreferencedVertex => ("unreferenced vertex", "unreferenced vertices"),
            FindingKind::DuplicateVertex => ("duplicate vertex", "duplicate vertices"),
            FindingKind::DegenerateTriangle => ("degenerate triangle", "degenerate triangles"),
            FindingKind::DuplicateTriangle => ("duplicate triangle", "duplicate triangles"),
            FindingKind::InconsistentOrientation => (
                "edge with inconsistent orientation",
                "edges with inconsistent orientation",
            ),
            FindingKind::NonManifoldEdge => ("non-manifold edge", "non-manifold edges"),
            FindingKind::CoplanarOverlap => ("coplanar overlap", "coplanar overlaps"),
            FindingKind::SelfIntersection => ("self-intersection", "self-intersections"),
        };
        format!("{n} {}", if n == 1 { one } else { many })
    }
}

/// Findings that [`repair`](super::repair) removed, by kind name: those `found` on import that
/// are not `remaining` on the repaired surface (both by kind name, as [`ValidationReport::counts`]).
pub fn repaired_counts(
    found: &BTreeMap<String, u64>,
    remaining: &BTreeMap<String, u64>,
) -> BTreeMap<String, u64> {
    FindingKind::ALL
        .iter()
        .map(|k| {
            let f = found.get(k.name()).copied().unwrap_or(0);
            let r = remaining.get(k.name()).copied().unwrap_or(0);
            (k.name().to_string(), f.saturating_sub(r))
        })
        .collect()
}

/// One line on what validation found on import and what repair left on the surface (counts by
/// kind name): `86 validation findings: 80 repaired (78 duplicate vertices, 2 degenerate
/// triangles), 6 remain (6 self-intersections)`, or `clean`.
pub fn repair_summary(found: &BTreeMap<String, u64>, remaining: &BTreeMap<String, u64>) -> String {
    let total: u64 = found.values().sum();
    let left: u64 = remaining.values().sum();
    if total == 0 && left == 0 {
        return "clean".to_string();
    }
    let repaired = repaired_counts(found, remaining);
    let fixed: u64 = repaired.values().sum();
    let list = |m: &BTreeMap<String, u64>| {
        FindingKind::ALL
            .iter()
            .filter_map(|k| {
                let n = m.get(k.name()).copied().unwrap_or(0);
                (n > 0).then(|| k.count_text(n))
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let fixed = match fixed {
        0 => "none repaired".to_string(),
        n => format!("{n} repaired ({})", list(&repaired)),
    };
    let left = match left {
        0 => "none remain".to_string(),
        1 => format!("1 remains ({})", list(remaining)),
        n => format!("{n} remain ({})", list(remaining)),
    };
    format!(
        "{total} validation finding{}: {fixed}, {left}",
        if total == 1 { "" } else { "s" }
    )
}

/// One defect. `vertices` are mesh indices (with their gOcad ids in `vertex_ids`), `triangles`
/// mesh indices; `lines` are the source lines of the triangles (of the vertices when the finding
/// has no triangle); `points` the coordinates of the vertices, or of the triangles' corners.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Finding {
    pub kind: FindingKind,
    pub part: Option<u32>,
    pub vertices: Vec<u32>,
    pub vertex_ids: Vec<u64>,
    pub triangles: Vec<u32>,
    pub lines: Vec<usize>,
    pub points: Vec<[f64; 3]>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ValidationReport {
    pub surface: String,
    pub file: String,
    pub part_names: Vec<String>,
    pub findings: Vec<Finding>,
    #[serde(skip)]
    vertex_part: Vec<u32>,
}

const NO_PART: u32 = u32::MAX;

impl ValidationReport {
    pub(super) fn new(s: &ImportedSurface) -> Self {
        let mut vertex_part = vec![NO_PART; s.mesh.vertices.len()];
        for (t, tri) in s.mesh.triangles.iter().enumerate() {
            let p = s.triangle_part.get(t).copied().unwrap_or(NO_PART);
            for &i in tri {
                if let Some(slot) = vertex_part.get_mut(i as usize)
                    && *slot == NO_PART
                {
                    *slot = p;
                }
            }
        }
        ValidationReport {
            surface: s.name.clone(),
            file: s.source.file.clone(),
            part_names: s.parts.iter().map(|p| p.name.clone()).collect(),
            findings: Vec::new(),
            vertex_part,
        }
    }

    fn part_of_vertex(&self, v: u32) -> Option<u32> {
        self.vertex_part
            .get(v as usize)
            .copied()
            .filter(|&p| p != NO_PART)
    }

    pub(super) fn push_vertices(&mut self, s: &ImportedSurface, kind: FindingKind, vs: &[u32]) {
        let part = vs.iter().find_map(|&v| self.part_of_vertex(v));
        self.findings.push(Finding {
            kind,
            part,
            vertices: vs.to_vec(),
            vertex_ids: vs.iter().filter_map(|&v| s.source.vertex_id(v)).collect(),
            triangles: Vec::new(),
            lines: vs.iter().map(|&v| s.source.vertex_line(v)).collect(),
            points: vs.iter().map(|&v| s.mesh.vertices[v as usize]).collect(),
        });
    }

    pub(super) fn push_triangles(&mut self, s: &ImportedSurface, kind: FindingKind, ts: &[u32]) {
        let vertices: Vec<u32> = ts
            .iter()
            .flat_map(|&t| s.mesh.triangles[t as usize])
            .collect();
        self.findings.push(Finding {
            kind,
            part: ts
                .first()
                .and_then(|&t| s.triangle_part.get(t as usize).copied()),
            vertex_ids: vertices
                .iter()
                .filter_map(|&v| s.source.vertex_id(v))
                .collect(),
            points: vertices
                .iter()
                .map(|&v| s.mesh.vertices[v as usize])
                .collect(),
            vertices,
            triangles: ts.to_vec(),
            lines: ts.iter().map(|&t| s.source.triangle_line(t)).collect(),
        });
    }

    pub(super) fn push_edge(
        &mut self,
        s: &ImportedSurface,
        kind: FindingKind,
        ends: [u32; 2],
        ts: &[u32],
    ) {
        self.findings.push(Finding {
            kind,
            part: ts
                .first()
                .and_then(|&t| s.triangle_part.get(t as usize).copied()),
            vertices: ends.to_vec(),
            vertex_ids: ends.iter().filter_map(|&v| s.source.vertex_id(v)).collect(),
            triangles: ts.to_vec(),
            lines: ts.iter().map(|&t| s.source.triangle_line(t)).collect(),
            points: ends.iter().map(|&v| s.mesh.vertices[v as usize]).collect(),
        });
    }

    pub(super) fn sort(&mut self) {
        self.findings.sort_by(|a, b| {
            (a.kind, &a.triangles, &a.vertices).cmp(&(b.kind, &b.triangles, &b.vertices))
        });
    }

    pub fn is_clean(&self) -> bool {
        self.findings.is_empty()
    }

    /// Number of findings of each kind (every kind present, zeros included).
    pub fn counts(&self) -> BTreeMap<String, u64> {
        let mut m: BTreeMap<String, u64> = FindingKind::ALL
            .iter()
            .map(|k| (k.name().to_string(), 0))
            .collect();
        for f in &self.findings {
            *m.entry(f.kind.name().to_string()).or_insert(0) += 1;
        }
        m
    }

    pub fn of_kind(&self, kind: FindingKind) -> impl Iterator<Item = &Finding> {
        self.findings.iter().filter(move |f| f.kind == kind)
    }

    /// Readable report: a summary line per kind and up to 10 findings of each kind.
    pub fn render_text(&self) -> String {
        let mut out = String::new();
        if self.is_clean() {
            let _ = writeln!(out, "surface '{}' ({}): clean", self.surface, self.file);
            return out;
        }
        let _ = writeln!(
            out,
            "surface '{}' ({}): {} findings",
            self.surface,
            self.file,
            self.findings.len()
        );
        for kind in FindingKind::ALL {
            let all: Vec<&Finding> = self.of_kind(kind).collect();
            if all.is_empty() {
                continue;
            }
            let _ = writeln!(out, "  {} x{}", kind.name().replace('_', " "), all.len());
            for f in all.iter().take(10) {
                let part = f
                    .part
                    .and_then(|p| self.part_names.get(p as usize))
                    .map_or("-", |s| s.as_str());
                let mut what = String::new();
                if !f.triangles.is_empty() {
                    let _ = write!(what, "triangles {:?} (lines {:?})", f.triangles, f.lines);
                } else {
                    let _ = write!(
                        what,
                        "vertices {:?} (ids {:?}, lines {:?})",
                        f.vertices, f.vertex_ids, f.lines
                    );
                }
                let pts: Vec<String> = f
                    .points
                    .iter()
                    .take(3)
                    .map(|p| format!("({:.3}, {:.3}, {:.3})", p[0], p[1], p[2]))
                    .collect();
                let more = if f.points.len() > 3 { " ..." } else { "" };
                let _ = writeln!(out, "    [{part}] {what} at {}{more}", pts.join(" "));
            }
            if all.len() > 10 {
                let _ = writeln!(
                    out,
                    "    ... and {} more (see the JSON report)",
                    all.len() - 10
                );
            }
        }
        out
    }

    pub fn to_json(&self) -> serde_json::Value {
        let mut v = serde_json::to_value(self).unwrap_or(serde_json::Value::Null);
        if let Some(o) = v.as_object_mut() {
            o.insert(
                "counts".into(),
                serde_json::to_value(self.counts()).unwrap_or_default(),
            );
            o.insert("clean".into(), serde_json::Value::Bool(self.is_clean()));
        }
        v
    }
}
