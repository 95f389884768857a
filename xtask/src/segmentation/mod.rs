//! `cargo xtask segmentation`: every room segmentation method scored on the
//! ipa room-segmentation benchmark (`../shared/maps/ipa-rooms`: ten floor
//! plans, each plain and furnished, with ground-truth rooms); writes
//! `docs/segmentation.md` and pictures of three plans beside their truth.
//!
//! - `score`: recall, precision and IoU as the benchmark's survey defines
//!   them (`../shared/maps/ipa-rooms/SOURCE.md`).
//! - `picture`: a plan's segments beside its ground truth, one PNG.
//!
//! Plans are read as the benchmark reads them (grey above 250 free, every
//! other value an obstacle) at 0.05 m per pixel; the ground-truth rooms are
//! the 4-connected components of grey 250 or more of 1 m² or more. Where
//! the folder is absent the task says so and writes nothing.

mod picture;
mod score;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use oxcover_decomp::{RoomParams, Rooms};
use oxcover_grid::io::{ReadOptions, Thresholds, read_map};
use oxcover_grid::{Grid, components4};

pub use self::score::{Score, score};

/// Metres per pixel of the benchmark's plans.
pub const RESOLUTION: f64 = 0.05;

/// The benchmark's plans, in name order.
pub const PLANS: [&str; 10] = [
    "Freiburg52_scan",
    "Freiburg79_scan",
    "lab_b_scan",
    "lab_d_scan",
    "lab_intel",
    "office_a",
    "office_c",
    "office_e",
    "office_g",
    "office_i",
];

/// The plans drawn beside their truth on the page.
const PICTURED: [&str; 3] = ["office_a", "Freiburg52_scan", "lab_intel"];

/// A segmentation method: its name and how it segments the free cells of
/// a plan at [`RESOLUTION`].
pub struct Method {
    /// As `oxcover segment --method` names it.
    pub name: &'static str,
    /// The segmentation.
    pub run: fn(&Grid<bool>, &RoomParams) -> Rooms,
}

/// Every method, the default first.
#[must_use]
pub fn methods() -> Vec<Method> {
    vec![
        Method {
            name: "doorways",
            run: oxcover_decomp::doorways,
        },
        Method {
            name: "voronoi",
            run: oxcover_decomp::voronoi,
        },
        Method {
            name: "morphological",
            run: oxcover_decomp::morphological,
        },
    ]
}

/// One plan of the benchmark: its free cells plain and furnished, and its
/// ground-truth rooms.
pub struct Plan {
    /// The plan's name.
    pub name: &'static str,
    /// Free cells of the plain plan.
    pub plain: Grid<bool>,
    /// Free cells of the furnished plan.
    pub furnished: Grid<bool>,
    /// Ground-truth room labels (0: no room).
    pub truth: Grid<u32>,
}

/// The benchmark's folder, if present.
#[must_use]
pub fn folder() -> Option<PathBuf> {
    crate::shared_maps()
        .map(|m| m.join("ipa-rooms"))
        .filter(|p| p.is_dir())
}

/// The free cells of the image at `path`: grey values of `min` or more.
fn white(path: &Path, min: u8) -> anyhow::Result<Grid<bool>> {
    // Occupancy p = (255 - v) / 255 below the cut is free.
    let cut = (255.0 - f64::from(min) + 0.5) / 255.0;
    let opts = ReadOptions::default()
        .resolution(RESOLUTION)
        .thresholds(Thresholds {
            occupied_thresh: cut,
            free_thresh: cut,
            ..Thresholds::default()
        });
    Ok(read_map(path, &opts)?.free_mask())
}

/// Reads plan `name` from `dir`.
///
/// # Errors
/// Missing or unreadable images, or images of different sizes.
pub fn read_plan(dir: &Path, name: &'static str) -> anyhow::Result<Plan> {
    // The plans: grey above 250; the truth: grey 250 or more.
    let plain = white(&dir.join(format!("{name}.png")), 251)?;
    let furnished = white(&dir.join(format!("{name}_furnitures.png")), 251)?;
    let gt = white(&dir.join(format!("{name}_gt_segmentation.png")), 250)?;
    anyhow::ensure!(
        (plain.width(), plain.height()) == (gt.width(), gt.height())
            && (furnished.width(), furnished.height()) == (gt.width(), gt.height()),
        "{name}: the plan and its truth differ in size"
    );
    let comps = components4(&gt);
    let min = (1.0 / (RESOLUTION * RESOLUTION)).round() as usize;
    let mut keep = vec![0u32; comps.sizes.len() + 1];
    let mut next = 0;
    for (i, &n) in comps.sizes.iter().enumerate() {
        if n >= min {
            next += 1;
            keep[i + 1] = next;
        }
    }
    let truth = comps.labels.map(|&l| keep[l as usize]);
    Ok(Plan {
        name,
        plain,
        furnished,
        truth,
    })
}

/// One method on one plan variant: its scores and milliseconds.
#[derive(Clone, Copy, Debug)]
pub struct Run {
    /// The scores.
    pub score: Score,
    /// Wall-clock time of the segmentation (ms).
    pub ms: f64,
}

/// Segments `free` with `method` and scores it against `plan`'s truth.
#[must_use]
pub fn evaluate(method: &Method, plan: &Plan, free: &Grid<bool>) -> (Run, Rooms) {
    let params = RoomParams::indoor(RESOLUTION);
    let t = Instant::now();
    let rooms = (method.run)(free, &params);
    let ms = t.elapsed().as_secs_f64() * 1000.0;
    let score = score(&plan.truth, &rooms.labels, free);
    (Run { score, ms }, rooms)
}

fn mean(v: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    if n == 0 { 0.0 } else { s / n as f64 }
}

/// Runs the task; with `filter`, only the plans whose name contains it
/// (the tables are printed, the page is kept); with `pictures`, every
/// plan's picture (both variants, the default method) is also written
/// into that folder.
///
/// # Errors
/// Unreadable plans, pictures or page.
pub fn run(filter: Option<&str>, pictures: Option<&Path>) -> anyhow::Result<()> {
    let Some(dir) = folder() else {
        eprintln!("segmentation: skipped (../shared/maps/ipa-rooms not found)");
        return Ok(());
    };
    let plans: Vec<Plan> = PLANS
        .iter()
        .filter(|n| filter.is_none_or(|f| n.contains(f)))
        .map(|n| read_plan(&dir, n))
        .collect::<anyhow::Result<_>>()?;
    let methods = methods();
    let docs = crate::root().join("docs");
    let mut md = String::from(
        "# Room segmentation on the ipa benchmark\n\n\
         Command: `cargo xtask segmentation` (release). Plans: the ten floor plans of `../shared/maps/ipa-rooms`, each plain and furnished, read as the benchmark reads them (grey above 250 free, every other value an obstacle) at 0.05 m per pixel; every method with `oxcover segment`'s defaults. \
         Ground truth: the 4-connected components of grey 250 or more of the `_gt_segmentation` images, 1 m² or more.\n\n\
         Scores, as the benchmark's survey defines them (Bormann et al. 2016; `../shared/maps/ipa-rooms/SOURCE.md`), over the pixels free in the plan that lie in a ground-truth room:\n\n\
         - recall: for each room, the largest share of it in one segment (mean over rooms);\n\
         - precision: for each segment, the largest share of it in one room (mean over segments);\n\
         - IoU: for each room, the best intersection over union with one segment (mean over rooms);\n\
         - `ms`: the segmentation alone, wall-clock, this machine.\n\n",
    );
    // Every method on every plan, plain and furnished.
    let mut rows: Vec<Vec<(Run, Run)>> = Vec::new();
    for m in &methods {
        let per: Vec<(Run, Run)> = plans
            .iter()
            .map(|p| {
                let (a, _) = evaluate(m, p, &p.plain);
                let (b, _) = evaluate(m, p, &p.furnished);
                (a, b)
            })
            .collect();
        rows.push(per);
    }
    md += "## Means over the plans\n\n| method | variant | recall | precision | IoU | worst IoU | ms per plan |\n|---|---|---:|---:|---:|---:|---:|\n";
    for (m, per) in methods.iter().zip(&rows) {
        for (variant, pick) in [("plain", 0usize), ("furnished", 1)] {
            let runs: Vec<Run> = per
                .iter()
                .map(|r| if pick == 0 { r.0 } else { r.1 })
                .collect();
            let _ = writeln!(
                md,
                "| {} | {variant} | {:.3} | {:.3} | {:.3} | {:.3} | {:.0} |",
                m.name,
                mean(runs.iter().map(|r| r.score.recall)),
                mean(runs.iter().map(|r| r.score.precision)),
                mean(runs.iter().map(|r| r.score.iou)),
                runs.iter().map(|r| r.score.iou).fold(1.0, f64::min),
                mean(runs.iter().map(|r| r.ms)),
            );
        }
    }
    md += "\nFor comparison, the ipa package's own methods on the same ten plans, plain (measured by issue 47 with the package built and run standalone; not re-run here): Voronoi recall 0.951, precision 0.983, IoU 0.918; morphological 0.986 / 0.932 / 0.810; distance 0.978 / 0.937 / 0.865.\n";
    // The default method (the first) against the targets of issue 47.
    md += "\n## Targets (the default method)\n\nMean recall and precision at least 0.95 and at least the peer's (0.951 / 0.983), mean IoU at least 0.93 and the peer's 0.918, no plan below IoU 0.85; plain and furnished.\n\n";
    for (variant, pick) in [("plain", 0usize), ("furnished", 1)] {
        let runs: Vec<Run> = rows[0]
            .iter()
            .map(|r| if pick == 0 { r.0 } else { r.1 })
            .collect();
        let (recall, precision, iou) = (
            mean(runs.iter().map(|r| r.score.recall)),
            mean(runs.iter().map(|r| r.score.precision)),
            mean(runs.iter().map(|r| r.score.iou)),
        );
        let low: Vec<String> = plans
            .iter()
            .zip(&runs)
            .filter(|(_, r)| r.score.iou < 0.85)
            .map(|(p, r)| format!("{} {:.3}", p.name, r.score.iou))
            .collect();
        let verdict = |ok: bool| if ok { "met" } else { "**not met**" };
        let _ = writeln!(
            md,
            "- {variant}: recall {recall:.3} {}, precision {precision:.3} {}, IoU {iou:.3} {}; plans below IoU 0.85: {} ({})",
            verdict(recall >= 0.951),
            verdict(precision >= 0.983),
            verdict(iou >= 0.93),
            if low.is_empty() {
                "none".to_string()
            } else {
                low.join(", ")
            },
            verdict(low.is_empty()),
        );
    }
    for (m, per) in methods.iter().zip(&rows) {
        let _ = write!(
            md,
            "\n## {}\n\n| plan | rooms | plain: segments | recall | precision | IoU | furnished: segments | recall | precision | IoU | ms plain / furnished |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
            m.name
        );
        for (p, (a, b)) in plans.iter().zip(per) {
            let _ = writeln!(
                md,
                "| {} | {} | {} | {:.3} | {:.3} | {:.3} | {} | {:.3} | {:.3} | {:.3} | {:.0} / {:.0} |",
                p.name,
                a.score.rooms,
                a.score.segments,
                a.score.recall,
                a.score.precision,
                a.score.iou,
                b.score.segments,
                b.score.recall,
                b.score.precision,
                b.score.iou,
                a.ms,
                b.ms
            );
        }
    }
    if let Some(dir) = pictures {
        std::fs::create_dir_all(dir)?;
        for p in &plans {
            for (variant, free) in [("plain", &p.plain), ("furnished", &p.furnished)] {
                let (_, rooms) = evaluate(&methods[0], p, free);
                let file = dir.join(format!("{}_{variant}.png", p.name));
                picture::write(free, &rooms.labels, &p.truth, &file)?;
            }
        }
    }
    if filter.is_some() {
        println!("{md}");
        return Ok(());
    }
    md += "\n## Pictures\n\nLeft the default method's segments on the furnished plan, right the ground truth (one colour per segment or room; obstacles dark, free cells outside every room light grey).\n\n";
    let default = &methods[0];
    for name in PICTURED {
        let Some(p) = plans.iter().find(|p| p.name == name) else {
            continue;
        };
        let (_, rooms) = evaluate(default, p, &p.furnished);
        let file = format!("segmentation_{name}.png");
        picture::write(&p.furnished, &rooms.labels, &p.truth, &docs.join(&file))?;
        let _ = writeln!(md, "![{name}: segments and truth]({file})\n");
    }
    std::fs::write(docs.join("segmentation.md"), md)?;
    println!("wrote docs/segmentation.md");
    Ok(())
}
