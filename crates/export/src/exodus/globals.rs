//! The parts of an Exodus file every mesh has: the global attributes (the 64-bit offset,
//! "large model" layout: `file_size` 1, one coordinate variable per axis, 8-byte floats, 32-bit
//! integers), the shared string dimensions, the unlimited `time_step` and `time_whole` (readers
//! require both) with the given times, one QA record (program, version, and
//! empty date and time, so the bytes never depend on when they were written), one info record
//! (the model name), the coordinate names and the coordinates.

use super::text::rows;
use crate::netcdf::{DimId, File, Values};
use geom::mesh::VolumeMesh;

/// The Exodus API and file version the file follows.
const EXODUS_VERSION: f32 = 8.03;
/// `len_string`: the width of a QA record string (32 characters and a NUL).
const LEN_STRING: usize = 33;
/// `len_line`: the width of an info record (80 characters and a NUL).
const LEN_LINE: usize = 81;

/// The dimensions the blocks and sets refer to.
pub(super) struct Common {
    /// `len_name`: the width of a name row.
    pub(super) len_name: (DimId, usize),
    /// `time_step`, the unlimited dimension.
    pub(super) time_step: DimId,
}

/// Writes the global attributes, shared dimensions, records and coordinates; `name_width` is
/// the `len_name` to use (the longest name and its NUL, at least 33), `times` the time steps.
pub(super) fn put(
    f: &mut File,
    mesh: &VolumeMesh,
    model: &str,
    name_width: usize,
    times: Vec<f64>,
) -> Common {
    f.attr("api_version", Values::Float(vec![EXODUS_VERSION]));
    f.attr("version", Values::Float(vec![EXODUS_VERSION]));
    f.attr("floating_point_word_size", Values::Int(vec![8]));
    f.attr("file_size", Values::Int(vec![1]));
    let max_name = i32::try_from(name_width - 1).unwrap_or(i32::MAX);
    f.attr("maximum_name_length", Values::Int(vec![max_name]));
    f.attr("int64_status", Values::Int(vec![0]));
    f.attr("title", Values::text(super::text::cut(model, LEN_LINE - 1)));
    let len_string = f.dim("len_string", LEN_STRING);
    let len_line = f.dim("len_line", LEN_LINE);
    let four = f.dim("four", 4);
    let len_name = f.dim("len_name", name_width);
    let time_step = f.unlimited_dim("time_step");
    let num_dim = f.dim("num_dim", 3);
    let num_qa = f.dim("num_qa_rec", 1);
    let num_info = f.dim("num_info", 1);
    f.var("time_whole", &[time_step], Values::Double(times));
    let qa = ["georecipe", env!("CARGO_PKG_VERSION"), "", ""];
    f.var(
        "qa_records",
        &[num_qa, four, len_string],
        rows(qa, LEN_STRING),
    );
    f.var(
        "info_records",
        &[num_info, len_line],
        rows([model], LEN_LINE),
    );
    f.var(
        "coor_names",
        &[num_dim, len_name],
        rows(["X", "Y", "Z"], name_width),
    );
    if !mesh.nodes.is_empty() {
        let num_nodes = f.dim("num_nodes", mesh.nodes.len());
        for (k, axis) in ["coordx", "coordy", "coordz"].into_iter().enumerate() {
            let values = mesh.nodes.iter().map(|p| p[k]).collect();
            f.var(axis, &[num_nodes], Values::Double(values));
        }
    }
    Common {
        len_name: (len_name, name_width),
        time_step,
    }
}
