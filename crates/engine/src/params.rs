//! Canonical operation parameters: what a node's key says about "how" it computes.
//!
//! Two parameter sets that mean the same thing must hash the same, and two that differ must not:
//! floats are keyed by their bits with `-0.0` folded to `0.0`, NaN is rejected (it has no
//! canonical value and never compares equal), maps are sorted by key (a `BTreeMap`), and the
//! byte form is tagged and length-prefixed so no two values share an encoding. `diff` explains a
//! change in recipe terms with nested paths such as `mesh.size` or `curves[2].n`.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;

/// Deepest nesting accepted in a parameter value; bounds every walk over a value.
pub const MAX_DEPTH: usize = 64;

/// One parameter value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Param {
    Bool(bool),
    Int(i64),
    Float(f64),
    Str(String),
    List(Vec<Param>),
    Map(BTreeMap<String, Param>),
}

/// Why a parameter value was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ParamError {
    #[error("parameter `{path}` is NaN, which has no canonical value")]
    NaN { path: String },
    #[error("parameter `{path}` = {value} does not fit in a signed 64-bit integer")]
    IntOutOfRange { path: String, value: u64 },
    #[error("parameter `{path}` is nested deeper than {MAX_DEPTH} levels")]
    TooDeep { path: String },
}

impl ParamError {
    /// Prefix the error's path with `key` (errors raised by conversions carry no path yet).
    fn under(self, key: &str) -> ParamError {
        let join = |p: String| {
            if p.is_empty() {
                key.to_string()
            } else {
                join_key(key, &p)
            }
        };
        match self {
            ParamError::NaN { path } => ParamError::NaN { path: join(path) },
            ParamError::IntOutOfRange { path, value } => ParamError::IntOutOfRange {
                path: join(path),
                value,
            },
            ParamError::TooDeep { path } => ParamError::TooDeep { path: join(path) },
        }
    }
}

impl From<std::convert::Infallible> for ParamError {
    fn from(e: std::convert::Infallible) -> Self {
        match e {}
    }
}

fn join_key(parent: &str, child: &str) -> String {
    if parent.is_empty() {
        child.to_string()
    } else if child.starts_with('[') {
        format!("{parent}{child}")
    } else {
        format!("{parent}.{child}")
    }
}

impl Param {
    /// Validate and canonicalize: NaN refused, `-0.0` folded to `0.0`, depth bounded.
    fn canonical(self, path: &str, depth: usize) -> Result<Param, ParamError> {
        if depth > MAX_DEPTH {
            return Err(ParamError::TooDeep {
                path: path.to_string(),
            });
        }
        Ok(match self {
            Param::Float(f) if f.is_nan() => {
                return Err(ParamError::NaN {
                    path: path.to_string(),
                });
            }
            Param::Float(f) => Param::Float(if f == 0.0 { 0.0 } else { f }),
            Param::List(items) => Param::List(
                items
                    .into_iter()
                    .enumerate()
                    .map(|(i, p)| p.canonical(&format!("{path}[{i}]"), depth + 1))
                    .collect::<Result<_, _>>()?,
            ),
            Param::Map(m) => Param::Map(
                m.into_iter()
                    .map(|(k, p)| {
                        let sub = join_key(path, &k);
                        p.canonical(&sub, depth + 1).map(|p| (k, p))
                    })
                    .collect::<Result<_, _>>()?,
            ),
            other => other,
        })
    }

    fn write_canonical(&self, out: &mut Vec<u8>) {
        match self {
            Param::Bool(b) => {
                out.push(1);
                out.push(u8::from(*b));
            }
            Param::Int(i) => {
                out.push(2);
                out.extend_from_slice(&i.to_le_bytes());
            }
            Param::Float(f) => {
                out.push(3);
                let f = if *f == 0.0 { 0.0 } else { *f };
                out.extend_from_slice(&f.to_bits().to_le_bytes());
            }
            Param::Str(s) => {
                out.push(4);
                write_str(out, s);
            }
            Param::List(items) => {
                out.push(5);
                out.extend_from_slice(&(items.len() as u64).to_le_bytes());
                for p in items {
                    p.write_canonical(out);
                }
            }
            Param::Map(m) => write_map(out, m),
        }
    }
}

fn write_str(out: &mut Vec<u8>, s: &str) {
    out.extend_from_slice(&(s.len() as u64).to_le_bytes());
    out.extend_from_slice(s.as_bytes());
}

fn write_map(out: &mut Vec<u8>, m: &BTreeMap<String, Param>) {
    out.push(6);
    out.extend_from_slice(&(m.len() as u64).to_le_bytes());
    for (k, p) in m {
        write_str(out, k);
        p.write_canonical(out);
    }
}

impl fmt::Display for Param {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Param::Bool(b) => write!(f, "{b}"),
            Param::Int(i) => write!(f, "{i}"),
            Param::Float(x) => write!(f, "{x:?}"),
            Param::Str(s) => write!(f, "{s:?}"),
            Param::List(items) => {
                f.write_str("[")?;
                for (i, p) in items.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{p}")?;
                }
                f.write_str("]")
            }
            Param::Map(m) => {
                f.write_str("{")?;
                for (i, (k, p)) in m.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{k} = {p}")?;
                }
                f.write_str("}")
            }
        }
    }
}

impl From<bool> for Param {
    fn from(v: bool) -> Self {
        Param::Bool(v)
    }
}
impl From<i64> for Param {
    fn from(v: i64) -> Self {
        Param::Int(v)
    }
}
impl From<i32> for Param {
    fn from(v: i32) -> Self {
        Param::Int(i64::from(v))
    }
}
impl From<u32> for Param {
    fn from(v: u32) -> Self {
        Param::Int(i64::from(v))
    }
}
/// Checked: a value above `i64::MAX` is refused rather than wrapped.
impl TryFrom<u64> for Param {
    type Error = ParamError;
    fn try_from(v: u64) -> Result<Self, ParamError> {
        i64::try_from(v)
            .map(Param::Int)
            .map_err(|_| ParamError::IntOutOfRange {
                path: String::new(),
                value: v,
            })
    }
}
/// Checked like `u64`.
impl TryFrom<usize> for Param {
    type Error = ParamError;
    fn try_from(v: usize) -> Result<Self, ParamError> {
        Param::try_from(v as u64)
    }
}
impl From<f64> for Param {
    fn from(v: f64) -> Self {
        Param::Float(v)
    }
}
impl From<&str> for Param {
    fn from(v: &str) -> Self {
        Param::Str(v.to_string())
    }
}
impl From<String> for Param {
    fn from(v: String) -> Self {
        Param::Str(v)
    }
}
impl<T: Into<Param>> From<Vec<T>> for Param {
    fn from(v: Vec<T>) -> Self {
        Param::List(v.into_iter().map(Into::into).collect())
    }
}
impl From<[f64; 3]> for Param {
    fn from(v: [f64; 3]) -> Self {
        Param::List(v.iter().map(|x| Param::Float(*x)).collect())
    }
}
impl<T: Into<Param>> From<BTreeMap<String, T>> for Param {
    fn from(v: BTreeMap<String, T>) -> Self {
        Param::Map(v.into_iter().map(|(k, p)| (k, p.into())).collect())
    }
}
impl From<Params> for Param {
    fn from(v: Params) -> Self {
        Param::Map(v.0)
    }
}

/// A node's parameters: a sorted map of canonical values.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Params(BTreeMap<String, Param>);

impl Params {
    pub fn new() -> Self {
        Params(BTreeMap::new())
    }

    /// Set `key` (replacing any previous value). NaN anywhere in the value is refused, `-0.0` is
    /// stored as `0.0`, `u64`/`usize` above `i64::MAX` are refused.
    pub fn set<V>(&mut self, key: &str, v: V) -> Result<&mut Self, ParamError>
    where
        V: TryInto<Param>,
        ParamError: From<V::Error>,
    {
        let p = v.try_into().map_err(|e| ParamError::from(e).under(key))?;
        let p = p.canonical(key, 0)?;
        self.0.insert(key.to_string(), p);
        Ok(self)
    }

    /// Builder form of [`Params::set`].
    pub fn with<V>(mut self, key: &str, v: V) -> Result<Self, ParamError>
    where
        V: TryInto<Param>,
        ParamError: From<V::Error>,
    {
        self.set(key, v)?;
        Ok(self)
    }

    pub fn get(&self, key: &str) -> Option<&Param> {
        self.0.get(key)
    }

    pub fn iter(&self) -> impl Iterator<Item = (&String, &Param)> {
        self.0.iter()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Tagged, length-prefixed bytes with keys sorted: equal meaning gives equal bytes.
    pub fn canonical_bytes(&self) -> Vec<u8> {
        let mut out = Vec::new();
        write_map(&mut out, &self.0);
        out
    }

    /// Every leaf that differs between `old` and `self`, by nested path, in sorted order.
    pub fn diff(&self, old: &Params) -> Vec<ParamChange> {
        let mut out = Vec::new();
        diff_maps("", &old.0, &self.0, &mut out, 0);
        out
    }
}

/// One changed parameter: `old` is `None` when added, `new` is `None` when removed.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ParamChange {
    pub path: String,
    pub old: Option<String>,
    pub new: Option<String>,
}

impl fmt::Display for ParamChange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let show = |v: &Option<String>| v.clone().unwrap_or_else(|| "(none)".to_string());
        write!(
            f,
            "{}: {} → {}",
            self.path,
            show(&self.old),
            show(&self.new)
        )
    }
}

fn change(path: &str, old: Option<&Param>, new: Option<&Param>) -> ParamChange {
    ParamChange {
        path: path.to_string(),
        old: old.map(|p| p.to_string()),
        new: new.map(|p| p.to_string()),
    }
}

fn diff_maps(
    path: &str,
    old: &BTreeMap<String, Param>,
    new: &BTreeMap<String, Param>,
    out: &mut Vec<ParamChange>,
    depth: usize,
) {
    let keys: std::collections::BTreeSet<&String> = old.keys().chain(new.keys()).collect();
    for k in keys {
        let sub = join_key(path, k);
        diff_values(&sub, old.get(k), new.get(k), out, depth + 1);
    }
}

fn diff_values(
    path: &str,
    old: Option<&Param>,
    new: Option<&Param>,
    out: &mut Vec<ParamChange>,
    depth: usize,
) {
    match (old, new) {
        (Some(Param::Map(a)), Some(Param::Map(b))) if depth <= MAX_DEPTH => {
            diff_maps(path, a, b, out, depth)
        }
        (Some(Param::List(a)), Some(Param::List(b))) if depth <= MAX_DEPTH => {
            for i in 0..a.len().max(b.len()) {
                diff_values(&format!("{path}[{i}]"), a.get(i), b.get(i), out, depth + 1);
            }
        }
        (Some(a), Some(b)) => {
            let (mut ba, mut bb) = (Vec::new(), Vec::new());
            a.write_canonical(&mut ba);
            b.write_canonical(&mut bb);
            if ba != bb {
                out.push(change(path, old, new));
            }
        }
        (None, None) => {}
        _ => out.push(change(path, old, new)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nan_is_refused_even_when_nested() {
        let mut p = Params::new();
        assert!(matches!(p.set("x", f64::NAN), Err(ParamError::NaN { .. })));
        let err = p.set("v", vec![1.0, f64::NAN]).unwrap_err();
        assert_eq!(
            err,
            ParamError::NaN {
                path: "v[1]".into()
            }
        );
    }

    #[test]
    fn negative_zero_and_zero_have_the_same_bytes() {
        let a = Params::new()
            .with("x", -0.0)
            .unwrap()
            .with("v", [0.0, -0.0, 1.0])
            .unwrap();
        let b = Params::new()
            .with("v", [0.0, 0.0, 1.0])
            .unwrap()
            .with("x", 0.0)
            .unwrap();
        assert_eq!(a.canonical_bytes(), b.canonical_bytes());
        assert!(a.diff(&b).is_empty());
    }

    #[test]
    fn a_u64_above_i64_max_is_refused_with_its_path() {
        let err = Params::new().with("n", u64::MAX).unwrap_err();
        assert_eq!(
            err,
            ParamError::IntOutOfRange {
                path: "n".into(),
                value: u64::MAX
            }
        );
        assert!(Params::new().with("n", 7usize).is_ok());
    }

    #[test]
    fn different_types_with_the_same_text_are_different_keys() {
        let a = Params::new().with("x", 1i64).unwrap();
        let b = Params::new().with("x", 1.0).unwrap();
        let c = Params::new().with("x", "1").unwrap();
        assert_ne!(a.canonical_bytes(), b.canonical_bytes());
        assert_ne!(a.canonical_bytes(), c.canonical_bytes());
        assert_eq!(
            b.diff(&a),
            vec![ParamChange {
                path: "x".into(),
                old: Some("1".into()),
                new: Some("1.0".into())
            }]
        );
    }

    #[test]
    fn nested_diff_names_the_leaf_path_with_old_and_new() {
        let mut inner = BTreeMap::new();
        inner.insert("size".to_string(), Param::Float(200.0));
        let old = Params::new()
            .with("mesh", inner.clone())
            .unwrap()
            .with("l", vec![1i64, 2])
            .unwrap();
        inner.insert("size".to_string(), Param::Float(100.0));
        let new = Params::new()
            .with("mesh", inner)
            .unwrap()
            .with("l", vec![1i64, 3, 4])
            .unwrap();
        let d: Vec<String> = new.diff(&old).iter().map(|c| c.to_string()).collect();
        assert_eq!(
            d,
            vec![
                "l[1]: 2 → 3",
                "l[2]: (none) → 4",
                "mesh.size: 200.0 → 100.0"
            ]
        );
    }

    #[test]
    fn nesting_beyond_the_limit_is_refused() {
        let mut p = Param::Int(0);
        for _ in 0..(MAX_DEPTH + 2) {
            p = Param::List(vec![p]);
        }
        assert!(matches!(
            Params::new().with("deep", p),
            Err(ParamError::TooDeep { .. })
        ));
    }
}
