//! Reads a volume msh (as `recipe build` writes it) and writes it again in every export format
//! into a directory, so two builds of the writers can be compared byte for byte on a big mesh:
//! `cargo run --release --example export_formats -- in.msh out_dir`.

use export::{Format, export};
use geom::mesh::read::read_volume_msh;

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().collect();
    let [_, input, dir] = args.as_slice() else {
        return Err("usage: export_formats <in.msh> <out_dir>".into());
    };
    let bytes = std::fs::read(input).map_err(|e| format!("{input}: {e}"))?;
    let mesh = read_volume_msh(&bytes, input).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{dir}: {e}"))?;
    for f in Format::EVERY {
        for (name, data) in export(&mesh, "m", f)? {
            let path = format!("{dir}/{}.{name}", f.name());
            std::fs::write(&path, data).map_err(|e| format!("{path}: {e}"))?;
        }
    }
    Ok(())
}
