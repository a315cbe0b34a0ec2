//! Node keys: blake3 over a domain tag, the operation kind, its implementation version, its
//! canonical parameters and the output hashes of its inputs, in input order.
//!
//! Every field is length-prefixed so no two different tuples share a byte stream. Input *names*
//! do not enter the key: a node depends on what its inputs contain, not on what they are called.
//! A file node's key is derived from its content alone, so touching a file changes nothing.

use crate::artifact::Hash;
use crate::params::Params;

const OP_DOMAIN: &[u8] = b"georecipe.engine.op-key.v1\0";
const FILE_DOMAIN: &[u8] = b"georecipe.engine.file-key.v1\0";

fn put(h: &mut blake3::Hasher, bytes: &[u8]) {
    h.update(&(bytes.len() as u64).to_le_bytes());
    h.update(bytes);
}

/// The key of an operation node.
pub fn op_key(kind: &str, version: u32, params: &Params, inputs: &[Hash]) -> Hash {
    let mut h = blake3::Hasher::new();
    h.update(OP_DOMAIN);
    put(&mut h, kind.as_bytes());
    h.update(&version.to_le_bytes());
    put(&mut h, &params.canonical_bytes());
    h.update(&(inputs.len() as u64).to_le_bytes());
    for i in inputs {
        h.update(&i.0);
    }
    Hash(*h.finalize().as_bytes())
}

/// The key of a file node with the given content hash.
pub fn file_key(content: Hash) -> Hash {
    let mut h = blake3::Hasher::new();
    h.update(FILE_DOMAIN);
    h.update(&content.0);
    Hash(*h.finalize().as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_ingredient_changes_the_key() {
        let p = Params::new().with("a", 1i64).unwrap();
        let base = op_key("k", 1, &p, &[Hash::of(b"x")]);
        assert_ne!(base, op_key("j", 1, &p, &[Hash::of(b"x")]));
        assert_ne!(base, op_key("k", 2, &p, &[Hash::of(b"x")]));
        assert_ne!(base, op_key("k", 1, &Params::new(), &[Hash::of(b"x")]));
        assert_ne!(base, op_key("k", 1, &p, &[Hash::of(b"y")]));
        assert_ne!(base, op_key("k", 1, &p, &[Hash::of(b"x"), Hash::of(b"x")]));
        assert_eq!(base, op_key("k", 1, &p.clone(), &[Hash::of(b"x")]));
    }
}
