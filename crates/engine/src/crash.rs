//! Crash points for the tests: `RECIPE_CRASH_AT_WRITE=n` ends the process at the `n`-th write
//! of the build (counting from 1), as a power cut or a `kill -9` would, at the most telling
//! moment: an atomic write's temporary written in full but not renamed into place, or a staged
//! output not yet moved into the output directory.
//!
//! Killing a build at moments spread over time hits writes by chance; counting them lets a test
//! stop a build at every write it makes, of every kind (cache entries, records, outputs, the lock
//! file, the report), and check that the next build clears what it left and writes the same
//! outputs. The point names the path on standard error and exits with [`CRASH_STATUS`] at once:
//! no destructor runs, so a temporary stays behind as after a real crash. Without the variable a
//! write costs one relaxed load more.

use std::io::Write;
use std::path::Path;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The exit status of a process ended at a crash point.
pub const CRASH_STATUS: i32 = 86;

/// The environment variable that names the write to crash at.
pub const CRASH_AT_WRITE: &str = "RECIPE_CRASH_AT_WRITE";

static WRITES: AtomicUsize = AtomicUsize::new(0);

/// Counts one write to `path`, ending the process there if it is the one
/// [`CRASH_AT_WRITE`] names.
pub fn point(path: &Path) {
    static AT: OnceLock<Option<usize>> = OnceLock::new();
    let Some(at) = *AT.get_or_init(|| std::env::var(CRASH_AT_WRITE).ok()?.parse().ok()) else {
        return;
    };
    let n = WRITES.fetch_add(1, Ordering::Relaxed) + 1;
    if n == at {
        let _ = writeln!(
            std::io::stderr(),
            "crash point: write {n}: {}",
            path.display()
        );
        std::process::exit(CRASH_STATUS);
    }
}
