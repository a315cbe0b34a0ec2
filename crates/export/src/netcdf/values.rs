//! The typed arrays a netCDF classic file holds (attribute values and variable data), encoded
//! the one way the format allows: big-endian, each array padded with zero bytes to a multiple
//! of 4 (zero is also the default fill of the one padded type we write, `char`).

/// One array of values of a single netCDF external type.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Values {
    /// `NC_CHAR`: bytes (text, or fixed-width rows of text).
    Char(Vec<u8>),
    /// `NC_INT`: 32-bit signed integers.
    Int(Vec<i32>),
    /// `NC_FLOAT`: 32-bit floats.
    Float(Vec<f32>),
    /// `NC_DOUBLE`: 64-bit floats.
    Double(Vec<f64>),
}

impl Values {
    /// A text value (an attribute such as a title or an element type).
    pub(crate) fn text(s: &str) -> Values {
        Values::Char(s.as_bytes().to_vec())
    }

    /// The `nc_type` tag of the format.
    pub(crate) fn nc_type(&self) -> u32 {
        match self {
            Values::Char(_) => 2,
            Values::Int(_) => 4,
            Values::Float(_) => 5,
            Values::Double(_) => 6,
        }
    }

    /// The number of values.
    pub(crate) fn len(&self) -> usize {
        match self {
            Values::Char(v) => v.len(),
            Values::Int(v) => v.len(),
            Values::Float(v) => v.len(),
            Values::Double(v) => v.len(),
        }
    }

    /// Bytes per value.
    pub(crate) fn value_size(&self) -> usize {
        match self {
            Values::Char(_) => 1,
            Values::Int(_) | Values::Float(_) => 4,
            Values::Double(_) => 8,
        }
    }

    /// The `n` values from `start` on (`start + n` within the array).
    pub(crate) fn slice(&self, start: usize, n: usize) -> Values {
        let r = start..start + n;
        match self {
            Values::Char(v) => Values::Char(v[r].to_vec()),
            Values::Int(v) => Values::Int(v[r].to_vec()),
            Values::Float(v) => Values::Float(v[r].to_vec()),
            Values::Double(v) => Values::Double(v[r].to_vec()),
        }
    }

    /// Appends the values big-endian, then the zero padding to a multiple of 4 bytes.
    pub(crate) fn write_padded(&self, out: &mut Vec<u8>) {
        let start = out.len();
        match self {
            Values::Char(v) => out.extend_from_slice(v),
            Values::Int(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_be_bytes())),
            Values::Float(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_be_bytes())),
            Values::Double(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_be_bytes())),
        }
        out.resize(start + padded(out.len() - start), 0);
    }
}

/// `n` rounded up to a multiple of 4 (the format's alignment).
pub(crate) fn padded(n: usize) -> usize {
    n.div_ceil(4) * 4
}
