//! `cargo xtask sweep` and `cargo xtask merge`: planners over seeded random maps.
//!
//! Map `i` of a sweep is generated from seed `seed + i` (unit cells, the
//! contract's default radii), planned by every requested planner without the
//! boundary pass (the planners' own behaviour) from the first cell of the
//! largest free region, and written as one JSON line. Maps run in parallel with
//! rayon; lines are written in map order and contain no timing unless asked,
//! so the output is byte-identical whatever the thread count (tested).
//! `--shard I/N` runs the maps with `i % N == I`, so a sweep too big for one
//! machine runs as a job array; `merge` combines the shards' lines into the
//! same summary a single run gives (sums are taken in map order). Every file
//! starts with a [`ShardHeader`], so `merge` refuses a missing, repeated or
//! truncated shard by name instead of summarising fewer maps.

use std::collections::BTreeMap;
use std::fmt;
use std::io::{BufRead, Write};
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::time::Instant;

use oxcover::pipeline::{PlanRequest, plan};
use oxcover::planners::{Start, largest_region_start};
use oxcover_grid::OccupancyGrid;
use oxcover_grid::random::{blobs, random_density, rectangles, uniform_connected};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// How sweep maps are generated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Generator {
    /// Exactly `density · size²` obstacles with 4-connected free space (rejection sampling).
    Connected,
    /// Each cell blocked with probability `density`.
    Density,
    /// Random boxes inside a wall, `density · size² / 20` of them.
    Rectangles,
    /// Random discs inside a wall, `density · size² / 12` of them.
    Blobs,
}

/// A sweep's parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepSpec {
    /// Planner names.
    pub planners: Vec<String>,
    /// Map side in cells.
    pub size: usize,
    /// Share of blocked cells.
    pub density: f64,
    /// Number of maps.
    pub count: usize,
    /// Seed of map 0.
    pub seed: u64,
    /// Map generator.
    pub generator: Generator,
    /// Record planning times.
    pub timing: bool,
}

/// A deterministic slice of a sweep: maps with `i % count == index`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `0..count`.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Default for Shard {
    fn default() -> Self {
        Self { index: 0, count: 1 }
    }
}

impl FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let err = || format!("expected I/N with 0 <= I < N, got `{s}`");
        let (i, n) = s.split_once('/').ok_or_else(err)?;
        let (index, count): (usize, usize) = (
            i.trim().parse().map_err(|_| err())?,
            n.trim().parse().map_err(|_| err())?,
        );
        if count == 0 || index >= count {
            return Err(err());
        }
        Ok(Self { index, count })
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// One planner's result on one map.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlannerRecord {
    /// Moves (`length / resolution`), when the planner ran.
    pub steps: Option<f64>,
    /// Coverage of the coverable cells (no boundary pass).
    pub coverage: f64,
    /// Turns (> 30°).
    pub turns: usize,
    /// The planner's refusal or failure, if any.
    pub error: Option<String>,
    /// Planning time, when `--timing` is on.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub ms: Option<f64>,
}

/// One map's line.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapRecord {
    /// Map index in the sweep.
    pub map: usize,
    /// Seed it was generated from.
    pub seed: u64,
    /// Side in cells.
    pub size: usize,
    /// Free cells.
    pub free: usize,
    /// Start cell `[row, col]`.
    pub start: [usize; 2],
    /// Results by planner name.
    pub results: BTreeMap<String, PlannerRecord>,
}

/// The first line of every file `sweep` writes: the sweep, which shard of
/// it the file holds and how many maps that shard has. `merge` checks the
/// files against their headers, so a missing or truncated shard is an error
/// naming it, never a silently smaller summary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ShardHeader {
    /// The sweep's parameters.
    pub sweep: SweepSpec,
    /// `[index, count]` of this shard.
    pub shard: [usize; 2],
    /// Maps of this shard (`i % count == index`).
    pub maps: usize,
}

impl ShardHeader {
    /// The header of `shard` of `spec`.
    #[must_use]
    pub fn new(spec: &SweepSpec, shard: Shard) -> Self {
        Self {
            sweep: spec.clone(),
            shard: [shard.index, shard.count],
            maps: shard_maps(spec.count, shard).count(),
        }
    }
}

/// The maps of `shard` in a sweep of `count` maps.
fn shard_maps(count: usize, shard: Shard) -> impl Iterator<Item = usize> {
    (0..count).filter(move |i| i % shard.count == shard.index)
}

/// Generates map `i` of a sweep.
#[must_use]
pub fn sweep_map(spec: &SweepSpec, i: usize) -> OccupancyGrid {
    let seed = spec.seed + i as u64;
    let n = spec.size;
    let cells = (spec.density.clamp(0.0, 1.0) * (n * n) as f64).round() as usize;
    match spec.generator {
        Generator::Connected => uniform_connected(n, n, cells, seed)
            .unwrap_or_else(|_| random_density(n, n, spec.density, seed)),
        Generator::Density => random_density(n, n, spec.density, seed),
        Generator::Rectangles => rectangles(n, n, (cells / 20).max(1), (n / 6).max(2), seed),
        Generator::Blobs => blobs(n, n, (cells / 12).max(1), (n / 10).max(1), seed),
    }
}

/// Plans map `i` with every planner of the spec.
#[must_use]
pub fn run_map(spec: &SweepSpec, i: usize) -> MapRecord {
    let map = sweep_map(spec, i);
    // The robot is a point: admissible cells are the free ones.
    let start = largest_region_start(&map, 0.0).unwrap_or_default();
    let mut results = BTreeMap::new();
    for name in &spec.planners {
        let request = PlanRequest::new(name, map.resolution()).map(|r| PlanRequest {
            seed: spec.seed + i as u64,
            ..r.start(Start::LargestRegion)
                .boundary_pass(false)
                .rooms(false)
        });
        let t = Instant::now();
        let rec = match request.and_then(|r| plan(&map, &r)) {
            Ok(out) => {
                let m = &out.evaluation.metrics;
                PlannerRecord {
                    steps: Some(m.steps),
                    coverage: m.coverage,
                    turns: m.turns,
                    error: None,
                    ms: spec.timing.then(|| t.elapsed().as_secs_f64() * 1e3),
                }
            }
            Err(e) => PlannerRecord {
                steps: None,
                coverage: 0.0,
                turns: 0,
                error: Some(e.to_string()),
                ms: None,
            },
        };
        results.insert(name.clone(), rec);
    }
    MapRecord {
        map: i,
        seed: spec.seed + i as u64,
        size: spec.size,
        free: map.counts().free,
        start: [start.row, start.col],
        results,
    }
}

/// Runs the maps of `shard` in parallel; records in map order.
#[must_use]
pub fn run(spec: &SweepSpec, shard: Shard) -> Vec<MapRecord> {
    let maps: Vec<usize> = shard_maps(spec.count, shard).collect();
    let bar = crate::progress(maps.len() as u64, "sweep");
    let out = maps
        .par_iter()
        .map(|&i| {
            let r = run_map(spec, i);
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();
    out
}

/// Per-planner statistics of a set of records.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlannerSummary {
    /// Maps planned.
    pub runs: usize,
    /// Maps refused or failed.
    pub errors: usize,
    /// Mean moves.
    pub steps_mean: f64,
    /// Fewest moves.
    pub steps_min: f64,
    /// Median moves.
    pub steps_median: f64,
    /// Most moves.
    pub steps_max: f64,
    /// Mean coverage.
    pub coverage_mean: f64,
    /// Lowest coverage.
    pub coverage_min: f64,
    /// Mean turns.
    pub turns_mean: f64,
}

/// The summary of a sweep: map count and per-planner statistics.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Maps in the records.
    pub maps: usize,
    /// Statistics by planner.
    pub planners: BTreeMap<String, PlannerSummary>,
}

/// Summarises records (sorted by map index first, so sums do not depend on shard order).
#[must_use]
pub fn summarise(records: &[MapRecord]) -> Summary {
    let mut recs: Vec<&MapRecord> = records.iter().collect();
    recs.sort_by_key(|r| r.map);
    let mut by: BTreeMap<String, Vec<&PlannerRecord>> = BTreeMap::new();
    for r in &recs {
        for (name, p) in &r.results {
            by.entry(name.clone()).or_default().push(p);
        }
    }
    let planners = by
        .into_iter()
        .map(|(name, ps)| {
            let ok: Vec<&&PlannerRecord> = ps.iter().filter(|p| p.steps.is_some()).collect();
            let mut steps: Vec<f64> = ok.iter().filter_map(|p| p.steps).collect();
            let n = steps.len().max(1) as f64;
            let mean = steps.iter().sum::<f64>() / n;
            steps.sort_by(f64::total_cmp);
            let median = if steps.is_empty() {
                0.0
            } else {
                steps[(steps.len() - 1) / 2]
            };
            let s = PlannerSummary {
                runs: ok.len(),
                errors: ps.len() - ok.len(),
                steps_mean: mean,
                steps_min: steps.first().copied().unwrap_or(0.0),
                steps_median: median,
                steps_max: steps.last().copied().unwrap_or(0.0),
                coverage_mean: ok.iter().map(|p| p.coverage).sum::<f64>() / n,
                coverage_min: ok
                    .iter()
                    .map(|p| p.coverage)
                    .fold(f64::INFINITY, f64::min)
                    .min(1.0),
                turns_mean: ok.iter().map(|p| p.turns as f64).sum::<f64>() / n,
            };
            (name, s)
        })
        .collect();
    Summary {
        maps: recs.len(),
        planners,
    }
}

/// JSON lines of the records.
///
/// # Errors
/// Serialisation failures (none expected).
pub fn to_lines(records: &[MapRecord]) -> anyhow::Result<String> {
    let mut s = String::new();
    for r in records {
        s += &serde_json::to_string(r)?;
        s.push('\n');
    }
    Ok(s)
}

/// The file of `shard` of `spec`: its [`ShardHeader`], then the records'
/// lines.
///
/// # Errors
/// Serialisation failures (none expected).
pub fn shard_file(spec: &SweepSpec, shard: Shard, records: &[MapRecord]) -> anyhow::Result<String> {
    let mut s = serde_json::to_string(&ShardHeader::new(spec, shard))?;
    s.push('\n');
    s += &to_lines(records)?;
    Ok(s)
}

/// The `sweep` command.
///
/// # Errors
/// Unknown planner names, unwritable files.
pub fn cli(
    spec: &SweepSpec,
    shard: Shard,
    out: Option<&Path>,
    summary: Option<&Path>,
) -> anyhow::Result<()> {
    for p in &spec.planners {
        oxcover::planners::find(p)?;
    }
    let records = run(spec, shard);
    let lines = shard_file(spec, shard, &records)?;
    // Whole or absent: a task killed while writing leaves no partial shard.
    let mut files = Vec::new();
    match out {
        Some(p) => files.push((p.to_path_buf(), lines.into_bytes())),
        None => std::io::stdout().write_all(lines.as_bytes())?,
    }
    if let Some(p) = summary {
        let text = serde_json::to_string_pretty(&summarise(&records))? + "\n";
        files.push((p.to_path_buf(), text.into_bytes()));
    }
    oxcover::output::write_files(files)?;
    eprintln!("sweep: {} maps of shard {shard}", records.len());
    Ok(())
}

/// Reads the files of a sweep's shards (as `sweep --out` writes them) and
/// checks that they are the whole sweep: every file starts with a
/// [`ShardHeader`] of the same sweep and shard count, holds exactly the maps
/// of its shard, and every shard is there exactly once.
///
/// # Errors
/// Unreadable files, malformed lines (named with file and line), a file
/// without a header, files of different sweeps, a shard twice, a shard
/// missing or holding fewer or other maps than its header says (each named).
pub fn read_records(files: &[PathBuf]) -> anyhow::Result<Vec<MapRecord>> {
    let mut all = Vec::new();
    let mut first: Option<(ShardHeader, &Path)> = None;
    let mut seen: BTreeMap<usize, &Path> = BTreeMap::new();
    for f in files {
        let file = std::fs::File::open(f).map_err(|e| anyhow::anyhow!("{}: {e}", f.display()))?;
        let mut header: Option<ShardHeader> = None;
        let mut records = Vec::new();
        for (n, line) in std::io::BufReader::new(file).lines().enumerate() {
            let line = line.map_err(|e| anyhow::anyhow!("{}: {e}", f.display()))?;
            if line.trim().is_empty() {
                continue;
            }
            if header.is_none() {
                let h: ShardHeader = serde_json::from_str(&line).map_err(|e| {
                    anyhow::anyhow!(
                        "{}: line {}: not a shard header ({e}); files of `cargo xtask sweep` start with one",
                        f.display(),
                        n + 1
                    )
                })?;
                header = Some(h);
                continue;
            }
            let r: MapRecord = serde_json::from_str(&line)
                .map_err(|e| anyhow::anyhow!("{}: line {}: {e}", f.display(), n + 1))?;
            records.push(r);
        }
        let Some(h) = header else {
            anyhow::bail!("{}: empty, not a shard of a sweep", f.display());
        };
        let [index, count] = h.shard;
        let shard = Shard { index, count };
        if count == 0 || index >= count {
            anyhow::bail!("{}: shard {index}/{count} is not a shard", f.display());
        }
        match &first {
            None => first = Some((h.clone(), f.as_path())),
            Some((h0, f0)) if h0.sweep != h.sweep || h0.shard[1] != count => anyhow::bail!(
                "{} and {} are shards of different sweeps (or shard counts)",
                f0.display(),
                f.display()
            ),
            Some(_) => {}
        }
        if let Some(other) = seen.insert(index, f.as_path()) {
            anyhow::bail!(
                "shard {shard} appears twice: in {} and in {}",
                other.display(),
                f.display()
            );
        }
        let expected: Vec<usize> = shard_maps(h.sweep.count, shard).collect();
        let got: Vec<usize> = records.iter().map(|r| r.map).collect();
        if got != expected {
            anyhow::bail!(
                "{}: shard {shard} holds {} of its {} maps{}; run it again",
                f.display(),
                got.len(),
                expected.len(),
                if got.len() == expected.len() {
                    " but not the right ones"
                } else {
                    ""
                }
            );
        }
        all.extend(records);
    }
    let Some((h, _)) = first else {
        anyhow::bail!("no shard files given");
    };
    let count = h.shard[1];
    let missing: Vec<String> = (0..count)
        .filter(|i| !seen.contains_key(i))
        .map(|i| format!("{i}/{count}"))
        .collect();
    if !missing.is_empty() {
        let (s, verb, pronoun) = if missing.len() > 1 {
            ("s", "are", "them")
        } else {
            ("", "is", "it")
        };
        anyhow::bail!(
            "shard{s} {} of the sweep {verb} missing: no file given holds {pronoun}",
            missing.join(", ")
        );
    }
    all.sort_by_key(|r| r.map);
    Ok(all)
}

/// The `merge` command.
///
/// # Errors
/// As [`read_records`]; unwritable output.
pub fn merge_cli(files: &[PathBuf], out: Option<&Path>) -> anyhow::Result<()> {
    let records = read_records(files)?;
    let text = serde_json::to_string_pretty(&summarise(&records))? + "\n";
    match out {
        Some(p) => {
            oxcover::output::write_files(vec![(p.to_path_buf(), text.into_bytes())])?;
        }
        None => std::io::stdout().write_all(text.as_bytes())?,
    }
    Ok(())
}
