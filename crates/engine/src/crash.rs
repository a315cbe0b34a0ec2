//! Crash points for the tests: `RECIPE_CRASH_AT_WRITE=n` ends the process at the `n`-th write
//! of the build (counting from 1), as a power cut or a `kill -9` would, at the most telling
//! moment: an atomic write's temporary written in full but not renamed into place, or a staged
//! output not yet moved into the output directory.
//!
//! Killing a build at moments spread over time hits writes by chance; counting them lets a test
//! stop a build at every write it makes, of every kind (cache entries, records, outputs, the lock
//! file, the report), and check that the next build clears what it left and writes the same
//! outputs. The point names the path on standard error and exits with [`CRASH_STATUS`] at once:
//! no destructor runs, so a temporary stays behind as after a real crash.
//!
//! [`PAUSE_AT`] and [`PAUSE_FLAG`] instead hold the build before its first write of a file of
//! that name, for as long as the flag file (which it creates) exists: a test orders two builds
//! exactly, where sleeping between them would only make a race likely. Without the variables a
//! write costs one relaxed load more.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// The exit status of a process ended at a crash point.
pub const CRASH_STATUS: i32 = 86;

/// The environment variable that names the write to crash at.
pub const CRASH_AT_WRITE: &str = "RECIPE_CRASH_AT_WRITE";

/// The environment variable naming the file before whose first write the build pauses.
pub const PAUSE_AT: &str = "RECIPE_PAUSE_AT";

/// The environment variable naming the flag file a paused build creates and waits on.
pub const PAUSE_FLAG: &str = "RECIPE_PAUSE_FLAG";

static WRITES: AtomicUsize = AtomicUsize::new(0);

/// Counts one write to `path`, ending the process there if it is the one
/// [`CRASH_AT_WRITE`] names.
pub fn point(path: &Path) {
    pause(path);
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

/// Holds the process before its first write of a file named as [`PAUSE_AT`] says, while the
/// file [`PAUSE_FLAG`] names exists (created here, removed by the test).
fn pause(path: &Path) {
    static PAUSE: OnceLock<Option<(String, PathBuf)>> = OnceLock::new();
    static PAUSED: AtomicBool = AtomicBool::new(false);
    let Some((name, flag)) = PAUSE.get_or_init(|| {
        Some((
            std::env::var(PAUSE_AT).ok()?,
            std::env::var(PAUSE_FLAG).ok()?.into(),
        ))
    }) else {
        return;
    };
    if path.file_name().is_none_or(|n| n != name.as_str()) || PAUSED.swap(true, Ordering::Relaxed) {
        return;
    }
    if std::fs::write(flag, b"paused").is_ok() {
        while flag.exists() {
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
    }
}
