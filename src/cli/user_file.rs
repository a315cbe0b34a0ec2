//! Reading a file of the user's that a command reads on its own account while it may hold the
//! cache's lock: a recipe's lock file, the recipes a cache recorded. A FIFO there would block
//! the command, and every build waiting on the lock; a link to `/dev/zero` would be read until
//! memory runs out. So only a regular file is read (a link to one is that file, as the user
//! means it), and no further than the size it had when opened.

use std::io::Read as _;
use std::path::Path;

/// What reading a file of the user's found.
#[derive(Debug, PartialEq)]
pub enum UserFile {
    Text(String),
    Missing,
    /// Something else than a regular file, in words (`"a FIFO (a named pipe)"`).
    Not(&'static str),
}

/// Reads the text at `path` (see the module docs); an I/O error, or text that is not UTF-8,
/// is an error.
pub fn read_text(path: &Path) -> std::io::Result<UserFile> {
    match super::load::file_kind(path) {
        crate::recipe::FileKind::File => {}
        crate::recipe::FileKind::Missing => return Ok(UserFile::Missing),
        crate::recipe::FileKind::Other(what) => return Ok(UserFile::Not(what)),
    }
    let file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    if !meta.is_file() {
        return Ok(UserFile::Not("not a regular file"));
    }
    let mut bytes = Vec::with_capacity(usize::try_from(meta.len()).unwrap_or(0));
    file.take(meta.len()).read_to_end(&mut bytes)?;
    String::from_utf8(bytes)
        .map(UserFile::Text)
        .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_is_read_and_a_missing_one_is_missing() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("r.toml.lock");
        assert_eq!(read_text(&p).unwrap(), UserFile::Missing);
        std::fs::write(&p, "version = 1\n").unwrap();
        assert_eq!(
            read_text(&p).unwrap(),
            UserFile::Text("version = 1\n".into())
        );
        std::fs::write(&p, b"\xff").unwrap();
        assert!(read_text(&p).is_err(), "not UTF-8");
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_a_device_link_or_a_directory_is_named_without_being_read() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("fifo");
        if std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .is_ok_and(|s| s.success())
        {
            assert_eq!(
                read_text(&fifo).unwrap(),
                UserFile::Not("a FIFO (a named pipe)")
            );
        } else {
            eprintln!("skipped the FIFO: mkfifo is not available");
        }
        let zero = dir.path().join("zero");
        std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
        assert_eq!(read_text(&zero).unwrap(), UserFile::Not("a device"));
        assert_eq!(read_text(dir.path()).unwrap(), UserFile::Not("a directory"));
    }
}
