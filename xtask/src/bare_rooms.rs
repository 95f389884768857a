//! The efficiency page's synthetic rooms: what a room's size and clutter
//! leave of the time efficiency, under the contract's time model.
//!
//! Rectangular rooms drawn at 0.05 m per cell (a wall two cells thick round
//! free space of the stated size), bare or with 10 cm specks (2 × 2
//! occupied cells) at fixed positions, are planned by `lanes` with the
//! efficiency page's robots (robot = tool radius 0.15 m and 0.3 m). Each
//! row sets the plan's time efficiency beside the **U-turn ceiling** of a
//! bare room: straight lanes of the tool's width along the room's long
//! side, no overlap, and one half turn (π rad at the turning rate) between
//! lanes, nothing else. That is a model of the pattern, not a proof that no
//! path does better; it shows how much of a small room's time the U-turns
//! alone take.

use std::f64::consts::PI;
use std::fmt::Write as _;

use oxcover::pipeline::{PlanRequest, plan, planner};
use oxcover::planners::{PlannerOptions, Start, TimeModel};
use oxcover_grid::{Cell, DiscRobot, Grid, Occupancy, OccupancyGrid, Point};
use rayon::prelude::*;

/// Metres per cell of the drawn rooms (the maps' own).
const RES: f64 = 0.05;
/// Wall thickness in cells.
const WALL: usize = 2;
/// A speck's side in cells (10 cm).
const SPECK: usize = 2;
/// Least distance of a speck from a wall and from another speck (metres).
const SPECK_CLEARANCE: f64 = 0.6;

/// A rectangular room of `w` × `h` metres of free space inside a wall, with
/// `specks` 10 cm obstacles spread over it by a fixed low-discrepancy
/// sequence (the same map every run).
#[must_use]
pub fn room(w: f64, h: f64, specks: usize) -> OccupancyGrid {
    let (fw, fh) = ((w / RES).round() as usize, (h / RES).round() as usize);
    let (gw, gh) = (fw + 2 * WALL, fh + 2 * WALL);
    let mut cells = Grid::from_fn(gw, gh, |c: Cell| {
        let inside = (WALL..WALL + fh).contains(&c.row) && (WALL..WALL + fw).contains(&c.col);
        if inside {
            Occupancy::Free
        } else {
            Occupancy::Occupied
        }
    });
    for (x, y) in speck_positions(w, h, specks) {
        let col = WALL + (x / RES) as usize;
        let row = WALL + (y / RES) as usize;
        for dr in 0..SPECK {
            for dc in 0..SPECK {
                cells[Cell::new(row + dr, col + dc)] = Occupancy::Occupied;
            }
        }
    }
    OccupancyGrid::new(cells, RES, Point::new(0.0, 0.0))
}

/// Lower-left corners (metres, from the free space's corner) of `n` specks:
/// the additive sequence of the plastic number over the room less
/// [`SPECK_CLEARANCE`] at its walls, skipping a point nearer than that to
/// an earlier speck. Fewer than `n` when the room cannot hold them.
fn speck_positions(w: f64, h: f64, n: usize) -> Vec<(f64, f64)> {
    // 1/ρ and 1/ρ² for the plastic number ρ: an even spread in two dimensions.
    const A: (f64, f64) = (0.754_877_666_246_692_7, 0.569_840_290_998_053_2);
    let (iw, ih) = (w - 2.0 * SPECK_CLEARANCE, h - 2.0 * SPECK_CLEARANCE);
    let mut out: Vec<(f64, f64)> = Vec::new();
    if iw <= 0.0 || ih <= 0.0 {
        return out;
    }
    for k in 1..=64 * n.max(1) {
        if out.len() == n {
            break;
        }
        let (u, v) = (
            (0.5 + A.0 * k as f64).fract(),
            (0.5 + A.1 * k as f64).fract(),
        );
        let p = (SPECK_CLEARANCE + u * iw, SPECK_CLEARANCE + v * ih);
        let near = out
            .iter()
            .any(|q| (q.0 - p.0).hypot(q.1 - p.1) < SPECK_CLEARANCE);
        if !near {
            out.push(p);
        }
    }
    out
}

/// Time efficiency of straight lanes of width `2 · tool` along the long side
/// of a bare `w` × `h` room, with a half turn between lanes and nothing else.
#[must_use]
pub fn u_turn_ceiling(w: f64, h: f64, tool: f64, time: &TimeModel) -> f64 {
    let (long, short) = (w.max(h), w.min(h));
    let lanes = (short / (2.0 * tool)).ceil().max(1.0);
    let bound = time.time(w * h / (2.0 * tool), 0.0);
    bound / (time.time(lanes * long, (lanes - 1.0) * PI))
}

/// One synthetic room's row.
struct Row {
    w: f64,
    h: f64,
    specks: usize,
    radius: f64,
    efficiency: f64,
    est_time_s: f64,
    turning_s: f64,
    ceiling: f64,
}

/// The rooms planned: bare rooms of four sizes for each robot, and the
/// middle size with more and more specks for the ROS maps' robot.
fn cases() -> Vec<(f64, f64, usize, f64)> {
    let mut v = Vec::new();
    for radius in [0.15, 0.3] {
        for (w, h) in [(3.0, 3.0), (5.0, 4.0), (8.0, 6.0), (15.0, 10.0)] {
            v.push((w, h, 0, radius));
        }
    }
    for specks in [1, 4, 16] {
        v.push((8.0, 6.0, specks, 0.15));
    }
    v
}

/// The page section: a table of the synthetic rooms and what it shows.
///
/// # Errors
/// When a room cannot be planned, or its plan misses a cell or collides.
pub fn section() -> anyhow::Result<String> {
    let time = TimeModel::default();
    let rows = cases()
        .into_par_iter()
        .map(|(w, h, specks, radius)| -> anyhow::Result<Row> {
            let map = room(w, h, specks);
            let req = PlanRequest::with_planner(planner("lanes", &PlannerOptions::new())?, RES)
                .robot(DiscRobot::new(radius, radius)?)
                .start(Start::LargestRegion);
            let out = plan(&map, &req)?;
            let m = &out.evaluation.metrics;
            anyhow::ensure!(
                m.coverage == 1.0 && m.collisions == 0,
                "lanes on a {w} x {h} m room with {specks} specks: coverage {}, {} collisions",
                m.coverage,
                m.collisions
            );
            Ok(Row {
                w,
                h,
                specks,
                radius,
                efficiency: m.time_efficiency.unwrap_or(0.0),
                est_time_s: m.est_time_s,
                turning_s: m.rotation_rad / time.angular_speed,
                ceiling: u_turn_ceiling(w, h, radius, &time),
            })
        })
        .collect::<anyhow::Result<Vec<Row>>>()?;
    let mut md = String::from(
        "## What a room's size and clutter leave\n\n\
         Synthetic rectangular rooms (free space of the size given inside a wall, 0.05 m per cell), bare or with 10 cm square specks spread evenly at least 0.6 m from the walls and from each other, planned by `lanes` with the two settings' robots. Measured by this page's run.\n\n\
         `U-turn ceiling`: the time efficiency of straight lanes of the tool's width along the room's long side with a half turn (π rad) between lanes and nothing else (no loop, no overlap, no link): a model of the pattern, not a bound on every path.\n\n\
         | room | specks | robot = tool radius | est. time s | of which turning s | time eff. | U-turn ceiling |\n\
         |---|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in &rows {
        let _ = writeln!(
            md,
            "| {} × {} m | {} | {} m | {:.0} | {:.0} | {:.3} | {:.3} |",
            r.w, r.h, r.specks, r.radius, r.est_time_s, r.turning_s, r.efficiency, r.ceiling
        );
    }
    let bare = |w: f64, radius: f64| {
        rows.iter()
            .find(|r| r.specks == 0 && r.radius == radius && r.w == w)
            .ok_or_else(|| anyhow::anyhow!("no bare {w} m room for radius {radius}"))
    };
    let (small, middle) = (bare(3.0, 0.15)?, bare(8.0, 0.15)?);
    let share: Vec<f64> = rows
        .iter()
        .filter(|r| r.specks == 0)
        .map(|r| r.efficiency / r.ceiling)
        .collect();
    let (lo, hi) = share.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &x| {
        (lo.min(x), hi.max(x))
    });
    let per_speck: Vec<String> = rows
        .iter()
        .filter(|r| r.specks > 0)
        .map(|r| {
            format!(
                "with {} {} {:.0} s more{}",
                r.specks,
                if r.specks == 1 { "speck" } else { "specks" },
                r.est_time_s - middle.est_time_s,
                if r.specks == 1 {
                    String::new()
                } else {
                    format!(
                        " ({:.0} s each)",
                        (r.est_time_s - middle.est_time_s) / r.specks as f64
                    )
                }
            )
        })
        .collect();
    let _ = writeln!(
        md,
        "\nOn the bare rooms `lanes` reaches {:.0} to {:.0} % of the U-turn ceiling (its loop along the walls, the links between lanes and, in the smaller rooms, the lanes' ends near the corners cost the rest). The ceiling itself falls with the room: at the ROS maps' 0.3 m lane spacing it is {:.2} for a 3 × 3 m room and {:.2} for an 8 × 6 m one.\n\n\
         Clutter costs far more than its area: a speck needs a loop round it (a full turn, 12 s at the contract's turning rate, and about 1.3 m of driving) and cuts the lanes beside it. In the 8 × 6 m room (bare: {:.0} s, {:.0} s of it turning) the plan takes {}.\n\n\
         A speck's loop alone, the full turn and the C-space outline of a 10 cm square for this robot, would take {:.0} s. `lanes` drives an island's loop from the lane passing nearest, so what it pays beyond that is the way out to the loop and back and the lanes' bends round the speck. The small rooms, pillar arenas and scanner specks of the ROS maps, not the last few hundredths on bare rooms, keep their mean far from 0.65.",
        100.0 * lo,
        100.0 * hi,
        small.ceiling,
        middle.ceiling,
        middle.est_time_s,
        middle.turning_s,
        per_speck.join(", "),
        time.time(4.0 * SPECK as f64 * RES + 2.0 * PI * 0.15, 2.0 * PI)
    );
    Ok(md)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rooms_have_their_size_and_specks() {
        let m = room(3.0, 2.0, 0);
        assert_eq!((m.width(), m.height()), (60 + 2 * WALL, 40 + 2 * WALL));
        assert_eq!(m.counts().free, 60 * 40);
        let s = room(8.0, 6.0, 4);
        assert_eq!(s.counts().free, 160 * 120 - 4 * SPECK * SPECK);
        // The same map every time.
        assert_eq!(room(8.0, 6.0, 16).cells(), room(8.0, 6.0, 16).cells());
        for (x, y) in speck_positions(8.0, 6.0, 16) {
            assert!((SPECK_CLEARANCE..=8.0 - SPECK_CLEARANCE).contains(&x));
            assert!((SPECK_CLEARANCE..=6.0 - SPECK_CLEARANCE).contains(&y));
        }
        assert_eq!(speck_positions(8.0, 6.0, 16).len(), 16);
        // A room too small for a speck holds none.
        assert!(speck_positions(1.0, 1.0, 3).is_empty());
    }

    #[test]
    fn u_turn_ceiling_counts_lanes_and_half_turns() {
        let t = TimeModel::default();
        // 3 m wide at 0.3 m lanes: 10 lanes of 3 m, 9 half turns.
        let expect = t.time(30.0, 0.0) / t.time(30.0, 9.0 * PI);
        assert!((u_turn_ceiling(3.0, 3.0, 0.15, &t) - expect).abs() < 1e-12);
        // Long rooms lose less to their turns.
        assert!(u_turn_ceiling(15.0, 3.0, 0.15, &t) > u_turn_ceiling(3.0, 3.0, 0.15, &t));
        assert!(u_turn_ceiling(3.0, 3.0, 0.3, &t) > u_turn_ceiling(3.0, 3.0, 0.15, &t));
    }
}
