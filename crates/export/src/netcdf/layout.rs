//! Where each variable's data lies in the file, and the shape checks that make those offsets
//! true. Fixed-size variables follow the header back to back in declaration order, each padded
//! to 4 bytes; record variables start where the fixed data ends, each at its place in the
//! first record (a record is every record variable's slab in turn). `vsize` is the padded size of one variable (of one record of it), capped at
//! 2³²−1 as the format prescribes for larger variables.

use super::values::padded;
use super::{File, Var};

/// The largest length a dimension or an attribute may have (a 32-bit signed count).
const MAX_LEN: usize = i32::MAX as usize;

/// Per variable (in declaration order): its `vsize` and its `begin` offset.
pub(super) struct Layout {
    pub(super) vsize: Vec<u32>,
    pub(super) begin: Vec<u64>,
}

impl Layout {
    /// Zero offsets, for measuring the header (its length does not depend on the offsets).
    pub(super) fn placeholder(file: &File) -> Layout {
        Layout {
            vsize: vec![0; file.vars.len()],
            begin: vec![0; file.vars.len()],
        }
    }

    /// The offsets of a file whose header is `header_len` bytes long.
    pub(super) fn new(file: &File, header_len: usize) -> Layout {
        let vsize: Vec<u64> = file.vars.iter().map(|v| var_size(file, v)).collect();
        let mut begin = vec![0u64; file.vars.len()];
        let mut at = header_len as u64;
        for record in [false, true] {
            for (i, v) in file.vars.iter().enumerate() {
                if is_record(file, v) == record {
                    begin[i] = at;
                    at += vsize[i];
                }
            }
        }
        Layout {
            vsize: vsize
                .iter()
                .map(|&s| u32::try_from(s).unwrap_or(u32::MAX))
                .collect(),
            begin,
        }
    }
}

/// Whether `v` runs along the unlimited dimension (which can only be its first).
pub(super) fn is_record(file: &File, v: &Var) -> bool {
    v.dims
        .first()
        .and_then(|&d| file.dims.get(d))
        .is_some_and(|d| d.len.is_none())
}

/// The padded byte size of `v` (of one record, for a record variable).
fn var_size(file: &File, v: &Var) -> u64 {
    let n: usize = v
        .dims
        .iter()
        .filter_map(|&d| file.dims.get(d).and_then(|d| d.len))
        .product();
    padded(n * v.data.value_size()) as u64
}

/// The number of records; fails when the file could not be read back as built: a bad
/// dimension, a shape that does not match its data, record variables of unequal record counts
/// or of a type narrower than a word, an over-long attribute.
pub(super) fn check(file: &File) -> Result<usize, String> {
    if file.dims.iter().filter(|d| d.len.is_none()).count() > 1 {
        return Err("netCDF: more than one unlimited dimension".into());
    }
    if let Some(d) = file
        .dims
        .iter()
        .find(|d| d.len.is_some_and(|n| n == 0 || n > MAX_LEN))
    {
        return Err(format!(
            "netCDF: dimension '{}' has length {:?} (1 to {MAX_LEN} allowed)",
            d.name, d.len
        ));
    }
    let mut numrecs = None;
    for v in &file.vars {
        let n = check_var(file, v)?;
        if let Some(n) = n.filter(|&n| numrecs.is_some_and(|m| m != n)) {
            return Err(format!(
                "netCDF: variable '{}' has {n} records, not {numrecs:?}",
                v.name
            ));
        }
        numrecs = numrecs.or(n);
    }
    let attrs = file
        .attrs
        .iter()
        .chain(file.vars.iter().flat_map(|v| &v.attrs));
    if let Some(a) = attrs.into_iter().find(|a| a.value.len() > MAX_LEN) {
        return Err(format!("netCDF: attribute '{}' is too long", a.name));
    }
    Ok(numrecs.unwrap_or(0))
}

/// Checks `v`'s dimensions against its data; its number of records if it is a record variable.
fn check_var(file: &File, v: &Var) -> Result<Option<usize>, String> {
    let mut n = 1usize;
    for (k, &d) in v.dims.iter().enumerate() {
        match file.dims.get(d).map(|d| d.len) {
            None => {
                return Err(format!(
                    "netCDF: variable '{}' has no dimension {d}",
                    v.name
                ));
            }
            Some(None) if k > 0 => {
                return Err(format!(
                    "netCDF: variable '{}' runs along the unlimited dimension not first",
                    v.name
                ));
            }
            Some(None) => {}
            Some(Some(len)) => n = n.saturating_mul(len),
        }
    }
    let record = is_record(file, v);
    let whole = if record {
        v.data.len().is_multiple_of(n)
    } else {
        v.data.len() == n
    };
    if !whole {
        return Err(format!(
            "netCDF: variable '{}' has {} values for a shape of {n}",
            v.name,
            v.data.len()
        ));
    }
    if record && v.data.value_size() < 4 {
        return Err(format!(
            "netCDF: record variable '{}' is narrower than a word",
            v.name
        ));
    }
    Ok(record.then(|| v.data.len() / n))
}
