//! Why a node re-ran (or did not), in recipe terms, computed by comparing a node with its entry
//! in the previous build's manifest.

use crate::params::ParamChange;
use serde::{Deserialize, Serialize};
use std::fmt;

#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub enum RebuildReason {
    /// Not in the previous build (or its kind changed).
    NewNode,
    ParamsChanged(Vec<ParamChange>),
    VersionChanged {
        old: u32,
        new: u32,
    },
    InputFileChanged {
        path: String,
    },
    /// These inputs' outputs differ from the previous build.
    UpstreamChanged {
        inputs: Vec<String>,
    },
    CacheCorrupt(String),
    CacheMissing,
    UpToDate,
    /// Skipped because these inputs failed or were skipped.
    InputFailed {
        inputs: Vec<String>,
    },
    /// Skipped because an earlier failure stopped the build (`keep_going = false`).
    BuildStopped,
    /// Skipped because a focused build ran only what the nodes it was focused on need.
    Unfocused,
}

impl RebuildReason {
    /// A short machine tag: "new", "params", "version", "input-file", "upstream", "corrupt",
    /// "missing", "up-to-date", "input-failed", "stopped", "unfocused".
    pub fn tag(&self) -> &'static str {
        match self {
            RebuildReason::NewNode => "new",
            RebuildReason::ParamsChanged(_) => "params",
            RebuildReason::VersionChanged { .. } => "version",
            RebuildReason::InputFileChanged { .. } => "input-file",
            RebuildReason::UpstreamChanged { .. } => "upstream",
            RebuildReason::CacheCorrupt(_) => "corrupt",
            RebuildReason::CacheMissing => "missing",
            RebuildReason::UpToDate => "up-to-date",
            RebuildReason::InputFailed { .. } => "input-failed",
            RebuildReason::BuildStopped => "stopped",
            RebuildReason::Unfocused => "unfocused",
        }
    }
}

impl fmt::Display for RebuildReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RebuildReason::NewNode => f.write_str("new node"),
            RebuildReason::ParamsChanged(changes) => {
                let parts: Vec<String> = changes.iter().map(|c| c.to_string()).collect();
                f.write_str(&parts.join(", "))
            }
            RebuildReason::VersionChanged { old, new } => {
                write!(f, "operation version {old} → {new}")
            }
            RebuildReason::InputFileChanged { path } => write!(f, "input file {path} changed"),
            RebuildReason::UpstreamChanged { inputs } => {
                write!(f, "upstream output changed: {}", inputs.join(", "))
            }
            RebuildReason::CacheCorrupt(detail) => write!(f, "cache entry corrupt ({detail})"),
            RebuildReason::CacheMissing => f.write_str("cache entry missing"),
            RebuildReason::UpToDate => f.write_str("up to date"),
            RebuildReason::InputFailed { inputs } => {
                write!(f, "input failed: {}", inputs.join(", "))
            }
            RebuildReason::BuildStopped => f.write_str("build stopped after a failure"),
            RebuildReason::Unfocused => {
                f.write_str("not needed by what failed before, which failed again")
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reasons_read_as_plain_words() {
        let p = RebuildReason::ParamsChanged(vec![ParamChange {
            path: "mesh.size".into(),
            old: Some("200".into()),
            new: Some("100".into()),
        }]);
        assert_eq!(p.to_string(), "mesh.size: 200 → 100");
        assert_eq!(RebuildReason::NewNode.to_string(), "new node");
        assert_eq!(
            RebuildReason::UpstreamChanged {
                inputs: vec!["import:top".into()]
            }
            .to_string(),
            "upstream output changed: import:top"
        );
        assert_eq!(
            RebuildReason::VersionChanged { old: 1, new: 2 }.to_string(),
            "operation version 1 → 2"
        );
        assert_eq!(
            RebuildReason::InputFileChanged {
                path: "data/top.ts".into()
            }
            .to_string(),
            "input file data/top.ts changed"
        );
        assert_eq!(
            RebuildReason::CacheCorrupt("hash mismatch".into()).to_string(),
            "cache entry corrupt (hash mismatch)"
        );
        assert_eq!(
            RebuildReason::CacheMissing.to_string(),
            "cache entry missing"
        );
        assert_eq!(RebuildReason::UpToDate.to_string(), "up to date");
        assert_eq!(
            RebuildReason::Unfocused.to_string(),
            "not needed by what failed before, which failed again"
        );
    }
}
