//! oxcover's project tasks (`cargo xtask <task>`), as a library so that tests
//! can check them (sweep determinism, shard merging).
//!
//! - [`acceptance`]: every complete planner on every real map (floor plans at
//!   0.3 m, unit grids with default radii), judged like `oxcover eval`;
//!   `docs/acceptance.md`.
//! - [`bench`](mod@bench): run the criterion benchmarks and write their figures, with the
//!   reference ratios and cells-touched counts, into `docs/benchmarks.md`.
//! - [`diagram`]: the stages of `lanes` as one picture, `docs/lanes.svg`.
//! - [`efficiency`]: every complete planner, rooms on and off, on the real
//!   floor plans, scored by estimated time; `docs/efficiency.md`, with
//!   [`bare_rooms`]: synthetic rooms, bare and with specks, beside the
//!   time their U-turns alone would take, and [`lane_ceiling`]: each map's
//!   ceiling for a plan of lanes and loops that wastes nothing else.
//! - [`fuzz`]: every input parser fed mutated fixture bytes; any panic or
//!   slow input is a finding.
//! - [`memory_map`]: the large generated map of the memory measurements.
//! - [`maps`]: plan and score every real map in `../shared/maps`; `docs/maps.md`.
//! - [`reproduce`]: the paper reproductions (`siamantas2010`,
//!   `siamantas2010-tracking`, `zhang2008`, `pavlicek2002`, `floorplans`,
//!   `lee2011`),
//!   each writing `docs/reproduction/<name>.md` with a table, an SVG figure
//!   and the command.
//! - [`segmentation`]: every room segmentation scored on the ipa room
//!   benchmark against its ground truth; `docs/segmentation.md`.
//! - [`sweep`]: any planner set over seeded random maps, one JSON line per map,
//!   deterministic shards for job arrays, and the merge of shards.
//! - [`plot`]: the small SVG line charts of the reproduction pages.

pub mod acceptance;
pub mod bare_rooms;
pub mod bench;
pub mod diagram;
pub mod efficiency;
pub mod fuzz;
pub mod lane_ceiling;
pub mod maps;
pub mod memory_map;
pub mod plot;
pub mod reproduce;
pub mod segmentation;
pub mod sweep;

use std::path::{Path, PathBuf};

/// The workspace root (this crate lives in `<root>/xtask`).
#[must_use]
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// `../shared/maps` next to the workspace, if present.
#[must_use]
pub fn shared_maps() -> Option<PathBuf> {
    let p = root().join("../shared/maps");
    p.is_dir().then_some(p)
}

/// Files under `dir` (recursively, sorted) with one of the extensions `ext`.
#[must_use]
pub fn map_files(dir: &Path, ext: &[&str]) -> Vec<PathBuf> {
    let mut out = Vec::new();
    collect_files(dir, ext, &mut out);
    out
}

fn collect_files(dir: &Path, ext: &[&str], out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            collect_files(&p, ext, out);
        } else if p
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| ext.contains(&e))
        {
            out.push(p);
        }
    }
}

/// The real floor plans of the issue-4 experiments: every ROS map of
/// `../shared/maps/ros` (with its yaml) and every plan of
/// `../shared/maps/ipa-floorplans` (images at 0.05 m/px, contract
/// thresholds), named by their path under `../shared/maps`.
///
/// # Errors
/// When `../shared/maps` is missing or a map cannot be read.
pub fn floor_plans() -> anyhow::Result<Vec<(String, oxcover_grid::OccupancyGrid)>> {
    use oxcover_grid::io::{ReadOptions, read_map};
    let Some(root) = shared_maps() else {
        anyhow::bail!("../shared/maps not found next to the workspace");
    };
    let name = |p: &Path| p.strip_prefix(&root).unwrap_or(p).display().to_string();
    let mut out = Vec::new();
    for p in map_files(&root.join("ros"), &["yaml"]) {
        out.push((name(&p), read_map(&p, &ReadOptions::default())?));
    }
    let opts = ReadOptions {
        resolution: 0.05,
        ..ReadOptions::default()
    };
    for p in map_files(&root.join("ipa-floorplans"), &["png", "pgm"]) {
        out.push((name(&p), read_map(&p, &opts)?));
    }
    Ok(out)
}

/// The rule the ipa benchmark reads its floor plans by
/// (`../shared/maps/ipa-floorplans/SOURCE.md`: grey above 250 free, every
/// other value an obstacle), as thresholds on the contract's occupancy
/// scale (`(255 - v) / 255`).
#[must_use]
pub fn ipa_benchmark_thresholds() -> oxcover_grid::io::Thresholds {
    let cut = 4.5 / 255.0;
    oxcover_grid::io::Thresholds {
        occupied_thresh: cut,
        free_thresh: cut,
        ..oxcover_grid::io::Thresholds::default()
    }
}

/// The floor plan `name` (as [`floor_plans`] names it) read by the ipa
/// benchmark's own rule ([`ipa_benchmark_thresholds`]), where that frees
/// or blocks a cell that `contract` (the contract's reading of it) does
/// not (unknown and occupied are both blocked to a planner).
///
/// # Errors
/// When `../shared/maps` is missing or the map cannot be read.
pub fn ipa_benchmark_reading(
    name: &str,
    contract: &oxcover_grid::OccupancyGrid,
) -> anyhow::Result<Option<oxcover_grid::OccupancyGrid>> {
    use oxcover_grid::io::{ReadOptions, read_map};
    let Some(root) = shared_maps() else {
        anyhow::bail!("../shared/maps not found next to the workspace");
    };
    let opts = ReadOptions::default()
        .resolution(contract.resolution())
        .thresholds(ipa_benchmark_thresholds());
    let map = read_map(&root.join(name), &opts)?;
    let free = |m: &oxcover_grid::OccupancyGrid| {
        m.cells()
            .as_slice()
            .iter()
            .map(|&o| o == oxcover_grid::Occupancy::Free)
            .collect::<Vec<_>>()
    };
    Ok((free(&map) != free(contract)).then_some(map))
}

/// Replaces the text between `<!-- BEGIN name -->` and `<!-- END name -->` in `file`.
///
/// # Errors
/// When the file cannot be read or written, or lacks the markers.
pub fn replace_section(file: &Path, name: &str, body: &str) -> anyhow::Result<()> {
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

/// A progress bar on stderr (drawn only when stderr is a terminal).
#[must_use]
pub fn progress(len: u64, what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(len);
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} ({eta})")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(what.to_string());
    bar
}

#[cfg(test)]
mod tests {
    use oxcover_grid::Occupancy::{Free, Occupied};

    #[test]
    fn the_ipa_rule_frees_only_grey_above_250() {
        let t = super::ipa_benchmark_thresholds();
        let read = |v: u8| t.classify(f64::from(v));
        assert_eq!(
            [read(255), read(251), read(250), read(230), read(0)],
            [Free, Free, Occupied, Occupied, Occupied]
        );
    }
}
