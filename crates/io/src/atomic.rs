//! Files that appear whole or not at all.
//!
//! A plan folder is read by other tools (QGroundControl, the report, `evaluate`), so a
//! half-written `plan.json` after a full disk or a kill is worse than none: it parses as
//! garbage or, worse, as a shorter plan. Each output is written to a temporary file in the
//! same folder and renamed over the target once complete and synced; a rename within one
//! file system is atomic on POSIX, so a reader sees the old file or the new one.

use std::io::Write as _;
use std::path::Path;

/// Writes `contents` to `path` atomically (temporary file in the same folder, sync,
/// rename). On error the target is untouched and the temporary file is removed.
///
/// # Errors
/// Creating, writing, syncing or renaming the temporary file failed.
pub fn write_atomic(path: &Path, contents: &[u8]) -> std::io::Result<()> {
    write_atomic_with(path, |w| w.write_all(contents))
}

/// Writes what `fill` writes to `path` atomically, through a buffer: a large output (the
/// convergence trace of a long run) streams to disk instead of being built in memory first.
///
/// # Errors
/// Creating, writing (`fill` included), syncing or renaming the temporary file failed.
pub fn write_atomic_with(
    path: &Path,
    fill: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    if !dir.is_dir() {
        // Said of the folder, not of the temporary file the error would otherwise name.
        return Err(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            format!("the folder {} does not exist", dir.display()),
        ));
    }
    let mut tmp = tempfile::Builder::new()
        .prefix(&format!(".{name}."))
        .suffix(".partial")
        .tempfile_in(dir)?;
    {
        let mut buffered = std::io::BufWriter::new(tmp.as_file_mut());
        fill(&mut buffered)?;
        buffered.flush()?;
    }
    // A temporary file is created private (0600); the result is an ordinary output file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))?;
    }
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_the_file_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("plan.json");
        write_atomic(&p, b"old").unwrap();
        write_atomic(&p, b"new").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"new");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(names.len(), 1);
        // A folder that does not exist: an error, nothing written.
        let missing = dir.path().join("no/such/x");
        let e = write_atomic(&missing, b"x").unwrap_err().to_string();
        assert!(e.contains("no/such does not exist"), "{e}");
        assert!(!e.contains(".partial"), "{e}");
    }

    #[test]
    fn a_failed_fill_leaves_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("convergence.csv");
        write_atomic(&p, b"old").unwrap();
        let e = write_atomic_with(&p, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("disk full"))
        })
        .unwrap_err();
        assert_eq!(e.to_string(), "disk full");
        assert_eq!(std::fs::read(&p).unwrap(), b"old");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        write_atomic_with(&p, |w| writeln!(w, "a,b")).unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"a,b\n");
    }
}
