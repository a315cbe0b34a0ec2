//! Engine-level failures: the cache directory or its lock is unusable. Node failures are not
//! errors here; they are recorded in the build report so independent nodes keep going.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum EngineError {
    #[error("cache `{}`: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cache `{}` is locked by another build", path.display())]
    Locked { path: PathBuf },
    #[error("cache `{}`: {message}", path.display())]
    Invalid { path: PathBuf, message: String },
    #[error(
        "`{}` is not a recipe cache ({found}): nothing in it was touched; point --cache-dir at a \
         new or empty directory, or at a cache that `recipe build` made",
        path.display()
    )]
    NotACache { path: PathBuf, found: String },
    #[error("cannot start {jobs} worker threads: {message}")]
    Threads { jobs: usize, message: String },
}

impl EngineError {
    pub(crate) fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        EngineError::Io {
            path: path.into(),
            source,
        }
    }
}
