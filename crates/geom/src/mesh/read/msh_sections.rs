//! Gmsh msh section parser: turns the bytes of a format 4.1 (ASCII or binary, little-endian,
//! `size_t` = 8) or 2.2 (ASCII) file into its raw parts — physical names, entity physical tags,
//! nodes by tag, lines, triangles and tets with their entity, scalar element data, and our own
//! surface kinds — checking every count against the bytes left so that no input can make it
//! allocate or loop without bound. Other element types are read past; unknown sections are skipped.

use super::ReadError;
use super::cursor::Cursor;
use crate::mesh::SurfaceKind;
use std::collections::BTreeMap;

/// A point, line, triangle or tet as read: its element tag, entity, nodes (by tag) and byte offset.
pub(super) struct Elem {
    pub tag: u64,
    pub dim: i32,
    pub entity: i32,
    /// Physical tag carried by the element itself (format 2.2).
    pub phys: Option<i32>,
    pub nodes: [u64; 4],
    pub n: usize,
    pub at: usize,
}

#[derive(Default)]
pub(super) struct Msh {
    pub names: BTreeMap<(i32, i32), String>,
    pub entity_phys: BTreeMap<(i32, i32), Vec<i32>>,
    pub node_tags: Vec<u64>,
    pub nodes: Vec<[f64; 3]>,
    pub elems: Vec<Elem>,
    pub data: BTreeMap<String, BTreeMap<u64, f64>>,
    /// Surface kinds by 2D physical tag (our own `$GeorecipeSurfaceKinds` section).
    pub kinds: BTreeMap<i32, SurfaceKind>,
    /// The 1D physical tags that section marks as the model's curves (where surfaces meet), not
    /// line groups.
    pub curves: std::collections::BTreeSet<i32>,
}

/// The element types kept: points (15), lines (1), triangles (2) and tets (4); the others are
/// read past.
fn kept(ty: i32) -> bool {
    matches!(ty, 15 | 1 | 2 | 4)
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
    /// The offset of the next value (after whitespace in text mode), for error lines.
    fn mark(&mut self) -> usize {
        if !self.binary {
            self.c.skip_ws();
        }
        self.c.pos
    }
    /// A count used to size a loop: refuse counts the remaining bytes cannot hold.
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

/// Parses a whole msh file: dispatches each section to its reader, then puts the nodes in
/// node-tag order.
pub(super) fn parse(bytes: &[u8], label: &str) -> Result<Msh, ReadError> {
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
            ("MeshFormat", _) => version = Some(mesh_format(&mut r)?),
            (_, None) => {
                return Err(r
                    .c
                    .err_at(at, format!("section ${section} before $MeshFormat")));
            }
            ("PhysicalNames", _) => physical_names(&mut r, &mut m)?,
            ("GeorecipeSurfaceKinds", _) => surface_kinds(&mut r, &mut m)?,
            ("Entities", Some(41)) => entities(&mut r, &mut m)?,
            ("Nodes", Some(ver)) => nodes(&mut r, &mut m, ver)?,
            ("Elements", Some(ver)) => elements(&mut r, &mut m, ver)?,
            ("ElementData", _) => element_data(&mut r, &mut m)?,
            (other, _) => skip_section(&mut r, other, at)?,
        }
    }
    if version.is_none() {
        return Err(r.c.err_at(0, "no $MeshFormat section: not a Gmsh msh file"));
    }
    sort_nodes_by_tag(&mut m);
    Ok(m)
}

/// `$MeshFormat`: which version (41 or 22) and whether the rest is binary (4.1, little-endian,
/// `size_t` = 8 only).
fn mesh_format(r: &mut Rd<'_>) -> Result<u32, ReadError> {
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
    r.expect_end("MeshFormat")?;
    Ok(ver)
}

/// `$PhysicalNames`: the name of each (dimension, physical tag); a name may not be empty.
fn physical_names(r: &mut Rd<'_>, m: &mut Msh) -> Result<(), ReadError> {
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
    r.expect_end("PhysicalNames")
}

/// `$GeorecipeSurfaceKinds`: the surface kind of each 2D physical tag, and which 1D ones are the
/// model's curves (`1 <tag> curve`); other dimensions are read past.
fn surface_kinds(r: &mut Rd<'_>, m: &mut Msh) -> Result<(), ReadError> {
    let n = r.c.u64("the number of surface kinds")?;
    for _ in 0..n {
        let dim = r.c.i64("a dimension")?;
        let tag = r.c.i64("a physical tag")?;
        let (k, kat) = r.c.tok("a surface kind")?;
        if (dim, k) == (1, "curve") {
            m.curves.insert(tag as i32);
            continue;
        }
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
    r.expect_end("GeorecipeSurfaceKinds")
}

/// `$Entities` (4.1): the physical tags of each (dimension, entity tag); bounding boxes and
/// bounding entities are read past.
fn entities(r: &mut Rd<'_>, m: &mut Msh) -> Result<(), ReadError> {
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
    r.expect_end("Entities")
}

/// `$Nodes`: node tags and coordinates in file order (4.1 entity blocks, parametric
/// coordinates read past, or the flat 2.2 list).
fn nodes(r: &mut Rd<'_>, m: &mut Msh, ver: u32) -> Result<(), ReadError> {
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
    r.expect_end("Nodes")
}

/// `$Elements`: keeps the triangles and tets, in file order, and reads past every other
/// supported element type.
fn elements(r: &mut Rd<'_>, m: &mut Msh, ver: u32) -> Result<(), ReadError> {
    if r.binary {
        r.c.skip_line_break();
    }
    if ver == 41 {
        elements_41(r, m)?;
    } else {
        elements_22(r, m)?;
    }
    r.expect_end("Elements")
}

/// `$Elements` body in 4.1: element blocks whose entity and type hold for all their elements.
fn elements_41(r: &mut Rd<'_>, m: &mut Msh) -> Result<(), ReadError> {
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
                if kept(ty) && k < 4 {
                    e.nodes[k] = v;
                    e.n = k + 1;
                }
            }
            if kept(ty) {
                m.elems.push(e);
            }
        }
    }
    Ok(())
}

/// `$Elements` body in 2.2: one flat list, each element with its own type and tags (physical
/// tag first, entity second).
fn elements_22(r: &mut Rd<'_>, m: &mut Msh) -> Result<(), ReadError> {
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
        if kept(ty) {
            m.elems.push(e);
        }
    }
    Ok(())
}

/// `$ElementData`: one value per element tag under the data's name, kept only for scalar data
/// (other component counts are read past).
fn element_data(r: &mut Rd<'_>, m: &mut Msh) -> Result<(), ReadError> {
    let (name, comps, n) = element_data_header(r)?;
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
            let v = element_value(r)?;
            if k == 0 {
                first = v;
            }
        }
        vals.insert(tag, first);
    }
    if comps == 1 {
        m.data.insert(name, vals);
    }
    r.expect_end("ElementData")
}

/// The `$ElementData` tags: the data's name (first string tag), its number of components
/// (second integer tag, default 1) and of values (third, default 0).
fn element_data_header(r: &mut Rd<'_>) -> Result<(String, i64, u64), ReadError> {
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
    Ok((name, comps, n))
}

/// One `$ElementData` value, NaN included.
fn element_value(r: &mut Rd<'_>) -> Result<f64, ReadError> {
    // NaN marks "undefined" in our own files: accept it here.
    Ok(if r.binary {
        let s = r.c.bytes(8, "a value")?;
        let mut a = [0u8; 8];
        a.copy_from_slice(s);
        f64::from_le_bytes(a)
    } else {
        let (t, tat) = r.c.tok("a value")?;
        t.parse::<f64>()
            .map_err(|_| r.c.err_at(tat, format!("expected a value, found '{t}'")))?
    })
}

/// An unknown section: skipped up to its `$End` line, which must exist.
fn skip_section(r: &mut Rd<'_>, other: &str, at: usize) -> Result<(), ReadError> {
    let want = format!("$End{other}");
    let rest = &r.c.b[r.c.pos..];
    let Some(k) = rest.windows(want.len()).position(|w| w == want.as_bytes()) else {
        return Err(r.c.err_at(at, format!("section ${other} has no {want}")));
    };
    r.c.pos += k + want.len();
    Ok(())
}

/// Vertices in node-tag order (files list nodes per entity block; the tags are the numbering).
fn sort_nodes_by_tag(m: &mut Msh) {
    if m.node_tags.windows(2).any(|w| w[0] > w[1]) {
        let mut order: Vec<usize> = (0..m.node_tags.len()).collect();
        order.sort_by_key(|&i| m.node_tags[i]);
        m.node_tags = order.iter().map(|&i| m.node_tags[i]).collect();
        m.nodes = order.iter().map(|&i| m.nodes[i]).collect();
    }
}
