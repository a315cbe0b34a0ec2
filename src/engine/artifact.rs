//! Content identity: the `Hash` every key and output is named by, the immutable `Artifact`
//! bytes a node produces, and the `FileSet` an exporting node hands to the engine to write.
//!
//! An artifact's hash is always blake3 of its bytes (computed here, never supplied by callers
//! except from a verified read), so "same hash" means "same content" everywhere in the engine.

use crate::engine::op::OpError;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;
use std::sync::Arc;

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
#[derive(Clone)]
pub struct Artifact {
    bytes: Arc<[u8]>,
    hash: Hash,
}

impl Artifact {
    pub fn from_bytes(b: Vec<u8>) -> Artifact {
        let hash = Hash::of(&b);
        Artifact {
            bytes: b.into(),
            hash,
        }
    }

    /// Serialize `v` with postcard.
    pub fn encode<T: Serialize>(v: &T) -> Result<Artifact, OpError> {
        postcard::to_stdvec(v)
            .map(Artifact::from_bytes)
            .map_err(|e| OpError::from(format!("cannot encode output: {e}")))
    }

    /// Deserialize with postcard; a mismatch in type is an error, never a panic.
    pub fn decode<T: DeserializeOwned>(&self) -> Result<T, OpError> {
        postcard::from_bytes(&self.bytes).map_err(|e| {
            OpError::from(format!("cannot decode artifact {}: {e}", self.hash.short()))
        })
    }

    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }

    pub fn hash(&self) -> Hash {
        self.hash
    }

    pub fn len(&self) -> usize {
        self.bytes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.bytes.is_empty()
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
        write!(
            f,
            "Artifact({} bytes, {})",
            self.bytes.len(),
            self.hash.short()
        )
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
}
