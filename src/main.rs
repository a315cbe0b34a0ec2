//! The `recipe` binary: parse arguments, run, map errors to exit codes. Everything else is in the library.

fn main() {
    std::process::exit(georecipe::cli::main());
}
