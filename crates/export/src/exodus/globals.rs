//! The parts of an Exodus file every mesh has: the global attributes (the 64-bit offset,
//! "large model" layout: `file_size` 1, one coordinate variable per axis, 8-byte floats, 32-bit
//! integers), the shared string dimensions, the unlimited `time_step` and `time_whole` (readers
//! require both) with the given times, the QA and info records, the coordinate names and the
//! coordinates.
//!
//! The QA records are rows of four 32-character strings (code, version, date, time), one per
//! program that processed the file: georecipe and its version, then, given a recipe, the recipe
//! as the "code" that made this mesh and the first 32 hex digits of the build's key as its
//! "version" (128 bits name a build well enough; the info records hold the whole key). Date and
//! time stay empty, so the bytes never depend on when they were written. The info records
//! (80-character lines) are the model name, then `recipe <file>` and `key <hex>`: the key is the
//! export node's key as the lock file records it, which changes with any input of the build.

use super::text::rows;
use crate::Provenance;
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
    (model, provenance): (&str, &Provenance),
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
    let qa = qa_records(provenance);
    let info = info_records(model, provenance);
    let num_qa = f.dim("num_qa_rec", qa.len() / 4);
    let num_info = f.dim("num_info", info.len());
    f.var("time_whole", &[time_step], Values::Double(times));
    f.var(
        "qa_records",
        &[num_qa, four, len_string],
        rows(qa.iter().map(String::as_str), LEN_STRING),
    );
    f.var(
        "info_records",
        &[num_info, len_line],
        rows(info.iter().map(String::as_str), LEN_LINE),
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

/// The QA records' strings, four per record: georecipe's, then the recipe's when there is one.
fn qa_records(provenance: &Provenance) -> Vec<String> {
    let mut qa = vec!["georecipe".into(), env!("CARGO_PKG_VERSION").into()];
    qa.extend([String::new(), String::new()]);
    if !provenance.recipe.is_empty() {
        let key = super::text::cut(&provenance.key, LEN_STRING - 1);
        qa.extend([provenance.recipe.clone(), key.into()]);
        qa.extend([String::new(), String::new()]);
    }
    qa
}

/// The info records: the model name, then the recipe and the key when they are given.
fn info_records(model: &str, provenance: &Provenance) -> Vec<String> {
    let mut info = vec![model.to_string()];
    if !provenance.recipe.is_empty() {
        info.push(format!("recipe {}", provenance.recipe));
    }
    if !provenance.key.is_empty() {
        info.push(format!("key {}", provenance.key));
    }
    info
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_recipe_adds_a_qa_record_and_info_lines_naming_it_and_its_key() {
        let key = "0123456789abcdef".repeat(4);
        let p = Provenance {
            recipe: "m.toml".into(),
            key: key.clone(),
        };
        let qa = qa_records(&p);
        assert_eq!(qa.len(), 8);
        assert_eq!(qa[4..6], ["m.toml".to_string(), key[..32].to_string()]);
        let info = info_records("m", &p);
        assert_eq!(
            info,
            [
                "m".to_string(),
                "recipe m.toml".into(),
                format!("key {key}")
            ]
        );
        assert!(info.iter().all(|l| l.len() < LEN_LINE));
        assert_eq!(qa_records(&Provenance::default()).len(), 4);
        assert_eq!(info_records("m", &Provenance::default()), ["m"]);
    }
}
