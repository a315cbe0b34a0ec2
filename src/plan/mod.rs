//! `plan`: not yet implemented.
