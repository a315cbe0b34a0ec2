//! Gmsh msh 4.1 writer, ASCII and binary (little-endian, `size_t` = 8 bytes), per the Gmsh
//! reference manual's "MSH file format version 4.1".
//!
//! Layout decisions (chosen so that both Gmsh and meshio read the file and recover the groups):
//!
//! - **Entities** ([`topology`]). One point entity per named point (a well's crossing of a
//!   surface; tag = point index + 1, at its node's coordinates), bounding nothing, like the
//!   curves. One discrete curve per line group, when the caller gives line
//!   elements (an embedded well's chain of tet edges; tag = group index + 1), lying inside its
//!   volume like a dangling fault, so no volume lists it. One discrete volume per region (tag =
//!   region index + 1). A
//!   surface group becomes one discrete surface per *piece*: its triangles that have the same
//!   region in front and the same behind (the outside of the model counted as no region) and
//!   in the same face sets (the recipe's `[groups]`), in order of group, region in front, region
//!   behind (none first) and face sets, tags 1, 2, ... in that order; a group without triangles keeps one empty surface so that its groups exist. One
//!   surface per group could not bound a volume: a horizon between two regions here and two
//!   others there would be the whole horizon in each region's boundary.
//! - **Topology.** Each volume lists its bounding surfaces with the sign Gmsh's built-in kernel
//!   gives them: `+` where the surface's triangle normals point out of the region, `-` where they
//!   point into it, so `gmsh.model.getBoundary([(3, r + 1)])` returns the region's pieces. A
//!   piece with the same region on both sides (where a dangling fault ends inside a region) lies
//!   inside that volume, not on its boundary, and the format has no documented record for an
//!   embedded entity, so no volume lists it. Each surface lists the curves around it
//!   ([`curves`]: recovered from the pieces, where pieces meet or end), signed `+` where the
//!   curve runs the way the surface's triangles turn, and each curve its first and last point
//!   (the end negated, as Gmsh writes them), so `getBoundary` and `getAdjacencies` walk the
//!   model from regions down to points, and Gmsh meshes the model again from the file
//!   (`createGeometry`, then `generate`). The curves are discrete curves
//!   with their line elements (tags after the line groups'), their end points point entities
//!   without elements (tags after the named points').
//! - **Physical groups.** 0D: named point `i` has tag `i + 1`, named after the point, on its
//!   point entity (the tags of each dimension are their own, so volumes, surfaces and curves keep
//!   theirs whether or not the mesh has points). 1D: line group `g` has tag `g + 1`, named after
//!   the group, on its curve; the curves' groups follow in name order, each named after the
//!   surface groups meeting there (`F1/H1`, names sorted) or `<group>:border` where the pieces of
//!   one group end (a dangling fault's free edge), on every curve of that name. 2D: surface group `g` has tag `g + 1` on its pieces; fault `k` (in group
//!   order, empty ones counted) of `n` groups has `<fault>:front` = `n + 2k + 1` and
//!   `<fault>:back` = `n + 2k + 2`, the ids of the Exodus side sets; face set `j` of the
//!   recipe's `[groups]` has `n + 2F + j + 1` (`F` faults) on the pieces it holds, which may
//!   also hold other sets' tags. 3D: region `r` has tag
//!   `r + 1` on its volume, and each distinct material id, the `k`-th in ascending order of the
//!   `R` regions' ids, has `R + k + 1`, named `material:<id>`, on the volumes of the regions of
//!   that material. An entity lists its group's (region's) tag first, which is the one meshio
//!   takes for `gmsh:physical`. `$PhysicalNames` names them all, by dimension and tag.
//! - **Fault sides.** A side's triangles are the fault's own triangles: separate entities would
//!   hold each fault triangle twice, and a conforming mesh would then carry two coincident
//!   elements per fault face, which a solver reading the 2D elements as facets takes for two.
//!   So the side groups hold the fault's own pieces with an orientation, as Gmsh does itself: a
//!   physical group may take an entity reversed (a negative tag in `Physical Surface`, with the
//!   default `Geometry.OrientedPhysicals`), which Gmsh's msh 4.1 writer stores as the group's
//!   tag negated in the entity's physical tags, and reads back the same way. A side holds each
//!   piece with the sign the piece has in the boundary of the volume on that side:
//!   `<fault>:front` negated (seen from the front, the triangles are reversed: these are the
//!   faces of the front tets, outward, as in the Exodus and Abaqus front side sets),
//!   `<fault>:back` as is. `getEntitiesForPhysicalGroup` gives the pieces of either side,
//!   `getPhysicalGroupsForEntity` the signed tags, and Gmsh reverses the front's elements when it
//!   saves a format that stores elements per group (MSH2). meshio matches tags without sign: it
//!   reads `<fault>` and `<fault>:back` and leaves `<fault>:front` empty.
//!
//! Nodes are classified on the entity of lowest dimension holding them (the first named point at
//! them, else the curves' end point there, else the first line group among their lines, else
//! the first curve through them, else the first piece among their triangles, else the region of
//! their first tet), one block per entity (tags = node index + 1, so the numbering is the mesh's
//! whatever the blocks); elements go in one block per entity (tets type 4 by region first, then
//! triangles type 2 by piece, then lines type 1 by group, then by curve, then one point element
//! type 15 per named point, last so that the other elements keep their tags), numbered
//! consecutively from 1. The recipe's surface kinds (horizon, fault, box, other) and which 1D
//! groups are curves go in a `$GeorecipeSurfaceKinds` section, which other readers skip as the
//! format prescribes for unknown sections. The recipe's attributes follow as `$ElementData` views over every element:
//! "material" (the material id, -1 where none, and -1 on triangles, lines and points) and one per region
//! property (NaN where undefined).

mod curves;
mod topology;

use super::{bbox_of, property_names, split_by};
use curves::Curves;
use geom::mesh::{LineGroup, SurfaceKind, VolumeMesh};
use std::collections::BTreeMap;
use std::io::Write as _;
use topology::Topology;

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
                match f {
                    F::S(v) => decimal(&mut self.buf, *v, false),
                    F::I(v) => decimal(&mut self.buf, u64::from(v.unsigned_abs()), *v < 0),
                    // Writing into a Vec<u8> cannot fail.
                    F::D(v) => {
                        let _ = write!(self.buf, "{v}");
                    }
                }
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

/// Appends `v` in decimal (after a `-` when `negative`), as `{}` writes it: the element and node
/// records are most of a large file, and the formatting machinery cost more than the digits.
fn decimal(buf: &mut Vec<u8>, mut v: u64, negative: bool) {
    let mut digits = [0u8; 20];
    let mut at = digits.len();
    loop {
        at -= 1;
        digits[at] = b'0' + (v % 10) as u8;
        v /= 10;
        if v == 0 {
            break;
        }
    }
    if negative {
        buf.push(b'-');
    }
    buf.extend_from_slice(&digits[at..]);
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

/// `mesh` as a msh file, with the line elements of `lines` (one curve entity and one 1D
/// physical group per group, tags 1, 2, ... in order) and the mesh's named points (one point
/// entity, one point element and one 0D physical group each).
pub(super) fn write(mesh: &VolumeMesh, lines: &[LineGroup], binary: bool) -> Vec<u8> {
    let mut o = Out {
        binary,
        buf: Vec::new(),
    };
    let topology = Topology::new(mesh);
    let tris_by_piece = &topology.tris;
    let curves = curves::curves(mesh, tris_by_piece);
    let tets_by_region = split_by(&mesh.tet_region, mesh.regions.len());
    let model = Model {
        topology: &topology,
        curves: &curves,
        curve_groups: curve_groups(mesh, &curves, lines.len()),
        lines,
        points: mesh.points.len(),
    };
    mesh_format(&mut o);
    physical_names(&mut o, mesh, &model);
    surface_kinds(&mut o, mesh, &model);
    entities(&mut o, mesh, &model, &tets_by_region);
    nodes(&mut o, mesh, &model);
    let total = elements(&mut o, mesh, &model, &tets_by_region);
    // Attributes as element data, in element-tag order: the order the elements were written
    // in (tets by region, then triangles by piece, then lines by group and by curve, then
    // points), so the tags are 1, 2, ... again.
    if total > 0 && !mesh.regions.is_empty() {
        let segments: usize = curves.chains.iter().map(|c| c.len() - 1).sum();
        let order = Order {
            tets: &tets_by_region,
            tris: tris_by_piece,
            lines: lines.iter().map(|g| g.lines.len()).sum::<usize>()
                + mesh.points.len()
                + segments,
            total: total as usize,
        };
        attributes(&mut o, mesh, &order);
    }
    o.buf.shrink_to_fit();
    o.buf
}

/// The entities besides the regions: the surface pieces, the curves bounding them and the line
/// groups. Point entities are the named points, then the curves' corners; curve entities the
/// line groups, then the curves.
struct Model<'a> {
    topology: &'a Topology,
    curves: &'a Curves,
    /// The curves' 1D physical groups, (tag, name), and per curve its tag.
    curve_groups: (Vec<(i32, String)>, Vec<i32>),
    lines: &'a [LineGroup],
    /// How many named points come before the corners.
    points: usize,
}

/// The curves' 1D physical groups, tagged after the `wells` line groups' in name order, and per
/// curve its group's tag.
fn curve_groups(
    mesh: &VolumeMesh,
    curves: &Curves,
    wells: usize,
) -> (Vec<(i32, String)>, Vec<i32>) {
    let mut of_curve = vec![0; curves.chains.len()];
    let mut names = Vec::new();
    for (j, (name, cs)) in curves.named(mesh).into_iter().enumerate() {
        let t = tag(wells + j);
        for c in cs {
            of_curve[c] = t;
        }
        names.push((t, name));
    }
    (names, of_curve)
}

impl Model<'_> {
    /// The entity index (tag - 1) of curve `c`.
    fn curve(&self, c: usize) -> usize {
        self.lines.len() + c
    }
    /// The entity index (tag - 1) of corner `k`, after the named points.
    fn corner(&self, k: usize) -> usize {
        self.points + k
    }
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

/// `$PhysicalNames` (always ASCII): the 0D groups (named points), the 1D ones (line groups, then curves), the
/// 2D ones (surface groups, then fault sides, then face sets), then the 3D ones (regions, then
/// materials).
fn physical_names(o: &mut Out, mesh: &VolumeMesh, model: &Model) {
    let (topology, lines, curves) = (model.topology, model.lines, &model.curve_groups.0);
    o.text("$PhysicalNames\n");
    let n = mesh.points.len() + lines.len() + curves.len() + topology.names.len();
    o.text(&format!("{n}\n"));
    for (i, p) in mesh.points.iter().enumerate() {
        o.text(&format!("0 {} {}\n", tag(i), quoted(&p.name)));
    }
    for (g, group) in lines.iter().enumerate() {
        o.text(&format!("1 {} {}\n", tag(g), quoted(&group.name)));
    }
    for (t, name) in curves {
        o.text(&format!("1 {t} {}\n", quoted(name)));
    }
    for (dim, tag, name) in &topology.names {
        o.text(&format!("{dim} {tag} {}\n", quoted(name)));
    }
    o.text("$EndPhysicalNames\n");
}

/// `$GeorecipeSurfaceKinds`: what each 2D group is, geologically, then which 1D groups are the
/// model's curves, `curve` (a section Gmsh and meshio skip, as the format allows; our reader
/// uses it to restore the surface kinds and to tell the curves from line groups).
fn surface_kinds(o: &mut Out, mesh: &VolumeMesh, model: &Model) {
    let curves = &model.curve_groups.0;
    o.text(&format!(
        "$GeorecipeSurfaceKinds\n{}\n",
        mesh.surface_groups.len() + curves.len()
    ));
    for (g, sg) in mesh.surface_groups.iter().enumerate() {
        o.text(&format!("2 {} {}\n", tag(g), kind_name(sg.kind)));
    }
    for (t, _) in curves {
        o.text(&format!("1 {t} curve\n"));
    }
    o.text("$EndGeorecipeSurfaceKinds\n");
}

/// `$Entities`: one point per named point (its coordinates and 0D physical tag), one curve per
/// line group, the surface pieces, then one volume per region, each
/// with its bounding box, its physical tags and its bounding entities (none for the curves and
/// surfaces).
fn entities(o: &mut Out, mesh: &VolumeMesh, model: &Model, tets_by_region: &[Vec<usize>]) {
    let (topology, curves, lines) = (model.topology, model.curves, model.lines);
    o.text("$Entities\n");
    o.rec(&[
        F::S((mesh.points.len() + curves.corners.len()) as u64),
        F::S((lines.len() + curves.chains.len()) as u64),
        F::S(topology.tris.len() as u64),
        F::S(mesh.regions.len() as u64),
    ]);
    let entity = |o: &mut Out, i: usize, bb: [[f64; 3]; 2], physicals: &[i32], bounds: &[i32]| {
        let [lo, hi] = bb;
        let mut rec = vec![F::I(tag(i))];
        rec.extend(lo.into_iter().chain(hi).map(F::D));
        rec.push(F::S(physicals.len() as u64));
        rec.extend(physicals.iter().map(|&p| F::I(p)));
        rec.push(F::S(bounds.len() as u64));
        rec.extend(bounds.iter().map(|&b| F::I(b)));
        o.rec(&rec);
    };
    for (i, p) in mesh.points.iter().enumerate() {
        let mut rec = vec![F::I(tag(i))];
        rec.extend(mesh.nodes[p.node as usize].map(F::D));
        rec.extend([F::S(1), F::I(tag(i))]);
        o.rec(&rec);
    }
    for (k, &v) in curves.corners.iter().enumerate() {
        let mut rec = vec![F::I(tag(model.corner(k)))];
        rec.extend(mesh.nodes[v as usize].map(F::D));
        rec.push(F::S(0));
        o.rec(&rec);
    }
    for (g, group) in lines.iter().enumerate() {
        let bb = bbox_of(mesh, group.lines.iter().map(|l| &l[..]));
        entity(o, g, bb, &[tag(g)], &[]);
    }
    for (c, chain) in curves.chains.iter().enumerate() {
        let bb = bbox_of(mesh, std::iter::once(&chain[..]));
        let [a, b] = curves.ends[c].map(|k| tag(model.corner(k)));
        entity(o, model.curve(c), bb, &[model.curve_groups.1[c]], &[a, -b]);
    }
    for (k, tris) in topology.tris.iter().enumerate() {
        let bb = bbox_of(mesh, tris.iter().map(|&t| &mesh.triangles[t][..]));
        let bounds: Vec<i32> = (curves.bounds[k].iter())
            .map(|&(c, along)| {
                if along {
                    tag(model.curve(c))
                } else {
                    -tag(model.curve(c))
                }
            })
            .collect();
        entity(o, k, bb, &topology.surface_physicals[k], &bounds);
    }
    for (r, sel) in tets_by_region.iter().enumerate() {
        let bb = bbox_of(mesh, sel.iter().map(|&t| &mesh.tets[t][..]));
        let (physicals, bounds) = (&topology.volume_physicals[r], &topology.volume_bounds[r]);
        entity(o, r, bb, physicals, bounds);
    }
    o.end("Entities");
}

/// The entity each node is classified on, as (dimension, index) → its nodes in index order: the
/// entity of lowest dimension that holds it (the first named point at it, else the corner at
/// it, else the first line group among its lines, else the first curve through it, else the
/// first piece among its triangles, else the region of its first tet; unused nodes on the first
/// entity).
fn node_blocks(mesh: &VolumeMesh, model: &Model) -> BTreeMap<(i32, usize), Vec<usize>> {
    let (tris_by_piece, curves) = (&model.topology.tris, model.curves);
    let n = mesh.nodes.len();
    let mut home: Vec<Option<(i32, usize)>> = vec![None; n];
    let points = mesh.points.iter().map(|p| p.node);
    for (i, v) in points.chain(curves.corners.iter().copied()).enumerate() {
        let h = &mut home[v as usize];
        if h.is_none() {
            *h = Some((0, i));
        }
    }
    for (g, group) in model.lines.iter().enumerate() {
        for &v in group.lines.iter().flatten() {
            let h = &mut home[v as usize];
            if h.is_none() {
                *h = Some((1, g));
            }
        }
    }
    for (c, chain) in curves.chains.iter().enumerate() {
        for &v in chain {
            let h = &mut home[v as usize];
            if h.is_none() {
                *h = Some((1, model.curve(c)));
            }
        }
    }
    for (k, tris) in tris_by_piece.iter().enumerate() {
        for &t in tris {
            for &v in &mesh.triangles[t] {
                let h = &mut home[v as usize];
                if h.is_none() {
                    *h = Some((2, k));
                }
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
    } else if !tris_by_piece.is_empty() {
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

/// `$Nodes`: one block per entity, points, curves, surfaces then volumes. Tags stay node index + 1
/// (sparse per block).
fn nodes(o: &mut Out, mesh: &VolumeMesh, model: &Model) {
    let blocks = node_blocks(mesh, model);
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

/// `$Elements`: tets per region, then triangles per piece, then lines (type 1) per group, then
/// lines per curve, then a point (type 15) per named point; tags 1.. in that order. Returns the
/// number of elements.
fn elements(o: &mut Out, mesh: &VolumeMesh, model: &Model, tets_by_region: &[Vec<usize>]) -> u64 {
    let (tris_by_piece, lines, chains) = (&model.topology.tris, model.lines, &model.curves.chains);
    let blocks = tets_by_region.iter().filter(|s| !s.is_empty()).count()
        + tris_by_piece.iter().filter(|s| !s.is_empty()).count()
        + lines.iter().filter(|g| !g.lines.is_empty()).count()
        + mesh.points.len()
        + chains.len();
    let n_lines: usize = lines.iter().map(|g| g.lines.len()).sum();
    let segments: usize = chains.iter().map(|c| c.len() - 1).sum();
    let total =
        (mesh.tets.len() + mesh.triangles.len() + n_lines + mesh.points.len() + segments) as u64;
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
    for (k, sel) in tris_by_piece
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.is_empty())
    {
        o.rec(&[F::I(2), F::I(tag(k)), F::I(2), F::S(sel.len() as u64)]);
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
    for (g, group) in lines
        .iter()
        .enumerate()
        .filter(|(_, g)| !g.lines.is_empty())
    {
        o.rec(&[
            F::I(1),
            F::I(tag(g)),
            F::I(1),
            F::S(group.lines.len() as u64),
        ]);
        for &[a, b] in &group.lines {
            o.rec(&[F::S(next), F::S(a as u64 + 1), F::S(b as u64 + 1)]);
            next += 1;
        }
    }
    for (c, chain) in chains.iter().enumerate() {
        let n = chain.len() as u64 - 1;
        o.rec(&[F::I(1), F::I(tag(model.curve(c))), F::I(1), F::S(n)]);
        for w in chain.windows(2) {
            o.rec(&[F::S(next), F::S(w[0] as u64 + 1), F::S(w[1] as u64 + 1)]);
            next += 1;
        }
    }
    for (i, p) in mesh.points.iter().enumerate() {
        o.rec(&[F::I(0), F::I(tag(i)), F::I(15), F::S(1)]);
        o.rec(&[F::S(next), F::S(p.node as u64 + 1)]);
        next += 1;
    }
    o.end("Elements");
    total
}

/// `$ElementData` views: "material" (-1 where none and on triangles, lines and points), then one per
/// region property (NaN where undefined).
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

/// The elements in tag order: `Some(tet)` for each tet by region, then `None` per triangle (by
/// piece), per line, per curve segment and per point.
struct Order<'a> {
    tets: &'a [Vec<usize>],
    tris: &'a [Vec<usize>],
    /// Lines, the curves' lines and point elements.
    lines: usize,
    total: usize,
}

impl Order<'_> {
    fn iter(&self) -> impl Iterator<Item = Option<usize>> + '_ {
        let tets = self.tets.iter().flatten().map(|&t| Some(t));
        let tris = self.tris.iter().flatten().map(|_| None);
        tets.chain(tris)
            .chain(std::iter::repeat_n(None, self.lines))
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

#[cfg(test)]
mod tests {
    use super::*;
    use topology::tests::three_tets;

    #[test]
    fn integers_are_written_as_the_standard_formatting_writes_them() {
        let cases: [(u64, bool); 7] = [
            (0, false),
            (9, false),
            (10, false),
            (1_234_567, false),
            (u64::MAX, false),
            (1, true),
            (2_147_483_648, true),
        ];
        for (v, negative) in cases {
            let mut buf = Vec::new();
            decimal(&mut buf, v, negative);
            let want = if negative {
                format!("-{v}")
            } else {
                v.to_string()
            };
            assert_eq!(String::from_utf8(buf).unwrap(), want);
        }
    }

    /// The lines of `section` in the ASCII file of `mesh`.
    fn section(mesh: &VolumeMesh, section: &str) -> Vec<String> {
        let text = String::from_utf8(write(mesh, &[], false)).unwrap();
        let start = format!("${section}\n");
        let (_, rest) = text.split_once(&start).unwrap();
        let (body, _) = rest.split_once(&format!("$End{section}")).unwrap();
        body.lines().map(str::to_string).collect()
    }

    #[test]
    fn each_entity_lists_its_physical_tags_and_each_volume_its_signed_bounding_surfaces() {
        let lines = section(&three_tets(), "Entities");
        let want = [
            "4 7 5 3",
            // Points: the corners, nodes 1 to 4, where three or more curve edges meet.
            "1 0 0 0 0",
            "2 1 0 0 0",
            "3 0 1 0 0",
            "4 0 0 1 0",
            // Curves: tag, bounding box, their 1D group (named after the surfaces meeting
            // there), start and end point (the end negated, as Gmsh writes it).
            "1 0 0 0 1 0 0 1 4 2 1 -2",
            "2 0 0 0 0 1 0 1 5 2 1 -3",
            "3 0 0 0 0 0 1 1 6 2 1 -4",
            "4 0 0 -1 1 0 0 1 6 2 1 -2",
            "5 0 0 0 1 1 0 1 1 2 2 -3",
            "6 0 0 0 1 0 1 1 2 2 2 -4",
            "7 0 0 0 0 1 1 1 3 2 3 -4",
            // Surfaces: tag, bounding box, physical tags, bounding curves (negative where the
            // curve runs against the way the surface's triangles turn).
            "1 0 0 0 1 0 1 1 1 3 -1 3 -6",
            "2 0 0 -1 1 0 0 1 1 2 1 -4",
            "3 0 0 0 1 1 0 1 2 3 1 -2 5",
            "4 0 0 0 1 1 1 3 3 -5 6 3 5 -6 7",
            "5 0 0 0 0 0 0 3 4 -7 8 0",
            // Volumes: tag, bounding box, region and material, bounding surfaces.
            "1 0 0 0 1 1 1 2 1 5 2 -1 -3",
            "2 0 0 -1 1 1 0 2 2 5 2 -2 3",
            "3 0 0 0 0 0 0 2 3 4 0",
        ];
        assert_eq!(lines, want);
    }

    #[test]
    fn triangles_are_written_piece_by_piece_and_their_nodes_on_the_first_piece() {
        let elements = section(&three_tets(), "Elements");
        let blocks: Vec<&str> = (elements.iter())
            .filter(|l| l.split(' ').count() == 4 && l.starts_with("2 "))
            .map(String::as_str)
            .collect();
        // Per piece (entity, type 2, one triangle): box/a, box/b, H, F; G's piece is empty.
        assert_eq!(blocks, ["2 1 2 1", "2 2 2 1", "2 3 2 1", "2 4 2 1"]);
        let nodes = section(&three_tets(), "Nodes");
        // Every triangle node lies on a curve: nodes 1 to 4 on the corners, node 5 on curve 4
        // (the free edges of b's box face); node 6 only in a tet.
        let headers: Vec<&str> = (nodes.iter())
            .filter(|l| l.split(' ').count() == 4)
            .map(String::as_str)
            .collect();
        assert_eq!(
            headers,
            [
                "6 6 1 6", "0 1 0 1", "0 2 0 1", "0 3 0 1", "0 4 0 1", "1 4 0 1", "3 1 0 1"
            ]
        );
    }

    #[test]
    fn a_line_group_is_a_curve_of_line_elements_after_the_triangles_with_its_own_1d_group() {
        let mesh = three_tets();
        let well = LineGroup {
            area: None,
            name: "well".into(),
            lines: vec![[3, 0], [0, 4]],
        };
        let text = String::from_utf8(write(&mesh, std::slice::from_ref(&well), false)).unwrap();
        let section = |name: &str| -> Vec<String> {
            let (_, rest) = text.split_once(&format!("${name}\n")).unwrap();
            let (body, _) = rest.split_once(&format!("$End{name}")).unwrap();
            body.lines().map(str::to_string).collect()
        };
        // The well's group comes first among the 1D groups, the curves' after it.
        assert_eq!(
            section("PhysicalNames")[1..3],
            ["1 1 \"well\"", "1 2 \"F/H\""]
        );
        let entities = section("Entities");
        // Four corners, the well's curve and the seven curves of the surfaces.
        assert_eq!(entities[0], "4 8 5 3");
        assert_eq!(entities[5], "1 0 0 -1 0 0 1 1 1 0");
        let elements = section("Elements");
        // Fourteen blocks: tets of two regions, four pieces of triangles, the well's two lines
        // and the surfaces' seven curves.
        assert_eq!(elements[0], "14 17 1 17");
        let at = elements.iter().position(|l| l == "1 1 1 2").unwrap();
        assert_eq!(elements[at + 1..at + 3], ["8 4 1", "9 1 5"]);
        // Of the well's nodes 4, 1 and 5, the first two are corners; node 5 lies on the well.
        assert!(section("Nodes").contains(&"1 1 0 1".to_string()));
        let lines = geom::mesh::read::read_msh_lines(text.as_bytes(), "w.msh").unwrap();
        assert_eq!(lines.lines, well.lines);
        let back = geom::mesh::read::read_volume_msh(text.as_bytes(), "w.msh").unwrap();
        assert_eq!(back.tets.len(), mesh.tets.len());
    }
}
