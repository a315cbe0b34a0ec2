//! A byte cursor shared by the text and binary readers: whitespace tokens, whole lines and
//! little-endian binary values, each failure turned into a [`ReadError`] carrying the line of
//! the current position (computed only when an error is made).

use super::ReadError;

pub(crate) struct Cursor<'a> {
    pub b: &'a [u8],
    pub pos: usize,
    pub label: &'a str,
}

impl<'a> Cursor<'a> {
    pub fn new(b: &'a [u8], label: &'a str) -> Self {
        Cursor { b, pos: 0, label }
    }

    /// 1-based line number of byte offset `at`.
    pub fn line_of(&self, at: usize) -> usize {
        let end = at.min(self.b.len());
        self.b[..end].iter().filter(|&&c| c == b'\n').count() + 1
    }

    pub fn err_at(&self, at: usize, message: impl Into<String>) -> ReadError {
        ReadError {
            file: self.label.to_string(),
            line: self.line_of(at),
            message: message.into(),
        }
    }

    pub fn err(&self, message: impl Into<String>) -> ReadError {
        self.err_at(self.pos, message)
    }

    pub fn at_end(&self) -> bool {
        self.pos >= self.b.len()
    }

    pub fn skip_ws(&mut self) {
        while self.pos < self.b.len() && self.b[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    /// The next whitespace-separated token and its offset; `what` names it for the error at EOF.
    pub fn tok(&mut self, what: &str) -> Result<(&'a str, usize), ReadError> {
        self.skip_ws();
        let start = self.pos;
        while self.pos < self.b.len() && !self.b[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if start == self.pos {
            return Err(self.err(format!("unexpected end of file: expected {what}")));
        }
        std::str::from_utf8(&self.b[start..self.pos])
            .map(|s| (s, start))
            .map_err(|_| {
                self.err_at(
                    start,
                    format!("expected {what}, found bytes that are not text"),
                )
            })
    }

    pub fn u64(&mut self, what: &str) -> Result<u64, ReadError> {
        let (t, at) = self.tok(what)?;
        t.parse().map_err(|_| {
            self.err_at(
                at,
                format!("expected {what} (a non-negative integer), found '{t}'"),
            )
        })
    }

    pub fn i64(&mut self, what: &str) -> Result<i64, ReadError> {
        let (t, at) = self.tok(what)?;
        t.parse()
            .map_err(|_| self.err_at(at, format!("expected {what} (an integer), found '{t}'")))
    }

    /// A finite float.
    pub fn f64(&mut self, what: &str) -> Result<f64, ReadError> {
        let (t, at) = self.tok(what)?;
        match t.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(self.err_at(at, format!("{what} is not finite: '{t}'"))),
            Err(_) => Err(self.err_at(at, format!("expected {what} (a number), found '{t}'"))),
        }
    }

    /// The rest of the current line (without the line break) and its start offset; `None` at EOF.
    pub fn line(&mut self) -> Option<(&'a [u8], usize)> {
        if self.at_end() {
            return None;
        }
        let start = self.pos;
        while self.pos < self.b.len() && self.b[self.pos] != b'\n' {
            self.pos += 1;
        }
        let mut end = self.pos;
        if self.pos < self.b.len() {
            self.pos += 1;
        }
        if end > start && self.b[end - 1] == b'\r' {
            end -= 1;
        }
        Some((&self.b[start..end], start))
    }

    /// Skips to just after the next line break (binary data starts there).
    pub fn skip_line_break(&mut self) {
        while self.pos < self.b.len() && self.b[self.pos] != b'\n' {
            self.pos += 1;
        }
        if self.pos < self.b.len() {
            self.pos += 1;
        }
    }

    pub fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8], ReadError> {
        match self.pos.checked_add(n) {
            Some(end) if end <= self.b.len() => {
                let s = &self.b[self.pos..end];
                self.pos = end;
                Ok(s)
            }
            _ => Err(self.err(format!(
                "unexpected end of file in binary data: expected {what}"
            ))),
        }
    }

    pub fn bin_i32(&mut self, what: &str) -> Result<i32, ReadError> {
        let s = self.bytes(4, what)?;
        Ok(i32::from_le_bytes([s[0], s[1], s[2], s[3]]))
    }

    pub fn bin_u64(&mut self, what: &str) -> Result<u64, ReadError> {
        let s = self.bytes(8, what)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(s);
        Ok(u64::from_le_bytes(a))
    }

    pub fn bin_f64(&mut self, what: &str) -> Result<f64, ReadError> {
        let at = self.pos;
        let s = self.bytes(8, what)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(s);
        let v = f64::from_le_bytes(a);
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err_at(at, format!("{what} is not finite ({v})")))
        }
    }
}
