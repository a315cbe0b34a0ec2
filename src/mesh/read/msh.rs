//! Gmsh msh reader: format 4.1 (ASCII and binary, little-endian, `size_t` = 8) and 2.2 (ASCII),
//! per the Gmsh reference manual. Reads `$MeshFormat`, `$PhysicalNames`, `$Entities`, `$Nodes`,
//! `$Elements` and scalar `$ElementData`; skips other sections. Node tags may be sparse; vertices
//! are returned in node-tag order.
//!
//! [`read_msh`] returns the triangles (type 2) as a [`BoundaryMesh`] tagged by their elementary
//! entity, each entity named after its first 2D physical group. [`read_volume_msh`] reads a whole
//! tet mesh back into a [`VolumeMesh`] (3D physical groups become regions, 2D ones surface
//! groups, the "material" element data and other scalar element data become region attributes),
//! which is how exports are round-trip tested.

use super::cursor::Cursor;
use super::{BoundaryMesh, ReadError};
use crate::mesh::{RegionGroup, SurfaceGroup, SurfaceKind, VolumeMesh};
use std::collections::BTreeMap;

struct Elem {
    tag: u64,
    dim: i32,
    entity: i32,
    /// Physical tag carried by the element itself (format 2.2).
    phys: Option<i32>,
    nodes: [u64; 4],
    n: usize,
    at: usize,
}

#[derive(Default)]
struct Msh {
    names: BTreeMap<(i32, i32), String>,
    entity_phys: BTreeMap<(i32, i32), Vec<i32>>,
    node_tags: Vec<u64>,
    nodes: Vec<[f64; 3]>,
    elems: Vec<Elem>,
    data: BTreeMap<String, BTreeMap<u64, f64>>,
    /// Surface kinds by 2D physical tag (our own `$GeorecipeSurfaceKinds` section).
    kinds: BTreeMap<i32, SurfaceKind>,
}

/// Nodes per element type, for the types a file may hold.
fn nodes_per_type(t: i32) -> Option<usize> {
    Some(match t {
        15 => 1,
        1 => 2,
        2 | 8 => 3,
        3 | 4 => 4,
        7 => 5,
        6 | 9 => 6,
        5 | 16 => 8,
        10 | 20 => 9,
        11 | 21 => 10,
        18 => 15,
        13 => 18,
        17 => 20,
        12 => 27,
        14 => 14,
        19 => 13,
        _ => return None,
    })
}

/// Reads numbers as text tokens or as little-endian binary, so one parser serves both encodings.
struct Rd<'a> {
    c: Cursor<'a>,
    binary: bool,
}

impl Rd<'_> {
    fn size(&mut self, what: &str) -> Result<u64, ReadError> {
        if self.binary {
            self.c.bin_u64(what)
        } else {
            self.c.u64(what)
        }
    }
    fn int(&mut self, what: &str) -> Result<i32, ReadError> {
        if self.binary {
            self.c.bin_i32(what)
        } else {
            let at = self.mark();
            let v = self.c.i64(what)?;
            i32::try_from(v).map_err(|_| self.c.err_at(at, format!("{what} {v} is out of range")))
        }
    }
    fn dbl(&mut self, what: &str) -> Result<f64, ReadError> {
        if self.binary {
            self.c.bin_f64(what)
        } else {
            self.c.f64(what)
        }
    }
    /// A count used to size a loop: refuse counts the remaining bytes cannot hold.
    /// The offset of the next value (after whitespace in text mode), for error lines.
    fn mark(&mut self) -> usize {
        if !self.binary {
            self.c.skip_ws();
        }
        self.c.pos
    }
    fn count(&mut self, what: &str) -> Result<usize, ReadError> {
        let at = self.mark();
        let n = self.size(what)?;
        let left = (self.c.b.len() - self.c.pos.min(self.c.b.len())) as u64;
        if n > left {
            return Err(self.c.err_at(
                at,
                format!("{what} {n} exceeds what the rest of the file can hold"),
            ));
        }
        Ok(n as usize)
    }
    fn expect_end(&mut self, section: &str) -> Result<(), ReadError> {
        let want = format!("$End{section}");
        let (t, at) = self.c.tok(&want)?;
        if t != want {
            return Err(self.c.err_at(
                at,
                format!(
                    "expected {want}, found '{}'",
                    t.chars().take(40).collect::<String>()
                ),
            ));
        }
        Ok(())
    }
}

fn parse(bytes: &[u8], label: &str) -> Result<Msh, ReadError> {
    let mut r = Rd {
        c: Cursor::new(bytes, label),
        binary: false,
    };
    let mut m = Msh::default();
    let mut version: Option<u32> = None; // 41 or 22
    loop {
        r.c.skip_ws();
        if r.c.at_end() {
            break;
        }
        let (t, at) = r.c.tok("a section")?;
        let Some(section) = t.strip_prefix('$') else {
            return Err(r.c.err_at(
                at,
                format!(
                    "expected a section header like $Nodes, found '{}'",
                    t.chars().take(40).collect::<String>()
                ),
            ));
        };
        match (section, version) {
            ("MeshFormat", _) => {
                let (v, vat) = r.c.tok("the format version")?;
                let ver = match v {
                    "4.1" => 41,
                    "2.2" | "2.1" | "2.0" | "2" => 22,
                    _ => {
                        return Err(r.c.err_at(
                            vat,
                            format!("msh format version {v} is not supported (4.1 and 2.2 are)"),
                        ));
                    }
                };
                let ft = r.c.u64("the file type")?;
                let ds = r.c.u64("the data size")?;
                if ft == 1 {
                    if ver != 41 {
                        return Err(r
                            .c
                            .err_at(vat, "binary msh is supported for format 4.1 only"));
                    }
                    if ds != 8 {
                        return Err(r.c.err_at(
                            vat,
                            format!("binary msh with data size {ds} is not supported (8 is)"),
                        ));
                    }
                    r.c.skip_line_break();
                    let one = r.c.bin_i32("the endianness marker")?;
                    if one != 1 {
                        return Err(r.c.err("big-endian binary msh is not supported"));
                    }
                    r.binary = true;
                }
                version = Some(ver);
                r.expect_end("MeshFormat")?;
            }
            (_, None) => {
                return Err(r
                    .c
                    .err_at(at, format!("section ${section} before $MeshFormat")));
            }
            ("PhysicalNames", _) => {
                let n = r.c.u64("the number of physical names")?;
                for _ in 0..n {
                    let dim = r.c.i64("a physical dimension")? as i32;
                    let tag = r.c.i64("a physical tag")? as i32;
                    let (line, lat) =
                        r.c.line()
                            .ok_or_else(|| r.c.err("unexpected end of file in $PhysicalNames"))?;
                    let name = String::from_utf8_lossy(line)
                        .trim()
                        .trim_matches('"')
                        .to_string();
                    if name.is_empty() {
                        return Err(r.c.err_at(lat, "physical name missing"));
                    }
                    m.names.insert((dim, tag), name);
                }
                r.expect_end("PhysicalNames")?;
            }
            ("GeorecipeSurfaceKinds", _) => {
                let n = r.c.u64("the number of surface kinds")?;
                for _ in 0..n {
                    let dim = r.c.i64("a dimension")?;
                    let tag = r.c.i64("a physical tag")?;
                    let (k, kat) = r.c.tok("a surface kind")?;
                    let kind = match k {
                        "horizon" => SurfaceKind::Horizon,
                        "fault" => SurfaceKind::Fault,
                        "box" => SurfaceKind::Box,
                        "other" => SurfaceKind::Other,
                        _ => return Err(r.c.err_at(kat, format!("unknown surface kind '{k}'"))),
                    };
                    if dim == 2 {
                        m.kinds.insert(tag as i32, kind);
                    }
                }
                r.expect_end("GeorecipeSurfaceKinds")?;
            }
            ("Entities", Some(41)) => {
                if r.binary {
                    r.c.skip_line_break();
                }
                let counts = [
                    r.count("points")?,
                    r.count("curves")?,
                    r.count("surfaces")?,
                    r.count("volumes")?,
                ];
                for (dim, &n) in counts.iter().enumerate() {
                    for _ in 0..n {
                        let tag = r.int("an entity tag")?;
                        for _ in 0..(if dim == 0 { 3 } else { 6 }) {
                            r.dbl("an entity bounding box")?;
                        }
                        let np = r.count("the number of physical tags")?;
                        let mut phys = Vec::with_capacity(np.min(64));
                        for _ in 0..np {
                            phys.push(r.int("a physical tag")?);
                        }
                        m.entity_phys.insert((dim as i32, tag), phys);
                        if dim > 0 {
                            let nb = r.count("the number of bounding entities")?;
                            for _ in 0..nb {
                                r.int("a bounding entity")?;
                            }
                        }
                    }
                }
                r.expect_end("Entities")?;
            }
            ("Nodes", Some(ver)) => {
                if r.binary {
                    r.c.skip_line_break();
                }
                if ver == 41 {
                    let blocks = r.count("the number of node blocks")?;
                    let _total = r.size("the number of nodes")?;
                    r.size("the minimum node tag")?;
                    r.size("the maximum node tag")?;
                    for _ in 0..blocks {
                        let dim = r.int("an entity dimension")?;
                        r.int("an entity tag")?;
                        let param = r.int("the parametric flag")?;
                        let n = r.count("the number of nodes in a block")?;
                        let first = m.node_tags.len();
                        for _ in 0..n {
                            m.node_tags.push(r.size("a node tag")?);
                        }
                        let extra = if param != 0 {
                            dim.clamp(0, 3) as usize
                        } else {
                            0
                        };
                        for _ in first..first + n {
                            let p = [r.dbl("x")?, r.dbl("y")?, r.dbl("z")?];
                            for _ in 0..extra {
                                r.dbl("a parametric coordinate")?;
                            }
                            m.nodes.push(p);
                        }
                    }
                } else {
                    let n = r.count("the number of nodes")?;
                    for _ in 0..n {
                        m.node_tags.push(r.size("a node tag")?);
                        m.nodes.push([r.dbl("x")?, r.dbl("y")?, r.dbl("z")?]);
                    }
                }
                r.expect_end("Nodes")?;
            }
            ("Elements", Some(ver)) => {
                if r.binary {
                    r.c.skip_line_break();
                }
                if ver == 41 {
                    let blocks = r.count("the number of element blocks")?;
                    for _ in 0..3 {
                        r.size("the element counts")?;
                    }
                    for _ in 0..blocks {
                        let dim = r.int("an entity dimension")?;
                        let entity = r.int("an entity tag")?;
                        let bat = r.mark();
                        let ty = r.int("an element type")?;
                        let nn = nodes_per_type(ty).ok_or_else(|| {
                            r.c.err_at(bat, format!("element type {ty} is not supported"))
                        })?;
                        let n = r.count("the number of elements in a block")?;
                        for _ in 0..n {
                            let at = r.mark();
                            let tag = r.size("an element tag")?;
                            let mut e = Elem {
                                tag,
                                dim,
                                entity,
                                phys: None,
                                nodes: [0; 4],
                                n: 0,
                                at,
                            };
                            for k in 0..nn {
                                let v = r.size("a node tag")?;
                                if (ty == 2 || ty == 4) && k < 4 {
                                    e.nodes[k] = v;
                                    e.n = k + 1;
                                }
                            }
                            if ty == 2 || ty == 4 {
                                m.elems.push(e);
                            }
                        }
                    }
                } else {
                    let n = r.count("the number of elements")?;
                    for _ in 0..n {
                        let at = r.mark();
                        let tag = r.size("an element tag")?;
                        let tat = r.mark();
                        let ty = r.int("an element type")?;
                        let nn = nodes_per_type(ty).ok_or_else(|| {
                            r.c.err_at(tat, format!("element type {ty} is not supported"))
                        })?;
                        let nt = r.count("the number of element tags")?;
                        let mut tags = Vec::with_capacity(nt.min(8));
                        for _ in 0..nt {
                            tags.push(r.int("an element tag")?);
                        }
                        let dim = match ty {
                            15 => 0,
                            1 | 8 => 1,
                            2 | 3 | 9 | 10 | 16 => 2,
                            _ => 3,
                        };
                        let entity = tags.get(1).or(tags.first()).copied().unwrap_or(0);
                        let mut e = Elem {
                            tag,
                            dim,
                            entity,
                            phys: tags.first().copied(),
                            nodes: [0; 4],
                            n: 0,
                            at,
                        };
                        for k in 0..nn {
                            let v = r.size("a node tag")?;
                            if k < 4 {
                                e.nodes[k] = v;
                            }
                        }
                        e.n = nn.min(4);
                        if ty == 2 || ty == 4 {
                            m.elems.push(e);
                        }
                    }
                }
                r.expect_end("Elements")?;
            }
            ("ElementData", _) => {
                let ns = r.c.u64("the number of string tags")?;
                let mut name = String::new();
                for i in 0..ns {
                    let (line, _) =
                        r.c.line()
                            .ok_or_else(|| r.c.err("unexpected end of file in $ElementData"))?;
                    let mut s = String::from_utf8_lossy(line).trim().to_string();
                    if s.is_empty() {
                        // The rest of the count line: the tag is on the next one.
                        let (l2, _) =
                            r.c.line()
                                .ok_or_else(|| r.c.err("unexpected end of file in $ElementData"))?;
                        s = String::from_utf8_lossy(l2).trim().to_string();
                    }
                    if i == 0 {
                        name = s.trim_matches('"').to_string();
                    }
                }
                let nr = r.c.u64("the number of real tags")?;
                for _ in 0..nr {
                    r.c.tok("a real tag")?;
                }
                let ni = r.c.u64("the number of integer tags")?;
                let mut ints = Vec::new();
                for _ in 0..ni {
                    ints.push(r.c.i64("an integer tag")?);
                }
                let comps = ints.get(1).copied().unwrap_or(1);
                let n = ints.get(2).copied().unwrap_or(0).max(0) as u64;
                if r.binary {
                    r.c.skip_line_break();
                }
                let mut vals = BTreeMap::new();
                for _ in 0..n {
                    let tag = if r.binary {
                        r.int("an element tag")?.max(0) as u64
                    } else {
                        r.size("an element tag")?
                    };
                    let mut first = f64::NAN;
                    for k in 0..comps.max(1) {
                        // NaN marks "undefined" in our own files: accept it here.
                        let v = if r.binary {
                            let s = r.c.bytes(8, "a value")?;
                            let mut a = [0u8; 8];
                            a.copy_from_slice(s);
                            f64::from_le_bytes(a)
                        } else {
                            let (t, tat) = r.c.tok("a value")?;
                            t.parse::<f64>().map_err(|_| {
                                r.c.err_at(tat, format!("expected a value, found '{t}'"))
                            })?
                        };
                        if k == 0 {
                            first = v;
                        }
                    }
                    vals.insert(tag, first);
                }
                if comps == 1 {
                    m.data.insert(name, vals);
                }
                r.expect_end("ElementData")?;
            }
            (other, _) => {
                let want = format!("$End{other}");
                let rest = &r.c.b[r.c.pos..];
                let Some(k) = rest.windows(want.len()).position(|w| w == want.as_bytes()) else {
                    return Err(r.c.err_at(at, format!("section ${other} has no {want}")));
                };
                r.c.pos += k + want.len();
            }
        }
    }
    if version.is_none() {
        return Err(r.c.err_at(0, "no $MeshFormat section: not a Gmsh msh file"));
    }
    // Vertices in node-tag order (files list nodes per entity block; the tags are the numbering).
    if m.node_tags.windows(2).any(|w| w[0] > w[1]) {
        let mut order: Vec<usize> = (0..m.node_tags.len()).collect();
        order.sort_by_key(|&i| m.node_tags[i]);
        m.node_tags = order.iter().map(|&i| m.node_tags[i]).collect();
        m.nodes = order.iter().map(|&i| m.nodes[i]).collect();
    }
    Ok(m)
}

/// Maps node tags to indices and checks every element's nodes.
fn resolve(m: &Msh, c: &Cursor) -> Result<Vec<[u32; 4]>, ReadError> {
    // Dense lookup when the tags are not too sparse (the usual 1..n), a map otherwise.
    let max = m.node_tags.iter().copied().max().unwrap_or(0);
    let dense = max <= 2 * m.node_tags.len() as u64 + 1024;
    let mut table: Vec<u32> = Vec::new();
    let mut map: BTreeMap<u64, u32> = BTreeMap::new();
    if dense {
        table = vec![u32::MAX; max as usize + 1];
    }
    for (i, &t) in m.node_tags.iter().enumerate() {
        let old = if dense {
            std::mem::replace(&mut table[t as usize], i as u32) != u32::MAX
        } else {
            map.insert(t, i as u32).is_some()
        };
        if old {
            return Err(c.err(format!("node tag {t} is defined twice")));
        }
    }
    let lookup = |t: u64| -> Option<u32> {
        if dense {
            table
                .get(usize::try_from(t).ok()?)
                .copied()
                .filter(|&i| i != u32::MAX)
        } else {
            map.get(&t).copied()
        }
    };
    m.elems
        .iter()
        .map(|e| {
            let mut out = [0u32; 4];
            for (k, slot) in out.iter_mut().enumerate().take(e.n) {
                *slot = lookup(e.nodes[k]).ok_or_else(|| {
                    c.err_at(
                        e.at,
                        format!(
                            "element {} refers to node {}, which is not defined",
                            e.tag, e.nodes[k]
                        ),
                    )
                })?;
            }
            Ok(out)
        })
        .collect()
}

/// The physical group of an element of dimension `dim`, if any.
fn phys_of(m: &Msh, e: &Elem) -> Option<i32> {
    e.phys.filter(|&p| p != 0).or_else(|| {
        m.entity_phys
            .get(&(e.dim, e.entity))
            .and_then(|v| v.first().copied())
    })
}

/// Reads the triangles of a Gmsh msh file (4.1 ASCII/binary, 2.2 ASCII).
pub fn read_msh(bytes: &[u8], label: &str) -> Result<BoundaryMesh, ReadError> {
    let m = parse(bytes, label)?;
    let c = Cursor::new(bytes, label);
    let idx = resolve(&m, &c)?;
    let mut out = BoundaryMesh {
        vertices: m.nodes.clone(),
        ..Default::default()
    };
    for (e, ix) in m.elems.iter().zip(&idx) {
        if e.n != 3 {
            continue;
        }
        out.triangles.push([ix[0], ix[1], ix[2]]);
        out.triangle_tag.push(e.entity);
        if let Some(name) = phys_of(&m, e).and_then(|p| m.names.get(&(2, p))) {
            out.tag_names
                .entry(e.entity)
                .or_insert_with(|| name.clone());
        }
    }
    if out.triangles.is_empty() {
        return Err(c.err_at(bytes.len(), "the file holds no triangles (element type 2)"));
    }
    Ok(out)
}

/// Reads a tet mesh (tets type 4, triangles type 2) back into a [`VolumeMesh`]: regions are the 3D
/// physical groups in tag order (an element without one goes to a group named after its entity),
/// surface groups the 2D ones (kinds from our `$GeorecipeSurfaceKinds` section, else `Other`). Region attributes come from
/// scalar `$ElementData`: "material" (negative or NaN = none) and every other view as a property,
/// taken from the region's first tet that has a finite value.
pub fn read_volume_msh(bytes: &[u8], label: &str) -> Result<VolumeMesh, ReadError> {
    let m = parse(bytes, label)?;
    let c = Cursor::new(bytes, label);
    let idx = resolve(&m, &c)?;
    let mut out = VolumeMesh {
        nodes: m.nodes.clone(),
        ..Default::default()
    };
    // Group keys: Ok(physical tag) or Err(entity tag) when the element has no physical group.
    let key = |e: &Elem| phys_of(&m, e).ok_or(e.entity);
    let mut reg_keys: BTreeMap<Result<i32, i32>, u32> = BTreeMap::new();
    let mut grp_keys: BTreeMap<Result<i32, i32>, u32> = BTreeMap::new();
    for e in &m.elems {
        match e.n {
            4 => reg_keys.insert(key(e), 0),
            3 => grp_keys.insert(key(e), 0),
            _ => None,
        };
    }
    let name = |dim: i32, k: &Result<i32, i32>| match k {
        Ok(p) => m
            .names
            .get(&(dim, *p))
            .cloned()
            .unwrap_or_else(|| format!("physical_{p}")),
        Err(ent) => format!("entity_{ent}"),
    };
    for (i, (k, v)) in reg_keys.iter_mut().enumerate() {
        *v = i as u32;
        out.regions.push(RegionGroup {
            name: name(3, k),
            material: None,
            properties: BTreeMap::new(),
        });
    }
    for (i, (k, v)) in grp_keys.iter_mut().enumerate() {
        *v = i as u32;
        let kind = k
            .ok()
            .and_then(|p| m.kinds.get(&p).copied())
            .unwrap_or(SurfaceKind::Other);
        out.surface_groups.push(SurfaceGroup {
            name: name(2, k),
            kind,
        });
    }
    for (e, ix) in m.elems.iter().zip(&idx) {
        if e.n == 4 {
            let r = reg_keys[&key(e)];
            out.tets.push(*ix);
            out.tet_region.push(r);
            let region = &mut out.regions[r as usize];
            for (view, vals) in &m.data {
                let Some(&v) = vals.get(&e.tag) else { continue };
                if !v.is_finite() {
                    continue;
                }
                if view == "material" {
                    if region.material.is_none() && v >= 0.0 && v.fract() == 0.0 {
                        region.material = Some(v as i64);
                    }
                } else {
                    region.properties.entry(view.clone()).or_insert(v);
                }
            }
        } else if e.n == 3 {
            out.triangles.push([ix[0], ix[1], ix[2]]);
            out.triangle_group.push(grp_keys[&key(e)]);
        }
    }
    if out.tets.is_empty() {
        return Err(c.err_at(bytes.len(), "the file holds no tetrahedra (element type 4)"));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const V22: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 7 \"top face\"\n$EndPhysicalNames\n\
$Nodes\n4\n10 0 0 0\n20 1 0 0\n30 0 1 0\n40 0 0 1\n$EndNodes\n$Elements\n2\n1 2 2 7 3 10 20 30\n2 15 2 1 1 40\n$EndElements\n";

    #[test]
    fn a_version_2_2_file_gives_triangles_tagged_by_elementary_entity_with_physical_names() {
        let m = read_msh(V22.as_bytes(), "v22.msh").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
        assert_eq!(m.triangle_tag, vec![3]);
        assert_eq!(m.tag_names.get(&3).map(String::as_str), Some("top face"));
    }

    #[test]
    fn a_triangle_pointing_at_a_missing_node_names_the_line() {
        let bad = V22.replace("1 2 2 7 3 10 20 30", "1 2 2 7 3 10 20 99");
        let e = read_msh(bad.as_bytes(), "bad.msh").unwrap_err();
        assert_eq!(e.line, 17, "{e}");
        assert!(e.message.contains("node 99"), "{e}");
    }

    #[test]
    fn very_sparse_node_tags_are_looked_up_through_a_map() {
        let sparse = V22
            .replace("\n10 0 0 0", "\n1000000000000 0 0 0")
            .replace(" 10 20 30", " 1000000000000 20 30");
        let m = read_msh(sparse.as_bytes(), "s.msh").unwrap();
        // Vertices come in tag order: the huge tag is last.
        assert_eq!(m.triangles, vec![[3, 0, 1]]);
        assert_eq!(m.vertices[3], [0.0; 3]);
        let dup = V22.replace("\n20 1 0 0", "\n10 1 0 0");
        assert!(
            read_msh(dup.as_bytes(), "d.msh")
                .unwrap_err()
                .message
                .contains("node tag 10 is defined twice")
        );
    }

    #[test]
    fn a_truncated_file_is_an_error_not_a_panic() {
        for cut in [10, 40, 90, 130, 160, V22.len() - 14] {
            let e = read_msh(&V22.as_bytes()[..cut], "cut.msh");
            assert!(e.is_err(), "cut at {cut} was accepted");
        }
    }

    #[test]
    fn an_unsupported_version_is_named() {
        let e = read_msh(b"$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", "v3.msh").unwrap_err();
        assert_eq!(
            e.to_string(),
            "v3.msh:2: msh format version 3.0 is not supported (4.1 and 2.2 are)"
        );
    }
}
