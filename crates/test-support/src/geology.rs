//! A corpus of geological situations, each a recipe and the gOcad TSurf files it imports, made
//! the way real exports look: irregular jittered triangulations at UTM coordinates, some written
//! with `ZPOSITIVE Depth` or CRLF, every surface reaching past the box so that the box cuts it.
//! Each case knows how many regions its model has, so a test can build it and check the mesh.
//! Some cases carry a well (a gOcad PLine) across their bodies: through a fault, a lens, into a
//! salt flank.
//!
//! The box is [0, 4000]² × [-2000, 0] m before the UTM shift of `didactic`. A fault plane with
//! strike along y is `x = x0 + (z - z0) / tan(dip)`: its height over a column grows with x, so the
//! side of smaller x is above it (the hanging wall) and the other below it (the footwall).

use crate::didactic::write_tsurf;
use crate::didactic::{ORIGIN_X, ORIGIN_Y, Rng, Style, Surface, graded_axis, grid_surface};

/// One situation: the recipe text, its files (name, TSurf text) and the regions it must mesh to.
pub struct Case {
    pub name: &'static str,
    pub recipe: String,
    pub files: Vec<(String, String)>,
    pub regions: usize,
    /// The smallest dihedral angle (degrees) every region must reach: 8, or less where the
    /// boundary itself forces thinner tets (a wedge pinching out at a small angle).
    pub min_dihedral: f64,
}

impl Case {
    /// Writes the recipe (as `<name>.toml`) and its files into `dir`; returns the recipe path.
    pub fn write(&self, dir: &std::path::Path) -> std::path::PathBuf {
        std::fs::create_dir_all(dir.join("data")).expect("a data folder");
        for (file, text) in &self.files {
            std::fs::write(dir.join("data").join(file), text).expect("write a surface");
        }
        let path = dir.join(format!("{}.toml", self.name));
        std::fs::write(&path, &self.recipe).expect("write the recipe");
        path
    }
}

/// Every case of the corpus.
pub fn cases() -> Vec<Case> {
    vec![
        fault_with_throw("normal_fault", -150.0),
        fault_with_throw("reverse_fault", 150.0),
        fault_with_throw("small_throw_fault", -5.0),
        fault_stopping_in_a_layer(),
        erosional_unconformity(),
        x_fault_junction(),
        y_fault_junction(),
        recumbent_fold(),
        vertical_tube(),
        salt_stock(),
        closed_salt_diapir(),
        closed_salt_diapir_with_well(),
        salt_dome_cut_by_the_box(),
        lens(),
        fault_patches_touching_at_corners(),
        dense_fault_patches_touching_at_corners(),
        dangling_faults_crossing(),
        horizons_touching_at_a_point(),
        horizons_touching_along_a_line(),
        raft_in_salt(),
        chevron_fold(),
        intrusion_cutting_a_body(),
        fault_splay(),
        fault_with_a_hole(),
        graben(),
        horst(),
        tilted_layers(),
        fault_under_an_unconformity(),
        relay_ramp(),
        listric_fault(),
        fault_through_salt(),
        horizon_with_standing_caps(),
        caps_cut_by_curves(),
        salt_overhang(),
    ]
}

/// Situations the pipeline cannot mesh yet, or not to the corpus's quality bars, kept so that
/// they can be reproduced and moved into [`cases`] once they do. Each fails naming the place and
/// the input line nearest it, or meshes validly below the bars:
/// - `two_lenses`: meshes (once no chart's border overlaps itself in map view), but the lenses'
///   rims are crumpled into sliver facets (their neighbours bend away by 30° to 115°), each a
///   patch of its own between creases, with corners of a few degrees: tets on them reach 5.0°.
/// - `onlap`: H1 onlaps U at 2.0°; meshes, but the surface meshes meet at the tip at about 1°
///   (0.96° at the sharpest), and the wedge, one element across, reaches 0.45° there (1.26° with
///   `refine_close_curves = true`, which its warnings give). The regions beside it meet the
///   bars: the part of H1 discarded above U leaves no curve on the box (`model::rejoin`).
/// - `onlap_under_a_degree`: the same at 0.86°; meshes, at 0.13°. While every turn of `H1/U`
///   sharper than the kink angle cut it, however short the jog, the meshes of U and H1 crossed
///   near the tip, and the build refined along `H1/U` to a tenth of the size and built again
///   (0.31°, at 266,000 tets against 203,000).
/// - `downlap`: the onlap upside down, at 2.0°; meshes, at 1.2°, and its other regions meet the
///   bars. In both, the two surfaces
///   cross again and again near the tip, so the box side holds nodes of the tip a few metres
///   apart; the curves there grade from them (`model::tips`), else needles (0.11°).
/// - `fault_splay_at_one_degree`: the fault splay with F2 only 1° steeper than F1; meshes, at
///   0.89°, near its wedge's bound of 1.0° (planar faults leave no crossings at the branch line);
///   the region above the splay reaches 2.7° beside it.
/// - `detachment`: a thrust's flat 10 m above a horizon; meshes, but the slab between is one
///   element across under the flat, at 1.8° (2.6° with `min_layers = 3`, which takes the
///   region's median thickness, and the ramp makes that large).
/// - `zero_thickness_layer`: a layer collapsed to nothing where it pinches out, its two
///   surfaces one and the same there; the common triangles are one interface and the layer
///   ends where the two part, at about 3°; meshes, at 0.28° where they part. The base's facets
///   next to where they part lean on the top at far less than the layer's angle (clamping a
///   surface to another leaves facets with one corner a little below it): at 15°, the same
///   layer's facets there lean at 0.4° to 6° (median 5.8°), and its tets reach 0.67°.
/// - `channel`: a meandering closed sand body 3 km long and 60 m high, tapering to a point at
///   both ends; meshes, but its closed surface is cut into charts whose seams run 2-3 m apart
///   near its tips (curves of the chart borders under a tenth of their size), and the tets
///   there reach 2.2° (the same with `min_layers = 2`, at 1.8 million tets). The worst lie
///   within 1.5 m of the two apexes, where the rim's facets (crease strips, kept as features)
///   have corners of 1.1-1.3° on a cone about 9° high; with `min_size = 0.5` (1.5 million tets)
///   they still reach 2.1°, so sizes alone do not lift it.
/// - `smoothed_channel`: the channel with `smooth = true`; meshes (2.0 million tets), at 1.95°
///   within a few metres of its east tip, where its top chart's border runs as a stair of
///   needles 4 m wide along the rim. Its top and bottom charts each face one way but for two to
///   six triangles (teeth of that stair curled round the rim, a needle beside them): their
///   projections are mended (`surface_mesh`'s `relax`); flattened on a circle by a Tutte
///   embedding instead, the 3 km strips folded their meshes. And a needle that `untwist` moved
///   off the top chart's crossing came back on every pass (`unpinch`), until it took along
///   the gap it left (`charts::gaps`).
/// - `lens_cut_by_a_fault`: a closed lens offset 100 m by a normal fault, each half a body closed
///   by the fault; meshes into its eight regions, at 6.6° in the footwall half (7.3° with
///   `refine_close_curves = true`, at 301,000 tets against 161,000): the curves of the lens's
///   seams and creases come within 6 to 20 m of each other (warned), as on `two_lenses`.
pub fn known_gaps() -> Vec<Case> {
    vec![
        lens_cut_by_a_fault(),
        two_lenses(),
        onlap("onlap", 0.035),
        onlap("onlap_under_a_degree", 0.015),
        downlap("downlap", 0.035),
        detachment(),
        fault_splay_at("fault_splay_at_one_degree", 61.0),
        zero_thickness_layer(),
        channel("channel"),
        smoothed_channel(),
    ]
}

/// Fault systems of the SCEC Community Fault Model (`../shared/data/gocad/SCECcode__CFM`, the
/// 1 km resampled CFM 5.3 files, at UTM zone 11 coordinates with topography above z = 0),
/// intersected with each other and a box, each fault cut by the box where it leaves it:
/// - `scec_western_transverse_ranges`: the San Andreas (Carrizo), Pine Mountain, Lockwood
///   Valley and Big Pine faults; the San Andreas crosses the box, the others end inside it or on
///   one another, and their traces meet the box top where curves of three surfaces cross.
/// - `scec_tejon_pass`: the San Andreas, Garlock, Pleito and White Wolf faults round Tejon Pass;
///   White Wolf is one file of several strands crossing along a line (non-manifold edges kept
///   as curves), dying out inside the box. `scec_tejon_pass_coarse` is the same at 2 km: a
///   White Wolf triangle then hangs in a recovery hole as a fin (two edges on its wall, the
///   third free inside), which only peeling fills; the region round the strands reaches 6.5°
///   there (13° at 1 km), so its bar is 6°.
///
/// `cfm` is that folder; the recipes name the files by absolute path, so `files` is empty.
pub fn scec_cases(cfm: &std::path::Path) -> Vec<Case> {
    let case = |name, faults: &[(&str, &str)], lo, hi, size| {
        fault_system(cfm, name, faults, [lo, hi], size)
    };
    let tejon = [
        ("saf", "SAFS-SAFZ-CRRZ-San_Andreas_fault-CFM4"),
        ("garlock", "GRFS-GRFZ-WEST-Garlock_fault-CFM5"),
        ("pleito", "GVFA-PLFZ-MULT-Pleito_fault-CFM2"),
        ("whitewolf", "GVFA-WWFZ-MULT-White_Wolf_fault-CFM5"),
    ];
    vec![
        case(
            "scec_western_transverse_ranges",
            &[
                ("saf", "SAFS-SAFZ-CRRZ-San_Andreas_fault-CFM4"),
                ("pinemtn", "CRFA-BPPM-PMTS-Pine_Mountain_fault-CFM2"),
                ("lockwood", "CRFA-BPPM-LKWV-Lockwood_Valley_fault-CFM2"),
                ("bigpine", "CRFA-BPPM-WEST-Big_Pine_fault-CFM2"),
            ],
            [265000.0, 3832000.0, -12000.0],
            [315000.0, 3860000.0, 0.0],
            2000.0,
        ),
        case(
            "scec_tejon_pass",
            &tejon,
            [320000.0, 3845000.0, -12000.0],
            [360000.0, 3880000.0, 0.0],
            1000.0,
        ),
        Case {
            min_dihedral: 6.0,
            ..case(
                "scec_tejon_pass_coarse",
                &tejon,
                [320000.0, 3845000.0, -12000.0],
                [360000.0, 3880000.0, 0.0],
                2000.0,
            )
        },
    ]
}

/// The 1857 rupture of the San Andreas with the Garlock, Pine Mountain, Pleito, White Wolf and
/// Lockwood Valley faults round the Big Bend, in a 90 × 55 × 14 km box at 2.5 km: it builds, but
/// the rupture file is two strands whose free edges run 2–4 m apart down the whole depth at
/// x ≈ 362.4 km, and Lockwood Valley ends 11 m from the San Andreas at the box floor, so the
/// tets there are flat (0.1°): the build must say where. Not in [`scec_cases`]: it cannot meet
/// a quality bar at this size (refining along the slit to 20 m gives 0.28° in 9.6 million tets).
pub fn scec_big_bend(cfm: &std::path::Path) -> Case {
    let case = fault_system(
        cfm,
        "scec_big_bend",
        &[
            ("saf", "SAFS-SAFZ-1857-San_Andreas_fault_rupture-CFM5"),
            ("garlock", "GRFS-GRFZ-WEST-Garlock_fault-CFM5"),
            ("pinemtn", "CRFA-BPPM-PMTS-Pine_Mountain_fault-CFM2"),
            ("pleito", "GVFA-PLFZ-MULT-Pleito_fault-CFM2"),
            ("whitewolf", "GVFA-WWFZ-MULT-White_Wolf_fault-CFM5"),
            ("lockwood", "CRFA-BPPM-LKWV-Lockwood_Valley_fault-CFM2"),
        ],
        [[280000.0, 3835000.0, -14000.0], [370000.0, 3890000.0, 0.0]],
        2500.0,
    );
    // No fault crosses the box whole: one region.
    Case { regions: 1, ..case }
}

/// A case of SCEC faults (name in the recipe, CFM file stem) intersected with each other and
/// the box `[lo, hi]`, meshed at `size`, written to an msh; two regions, the 8° bar.
fn fault_system(
    cfm: &std::path::Path,
    name: &'static str,
    faults: &[(&str, &str)],
    [lo, hi]: [[f64; 3]; 2],
    size: f64,
) -> Case {
    let ts = cfm.join("CFM5.3_4/ts/1000m");
    let mut t = format!("[model]\nname = \"{name}\"\n\n[surfaces]\n");
    for (f, file) in faults {
        let path = ts.join(format!("{file}_1000m.ts"));
        t.push_str(&format!(
            "{f} = {{ file = \"{}\", kind = \"fault\" }}\n",
            path.display()
        ));
    }
    let all: Vec<String> = faults.iter().map(|(f, _)| format!("\"{f}\"")).collect();
    t.push_str(&format!(
        "\n[box]\nmin = {lo:?}\nmax = {hi:?}\n\n[intersect]\nall = [\"box\", {}]\n\n\
         [mesh]\nsize = {size:?}\n\n[output]\ndir = \"out\"\nformats = [\"msh\"]\n",
        all.join(", ")
    ));
    Case {
        name,
        recipe: t,
        files: Vec::new(),
        regions: 2,
        min_dihedral: 8.0,
    }
}

/// The extent surfaces are made over (past the box on every side).
const LO: f64 = -300.0;
const HI: f64 = 4300.0;

/// A horizon `z = z0 + amp sin(x / 700 + phase) cos(y / 900)` over the plan of the box.
fn horizon(z0: f64, amp: f64, phase: f64, rng: &mut Rng) -> Surface {
    let us = graded_axis(LO, HI, 160.0, phase);
    let vs = graded_axis(LO, HI, 170.0, phase + 1.0);
    grid_surface(
        &us,
        &vs,
        |x, y| {
            [
                x,
                y,
                z0 + amp * (x / 700.0 + phase).sin() * (y / 900.0).cos(),
            ]
        },
        rng,
    )
}

/// A plane fault striking along y through `x = x0` at `z = z0`, dipping `dip` degrees, over the
/// box's height and plan (or over `y` in `ys` and `z` in `zs` when it is smaller).
fn fault_y(x0: f64, z0: f64, dip: f64, ys: (f64, f64), zs: (f64, f64), rng: &mut Rng) -> Surface {
    let cot = 1.0 / dip.to_radians().tan();
    let us = graded_axis(ys.0, ys.1, 170.0, 0.3);
    let vs = graded_axis(zs.0, zs.1, 150.0, 0.7);
    grid_surface(&us, &vs, |y, z| [x0 + (z - z0) * cot, y, z], rng)
}

/// As [`fault_y`], striking along x through `y = y0`.
fn fault_x(y0: f64, z0: f64, dip: f64, rng: &mut Rng) -> Surface {
    let cot = 1.0 / dip.to_radians().tan();
    let us = graded_axis(LO, HI, 170.0, 1.3);
    let vs = graded_axis(-2300.0, 300.0, 150.0, 0.2);
    grid_surface(&us, &vs, |x, z| [x, y0 + (z - z0) * cot, z], rng)
}

const PLAIN: Style = Style {
    depth_positive: false,
    crlf: false,
    property: None,
};
const DEPTH: Style = Style {
    depth_positive: true,
    crlf: false,
    property: None,
};
const DEPTH_CRLF: Style = Style {
    depth_positive: true,
    crlf: true,
    property: None,
};

/// A recipe under construction: surfaces, trims and the rest of its text.
struct Recipe {
    name: &'static str,
    surfaces: Vec<(String, &'static str)>,
    files: Vec<(String, String)>,
    trims: Vec<String>,
    /// `[wells]` entries: name and mesh edge size.
    wells: Vec<(String, f64)>,
}

impl Recipe {
    fn new(name: &'static str) -> Recipe {
        Recipe {
            name,
            surfaces: Vec::new(),
            files: Vec::new(),
            trims: Vec::new(),
            wells: Vec::new(),
        }
    }

    /// A well through the local `stations` (from its head down), written as a gOcad PLine with
    /// its segments in reverse order, as an export may list them.
    fn well(&mut self, name: &str, stations: &[[f64; 3]], size: f64) {
        let mut t = format!("GOCAD PLine 1\r\nHEADER {{\r\nname:{name}\r\n}}\r\nILINE\r\n");
        for (i, p) in stations.iter().enumerate() {
            t.push_str(&format!(
                "VRTX {} {:.3} {:.3} {:.3}\r\n",
                i + 1,
                p[0] + ORIGIN_X,
                p[1] + ORIGIN_Y,
                p[2]
            ));
        }
        for i in (1..stations.len()).rev() {
            t.push_str(&format!("SEG {} {}\r\n", i + 1, i));
        }
        t.push_str("END\r\n");
        self.files.push((format!("{name}.pl"), t));
        self.wells.push((name.to_string(), size));
    }

    fn surface(&mut self, name: &str, kind: &'static str, s: &Surface, style: &Style) {
        let file = format!("{name}.ts");
        self.files.push((file, write_tsurf(name, s, style)));
        self.surfaces.push((name.to_string(), kind));
    }

    /// `[[trim]] surface = s, keep = { side = of }`.
    fn keep(&mut self, s: &str, side: &str, of: &str) {
        self.trims.push(format!(
            "[[trim]]\nsurface = \"{s}\"\nkeep = {{ {side} = \"{of}\" }}\n"
        ));
    }

    /// The case, with the surfaces of `all` (and the box) intersected pairwise.
    fn case(self, all: &[&str], regions: usize) -> Case {
        let mut t = format!("[model]\nname = \"{}\"\n\n[surfaces]\n", self.name);
        for (s, kind) in &self.surfaces {
            t.push_str(&format!(
                "{s} = {{ file = \"data/{s}.ts\", kind = \"{kind}\" }}\n"
            ));
        }
        t.push_str(&format!(
            "\n[box]\nmin = [{}, {}, -2000.0]\nmax = [{}, {}, 0.0]\n",
            ORIGIN_X,
            ORIGIN_Y,
            ORIGIN_X + 4000.0,
            ORIGIN_Y + 4000.0
        ));
        let all: Vec<String> = all.iter().map(|s| format!("\"{s}\"")).collect();
        t.push_str(&format!("\n[intersect]\nall = [{}]\n\n", all.join(", ")));
        for tr in &self.trims {
            t.push_str(tr);
            t.push('\n');
        }
        if !self.wells.is_empty() {
            t.push_str("[wells]\n");
            for (w, size) in &self.wells {
                t.push_str(&format!(
                    "{w} = {{ file = \"data/{w}.pl\", size = {size:?} }}\n"
                ));
            }
            t.push('\n');
        }
        t.push_str("[mesh]\nsize = 250.0\n\n[output]\ndir = \"out\"\nformats = [\"msh\"]\n");
        Case {
            name: self.name,
            recipe: t,
            files: self.files,
            regions,
            min_dihedral: 8.0,
        }
    }
}

/// A through-going fault dipping 60° with two horizons offset by `throw` across it (negative:
/// the hanging wall went down, a normal fault). Each horizon is one surface per fault block,
/// reaching past the fault and trimmed at it.
fn fault_with_throw(name: &'static str, throw: f64) -> Case {
    let mut rng = Rng(0x6661_756c_7420_3031 ^ throw.to_bits());
    let mut r = Recipe::new(name);
    let f = fault_y(2000.0, -1000.0, 60.0, (LO, HI), (-2300.0, 300.0), &mut rng);
    r.surface("F", "fault", &f, &PLAIN);
    for (h, z) in [("H1", -700.0), ("H2", -1150.0)] {
        let hw = horizon(z + throw, 25.0, 0.4, &mut rng);
        let fw = horizon(z, 25.0, 0.4, &mut rng);
        r.surface(&format!("{h}_hw"), "horizon", &hw, &DEPTH);
        r.surface(&format!("{h}_fw"), "horizon", &fw, &PLAIN);
        r.keep(&format!("{h}_hw"), "above", "F");
        r.keep(&format!("{h}_fw"), "below", "F");
    }
    // A deviated well from the hanging wall across the fault into the footwall.
    r.well(
        "W",
        &[
            [1400.0, 1910.0, 40.0],
            [1430.0, 1915.0, -500.0],
            [1900.0, 1990.0, -1200.0],
            [2550.0, 2080.0, -1750.0],
        ],
        120.0,
    );
    r.case(&["box", "F", "H1_hw", "H1_fw", "H2_hw", "H2_fw"], 6)
}

/// A listric normal fault F: 70° at the surface, flattening with depth to 20° by 2300 m (the
/// dip falling evenly between), so it meets the box's floor at about 27°, with a rollover: the
/// hanging wall's horizons (150 m down) bend down towards the fault by up to 200 m more. Each
/// horizon is one surface per block, trimmed at the fault; F reaches far past the box so that
/// it lies under or over every point it trims.
fn listric_fault() -> Case {
    let mut rng = Rng(0x6c69_7374_7269_6321);
    let mut r = Recipe::new("listric_fault");
    let dip = |z: f64| (70.0 + 50.0 * z / 2300.0).clamp(20.0, 70.0);
    // x of the fault at depth z: from 3300 m at z = 0, x' = cot(dip) (dipping towards -x),
    // integrated in 10 m steps.
    let fault_x = |z: f64| {
        let (n, sign) = ((z.abs() / 10.0).ceil().max(1.0), z.signum());
        let h = z.abs() / n;
        (0..n as usize).fold(3300.0, |x, k| {
            let mid = sign * (k as f64 + 0.5) * h;
            x + sign * h / dip(mid).to_radians().tan()
        })
    };
    let us = graded_axis(LO, HI, 170.0, 0.9);
    let vs = graded_axis(-4000.0, 3000.0, 150.0, 0.4);
    let f = grid_surface(&us, &vs, |y, z| [fault_x(z), y, z], &mut rng);
    r.surface("F", "fault", &f, &DEPTH);
    for (h, z0, phase) in [("H1", -600.0, 0.2), ("H2", -1200.0, 1.1)] {
        let at = fault_x(z0);
        let (xs, ys) = (
            graded_axis(LO, HI, 160.0, phase),
            graded_axis(LO, HI, 170.0, phase + 1.0),
        );
        let relief = move |x: f64, y: f64| 20.0 * (x / 700.0 + phase).sin() * (y / 900.0).cos();
        let roll = |x: f64| 200.0 * (-(at - x).max(0.0) / 800.0).exp();
        let hw = grid_surface(
            &xs,
            &ys,
            |x, y| [x, y, z0 - 150.0 - roll(x) + relief(x, y)],
            &mut rng,
        );
        let fw = grid_surface(&xs, &ys, |x, y| [x, y, z0 + relief(x, y)], &mut rng);
        r.surface(&format!("{h}_hw"), "horizon", &hw, &PLAIN);
        r.surface(&format!("{h}_fw"), "horizon", &fw, &DEPTH_CRLF);
        r.keep(&format!("{h}_hw"), "above", "F");
        r.keep(&format!("{h}_fw"), "below", "F");
    }
    r.case(&["box", "F", "H1_hw", "H1_fw", "H2_hw", "H2_fw"], 6)
}

/// A meandering channel: a closed sand body 3 km long, 300 m wide and 60 m high at its middle,
/// tapering to a point at both ends, its axis swinging 400 m either side in plan, inside the
/// layer between H1 and H2: a body long and thin where the lens is round.
fn channel(name: &'static str) -> Case {
    use std::f64::consts::TAU;
    let mut rng = Rng(0x6368_616e_6e65_6c21);
    let mut r = Recipe::new(name);
    layer_between(&mut r, (0.6, 0.2), &PLAIN, &mut rng);
    let axis = |t: f64| {
        [
            500.0 + 3000.0 * t,
            2000.0 + 400.0 * (1.5 * TAU * t).sin(),
            -1000.0,
        ]
    };
    let bulge = |t: f64| (4.0 * t * (1.0 - t)).sqrt();
    let point = |t: f64, a: f64| {
        let [x, y, z] = axis(t);
        // The horizontal normal to the axis.
        let (dx, dy): (f64, f64) = (3000.0, 400.0 * 1.5 * TAU * (1.5 * TAU * t).cos());
        let len = dx.hypot(dy);
        let (w, h) = (150.0 * bulge(t), 30.0 * bulge(t));
        [
            x - w * a.cos() * dy / len,
            y + w * a.cos() * dx / len,
            z + h * a.sin(),
        ]
    };
    let c = tube(point, bulge, |_| 0.1, (40, 24), &mut rng);
    r.surface("C", "other", &c, &DEPTH);
    r.case(&["box", "H1", "H2"], 4)
}

/// The channel with its support refined and smoothed (`smooth = true`), as an FE analyst meshing
/// finer than the file's facets would ask.
fn smoothed_channel() -> Case {
    let c = channel("smoothed_channel");
    let other = "kind = \"other\" }";
    assert!(
        c.recipe.contains(other),
        "the channel's body is an `other` surface"
    );
    Case {
        recipe: c.recipe.replace(other, "kind = \"other\", smooth = true }"),
        ..c
    }
}

/// A graben: a master fault F1 (60° east) and an antithetic fault F2 (60° west) ending on it
/// at 1540 m depth, the block between them dropped 150 m: the horizon's footwalls are one
/// surface H whose part in the graben is discarded, the graben's H_g is kept above both faults.
fn graben() -> Case {
    let mut rng = Rng(0x6772_6162_656e_2121);
    let mut r = Recipe::new("graben");
    let block = Block {
        dips: (120.0, 60.0),
        outer_z: -800.0,
        block_z: -950.0,
        side: "above",
    };
    block.draw(&mut r, &mut rng, "H_g", true);
    r.case(&["box", "F1", "F2", "H", "H_g"], 6)
}

/// A fault block between F1 (at x = 1400 m) and F2 (at 2600 m), both at -500 m, with the
/// dips `dips`: the horizon H of the outer blocks at `outer_z`, one surface whose part in the
/// block is discarded; the block's own horizon at `block_z`, kept on `side` of both faults.
struct Block {
    dips: (f64, f64),
    outer_z: f64,
    block_z: f64,
    side: &'static str,
}

impl Block {
    /// Adds F1, F2, H and the block's horizon `inner` to `r`; with `ending`, F2 ends on F1
    /// (kept above it).
    fn draw(&self, r: &mut Recipe, rng: &mut Rng, inner: &str, ending: bool) {
        // Both reach far past the box, so that each lies under or over every point it trims
        // (`above` and `below` look vertically).
        let zs = (-6000.0, 3000.0);
        let f1 = fault_y(1400.0, -500.0, self.dips.0, (LO, HI), zs, rng);
        let f2 = fault_y(2600.0, -500.0, self.dips.1, (LO, HI), zs, rng);
        r.surface("F1", "fault", &f1, &PLAIN);
        r.surface("F2", "fault", &f2, &DEPTH);
        if ending {
            r.keep("F2", "above", "F1");
        }
        let z = self.outer_z;
        r.surface("H", "horizon", &horizon(z, 25.0, 0.5, rng), &PLAIN);
        r.trims.push(format!(
            "[[trim]]\nsurface = \"H\"\ndiscard = {{ nearest = [{}, {}, {z:.1}] }}\n",
            ORIGIN_X + 2000.0,
            ORIGIN_Y + 2000.0
        ));
        let h = horizon(self.block_z, 25.0, 0.2, rng);
        r.surface(inner, "horizon", &h, &PLAIN);
        r.keep(inner, self.side, "F1");
        r.keep(inner, self.side, "F2");
    }
}

/// Layers tilted to 35°, as on a fold's limb: three horizons striking along y, each leaving the
/// box through its top or east side and through its base or west side; of the four regions,
/// the two layers between horizons reach from the box's top to its base.
fn tilted_layers() -> Case {
    let mut rng = Rng(0x7469_6c74_6564_2121);
    let mut r = Recipe::new("tilted_layers");
    let zs = (-2600.0, 600.0);
    for (name, x0) in [("H1", 1200.0), ("H2", 2000.0), ("H3", 2800.0)] {
        let h = fault_y(x0, -1000.0, 35.0, (LO, HI), zs, &mut rng);
        r.surface(name, "horizon", &h, &PLAIN);
    }
    r.case(&["box", "H1", "H2", "H3"], 4)
}

/// A horst: two faults dipping away from each other (F1 60° west, F2 60° east), both through
/// the box, the block between them raised 150 m: the horizon H of the two outer blocks is one
/// surface whose part in the horst is discarded, the horst's H_h is kept below both faults.
fn horst() -> Case {
    let mut rng = Rng(0x686f_7273_7421_2121);
    let mut r = Recipe::new("horst");
    let block = Block {
        dips: (60.0, 120.0),
        outer_z: -950.0,
        block_z: -800.0,
        side: "below",
    };
    block.draw(&mut r, &mut rng, "H_h", false);
    r.case(&["box", "F1", "F2", "H", "H_h"], 6)
}

/// A splay: F2 branches upwards from a through-going fault F1 (60°) along a line at 1300 m
/// depth, 8° steeper than it, and is kept above it (ending on it); a horizon H crosses both.
/// The hanging wall between the two faults is a wedge closing to 8° at the branch line (Table 2's
/// bound): its tets reach 7.4° there.
fn fault_splay() -> Case {
    fault_splay_at("fault_splay", 68.0)
}

/// The splay, with F2 dipping `dip2` degrees.
fn fault_splay_at(name: &'static str, dip2: f64) -> Case {
    let mut rng = Rng(0x7370_6c61_795f_3031);
    let mut r = Recipe::new(name);
    let zs = (-2300.0, 300.0);
    let f1 = fault_y(2000.0, -1300.0, 60.0, (LO, HI), zs, &mut rng);
    r.surface("F1", "fault", &f1, &PLAIN);
    let f2 = fault_y(2000.0, -1300.0, dip2, (LO, HI), zs, &mut rng);
    r.surface("F2", "fault", &f2, &DEPTH);
    r.surface(
        "H",
        "horizon",
        &horizon(-800.0, 25.0, 0.3, &mut rng),
        &PLAIN,
    );
    r.keep("F2", "above", "F1");
    r.case(&["box", "F1", "F2", "H"], 6)
}

/// A layer whose base H2 is drawn onto its top H1 where it thins to nothing, vertex for vertex,
/// as stratigraphic models collapse a pinched-out layer: east of a line the two surfaces are
/// one, west of it the layer thickens to about 150 m at the box's side.
fn zero_thickness_layer() -> Case {
    collapsed_layer("zero_thickness_layer", "H1", "H2", -1060.0, 0.045)
}

/// A layer whose base `base` is drawn onto its top `top` where it has no thickness (the surface
/// whose name sorts first keeps the part they have in common): the base is the top wherever the
/// plane through depth `at_2000` at 2000 m east of the box's west side, rising eastwards by
/// `slope`, is above it, and that plane elsewhere.
pub fn collapsed_layer(
    name: &'static str,
    top: &str,
    base: &str,
    at_2000: f64,
    slope: f64,
) -> Case {
    let mut rng = Rng(0x7a65_726f_5f74_6869);
    let mut r = Recipe::new(name);
    let h1 = horizon(-1000.0, 30.0, 0.5, &mut rng);
    let mut h2 = Surface {
        vertices: h1.vertices.clone(),
        triangles: h1.triangles.clone(),
        corners: h1.corners.clone(),
    };
    for v in &mut h2.vertices {
        v[2] = v[2].min(at_2000 + slope * (v[0] - 2000.0));
    }
    r.surface(top, "horizon", &h1, &PLAIN);
    r.surface(base, "horizon", &h2, &DEPTH);
    r.case(&["box", top, base], 3)
}

/// A ramp-flat thrust F whose flat runs 10 m above a horizon H (a detachment along a weak
/// layer), its ramp rising at 30° from 1500 m east of the box's west side: the slab between
/// them is 10 m thick under the flat and thickens under the ramp.
fn detachment() -> Case {
    let mut rng = Rng(0x6465_7461_6368_3031);
    let mut r = Recipe::new("detachment");
    let ramp = 30f64.to_radians().tan();
    let (us, vs) = (
        graded_axis(LO, HI, 150.0, 0.4),
        graded_axis(LO, HI, 170.0, 0.8),
    );
    let f = grid_surface(
        &us,
        &vs,
        |x, y| [x, y, -1500.0 + ramp * (x - 1500.0).max(0.0)],
        &mut rng,
    );
    r.surface("F", "fault", &f, &PLAIN);
    r.surface(
        "H",
        "horizon",
        &horizon(-1510.0, 3.0, 0.6, &mut rng),
        &PLAIN,
    );
    r.case(&["box", "F", "H"], 3)
}

/// A small fault that dies out inside the middle of three layers, crossing nothing.
fn fault_stopping_in_a_layer() -> Case {
    let mut rng = Rng(0x7374_6f70_7320_7368);
    let mut r = Recipe::new("fault_stops_in_a_layer");
    layer_between(&mut r, (0.1, 0.9), &DEPTH_CRLF, &mut rng);
    let f = fault_y(
        2000.0,
        -1000.0,
        70.0,
        (1200.0, 2800.0),
        (-1200.0, -800.0),
        &mut rng,
    );
    r.surface("F", "fault", &f, &PLAIN);
    r.case(&["box", "H1", "H2"], 3)
}

/// Horizons H1 at 600 m depth (written in `top` style) and H2 at 1400 m, their reliefs at the
/// `phases` given: the layer between holds the faults of the cases that add them.
fn layer_between(r: &mut Recipe, phases: (f64, f64), top: &Style, rng: &mut Rng) {
    r.surface("H1", "horizon", &horizon(-600.0, 30.0, phases.0, rng), top);
    r.surface(
        "H2",
        "horizon",
        &horizon(-1400.0, 30.0, phases.1, rng),
        &PLAIN,
    );
}

/// `s` without the triangles whose centroid `cut` holds: a hole in it.
fn with_hole(s: Surface, cut: impl Fn([f64; 3]) -> bool) -> Surface {
    let centroid = |t: &[usize; 3]| {
        let p = t.map(|v| s.vertices[v]);
        [0, 1, 2].map(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0)
    };
    let triangles = (s.triangles.iter())
        .filter(|t| !cut(centroid(t)))
        .copied()
        .collect();
    Surface { triangles, ..s }
}

/// Two horizons, the lower one H2 with a hole 1.2 km across that nothing fills: the layers above
/// and below H2 would meet through it, which a horizon may not let them do (a fault may), so the
/// model fails naming the hole. Not a corpus case: the build refuses it.
pub fn horizon_with_a_hole() -> Case {
    let mut rng = Rng(0x7769_6e64_6f77_2121);
    let mut r = Recipe::new("horizon_with_a_hole");
    let h1 = horizon(-600.0, 30.0, 0.2, &mut rng);
    r.surface("H1", "horizon", &h1, &PLAIN);
    let round = |p: [f64; 3]| (p[0] - 2100.0).hypot(p[1] - 1900.0) < 600.0;
    let h2 = with_hole(horizon(-1300.0, 40.0, 0.6, &mut rng), round);
    r.surface("H2", "horizon", &h2, &DEPTH);
    r.case(&["box", "H1", "H2"], 2)
}

/// A fault dying out inside a layer, with a hole where its slip was never mapped: an embedded
/// patch with a loop inside its border.
fn fault_with_a_hole() -> Case {
    let mut rng = Rng(0x686f_6c65_2066_6c74);
    let mut r = Recipe::new("fault_with_a_hole");
    layer_between(&mut r, (0.3, 0.8), &PLAIN, &mut rng);
    let f = fault_y(
        2000.0,
        -1000.0,
        65.0,
        (900.0, 3100.0),
        (-1250.0, -750.0),
        &mut rng,
    );
    let hole = |p: [f64; 3]| (p[1] - 2000.0).abs() < 400.0 && (p[2] + 1000.0).abs() < 120.0;
    r.surface("F", "fault", &with_hole(f, hole), &PLAIN);
    r.case(&["box", "H1", "H2"], 3)
}

/// A fault mapped as slip patches that touch only at their corners: 12 × 12 right triangles on
/// a chequerboard inside the layer between H1 and H2, each sharing only vertices with its
/// neighbours, so that each triangle's border is its own free-border curve (432 curves) and
/// every patch is embedded in the layer's region. What a fault stick export or a thresholded
/// slip map looks like; it once cost time quadratic in the number of curves.
fn fault_patches_touching_at_corners() -> Case {
    patches_at_corners_in_a_layer("fault_patches_at_corners", 0x7061_7463_6865_7321, 12, 100.0)
}

/// The same fault as [`fault_patches_touching_at_corners`] mapped five times as finely (60 ×
/// 60 triangles of 20 m, 3,600 patches): the grid's cells are cocircular, so the Delaunay
/// tetrahedralization of the layer splits about half of them along the diagonal through the
/// gap, and each such triangle is recovered by flipping that diagonal. Before, 1,816 of the
/// layer's 5,362 boundary and embedded triangles were missing: the recovery gave way to the
/// advancing front, which failed.
fn dense_fault_patches_touching_at_corners() -> Case {
    patches_at_corners_in_a_layer(
        "dense_fault_patches_at_corners",
        0x6465_6e73_6520_7321,
        60,
        20.0,
    )
}

/// Two horizons (their relief drawn from `seed`) and between them a fault of `k × k` triangles
/// of `d` m touching only at their corners ([`corner_patches`]).
fn patches_at_corners_in_a_layer(name: &'static str, seed: u64, k: usize, d: f64) -> Case {
    let mut rng = Rng(seed);
    let mut r = Recipe::new(name);
    r.surface(
        "H1",
        "horizon",
        &horizon(-600.0, 30.0, 0.4, &mut rng),
        &PLAIN,
    );
    r.surface(
        "H2",
        "horizon",
        &horizon(-1400.0, 30.0, 1.1, &mut rng),
        &PLAIN,
    );
    r.surface("F", "fault", &corner_patches(k, d), &PLAIN);
    r.case(&["box", "H1", "H2"], 3)
}

/// Two faults that die out inside the layer between H1 and H2 and cross each other there: F1
/// striking along y, F2 along x and reaching past F1 on both sides, so that their intersection
/// runs from F2's upper tip line to its lower one. Where a tip line passes through the other
/// fault, one fault is a whole disk round the point and the other a half-disk, so four sheets
/// meet along the intersection and two at its ends: the fault network of a real multi-strand
/// fault file. Both are embedded in the layer's region.
fn dangling_faults_crossing() -> Case {
    let mut rng = Rng(0x6461_6e67_6c65_2078);
    let mut r = Recipe::new("dangling_faults_crossing");
    r.surface(
        "H1",
        "horizon",
        &horizon(-400.0, 30.0, 0.3, &mut rng),
        &PLAIN,
    );
    r.surface(
        "H2",
        "horizon",
        &horizon(-1600.0, 30.0, 1.3, &mut rng),
        &DEPTH,
    );
    let f1 = fault_y(
        2000.0,
        -1000.0,
        70.0,
        (1000.0, 3000.0),
        (-1400.0, -600.0),
        &mut rng,
    );
    r.surface("F1", "fault", &f1, &PLAIN);
    let cot = 1.0 / 75f64.to_radians().tan();
    let us = graded_axis(900.0, 2900.0, 170.0, 1.1);
    let vs = graded_axis(-1200.0, -800.0, 150.0, 0.4);
    let f2 = grid_surface(
        &us,
        &vs,
        |x, z| [x, 2000.0 + (z + 1000.0) * cot, z],
        &mut rng,
    );
    r.surface("F2", "fault", &f2, &DEPTH);
    r.case(&["box", "H1", "H2", "F1", "F2"], 3)
}

/// Two horizons over a fault, H1 carrying standing caps, as a triangulation repaired at
/// T-junctions has them: in every fifth cell split along its a-c diagonal, a vertex a tenth of a
/// percent off the middle of that diagonal towards the cell's fourth corner, and 0.5 m above the
/// surface, splits the far triangle in two; the cap between them and the diagonal, 179.5-179.7°
/// at that vertex, stands at 71-80° to the triangles round it. The caps lie in the box, 500 m or
/// more from the fault and the box's sides. Their edges are no creases: each cap lies on a
/// smooth stretch, so it stands for the horizon (`geom::facets`), and the horizon's patches are
/// those of a horizon without caps; nor is a cap's wall a bend the surface meshes refine at.
fn horizon_with_standing_caps() -> Case {
    standing_caps("horizon_with_standing_caps", |[x, y, _]| {
        let inside = |v: f64| (500.0..3500.0).contains(&v);
        inside(x) && inside(y) && (x - 2000.0).abs() > 500.0
    })
}

/// [`horizon_with_standing_caps`] with caps anywhere, those the box's sides and the fault cut
/// included. Where a curve cuts a cap it climbs the cap's 0.5 m wall and comes down within
/// 0.1 m: no corner of the curve (`model::kinks`); and the pieces of the cap, a needle on its
/// wall among them, stand for the horizon as the cap does.
fn caps_cut_by_curves() -> Case {
    standing_caps("caps_cut_by_curves", |_| true)
}

/// The model of `horizon_with_standing_caps` (in [`cases`]), named `name`, with caps where `at`
/// (given the middle of a cell's diagonal, in the surfaces' own coordinates) says.
pub fn standing_caps(name: &'static str, at: impl Fn([f64; 3]) -> bool) -> Case {
    let mut rng = Rng(0x6361_7073_2121_2121);
    let mut r = Recipe::new(name);
    let f = fault_y(2000.0, -1000.0, 60.0, (LO, HI), (-2300.0, 300.0), &mut rng);
    r.surface("F", "fault", &f, &PLAIN);
    let mut h1 = horizon(-700.0, 40.0, 0.2, &mut rng);
    stand_caps(&mut h1, 5, 0.5, at);
    r.surface("H1", "horizon", &h1, &DEPTH);
    let h2 = horizon(-1300.0, 40.0, 0.6, &mut rng);
    r.surface("H2", "horizon", &h2, &PLAIN);
    r.case(&["box", "F", "H1", "H2"], 6)
}

/// Splits the second triangle `[a, c, d]` of every `every`-th cell of `s` split along a-c (its
/// first triangle `[a, b, c]`) whose diagonal's middle is `at`, at a new vertex m just off that
/// middle towards d and `lift` above it: `[a, c, m]` is then a cap standing off the surface,
/// `[a, m, d]` and `[m, c, d]` the rest of the cell, every edge used once each way as before.
fn stand_caps(s: &mut Surface, every: usize, lift: f64, at: impl Fn([f64; 3]) -> bool) {
    let mut seen = 0;
    let mut out = Vec::with_capacity(s.triangles.len() + s.triangles.len() / every);
    let mut k = 0;
    while k < s.triangles.len() {
        let t = s.triangles[k];
        let next = s.triangles.get(k + 1).copied();
        match next {
            Some([a, c, d]) if a == t[0] && c == t[2] => {
                let p = |i: usize| s.vertices[i];
                let (pa, pc, pd) = (p(a), p(c), p(d));
                let mid = |q: usize| 0.5 * (pa[q] + pc[q]);
                let here = at([mid(0), mid(1), mid(2)]);
                seen += usize::from(here);
                out.push(t);
                if here && seen % every == 0 {
                    let toward = |q: usize| mid(q) + 0.001 * (pd[q] - mid(q));
                    s.vertices.push([toward(0), toward(1), toward(2) + lift]);
                    let m = s.vertices.len() - 1;
                    out.extend([[a, c, m], [a, m, d], [m, c, d]]);
                } else {
                    out.push([a, c, d]);
                }
                k += 2;
            }
            _ => {
                out.push(t);
                k += 1;
            }
        }
    }
    s.triangles = out;
}

/// A flat horizon H1 at z = -600 and below it a horizon H2 domed up so that its apex, one of
/// its vertices, lies exactly on H1: the two surfaces touch at that point only (tangent there),
/// and the layer between them thins to nothing round it. H3 below closes the layer under H2.
/// A touch at one point separates nothing, so the layer is one region, pinched there: the touch
/// point is a node of both surfaces' meshes (without it H2's mesh cut its apex off 16 m under H1
/// at size 250, and the thin wedge left held a 7.75° tet; with it the layer's worst is 11.6°).
fn horizons_touching_at_a_point() -> Case {
    let mut rng = Rng(0x746f_7563_6820_7074);
    let mut r = Recipe::new("horizons_touching_at_a_point");
    r.surface(
        "H1",
        "horizon",
        &horizon(-600.0, 0.0, 0.0, &mut rng),
        &PLAIN,
    );
    let mut h2 = horizon(0.0, 0.0, 0.7, &mut rng);
    let apex = nearest_vertex(&h2, [2000.0, 2000.0]);
    let [cx, cy, _] = h2.vertices[apex];
    for v in &mut h2.vertices {
        let r2 = (v[0] - cx).powi(2) + (v[1] - cy).powi(2);
        v[2] = -1000.0 + 400.0 * (-r2 / 600f64.powi(2)).exp();
    }
    r.surface("H2", "horizon", &h2, &DEPTH);
    r.surface(
        "H3",
        "horizon",
        &horizon(-1500.0, 30.0, 1.9, &mut rng),
        &PLAIN,
    );
    r.case(&["box", "H1", "H2", "H3"], 4)
}

/// As [`horizons_touching_at_a_point`], with H2 a ridge whose crest, a column of its vertices
/// (a zigzag chain of its edges, as jittered), lies exactly on H1: they touch along that line,
/// which cuts the layer between them into a west and an east region.
fn horizons_touching_along_a_line() -> Case {
    let mut rng = Rng(0x746f_7563_6820_6c6e);
    let mut r = Recipe::new("horizons_touching_along_a_line");
    r.surface(
        "H1",
        "horizon",
        &horizon(-600.0, 0.0, 0.0, &mut rng),
        &DEPTH,
    );
    let mut h2 = horizon(0.0, 0.0, 0.2, &mut rng);
    // The grid's width (its second corner is the end of the first row) and the crest column.
    let width = h2.corners[1] + 1;
    let column = nearest_vertex(&h2, [2000.0, 2000.0]) % width;
    for (i, v) in h2.vertices.iter_mut().enumerate() {
        let k = i % width;
        let dx = 200.0 * (k as f64 - column as f64);
        v[2] = match k == column {
            true => -600.0,
            false => -1000.0 + 400.0 * (-dx.powi(2) / 600f64.powi(2)).exp(),
        };
    }
    r.surface("H2", "horizon", &h2, &PLAIN);
    r.surface(
        "H3",
        "horizon",
        &horizon(-1500.0, 30.0, 2.3, &mut rng),
        &DEPTH,
    );
    r.case(&["box", "H1", "H2", "H3"], 5)
}

/// The vertex of `s` nearest `(x, y)` in plan.
fn nearest_vertex(s: &Surface, [x, y]: [f64; 2]) -> usize {
    let d = |v: &[f64; 3]| (v[0] - x).powi(2) + (v[1] - y).powi(2);
    (0..s.vertices.len())
        .min_by(|&a, &b| d(&s.vertices[a]).total_cmp(&d(&s.vertices[b])))
        .unwrap_or(0)
}

/// `k × k` right triangles of leg `d` on a chequerboard in a plane dipping 60° to the east,
/// centred in the box at 1000 m depth; triangle (i, j) spans grid points (i, j), (i+1, j) and
/// (i, j+1), so neighbours share one vertex and no edge.
fn corner_patches(k: usize, d: f64) -> Surface {
    let cot = 1.0 / 60f64.to_radians().tan();
    let at = |i: usize, j: usize| {
        let (u, v) = (
            i as f64 * d - k as f64 * d / 2.0,
            j as f64 * d - k as f64 * d / 2.0,
        );
        [2000.0 + v * cot * 0.5, 2000.0 + u, -1000.0 + v * 0.5]
    };
    let index = |i: usize, j: usize| i * (k + 1) + j;
    let vertices = (0..=k)
        .flat_map(|i| (0..=k).map(move |j| (i, j)))
        .map(|(i, j)| at(i, j));
    let triangles = (0..k)
        .flat_map(|i| (0..k).map(move |j| (i, j)))
        .map(|(i, j)| [index(i, j), index(i + 1, j), index(i, j + 1)])
        .collect();
    Surface {
        vertices: vertices.collect(),
        triangles,
        corners: Vec::new(),
    }
}

/// An erosional surface U cutting down to the east through horizon H1 (which is kept only below
/// U), above an untouched H2: above U, the wedge between U and H1, the layer between H1 (or U)
/// and H2, and below H2. U dips at atan(0.15) = 8.5°, but with U's undulation and H1's relief
/// the surface meshes of U and H1 meet along the wedge's tip at 7.1° to 10.2° (median 9.3°,
/// measured between the two triangles on each tip edge at the recipe's 250 m): the tets at the
/// tip cannot beat 7.1° there (Table 2's bound), and the mesher reaches it.
fn erosional_unconformity() -> Case {
    let mut rng = Rng(0x756e_636f_6e66_6f72);
    let mut r = Recipe::new("erosional_unconformity");
    let us = graded_axis(LO, HI, 160.0, 0.5);
    let vs = graded_axis(LO, HI, 170.0, 1.5);
    let u = grid_surface(
        &us,
        &vs,
        |x, y| [x, y, -700.0 - 0.15 * x + 20.0 * (y / 800.0).sin()],
        &mut rng,
    );
    r.surface("U", "horizon", &u, &DEPTH);
    r.surface(
        "H1",
        "horizon",
        &horizon(-1000.0, 20.0, 0.2, &mut rng),
        &PLAIN,
    );
    r.surface(
        "H2",
        "horizon",
        &horizon(-1600.0, 20.0, 1.2, &mut rng),
        &PLAIN,
    );
    r.keep("H1", "below", "U");
    r.case(&["box", "U", "H1", "H2"], 4)
}

/// A normal fault F (60°) offsetting a horizon by 150 m and ending upwards on an unconformity U
/// above, which erosion left gently dipping and unfaulted: F is kept below U, the horizon's two
/// blocks each beside F, and the layer above U is whole.
fn fault_under_an_unconformity() -> Case {
    let mut rng = Rng(0x756e_6465_7220_5521);
    let mut r = Recipe::new("fault_under_an_unconformity");
    let f = fault_y(2000.0, -1000.0, 60.0, (LO, HI), (-6000.0, 3000.0), &mut rng);
    r.surface("F", "fault", &f, &PLAIN);
    let (us, vs) = (
        graded_axis(LO, HI, 160.0, 0.9),
        graded_axis(LO, HI, 170.0, 0.1),
    );
    let u = grid_surface(
        &us,
        &vs,
        |x, y| [x, y, -600.0 - 0.05 * x + 15.0 * (y / 700.0).sin()],
        &mut rng,
    );
    r.surface("U", "horizon", &u, &DEPTH);
    r.keep("F", "below", "U");
    let hw = horizon(-1250.0, 25.0, 0.7, &mut rng);
    let fw = horizon(-1100.0, 25.0, 0.7, &mut rng);
    r.surface("H_hw", "horizon", &hw, &PLAIN);
    r.surface("H_fw", "horizon", &fw, &DEPTH_CRLF);
    r.keep("H_hw", "above", "F");
    r.keep("H_fw", "below", "F");
    r.case(&["box", "F", "U", "H_hw", "H_fw"], 5)
}

/// A relay ramp: two en-echelon faults 300 m apart, overlapping over 800 m along strike, each
/// dying out inside the box, both cutting a horizon that ramps between them unbroken: two slits
/// in the horizon, side by side, and the faults' free edges dangling in both layers.
fn relay_ramp() -> Case {
    let mut rng = Rng(0x7265_6c61_7920_7221);
    let mut r = Recipe::new("relay_ramp");
    let zs = (-2300.0, 300.0);
    let fa = fault_y(1800.0, -1000.0, 70.0, (LO, 2400.0), zs, &mut rng);
    let fb = fault_y(2100.0, -1000.0, 70.0, (1600.0, HI), zs, &mut rng);
    r.surface("Fa", "fault", &fa, &PLAIN);
    r.surface("Fb", "fault", &fb, &DEPTH);
    r.surface(
        "H",
        "horizon",
        &horizon(-1000.0, 25.0, 0.4, &mut rng),
        &PLAIN,
    );
    r.case(&["box", "Fa", "Fb", "H"], 2)
}

/// Two faults crossing (F1 striking along y, F2 along x) and one horizon H, with F2 and H
/// written in the given styles.
fn two_faults(name: &'static str, seed: u64, f2: &Style, h: &Style) -> Recipe {
    let mut rng = Rng(seed);
    let mut r = Recipe::new(name);
    let f1 = fault_y(2000.0, -1000.0, 70.0, (LO, HI), (-2300.0, 300.0), &mut rng);
    r.surface("F1", "fault", &f1, &PLAIN);
    r.surface("F2", "fault", &fault_x(2000.0, -1000.0, 75.0, &mut rng), f2);
    r.surface("H", "horizon", &horizon(-1000.0, 30.0, 0.6, &mut rng), h);
    r
}

/// Two through-going faults crossing in an X (strikes along y and along x), one horizon.
fn x_fault_junction() -> Case {
    let r = two_faults("x_fault_junction", 0x785f_6a75_6e63_7469, &PLAIN, &DEPTH);
    r.case(&["box", "F1", "F2", "H"], 8)
}

/// A fault F2 that ends on a through-going fault F1 (kept on F1's east side only), one horizon.
fn y_fault_junction() -> Case {
    let mut r = two_faults("y_fault_junction", 0x795f_6a75_6e63_7469, &DEPTH, &PLAIN);
    r.keep("F2", "below", "F1");
    r.case(&["box", "F1", "F2", "H"], 6)
}

/// A point along a Z-shaped section through a recumbent fold, `s` in [0, 1]: a lower limb east at
/// z = -1400 to x = 3000, a hinge turning up to an overturned limb running back west at z = -1000
/// to x = 1000, a second hinge, and an upper limb east at z = -600 past the box.
fn z_fold(s: f64) -> (f64, f64) {
    use std::f64::consts::PI;
    let r = 200.0;
    let legs = [3300.0, PI * r, 2000.0, PI * r, 3300.0];
    let total: f64 = legs.iter().sum();
    let mut d = s * total;
    if d <= legs[0] {
        return (-300.0 + d, -1400.0);
    }
    d -= legs[0];
    if d <= legs[1] {
        let a = d / r;
        return (3000.0 + r * a.sin(), -1200.0 - r * a.cos());
    }
    d -= legs[1];
    if d <= legs[2] {
        return (3000.0 - d, -1000.0);
    }
    d -= legs[2];
    if d <= legs[3] {
        let a = d / r;
        return (1000.0 - r * a.sin(), -800.0 - r * a.cos());
    }
    d -= legs[3];
    (1000.0 + d, -600.0)
}

/// A horizon folded into a recumbent (overturned) Z fold, cutting the box in two. Its hinges
/// (radius 200 m, triangles of about 120 m) bend by more than the kink angle from triangle to
/// triangle, so they are cut into narrow strips between creases.
fn recumbent_fold() -> Case {
    let mut rng = Rng(0x7265_6375_6d62_656e);
    let mut r = Recipe::new("recumbent_fold");
    let us = graded_axis(0.0, 1.0, 0.012, 0.3);
    let vs = graded_axis(LO, HI, 170.0, 0.9);
    let h = grid_surface(
        &us,
        &vs,
        |s, y| {
            let (x, z) = z_fold(s);
            [x, y, z + 15.0 * (y / 700.0).sin()]
        },
        &mut rng,
    );
    r.surface("H", "horizon", &h, &DEPTH);
    r.case(&["box", "H"], 2)
}

/// How far (a fraction of the ring spacing) the points of the ring at `t` are jittered along the
/// profile: a fifth of the spacing, but never more than two fifths of the spacing of the points
/// around the ring, so that the long thin triangles near a pole do not fold over each other.
fn along_jitter(
    profile: &impl Fn(f64) -> (f64, f64),
    t: f64,
    (scale, nt, na): (f64, usize, usize),
) -> f64 {
    let step = 1.0 / nt as f64;
    let (r, z) = profile(t);
    let spacing = |u: f64| {
        let (ru, zu) = profile(u.clamp(0.0, 1.0));
        ((ru - r) * scale).hypot(zu - z)
    };
    let along = spacing(t - step).min(spacing(t + step));
    let around = std::f64::consts::TAU * r.abs() * scale / na as f64;
    0.2 * (2.0 * around / along).min(1.0)
}

/// A surface of revolution about the vertical line through `(cx, cy)`, stretched by `(sx, sy)`
/// in plan: `profile(t)` gives the radius and height for `t` in [0, 1] over `nt` rings of `na`
/// points. An end whose radius is zero is closed by one pole vertex; any other end is a border.
/// Triangles face outwards (away from the axis) when z decreases with `t`. Ring heights and
/// angles are jittered like the grids, and the quad diagonals are chosen by the seeded generator.
fn revolution(
    (cx, cy): (f64, f64),
    (sx, sy): (f64, f64),
    profile: impl Fn(f64) -> (f64, f64),
    (nt, na): (usize, usize),
    rng: &mut Rng,
) -> Surface {
    let point = |t: f64, a: f64| {
        let (r, z) = profile(t);
        [cx + sx * r * a.cos(), cy + sy * r * a.sin(), z]
    };
    let along = |t: f64| along_jitter(&profile, t, (sx.min(sy), nt, na));
    tube(point, |t| profile(t).0, along, (nt, na), rng)
}

/// A tube of `nt` rings of `na` points: `point(t, a)` for `t` in [0, 1] and `a` round the ring;
/// a ring whose `radius(t)` is zero is one pole vertex, closing that end; any other end is a
/// border. Inner rings are jittered along the tube by up to `along(t)` of a ring's spacing and
/// round it, and the quad diagonals are chosen by the seeded generator.
fn tube(
    point: impl Fn(f64, f64) -> [f64; 3],
    radius: impl Fn(f64) -> f64,
    along: impl Fn(f64) -> f64,
    (nt, na): (usize, usize),
    rng: &mut Rng,
) -> Surface {
    use std::f64::consts::TAU;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    let ring = |t: f64, jitter: bool, vertices: &mut Vec<[f64; 3]>, rng: &mut Rng| {
        let first = vertices.len();
        if radius(t).abs() < 1e-9 {
            vertices.push(point(t, 0.0));
            return (first, 1);
        }
        let shift = if jitter { 0.5 * rng.unit() } else { 0.0 };
        let along = along(t);
        for k in 0..na {
            let tj = if jitter {
                t + along * rng.unit() / nt as f64
            } else {
                t
            };
            let a = (k as f64 + shift + 0.2 * rng.unit()) * TAU / na as f64;
            vertices.push(point(tj, a));
        }
        (first, na)
    };
    let mut rings = Vec::with_capacity(nt + 1);
    for i in 0..=nt {
        let t = i as f64 / nt as f64;
        rings.push(ring(t, i > 0 && i < nt, &mut vertices, rng));
    }
    for w in rings.windows(2) {
        let ((a, na_a), (b, na_b)) = (w[0], w[1]);
        for k in 0..na {
            let (a0, a1) = (a + k % na_a, a + (k + 1) % na_a);
            let (b0, b1) = (b + k % na_b, b + (k + 1) % na_b);
            if na_a == 1 {
                triangles.push([a0, b0, b1]);
            } else if na_b == 1 {
                triangles.push([a0, b0, a1]);
            } else if rng.next_u64() & 1 == 0 {
                triangles.push([a0, b0, b1]);
                triangles.push([a0, b1, a1]);
            } else {
                triangles.push([a0, b0, a1]);
                triangles.push([a1, b0, b1]);
            }
        }
    }
    Surface {
        vertices,
        triangles,
        corners: Vec::new(),
    }
}

/// A closed lens of sand (an ellipsoid 1800 x 1200 x 300 m, coarsely faceted) inside the middle
/// of three layers, touching nothing: its own region, and an inner shell of its host. Thinner
/// than the mesh size, it asks for two layers (`min_layers = 2`), as the build's warning says.
/// Its rim bends by 30-70° between facet rows, so creases cut it into needle patches whose
/// triangles have angles down to 4.5°: tets on them reach 7.5°, not 8.
fn lens() -> Case {
    let mut rng = Rng(0x6c65_6e73_2020_2020);
    let mut r = Recipe::new("lens");
    r.surface(
        "H1",
        "horizon",
        &horizon(-600.0, 30.0, 0.1, &mut rng),
        &PLAIN,
    );
    r.surface(
        "H2",
        "horizon",
        &horizon(-1400.0, 30.0, 0.9, &mut rng),
        &DEPTH,
    );
    let l = lens_surface((2100.0, 1900.0), -1000.0, 150.0, &mut rng);
    r.surface("L", "other", &l, &PLAIN);
    // A vertical well through the lens, off its axis.
    r.well(
        "W",
        &[[2040.0, 1960.0, 30.0], [2040.0, 1960.0, -1800.0]],
        100.0,
    );
    with_two_layers(r.case(&["box", "H1", "H2"], 4))
}

/// A closed lens cut by a normal fault F (60°, through the box) with 100 m of throw: the
/// horizons and the lens are each one surface per block (the hanging wall's drawn 100 m lower),
/// kept on their side of F, so each half of the lens is a body closed by the fault. Eight
/// regions: three layers per block and the lens's two halves.
fn lens_cut_by_a_fault() -> Case {
    let mut rng = Rng(0x6c65_6e73_2066_6c74);
    let mut r = Recipe::new("lens_cut_by_a_fault");
    // Far past the box, so that it lies under or over every point it trims (`above` and
    // `below` look vertically).
    let f = fault_y(2000.0, -1000.0, 60.0, (LO, HI), (-4000.0, 2000.0), &mut rng);
    r.surface("F", "fault", &f, &PLAIN);
    for (h, z) in [("H1", -600.0), ("H2", -1400.0)] {
        let hw = horizon(z - 100.0, 25.0, 0.4, &mut rng);
        let fw = horizon(z, 25.0, 0.4, &mut rng);
        r.surface(&format!("{h}_hw"), "horizon", &hw, &PLAIN);
        r.surface(&format!("{h}_fw"), "horizon", &fw, &DEPTH);
        r.keep(&format!("{h}_hw"), "above", "F");
        r.keep(&format!("{h}_fw"), "below", "F");
    }
    let hw = lens_surface((2100.0, 1900.0), -1100.0, 150.0, &mut rng);
    let fw = lens_surface((2100.0, 1900.0), -1000.0, 150.0, &mut rng);
    r.surface("L_hw", "other", &hw, &PLAIN);
    r.surface("L_fw", "other", &fw, &PLAIN);
    r.keep("L_hw", "above", "F");
    r.keep("L_fw", "below", "F");
    r.case(
        &[
            "box", "F", "H1_hw", "H1_fw", "H2_hw", "H2_fw", "L_hw", "L_fw",
        ],
        8,
    )
}

/// A closed lens 1800 x 1200 m in plan centred at `c`, `half` thick above and below `z`,
/// faceted in 14 rings of 40 points.
fn lens_surface(c: (f64, f64), z: f64, half: f64, rng: &mut Rng) -> Surface {
    use std::f64::consts::PI;
    revolution(
        c,
        (900.0, 600.0),
        |t| ((PI * t).sin(), z + half * (PI * t).cos()),
        (14, 40),
        rng,
    )
}

/// `case` asking two layers of elements across every region (`min_layers = 2`), as the build's
/// warning says of a lens thinner than the mesh size; its rim's needle patches hold its tets to
/// 7°.
fn with_two_layers(case: Case) -> Case {
    Case {
        recipe: case
            .recipe
            .replace("size = 250.0\n", "size = 250.0\nmin_layers = 2\n"),
        min_dihedral: 7.0,
        ..case
    }
}

/// A vertical tube (a cylinder of radius 400 m, a well's damaged zone or a volcanic pipe) through
/// the box and one horizon: inside and outside the tube, above and below the horizon.
fn vertical_tube() -> Case {
    let mut rng = Rng(0x7475_6265_2020_2020);
    let mut r = Recipe::new("vertical_tube");
    r.surface(
        "H",
        "horizon",
        &horizon(-1000.0, 30.0, 0.3, &mut rng),
        &PLAIN,
    );
    let t = revolution(
        (2000.0, 2000.0),
        (400.0, 400.0),
        |t| (1.0, 300.0 - 2600.0 * t),
        (18, 24),
        &mut rng,
    );
    r.surface("T", "other", &t, &DEPTH);
    r.case(&["box", "H", "T"], 4)
}

/// The profile of a salt body: a round cap of radius 700 m at `top`, vertical walls below it
/// down to `bottom`, closed there by a second cap when `closed` (`top - bottom` must exceed the
/// caps' height).
fn salt_profile(t: f64, top: f64, bottom: f64, closed: bool) -> (f64, f64) {
    use std::f64::consts::FRAC_PI_2;
    let r = 700.0;
    let cap = FRAC_PI_2 * r;
    let wall = top - bottom - if closed { 2.0 * r } else { r };
    let total = cap + wall + if closed { cap } else { 0.0 };
    let d = t * total;
    if d <= cap {
        let a = d / r;
        return (a.sin(), top - r + r * a.cos());
    }
    if d <= cap + wall {
        return (1.0, top - r - (d - cap));
    }
    let a = (d - cap - wall) / r;
    (a.cos(), top - r - wall - r * a.sin())
}

/// Two horizons pierced by a salt stock of `salt`'s shape, each horizon's disk inside the salt
/// discarded (the nearest patch to the stock's axis on it).
/// With `well`, a well beside the salt turns into its flank and ends inside it.
fn salt_case(
    name: &'static str,
    seed: u64,
    (top, bottom): (f64, f64),
    closed: bool,
    well: bool,
) -> Case {
    salt_case_at(name, seed, (top, bottom), closed, well, (2000.0, 2100.0))
}

/// As [`salt_case`], the salt's axis at `(cx, cy)`.
fn salt_case_at(
    name: &'static str,
    seed: u64,
    (top, bottom): (f64, f64),
    closed: bool,
    well: bool,
    (cx, cy): (f64, f64),
) -> Case {
    let mut rng = Rng(seed);
    let mut r = Recipe::new(name);
    for (h, z, style) in [("H1", -900.0, &PLAIN), ("H2", -1400.0, &DEPTH)] {
        r.surface(h, "horizon", &horizon(z, 30.0, 0.5, &mut rng), style);
        r.trims.push(format!(
            "[[trim]]\nsurface = \"{h}\"\ndiscard = {{ nearest = [{}, {}, {z}] }}\n",
            ORIGIN_X + cx,
            ORIGIN_Y + cy
        ));
    }
    let s = revolution(
        (cx, cy),
        (1.0, 1.0),
        |t| {
            let (rr, z) = salt_profile(t, top, bottom, closed);
            (700.0 * rr, z)
        },
        (30, 36),
        &mut rng,
    );
    r.surface("SALT", "other", &s, &PLAIN);
    if well {
        r.well(
            "W",
            &[
                [2930.0, 2130.0, 25.0],
                [2930.0, 2130.0, -700.0],
                [2640.0, 2110.0, -1050.0],
                [2310.0, 2090.0, -1250.0],
            ],
            100.0,
        );
    }
    r.case(&["box", "H1", "H2", "SALT"], 4)
}

/// A salt stock rising from below the box through two horizons to a round top at -500 m, with
/// a well into its flank.
fn salt_stock() -> Case {
    salt_case(
        "salt_stock",
        0x7361_6c74_2073_746b,
        (-500.0, -2300.0),
        false,
        true,
    )
}

/// The closed diapir with a well through the overburden into its flank: the salt region's
/// recovery holes (thin slabs under its curved top) must be filled without falling back to the
/// front, which embeds no well.
fn closed_salt_diapir_with_well() -> Case {
    salt_case(
        "closed_salt_diapir_with_well",
        0x7361_6c74_2064_6970,
        (-300.0, -1900.0),
        true,
        true,
    )
}

/// The closed diapir with its axis 300 m inside the box's east side, so the side cuts off its
/// eastern 400 m: a closed body opened by the box, its border a loop on the side. Still four
/// regions, the salt's bounded by the salt and that side. The side clips one of the dome's
/// charts near its tip, leaving a wedge 6 m wide on the cut between long seams.
fn salt_dome_cut_by_the_box() -> Case {
    salt_case_at(
        "salt_dome_cut_by_the_box",
        0x7361_6c74_2063_7574,
        (-300.0, -1900.0),
        true,
        false,
        (3700.0, 2100.0),
    )
}

/// A closed salt diapir from -1900 m to -300 m, inside the box, piercing both horizons.
fn closed_salt_diapir() -> Case {
    salt_case(
        "closed_salt_diapir",
        0x7361_6c74_2064_6970,
        (-300.0, -1900.0),
        true,
        false,
    )
}

/// A closed salt body shaped like a mushroom: a round cap 900 m wide at -300 m over an overhang
/// whose underside curves in to a stem of radius 350 m, closed at -1900 m. H1 meets the salt on
/// the overhang's underside (facing down), H2 on the stem; each horizon's disk inside the salt
/// is discarded.
fn salt_overhang() -> Case {
    use std::f64::consts::FRAC_PI_2;
    let mut rng = Rng(0x6f76_6572_6861_6e67);
    let mut r = Recipe::new("salt_overhang");
    let (cx, cy) = (2000.0, 2000.0);
    for (h, z, style) in [("H1", -700.0, &PLAIN), ("H2", -1300.0, &DEPTH)] {
        r.surface(h, "horizon", &horizon(z, 30.0, 0.5, &mut rng), style);
        r.trims.push(format!(
            "[[trim]]\nsurface = \"{h}\"\ndiscard = {{ nearest = [{}, {}, {z}] }}\n",
            ORIGIN_X + cx,
            ORIGIN_Y + cy
        ));
    }
    let profile = |t: f64| {
        let legs = [0.36, 0.22, 0.28, 0.14];
        if t <= legs[0] {
            let a = t / legs[0] * FRAC_PI_2;
            return (900.0 * a.sin(), -550.0 + 250.0 * a.cos());
        }
        let t = t - legs[0];
        if t <= legs[1] {
            let b = t / legs[1] * FRAC_PI_2;
            return (350.0 + 550.0 * b.cos(), -550.0 - 300.0 * b.sin());
        }
        let t = t - legs[1];
        if t <= legs[2] {
            return (350.0, -850.0 - 850.0 * t / legs[2]);
        }
        let c = ((t - legs[2]) / legs[3]).min(1.0) * FRAC_PI_2;
        (350.0 * c.cos(), -1700.0 - 200.0 * c.sin())
    };
    let s = revolution((cx, cy), (1.0, 1.0), profile, (34, 36), &mut rng);
    r.surface("SALT", "other", &s, &PLAIN);
    r.case(&["box", "H1", "H2", "SALT"], 4)
}

/// The closed salt diapir with a raft of sediment (a closed lens 500 x 400 x 120 m) floating
/// inside the salt: the raft is its own region, and an inner shell of the salt's (a body inside
/// a body that pierces the horizons).
fn raft_in_salt() -> Case {
    use std::f64::consts::PI;
    let mut case = closed_salt_diapir();
    let mut rng = Rng(0x7261_6674_2020_2020);
    let raft = revolution(
        (2000.0, 2100.0),
        (250.0, 200.0),
        |t| ((PI * t).sin(), -1100.0 + 60.0 * (PI * t).cos()),
        (10, 24),
        &mut rng,
    );
    case.files
        .push(("RAFT.ts".to_string(), write_tsurf("RAFT", &raft, &PLAIN)));
    case.recipe = case.recipe.replace(
        "SALT = {",
        "RAFT = { file = \"data/RAFT.ts\", kind = \"other\" }\nSALT = {",
    );
    Case {
        name: "raft_in_salt",
        recipe: case.recipe.replace("closed_salt_diapir", "raft_in_salt"),
        regions: 5,
        ..case
    }
}

/// Two closed lenses in the middle of three layers, overlapping in plan and 100 m apart in
/// depth: the host has two inner shells.
fn two_lenses() -> Case {
    let mut rng = Rng(0x7477_6f20_6c65_6e73);
    let mut r = Recipe::new("two_lenses");
    r.surface(
        "H1",
        "horizon",
        &horizon(-500.0, 30.0, 0.1, &mut rng),
        &PLAIN,
    );
    r.surface(
        "H2",
        "horizon",
        &horizon(-1500.0, 30.0, 0.9, &mut rng),
        &DEPTH,
    );
    for (name, c, z) in [
        ("L1", (1500.0, 1600.0), -850.0),
        ("L2", (2500.0, 2400.0), -1150.0),
    ] {
        let l = lens_surface(c, z, 100.0, &mut rng);
        r.surface(name, "other", &l, &PLAIN);
    }
    with_two_layers(r.case(&["box", "H1", "H2"], 5))
}

/// A younger intrusion `B` cutting an older body `A` below a horizon, modelled as two closed
/// bodies that overlap (as a geomodeller builds each on its own): `A`'s part inside `B` is
/// discarded (`keep = { outside = "B" }`), so the overlap belongs to `B` alone. Regions: above
/// the horizon, the host below it, `B`, and what is left of `A`.
fn intrusion_cutting_a_body() -> Case {
    let mut rng = Rng(0x696e_7472_7573_696f);
    let mut r = Recipe::new("intrusion_cutting_a_body");
    r.surface(
        "H",
        "horizon",
        &horizon(-500.0, 30.0, 0.4, &mut rng),
        &PLAIN,
    );
    r.surface(
        "A",
        "other",
        &body((1700.0, 2000.0), 650.0, (-1100.0, 500.0), &mut rng),
        &PLAIN,
    );
    r.surface(
        "B",
        "other",
        &body((2450.0, 2100.0), 550.0, (-1000.0, 450.0), &mut rng),
        &DEPTH,
    );
    r.trims
        .push("[[trim]]\nsurface = \"A\"\nkeep = { outside = \"B\" }\n".to_string());
    r.case(&["box", "H", "A", "B"], 4)
}

/// A closed body: an ellipsoid of revolution centred at `c` in plan and `z` in height, of
/// radius `radius` and half height `half`, faceted in 24 rings of 64 points.
fn body(c: (f64, f64), radius: f64, (z, half): (f64, f64), rng: &mut Rng) -> Surface {
    use std::f64::consts::PI;
    revolution(
        c,
        (radius, radius),
        |t| ((PI * t).sin(), z + half * (PI * t).cos()),
        (24, 64),
        rng,
    )
}

/// Two horizons folded into a chevron anticline: straight limbs dipping 39° meeting at a sharp
/// hinge along x = 2000 m, so each horizon's support bends by 77° across one row of triangles;
/// the creases that bend are curves of the model, so the FE surfaces keep the hinge.
fn chevron_fold() -> Case {
    let mut rng = Rng(0x6368_6576_726f_6e20);
    let mut r = Recipe::new("chevron_fold");
    for (h, z0, style) in [("H1", -700.0, &PLAIN), ("H2", -1100.0, &DEPTH)] {
        let us = graded_axis(LO, HI, 150.0, 0.2);
        let vs = graded_axis(LO, HI, 170.0, 0.8);
        let s = grid_surface(
            &us,
            &vs,
            |x, y| {
                [
                    x,
                    y,
                    z0 - 0.8 * (x - 2000.0).abs() + 20.0 * (y / 800.0).sin(),
                ]
            },
            &mut rng,
        );
        r.surface(h, "horizon", &s, style);
    }
    r.case(&["box", "H1", "H2"], 3)
}

/// A through-going fault dipping 60° that cuts a closed salt diapir in two: the salt is two
/// regions, one on each side of the fault, and so is its host. The revolved wall's jittered rows
/// hold caps standing at 89-118° to the wall round them (a needle of 1.2 m by 12 m and tets of
/// 5.7° while their edges were creases).
fn fault_through_salt() -> Case {
    let mut rng = Rng(0x6661_756c_7473_6c74);
    let mut r = Recipe::new("fault_through_salt");
    let f = fault_y(2100.0, -1000.0, 60.0, (LO, HI), (-2300.0, 300.0), &mut rng);
    r.surface("F", "fault", &f, &PLAIN);
    let s = revolution(
        (2000.0, 2100.0),
        (1.0, 1.0),
        |t| {
            let (rr, z) = salt_profile(t, -300.0, -1900.0, true);
            (700.0 * rr, z)
        },
        (30, 36),
        &mut rng,
    );
    r.surface("SALT", "other", &s, &DEPTH);
    r.case(&["box", "F", "SALT"], 4)
}

/// A horizon H1 onlapping an unconformity U: both bend alike (a dome-and-basin relief of 120 m),
/// H1 rises westwards to meet U at `slope` and is kept below it, above an untouched H2. Where
/// two triangulated surfaces meet at so small an angle, their facets cross each other again and
/// again near the tip: the curves where they meet come in pieces metres apart.
fn onlap(name: &'static str, slope: f64) -> Case {
    lap(name, slope, Lap::On)
}

/// The onlap upside down: H1 sinks westwards onto a surface U below it (a downlap onto a
/// basin floor), is kept above it, and an untouched H0 lies above both.
fn downlap(name: &'static str, slope: f64) -> Case {
    lap(name, slope, Lap::Down)
}

/// Which way H1 meets U.
#[derive(Clone, Copy, PartialEq)]
enum Lap {
    /// Rising onto U from below.
    On,
    /// Sinking onto U from above.
    Down,
}

fn lap(name: &'static str, slope: f64, lap: Lap) -> Case {
    let mut rng = Rng(0x7069_6e63_685f_6f75);
    let mut r = Recipe::new(name);
    let relief = |x: f64, y: f64| -1000.0 + 120.0 * (x / 900.0).sin() * (y / 1100.0).cos();
    let (us, vs) = (
        graded_axis(LO, HI, 160.0, 0.5),
        graded_axis(LO, HI, 170.0, 1.5),
    );
    let u = grid_surface(&us, &vs, |x, y| [x, y, relief(x, y)], &mut rng);
    r.surface("U", "horizon", &u, &DEPTH);
    let (us, vs) = (
        graded_axis(LO, HI, 150.0, 0.9),
        graded_axis(LO, HI, 180.0, 0.2),
    );
    let rise = if lap == Lap::On { -slope } else { slope };
    let h1 = |x: f64, y: f64| [x, y, relief(x, y) + rise * (x - 2000.0)];
    r.surface(
        "H1",
        "horizon",
        &grid_surface(&us, &vs, h1, &mut rng),
        &PLAIN,
    );
    let (other, z, side) = match lap {
        Lap::On => ("H2", -1600.0, "below"),
        Lap::Down => ("H0", -400.0, "above"),
    };
    r.surface(other, "horizon", &horizon(z, 20.0, 1.2, &mut rng), &PLAIN);
    r.keep("H1", side, "U");
    r.case(&["box", "U", "H1", other], 4)
}
