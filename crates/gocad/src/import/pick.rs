//! Which object of a file the options mean, for any object type the importer reads (surfaces,
//! lines, wells): the one named, the one at a position, or the only one of its type. A name that
//! two objects share, a position past the end, an object of another type or a file with none of
//! the type is an error that lists what the file holds, so the recipe can be fixed from the
//! message alone.

use super::parser::{GocadFile, GocadObject};
use super::{ImportError, ImportOptions, ObjectRef};

/// An object type as the importer reads it.
pub(super) struct Kind {
    /// The gOcad type name (`GOCAD <gocad>`).
    pub gocad: &'static str,
    /// What an object of the type becomes, in messages.
    pub noun: &'static str,
}

pub(super) const SURFACE: Kind = Kind {
    gocad: "TSurf",
    noun: "surface",
};
pub(super) const LINE: Kind = Kind {
    gocad: "PLine",
    noun: "line",
};
pub(super) const WELL: Kind = Kind {
    gocad: "Well",
    noun: "path",
};

impl Kind {
    pub(super) fn holds(&self, o: &GocadObject) -> bool {
        o.kind == self.gocad
    }
}

/// Index of the object the options select.
pub(super) fn pick(
    file: &GocadFile,
    label: &str,
    opts: &ImportOptions,
    kind: &Kind,
) -> Result<usize, ImportError> {
    match &opts.object {
        Some(ObjectRef::Position(k)) => by_position(file, label, *k, kind),
        Some(ObjectRef::Name(want)) => by_name(file, label, want, kind),
        None => only_one(file, label, opts, kind),
    }
}

/// Checks that the file holds at least one object of the type, and no object of another type
/// unless `opts.skip_other_types`: what importing every object of a type requires.
pub(super) fn every(
    file: &GocadFile,
    label: &str,
    opts: &ImportOptions,
    kind: &Kind,
) -> Result<(), ImportError> {
    if !file.objects.iter().any(|o| kind.holds(o)) {
        return Err(none_of(file, label, kind));
    }
    if !opts.skip_other_types
        && let Some(o) = file.objects.iter().find(|o| !kind.holds(o))
    {
        return Err(other_type(o, label, kind));
    }
    Ok(())
}

fn by_position(file: &GocadFile, label: &str, k: u32, kind: &Kind) -> Result<usize, ImportError> {
    let at = (k as usize)
        .checked_sub(1)
        .filter(|&i| i < file.objects.len());
    match at {
        Some(i) if kind.holds(&file.objects[i]) => Ok(i),
        Some(i) => Err(other_type(&file.objects[i], label, kind)),
        None => Err(ImportError::new(
            label,
            0,
            format!(
                "there is no object #{k}: the file holds {} GOCAD object{}, counted \
                 from 1 ({} objects: {})",
                file.objects.len(),
                if file.objects.len() == 1 { "" } else { "s" },
                kind.gocad,
                listed_of(file, kind)
            ),
        )),
    }
}

fn by_name(file: &GocadFile, label: &str, want: &str, kind: &Kind) -> Result<usize, ImportError> {
    let named: Vec<usize> = (0..file.objects.len())
        .filter(|&i| file.objects[i].name == want)
        .collect();
    match named.as_slice() {
        [one] if kind.holds(&file.objects[*one]) => Ok(*one),
        [one] => Err(other_type(&file.objects[*one], label, kind)),
        [] => Err(ImportError::new(
            label,
            0,
            format!(
                "no object named '{want}'; {} objects here: {}",
                kind.gocad,
                listed_of(file, kind)
            ),
        )),
        [first, ..] => Err(ImportError::new(
            label,
            file.objects[*first].line,
            format!(
                "{} objects are named '{want}': {}; the name cannot tell them apart, so \
                 select one by its position in the file, e.g. `object = {}`",
                named.len(),
                named
                    .iter()
                    .map(|&i| listed(file, i))
                    .collect::<Vec<_>>()
                    .join(", "),
                first + 1
            ),
        )),
    }
}

fn only_one(
    file: &GocadFile,
    label: &str,
    opts: &ImportOptions,
    kind: &Kind,
) -> Result<usize, ImportError> {
    if !opts.skip_other_types
        && let Some(o) = file.objects.iter().find(|o| !kind.holds(o))
    {
        return Err(other_type(o, label, kind));
    }
    let of_kind = indices_of(file, kind);
    match of_kind.as_slice() {
        [one] => Ok(*one),
        [] => Err(none_of(file, label, kind)),
        many => {
            let first = &file.objects[many[0]];
            let mut names: Vec<&str> = many
                .iter()
                .map(|&i| file.objects[i].name.as_str())
                .collect();
            names.sort_unstable();
            names.dedup();
            let k = many[0] + 1;
            let how = if names.len() == many.len() {
                format!(
                    "name one with `object = \"{}\"`, or select it by its position in the file, \
                     e.g. `object = {k}`",
                    first.name
                )
            } else {
                format!(
                    "some share a name, so select one by its position in the file, e.g. \
                     `object = {k}`"
                )
            };
            Err(ImportError::new(
                label,
                file.objects[many[1]].line,
                format!(
                    "the file holds {} {} objects ({}); {how}",
                    many.len(),
                    kind.gocad,
                    listed_of(file, kind)
                ),
            ))
        }
    }
}

/// The file holds no object of the type.
fn none_of(file: &GocadFile, label: &str, kind: &Kind) -> ImportError {
    match file.objects.first() {
        None => ImportError::new(
            label,
            0,
            "the file holds no GOCAD object: it is empty, or not a gOcad ASCII file (no \
             `GOCAD <type> 1` header line)",
        ),
        Some(o) => ImportError::new(
            label,
            o.line,
            format!(
                "the file holds no GOCAD {} object (its first object is a GOCAD {})",
                kind.gocad, o.kind
            ),
        ),
    }
}

/// ` 'name'` for messages that name an object, empty when the object has no name.
pub(super) fn quoted_name(o: &GocadObject) -> String {
    if o.name.is_empty() {
        String::new()
    } else {
        format!(" '{}'", o.name)
    }
}

/// The object is of another type than the one asked for.
fn other_type(o: &GocadObject, label: &str, kind: &Kind) -> ImportError {
    let name = quoted_name(o);
    ImportError::new(
        label,
        o.line,
        format!(
            "object{name} is a GOCAD {} where a {} {} is expected (set skip_other_types to ignore it)",
            o.kind, kind.gocad, kind.noun
        ),
    )
}

fn indices_of(file: &GocadFile, kind: &Kind) -> Vec<usize> {
    (0..file.objects.len())
        .filter(|&i| kind.holds(&file.objects[i]))
        .collect()
}

/// How an object is listed in messages: `#2 'name' (line 134)`, its position counted from 1.
fn listed(file: &GocadFile, i: usize) -> String {
    let o = &file.objects[i];
    format!("#{} '{}' (line {})", i + 1, o.name, o.line)
}

/// The objects of the type, listed; when there are none, every object with its type.
fn listed_of(file: &GocadFile, kind: &Kind) -> String {
    let of_kind = indices_of(file, kind);
    if !of_kind.is_empty() {
        return of_kind
            .iter()
            .map(|&i| listed(file, i))
            .collect::<Vec<_>>()
            .join(", ");
    }
    if file.objects.is_empty() {
        return "none".to_string();
    }
    let all: Vec<String> = (0..file.objects.len())
        .map(|i| format!("{} {}", file.objects[i].kind, listed(file, i)))
        .collect();
    format!("none; the file holds {}", all.join(", "))
}
