//! `nav_msgs/msg/OccupancyGrid` messages to and from oxcover's occupancy
//! grids, by the contract's reading rules: values 0..100 are occupancy in
//! percent, classified with map_server's thresholds (occupied above
//! `occupied_thresh`, free below `free_thresh`), -1 is unknown; row 0 lies
//! at the origin (the bottom row of an image); the origin's yaw comes from
//! its quaternion.

use std::path::Path;

use oxcover_grid::io::{MAX_ORIGIN, MAX_RESOLUTION, Thresholds};
use oxcover_grid::math::Point;
use oxcover_grid::{Cell, Error, Grid, Occupancy};

use crate::msgs::{self, Header, MapMetaData, Pose, Quaternion, Time};

/// The grid of `msg` (read from `path`, for messages), classified with
/// `thresholds`' `free_thresh` and `occupied_thresh`.
///
/// The resolution is a float32 in the message; it is taken as the shortest
/// decimal that reads back to the same float32 (0.05, not
/// 0.0500000007), the figure a map's author wrote, so that a map read from
/// a bag places its cells exactly where its yaml and image place them.
///
/// # Errors
/// [`Error::InvalidField`] for a resolution that is not positive and
/// finite (or above 1000 m), an origin that is not finite (or beyond 1e9 m),
/// a value outside -1..100; [`Error::Truncated`] where `data` does not hold
/// `width × height` values; [`Error::TooLarge`]/[`Error::EmptyMap`] by size.
pub fn from_msg(
    path: &Path,
    msg: &msgs::OccupancyGrid,
    thresholds: &Thresholds,
    max_cells: usize,
) -> Result<oxcover_grid::OccupancyGrid, Error> {
    let info = &msg.info;
    let (w, h) = (info.width as usize, info.height as usize);
    if w == 0 || h == 0 {
        return Err(Error::EmptyMap {
            path: path.to_path_buf(),
            width: w,
            height: h,
        });
    }
    if w.checked_mul(h).is_none_or(|n| n > max_cells) {
        return Err(Error::TooLarge {
            path: path.to_path_buf(),
            width: w as u64,
            height: h as u64,
            limit: max_cells,
        });
    }
    let invalid =
        |field: &'static str, value: String, expected: &'static str| Error::InvalidField {
            path: path.to_path_buf(),
            field,
            value,
            expected,
        };
    let r32 = info.resolution;
    if !(r32.is_finite() && r32 > 0.0 && f64::from(r32) <= MAX_RESOLUTION) {
        return Err(invalid(
            "info.resolution",
            r32.to_string(),
            "a positive finite number of metres per cell, at most 1000",
        ));
    }
    let resolution: f64 = r32.to_string().parse().unwrap_or(f64::from(r32));
    let o = &info.origin;
    let origin_ok = [o.position.x, o.position.y]
        .iter()
        .all(|v| v.is_finite() && v.abs() <= MAX_ORIGIN);
    let q = &o.orientation;
    if !origin_ok || ![q.x, q.y, q.z, q.w].iter().all(|v| v.is_finite()) {
        return Err(invalid(
            "info.origin",
            format!(
                "({}, {}) {:?}",
                o.position.x,
                o.position.y,
                [q.x, q.y, q.z, q.w]
            ),
            "finite coordinates within 1e9 m and a finite quaternion",
        ));
    }
    if msg.data.len() != w * h {
        return Err(Error::Truncated {
            path: path.to_path_buf(),
            width: w,
            height: h,
            expected: w * h,
            found: msg.data.len(),
            unit: "values (info.width x info.height)",
        });
    }
    if let Some(i) = msg.data.iter().position(|&v| !(-1..=100).contains(&v)) {
        return Err(invalid(
            "data",
            format!("{} at row {}, column {}", msg.data[i], i / w, i % w),
            "-1 (unknown) or an occupancy in percent, 0..100",
        ));
    }
    // Each value's class, looked up: -1 unknown, 0..100 by the thresholds.
    let mut class = [Occupancy::Unknown; 256];
    for v in 0..=100i8 {
        let p = f64::from(v) / 100.0;
        class[usize::from(v as u8)] = if p > thresholds.occupied_thresh {
            Occupancy::Occupied
        } else if p < thresholds.free_thresh {
            Occupancy::Free
        } else {
            Occupancy::Unknown
        };
    }
    // Our rows run top-down, the message's bottom-up.
    let mut cells = Vec::with_capacity(w * h);
    for row in msg.data.chunks_exact(w).rev() {
        cells.extend(row.iter().map(|&v| class[usize::from(v as u8)]));
    }
    let cells = Grid::from_vec(w, h, cells)
        .ok_or_else(|| invalid("data", "a grid".into(), "width x height values"))?;
    let yaw = q_yaw(q);
    Ok(
        oxcover_grid::OccupancyGrid::new(cells, resolution, Point::new(o.position.x, o.position.y))
            .with_yaw(yaw),
    )
}

/// The yaw of a map origin's quaternion; exactly 0 for the identity (and
/// for rotations below a nanoradian, which float noise makes).
fn q_yaw(q: &Quaternion) -> f64 {
    let yaw = q.yaw();
    if yaw.abs() < 1e-9 { 0.0 } else { yaw }
}

/// The message of `grid`: 0 free, 100 occupied, -1 unknown, frame `map`,
/// stamped `stamp`.
#[must_use]
pub fn to_msg(grid: &oxcover_grid::OccupancyGrid, stamp: Time) -> msgs::OccupancyGrid {
    let (w, h) = (grid.width(), grid.height());
    let cells = grid.cells();
    let mut data = Vec::with_capacity(w * h);
    for row in (0..h).rev() {
        for col in 0..w {
            data.push(match cells[Cell::new(row, col)] {
                Occupancy::Free => 0,
                Occupancy::Occupied => 100,
                Occupancy::Unknown => -1,
            });
        }
    }
    let origin = grid.frame().origin();
    msgs::OccupancyGrid {
        header: Header {
            stamp,
            frame_id: "map".into(),
        },
        info: MapMetaData {
            map_load_time: stamp,
            resolution: grid.resolution() as f32,
            width: u32::try_from(w).unwrap_or(u32::MAX),
            height: u32::try_from(h).unwrap_or(u32::MAX),
            origin: Pose {
                position: msgs::Point {
                    x: origin.x,
                    y: origin.y,
                    z: 0.0,
                },
                orientation: Quaternion::from_yaw(grid.frame().yaw()),
            },
        },
        data,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oxcover_grid::io::parse_ascii;

    fn map() -> oxcover_grid::OccupancyGrid {
        let cells = parse_ascii("#..\n.?#\n").expect("ascii").0.cells().clone();
        oxcover_grid::OccupancyGrid::new(cells, 0.05, Point::new(-10.0, 2.5)).with_yaw(0.5)
    }

    #[test]
    fn a_grid_round_trips_through_its_message() {
        let grid = map();
        let msg = to_msg(&grid, Time::default());
        // Row 0 of the message is the bottom row: ". ? #".
        assert_eq!(msg.data, vec![0, -1, 100, 100, 0, 0]);
        assert_eq!(msg.info.resolution, 0.05_f32);
        let back = from_msg(Path::new("m"), &msg, &Thresholds::default(), 1 << 20).expect("read");
        assert_eq!(back.cells(), grid.cells());
        assert_eq!(
            back.resolution(),
            0.05,
            "the float32 read as the decimal written"
        );
        assert_eq!(back.frame().origin(), grid.frame().origin());
        assert!((back.frame().yaw() - 0.5).abs() < 1e-12);
    }

    #[test]
    fn values_are_classified_by_map_servers_thresholds() {
        let mut msg = to_msg(&map(), Time::default());
        msg.data = vec![19, 20, 65, 66, -1, 0];
        let back = from_msg(Path::new("m"), &msg, &Thresholds::default(), 1 << 20).expect("read");
        let bottom: Vec<Occupancy> = (0..3).map(|c| back.cells()[Cell::new(1, c)]).collect();
        let top: Vec<Occupancy> = (0..3).map(|c| back.cells()[Cell::new(0, c)]).collect();
        use Occupancy::{Free, Occupied, Unknown};
        assert_eq!(bottom, [Free, Unknown, Unknown]);
        assert_eq!(top, [Occupied, Unknown, Free]);
    }

    #[test]
    fn bad_grids_name_the_field() {
        let good = to_msg(&map(), Time::default());
        let check = |msg: msgs::OccupancyGrid, want: &str| {
            let e = from_msg(Path::new("b.mcap"), &msg, &Thresholds::default(), 1 << 20)
                .expect_err(want)
                .to_string();
            assert!(e.contains(want) && e.starts_with("b.mcap"), "{e}");
        };
        let mut m = good.clone();
        m.data.pop();
        check(m, "needs 6 values");
        for r in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            let mut m = good.clone();
            m.info.resolution = r;
            check(m, "info.resolution");
        }
        let mut m = good.clone();
        m.info.origin.position.x = f64::NAN;
        check(m, "info.origin");
        let mut m = good.clone();
        m.data[2] = 101;
        check(m, "101 at row 0, column 2");
        let mut m = good.clone();
        m.info.width = 0;
        check(m, "empty");
        let mut m = good;
        m.info.width = 1 << 20;
        m.info.height = 1 << 20;
        check(m, "exceeds the limit");
    }
}
