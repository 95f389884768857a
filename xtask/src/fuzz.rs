//! `cargo xtask fuzz`: every input parser fed mutated bytes of the fixture
//! files, on stable Rust, deterministic for a seed.
//!
//! Each [`Target`] names a parser the command line reaches (ROS yaml, PGM,
//! PNG, BMP, MovingAI, path CSV, poses CSV, world RON, camera RON, profile
//! RON, robot RON) and its seed files (fixtures, plus the small hand-made
//! files in `fixtures/fuzz/seeds/`). A run first replays every seed and every
//! saved regression (`fixtures/fuzz/regressions/<target>/`), then mutates:
//! bit flips, interesting bytes, deleted, copied and inserted runs, cuts,
//! numbers swapped for extreme ones (`1e308`, `NaN`, `-1`, `4294967296`) and
//! splices of two seeds, one to four at a time, from a ChaCha stream of the
//! seed.
//!
//! A finding is a panic (caught and reported with the input), or an input
//! taking longer than [`SLOW`]. Each input is written to
//! `target/fuzz/current-<target>` before it runs, so one that aborts the
//! process (an allocation failure) is left on disk to become a regression.
//! Findings are saved under `target/fuzz/findings/`; copy one into
//! `fixtures/fuzz/regressions/<target>/` once fixed, and every later run
//! replays it.

use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::{Context, bail};
use oxcover_grid::io::{ReadOptions, Thresholds, read_map};
use oxcover_rosbag::MessageChoice;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// An input slower than this is a finding (a parser should answer at once).
pub const SLOW: Duration = Duration::from_secs(2);

/// How a target's parser consumes an input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Feed {
    /// Written to a file with this extension in a scratch folder holding the
    /// fixture images, then read as a map (`read_map`, the CLI's reader).
    Map(&'static str),
    /// A path file (`x,y` CSV).
    PathCsv,
    /// A poses file of `map-from-camera`.
    Poses,
    /// A world of `explore`.
    World,
    /// A camera of `map-from-camera` (parsed, checked, then used).
    Camera,
    /// A colour profile of `map-from-camera` (parsed, checked, then used).
    Profile,
    /// A robot description of `simulate`.
    Robot,
    /// A ROS 2 bag in MCAP storage: written as `input.mcap`, its topics
    /// listed and its map read (`oxcover_rosbag::read_map`).
    Mcap,
    /// One CDR message, decoded as each type a bag of ours holds; an
    /// OccupancyGrid then read as a map.
    Cdr,
}

/// One parser and where its seeds come from.
#[derive(Clone, Copy, Debug)]
pub struct Target {
    /// Name on the command line (`--target`).
    pub name: &'static str,
    feed: Feed,
    /// Seed files or folders, relative to the workspace root.
    seeds: &'static [&'static str],
}

/// Every fuzz target.
pub const TARGETS: &[Target] = &[
    Target {
        name: "ros-yaml",
        feed: Feed::Map("yaml"),
        seeds: &[
            "fixtures/maps/navigation_tutorials/lse_arena.yaml",
            "fixtures/maps/turtlebot_simulator/simple_rooms.yaml",
            "fixtures/maps/nobleo/basement.yaml",
            "fixtures/maps/lee2011/office.yaml",
        ],
    },
    Target {
        name: "pgm",
        feed: Feed::Map("pgm"),
        seeds: &[
            "fixtures/maps/navigation_tutorials/lse_arena.pgm",
            "fixtures/fuzz/seeds/pgm",
        ],
    },
    Target {
        name: "png",
        feed: Feed::Map("png"),
        seeds: &[
            "fixtures/maps/pythonrobotics/test.png",
            "fixtures/maps/turtlebot_simulator/simple_rooms.png",
            "fixtures/maps/turtlebot_simulator/hospital_section.png",
        ],
    },
    Target {
        name: "bmp",
        feed: Feed::Map("bmp"),
        seeds: &["fixtures/fuzz/seeds/bmp"],
    },
    Target {
        name: "movingai",
        feed: Feed::Map("map"),
        seeds: &["fixtures/maps/movingai"],
    },
    Target {
        name: "path-csv",
        feed: Feed::PathCsv,
        seeds: &["fixtures/fuzz/seeds/csv"],
    },
    Target {
        name: "poses-csv",
        feed: Feed::Poses,
        seeds: &["fixtures/fuzz/seeds/poses"],
    },
    Target {
        name: "world-ron",
        feed: Feed::World,
        seeds: &["fixtures/worlds/demir2018", "fixtures/worlds/lee2011"],
    },
    Target {
        name: "camera-ron",
        feed: Feed::Camera,
        seeds: &["fixtures/fuzz/seeds/camera"],
    },
    Target {
        name: "profile-ron",
        feed: Feed::Profile,
        seeds: &["fixtures/fuzz/seeds/profile"],
    },
    Target {
        name: "robot-ron",
        feed: Feed::Robot,
        seeds: &["fixtures/robots/floor_cleaner.ron"],
    },
    Target {
        name: "mcap",
        feed: Feed::Mcap,
        seeds: &["fixtures/fuzz/seeds/mcap"],
    },
    Target {
        name: "cdr",
        feed: Feed::Cdr,
        seeds: &["fixtures/fuzz/seeds/cdr"],
    },
];

/// What a run found and did.
#[derive(Debug, Default)]
pub struct Outcome {
    /// Inputs run, per target.
    pub runs: Vec<(&'static str, u64)>,
    /// Findings: target, what happened, where the input was saved.
    pub findings: Vec<(&'static str, String, PathBuf)>,
}

/// A target's seed inputs: its seed files and saved regressions.
///
/// # Errors
/// A seed file that cannot be read, or a target without seeds.
pub fn seeds(root: &Path, target: &Target) -> anyhow::Result<Vec<Vec<u8>>> {
    let mut files: Vec<PathBuf> = Vec::new();
    let regressions = format!("fixtures/fuzz/regressions/{}", target.name);
    for s in target.seeds.iter().copied().chain([regressions.as_str()]) {
        let p = root.join(s);
        if p.is_dir() {
            let mut inside: Vec<PathBuf> = std::fs::read_dir(&p)?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| f.is_file())
                .collect();
            inside.sort();
            files.extend(inside);
        } else if p.is_file() {
            files.push(p);
        }
    }
    let out: Vec<Vec<u8>> = files
        .iter()
        .map(|f| std::fs::read(f).with_context(|| format!("reading {}", f.display())))
        .collect::<anyhow::Result<_>>()?;
    if out.is_empty() {
        bail!("fuzz target {} has no seed files", target.name);
    }
    Ok(out)
}

/// A scratch folder holding the images the yaml seeds name.
///
/// # Errors
/// When the folder or the images cannot be written.
pub fn scratch(root: &Path, name: &str) -> anyhow::Result<PathBuf> {
    let dir = std::env::temp_dir().join(format!("oxcover-fuzz-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    for image in [
        "fixtures/maps/navigation_tutorials/lse_arena.pgm",
        "fixtures/maps/turtlebot_simulator/simple_rooms.png",
        "fixtures/maps/nobleo/basement.png",
        "fixtures/maps/lee2011/office.pgm",
    ] {
        let from = root.join(image);
        let name = from.file_name().context("image name")?;
        std::fs::copy(&from, dir.join(name))
            .with_context(|| format!("copying {}", from.display()))?;
    }
    Ok(dir)
}

/// Runs one input through the target's parser; `Err` only for a panic.
fn feed(target: &Target, dir: &Path, input: &[u8]) -> Result<(), String> {
    let text = || String::from_utf8_lossy(input).into_owned();
    let run = || match target.feed {
        Feed::Map(ext) => {
            let file = dir.join(format!("input.{ext}"));
            // PNG chunks carry CRCs: mend them, or nearly every mutation
            // would stop at the first checksum instead of reaching the decoder.
            let bytes = if ext == "png" {
                mend_png_crcs(input)
            } else {
                input.to_vec()
            };
            if std::fs::write(&file, bytes).is_ok()
                && let Ok(map) = read_map(&file, &ReadOptions::default())
            {
                // What every command does next with a map.
                let _ = map.counts();
                let _ = map.frame().cell_center(oxcover_grid::Cell::new(0, 0));
            }
        }
        Feed::PathCsv => {
            if let Ok(points) = oxcover::path::parse_csv(Path::new("input.csv"), &text()) {
                let _ = oxcover::path::to_csv(&points);
            }
        }
        Feed::Poses => {
            let file = dir.join("poses.csv");
            if std::fs::write(&file, input).is_ok() {
                let _ = oxcover_vision::read_views(&file);
            }
        }
        Feed::World => {
            if let Ok(world) = oxcover_world::World::parse(&text(), "input.ron") {
                let _ = world.rasterise();
            }
        }
        Feed::Camera => {
            if let Ok(camera) = ron::from_str::<oxcover_vision::Camera>(&text())
                && camera.check().is_ok()
            {
                let pose = oxcover_grid::Pose::new(0.0, 0.0, 0.0);
                for (u, v) in [(0.0, 0.0), (320.0, 240.0), (1e9, -1e9)] {
                    if let Some(q) = camera.pixel_to_world(pose, u, v) {
                        let _ = camera.world_to_pixel(pose, q);
                    }
                }
            }
        }
        Feed::Profile => {
            if let Ok(profile) = ron::from_str::<oxcover_vision::Profile>(&text())
                && profile.check().is_ok()
            {
                for rgb in [[0, 0, 0], [255, 255, 255], [12, 200, 99]] {
                    let _ = profile.p_occ(rgb);
                }
            }
        }
        Feed::Robot => {
            let _ = oxcover_robot::RobotSpec::from_ron(&text());
        }
        Feed::Mcap => {
            let file = dir.join("input.mcap");
            if std::fs::write(&file, input).is_ok() {
                if let Ok(mut bag) = oxcover_rosbag::Bag::open(&file) {
                    let _ = bag.topics();
                }
                for choice in [MessageChoice::Last, MessageChoice::First] {
                    let _ = oxcover_rosbag::read_map(
                        &file,
                        None,
                        choice,
                        &Thresholds::default(),
                        1 << 24,
                    );
                }
            }
        }
        Feed::Cdr => {
            use oxcover_rosbag::{cdr::decode, msgs};
            if let Ok(grid) = decode::<msgs::OccupancyGrid>(input) {
                let _ = oxcover_rosbag::grid::from_msg(
                    Path::new("input"),
                    &grid,
                    &Thresholds::default(),
                    1 << 24,
                );
            }
            let _ = decode::<msgs::Path>(input);
            let _ = decode::<msgs::MarkerArray>(input);
            let _ = decode::<msgs::Odometry>(input);
        }
    };
    std::panic::catch_unwind(AssertUnwindSafe(run)).map_err(|e| {
        e.downcast_ref::<String>()
            .cloned()
            .or_else(|| e.downcast_ref::<&str>().map(|s| (*s).to_string()))
            .unwrap_or_else(|| "panic".into())
    })
}

/// `bytes` with every whole PNG chunk's CRC recomputed (the rest unchanged).
fn mend_png_crcs(bytes: &[u8]) -> Vec<u8> {
    let mut v = bytes.to_vec();
    let mut at = 8;
    while at + 12 <= v.len() {
        let len = u32::from_be_bytes([v[at], v[at + 1], v[at + 2], v[at + 3]]) as usize;
        let Some(end) = (at + 8).checked_add(len).filter(|e| e + 4 <= v.len()) else {
            break;
        };
        let crc = crc32(&v[at + 4..end]);
        v[end..end + 4].copy_from_slice(&crc.to_be_bytes());
        at = end + 4;
    }
    v
}

/// The CRC-32 of PNG chunks (ISO 3309), bit by bit: inputs are small.
fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// Numbers a mutation puts in place of one in the text.
const NUMBERS: &[&str] = &[
    "0",
    "-0",
    "-1",
    "1e308",
    "-1e308",
    "1e-320",
    "NaN",
    "inf",
    "-inf",
    "4294967296",
    "18446744073709551616",
    "65535",
    "2147483647",
    "99999999999999999999999",
    "0.0000001",
    "",
];

/// Bytes a mutation writes in place of one.
const BYTES: &[u8] = &[
    0, 0xff, 0x7f, 0x80, b'0', b'9', b'-', b'.', b'e', b'\n', b' ', b':', b',', b'[', b']', b'(',
    b')', b'&', b'*', b'#', b'"',
];

/// One to four mutations of `base` (another seed may be spliced in).
fn mutate(rng: &mut ChaCha8Rng, base: &[u8], other: &[u8]) -> Vec<u8> {
    let mut v = base.to_vec();
    for _ in 0..rng.random_range(1..=4) {
        let n = v.len();
        let at = |rng: &mut ChaCha8Rng| if n == 0 { 0 } else { rng.random_range(0..n) };
        match rng.random_range(0..9) {
            0 if n > 0 => {
                let i = at(rng);
                v[i] ^= 1 << rng.random_range(0..8);
            }
            1 if n > 0 => {
                let i = at(rng);
                v[i] = BYTES[rng.random_range(0..BYTES.len())];
            }
            2 if n > 0 => {
                let i = at(rng);
                let len = rng.random_range(1..=(n - i).min(64));
                v.drain(i..i + len);
            }
            3 if n > 0 => {
                let i = at(rng);
                let len = rng.random_range(1..=(n - i).min(64));
                let copy = v[i..i + len].to_vec();
                let j = rng.random_range(0..=n);
                v.splice(j..j, copy);
            }
            4 => {
                let j = rng.random_range(0..=n);
                let len = rng.random_range(1..=16);
                let bytes: Vec<u8> = (0..len).map(|_| rng.random()).collect();
                v.splice(j..j, bytes);
            }
            5 if n > 0 => v.truncate(at(rng)),
            6 => swap_number(rng, &mut v),
            7 if !other.is_empty() => {
                let cut = rng.random_range(0..=n);
                let from = rng.random_range(0..other.len());
                v.truncate(cut);
                v.extend_from_slice(&other[from..]);
            }
            _ => swap_number(rng, &mut v),
        }
    }
    v
}

/// Replaces one run of digits (with sign, point and exponent) by an extreme number.
fn swap_number(rng: &mut ChaCha8Rng, v: &mut Vec<u8>) {
    let starts: Vec<usize> = (0..v.len())
        .filter(|&i| v[i].is_ascii_digit() && (i == 0 || !v[i - 1].is_ascii_digit()))
        .collect();
    if starts.is_empty() {
        return;
    }
    let s = starts[rng.random_range(0..starts.len())];
    let mut e = s;
    while e < v.len() && (v[e].is_ascii_digit() || matches!(v[e], b'.' | b'e' | b'E' | b'-')) {
        e += 1;
    }
    let with = NUMBERS[rng.random_range(0..NUMBERS.len())].as_bytes();
    v.splice(s..e, with.iter().copied());
}

/// Fuzzes `targets` for `budget` in all (shared equally), or for `iterations`
/// inputs each when given; findings are saved under `out`.
///
/// # Errors
/// Missing seeds or an unwritable scratch folder.
pub fn fuzz(
    root: &Path,
    targets: &[Target],
    seed: u64,
    budget: Duration,
    iterations: Option<u64>,
    out: &Path,
) -> anyhow::Result<Outcome> {
    let mut outcome = Outcome::default();
    std::fs::create_dir_all(out)?;
    let quiet = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let share = budget / u32::try_from(targets.len().max(1)).unwrap_or(1);
    for (t, target) in targets.iter().enumerate() {
        let corpus = seeds(root, target)?;
        let dir = scratch(root, target.name)?;
        let current = out.join(format!("current-{}", target.name));
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ ((t as u64) << 32));
        let started = Instant::now();
        let mut runs = 0u64;
        let mut k = 0usize;
        loop {
            let replay = k < corpus.len();
            let done = match iterations {
                Some(n) => !replay && runs >= n,
                None => !replay && started.elapsed() >= share,
            };
            if done {
                break;
            }
            let input = if replay {
                corpus[k].clone()
            } else {
                let a = &corpus[rng.random_range(0..corpus.len())];
                let b = &corpus[rng.random_range(0..corpus.len())];
                mutate(&mut rng, a, b)
            };
            k += 1;
            std::fs::write(&current, &input)?;
            let t0 = Instant::now();
            let result = feed(target, &dir, &input);
            let took = t0.elapsed();
            runs += 1;
            let what = match result {
                Err(message) => Some(format!("panic: {message}")),
                Ok(()) if took > SLOW => Some(format!("slow: {:.1} s", took.as_secs_f64())),
                Ok(()) => None,
            };
            if let Some(what) = what {
                let saved = out.join(format!("findings/{}-{runs}", target.name));
                std::fs::create_dir_all(saved.parent().context("findings folder")?)?;
                std::fs::write(&saved, &input)?;
                outcome.findings.push((target.name, what, saved));
            }
        }
        let _ = std::fs::remove_file(&current);
        let _ = std::fs::remove_dir_all(&dir);
        outcome.runs.push((target.name, runs));
    }
    std::panic::set_hook(quiet);
    Ok(outcome)
}

/// The command: fuzz, print a line per target and per finding, fail on any.
///
/// # Errors
/// An unknown target, missing seeds, or any finding.
pub fn run(
    seconds: f64,
    seed: u64,
    iterations: Option<u64>,
    only: Option<&str>,
) -> anyhow::Result<()> {
    let root = crate::root();
    let targets: Vec<Target> = TARGETS
        .iter()
        .filter(|t| only.is_none_or(|o| o.split(',').any(|n| n.trim() == t.name)))
        .copied()
        .collect();
    if targets.is_empty() {
        let names: Vec<&str> = TARGETS.iter().map(|t| t.name).collect();
        bail!("--target names none of: {}", names.join(", "));
    }
    if !(seconds.is_finite() && seconds > 0.0) {
        bail!("--seconds must be a positive number");
    }
    let out = root.join("target/fuzz");
    let started = Instant::now();
    let outcome = fuzz(
        &root,
        &targets,
        seed,
        Duration::from_secs_f64(seconds),
        iterations,
        &out,
    )?;
    let total: u64 = outcome.runs.iter().map(|(_, n)| n).sum();
    for (name, n) in &outcome.runs {
        println!("{name:<12} {n:>8} inputs");
    }
    println!(
        "{total} inputs in {:.1} s, seed {seed}, {} finding(s)",
        started.elapsed().as_secs_f64(),
        outcome.findings.len()
    );
    for (name, what, saved) in outcome.findings.iter().take(10) {
        println!(
            "FINDING {name}: {what} (input saved as {})",
            saved.display()
        );
    }
    if outcome.findings.len() > 10 {
        println!(
            "... and {} more in {}",
            outcome.findings.len() - 10,
            out.join("findings").display()
        );
    }
    if outcome.findings.is_empty() {
        Ok(())
    } else {
        bail!("the fuzzer found {} problem(s)", outcome.findings.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mutations_are_deterministic_and_change_the_input() {
        let base = b"resolution: 0.05\norigin: [1.0, -2.5, 0]\n".to_vec();
        let run = |seed| {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            (0..50)
                .map(|_| mutate(&mut rng, &base, b"other"))
                .collect::<Vec<_>>()
        };
        assert_eq!(run(7), run(7));
        assert_ne!(run(7), run(8));
        assert!(run(7).iter().filter(|m| **m != base).count() > 40);
    }

    #[test]
    fn mended_png_crcs_are_the_real_ones() {
        let png = std::fs::read(crate::root().join("fixtures/maps/pythonrobotics/test.png"))
            .expect("fixture");
        assert_eq!(mend_png_crcs(&png), png);
        let mut broken = png.clone();
        broken[20] ^= 0x10; // inside IHDR
        let mended = mend_png_crcs(&broken);
        assert_ne!(mended[29..33], png[29..33], "IHDR's CRC was not recomputed");
        assert_eq!(mend_png_crcs(&mended), mended);
    }

    /// Every seed and saved regression, and a few hundred mutations of
    /// each target, run clean (the CI run fuzzes for longer).
    #[test]
    fn seeds_and_regressions_run_clean() {
        let root = crate::root();
        let out = std::env::temp_dir().join(format!("oxcover-fuzz-test-{}", std::process::id()));
        let outcome = fuzz(&root, TARGETS, 1, Duration::ZERO, Some(200), &out).unwrap();
        assert_eq!(outcome.runs.len(), TARGETS.len());
        assert!(outcome.runs.iter().all(|(_, n)| *n >= 200));
        assert!(outcome.findings.is_empty(), "{:?}", outcome.findings);
        let _ = std::fs::remove_dir_all(&out);
    }
}
