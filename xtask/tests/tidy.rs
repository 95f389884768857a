//! Tidy checks run by plain `cargo test`: the house rules that keep the layout
//! readable (`../shared/docs/STYLE.md`).

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root")
        .to_path_buf()
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("readable dir").flatten() {
        let p = e.path();
        if p.is_dir() {
            if p.file_name().is_some_and(|n| n != "target") {
                rust_files(&p, out);
            }
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

fn sources() -> Vec<PathBuf> {
    let mut v = Vec::new();
    rust_files(&root().join("crates"), &mut v);
    rust_files(&root().join("xtask"), &mut v);
    v
}

#[test]
fn no_grab_bag_modules() {
    for f in sources() {
        let stem = f.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        assert!(
            !["utils", "util", "helpers", "helper", "common", "misc"].contains(&stem),
            "{}: name modules after what they hold",
            f.display()
        );
    }
}

#[test]
fn every_module_says_what_it_holds() {
    for f in sources() {
        let text = std::fs::read_to_string(&f).expect("readable source");
        assert!(
            text.trim_start().starts_with("//!"),
            "{}: start with a //! module doc",
            f.display()
        );
    }
}

#[test]
fn no_placeholders_in_library_code() {
    for f in sources() {
        let text = std::fs::read_to_string(&f).expect("readable source");
        // Spelled in pieces so this file does not trip its own check.
        for bad in [
            concat!("todo", "!("),
            concat!("unimplemented", "!("),
            concat!("dbg", "!("),
        ] {
            assert!(!text.contains(bad), "{}: contains {bad}", f.display());
        }
    }
}

/// Rank of each crate in the dependency order; a crate may depend only on lower ranks.
fn rank(name: &str) -> Option<u32> {
    Some(match name {
        "oxcover-grid" => 0,
        "oxcover-distance" => 1,
        "oxcover-decomp" => 2,
        "oxcover-robot" | "oxcover-vision" => 3,
        "oxcover-planners" => 4,
        "oxcover" => 5,
        "xtask" => 6,
        _ => return None,
    })
}

#[test]
fn dependencies_point_one_way_and_lints_are_shared() {
    let mut manifests: Vec<PathBuf> = std::fs::read_dir(root().join("crates"))
        .expect("crates dir")
        .flatten()
        .map(|e| e.path().join("Cargo.toml"))
        .collect();
    manifests.push(root().join("xtask/Cargo.toml"));
    for m in manifests {
        let text = std::fs::read_to_string(&m).expect("manifest");
        let name = text
            .lines()
            .find_map(|l| l.strip_prefix("name = \""))
            .and_then(|l| l.strip_suffix('"'))
            .expect("package name");
        let me = rank(name).unwrap_or_else(|| panic!("{name}: add it to the rank table"));
        assert!(
            text.contains("[lints]\nworkspace = true"),
            "{name}: use the workspace lints"
        );
        let deps = text.split("[dependencies]").nth(1).unwrap_or("");
        let deps = deps.split("\n[").next().unwrap_or("");
        for line in deps.lines() {
            let dep = line.split(['=', '.', ' ']).next().unwrap_or("").trim();
            if let Some(r) = rank(dep) {
                assert!(r < me, "{name} depends on {dep}, which is not below it");
            }
        }
    }
}

#[test]
fn ci_runs_the_readme_test_command() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let ci = std::fs::read_to_string(root().join(".ci/run")).expect(".ci/run");
    let blocks: Vec<&str> = readme.split("```").skip(1).step_by(2).collect();
    let second = blocks.get(1).expect("README has a second code block");
    let cmd = second
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with("cargo"))
        .expect("a cargo command");
    assert!(
        ci.contains(cmd),
        ".ci/run must run the README's test command `{cmd}`"
    );
}
