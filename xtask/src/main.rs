//! `cargo xtask <task>`: project tasks that are not part of any library.
//!
//! - `bench`: run the criterion benchmarks and write their figures (with the
//!   reference ratios and cells-touched counts) into `docs/benchmarks.md`.
//! - `maps`: plan and score every real map in `../shared/maps` and write the
//!   table to `docs/maps.md`.
//!
//! One module per task; results go under `target/xtask/` and `docs/`.

mod bench;
mod maps;

use std::path::{Path, PathBuf};

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(name = "cargo xtask", about = "oxcover project tasks")]
struct Cli {
    #[command(subcommand)]
    task: Task,
}

#[derive(Subcommand)]
enum Task {
    /// Run the criterion benches and update docs/benchmarks.md.
    Bench {
        /// Reuse the last criterion results instead of running the benches.
        #[arg(long)]
        no_run: bool,
    },
    /// Plan and score every real map in ../shared/maps; write docs/maps.md.
    Maps {
        /// Only maps whose path contains this text.
        #[arg(long)]
        filter: Option<String>,
    },
}

fn main() -> anyhow::Result<()> {
    let cli = Cli::parse();
    match cli.task {
        Task::Bench { no_run } => bench::run(no_run),
        Task::Maps { filter } => maps::run(filter.as_deref()),
    }
}

/// The workspace root (this crate lives in `<root>/xtask`).
pub(crate) fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// `../shared/maps` next to the workspace, if present.
pub(crate) fn shared_maps() -> Option<PathBuf> {
    let p = root().join("../shared/maps");
    p.is_dir().then_some(p)
}

/// Replaces the text between `<!-- BEGIN name -->` and `<!-- END name -->` in `file`.
pub(crate) fn replace_section(file: &Path, name: &str, body: &str) -> anyhow::Result<()> {
    let text = std::fs::read_to_string(file)?;
    let (b, e) = (
        format!("<!-- BEGIN {name} -->"),
        format!("<!-- END {name} -->"),
    );
    let (Some(i), Some(j)) = (text.find(&b), text.find(&e)) else {
        anyhow::bail!("{}: markers {b} / {e} not found", file.display());
    };
    let new = format!("{}{b}\n{body}{}", &text[..i], &text[j..]);
    std::fs::write(file, new)?;
    Ok(())
}
