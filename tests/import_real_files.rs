//! Walks every file under ../shared/data/gocad (sorted) and pins its import outcome: object,
//! surface, vertex, triangle and part counts, or the exact error line and message.

use georecipe::stages::import::{ImportOptions, import_surfaces, parse_gocad};
use std::path::{Path, PathBuf};

fn shared() -> Option<PathBuf> {
    let p = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/gocad"));
    if p.is_dir() { Some(p) } else { None }
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    for e in rd.flatten() {
        let p = e.path();
        if p.is_dir() {
            walk(&p, out);
        } else {
            out.push(p);
        }
    }
}

fn is_gocad(p: &Path) -> bool {
    matches!(p.extension().and_then(|e| e.to_str()), Some("ts" | "ml" | "gp" | "pl" | "vs" | "gcd"))
}

/// One-line outcome of a file: what parse_gocad and import_surfaces (skipping other types) say.
pub fn outcome(bytes: &[u8], label: &str) -> String {
    let parsed = match parse_gocad(bytes, label) {
        Ok(f) => f,
        Err(e) => return format!("parse error line {}: {}", e.line, e.message),
    };
    let opts = ImportOptions { skip_other_types: true, ..Default::default() };
    let regions = parsed.model3d.as_ref().map_or(0, |m| m.regions.len());
    match import_surfaces(bytes, label, &opts) {
        Ok(s) => {
            let v: usize = s.iter().map(|s| s.mesh.vertices.len()).sum();
            let t: usize = s.iter().map(|s| s.mesh.triangles.len()).sum();
            let p: usize = s.iter().map(|s| s.parts.len()).sum();
            format!("objects={} surfaces={} V={v} T={t} parts={p} regions={regions}", parsed.objects.len(), s.len())
        }
        Err(e) => format!("objects={} error line {}: {}", parsed.objects.len(), e.line, e.message),
    }
}

#[test]
fn print_outcomes() {
    let Some(root) = shared() else {
        eprintln!("skipping: ../shared is absent");
        return;
    };
    let mut files = Vec::new();
    walk(&root, &mut files);
    files.sort();
    for f in files.iter().filter(|p| is_gocad(p)) {
        let rel = f.strip_prefix(&root).unwrap().to_string_lossy().to_string();
        let bytes = std::fs::read(f).unwrap();
        println!("(\"{rel}\", \"{}\"),", outcome(&bytes, &rel).replace('"', "\\\""));
    }
}
