//! Checks that need the built model: a `[mesh.curves]` rule whose selector matches no curve of
//! the model is an error (the surfaces exist, but do not meet as the rule says), reported at the
//! rule's recipe location with the closest actual curve names. The planner calls this once the
//! model's curve names are known.

use super::Recipe;
use super::diagnostic::{Diagnostic, did_you_mean};

/// How many curve names a help line lists at most.
const LIST_MAX: usize = 8;

impl Recipe {
    /// One diagnostic per curve rule that matches none of `curve_names`, in recipe order.
    pub fn check_curve_rules(&self, curve_names: &[String]) -> Vec<Diagnostic> {
        let mut out = Vec::new();
        for rule in &self.mesh.curves {
            if curve_names.iter().any(|c| rule.selector.matches(c)) {
                continue;
            }
            let text = &rule.selector.text;
            // Curves that involve at least one side of the rule: the likely intended ones.
            let mut related: Vec<&str> = curve_names
                .iter()
                .filter(|c| {
                    rule.selector
                        .sides
                        .iter()
                        .any(|s| c.split(['/', '#']).any(|part| s.matches(part)))
                })
                .map(String::as_str)
                .collect();
            related.sort();
            related.dedup();
            let help = match did_you_mean(text, curve_names.iter().map(String::as_str)) {
                Some(c) => Some(format!("did you mean `{c}`?")),
                None if !related.is_empty() => {
                    let shown: Vec<String> = related
                        .iter()
                        .take(LIST_MAX)
                        .map(|c| format!("`{c}`"))
                        .collect();
                    let more = if related.len() > LIST_MAX {
                        ", ..."
                    } else {
                        ""
                    };
                    Some(format!("the model has {}{more}", shown.join(", ")))
                }
                None => Some(
                    "these surfaces do not meet in the model: check `[intersect]` and the trims"
                        .into(),
                ),
            };
            out.push(self.diagnostic_at(
                rule.span,
                format!("curve selector `{text}` matches no curve of the model"),
                help,
            ));
        }
        out
    }
}
