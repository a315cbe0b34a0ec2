//! `[groups]` resolved against the built model: each group's patches, by the model's patch
//! names. A selector that matches no patch is an error at its recipe location (a `#k` beyond a
//! surface's patches, or a patch the trims discarded), listing the patches the surface has, so
//! a group never silently holds less than the recipe says.

use super::Recipe;
use super::diagnostic::Diagnostic;
use super::selector::PatchSelector;

/// How many patch names a help line lists at most.
const LIST_MAX: usize = 8;

/// A group's name and the names of its patches, in the model's order.
pub type GroupPatches = (String, Vec<String>);

impl Recipe {
    /// Every group's patches among `patch_names` (the model's, in model order), in name order;
    /// or one diagnostic per selector that matches none, in recipe order.
    pub fn group_patches(
        &self,
        patch_names: &[String],
    ) -> Result<Vec<GroupPatches>, Vec<Diagnostic>> {
        let mut out = Vec::with_capacity(self.groups.len());
        let mut errors = Vec::new();
        for (name, g) in &self.groups {
            let mut patches = Vec::new();
            for (s, span) in g.selectors.iter().zip(&g.selector_spans) {
                let before = patches.len();
                patches.extend(
                    (patch_names.iter().enumerate())
                        .filter(|(_, p)| s.matches(p))
                        .map(|(i, _)| i),
                );
                if patches.len() == before {
                    errors.push(self.diagnostic_at(
                        *span,
                        format!("group selector `{}` matches no patch of the model", s.text),
                        Some(help(s, patch_names)),
                    ));
                }
            }
            patches.sort_unstable();
            patches.dedup();
            let names = patches.iter().map(|&p| patch_names[p].clone()).collect();
            out.push((name.clone(), names));
        }
        if errors.is_empty() {
            Ok(out)
        } else {
            errors.sort_by_key(|d| (d.line, d.col));
            Err(errors)
        }
    }
}

/// The patches the selector's surfaces have (the likely intended ones), or why there are none.
fn help(s: &PatchSelector, patch_names: &[String]) -> String {
    let any_patch = PatchSelector {
        patch: None,
        ..s.clone()
    };
    let of_surface: Vec<String> = (patch_names.iter())
        .filter(|p| any_patch.matches(p))
        .map(|p| format!("`{p}`"))
        .collect();
    if of_surface.is_empty() {
        return format!(
            "`{}` has no patch in the model (trimmed away, or outside the box)",
            s.surface.pattern
        );
    }
    let more = if of_surface.len() > LIST_MAX {
        ", ..."
    } else {
        ""
    };
    let shown = of_surface[..of_surface.len().min(LIST_MAX)].join(", ");
    format!("the model has {shown}{more}")
}
