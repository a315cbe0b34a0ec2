//! A geometric fuzzer: the shipped example with one of its surfaces perturbed the ways real data
//! is (vertices jittered, a triangle collapsed, one flipped, a vertex dragged across the next
//! surface, a surface given as a triangle soup), built through the command line.
//!
//! Each build finishes within ten times the unperturbed build's time (plus a margin for a
//! machine busy with the other tests), and either writes a mesh that the independent checker
//! passes with the regions its quality tables list, or fails with a message that points at a
//! line of the recipe or of a surface file. The perturbations are seeded: every run builds the
//! same files.

use crate::common_cli::*;
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

/// A deterministic generator (xorshift64*), uniform in `[-1, 1)`.
struct Noise(u64);

impl Noise {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        bits as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// The lines of a TSurf file, to edit its records.
struct TSurf {
    lines: Vec<String>,
}

impl TSurf {
    fn read(path: &Path) -> TSurf {
        let text = std::fs::read_to_string(path).expect("the example's surface");
        TSurf {
            lines: text.lines().map(String::from).collect(),
        }
    }
    fn write(&self, path: &Path) {
        std::fs::write(path, self.lines.join("\n") + "\n").expect("write the surface");
    }
    fn indices(&self, keyword: &str) -> Vec<usize> {
        (0..self.lines.len())
            .filter(|&i| self.lines[i].split_whitespace().next() == Some(keyword))
            .collect()
    }
    fn fields(&self, i: usize) -> Vec<String> {
        self.lines[i].split_whitespace().map(String::from).collect()
    }
    /// The vertex record with id `id`.
    fn vertex(&self, id: &str) -> usize {
        self.indices("VRTX")
            .into_iter()
            .find(|&i| self.fields(i)[1] == id)
            .expect("the vertex exists")
    }
    fn move_vertex(&mut self, i: usize, to: [f64; 3]) {
        let f = self.fields(i);
        self.lines[i] = format!("{} {} {:.3} {:.3} {:.3}", f[0], f[1], to[0], to[1], to[2]);
    }
    fn position(&self, i: usize) -> [f64; 3] {
        let f = self.fields(i);
        [2, 3, 4].map(|k| f[k].parse().expect("a coordinate"))
    }
}

/// The perturbations, each on one file of the example.
#[derive(Clone, Copy, Debug)]
enum Perturbation {
    /// Every vertex's elevation moved by up to this much (metres), seeded.
    Jitter(f64, u64),
    /// A triangle's second vertex moved onto its first: a zero-area triangle.
    Collapse,
    /// A triangle's orientation reversed.
    Flip,
    /// The middle vertex moved vertically by this much (metres), through the next surface.
    Drag(f64),
    /// Every triangle with vertices of its own, in a shuffled order, without border records.
    Soup,
}

fn perturb(file: &Path, p: Perturbation) {
    let mut s = TSurf::read(file);
    match p {
        Perturbation::Jitter(amplitude, seed) => {
            let mut noise = Noise(seed);
            for i in s.indices("VRTX") {
                let mut at = s.position(i);
                at[2] += amplitude * noise.next();
                s.move_vertex(i, at);
            }
        }
        Perturbation::Collapse => {
            let t = s.fields(s.indices("TRGL")[100]);
            let first = s.position(s.vertex(&t[1]));
            let second = s.vertex(&t[2]);
            s.move_vertex(second, first);
        }
        Perturbation::Flip => {
            let i = s.indices("TRGL")[50];
            let f = s.fields(i);
            s.lines[i] = format!("TRGL {} {} {}", f[1], f[3], f[2]);
        }
        Perturbation::Drag(dz) => {
            let vs = s.indices("VRTX");
            let i = vs[vs.len() / 2];
            let mut at = s.position(i);
            at[2] += dz;
            s.move_vertex(i, at);
        }
        Perturbation::Soup => soup(&mut s),
    }
    s.write(file);
}

fn soup(s: &mut TSurf) {
    let mut tris: Vec<[[f64; 3]; 3]> = s
        .indices("TRGL")
        .into_iter()
        .map(|i| {
            let f = s.fields(i);
            [1, 2, 3].map(|k| s.position(s.vertex(&f[k])))
        })
        .collect();
    let mut noise = Noise(3);
    for i in (1..tris.len()).rev() {
        let j = ((noise.next() + 1.0) * 0.5 * (i + 1) as f64) as usize;
        tris.swap(i, j.min(i));
    }
    let records = ["VRTX", "PVRTX", "TRGL", "BSTONE", "BORDER", "END"];
    s.lines
        .retain(|l| !records.contains(&l.split_whitespace().next().unwrap_or("")));
    let mut id = 0;
    for t in &tris {
        for p in t {
            id += 1;
            s.lines
                .push(format!("VRTX {id} {:.3} {:.3} {:.3}", p[0], p[1], p[2]));
        }
        s.lines.push(format!("TRGL {} {} {}", id - 2, id - 1, id));
    }
    s.lines.push("END".into());
}

/// How a build ended: whether it succeeded, its stderr, and its time.
struct Ended {
    ok: bool,
    stderr: String,
    took: Duration,
}

/// `recipe build --quiet didactic.toml` in `s`, killed (and the test failed) past `limit`.
fn build_within(s: &Scratch, limit: Duration, what: &str) -> Ended {
    let started = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_recipe"))
        .args(["build", "--quiet", "didactic.toml"])
        .current_dir(s.dir.path())
        .env_remove("RECIPE_CACHE_DIR")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run recipe");
    // Stderr is read on its own thread, so a build that writes much cannot block on the pipe.
    let mut pipe = child.stderr.take().expect("stderr");
    let reader = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = std::io::Read::read_to_string(&mut pipe, &mut text);
        text
    });
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if started.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{what}: the build ran longer than {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    Ended {
        ok: status.success(),
        stderr: reader.join().expect("stderr read"),
        took: started.elapsed(),
    }
}

/// The unperturbed example's build time (a cold cache), measured once per test binary.
fn unperturbed() -> Duration {
    static TIME: OnceLock<Duration> = OnceLock::new();
    *TIME.get_or_init(|| {
        let s = Scratch::didactic();
        let e = build_within(&s, Duration::from_secs(600), "the unperturbed example");
        assert!(e.ok, "{}", e.stderr);
        e.took
    })
}

/// The regions the quality tables list (every row of Table 2 but the total).
fn regions_listed(s: &Scratch) -> usize {
    let q: serde_json::Value = serde_json::from_slice(
        &std::fs::read(s.path("out/didactic/didactic.quality.json")).expect("quality tables"),
    )
    .expect("quality JSON");
    q["table2"]
        .as_array()
        .expect("table 2")
        .iter()
        .filter(|r| r["name"].as_str() != Some("all"))
        .count()
}

/// Builds the example with `file` perturbed by `p` and checks the outcome; returns whether the
/// build succeeded.
fn builds_or_fails_at_a_place(file: &str, p: Perturbation) -> bool {
    let base = unperturbed();
    let s = Scratch::didactic();
    perturb(&s.path(&format!("data/didactic/{file}")), p);
    let what = format!("{file} {p:?}");
    let limit = 10 * base + Duration::from_secs(30);
    let e = build_within(&s, limit, &what);
    eprintln!(
        "{what}: {} in {:.2} s (unperturbed {:.2} s)",
        if e.ok { "built" } else { "failed" },
        e.took.as_secs_f64(),
        base.as_secs_f64()
    );
    assert!(!e.stderr.contains("panicked"), "{what}: {}", e.stderr);
    if !e.ok {
        let at_recipe_line = e.stderr.contains("didactic.toml:");
        let at_file_line = e.stderr.contains(&format!("{file}:"));
        assert!(
            at_recipe_line || at_file_line,
            "{what}: the error names no line of the recipe or of {file}:\n{}",
            e.stderr
        );
        return false;
    }
    let regions = regions_listed(&s);
    assert!(regions >= 6, "{what}: {regions} regions");
    if let Some(tool) = checker() {
        let msh = s.path("out/didactic/didactic.msh");
        let (ok, out) = test_support::export_support::run_checker(&tool, &msh, regions, None);
        assert!(ok && out.contains("\"fail\": []"), "{what}: {out}");
    }
    true
}

/// [`builds_or_fails_at_a_place`], which must build.
fn meshes(file: &str, p: Perturbation) {
    assert!(
        builds_or_fails_at_a_place(file, p),
        "{file} {p:?} did not build"
    );
}

#[test]
fn a_horizon_jittered_by_a_metre_meshes_and_passes_the_checker() {
    meshes("H1_top_reservoir.ts", Perturbation::Jitter(1.0, 1));
}

#[test]
fn a_horizon_jittered_by_five_metres_meshes_and_passes_the_checker() {
    meshes("H1_top_reservoir.ts", Perturbation::Jitter(5.0, 2));
}

#[test]
fn a_horizon_jittered_by_fifteen_metres_meshes_and_passes_the_checker() {
    meshes("H1_top_reservoir.ts", Perturbation::Jitter(15.0, 3));
}

#[test]
fn a_horizon_jittered_across_the_reservoir_meshes_or_fails_naming_a_recipe_line() {
    // 25 m on a 35 m reservoir: the horizons cross, and a region's point may fall elsewhere.
    builds_or_fails_at_a_place("H1_top_reservoir.ts", Perturbation::Jitter(25.0, 4));
}

#[test]
fn a_collapsed_triangle_in_a_horizon_meshes_and_passes_the_checker() {
    meshes("H1_top_reservoir.ts", Perturbation::Collapse);
}

#[test]
fn a_flipped_triangle_in_a_fault_meshes_and_passes_the_checker() {
    meshes("F1_through.ts", Perturbation::Flip);
}

#[test]
fn a_horizon_vertex_dragged_through_the_next_horizon_meshes_and_passes_the_checker() {
    meshes("H1_top_reservoir.ts", Perturbation::Drag(-100.0));
    meshes("H2_base_reservoir.ts", Perturbation::Drag(30.0));
}

#[test]
fn a_dangling_fault_given_as_a_triangle_soup_meshes_and_passes_the_checker() {
    meshes("F2_dangling.ts", Perturbation::Soup);
}
