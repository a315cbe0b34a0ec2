//! Content identity: the `Hash` every key and output is named by, the immutable `Artifact`
//! bytes a node produces, and the `FileSet` an exporting node hands to the engine to write.
//!
//! An artifact's hash is always blake3 of its bytes (computed here, never supplied by callers
//! except from a verified read), so "same hash" means "same content" everywhere in the engine.
//! A cache hit may hand out an artifact whose bytes are still in the store (`stored`): it is
//! read and verified the first time its bytes are asked for, so a build that only needs hashes
//! (every key of a no-op build) never reads it.
//!
//! An artifact read by many nodes (the model, read by one node per curve, patch and well) can be
//! decoded once and shared by all of them ([`Artifact::decode_shared`]): decoding it again in
//! each reader made the build quadratic in the number of readers.

use crate::op::OpError;
use crate::stored::Stored;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::any::Any;
use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;
use std::sync::{Arc, OnceLock};

/// A blake3 digest. Displays as lowercase hex; serializes as a hex string.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct Hash(pub [u8; 32]);

impl Hash {
    /// The all-zero hash, used where no key could be computed (a skipped node).
    pub const ZERO: Hash = Hash([0; 32]);

    pub fn of(bytes: &[u8]) -> Hash {
        Hash(*blake3::hash(bytes).as_bytes())
    }

    pub fn to_hex(&self) -> String {
        let mut s = String::with_capacity(64);
        for b in self.0 {
            s.push(char::from_digit(u32::from(b >> 4), 16).unwrap_or('0'));
            s.push(char::from_digit(u32::from(b & 15), 16).unwrap_or('0'));
        }
        s
    }

    /// The first 12 hex characters, for messages.
    pub fn short(&self) -> String {
        let mut s = self.to_hex();
        s.truncate(12);
        s
    }

    pub fn from_hex(s: &str) -> Result<Hash, String> {
        let b = s.as_bytes();
        if b.len() != 64 {
            return Err(format!("`{s}` is not a 64-character hex hash"));
        }
        let mut out = [0u8; 32];
        for (i, pair) in b.chunks(2).enumerate() {
            let hi = (pair[0] as char).to_digit(16);
            let lo = (pair[1] as char).to_digit(16);
            match (hi, lo) {
                (Some(h), Some(l)) => out[i] = (h * 16 + l) as u8,
                _ => return Err(format!("`{s}` is not a hex hash")),
            }
        }
        Ok(Hash(out))
    }
}

impl fmt::Display for Hash {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_hex())
    }
}

impl fmt::Debug for Hash {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Hash({})", self.short())
    }
}

impl FromStr for Hash {
    type Err = String;
    fn from_str(s: &str) -> Result<Hash, String> {
        Hash::from_hex(s)
    }
}

impl Serialize for Hash {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_hex())
    }
}

impl<'de> Deserialize<'de> for Hash {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Hash, D::Error> {
        let s = String::deserialize(d)?;
        Hash::from_hex(&s).map_err(serde::de::Error::custom)
    }
}

/// Immutable output bytes of a node, with their hash. Cheap to clone.
///
/// The bytes live in the `Vec` they were produced in (no copy into a fresh allocation), and
/// every encoder here sizes that `Vec` exactly, so no growth slack lives as long as the artifact.
#[derive(Clone)]
pub struct Artifact {
    body: Arc<Body>,
    hash: Hash,
    /// The first value [`Artifact::decode_shared`] decoded, shared by every clone.
    decoded: Arc<OnceLock<Arc<dyn Any + Send + Sync>>>,
}

enum Body {
    Bytes(Vec<u8>),
    /// In the cache, not read yet.
    Stored(Box<Stored>),
}

impl Artifact {
    /// Takes `b` as it is (its spare capacity, if any, stays with it).
    pub fn from_bytes(b: Vec<u8>) -> Artifact {
        let hash = Hash::of(&b);
        Artifact {
            body: Arc::new(Body::Bytes(b)),
            hash,
            decoded: Arc::default(),
        }
    }

    /// The artifact named `stored.hash()` in the cache, read when its bytes are first needed.
    pub(crate) fn stored(stored: Stored) -> Artifact {
        Artifact {
            hash: stored.hash(),
            body: Arc::new(Body::Stored(Box::new(stored))),
            decoded: Arc::default(),
        }
    }

    /// Whether the bytes are in memory (produced here, or a stored artifact already read).
    pub fn is_loaded(&self) -> bool {
        match &*self.body {
            Body::Bytes(_) => true,
            Body::Stored(s) => s.is_read(),
        }
    }

    /// For a stored artifact that was damaged in the cache and made again when read: the node
    /// that made it and what was wrong, the first time it is asked.
    pub(crate) fn take_repair(&self) -> Option<(String, String)> {
        match &*self.body {
            Body::Bytes(_) => None,
            Body::Stored(s) => s.take_repair(),
        }
    }

    /// Serialize `v` with postcard, into a buffer of exactly the encoded size.
    pub fn encode<T: Serialize>(v: &T) -> Result<Artifact, OpError> {
        let failed = |e: postcard::Error| OpError::from(format!("cannot encode output: {e}"));
        let mut buf = vec![0u8; postcard::experimental::serialized_size(v).map_err(failed)?];
        let used = postcard::to_slice(v, &mut buf).map_err(failed)?.len();
        buf.truncate(used);
        Ok(Artifact::from_bytes(buf))
    }

    /// Deserialize with postcard; a mismatch in type is an error, never a panic.
    pub fn decode<T: DeserializeOwned>(&self) -> Result<T, OpError> {
        postcard::from_bytes(self.bytes()?).map_err(|e| {
            OpError::from(format!("cannot decode artifact {}: {e}", self.hash.short()))
        })
    }

    /// The decoded value, decoded once and shared by every clone of this artifact (every node
    /// that reads it in one build); it lives as long as the artifact. Only one type is kept: asked
    /// for another, it decodes afresh each time, like [`Artifact::decode`].
    pub fn decode_shared<T: DeserializeOwned + Send + Sync + 'static>(
        &self,
    ) -> Result<Arc<T>, OpError> {
        if let Some(v) = self.decoded.get() {
            if let Ok(t) = Arc::clone(v).downcast::<T>() {
                return Ok(t);
            }
            return self.decode().map(Arc::new);
        }
        let t: Arc<T> = Arc::new(self.decode()?);
        // Two first readers at once may both decode; the value kept is the same either way.
        let _ = self.decoded.set(t.clone());
        Ok(t)
    }

    /// The files of an artifact that encodes a [`FileSet`], read in place (see
    /// [`FileSet::entries`]); the error names the artifact.
    pub fn file_entries(&self) -> Result<Vec<(&str, &[u8])>, OpError> {
        FileSet::entries(self.bytes()?).map_err(|e| {
            OpError::from(format!(
                "artifact {} is not a file set: {e}",
                self.hash.short()
            ))
        })
    }

    /// The bytes; a stored artifact is read (and verified) the first time. The error says why a
    /// stored artifact could neither be read nor made again.
    pub fn bytes(&self) -> Result<&[u8], OpError> {
        match &*self.body {
            Body::Bytes(b) => Ok(b),
            Body::Stored(s) => s.read().map_err(OpError::from),
        }
    }

    pub fn hash(&self) -> Hash {
        self.hash
    }
}

impl PartialEq for Artifact {
    fn eq(&self, other: &Self) -> bool {
        self.hash == other.hash
    }
}
impl Eq for Artifact {}

impl fmt::Debug for Artifact {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &*self.body {
            Body::Bytes(b) => write!(f, "Artifact({} bytes, {})", b.len(), self.hash.short()),
            Body::Stored(_) => write!(f, "Artifact(stored, {})", self.hash.short()),
        }
    }
}

/// Files an exporting node asks the engine to write: relative path (with `/`) -> bytes.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct FileSet {
    pub files: BTreeMap<String, Vec<u8>>,
}

impl FileSet {
    pub fn new() -> Self {
        FileSet::default()
    }

    pub fn with(mut self, path: &str, bytes: Vec<u8>) -> Self {
        self.files.insert(path.to_string(), bytes);
        self
    }

    /// Reads the files of an encoded set in place: `(path, bytes)` in path order, borrowing
    /// `bytes`. Truncated or malformed bytes, a path that is not UTF-8, paths out of order or
    /// repeated, and trailing bytes are errors naming the byte offset; nothing panics.
    pub fn entries(bytes: &[u8]) -> Result<Vec<(&str, &[u8])>, String> {
        let mut r = Reader { bytes, at: 0 };
        let n = r.varint("the file count")?;
        let mut out: Vec<(&str, &[u8])> = Vec::with_capacity(n.min(bytes.len() / 2));
        for i in 0..n {
            let at = r.at;
            let len = r.varint("a path length")?;
            let path = std::str::from_utf8(r.take(len, "a path")?)
                .map_err(|e| format!("path of file {i} at byte {at} is not UTF-8: {e}"))?;
            let len = r.varint("a file length")?;
            let data = r.take(len, "file contents")?;
            if let Some((prev, _)) = out.last()
                && *prev >= path
            {
                return Err(format!(
                    "file `{path}` at byte {at} is not after `{prev}` in path order"
                ));
            }
            out.push((path, data));
        }
        if r.at != bytes.len() {
            return Err(format!(
                "{} trailing bytes after the last file (at byte {})",
                bytes.len() - r.at,
                r.at
            ));
        }
        Ok(out)
    }
}

/// Builds a [`FileSet`]'s encoding one file at a time, in path order, freeing each file as it
/// is appended: the bytes (and hash) are those of `Artifact::encode` of the whole set, but the
/// set never exists whole beside its encoding (the peak is the encoding plus the last file).
#[derive(Debug)]
pub struct FileSetEncoder {
    buf: Vec<u8>,
    announced: usize,
    pushed: usize,
    last: Option<String>,
}

impl FileSetEncoder {
    /// An encoder for exactly `n_files` files.
    pub fn new(n_files: usize) -> FileSetEncoder {
        let mut buf = Vec::new();
        buf.extend_from_slice(encode_varint(n_files).as_slice());
        FileSetEncoder {
            buf,
            announced: n_files,
            pushed: 0,
            last: None,
        }
    }

    /// Appends one file; paths must come in strictly increasing order (as a `BTreeMap` holds
    /// them) and no more than announced.
    pub fn push(&mut self, path: &str, bytes: Vec<u8>) -> Result<(), String> {
        if self.pushed == self.announced {
            return Err(format!(
                "file `{path}` is one more than the {} announced",
                self.announced
            ));
        }
        if let Some(prev) = &self.last
            && prev.as_str() >= path
        {
            return Err(format!("file `{path}` comes after `{prev}` in path order"));
        }
        let mut head = Vec::with_capacity(entry_len(path, 0) + 10);
        head.extend_from_slice(encode_varint(path.len()).as_slice());
        head.extend_from_slice(path.as_bytes());
        head.extend_from_slice(encode_varint(bytes.len()).as_slice());
        if bytes.len() > self.buf.len() {
            self.buf = prepend(bytes, &[&self.buf, &head]);
        } else {
            self.buf.reserve_exact(head.len() + bytes.len());
            self.buf.extend_from_slice(&head);
            self.buf.extend_from_slice(&bytes);
        }
        self.pushed += 1;
        self.last = Some(path.to_string());
        Ok(())
    }

    /// The artifact, once every announced file was pushed.
    pub fn finish(self) -> Result<Artifact, String> {
        if self.pushed != self.announced {
            return Err(format!(
                "{} files announced but {} pushed",
                self.announced, self.pushed
            ));
        }
        // A file taken in whole (`prepend`) brings the slack of the `Vec` it was written in.
        let mut buf = self.buf;
        buf.shrink_to_fit();
        Ok(Artifact::from_bytes(buf))
    }
}

/// `front` (its slices in order) followed by `bytes`, built in `bytes`'s own allocation: its
/// contents move up within it, and only the front's few bytes are new. A file of hundreds of
/// megabytes (a mesh) is then not copied into fresh memory: the copy itself is cheap, but every
/// fresh page is a fault, which on a virtual machine cost seconds for a large mesh, and the two
/// copies side by side doubled the peak.
fn prepend(mut bytes: Vec<u8>, front: &[&[u8]]) -> Vec<u8> {
    let shift: usize = front.iter().map(|f| f.len()).sum();
    let len = bytes.len();
    bytes.resize(len + shift, 0);
    bytes.copy_within(..len, shift);
    let mut at = 0;
    for f in front {
        bytes[at..at + f.len()].copy_from_slice(f);
        at += f.len();
    }
    bytes
}

/// Bytes of the unsigned LEB128 varint postcard writes for a length.
fn varint_len(v: usize) -> usize {
    let bits = usize::BITS - (v | 1).leading_zeros();
    bits.div_ceil(7) as usize
}

fn entry_len(path: &str, len: usize) -> usize {
    varint_len(path.len()) + path.len() + varint_len(len) + len
}

/// A varint as a small stack buffer and its length.
struct Varint([u8; 10], usize);

impl Varint {
    fn as_slice(&self) -> &[u8] {
        &self.0[..self.1]
    }
}

fn encode_varint(mut v: usize) -> Varint {
    let mut out = Varint([0; 10], 0);
    loop {
        let low = (v & 0x7f) as u8;
        v >>= 7;
        if v == 0 {
            out.0[out.1] = low;
            out.1 += 1;
            return out;
        }
        out.0[out.1] = low | 0x80;
        out.1 += 1;
    }
}

/// Reads an encoded set, checking every length against what is left.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn varint(&mut self, what: &str) -> Result<usize, String> {
        let start = self.at;
        let mut v: u64 = 0;
        for i in 0..10 {
            let Some(&b) = self.bytes.get(self.at) else {
                return Err(format!("{what} at byte {start} is truncated"));
            };
            self.at += 1;
            if i == 9 && b > 1 {
                break;
            }
            v |= u64::from(b & 0x7f) << (7 * i);
            if b & 0x80 == 0 {
                return usize::try_from(v)
                    .map_err(|_| format!("{what} at byte {start} is too large ({v})"));
            }
        }
        Err(format!("{what} at byte {start} is not a valid varint"))
    }

    fn take(&mut self, len: usize, what: &str) -> Result<&'a [u8], String> {
        let end = self
            .at
            .checked_add(len)
            .filter(|&e| e <= self.bytes.len())
            .ok_or_else(|| {
                format!(
                    "{what} at byte {} claims {len} bytes but only {} remain",
                    self.at,
                    self.bytes.len() - self.at
                )
            })?;
        let out = &self.bytes[self.at..end];
        self.at = end;
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hash_round_trips_through_hex_and_refuses_bad_text() {
        let h = Hash::of(b"abc");
        assert_eq!(Hash::from_hex(&h.to_string()), Ok(h));
        assert_eq!(h.short().len(), 12);
        assert!(Hash::from_hex("zz").is_err());
        assert!(Hash::from_hex(&"g".repeat(64)).is_err());
    }

    #[test]
    fn decoding_an_artifact_as_the_wrong_type_is_an_error() {
        let a = Artifact::encode(&(1u8, 2u8)).unwrap();
        assert_eq!(a.decode::<(u8, u8)>().unwrap(), (1, 2));
        assert!(a.decode::<FileSet>().is_err() || a.decode::<String>().is_err());
        assert!(Artifact::from_bytes(vec![]).decode::<u64>().is_err());
    }

    #[test]
    fn every_clone_of_an_artifact_shares_one_decoded_value() {
        let a = Artifact::encode(&vec![1u32, 2, 3]).unwrap();
        let b = a.clone();
        let first = a.decode_shared::<Vec<u32>>().unwrap();
        let again = b.decode_shared::<Vec<u32>>().unwrap();
        assert!(Arc::ptr_eq(&first, &again), "decoded twice");
        assert_eq!(*again, vec![1, 2, 3]);
        // Another type still decodes, without replacing the kept value.
        assert_eq!(b.decode_shared::<(u8, u8, u8, u8)>().unwrap().0, 3);
        assert!(Arc::ptr_eq(&first, &a.decode_shared::<Vec<u32>>().unwrap()));
        // A failed decode keeps nothing.
        let c = Artifact::from_bytes(vec![]);
        assert!(c.decode_shared::<u64>().is_err());
        assert!(c.decoded.get().is_none());
    }

    fn sets() -> Vec<FileSet> {
        let bytes = |n: usize| (0..n).map(|i| (i * 7 + n) as u8).collect::<Vec<u8>>();
        let mut out = vec![
            FileSet::new(),
            FileSet::new().with("a.msh", bytes(200)),
            FileSet::new()
                .with("validation.json", bytes(200))
                .with("m.vtu", bytes(70_000))
                .with("m.msh", bytes(69_999))
                .with("m.curves.vtu", vec![]),
        ];
        // Varint edges for file lengths, path lengths and the file count.
        for n in [127, 128, 16_383, 16_384, 2_097_152] {
            out.push(FileSet::new().with("x", bytes(n)).with("y", bytes(3)));
            out.push(FileSet::new().with(&"p".repeat(n.min(16_384)), bytes(5)));
        }
        let mut many = FileSet::new();
        for i in 0..130 {
            many = many.with(&format!("f{i:03}"), bytes(i));
        }
        out.push(many);
        out
    }

    #[test]
    fn a_file_set_is_read_in_place_with_its_paths_in_order() {
        for set in sets() {
            let a = Artifact::encode(&set).unwrap();
            let entries = a.file_entries().unwrap();
            let want: Vec<(&str, &[u8])> = set
                .files
                .iter()
                .map(|(k, v)| (k.as_str(), v.as_slice()))
                .collect();
            assert_eq!(entries, want);
        }
    }

    #[test]
    fn truncated_or_garbage_file_set_bytes_are_errors_not_panics() {
        let set = FileSet::new()
            .with("a.txt", b"hello".to_vec())
            .with("b.txt", vec![7; 300]);
        let good = postcard::to_stdvec(&set).unwrap();
        for cut in 0..good.len() {
            let e = FileSet::entries(&good[..cut]).unwrap_err();
            assert!(e.contains("byte"), "{e}");
        }
        let mut trailing = good.clone();
        trailing.push(0);
        assert!(
            FileSet::entries(&trailing)
                .unwrap_err()
                .contains("trailing")
        );
        // A length far beyond the bytes, an endless varint, a non-UTF-8 path, paths out of order.
        assert!(FileSet::entries(&[1, 0xff, 0xff, 0xff, 0xff, 0x0f]).is_err());
        assert!(
            FileSet::entries(&[0xff; 12])
                .unwrap_err()
                .contains("varint")
        );
        assert!(
            FileSet::entries(&[1, 2, 0xc3, 0x28, 0])
                .unwrap_err()
                .contains("UTF-8")
        );
        let swapped = [2, 1, b'b', 0, 1, b'a', 0];
        assert!(FileSet::entries(&swapped).unwrap_err().contains("order"));
        let repeated = [2, 1, b'a', 0, 1, b'a', 0];
        assert!(FileSet::entries(&repeated).is_err());
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..2000 {
            let n = (state % 40) as usize;
            let junk: Vec<u8> = (0..n)
                .map(|_| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    (state >> 24) as u8
                })
                .collect();
            let _ = FileSet::entries(&junk);
        }
        assert_eq!(FileSet::entries(&[0]).unwrap(), vec![]);
    }

    #[test]
    fn a_file_set_encoded_whole_or_file_by_file_has_postcards_bytes() {
        for set in sets() {
            let want = postcard::to_stdvec(&set).unwrap();
            assert_eq!(Artifact::encode(&set).unwrap().bytes().unwrap(), &want[..]);
            let mut enc = FileSetEncoder::new(set.files.len());
            for (k, v) in set.files {
                enc.push(&k, v).unwrap();
            }
            assert_eq!(enc.finish().unwrap().bytes().unwrap(), &want[..]);
        }
    }

    #[test]
    fn a_file_set_encoder_refuses_files_out_of_order_or_miscounted() {
        let mut enc = FileSetEncoder::new(2);
        enc.push("b", vec![1]).unwrap();
        assert!(enc.push("a", vec![2]).unwrap_err().contains("order"));
        assert!(enc.push("b", vec![2]).unwrap_err().contains("order"));
        assert!(FileSetEncoder::new(2).finish().is_err());
        enc.push("c", vec![]).unwrap();
        assert!(enc.push("d", vec![]).unwrap_err().contains("announced"));
        assert!(enc.finish().is_ok());
    }

    #[test]
    fn varint_lengths_match_postcard_at_every_edge() {
        for v in [
            0usize,
            1,
            127,
            128,
            16_383,
            16_384,
            2_097_151,
            2_097_152,
            usize::MAX,
        ] {
            let want = postcard::to_stdvec(&v).unwrap();
            assert_eq!(varint_len(v), want.len(), "{v}");
            assert_eq!(encode_varint(v).as_slice(), &want[..], "{v}");
            let mut r = Reader {
                bytes: &want,
                at: 0,
            };
            assert_eq!(r.varint("v"), Ok(v));
        }
    }
}
