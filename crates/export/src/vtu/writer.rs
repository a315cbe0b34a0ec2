//! The VTK XML pieces every VTU file here is made of: data arrays in ASCII or as raw appended
//! binary (little-endian, `UInt64` block headers), single-value field data for names tables, and
//! the document's end. Values go straight from their iterator into the buffers: no array is
//! materialized and no value gets a `String`. Index arrays take the narrowest exact type VTK and
//! meshio read (`Int32` when every value fits, else `Int64`), so binary files stay small.

use std::fmt::Write as _;

/// `s` as XML attribute text (control characters become spaces).
pub(crate) fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// A value type of a data array: its VTK name and its two spellings.
pub(crate) trait Value: Copy {
    const VTK: &'static str;
    /// Appends the ASCII text (Rust's shortest round-trip `Display`; `nan` for NaN).
    fn ascii(self, out: &mut String);
    /// Appends the little-endian bytes.
    fn raw(self, out: &mut Vec<u8>);
}

impl Value for f64 {
    const VTK: &'static str = "Float64";
    fn ascii(self, out: &mut String) {
        if self.is_nan() {
            out.push_str("nan");
        } else {
            let _ = write!(out, "{self}");
        }
    }
    fn raw(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

macro_rules! int_value {
    ($t:ty, $name:literal) => {
        impl Value for $t {
            const VTK: &'static str = $name;
            fn ascii(self, out: &mut String) {
                let _ = write!(out, "{self}");
            }
            fn raw(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
        }
    };
}
int_value!(i64, "Int64");
int_value!(i32, "Int32");
int_value!(u8, "UInt8");

/// Collects the XML and, in binary mode, the appended raw block.
pub(crate) struct Writer {
    pub(crate) xml: String,
    appended: Option<Vec<u8>>,
}

impl Writer {
    /// A document with the `UnstructuredGrid` header; `raw_capacity` sizes the binary block.
    pub(crate) fn new(binary: bool, raw_capacity: usize) -> Writer {
        let mut xml = String::from("<?xml version=\"1.0\"?>\n");
        xml.push_str("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
        xml.push_str("<UnstructuredGrid>\n");
        Writer {
            xml,
            appended: binary.then(|| Vec::with_capacity(raw_capacity)),
        }
    }

    /// A one-value `Int32` field data array (inside `<FieldData>`), always ASCII.
    pub(crate) fn field_int(&mut self, name: &str, value: i64) {
        let _ = writeln!(
            self.xml,
            "<DataArray type=\"Int32\" Name=\"{}\" NumberOfTuples=\"1\" format=\"ascii\">{value}</DataArray>",
            xml_escape(name)
        );
    }

    /// Index values (connectivity, offsets) as `Int32` when `max` fits, else `Int64`.
    pub(crate) fn indices<I>(&mut self, name: &str, max: usize, values: impl Fn() -> I)
    where
        I: Iterator<Item = usize>,
    {
        if i32::try_from(max).is_ok() {
            self.array(name, 1, values().map(|v| v as i32));
        } else {
            self.array(name, 1, values().map(|v| v as i64));
        }
    }

    /// A data array of `comps` components per tuple.
    pub(crate) fn array<T: Value>(
        &mut self,
        name: &str,
        comps: usize,
        values: impl Iterator<Item = T>,
    ) {
        let _ = write!(
            self.xml,
            "<DataArray type=\"{}\" Name=\"{}\"",
            T::VTK,
            xml_escape(name)
        );
        if comps > 1 {
            let _ = write!(self.xml, " NumberOfComponents=\"{comps}\"");
        }
        match &mut self.appended {
            Some(raw) => {
                let _ = writeln!(self.xml, " format=\"appended\" offset=\"{}\"/>", raw.len());
                // The block's byte count, patched once the values are written.
                let at = raw.len();
                raw.extend_from_slice(&0u64.to_le_bytes());
                values.for_each(|v| v.raw(raw));
                let len = (raw.len() - at - 8) as u64;
                raw[at..at + 8].copy_from_slice(&len.to_le_bytes());
            }
            None => self.ascii_values(comps, values),
        }
    }

    fn ascii_values<T: Value>(&mut self, comps: usize, values: impl Iterator<Item = T>) {
        self.xml.push_str(" format=\"ascii\">\n");
        let per_line = if comps > 1 { comps } else { 12 };
        let mut n = 0usize;
        for v in values {
            if n > 0 {
                self.xml.push(if n.is_multiple_of(per_line) {
                    '\n'
                } else {
                    ' '
                });
            }
            v.ascii(&mut self.xml);
            n += 1;
        }
        if n > 0 {
            self.xml.push('\n');
        }
        self.xml.push_str("</DataArray>\n");
    }

    /// Closes the piece and the document; returns its bytes.
    pub(crate) fn finish(mut self) -> Vec<u8> {
        self.xml.push_str("</Piece>\n</UnstructuredGrid>\n");
        match self.appended {
            None => {
                self.xml.push_str("</VTKFile>\n");
                self.xml.shrink_to_fit();
                self.xml.into_bytes()
            }
            Some(mut raw) => {
                // The (small) XML goes in front of the raw block in place: one move, no copy of
                // the block into a second buffer.
                self.xml.push_str("<AppendedData encoding=\"raw\">\n_");
                let head = self.xml.as_bytes();
                let tail = b"\n</AppendedData>\n</VTKFile>\n";
                let body = raw.len();
                raw.reserve_exact(head.len() + tail.len());
                raw.resize(body + head.len(), 0);
                raw.copy_within(..body, head.len());
                raw[..head.len()].copy_from_slice(head);
                raw.extend_from_slice(tail);
                raw.shrink_to_fit();
                raw
            }
        }
    }
}
