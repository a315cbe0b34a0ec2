//! Abaqus names for the regions, the surface groups, the fault sides, the wells (line
//! groups) and the named points (labelled last, wells then points, so a mesh without them
//! keeps its labels): letters, digits and
//! `_`, starting with a letter, unique without regard to case (Abaqus folds names to upper
//! case), and the `**` comments that pair each with its original name.

use crate::exodus::sets::SideSet;
use geom::mesh::VolumeMesh;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

/// The labels of one file.
pub(super) struct Labels {
    /// Per region, its element set.
    pub(super) regions: Vec<String>,
    /// Per side set id, its surface (and, for a group, its node set).
    pub(super) sets: BTreeMap<usize, String>,
    /// Per line group, its element set.
    pub(super) wells: Vec<String>,
    /// Per named point, its node set.
    pub(super) points: Vec<String>,
}

impl Labels {
    pub(super) fn new(mesh: &VolumeMesh, side_sets: &[SideSet]) -> Labels {
        let mut taken = BTreeSet::new();
        let regions = (mesh.regions.iter().enumerate())
            .map(|(r, g)| label(&g.name, &format!("R{}", r + 1), &mut taken))
            .collect();
        let sets = (side_sets.iter())
            .map(|s| (s.id, label(&s.name, &format!("S{}", s.id), &mut taken)))
            .collect();
        let wells = (mesh.lines.iter().enumerate())
            .map(|(w, g)| label(&g.name, &format!("W{}", w + 1), &mut taken))
            .collect();
        let points = (mesh.points.iter().enumerate())
            .map(|(i, p)| label(&p.name, &format!("P{}", i + 1), &mut taken))
            .collect();
        Labels {
            regions,
            sets,
            wells,
            points,
        }
    }

    /// `**` lines naming every region (with its material) and every set by its original name.
    pub(super) fn comments(&self, s: &mut String, mesh: &VolumeMesh, side_sets: &[SideSet]) {
        for (r, g) in mesh.regions.iter().enumerate() {
            let mat = g.material.map_or("none".to_string(), |m| m.to_string());
            let label = &self.regions[r];
            let _ = writeln!(
                s,
                "** region {} \"{}\" elset={label} material={mat}",
                r + 1,
                g.name
            );
        }
        for set in side_sets {
            let label = &self.sets[&set.id];
            let _ = writeln!(s, "** set {} \"{}\" surface={label}", set.id, set.name);
        }
        for (w, g) in mesh.lines.iter().enumerate() {
            let section = match g.area {
                Some(a) => format!("T3D2, section area {a}"),
                None => "T3D2 without a section: give the well an `area` in the recipe, or \
                         add a section, to run it"
                    .to_string(),
            };
            let _ = writeln!(
                s,
                "** well {} \"{}\" elset={} ({section})",
                w + 1,
                g.name,
                self.wells[w]
            );
        }
        for (i, p) in mesh.points.iter().enumerate() {
            let label = &self.points[i];
            let _ = writeln!(s, "** point {} \"{}\" nset={label}", i + 1, p.name);
        }
    }
}

/// An Abaqus-safe label: letters, digits, `_`; starting with a letter; unique in `taken`.
pub(super) fn label(name: &str, fallback: &str, taken: &mut BTreeSet<String>) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if !s.chars().next().is_some_and(|c| c.is_ascii_alphabetic()) {
        s = format!("{fallback}_{s}");
    }
    let mut out = s.clone();
    let mut k = 2;
    while !taken.insert(out.to_ascii_uppercase()) {
        out = format!("{s}_{k}");
        k += 1;
    }
    out
}

/// Writes `items` comma-separated, at most 16 per line (the Abaqus data-line limit).
pub(super) fn list(s: &mut String, items: impl Iterator<Item = usize>) {
    let mut k = 0;
    for it in items {
        if k > 0 {
            s.push_str(if k % 16 == 0 { ",\n" } else { ", " });
        }
        let _ = write!(s, "{it}");
        k += 1;
    }
    if k > 0 {
        s.push('\n');
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_are_abaqus_safe_and_unique() {
        let mut taken = BTreeSet::new();
        assert_eq!(label("H1 top", "S1", &mut taken), "H1_top");
        assert_eq!(label("h1,top", "S2", &mut taken), "h1_top_2");
        assert_eq!(label("2nd", "R3", &mut taken), "R3_2nd");
        assert_eq!(label("F1:front", "S9", &mut taken), "F1_front");
    }
}
