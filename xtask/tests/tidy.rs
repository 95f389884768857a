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

/// Most lines a source file may hold, tests included: a file is one
/// algorithm or stage, small enough to read whole.
const MAX_LINES: usize = 800;

/// The files under `dirs` longer than [`MAX_LINES`], with their lengths.
fn overlong(dirs: &[PathBuf]) -> Vec<(PathBuf, usize)> {
    let mut files = Vec::new();
    for d in dirs {
        rust_files(d, &mut files);
    }
    files.sort();
    files
        .into_iter()
        .filter_map(|f| {
            let n = std::fs::read_to_string(&f)
                .expect("readable source")
                .lines()
                .count();
            (n > MAX_LINES).then_some((f, n))
        })
        .collect()
}

#[test]
fn no_file_passes_800_lines() {
    let long = overlong(&[root().join("crates"), root().join("xtask")]);
    assert!(
        long.is_empty(),
        "split these by stage or concern (at most {MAX_LINES} lines, tests included): {long:?}"
    );
}

/// The rule finds a planted file of 801 lines and lets one of 800 pass.
#[test]
fn the_line_rule_finds_a_planted_long_file() {
    let dir = std::env::temp_dir().join(format!("oxcover-tidy-{}", std::process::id()));
    let nested = dir.join("src/stage");
    std::fs::create_dir_all(&nested).expect("scratch folder");
    let lines = |n: usize| "//! line\n".repeat(n);
    std::fs::write(nested.join("ok.rs"), lines(MAX_LINES)).expect("write");
    std::fs::write(nested.join("long.rs"), lines(MAX_LINES + 1)).expect("write");
    let found = overlong(std::slice::from_ref(&dir));
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].0.ends_with("src/stage/long.rs"), "{found:?}");
    assert_eq!(found[0].1, MAX_LINES + 1);
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
        "oxcover-robot" | "oxcover-vision" | "oxcover-world" | "oxcover-rosbag" => 3,
        "oxcover-planners" => 4,
        "oxcover" => 5,
        "xtask" | "oxcover-py" => 6,
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
        if name == "oxcover-py" {
            // PyO3's macros expand to `unsafe` blocks, which the workspace's
            // `forbid` refuses: the bindings deny unsafe code of their own
            // and keep the other workspace lints.
            for lint in [
                "unsafe_code = \"deny\"",
                "missing_docs = \"warn\"",
                "unwrap_used = \"warn\"",
            ] {
                assert!(text.contains(lint), "{name}: keep `{lint}`");
            }
        } else {
            assert!(
                text.contains("[lints]\nworkspace = true"),
                "{name}: use the workspace lints"
            );
        }
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
fn ci_builds_and_tests_the_python_package_as_the_readme_installs_it() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let ci = std::fs::read_to_string(root().join(".ci/run")).expect(".ci/run");
    let install = "pip install ./crates/oxcover-py";
    assert!(
        readme.contains(install),
        "the README installs with `{install}`"
    );
    assert!(
        ci.contains("pip install --quiet --disable-pip-version-check ./crates/oxcover-py"),
        ".ci/run must install the package as the README does"
    );
    assert!(
        ci.contains("-m pytest -q crates/oxcover-py/tests"),
        ".ci/run must run pytest"
    );
    let example = "crates/oxcover-py/examples/plot_plan.py";
    assert!(
        readme.contains(&format!("python {example}")) && ci.contains(example),
        ".ci/run must run the README's example script"
    );
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

/// The module path of a source file under `src` (`lib.rs`/`main.rs` → the
/// root `""`, `a/mod.rs` and `a.rs` → `a`, `a/b.rs` → `a::b`).
fn module_of(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).ok()?;
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    Some(parts.join("::"))
}

/// Module-to-module references of one crate's `src`: `crate::a::b` and
/// `super::x` paths, resolved to the longest known module. Re-exports
/// (`pub use`), module declarations and the crate root are left out: a
/// root that re-exports its modules is no dependency of theirs.
fn module_edges(src: &Path) -> Vec<(String, String)> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mods: std::collections::BTreeMap<String, PathBuf> = files
        .iter()
        .filter_map(|f| module_of(src, f).map(|m| (m, f.clone())))
        .collect();
    let resolve = |path: &[&str]| -> Option<String> {
        (1..=path.len())
            .rev()
            .map(|n| path[..n].join("::"))
            .find(|m| mods.contains_key(m))
    };
    let mut edges = Vec::new();
    for (me, file) in &mods {
        let text = std::fs::read_to_string(file).expect("readable source");
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        for line in code.lines().map(str::trim) {
            if line.starts_with("//")
                || line.starts_with("pub use")
                || line.starts_with("pub(crate) use")
            {
                continue;
            }
            for (prefix, base) in [
                ("crate::", Vec::new()),
                ("super::", {
                    let mut b: Vec<&str> = me.split("::").collect();
                    // A `mod.rs`'s `super` is its parent; a file's too.
                    b.pop();
                    b
                }),
            ] {
                for (i, _) in line.match_indices(prefix) {
                    // `crate::` inside a longer identifier (`oxcover_crate::`) is not ours.
                    if line[..i].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
                        continue;
                    }
                    let rest = &line[i + prefix.len()..];
                    let mut path = base.clone();
                    path.extend(
                        rest.split("::")
                            .map(|s| {
                                s.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                                    .next()
                                    .unwrap_or("")
                            })
                            .take_while(|s| {
                                !s.is_empty() && s.starts_with(|c: char| c.is_lowercase())
                            }),
                    );
                    if let Some(to) = resolve(&path).filter(|to| !to.is_empty() && to != me) {
                        edges.push((me.clone(), to));
                    }
                }
            }
        }
    }
    edges.sort();
    edges.dedup();
    edges
}

/// A cycle in `edges`, if any (as the modules along it).
fn find_cycle(edges: &[(String, String)]) -> Option<Vec<String>> {
    use std::collections::BTreeMap;
    let mut next: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (a, b) in edges {
        next.entry(a).or_default().push(b);
    }
    // 0 unvisited, 1 on the stack, 2 done.
    fn visit<'a>(
        n: &'a str,
        next: &BTreeMap<&'a str, Vec<&'a str>>,
        state: &mut BTreeMap<&'a str, u8>,
        stack: &mut Vec<&'a str>,
    ) -> Option<Vec<String>> {
        state.insert(n, 1);
        stack.push(n);
        for &m in next.get(n).map(Vec::as_slice).unwrap_or_default() {
            match state.get(m).copied().unwrap_or(0) {
                1 => {
                    let at = stack.iter().position(|&s| s == m).unwrap_or(0);
                    let mut cycle: Vec<String> =
                        stack[at..].iter().map(|s| (*s).to_string()).collect();
                    cycle.push(m.to_string());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(m, next, state, stack) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        stack.pop();
        state.insert(n, 2);
        None
    }
    let mut state = BTreeMap::new();
    let nodes: Vec<&str> = next.keys().copied().collect();
    for n in nodes {
        if state.get(n).copied().unwrap_or(0) == 0 {
            let mut stack = Vec::new();
            if let Some(c) = visit(n, &next, &mut state, &mut stack) {
                return Some(c);
            }
        }
    }
    None
}

#[test]
fn no_import_circles_between_modules_of_a_crate() {
    let mut crates: Vec<PathBuf> = std::fs::read_dir(root().join("crates"))
        .expect("crates dir")
        .flatten()
        .map(|e| e.path().join("src"))
        .collect();
    crates.push(root().join("xtask/src"));
    for src in crates {
        let edges = module_edges(&src);
        if let Some(cycle) = find_cycle(&edges) {
            panic!("{}: import circle {}", src.display(), cycle.join(" -> "));
        }
    }
}

#[test]
fn the_cycle_finder_finds_cycles() {
    let e = |a: &str, b: &str| (a.to_string(), b.to_string());
    assert!(find_cycle(&[e("a", "b"), e("b", "c")]).is_none());
    let c = find_cycle(&[e("a", "b"), e("b", "c"), e("c", "a")]).expect("a cycle");
    assert_eq!(c.first(), c.last());
}

/// Where the planners' input and the coverage problem may be built: their
/// home (`problem/`), the grid crate (the contract's cells), the metrics
/// (a path is scored on the contract's problem from its own start) and the
/// boundary pass's own tests (it takes the contract's cells).
#[test]
fn planner_inputs_are_built_in_their_home() {
    let home = |f: &Path| {
        let s = f.to_string_lossy().replace('\\', "/");
        s.contains("oxcover-planners/src/problem/")
            || s.contains("crates/oxcover-grid/")
            || s.ends_with("crates/oxcover/src/metrics.rs")
            || s.ends_with("oxcover-planners/src/boundary_pass.rs")
            || s.ends_with("xtask/tests/tidy.rs")
    };
    for f in sources() {
        if home(&f) {
            continue;
        }
        let text = std::fs::read_to_string(&f).expect("readable source");
        for bad in [
            "PlannerInput {",
            "PlannerInput::new",
            "Coverability::new(",
            "Coverability::with_start_cell(",
            "Coverability {",
            "fn coarse_block",
            "fn largest_region_start",
        ] {
            assert!(
                !text.contains(bad),
                "{}: `{bad}` outside its home; build a CoverageProblem (oxcover_planners::problem)",
                f.display()
            );
        }
    }
}

/// Papers are named by author and year (Siamantas 2010, Zhang & Yan 2008,
/// Lee 2011, Demir 2018, Pavlíček 2002), never by the label of their file
/// in `../shared/seeds`, which reads like the random `seed` everywhere.
#[test]
fn papers_are_named_by_author_and_year() {
    let label = concat!("seed", " 00");
    let mut files = sources();
    for dir in ["docs", "fixtures/worlds"] {
        let mut stack = vec![root().join(dir)];
        while let Some(d) = stack.pop() {
            for e in std::fs::read_dir(&d).expect("readable dir").flatten() {
                let p = e.path();
                if p.is_dir() {
                    stack.push(p);
                } else if p.extension().is_some_and(|x| x == "md" || x == "ron") {
                    files.push(p);
                }
            }
        }
    }
    files.push(root().join("README.md"));
    for f in files {
        let text = std::fs::read_to_string(&f).expect("readable file");
        assert!(
            !text.to_lowercase().contains(label),
            "{}: name the paper by author and year, not `{label}…`",
            f.display()
        );
    }
}

/// Coordinates in public signatures are `Point`, `Vector` or `Pose`
/// (`oxcover_grid::math`), never bare tuples. The pairs allowed are not
/// coordinates: (v, ω) commands and wheel speeds, PID gains, y and size
/// ranges, HSV colours, a cost before and after.
#[test]
fn no_tuple_coordinates_in_public_signatures() {
    let allowed = [
        "fn wheel_speeds",
        "fn from_wheels",
        "fn wheel_rates",
        "fn saturate",
        "pub fillet_time",
        "pub size",
        "pub x: (f64, f64)",
        "pub span",
        "pub gains",
        "fn wall(",
        "fn command(",
        "fn hsv(",
        "fn index(",
    ];
    let mut files = Vec::new();
    rust_files(&root().join("crates"), &mut files);
    for f in files {
        let s = f.to_string_lossy().replace('\\', "/");
        if s.contains("/tests/") || s.contains("/benches/") {
            continue;
        }
        let text = std::fs::read_to_string(&f).expect("readable source");
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        for line in code.lines().map(str::trim) {
            let public =
                line.starts_with("pub fn") || (line.starts_with("pub ") && line.contains(": "));
            if public
                && (line.contains("(f64, f64)") || line.contains("(f64, f64, f64)"))
                && !allowed.iter().any(|a| line.contains(a))
            {
                panic!("{}: `{line}`: use Point, Vector or Pose", f.display());
            }
        }
    }
}
