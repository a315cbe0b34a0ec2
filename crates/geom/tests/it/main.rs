//! The integration tests of this crate, one module per subject, in one binary (one link per
//! change instead of one per file).

mod read_fixtures;
mod read_peer_boundaries;
