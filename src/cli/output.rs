//! Writing to standard output and standard error without ever panicking.
//!
//! `println!` panics when the stream is closed or full (`recipe explain R | head -1`, output on
//! `/dev/full`), which ends the command with status 101 and a backtrace hint. Here a closed
//! standard output (a reader that stopped reading) ends the command quietly with the status a
//! shell gives a command killed by SIGPIPE, 141, as `git log | head -1` does; any other write
//! error on standard output is a failure with its message. Standard error is the channel for
//! messages: when it cannot be written either, there is nowhere left to report, so its errors
//! are ignored.

use super::Failure;
use std::io::{ErrorKind, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// The exit status after standard output was closed by its reader (128 + SIGPIPE).
pub const BROKEN_PIPE_STATUS: i32 = 141;

static BROKEN_PIPE: AtomicBool = AtomicBool::new(false);

/// Whether a write to standard output found it closed by its reader.
pub fn broken_pipe() -> bool {
    BROKEN_PIPE.load(Ordering::Relaxed)
}

/// Writes `text` to standard output and flushes it.
pub fn out(text: &str) -> Result<(), Failure> {
    let mut o = std::io::stdout().lock();
    match o.write_all(text.as_bytes()).and_then(|()| o.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == ErrorKind::BrokenPipe => {
            BROKEN_PIPE.store(true, Ordering::Relaxed);
            Err(Failure(String::new()))
        }
        Err(e) => Err(Failure(format!(
            "error: cannot write to standard output: {e}"
        ))),
    }
}

/// Writes `text` to standard error, ignoring a stream that cannot take it.
pub fn err(text: &str) {
    let mut e = std::io::stderr().lock();
    let _ = e.write_all(text.as_bytes()).and_then(|()| e.flush());
}
