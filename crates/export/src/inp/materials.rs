//! A `*Material` and a `*Solid Section` per region with tets, so the file runs in Abaqus or
//! CalculiX once the analyst adds the constitutive cards. Each region gets its own material,
//! named by its material id and its label (`M2_reservoir`; `MN7_` for id -7, `NOMAT_` for a
//! region without one), because properties are per region and two regions of one material id
//! may differ. A property named `density` becomes `*Density` (the one property keyword every
//! reader shares); every other property is listed in a `**` comment under the material, since
//! no standard keyword takes an arbitrary named constant (`*User Material` would demand a UMAT).
//! A well given a cross-section area gets a material `WELL_<elset>` and a `*Solid Section` whose
//! data line is that area (a truss element's section); a well without one gets none (its `**`
//! comment says to add one).

use super::labels::Labels;
use crate::numbering::Numbering;
use geom::mesh::VolumeMesh;
use std::fmt::Write as _;

/// Writes the materials and sections of the regions that have tets.
pub(super) fn put(s: &mut String, mesh: &VolumeMesh, labels: &Labels, numbering: &Numbering) {
    for (r, _) in &numbering.blocks {
        let region = &mesh.regions[*r];
        let elset = &labels.regions[*r];
        let name = material_name(region.material, elset);
        let _ = writeln!(s, "*Material, name={name}");
        if let Some(d) = region.properties.get("density") {
            let _ = writeln!(s, "*Density\n{d},");
        }
        for (p, v) in region.properties.iter().filter(|(p, _)| *p != "density") {
            let _ = writeln!(s, "** property {p} = {v}");
        }
        let _ = writeln!(s, "*Solid Section, elset={elset}, material={name}");
    }
    for &(w, _) in &numbering.wells {
        if let Some(area) = mesh.lines[w].area {
            let elset = &labels.wells[w];
            let _ = writeln!(
                s,
                "*Material, name=WELL_{elset}\n*Solid Section, elset={elset}, material=WELL_{elset}\n{area},"
            );
        }
    }
}

/// `M<id>_<elset>`, `MN<-id>_<elset>` for a negative id, `NOMAT_<elset>` without one.
fn material_name(material: Option<i64>, elset: &str) -> String {
    match material {
        Some(m) if m >= 0 => format!("M{m}_{elset}"),
        Some(m) => format!("MN{}_{elset}", m.unsigned_abs()),
        None => format!("NOMAT_{elset}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_material_is_named_by_its_id_and_region() {
        assert_eq!(material_name(Some(2), "res"), "M2_res");
        assert_eq!(material_name(Some(-7), "res"), "MN7_res");
        assert_eq!(material_name(None, "res"), "NOMAT_res");
    }
}
