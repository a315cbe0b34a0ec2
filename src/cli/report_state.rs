//! Whether the report in the output directory is already the one a build would write.
//!
//! `report.html` and `report.json` quote every step's time, so two builds never render the same
//! bytes; apart from the timings, a build where nothing changed renders what the last one did.
//! The recipe's record keeps, for the report it last put into the output directory, a
//! fingerprint of what it shows with the timings left out (blake3 of both documents rendered
//! with every duration zero) and the hashes of the two files as written. A build whose
//! fingerprint is the recorded one, and whose output directory holds files that hash as
//! recorded (so nobody removed or edited them), leaves them alone: the report on disk keeps the
//! timings of the build that wrote it. Anything else (no record, a different fingerprint, a file
//! changed on disk) writes the report.

use crate::report::Draft;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The report files, by name in the output directory.
pub const FILES: [&str; 2] = ["report.html", "report.json"];

/// What the record keeps of the report in the output directory.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ReportState {
    /// What the report shows, timings aside (see [`fingerprint`]).
    pub fingerprint: String,
    /// blake3 of each file of [`FILES`] as written.
    pub files: BTreeMap<String, String>,
}

fn path(record_dir: &Path) -> PathBuf {
    record_dir.join("report-state.json")
}

fn hash(bytes: &[u8]) -> String {
    blake3::hash(bytes).to_hex().to_string()
}

/// blake3 over both documents of a report with every step's duration zero.
pub fn fingerprint(draft: &Draft) -> String {
    let (html, json) = draft.timeless();
    let mut h = blake3::Hasher::new();
    h.update(hash(html.as_bytes()).as_bytes());
    h.update(hash(json.as_bytes()).as_bytes());
    h.finalize().to_hex().to_string()
}

impl ReportState {
    /// The state of a report with fingerprint `fingerprint` written as `html` and `json`.
    pub fn of(fingerprint: String, html: &str, json: &str) -> ReportState {
        let files = FILES
            .iter()
            .zip([html, json])
            .map(|(name, text)| (name.to_string(), hash(text.as_bytes())))
            .collect();
        ReportState { fingerprint, files }
    }

    /// The record's state, or `None` when it has none (or an unreadable one).
    pub fn load(record_dir: &Path) -> Option<ReportState> {
        let text = engine::checked::read(&path(record_dir)).ok()?;
        serde_json::from_slice(&text).ok()
    }

    /// Writes the state into the record.
    pub fn save(&self, record_dir: &Path) -> Result<(), super::Failure> {
        let text = serde_json::to_string_pretty(self)?;
        super::build::write_record(&path(record_dir), text.as_bytes())
    }

    /// Whether `output_dir` holds the report this state describes, byte for byte.
    pub fn on_disk(&self, output_dir: &Path) -> bool {
        FILES.iter().all(|name| {
            let Some(want) = self.files.get(*name) else {
                return false;
            };
            std::fs::read(output_dir.join(name)).is_ok_and(|b| hash(&b) == *want)
        })
    }
}
