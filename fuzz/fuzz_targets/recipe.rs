//! Any text given to the recipe loader gives a recipe or positioned diagnostics that render,
//! never a panic.
#![no_main]

use georecipe::recipe::{check_files, parse};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    match parse(Path::new("fuzz/r.toml"), text) {
        Ok(r) => {
            let _ = check_files(&r, &|_| false);
        }
        Err(diags) => {
            assert!(!diags.is_empty(), "an error without a diagnostic");
            for d in &diags {
                let _ = d.to_string();
            }
        }
    }
});
