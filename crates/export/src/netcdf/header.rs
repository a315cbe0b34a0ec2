//! The header of a 64-bit offset (CDF-2) file: `CDF\x02`, the record count,
//! then the dimension, global attribute and variable lists. Every count and length is a
//! big-endian 32-bit integer, every name a counted string padded to 4 bytes with zeros, an empty
//! list is `ABSENT` (two zero words), and a variable's `begin` is a 64-bit offset.

use super::layout::Layout;
use super::values::padded;
use super::{Attr, File};

const NC_DIMENSION: u32 = 0x0A;
const NC_VARIABLE: u32 = 0x0B;
const NC_ATTRIBUTE: u32 = 0x0C;

/// Writes the header of `file` with the offsets of `layout`.
pub(super) fn write(file: &File, numrecs: usize, layout: &Layout, out: &mut Vec<u8>) {
    out.extend_from_slice(b"CDF\x02");
    word(out, numrecs);
    list_tag(out, NC_DIMENSION, file.dims.len());
    for d in &file.dims {
        name(out, &d.name);
        word(out, d.len.unwrap_or(0));
    }
    attrs(out, &file.attrs);
    list_tag(out, NC_VARIABLE, file.vars.len());
    for (i, v) in file.vars.iter().enumerate() {
        name(out, &v.name);
        word(out, v.dims.len());
        v.dims.iter().for_each(|&d| word(out, d));
        attrs(out, &v.attrs);
        word(out, v.data.nc_type() as usize);
        out.extend_from_slice(&layout.vsize[i].to_be_bytes());
        out.extend_from_slice(&layout.begin[i].to_be_bytes());
    }
}

/// A list's tag and count, or `ABSENT` when it is empty.
fn list_tag(out: &mut Vec<u8>, tag: u32, n: usize) {
    if n == 0 {
        word(out, 0);
        word(out, 0);
    } else {
        out.extend_from_slice(&tag.to_be_bytes());
        word(out, n);
    }
}

fn attrs(out: &mut Vec<u8>, attrs: &[Attr]) {
    list_tag(out, NC_ATTRIBUTE, attrs.len());
    for a in attrs {
        name(out, &a.name);
        word(out, a.value.nc_type() as usize);
        word(out, a.value.len());
        a.value.write_padded(out);
    }
}

/// A counted name padded to 4 bytes.
fn name(out: &mut Vec<u8>, s: &str) {
    word(out, s.len());
    out.extend_from_slice(s.as_bytes());
    out.resize(out.len() - s.len() + padded(s.len()), 0);
}

/// A 32-bit big-endian count (the checks keep every count below 2³¹).
fn word(out: &mut Vec<u8>, n: usize) {
    out.extend_from_slice(&u32::try_from(n).unwrap_or(u32::MAX).to_be_bytes());
}
