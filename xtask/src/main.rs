//! `cargo xtask <task>`: project tasks that are not part of any library; see
//! the `xtask` library docs for what each does.

use std::path::PathBuf;

use clap::{Parser, Subcommand};
use xtask::sweep::{Generator, Shard, SweepSpec};

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
        /// Only this bench: floorplan, efficiency, smooth, sensor_bcd, grid_cover or wavefront.
        #[arg(long)]
        only: Option<String>,
    },
    /// Write the large generated map of the memory measurements (grey PNG).
    MemoryMap {
        /// Side in pixels.
        #[arg(long, default_value_t = 16384)]
        size: u32,
        /// PNG file to write.
        #[arg(long)]
        out: std::path::PathBuf,
    },
    /// Plan and score every real map in ../shared/maps; write docs/maps.md.
    Maps {
        /// Only maps whose path contains this text.
        #[arg(long)]
        filter: Option<String>,
    },
    /// Every complete planner on every real map; write docs/acceptance.md.
    Acceptance {
        /// Only maps whose path contains this text.
        #[arg(long)]
        filter: Option<String>,
        /// Only these planners (comma-separated).
        #[arg(long)]
        planners: Option<String>,
    },
    /// Score every room segmentation on the ipa room benchmark
    /// (../shared/maps/ipa-rooms); write docs/segmentation.md.
    Segmentation {
        /// Only plans whose name contains this text (prints the tables).
        #[arg(long)]
        filter: Option<String>,
        /// Also write every plan's picture (the default method) here.
        #[arg(long)]
        pictures: Option<PathBuf>,
    },
    /// Draw the stages of `lanes` as one picture: docs/lanes.svg.
    Diagram,
    /// Every complete planner, rooms on and off, on the real floor plans,
    /// scored by estimated time; write docs/efficiency.md.
    Efficiency {
        /// Only these planners (comma-separated); prints the tables instead
        /// of writing the page.
        #[arg(long)]
        planners: Option<String>,
        /// Only maps whose name contains this text (prints, as `--planners`).
        #[arg(long)]
        filter: Option<String>,
    },
    /// Feed every input parser mutated bytes of the fixture files; fail on a
    /// panic or a slow input (saved under target/fuzz/findings).
    Fuzz {
        /// Time for all targets together, in seconds.
        #[arg(long, default_value_t = 60.0)]
        seconds: f64,
        /// Seed of the mutations.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Run exactly this many mutated inputs per target instead of timing.
        #[arg(long)]
        iterations: Option<u64>,
        /// Only these targets (comma-separated).
        #[arg(long)]
        target: Option<String>,
    },
    /// Reproduce a paper's experiment: siamantas2010, siamantas2010-tracking, zhang2008, pavlicek2002, floorplans, lee2011, demir2018 or pavlicek2002-camera.
    Reproduce {
        /// Experiment name.
        name: String,
    },
    /// Run planners over seeded random maps, one JSON line per map.
    Sweep {
        /// Comma-separated planner names.
        #[arg(long, default_value = "dtc,grid-cover")]
        planners: String,
        /// Map side in cells.
        #[arg(long, default_value_t = 32)]
        size: usize,
        /// Share of blocked cells.
        #[arg(long, default_value_t = 0.2)]
        density: f64,
        /// Number of maps.
        #[arg(long, default_value_t = 100)]
        count: usize,
        /// Seed of map 0 (map i uses seed + i).
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Map generator.
        #[arg(long, value_enum, default_value_t = Generator::Connected)]
        generator: Generator,
        /// Run only the maps of this shard, `I/N` (maps i with i % N == I).
        #[arg(long)]
        shard: Option<Shard>,
        /// Record planning times (makes the output machine-dependent).
        #[arg(long)]
        timing: bool,
        /// JSON-lines output (default: stdout).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Summary output (JSON).
        #[arg(long)]
        summary: Option<PathBuf>,
    },
    /// Run the job array of docs/sweeps.md on a real single-node Slurm started
    /// here (needs root; installs slurm and munge with apt-get), merge, and
    /// check against the same sweep in one process (xtask/scripts/slurm-check.sh).
    SlurmCheck,
    /// Merge sweep shards into the summary a single run gives.
    Merge {
        /// Shard files (JSON lines).
        files: Vec<PathBuf>,
        /// Summary output (default: stdout).
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

fn main() -> anyhow::Result<()> {
    match Cli::parse().task {
        Task::Bench { no_run, only } => xtask::bench::run(no_run, only.as_deref()),
        Task::Maps { filter } => xtask::maps::run(filter.as_deref()),
        Task::MemoryMap { size, out } => xtask::memory_map::run(size, &out),
        Task::Acceptance { filter, planners } => {
            xtask::acceptance::run(filter.as_deref(), planners.as_deref())
        }
        Task::Reproduce { name } => xtask::reproduce::run(&name),
        Task::Diagram => xtask::diagram::run(),
        Task::Segmentation { filter, pictures } => {
            xtask::segmentation::run(filter.as_deref(), pictures.as_deref())
        }
        Task::Efficiency { planners, filter } => {
            xtask::efficiency::run(planners.as_deref(), filter.as_deref())
        }
        Task::Fuzz {
            seconds,
            seed,
            iterations,
            target,
        } => xtask::fuzz::run(seconds, seed, iterations, target.as_deref()),
        Task::Sweep {
            planners,
            size,
            density,
            count,
            seed,
            generator,
            shard,
            timing,
            out,
            summary,
        } => {
            let spec = SweepSpec {
                planners: planners
                    .split(',')
                    .map(|s| s.trim().to_string())
                    .filter(|s| !s.is_empty())
                    .collect(),
                size,
                density,
                count,
                seed,
                generator,
                timing,
            };
            xtask::sweep::cli(
                &spec,
                shard.unwrap_or_default(),
                out.as_deref(),
                summary.as_deref(),
            )
        }
        Task::Merge { files, out } => xtask::sweep::merge_cli(&files, out.as_deref()),
        Task::SlurmCheck => {
            let script =
                std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/slurm-check.sh");
            let status = std::process::Command::new("bash").arg(&script).status()?;
            anyhow::ensure!(status.success(), "{} failed ({status})", script.display());
            Ok(())
        }
    }
}
