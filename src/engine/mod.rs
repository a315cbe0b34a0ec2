//! `engine`: not yet implemented.
