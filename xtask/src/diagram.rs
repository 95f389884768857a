//! `cargo xtask diagram`: the stages of `lanes` as one picture,
//! `docs/lanes.svg` (linked from `docs/architecture.md`).
//!
//! The picture is written from the table of stages below, a box per file
//! of `crates/oxcover-planners/src/lanes/` in the order `plan_lanes` runs
//! them; a test checks that the committed picture is what this writes and
//! that every box names a file that exists.

use std::fmt::Write as _;

/// The picture's boxes, a line each, rows in the order `plan_lanes` runs
/// them: the row's label, `chain` where its boxes run one after another
/// (else side by side, in parallel), the file (under the planners crate's
/// `src/`), the box's title and two lines of what it does. Consecutive
/// lines with the same label are one row.
const PICTURE: &str = "\
input | | problem/input.rs | PlannerInput | a region's plannable, coverable and admissible cells, | coverage grid, start, exit, time model (one room or the map)
lay out (in parallel) | | lanes/loops.rs | edge loops | Moore tracing, points pushed | to the wall, straightened
lay out (in parallel) | | lanes/layout.rs | lane mask | C-space a tool radius in; | lines, lanes, chains
lay out (in parallel) | | lanes/islands.rs | small islands | specks lanes run past, | loops lanes drive
choose angles | | lanes/angles.rs | angles | every 15° and the walls' directions, each modelled by its | chains' time; the best few go on (every one on a small plan)
per angle (in parallel) | chain | lanes/rehatch.rs | re-hatching | pieces one angle does | not suit, laid again
per angle (in parallel) | chain | lanes/islands.rs | splices | island loops driven | from the nearest lane
per angle (in parallel) | chain | lanes/order.rs | order | nodes.rs, transits.rs: | GTSP in seconds
best few (in parallel) | chain | lanes/build.rs | drive | loops, chains, transits | by clear routes
best few (in parallel) | chain | detours/insert.rs | detours | cells just out of reach: | the cheapest bend
best few (in parallel) | chain | detours/tighten.rs | tightening | waypoints removed or | moved, coverage kept
output | | problem/input.rs | PlanOutput::Metres | the fastest of the paths built, after a last pass over coverage cells still open; | then the pipeline's boundary pass, rooms and metrics
";

/// A box: its file, its title and two lines of what it does.
struct Stage {
    file: &'static str,
    title: &'static str,
    lines: [&'static str; 2],
}

/// One row of the picture: its label, whether its boxes run one after
/// another, and its boxes.
struct Row {
    label: &'static str,
    chain: bool,
    stages: Vec<Stage>,
}

/// The rows of [`PICTURE`].
fn rows() -> Vec<Row> {
    let mut rows: Vec<Row> = Vec::new();
    for line in PICTURE.lines() {
        let f: Vec<&'static str> = line.split('|').map(str::trim).collect();
        let [label, mode, file, title, a, b] = f[..] else {
            continue;
        };
        let stage = Stage {
            file,
            title,
            lines: [a, b],
        };
        match rows.last_mut() {
            Some(row) if row.label == label => row.stages.push(stage),
            _ => rows.push(Row {
                label,
                chain: mode == "chain",
                stages: vec![stage],
            }),
        }
    }
    rows
}

/// Width and height of the picture, and of a box.
const W: f64 = 980.0;
const LEFT: f64 = 190.0;
const BOX_H: f64 = 70.0;
const ROW_GAP: f64 = 38.0;
const TOP: f64 = 56.0;

/// The files every box names (under `crates/oxcover-planners/src/`).
#[must_use]
pub fn files() -> Vec<&'static str> {
    PICTURE
        .lines()
        .filter_map(|l| l.split('|').nth(2).map(str::trim))
        .collect()
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The picture.
#[must_use]
pub fn lanes_svg() -> String {
    let all = rows();
    let rows = all.len() as f64;
    let h = TOP + rows * (BOX_H + ROW_GAP) - ROW_GAP + 20.0;
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{h}" viewBox="0 0 {W} {h}" font-family="DejaVu Sans, Arial, sans-serif">"#
    );
    svg += "<title>The stages of the lanes planner</title>\n";
    svg += r##"<defs><marker id="a" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" markerHeight="7" orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" fill="#333"/></marker></defs>"##;
    let _ = writeln!(svg, "\n<rect width=\"{W}\" height=\"{h}\" fill=\"white\"/>");
    let _ = writeln!(
        svg,
        r#"<text x="{}" y="30" text-anchor="middle" font-weight="bold" font-size="16">lanes: one region's plan, stage by stage (crates/oxcover-planners/src/)</text>"#,
        W / 2.0
    );
    let span = W - LEFT - 20.0;
    // Each row's box centres, to draw the arrows between rows.
    let mut prev: Vec<(f64, f64)> = Vec::new();
    for (i, row) in all.iter().enumerate() {
        let y = TOP + i as f64 * (BOX_H + ROW_GAP);
        let n = row.stages.len() as f64;
        let gap = 24.0;
        let bw = (span - gap * (n - 1.0)) / n;
        let _ = writeln!(
            svg,
            r##"<text x="14" y="{}" font-size="12.5" fill="#555">{}</text>"##,
            y + BOX_H / 2.0 + 4.0,
            esc(row.label)
        );
        let mut centres = Vec::new();
        for (k, s) in row.stages.iter().enumerate() {
            let x = LEFT + k as f64 * (bw + gap);
            let fill = if s.file.starts_with("lanes/") {
                "#eef4fb"
            } else {
                "#f4f4f4"
            };
            let _ = writeln!(
                svg,
                r##"<rect x="{x:.1}" y="{y:.1}" width="{bw:.1}" height="{BOX_H}" rx="8" fill="{fill}" stroke="#777" stroke-width="1.5"/>"##
            );
            let cx = x + bw / 2.0;
            let _ = writeln!(
                svg,
                r##"<text x="{cx:.1}" y="{:.1}" text-anchor="middle" font-weight="bold" font-size="13">{} <tspan font-weight="normal" font-size="11" fill="#555">{}</tspan></text>"##,
                y + 19.0,
                esc(s.title),
                esc(s.file)
            );
            for (l, line) in s.lines.iter().enumerate() {
                let _ = writeln!(
                    svg,
                    r#"<text x="{cx:.1}" y="{:.1}" text-anchor="middle" font-size="11.5">{}</text>"#,
                    y + 38.0 + 15.0 * l as f64,
                    esc(line)
                );
            }
            if row.chain && k > 0 {
                let _ = writeln!(
                    svg,
                    r##"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#333" stroke-width="1.5" marker-end="url(#a)"/>"##,
                    x - gap + 2.0,
                    y + BOX_H / 2.0,
                    x - 2.0,
                    y + BOX_H / 2.0
                );
            }
            centres.push((cx, y));
        }
        // Arrows from the row above: from each box above to the first box
        // of a chain, or to each box of a parallel row below one box.
        let targets: Vec<(f64, f64)> = if row.chain {
            centres.iter().take(1).copied().collect()
        } else {
            centres.clone()
        };
        for &(px, py) in &prev {
            for &(tx, ty) in &targets {
                if prev.len() > 1 && targets.len() > 1 && (px - tx).abs() > 1.0 {
                    continue;
                }
                let _ = writeln!(
                    svg,
                    r##"<line x1="{px:.1}" y1="{:.1}" x2="{tx:.1}" y2="{:.1}" stroke="#333" stroke-width="1.5" marker-end="url(#a)"/>"##,
                    py + BOX_H,
                    ty - 2.0
                );
            }
        }
        prev = if row.chain {
            centres.last().copied().into_iter().collect()
        } else {
            centres
        };
    }
    svg += "</svg>\n";
    svg
}

/// Writes `docs/lanes.svg`.
///
/// # Errors
/// When the file cannot be written.
pub fn run() -> anyhow::Result<()> {
    let path = crate::root().join("docs/lanes.svg");
    std::fs::write(&path, lanes_svg())?;
    println!("wrote {}", path.display());
    Ok(())
}
