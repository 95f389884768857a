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
//! behind; so is the probe [`check_outputs`] creates to test a folder.
//! Only SIGKILL, which no program can catch, can leave a hidden
//! `.NAME.oxcover-PID-K.tmp` (or `.oxcover-probe-PID`) beside a target;
//! the target itself is still whole or absent.

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

/// Creates `tmp` (which must not exist) and registers it, both under the
/// lock: a signal handler's [`abandon`] either runs first (and this waits
/// for the process to exit) or finds the file and removes it. Registering
/// first and creating after the lock is let go would let a handler run in
/// between and leave the file behind.
fn create_registered(tmp: &Path) -> std::io::Result<std::fs::File> {
    let mut registry = in_flight();
    registry.push(tmp.to_path_buf());
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(tmp)
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
        let written = create_registered(&tmp).and_then(|mut f| {
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

/// A path as it will be opened: canonical when it exists, else its
/// existing folder made canonical with the file name added.
fn resolved(p: &Path) -> std::path::PathBuf {
    if let Ok(c) = p.canonicalize() {
        return c;
    }
    let parent = p.parent().filter(|d| !d.as_os_str().is_empty());
    let dir = parent.map_or_else(|| Path::new(".").canonicalize(), Path::canonicalize);
    match (dir, p.file_name()) {
        (Ok(d), Some(f)) => d.join(f),
        _ => p.to_path_buf(),
    }
}

/// An output a command will write: its option, its path, and the file name
/// endings its format allows (empty: any name).
pub type Output<'a> = (&'static str, &'a Path, &'static [&'static str]);

/// Any file name.
pub const ANY: &[&str] = &[];
/// An SVG picture.
pub const SVG: &[&str] = &["svg"];
/// A PNG picture.
pub const PNG: &[&str] = &["png"];
/// A picture in the format its name ends in.
pub const PICTURE: &[&str] = &["svg", "png"];
/// A ROS 2 bag in MCAP storage.
pub const MCAP: &[&str] = &["mcap"];
/// A ROS map (its image is written beside it).
pub const YAML: &[&str] = &["yaml"];

/// The outputs among `candidates` that were asked for.
pub fn asked<'a, const N: usize>(
    candidates: [(&'static str, Option<&'a Path>, &'static [&'static str]); N],
) -> Vec<Output<'a>> {
    candidates
        .into_iter()
        .filter_map(|(f, p, e)| p.map(|p| (f, p, e)))
        .collect()
}

/// Refuses, before any work, an output that could not be written or would
/// destroy a file: its folder missing, not writable or not a folder; the
/// path a folder; a file name ending other than its format's; one of the
/// inputs or another output (`--out f.csv --report f.csv`, `plan m.pgm
/// --out m.pgm`: the second write would silently destroy the first file).
pub fn check_outputs(inputs: &[&Path], outputs: &[Output<'_>]) -> Result<()> {
    let ins: Vec<std::path::PathBuf> = inputs.iter().map(|p| resolved(p)).collect();
    let mut seen: Vec<(&'static str, std::path::PathBuf)> = Vec::new();
    for &(flag, out, endings) in outputs {
        let bad = |expected: String| Error::BadParameter {
            name: flag,
            value: out.display().to_string(),
            expected,
        };
        let r = resolved(out);
        if let Some(i) = ins.iter().position(|x| *x == r) {
            return Err(bad(format!(
                "a file other than the input {}",
                inputs[i].display()
            )));
        }
        let stream = std::fs::metadata(out).is_ok_and(|m| !m.is_file() && !m.is_dir());
        if let Some((other, _)) = seen.iter().find(|(_, x)| *x == r && !stream) {
            return Err(bad(format!("a file other than the one {other} writes")));
        }
        let ext = out
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .unwrap_or_default();
        if !endings.is_empty() && !endings.contains(&ext.as_str()) {
            return Err(bad(format!("a file name ending in {}", one_of(endings))));
        }
        if out.is_dir() {
            return Err(bad("a file name, not a folder".into()));
        }
        let folder = out
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or_else(|| Path::new("."));
        if !folder.is_dir() {
            return Err(bad(format!(
                "a file in an existing folder ({} does not exist)",
                folder.display()
            )));
        }
        if !writable(folder) {
            return Err(bad(format!(
                "a file in a folder this user may write ({} is not writable)",
                folder.display()
            )));
        }
        seen.push((flag, r));
    }
    Ok(())
}

/// `.a`, `.a or .b`, `.a, .b or .c`.
fn one_of(endings: &[&str]) -> String {
    let names: Vec<String> = endings.iter().map(|e| format!(".{e}")).collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => names.concat(),
    }
}

/// Whether a file can be created in `folder` (tried with a probe file that
/// is removed at once: permission bits do not tell about read-only mounts).
///
/// The probe lives while the registry of temporary files is locked, so a
/// signal handler's [`abandon`] runs before it is created or after it is
/// removed: an interrupted run leaves no probe behind.
fn writable(folder: &Path) -> bool {
    let probe = folder.join(format!(".oxcover-probe-{}", std::process::id()));
    let _registry = in_flight();
    match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
    {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            true
        }
        // Left over by a killed run of this very process id: still writable.
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => true,
        Err(_) => false,
    }
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
