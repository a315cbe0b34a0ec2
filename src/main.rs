//! The `recipe` binary: parse arguments, run, map errors to exit codes. Everything else is in the library.

fn main() {
    return_big_blocks_to_the_system();
    std::process::exit(georecipe::cli::main());
}

/// With glibc, a block of 1 MiB or more gets its own mapping, given back to the system when it is
/// freed. By default glibc raises that threshold as big blocks are freed (up to 32 MiB), after
/// which the mesh-sized buffers of one stage stay resident in the allocator's per-thread arenas
/// while the next stage allocates its own: refinement (d) at `-j 2` peaked at 211-310 MB of
/// resident memory for 178 MB of heap; with the fixed threshold it peaks at 200-205 MB, at the
/// same speed.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn return_big_blocks_to_the_system() {
    unsafe extern "C" {
        fn mallopt(param: i32, value: i32) -> i32;
    }
    const M_MMAP_THRESHOLD: i32 = -3;
    // SAFETY: `mallopt` only tunes the allocator; it is called first thing in `main`, before any
    // other thread exists or any block is allocated by this program.
    unsafe {
        mallopt(M_MMAP_THRESHOLD, 1 << 20);
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn return_big_blocks_to_the_system() {}
