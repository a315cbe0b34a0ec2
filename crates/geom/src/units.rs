//! Length units of model coordinates. The recipe names the model's units; the importer converts
//! each file's `AXIS_UNIT` into them. Nothing else ever rescales coordinates.

use serde::{Deserialize, Serialize};

#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum Units {
    Metre,
    Kilometre,
    Foot,
}

impl Units {
    /// Size of one unit in metres.
    pub fn metres(self) -> f64 {
        match self {
            Units::Metre => 1.0,
            Units::Kilometre => 1000.0,
            Units::Foot => 0.3048,
        }
    }

    /// The recipe spelling: `m`, `km`, `ft`.
    pub fn as_str(self) -> &'static str {
        match self {
            Units::Metre => "m",
            Units::Kilometre => "km",
            Units::Foot => "ft",
        }
    }

    /// Recognises the `AXIS_UNIT` spellings seen in gOcad files (case-insensitive).
    pub fn parse(s: &str) -> Option<Units> {
        match s.trim().to_ascii_lowercase().as_str() {
            "m" | "meter" | "meters" | "metre" | "metres" => Some(Units::Metre),
            "km" | "kilometer" | "kilometers" | "kilometre" | "kilometres" => {
                Some(Units::Kilometre)
            }
            "ft" | "feet" | "foot" => Some(Units::Foot),
            _ => None,
        }
    }
}
