//! A writer of netCDF classic files in the 64-bit offset variant (CDF-2, version byte 2), after
//! Unidata's "NetCDF Classic Format Specification": the subset the Exodus II writer needs.
//!
//! What it decides: the file is built in memory from dimensions, global attributes and
//! variables, written in the order they were added, and the variables' data follow the header in
//! that same order, so the bytes are a pure function of the calls. The one unlimited (record)
//! dimension may exist (Exodus requires `time_step`); record variables all hold the same number
//! of records, written record by record after the fixed-size data, and are of 4- or 8-byte
//! types so that no record needs padding (the format pads a lone record variable differently
//! from several; with whole words both rules agree). The format
//! reads a dimension of length 0 as the record dimension, so a fixed dimension must be at least 1
//! long: callers leave empty things out rather than declare them empty. Shapes are checked
//! before anything is written; a mismatch is a message, never a malformed file.

mod header;
mod layout;
mod values;

pub(crate) use values::Values;

/// The index of a dimension in its [`File`].
pub(crate) type DimId = usize;

/// A named dimension; `None` is the unlimited (record) dimension.
#[derive(Clone, Debug)]
pub(crate) struct Dim {
    pub(crate) name: String,
    pub(crate) len: Option<usize>,
}

/// A named attribute (of the file or of a variable).
#[derive(Clone, Debug)]
pub(crate) struct Attr {
    pub(crate) name: String,
    pub(crate) value: Values,
}

/// A variable: its shape (dimension ids, outermost first), attributes and row-major data.
#[derive(Clone, Debug)]
pub(crate) struct Var {
    pub(crate) name: String,
    pub(crate) dims: Vec<DimId>,
    pub(crate) attrs: Vec<Attr>,
    pub(crate) data: Values,
}

impl Var {
    /// Adds an attribute to the variable.
    pub(crate) fn attr(&mut self, name: &str, value: Values) -> &mut Var {
        self.attrs.push(Attr {
            name: name.to_string(),
            value,
        });
        self
    }
}

/// A netCDF classic file being built.
#[derive(Clone, Debug, Default)]
pub(crate) struct File {
    pub(crate) dims: Vec<Dim>,
    pub(crate) attrs: Vec<Attr>,
    pub(crate) vars: Vec<Var>,
}

impl File {
    /// Adds a fixed dimension of `len` (at least 1 for a valid file).
    pub(crate) fn dim(&mut self, name: &str, len: usize) -> DimId {
        self.push_dim(name, Some(len))
    }

    /// Adds the unlimited (record) dimension.
    pub(crate) fn unlimited_dim(&mut self, name: &str) -> DimId {
        self.push_dim(name, None)
    }

    fn push_dim(&mut self, name: &str, len: Option<usize>) -> DimId {
        self.dims.push(Dim {
            name: name.to_string(),
            len,
        });
        self.dims.len() - 1
    }

    /// Adds a global attribute.
    pub(crate) fn attr(&mut self, name: &str, value: Values) {
        self.attrs.push(Attr {
            name: name.to_string(),
            value,
        });
    }

    /// Adds a variable of shape `dims` holding `data` (row-major; empty for a record variable).
    pub(crate) fn var(&mut self, name: &str, dims: &[DimId], data: Values) -> &mut Var {
        self.vars.push(Var {
            name: name.to_string(),
            dims: dims.to_vec(),
            attrs: Vec::new(),
            data,
        });
        let last = self.vars.len() - 1;
        &mut self.vars[last]
    }

    /// The file's bytes: header (with every variable's offset), then the fixed-size variables'
    /// data, then the records.
    pub(crate) fn to_bytes(&self) -> Result<Vec<u8>, String> {
        let numrecs = layout::check(self)?;
        let mut out = Vec::new();
        header::write(self, numrecs, &layout::Layout::placeholder(self), &mut out);
        let layout = layout::Layout::new(self, out.len());
        out.clear();
        header::write(self, numrecs, &layout, &mut out);
        let (records, fixed): (Vec<&Var>, Vec<&Var>) =
            self.vars.iter().partition(|v| layout::is_record(self, v));
        for v in fixed {
            v.data.write_padded(&mut out);
        }
        for r in 0..numrecs {
            for v in &records {
                let n = v.data.len() / numrecs;
                v.data.slice(r * n, n).write_padded(&mut out);
            }
        }
        Ok(out)
    }
}
