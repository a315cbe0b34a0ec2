//! Any bytes given to the mesh readers (OFF, OBJ, msh 4.1 and 2.2, ASCII and binary) give a mesh
//! or an error naming the file, never a panic.
#![no_main]

use geom::mesh::read::{read_by_extension, read_msh, read_obj, read_off, read_volume_msh};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    if let Err(e) = read_off(bytes, "f.off") {
        assert_eq!(e.file, "f.off");
    }
    if let Err(e) = read_obj(bytes, "f.obj") {
        assert_eq!(e.file, "f.obj");
    }
    let _ = read_msh(bytes, "f.msh");
    let _ = read_volume_msh(bytes, "f.msh");
    for name in ["f.off", "f.obj", "f.msh"] {
        let _ = read_by_extension(name, bytes);
    }
});
