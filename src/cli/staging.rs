//! Where a `--locked` build puts its output files until the lock check accepts them.
//!
//! The staging directory is a fresh `.tmp-<output dir name>-XXXXXX` beside the output directory,
//! so it is on the same filesystem and each staged file is published by one atomic rename. The
//! engine writes there only the emitted files that differ from the output directory, the command
//! line its report files. Until [`Staging::publish`] the output directory is never written; a
//! staging directory that is dropped unpublished (the build or the lock check failed) is removed
//! with everything in it, and so are the parent directories that were created for it. A process
//! killed outright leaves one behind, with its pid in it, which the next build removes (`debris`).

use super::Failure;
use std::path::{Path, PathBuf};

pub struct Staging {
    dir: Option<tempfile::TempDir>,
    /// Directories created to hold the staging directory, outermost first: removed again, when
    /// empty, if nothing is published.
    created: Vec<PathBuf>,
}

impl Staging {
    /// A new, empty staging directory beside `output_dir`.
    pub fn beside(output_dir: &Path) -> Result<Staging, Failure> {
        let cannot = |e: std::io::Error| {
            Failure(format!(
                "error: cannot make a staging directory beside {}: {e}",
                output_dir.display()
            ))
        };
        let parent = match output_dir.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = output_dir
            .file_name()
            .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
        let mut created: Vec<PathBuf> = parent
            .ancestors()
            .take_while(|a| !a.as_os_str().is_empty() && !a.exists())
            .map(Path::to_path_buf)
            .collect();
        created.reverse();
        let mut staging = Staging { dir: None, created };
        std::fs::create_dir_all(&parent).map_err(cannot)?;
        let dir = tempfile::Builder::new()
            .prefix(&format!("{}{name}-", engine::store::TEMP_PREFIX))
            .tempdir_in(&parent)
            .map_err(cannot)?;
        // Whose it is: a later build removes it if this process dies before it does.
        std::fs::write(
            dir.path().join(super::debris::OWNER),
            std::process::id().to_string(),
        )
        .map_err(cannot)?;
        staging.dir = Some(dir);
        Ok(staging)
    }

    pub fn path(&self) -> &Path {
        self.dir.as_ref().map_or(Path::new(""), |d| d.path())
    }

    /// Moves every staged file into `output_dir` under the same relative path (a rename each,
    /// so a reader sees the old file or the new one), then removes the staging directory.
    pub fn publish(mut self, output_dir: &Path) -> Result<(), Failure> {
        let root = self.path().to_path_buf();
        let mut files = Vec::new();
        list_files(&root, &root, &mut files)?;
        files.retain(|f| f != Path::new(super::debris::OWNER));
        files.sort();
        for rel in &files {
            let to = output_dir.join(rel);
            if let Some(dir) = to.parent() {
                std::fs::create_dir_all(dir)
                    .map_err(|e| Failure(format!("error: cannot create {}: {e}", dir.display())))?;
            }
            engine::crash::point(&to);
            move_file(&root.join(rel), &to)
                .map_err(|e| Failure(format!("error: cannot write {}: {e}", to.display())))?;
        }
        // The directories made for the staging directory now hold the outputs.
        self.created.clear();
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        drop(self.dir.take());
        for d in self.created.iter().rev() {
            let _ = std::fs::remove_dir(d);
        }
    }
}

/// Every regular file under `dir`, as a path relative to `root`.
fn list_files(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) -> Result<(), Failure> {
    let unreadable =
        |e: std::io::Error| Failure(format!("error: cannot read {}: {e}", dir.display()));
    for entry in std::fs::read_dir(dir).map_err(unreadable)? {
        let entry = entry.map_err(unreadable)?;
        let path = entry.path();
        if entry.file_type().map_err(unreadable)?.is_dir() {
            list_files(root, &path, out)?;
        } else if let Ok(rel) = path.strip_prefix(root) {
            out.push(rel.to_path_buf());
        }
    }
    Ok(())
}

/// Renames `from` to `to`; where they are on different filesystems (an output directory that
/// is a mount point or a symbolic link), copies through a temporary beside `to` and renames that.
fn move_file(from: &Path, to: &Path) -> std::io::Result<()> {
    match std::fs::rename(from, to) {
        Err(e) if e.kind() == std::io::ErrorKind::CrossesDevices => {
            let mut tmp = temporary_beside(to, std::fs::metadata(from)?.permissions())?;
            std::io::copy(&mut std::fs::File::open(from)?, tmp.as_file_mut())?;
            tmp.as_file().sync_data()?;
            tmp.persist(to).map_err(|e| e.error)?;
            std::fs::remove_file(from)
        }
        other => other,
    }
}

/// A temporary beside `to`, named as every atomic write's temporaries are, so that one a killed
/// copy left is swept (`debris`).
fn temporary_beside(
    to: &Path,
    permissions: std::fs::Permissions,
) -> std::io::Result<tempfile::NamedTempFile> {
    let dir = to.parent().unwrap_or(Path::new("."));
    tempfile::Builder::new()
        .prefix(&engine::store::temp_prefix_of(to))
        .permissions(permissions)
        .tempfile_in(dir)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_temporary_of_a_copy_across_filesystems_is_one_that_sweeping_removes() {
        let dir = tempfile::tempdir().unwrap();
        let to = dir.path().join("model.msh");
        let perms = std::fs::metadata(dir.path()).unwrap().permissions();
        let tmp = temporary_beside(&to, perms).unwrap();
        let name = tmp
            .path()
            .file_name()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        assert!(super::super::debris::is_temporary(&name), "{name}");
    }

    #[test]
    fn publishing_moves_every_staged_file_into_the_output_directory() {
        let root = tempfile::tempdir().unwrap();
        let out = root.path().join("out/model");
        std::fs::create_dir_all(&out).unwrap();
        std::fs::write(out.join("kept"), b"kept").unwrap();
        std::fs::write(out.join("old"), b"before").unwrap();
        let s = Staging::beside(&out).unwrap();
        let staged = s.path().to_path_buf();
        assert_eq!(staged.parent(), Some(root.path().join("out").as_path()));
        std::fs::write(staged.join("old"), b"after").unwrap();
        std::fs::create_dir(staged.join("sub")).unwrap();
        std::fs::write(staged.join("sub/new"), b"new").unwrap();
        s.publish(&out).unwrap();
        assert!(!staged.exists());
        assert_eq!(std::fs::read(out.join("kept")).unwrap(), b"kept");
        assert_eq!(std::fs::read(out.join("old")).unwrap(), b"after");
        assert_eq!(std::fs::read(out.join("sub/new")).unwrap(), b"new");
    }

    #[test]
    fn an_unpublished_staging_directory_goes_with_the_directories_made_for_it() {
        let root = tempfile::tempdir().unwrap();
        let out = root.path().join("a/b/model");
        let s = Staging::beside(&out).unwrap();
        assert!(s.path().starts_with(root.path().join("a/b")));
        std::fs::write(s.path().join("file"), b"x").unwrap();
        drop(s);
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 0);
    }
}
