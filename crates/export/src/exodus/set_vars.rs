//! The side-set and node-set variables: a table per kind (`ss_status`/`ns_status` all 1,
//! `ss_prop1`/`ns_prop1` the ids with the property name "ID", `ss_names`/`ns_names`) and per set
//! its entries: `elem_ss{i}` and `side_ss{i}` (element numbers and TETRA4 side numbers), or
//! `node_ns{i}` (node ids). No distribution factors: they are optional and a mesh has none.

use super::Common;
use super::sets::{NodeSet, SideSet};
use super::text::rows;
use crate::netcdf::{File, Values};

/// Writes the side sets (nothing when there are none).
pub(super) fn put_side_sets(f: &mut File, c: &Common, sets: &[SideSet]) {
    let table = sets.iter().map(|s| (s.id, s.name.as_str()));
    if !put_table(f, c, "num_side_sets", "ss", table) {
        return;
    }
    for (i, s) in sets.iter().enumerate() {
        let n = f.dim(&format!("num_side_ss{}", i + 1), s.faces.len());
        let elems = s.faces.iter().map(|u| u.elem as i32).collect();
        f.var(&format!("elem_ss{}", i + 1), &[n], Values::Int(elems));
        let sides = s.faces.iter().map(|u| u.side as i32).collect();
        f.var(&format!("side_ss{}", i + 1), &[n], Values::Int(sides));
    }
}

/// Writes the node sets (nothing when there are none).
pub(super) fn put_node_sets(f: &mut File, c: &Common, sets: &[NodeSet]) {
    let table = sets.iter().map(|s| (s.id, s.name.as_str()));
    if !put_table(f, c, "num_node_sets", "ns", table) {
        return;
    }
    for (i, s) in sets.iter().enumerate() {
        let n = f.dim(&format!("num_nod_ns{}", i + 1), s.nodes.len());
        let nodes = s.nodes.iter().map(|&v| v as i32).collect();
        f.var(&format!("node_ns{}", i + 1), &[n], Values::Int(nodes));
    }
}

/// The count dimension and the status, id and name variables of a kind of set; false (and
/// nothing written) when there is no set.
fn put_table<'a>(
    f: &mut File,
    c: &Common,
    count: &str,
    prefix: &str,
    sets: impl Iterator<Item = (usize, &'a str)>,
) -> bool {
    let (ids, names): (Vec<i32>, Vec<&str>) = sets.map(|(id, n)| (id as i32, n)).unzip();
    if ids.is_empty() {
        return false;
    }
    let n = f.dim(count, ids.len());
    f.var(
        &format!("{prefix}_status"),
        &[n],
        Values::Int(vec![1; ids.len()]),
    );
    f.var(&format!("{prefix}_prop1"), &[n], Values::Int(ids))
        .attr("name", Values::text("ID"));
    f.var(
        &format!("{prefix}_names"),
        &[n, c.len_name.0],
        rows(names, c.len_name.1),
    );
    true
}
