//! Any bytes given to the gOcad readers (TSurf, PLine, Well, Model3d, group) give objects or an
//! error, never a panic or a hang.
#![no_main]

use gocad::import::{ImportOptions, import_lines, import_surfaces, import_wells, parse_gocad};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let _ = parse_gocad(bytes, "fuzz.ts");
    let opts = ImportOptions {
        skip_other_types: true,
        ..Default::default()
    };
    let _ = import_surfaces(bytes, "fuzz.ts", &opts);
    let _ = import_lines(bytes, "fuzz.pl", &opts);
    let _ = import_wells(bytes, "fuzz.wl", &opts);
});
