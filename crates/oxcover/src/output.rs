//! Writing outputs whole or not at all.
//!
//! [`write_files`] writes every file of a set aside first (a hidden
//! temporary file in the target's own folder), and only when all of them
//! are written renames them into place; if any write fails, the temporary
//! files are removed and no target is touched. A rename within one folder
//! is atomic, so a reader (or a run interrupted by SIGINT or SIGTERM) sees
//! either the old file or the whole new one, never half of it.
//!
//! The temporary files in flight are registered: on SIGINT or SIGTERM the
//! command line calls [`abandon`], which removes them (waiting for a set
//! being renamed into place to finish) so an interrupted run leaves nothing
//! behind. Only SIGKILL, which no program can catch, can leave a hidden
//! `.NAME.oxcover-PID-K.tmp` beside a target; the target itself is still
//! whole or absent.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Temporary files written and not yet renamed into place.
static STAGED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Removes every temporary file of this process not yet renamed into place
/// and holds back every later write; for a signal handler about to exit. A set
/// being renamed into place is finished first (the lock is held while it
/// is).
pub fn abandon() {
    let mut staged = STAGED
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    for tmp in staged.drain(..) {
        let _ = std::fs::remove_file(tmp);
    }
    // Keep the lock: no write may start after this.
    std::mem::forget(staged);
}

fn in_flight() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    STAGED
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn unregister(tmps: &[&Path]) {
    in_flight().retain(|p| !tmps.contains(&p.as_path()));
}

use crate::error::{Error, Result};

/// The hidden temporary name of `target` for this process.
fn temporary(target: &Path, k: usize) -> PathBuf {
    let name = target
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    target.with_file_name(format!(".{name}.oxcover-{}-{k}.tmp", std::process::id()))
}

/// Writes `files` (path, contents) whole or not at all; returns the paths.
///
/// # Errors
/// [`Error::Write`] naming the first file that could not be written (its
/// folder missing or read-only, a device that refuses writes, a full disk);
/// nothing is left behind then.
pub fn write_files(files: Vec<(PathBuf, Vec<u8>)>) -> Result<Vec<PathBuf>> {
    let mut staged: Vec<(PathBuf, PathBuf)> = Vec::with_capacity(files.len());
    let mut streams: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut shown: Vec<PathBuf> = Vec::with_capacity(files.len());
    let cleanup = |staged: &[(PathBuf, PathBuf)]| {
        for (_, tmp) in staged {
            let _ = std::fs::remove_file(tmp);
        }
        unregister(&staged.iter().map(|(_, t)| t.as_path()).collect::<Vec<_>>());
    };
    for (k, (target, bytes)) in files.into_iter().enumerate() {
        shown.push(target.clone());
        // A device, pipe or socket (`--out /dev/null`, a fifo) is written
        // to as it is: renaming over it would replace it with a file.
        let existing = std::fs::metadata(&target).ok();
        if existing.as_ref().is_some_and(|m| !m.is_file()) {
            streams.push((target, bytes));
            continue;
        }
        // A link to a file is followed: the file it names is replaced, the
        // link stays.
        let target = if existing.is_some() {
            std::fs::canonicalize(&target).unwrap_or(target)
        } else {
            target
        };
        let tmp = temporary(&target, k);
        in_flight().push(tmp.clone());
        let written = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .and_then(|mut f| {
                f.write_all(&bytes)?;
                f.sync_all()
            });
        if let Err(e) = written {
            let _ = std::fs::remove_file(&tmp);
            unregister(&[&tmp]);
            cleanup(&staged);
            return Err(Error::write(&target, e));
        }
        staged.push((target, tmp));
    }
    for (target, bytes) in &streams {
        let written = std::fs::OpenOptions::new()
            .write(true)
            .open(target)
            .and_then(|mut f| f.write_all(bytes));
        if let Err(e) = written {
            cleanup(&staged);
            return Err(Error::write(target, e));
        }
    }
    // The set is renamed under the lock: a signal handler's `abandon` waits
    // until every file of it is in place.
    let mut registry = in_flight();
    for (i, (target, tmp)) in staged.iter().enumerate() {
        if let Err(e) = std::fs::rename(tmp, target) {
            drop(registry);
            cleanup(&staged[i..]);
            return Err(Error::write(target, e));
        }
    }
    registry.retain(|p| !staged.iter().any(|(_, t)| t == p));
    Ok(shown)
}

/// Writes one file whole or not at all ([`write_files`]).
///
/// # Errors
/// As [`write_files`].
pub fn write_file(path: &Path, bytes: Vec<u8>) -> Result<()> {
    write_files(vec![(path.to_path_buf(), bytes)]).map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_set_leaves_nothing() {
        let dir = std::env::temp_dir().join(format!("oxcover-output-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let a = dir.join("a.txt");
        let missing = dir.join("no/such/folder/b.txt");
        assert!(write_files(vec![(a.clone(), b"a".to_vec()), (missing, b"b".to_vec())]).is_err());
        assert!(!a.exists());
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            0,
            "temporary files left"
        );
        write_file(&a, b"whole".to_vec()).unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), b"whole");
    }

    #[test]
    fn devices_and_links_are_written_through() {
        let dir = std::env::temp_dir().join(format!("oxcover-output-dev-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // A character device stays one: written to, not replaced.
        write_file(Path::new("/dev/null"), b"gone".to_vec()).unwrap();
        let meta = std::fs::metadata("/dev/null").unwrap();
        assert!(!meta.is_file(), "/dev/null was replaced by a file");
        // A link to a file keeps being a link; the file gets the new bytes.
        let file = dir.join("real.csv");
        let link = dir.join("link.csv");
        std::fs::write(&file, b"old").unwrap();
        std::os::unix::fs::symlink(&file, &link).unwrap();
        write_file(&link, b"new".to_vec()).unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read(&file).unwrap(), b"new");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
