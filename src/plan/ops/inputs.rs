//! Named input groups. A node's inputs are one list, whose order enters its key; an operation that
//! takes several kinds of input (the model, the curve set, the assembled mesh, the export) is
//! wired group by group with a [`Wiring`] and reads its inputs back by the same names from the
//! [`Groups`] the wiring produced. Where a node is wired and how it reads its inputs therefore
//! cannot disagree: there is no position to get wrong on either side.

use engine::{Artifact, NodeId, OpError};
use serde::de::DeserializeOwned;

/// The shape of a node's inputs: each group's name and size, in wiring order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Groups(Vec<(&'static str, usize)>);

/// A node's inputs (graph node ids), built group by group.
pub struct Wiring<T = NodeId> {
    ids: Vec<T>,
    groups: Groups,
}

impl<T> Default for Wiring<T> {
    fn default() -> Self {
        Wiring {
            ids: Vec::new(),
            groups: Groups::default(),
        }
    }
}

impl<T> Wiring<T> {
    pub fn new() -> Wiring<T> {
        Wiring::default()
    }

    /// Appends the group `name` (a name used once per node).
    pub fn group(mut self, name: &'static str, ids: impl IntoIterator<Item = T>) -> Wiring<T> {
        debug_assert!(
            self.groups.0.iter().all(|(n, _)| *n != name),
            "{name} twice"
        );
        let before = self.ids.len();
        self.ids.extend(ids);
        self.groups.0.push((name, self.ids.len() - before));
        self
    }

    /// The node ids in wiring order (what the graph gets) and their groups (what the op keeps).
    pub fn finish(self) -> (Vec<T>, Groups) {
        (self.ids, self.groups)
    }
}

impl Groups {
    /// The number of inputs in group `name` (0 for a group the node was not wired with).
    pub fn len(&self, name: &str) -> usize {
        self.0.iter().find(|(n, _)| *n == name).map_or(0, |g| g.1)
    }

    /// The inputs of group `name`; an error when `inputs` is not what the node was wired with or
    /// the node has no group of that name (a group may be wired empty, never left out).
    pub fn get<'a>(&self, name: &str, inputs: &'a [Artifact]) -> Result<&'a [Artifact], OpError> {
        let total: usize = self.0.iter().map(|g| g.1).sum();
        if inputs.len() != total {
            return Err(format!(
                "wired with {total} inputs ({}), given {}",
                self.describe(),
                inputs.len()
            )
            .into());
        }
        let mut at = 0;
        for (n, k) in &self.0 {
            if *n == name {
                return Ok(&inputs[at..at + k]);
            }
            at += k;
        }
        Err(format!("no input group `{name}` (wired: {})", self.describe()).into())
    }

    /// Every input of group `name`, decoded.
    pub fn decode<T: DeserializeOwned>(
        &self,
        name: &str,
        inputs: &[Artifact],
    ) -> Result<Vec<T>, OpError> {
        self.get(name, inputs)?.iter().map(|a| a.decode()).collect()
    }

    fn describe(&self) -> String {
        let parts: Vec<String> = self.0.iter().map(|(n, k)| format!("{k} {n}")).collect();
        parts.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn art(v: u32) -> Artifact {
        Artifact::encode(&v).unwrap()
    }

    #[test]
    fn groups_read_back_what_was_wired_under_each_name() {
        let (ids, groups) = Wiring::new()
            .group("a", [4, 5])
            .group("b", [])
            .group("c", [1])
            .finish();
        assert_eq!(ids, vec![4, 5, 1]);
        let inputs = [art(4), art(5), art(1)];
        assert_eq!(groups.decode::<u32>("a", &inputs).unwrap(), vec![4, 5]);
        assert!(groups.get("b", &inputs).unwrap().is_empty());
        assert_eq!(groups.decode::<u32>("c", &inputs).unwrap(), vec![1]);
        assert_eq!((groups.len("a"), groups.len("missing")), (2, 0));
    }

    #[test]
    fn inputs_of_another_shape_are_an_error_naming_the_groups() {
        let (_, groups) = Wiring::new()
            .group("surfaces", [0])
            .group("mesh", [1])
            .finish();
        let e = groups.get("mesh", &[art(0)]).unwrap_err();
        assert!(e.to_string().contains("1 surfaces, 1 mesh"), "{e}");
        let e = groups.get("meshes", &[art(0), art(1)]).unwrap_err();
        assert!(e.to_string().contains("no input group `meshes`"), "{e}");
    }
}
