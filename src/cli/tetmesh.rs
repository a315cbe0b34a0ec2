//! `recipe tetmesh`: the tetrahedral mesher on its own, for one closed boundary given as a file
//! (Gmsh .msh, .off, .obj), with optional embedded (dangling) faces and embedded lines (well
//! paths, each meshed as a chain of tet edges and written as line elements). The boundary may
//! hold inner shells (each connected piece is a shell) and point either way: region finding
//! orients it.

use super::Failure;
use super::build::write_atomic;
use export::quality;
use export::{Format, export};
use geom::mesh::read::{BoundaryMesh, read_by_extension, read_lines_by_extension};
use geom::mesh::{LineGroup, RegionGroup, SurfaceGroup, SurfaceKind, VolumeMesh};
use model::regions;
use std::collections::BTreeMap;
use std::path::PathBuf;
use tet_mesh::{Method, RegionInput, SizeField, TetMeshOptions, mesh_region};

#[derive(clap::Args, Debug)]
pub struct TetmeshArgs {
    /// Closed boundary surface (.msh, .off, .obj): an outer shell and any inner shells (the
    /// cavities of a host around a body); either orientation
    pub boundary: PathBuf,
    /// Output mesh; the format follows the extension: .msh (4.1), .vtu, .mesh (MEDIT), .node (TetGen)
    #[arg(short, long)]
    pub output: PathBuf,
    /// Triangles of the boundary file with these tags (msh entity, obj group) are embedded faces
    #[arg(long, value_delimiter = ',')]
    pub embedded_tags: Vec<i32>,
    /// A further file whose triangles are all embedded faces (a dangling fault); vertices are
    /// matched to the boundary's by exact coordinates
    #[arg(long)]
    pub embed: Option<PathBuf>,
    /// Take only the triangles with these tags from the --embed file
    #[arg(long, value_delimiter = ',')]
    pub embed_tags: Vec<i32>,
    /// Lines to embed as chains of tet edges (well paths): the `l` polylines of an .obj or the
    /// line elements (type 1) of a .msh; their vertices are matched to the others by exact
    /// coordinates, or are new inner vertices. Written to every output format as line elements
    /// named after the file (in .msh a 1D physical group; see `export::export`)
    #[arg(long)]
    pub embed_lines: Option<PathBuf>,
    /// Weld --embed vertices to boundary vertices closer than this (model units); files written
    /// with fewer digits need it [default: 1e-9 × the boundary's bounding-box diagonal]
    #[arg(long)]
    pub weld: Option<f64>,
    /// Interior target element size [default: sizes grow from the boundary's, at --growth]
    #[arg(long)]
    pub size: Option<f64>,
    /// Size growth away from the boundary (a recipe's `[mesh] growth` default)
    #[arg(long, default_value_t = 1.3)]
    pub growth: f64,
    /// Skip quality optimization
    #[arg(long)]
    pub no_optimize: bool,
    /// Meshing method: `delaunay` (falls back to the front where boundary recovery fails) or
    /// `front` (advancing front only)
    #[arg(long, default_value = "delaunay", value_parser = Method::NAMES.map(|(n, _)| n))]
    pub method: String,
    /// Region name [default: the boundary file's stem]
    #[arg(long)]
    pub name: Option<String>,
}

fn read(path: &PathBuf) -> Result<BoundaryMesh, Failure> {
    let bytes = std::fs::read(path)
        .map_err(|e| Failure(format!("error: cannot read {}: {e}", path.display())))?;
    read_by_extension(&path.display().to_string(), &bytes)
        .map_err(|e| Failure(format!("error: {e}")))
}

/// Earlier vertices by position, with their index.
type PointTree = rstar::RTree<rstar::primitives::GeomWithData<[f64; 3], u32>>;

/// Merges vertices by exact coordinates (bit patterns), so faces from several files share nodes;
/// after `weld_to_existing`, a new vertex within the weld distance of an earlier one reuses it.
#[derive(Default)]
struct VertexPool {
    index: BTreeMap<[u64; 3], u32>,
    vertices: Vec<[f64; 3]>,
    weld: Option<(f64, PointTree)>,
}

impl VertexPool {
    fn add(&mut self, p: [f64; 3]) -> u32 {
        self.add_welding(p, true)
    }
    /// [`VertexPool::add`] by exact coordinates only, whatever the weld distance.
    fn add_exact(&mut self, p: [f64; 3]) -> u32 {
        self.add_welding(p, false)
    }
    fn add_welding(&mut self, p: [f64; 3], weld: bool) -> u32 {
        let key = p.map(|c| (if c == 0.0 { 0.0 } else { c }).to_bits());
        if let Some(&i) = self.index.get(&key) {
            return i;
        }
        if weld
            && let Some((tol, tree)) = &self.weld
            && let Some(n) = tree.nearest_neighbor(p)
        {
            let q = n.geom();
            let d2 = (0..3).map(|k| (q[k] - p[k]).powi(2)).sum::<f64>();
            if d2 <= tol * tol {
                return n.data;
            }
        }
        self.vertices.push(p);
        let i = (self.vertices.len() - 1) as u32;
        self.index.insert(key, i);
        i
    }
    /// From now on, vertices within `tol` of one already in the pool are welded to it.
    fn weld_to_existing(&mut self, tol: f64) {
        let pts = self
            .vertices
            .iter()
            .enumerate()
            .map(|(i, &p)| rstar::primitives::GeomWithData::new(p, i as u32))
            .collect();
        self.weld = Some((tol, rstar::RTree::bulk_load(pts)));
    }
    fn triangles(&mut self, m: &BoundaryMesh, keep: impl Fn(i32) -> bool) -> Vec<[u32; 3]> {
        let map: Vec<u32> = m.vertices.iter().map(|&p| self.add(p)).collect();
        m.triangles
            .iter()
            .zip(&m.triangle_tag)
            .filter(|(_, tag)| keep(**tag))
            .map(|(t, _)| t.map(|v| map[v as usize]))
            .collect()
    }
}

/// The segments of the --embed-lines file, over the pool's vertices (by exact coordinates), and
/// the group name their line elements get (the file's stem).
fn embed_lines(path: &PathBuf, pool: &mut VertexPool) -> Result<(Vec<[u32; 2]>, String), Failure> {
    let bytes = std::fs::read(path)
        .map_err(|e| Failure(format!("error: cannot read {}: {e}", path.display())))?;
    let m = read_lines_by_extension(&path.display().to_string(), &bytes)
        .map_err(|e| Failure(format!("error: {e}")))?;
    let map: Vec<u32> = m.vertices.iter().map(|&p| pool.add_exact(p)).collect();
    let lines = m.lines.iter().map(|l| l.map(|v| map[v as usize])).collect();
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "lines".into());
    Ok((lines, name))
}

pub fn run(a: &TetmeshArgs) -> Result<(), Failure> {
    let format = output_format(&a.output)?;
    let b = read(&a.boundary)?;
    let mut pool = VertexPool::default();
    let mut boundary = pool.triangles(&b, |t| !a.embedded_tags.contains(&t));
    let mut embedded = pool.triangles(&b, |t| a.embedded_tags.contains(&t));
    if let Some(e) = &a.embed {
        let diag = {
            let b = geom::BBox::from_points(pool.vertices.iter());
            let e = b.extent();
            (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt()
        };
        let weld = a.weld.unwrap_or(1e-9 * diag);
        pool.weld_to_existing(weld);
        embedded.extend(pool.triangles(&read(e)?, |t| {
            a.embed_tags.is_empty() || a.embed_tags.contains(&t)
        }));
    }
    let (lines, line_group) = match &a.embed_lines {
        Some(path) => embed_lines(path, &mut pool)?,
        None => (Vec::new(), String::new()),
    };
    if boundary.is_empty() {
        return Err(Failure(format!(
            "error: {}: no boundary triangles",
            a.boundary.display()
        )));
    }
    orient_outwards(&pool.vertices, &mut boundary).map_err(|e| {
        Failure(format!(
            "error: {}: the boundary does not enclose a region: {e}",
            a.boundary.display()
        ))
    })?;
    let name = a.name.clone().unwrap_or_else(|| {
        a.boundary
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "region".into())
    });
    if let Some(sz) = a.size.filter(|s| !(*s > 0.0 && s.is_finite())) {
        return Err(Failure(format!("error: --size must be positive, got {sz}")));
    }
    if !(a.growth > 1.0 && a.growth.is_finite()) {
        return Err(Failure(format!(
            "error: --growth must be greater than 1, got {}",
            a.growth
        )));
    }
    let input = RegionInput {
        name: name.clone(),
        vertices: pool.vertices,
        boundary,
        embedded,
        lines,
    };
    let field = SizeField {
        size: a.size.unwrap_or(f64::INFINITY),
        growth: a.growth,
        refine: Vec::new(),
        ..SizeField::default()
    };
    let opts = TetMeshOptions {
        optimize: !a.no_optimize,
        method: Method::from_name(&a.method).unwrap_or_default(),
        ..TetMeshOptions::default()
    };
    let t0 = std::time::Instant::now();
    let out = mesh_region(&input, &field, &opts).map_err(|e| Failure(format!("error: {e}")))?;
    let secs = t0.elapsed().as_secs_f64();
    let how = match (&out.stats.fallback, opts.method) {
        (_, Method::Front) => "advancing front".to_string(),
        (Some(why), _) => format!("advancing front (Delaunay gave way: {why})"),
        (None, _) => format!(
            "Delaunay, {} boundary triangles recovered by flips, {} through holes",
            out.stats.flipped_faces, out.stats.recovered_faces
        ),
    };

    let mut triangles = input.boundary.clone();
    triangles.extend(&input.embedded);
    let mut triangle_group = vec![0u32; input.boundary.len()];
    triangle_group.extend(std::iter::repeat_n(1u32, input.embedded.len()));
    let mut surface_groups = vec![SurfaceGroup {
        name: "boundary".into(),
        kind: SurfaceKind::Other,
    }];
    if !input.embedded.is_empty() {
        surface_groups.push(SurfaceGroup {
            name: "embedded".into(),
            kind: SurfaceKind::Fault,
        });
    }
    let line_groups: Vec<LineGroup> = if input.lines.is_empty() {
        Vec::new()
    } else {
        let steps = out
            .lines
            .iter()
            .flat_map(|c| c.windows(2).map(|w| [w[0], w[1]]));
        errln!(
            "    Embedded {} line segments as {} line elements ({} new nodes on them)",
            input.lines.len(),
            steps.clone().count(),
            out.stats.line_nodes
        );
        vec![LineGroup {
            area: None,
            name: line_group,
            lines: steps.collect(),
        }]
    };
    let mesh = VolumeMesh {
        nodes: out.nodes,
        tet_region: vec![0; out.tets.len()],
        tets: out.tets,
        regions: vec![RegionGroup {
            name: name.clone(),
            material: None,
            properties: BTreeMap::new(),
        }],
        triangles,
        triangle_group,
        surface_groups,
        lines: line_groups,
        points: Vec::new(),
        face_sets: Vec::new(),
    };
    let stem = a
        .output
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| name.clone());
    let dir = a
        .output
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("."));
    for (file, bytes) in
        export(&mesh, &stem, format).map_err(|e| Failure(format!("error: export: {e}")))?
    {
        write_atomic(&dir.join(&file), &bytes)?;
        errln!("       Wrote {}", dir.join(&file).display());
    }
    errln!(
        "    Finished {}: {} tets, {} nodes in {:.3}s ({:.0} tets/s; {how})",
        name,
        mesh.tets.len(),
        mesh.nodes.len(),
        secs,
        mesh.tets.len() as f64 / secs.max(1e-9)
    );
    err!("{}", quality::render_table2(&quality::table2(&mesh)));
    Ok(())
}

/// Orients `boundary` (over `vertices`) to face away from the region it encloses. Each connected
/// piece is a shell: the outer one and any inner ones (the cavities of a host around a lens or a
/// salt body). Region finding decides exactly which side of each shell is enclosed; the region
/// meshed is the one every shell bounds, and the caller's triangles may point either way.
fn orient_outwards(vertices: &[[f64; 3]], boundary: &mut [[u32; 3]]) -> Result<(), String> {
    let all = geom::TriMesh::new(vertices.to_vec(), boundary.to_vec());
    let pieces = model::charts::connected_groups(&all, |_| 0);
    let shells: Vec<regions::PatchIn> = pieces
        .iter()
        .enumerate()
        .map(|(k, ts)| regions::PatchIn {
            chart_of: None,
            name: format!("shell#{}", k + 1),
            surface: "boundary".into(),
            mesh: geom::TriMesh::new(
                vertices.to_vec(),
                ts.iter().map(|&t| boundary[t as usize]).collect(),
            ),
        })
        .collect();
    let model = regions::find_regions(&shells, &[]).map_err(|e| e.to_string())?;
    let region = model
        .regions
        .iter()
        .find(|r| r.sides.len() == shells.len())
        .ok_or_else(|| {
            format!(
                "its {} shells do not bound one region together (are some outside the others, \
                 or nested twice?)",
                shells.len()
            )
        })?;
    for side in &region.sides {
        if side.side == regions::Side::Front {
            for &t in &pieces[side.patch as usize] {
                boundary[t as usize].swap(1, 2);
            }
        }
    }
    Ok(())
}

fn output_format(p: &std::path::Path) -> Result<Format, Failure> {
    let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("");
    match ext {
        "msh" => Ok(Format::Msh),
        "vtu" => Ok(Format::Vtu),
        "mesh" => Ok(Format::Medit),
        "node" | "ele" => Ok(Format::TetGen),
        _ => Err(Failure(format!(
            "error: {}: unknown output format `.{ext}` (use .msh, .vtu, .mesh or .node)",
            p.display()
        ))),
    }
}
