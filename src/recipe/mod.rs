//! `recipe`: not yet implemented.
