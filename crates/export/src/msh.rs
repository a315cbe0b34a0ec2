//! Gmsh msh 4.1 writer, ASCII and binary (little-endian, `size_t` = 8 bytes), per the Gmsh
//! reference manual's "MSH file format version 4.1".
//!
//! Layout decisions (chosen so that both Gmsh and meshio read the file and recover the groups):
//! one discrete volume entity per region (entity tag = physical tag = region index + 1) and one
//! discrete surface entity per surface group (tag = group index + 1), each with its bounding box
//! and one physical tag; `$PhysicalNames` names them all. Nodes are classified on the entity of
//! lowest dimension holding them, one block per entity (tags = node index + 1, so the numbering
//! is the mesh's whatever the blocks); elements go in one block per entity
//! (tets type 4 first, then triangles type 2), numbered consecutively from 1. The recipe's
//! surface kinds (horizon, fault, box, other) go in a `$GeorecipeSurfaceKinds` section, which
//! other readers skip as the format prescribes for unknown sections. The recipe's
//! attributes follow as `$ElementData` views over every element: "material" (the material id,
//! -1 where none, and -1 on triangles) and one per region property (NaN where undefined).

use super::{bbox_of, property_names, split_by};
use geom::mesh::{SurfaceKind, VolumeMesh};
use std::collections::BTreeMap;
use std::io::Write as _;

/// One value of a record: printed space-separated in ASCII, packed little-endian in binary.
enum F {
    /// `size_t` (8 bytes in binary).
    S(u64),
    /// `int` (4 bytes in binary).
    I(i32),
    /// `double`.
    D(f64),
}

struct Out {
    binary: bool,
    buf: Vec<u8>,
}

impl Out {
    fn text(&mut self, s: &str) {
        self.buf.extend_from_slice(s.as_bytes());
    }
    /// One record: a line in ASCII, raw values in binary.
    fn rec(&mut self, fields: &[F]) {
        if self.binary {
            for f in fields {
                match f {
                    F::S(v) => self.buf.extend_from_slice(&v.to_le_bytes()),
                    F::I(v) => self.buf.extend_from_slice(&v.to_le_bytes()),
                    F::D(v) => self.buf.extend_from_slice(&v.to_le_bytes()),
                }
            }
        } else {
            let mut first = true;
            for f in fields {
                if !first {
                    self.buf.push(b' ');
                }
                first = false;
                // Writing into a Vec<u8> cannot fail.
                let _ = match f {
                    F::S(v) => write!(self.buf, "{v}"),
                    F::I(v) => write!(self.buf, "{v}"),
                    F::D(v) => write!(self.buf, "{v}"),
                };
            }
            self.buf.push(b'\n');
        }
    }
    /// Ends a section whose body may be binary: binary bodies need a newline before `$End...`.
    fn end(&mut self, section: &str) {
        if self.binary {
            self.buf.push(b'\n');
        }
        self.text(&format!("$End{section}\n"));
    }
}

/// A name as Gmsh reads it between double quotes (no quote or line break inside).
fn quoted(name: &str) -> String {
    let clean: String = name
        .chars()
        .map(|c| {
            if c == '"' {
                '\''
            } else if c.is_control() {
                ' '
            } else {
                c
            }
        })
        .collect();
    format!("\"{clean}\"")
}

/// The kind's name in `$GeorecipeSurfaceKinds` (as serde spells it).
pub(crate) fn kind_name(k: SurfaceKind) -> &'static str {
    match k {
        SurfaceKind::Horizon => "horizon",
        SurfaceKind::Fault => "fault",
        SurfaceKind::Box => "box",
        SurfaceKind::Other => "other",
    }
}

fn tag(i: usize) -> i32 {
    i32::try_from(i + 1).unwrap_or(i32::MAX)
}

pub(super) fn write(mesh: &VolumeMesh, binary: bool) -> Vec<u8> {
    let mut o = Out {
        binary,
        buf: Vec::new(),
    };
    mesh_format(&mut o);
    physical_names(&mut o, mesh);
    surface_kinds(&mut o, mesh);
    let tris_by_group = split_by(&mesh.triangle_group, mesh.surface_groups.len());
    let tets_by_region = split_by(&mesh.tet_region, mesh.regions.len());
    entities(&mut o, mesh, &tris_by_group, &tets_by_region);
    nodes(&mut o, mesh);
    let total = elements(&mut o, mesh, &tris_by_group, &tets_by_region);
    // Attributes as element data, in element-tag order: the order the elements were written
    // in (tets by region, then triangles by group), so the tags are 1, 2, ... again.
    if total > 0 && !mesh.regions.is_empty() {
        let order = Order {
            tets: &tets_by_region,
            tris: &tris_by_group,
            total: total as usize,
        };
        attributes(&mut o, mesh, &order);
    }
    o.buf.shrink_to_fit();
    o.buf
}

/// `$MeshFormat`: version 4.1, ASCII or binary, 8-byte `size_t` (binary adds the endianness int).
fn mesh_format(o: &mut Out) {
    o.text("$MeshFormat\n");
    if o.binary {
        o.text("4.1 1 8\n");
        o.buf.extend_from_slice(&1i32.to_le_bytes());
        o.text("\n");
    } else {
        o.text("4.1 0 8\n");
    }
    o.text("$EndMeshFormat\n");
}

/// `$PhysicalNames` (always ASCII): surface groups as 2D physicals, then regions as 3D ones.
fn physical_names(o: &mut Out, mesh: &VolumeMesh) {
    o.text("$PhysicalNames\n");
    o.text(&format!(
        "{}\n",
        mesh.surface_groups.len() + mesh.regions.len()
    ));
    for (g, sg) in mesh.surface_groups.iter().enumerate() {
        o.text(&format!("2 {} {}\n", tag(g), quoted(&sg.name)));
    }
    for (r, rg) in mesh.regions.iter().enumerate() {
        o.text(&format!("3 {} {}\n", tag(r), quoted(&rg.name)));
    }
    o.text("$EndPhysicalNames\n");
}

/// `$GeorecipeSurfaceKinds`: what each 2D group is, geologically (a section Gmsh and meshio skip,
/// as the format allows; our reader uses it to restore the surface kinds).
fn surface_kinds(o: &mut Out, mesh: &VolumeMesh) {
    o.text(&format!(
        "$GeorecipeSurfaceKinds\n{}\n",
        mesh.surface_groups.len()
    ));
    for (g, sg) in mesh.surface_groups.iter().enumerate() {
        o.text(&format!("2 {} {}\n", tag(g), kind_name(sg.kind)));
    }
    o.text("$EndGeorecipeSurfaceKinds\n");
}

/// `$Entities`: one surface per group, then one volume per region, each with its bounding box
/// and its one physical tag.
fn entities(
    o: &mut Out,
    mesh: &VolumeMesh,
    tris_by_group: &[Vec<usize>],
    tets_by_region: &[Vec<usize>],
) {
    o.text("$Entities\n");
    o.rec(&[
        F::S(0),
        F::S(0),
        F::S(mesh.surface_groups.len() as u64),
        F::S(mesh.regions.len() as u64),
    ]);
    let entity = |o: &mut Out, i: usize, bb: [[f64; 3]; 2]| {
        let [lo, hi] = bb;
        o.rec(&[
            F::I(tag(i)),
            F::D(lo[0]),
            F::D(lo[1]),
            F::D(lo[2]),
            F::D(hi[0]),
            F::D(hi[1]),
            F::D(hi[2]),
            F::S(1),
            F::I(tag(i)),
            F::S(0),
        ]);
    };
    for (g, sel) in tris_by_group.iter().enumerate() {
        entity(
            o,
            g,
            bbox_of(mesh, sel.iter().map(|&t| &mesh.triangles[t][..])),
        );
    }
    for (r, sel) in tets_by_region.iter().enumerate() {
        entity(o, r, bbox_of(mesh, sel.iter().map(|&t| &mesh.tets[t][..])));
    }
    o.end("Entities");
}

/// The entity each node is classified on, as (dimension, index) → its nodes in index order: the
/// entity of lowest dimension that holds it (the first surface group among its triangles, else
/// the region of its first tet; unused nodes on the first entity).
fn node_blocks(mesh: &VolumeMesh) -> BTreeMap<(i32, usize), Vec<usize>> {
    let n = mesh.nodes.len();
    let mut home: Vec<Option<(i32, usize)>> = vec![None; n];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let g = mesh.triangle_group[t] as usize;
        for &v in tri {
            let h = &mut home[v as usize];
            if h.is_none_or(|(d, k)| d == 2 && g < k) {
                *h = Some((2, g));
            }
        }
    }
    for (t, tet) in mesh.tets.iter().enumerate() {
        let r = mesh.tet_region[t] as usize;
        for &v in tet {
            let h = &mut home[v as usize];
            if h.is_none() {
                *h = Some((3, r));
            }
        }
    }
    let fallback = if !mesh.regions.is_empty() {
        Some((3, 0))
    } else if !mesh.surface_groups.is_empty() {
        Some((2, 0))
    } else {
        None
    };
    let mut blocks: BTreeMap<(i32, usize), Vec<usize>> = Default::default();
    for (v, h) in home.iter().enumerate() {
        if let Some(key) = h.or(fallback) {
            blocks.entry(key).or_default().push(v);
        }
    }
    blocks
}

/// `$Nodes`: one block per entity, surfaces then volumes. Tags stay node index + 1 (sparse per
/// block).
fn nodes(o: &mut Out, mesh: &VolumeMesh) {
    let blocks = node_blocks(mesh);
    let written: usize = blocks.values().map(Vec::len).sum();
    o.text("$Nodes\n");
    let (lo, hi) = (
        blocks.values().flatten().min(),
        blocks.values().flatten().max(),
    );
    o.rec(&[
        F::S(blocks.len() as u64),
        F::S(written as u64),
        F::S(lo.map_or(0, |&v| v as u64 + 1)),
        F::S(hi.map_or(0, |&v| v as u64 + 1)),
    ]);
    for (&(dim, k), vs) in &blocks {
        o.rec(&[F::I(dim), F::I(tag(k)), F::I(0), F::S(vs.len() as u64)]);
        for &v in vs {
            o.rec(&[F::S(v as u64 + 1)]);
        }
        for &v in vs {
            let p = mesh.nodes[v];
            o.rec(&[F::D(p[0]), F::D(p[1]), F::D(p[2])]);
        }
    }
    o.end("Nodes");
}

/// `$Elements`: tets per region, then triangles per group; tags 1.. in that order. Returns the
/// number of elements.
fn elements(
    o: &mut Out,
    mesh: &VolumeMesh,
    tris_by_group: &[Vec<usize>],
    tets_by_region: &[Vec<usize>],
) -> u64 {
    let blocks = tets_by_region.iter().filter(|s| !s.is_empty()).count()
        + tris_by_group.iter().filter(|s| !s.is_empty()).count();
    let total = (mesh.tets.len() + mesh.triangles.len()) as u64;
    o.text("$Elements\n");
    o.rec(&[
        F::S(blocks as u64),
        F::S(total),
        F::S(if total > 0 { 1 } else { 0 }),
        F::S(total),
    ]);
    let mut next = 1u64;
    for (r, sel) in tets_by_region
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.is_empty())
    {
        o.rec(&[F::I(3), F::I(tag(r)), F::I(4), F::S(sel.len() as u64)]);
        for &t in sel {
            let [a, b, c, d] = mesh.tets[t];
            o.rec(&[
                F::S(next),
                F::S(a as u64 + 1),
                F::S(b as u64 + 1),
                F::S(c as u64 + 1),
                F::S(d as u64 + 1),
            ]);
            next += 1;
        }
    }
    for (g, sel) in tris_by_group
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.is_empty())
    {
        o.rec(&[F::I(2), F::I(tag(g)), F::I(2), F::S(sel.len() as u64)]);
        for &t in sel {
            let [a, b, c] = mesh.triangles[t];
            o.rec(&[
                F::S(next),
                F::S(a as u64 + 1),
                F::S(b as u64 + 1),
                F::S(c as u64 + 1),
            ]);
            next += 1;
        }
    }
    o.end("Elements");
    total
}

/// `$ElementData` views: "material" (-1 where none and on triangles), then one per region
/// property (NaN where undefined).
fn attributes(o: &mut Out, mesh: &VolumeMesh, order: &Order) {
    let region_of = |t: usize| &mesh.regions[mesh.tet_region[t] as usize];
    let material = |t: Option<usize>| {
        t.and_then(|t| region_of(t).material)
            .map_or(-1.0, |m| m as f64)
    };
    element_data(o, "material", order, material);
    for name in property_names(mesh) {
        let value = |t: Option<usize>| {
            t.and_then(|t| region_of(t).properties.get(&name).copied())
                .unwrap_or(f64::NAN)
        };
        element_data(o, &name, order, value);
    }
}

/// The elements in tag order: `Some(tet)` for each tet by region, then `None` per triangle.
struct Order<'a> {
    tets: &'a [Vec<usize>],
    tris: &'a [Vec<usize>],
    total: usize,
}

impl Order<'_> {
    fn iter(&self) -> impl Iterator<Item = Option<usize>> + '_ {
        let tets = self.tets.iter().flatten().map(|&t| Some(t));
        tets.chain(self.tris.iter().flatten().map(|_| None))
    }
}

fn element_data(o: &mut Out, name: &str, order: &Order, value: impl Fn(Option<usize>) -> f64) {
    o.text("$ElementData\n");
    o.text(&format!(
        "1\n{}\n1\n0\n3\n0\n1\n{}\n",
        quoted(name),
        order.total
    ));
    for (k, t) in (1u64..).zip(order.iter()) {
        if o.binary {
            o.rec(&[F::I(i32::try_from(k).unwrap_or(i32::MAX)), F::D(value(t))]);
        } else {
            o.rec(&[F::S(k), F::D(value(t))]);
        }
    }
    o.end("ElementData");
}
