//! `cli`: the `recipe` command line (clap). With the engine's store, the only code that touches
//! the filesystem. `watch.rs` is the only user of `notify`.
//!
//! Exit codes: 0 success; 1 the recipe is invalid, a node failed, or `--locked` found a
//! difference; 2 a usage error (from clap); 141 standard output was closed by its reader.

/// `println!` that ends the calling function with its [`Failure`] when standard output cannot
/// be written (see `output`).
macro_rules! outln {
    ($($t:tt)*) => {
        $crate::cli::output::out(&format!("{}\n", format_args!($($t)*)))?
    };
}

/// `print!` that ends the calling function with its [`Failure`] when standard output cannot be
/// written (see `output`).
macro_rules! out {
    ($($t:tt)*) => {
        $crate::cli::output::out(&format!($($t)*))?
    };
}

/// `eprintln!` that never panics (see `output`).
macro_rules! errln {
    ($($t:tt)*) => {
        $crate::cli::output::err(&format!("{}\n", format_args!($($t)*)))
    };
}

/// `eprint!` that never panics (see `output`).
macro_rules! err {
    ($($t:tt)*) => {
        $crate::cli::output::err(&format!($($t)*))
    };
}

mod build;
mod cache;
mod close_places;
mod crossings;
pub(crate) mod culprit;
mod debris;
mod load;
mod output;
mod render;
mod report;
mod report_state;
mod staging;
mod tetmesh;
mod user_file;
mod watch;

use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "recipe",
    version,
    about = "Compile a geological model recipe into finite-element meshes"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(clap::Args, Debug, Clone)]
pub struct CacheArgs {
    /// Cache directory [default: `.recipe/` beside the recipe; env RECIPE_CACHE_DIR]
    #[arg(long, env = "RECIPE_CACHE_DIR")]
    pub cache_dir: Option<PathBuf>,
}

#[derive(clap::Args, Debug, Clone)]
pub struct BuildArgs {
    /// The recipe (TOML)
    pub recipe: PathBuf,
    #[command(flatten)]
    pub cache: CacheArgs,
    /// Parallel jobs [default: number of cores]
    #[arg(short = 'j', long)]
    pub jobs: Option<usize>,
    /// Fail if any node key, output hash or output file differs from the lock file; a locked build that fails writes nothing, and none updates the lock file
    #[arg(long)]
    pub locked: bool,
    /// Use the cache for reading only and write nothing into it (a shared or archived cache); a cache that cannot be written (a read-only disk) is used this way without the flag
    #[arg(long)]
    pub read_only_cache: bool,
    /// Rebuild on every save of the recipe or an imported file
    #[arg(long)]
    pub watch: bool,
    /// Print only errors and the final line
    #[arg(short, long, conflicts_with = "verbose")]
    pub quiet: bool,
    /// Also print every cached node, the expansions and the full quality tables
    #[arg(short, long)]
    pub verbose: bool,
    /// Print a machine-readable report of every node on stdout
    #[arg(long)]
    pub json: bool,
    /// Print why each node re-ran
    #[arg(long)]
    pub explain: bool,
    /// In watch mode, exit after this many builds (for scripts and tests)
    #[arg(long, hide = true)]
    pub max_builds: Option<usize>,
}

impl BuildArgs {
    /// How much the build prints.
    pub fn verbosity(&self) -> render::Verbosity {
        match (self.quiet, self.verbose) {
            (true, _) => render::Verbosity::Quiet,
            (false, true) => render::Verbosity::Verbose,
            (false, false) => render::Verbosity::Normal,
        }
    }
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Build the recipe's outputs (cached, incremental)
    Build(BuildArgs),
    /// Validate a recipe without building
    Check { recipe: PathBuf },
    /// Say why each node of the last build re-ran
    Explain {
        recipe: PathBuf,
        #[command(flatten)]
        cache: CacheArgs,
    },
    /// Print the build graph (DOT) with each node's state in the last build
    Graph {
        recipe: PathBuf,
        #[command(flatten)]
        cache: CacheArgs,
    },
    /// Delete the recipe's cache directory
    Clean {
        recipe: PathBuf,
        #[command(flatten)]
        cache: CacheArgs,
    },
    /// Remove cache entries that the lock file and the last build do not reference
    Gc {
        recipe: PathBuf,
        #[command(flatten)]
        cache: CacheArgs,
    },
    /// Mesh one closed boundary (Gmsh .msh, .off, .obj) into tetrahedra, without a recipe
    Tetmesh(tetmesh::TetmeshArgs),
}

/// Runs the command line; returns the process exit code.
pub fn main() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        // A usage error goes to standard error (status 2); help and version to standard output,
        // which may be closed or full like any other.
        Err(e) if e.use_stderr() => {
            let _ = e.print();
            return 2;
        }
        Err(e) => {
            return match e.print() {
                Ok(()) => 0,
                Err(w) if w.kind() == std::io::ErrorKind::BrokenPipe => output::BROKEN_PIPE_STATUS,
                Err(w) => {
                    errln!("error: cannot write to standard output: {w}");
                    1
                }
            };
        }
    };
    let result = match cli.command {
        Command::Build(a) if a.watch => watch::run(&a),
        Command::Build(a) => build::run(&a).map(|_| ()),
        Command::Check { recipe } => load::check(&recipe),
        Command::Explain { recipe, cache } => cache::explain(&recipe, &cache),
        Command::Graph { recipe, cache } => cache::graph(&recipe, &cache),
        Command::Clean { recipe, cache } => cache::clean(&recipe, &cache),
        Command::Gc { recipe, cache } => cache::gc(&recipe, &cache),
        Command::Tetmesh(a) => tetmesh::run(&a),
    };
    match result {
        Ok(()) => 0,
        Err(_) if output::broken_pipe() => output::BROKEN_PIPE_STATUS,
        Err(Failure(msg)) => {
            if !msg.is_empty() {
                errln!("{msg}");
            }
            1
        }
    }
}

/// A failure already explained to the user (the message is printed once, by `main`).
#[derive(Debug)]
pub struct Failure(pub String);

impl<E: std::fmt::Display> From<E> for Failure {
    fn from(e: E) -> Self {
        Failure(format!("error: {e}"))
    }
}
