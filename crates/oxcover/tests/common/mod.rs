//! Helpers the command-line test files share: the binary, a scratch
//! folder per test process, paths from the repository root, and a
//! command that must succeed.

use std::path::PathBuf;
use std::process::Command;

/// The `oxcover` binary under test.
pub(crate) fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_oxcover")
}

/// `rel` (a path from the repository root) as an absolute path.
pub(crate) fn root(rel: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(rel)
        .display()
        .to_string()
}

/// A fresh folder for this process's files named `name`.
pub(crate) fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("oxcover-cli-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create scratch dir");
    dir
}

/// Runs `oxcover ARGS`, which must exit 0; its stdout and stderr.
pub(crate) fn run(args: &[&str]) -> (String, String) {
    let out = Command::new(bin())
        .args(args)
        .output()
        .expect("run oxcover");
    let (o, e) = (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    );
    assert_eq!(out.status.code(), Some(0), "{args:?}: {e}");
    (o, e)
}
