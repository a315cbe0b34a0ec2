//! The integration tests of this crate, one module per subject, in one binary (one link per
//! change instead of one per file).

mod export_bytes;
mod export_curves;
mod export_exodus;
mod export_formats;
mod export_lines;
mod export_points;
mod export_vtu;
mod quality_tables;
mod read_malformed;
mod read_volume_roundtrip;
