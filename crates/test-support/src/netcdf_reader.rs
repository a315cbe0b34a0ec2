//! A small reader of netCDF classic files (CDF-1 and the 64-bit offset CDF-2), for tests only:
//! it decodes the header (dimensions, attributes, variables with their offsets) and the data of
//! fixed-size variables, so a test can check a writer's bytes against the format without the C
//! library. Written from Unidata's "NetCDF Classic Format Specification"; errors are messages.

/// A decoded value array.
#[derive(Clone, Debug, PartialEq)]
pub enum Val {
    Byte(Vec<i8>),
    Char(Vec<u8>),
    Short(Vec<i16>),
    Int(Vec<i32>),
    Float(Vec<f32>),
    Double(Vec<f64>),
}

/// A variable as the header declares it.
#[derive(Clone, Debug)]
pub struct NcVar {
    pub name: String,
    pub dims: Vec<usize>,
    pub attrs: Vec<(String, Val)>,
    pub nc_type: u32,
    pub vsize: u32,
    pub begin: u64,
}

/// A decoded file: version byte, record count, header length and the three lists.
#[derive(Clone, Debug)]
pub struct Nc {
    pub version: u8,
    pub numrecs: u32,
    pub header_len: usize,
    /// `(name, length)`; length 0 is the record dimension.
    pub dims: Vec<(String, u32)>,
    pub attrs: Vec<(String, Val)>,
    pub vars: Vec<NcVar>,
}

struct Cursor<'a> {
    b: &'a [u8],
    at: usize,
}

impl Cursor<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        let s = self
            .b
            .get(self.at..self.at + n)
            .ok_or_else(|| format!("truncated at byte {}", self.at))?;
        self.at += n;
        Ok(s)
    }
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_be_bytes(self.take(4)?.try_into().unwrap()))
    }
    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_be_bytes(self.take(8)?.try_into().unwrap()))
    }
    fn padding(&mut self, n: usize) -> Result<(), String> {
        let pad = n.div_ceil(4) * 4 - n;
        if self.take(pad)?.iter().any(|&b| b != 0) {
            return Err(format!("non-zero padding before byte {}", self.at));
        }
        Ok(())
    }
    fn name(&mut self) -> Result<String, String> {
        let n = self.u32()? as usize;
        let s = String::from_utf8(self.take(n)?.to_vec()).map_err(|e| e.to_string())?;
        self.padding(n)?;
        Ok(s)
    }
    /// A list's count after its tag (0 for ABSENT).
    fn list(&mut self, tag: u32) -> Result<usize, String> {
        let (t, n) = (self.u32()?, self.u32()?);
        if t != tag && !(t == 0 && n == 0) {
            return Err(format!("expected list tag {tag:#x}, got {t:#x}"));
        }
        Ok(n as usize)
    }
    fn values(&mut self, nc_type: u32, n: usize) -> Result<Val, String> {
        let size = type_size(nc_type)?;
        let v = decode(nc_type, self.take(n * size)?)?;
        self.padding(n * size)?;
        Ok(v)
    }
    fn attrs(&mut self) -> Result<Vec<(String, Val)>, String> {
        let n = self.list(0x0C)?;
        (0..n)
            .map(|_| {
                let name = self.name()?;
                let t = self.u32()?;
                let len = self.u32()? as usize;
                Ok((name, self.values(t, len)?))
            })
            .collect()
    }
}

fn type_size(nc_type: u32) -> Result<usize, String> {
    match nc_type {
        1 | 2 => Ok(1),
        3 => Ok(2),
        4 | 5 => Ok(4),
        6 => Ok(8),
        t => Err(format!("unknown nc_type {t}")),
    }
}

fn decode(nc_type: u32, b: &[u8]) -> Result<Val, String> {
    let n = |k: usize| b.chunks_exact(k);
    Ok(match nc_type {
        1 => Val::Byte(b.iter().map(|&x| x as i8).collect()),
        2 => Val::Char(b.to_vec()),
        3 => Val::Short(n(2).map(|c| i16::from_be_bytes([c[0], c[1]])).collect()),
        4 => Val::Int(
            n(4).map(|c| i32::from_be_bytes(c.try_into().unwrap()))
                .collect(),
        ),
        5 => Val::Float(
            n(4).map(|c| f32::from_be_bytes(c.try_into().unwrap()))
                .collect(),
        ),
        6 => Val::Double(
            n(8).map(|c| f64::from_be_bytes(c.try_into().unwrap()))
                .collect(),
        ),
        t => return Err(format!("unknown nc_type {t}")),
    })
}

impl Nc {
    /// Decodes the header of `bytes`.
    pub fn parse(bytes: &[u8]) -> Result<Nc, String> {
        let mut c = Cursor { b: bytes, at: 0 };
        let magic = c.take(4)?;
        if &magic[..3] != b"CDF" || !matches!(magic[3], 1 | 2) {
            return Err(format!("not a netCDF classic file: {magic:?}"));
        }
        let version = magic[3];
        let numrecs = c.u32()?;
        let nd = c.list(0x0A)?;
        let dims = (0..nd)
            .map(|_| Ok((c.name()?, c.u32()?)))
            .collect::<Result<_, String>>()?;
        let attrs = c.attrs()?;
        let nv = c.list(0x0B)?;
        let mut vars = Vec::new();
        for _ in 0..nv {
            let name = c.name()?;
            let rank = c.u32()? as usize;
            let dims = (0..rank)
                .map(|_| c.u32().map(|d| d as usize))
                .collect::<Result<_, _>>()?;
            let attrs = c.attrs()?;
            let nc_type = c.u32()?;
            let vsize = c.u32()?;
            let begin = if version == 2 {
                c.u64()?
            } else {
                c.u32()? as u64
            };
            vars.push(NcVar {
                name,
                dims,
                attrs,
                nc_type,
                vsize,
                begin,
            });
        }
        Ok(Nc {
            version,
            numrecs,
            header_len: c.at,
            dims,
            attrs,
            vars,
        })
    }

    /// The length of dimension `name` (None when absent).
    pub fn dim(&self, name: &str) -> Option<u32> {
        self.dims.iter().find(|(n, _)| n == name).map(|(_, l)| *l)
    }

    /// A global attribute.
    pub fn attr(&self, name: &str) -> Option<&Val> {
        self.attrs.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    /// A variable's declaration.
    pub fn var(&self, name: &str) -> Option<&NcVar> {
        self.vars.iter().find(|v| v.name == name)
    }

    /// Whether `v` runs along the record dimension.
    pub fn is_record(&self, v: &NcVar) -> bool {
        v.dims.first().is_some_and(|&d| self.dims[d].1 == 0)
    }

    /// The shape of `v` (the record dimension counts `numrecs`).
    pub fn shape(&self, v: &NcVar) -> Vec<usize> {
        v.dims
            .iter()
            .map(|&d| match self.dims[d].1 {
                0 => self.numrecs as usize,
                n => n as usize,
            })
            .collect()
    }

    /// The data of fixed-size variable `name`, read from `bytes` at its offset.
    pub fn data(&self, bytes: &[u8], name: &str) -> Result<Val, String> {
        let v = self
            .var(name)
            .ok_or_else(|| format!("no variable {name}"))?;
        if self.is_record(v) {
            return Err(format!("{name} is a record variable"));
        }
        let n: usize = self.shape(v).iter().product();
        let size = type_size(v.nc_type)?;
        let at = v.begin as usize;
        let b = bytes
            .get(at..at + n * size)
            .ok_or_else(|| format!("{name}: data beyond the file"))?;
        decode(v.nc_type, b)
    }

    /// Every record of `NC_DOUBLE` record variable `name`, records in order (the record size is
    /// the sum of the record variables' `vsize`).
    pub fn records(&self, bytes: &[u8], name: &str) -> Vec<f64> {
        let v = self
            .var(name)
            .unwrap_or_else(|| panic!("no variable {name}"));
        assert!(self.is_record(v) && v.nc_type == 6, "{name}");
        let recsize: u64 = self
            .vars
            .iter()
            .filter(|w| self.is_record(w))
            .map(|w| w.vsize as u64)
            .sum();
        let per: usize = self.shape(v).iter().skip(1).product();
        (0..self.numrecs as u64)
            .flat_map(|r| {
                let at = (v.begin + r * recsize) as usize;
                match decode(6, &bytes[at..at + per * 8]) {
                    Ok(Val::Double(d)) => d,
                    _ => unreachable!(),
                }
            })
            .collect()
    }

    /// The data of an `NC_INT` variable.
    pub fn ints(&self, bytes: &[u8], name: &str) -> Vec<i32> {
        match self.data(bytes, name) {
            Ok(Val::Int(v)) => v,
            other => panic!("{name}: {other:?}"),
        }
    }

    /// The data of an `NC_DOUBLE` variable.
    pub fn doubles(&self, bytes: &[u8], name: &str) -> Vec<f64> {
        match self.data(bytes, name) {
            Ok(Val::Double(v)) => v,
            other => panic!("{name}: {other:?}"),
        }
    }

    /// The rows of a 2D (or more) `NC_CHAR` variable as strings, each up to its first NUL.
    pub fn strings(&self, bytes: &[u8], name: &str) -> Vec<String> {
        let v = self
            .var(name)
            .unwrap_or_else(|| panic!("no variable {name}"));
        let width = *self.shape(v).last().unwrap();
        let Ok(Val::Char(b)) = self.data(bytes, name) else {
            panic!("{name} is not text");
        };
        b.chunks(width)
            .map(|row| {
                let end = row.iter().position(|&c| c == 0).unwrap_or(row.len());
                String::from_utf8_lossy(&row[..end]).into_owned()
            })
            .collect()
    }
}

/// The text of a `char` attribute value.
pub fn text(v: Option<&Val>) -> Option<String> {
    match v {
        Some(Val::Char(b)) => Some(String::from_utf8_lossy(b).into_owned()),
        _ => None,
    }
}
