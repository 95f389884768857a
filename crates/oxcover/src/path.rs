//! Paths in metres: conversion from cell paths, and the contract's CSV path file.
//!
//! A path file is CSV with header `x,y` (further columns may follow and are
//! ignored on reading), one waypoint per line, metres in the map frame. The path
//! is the polyline through the waypoints.

use std::fmt::Write as _;
use std::path::Path;

use oxcover_grid::{Cell, MapFrame, Point};

use crate::error::{Error, Result};

/// Metre waypoints through the centres of a cell path, keeping only the cells
/// where the direction changes (and both ends). Consecutive duplicates are dropped.
#[must_use]
pub fn cells_to_points(frame: &MapFrame, cells: &[Cell]) -> Vec<Point> {
    let mut kept: Vec<Cell> = Vec::with_capacity(cells.len() / 4 + 2);
    for &c in cells {
        if kept.last() == Some(&c) {
            continue;
        }
        if kept.len() >= 2 {
            let a = kept[kept.len() - 2];
            let b = kept[kept.len() - 1];
            if collinear(a, b, c) {
                let last = kept.len() - 1;
                kept[last] = c;
                continue;
            }
        }
        kept.push(c);
    }
    kept.iter().map(|&c| frame.cell_center(c)).collect()
}

/// Whether `b` lies on the segment `a`–`c` continuing in the same direction.
fn collinear(a: Cell, b: Cell, c: Cell) -> bool {
    let (ar, ac) = (a.row as i64, a.col as i64);
    let (br, bc) = (b.row as i64, b.col as i64);
    let (cr, cc) = (c.row as i64, c.col as i64);
    let (d1r, d1c) = (br - ar, bc - ac);
    let (d2r, d2c) = (cr - br, cc - bc);
    d1r * d2c == d1c * d2r && d1r * d2r + d1c * d2c > 0
}

/// The path file text for `points` (`x,y` header; shortest round-trip decimals).
#[must_use]
pub fn to_csv(points: &[Point]) -> String {
    let mut s = String::with_capacity(points.len() * 24 + 4);
    s.push_str("x,y\n");
    for p in points {
        let _ = writeln!(s, "{},{}", p.x, p.y);
    }
    s
}

/// Writes a path file.
///
/// # Errors
/// [`Error::Write`] when the file cannot be written.
pub fn write_csv(path: &Path, points: &[Point]) -> Result<()> {
    crate::output::write_file(path, to_csv(points).into_bytes())
}

/// Reads a path file.
///
/// # Errors
/// [`Error::Read`], or [`Error::PathFile`] naming the line: missing `x,y`
/// header, a non-numeric or non-finite value, a missing column, no waypoint.
pub fn read_csv(path: &Path) -> Result<Vec<Point>> {
    let bytes = oxcover_grid::io::limited::read_limited_after(
        path,
        oxcover_grid::io::limited::MAX_PATH_BYTES,
        oxcover_grid::io::limited::text_head,
    )
    .map_err(|source| Error::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let text = String::from_utf8(bytes).map_err(|_| Error::PathFile {
        path: path.to_path_buf(),
        line: 1,
        message: "not UTF-8 text, expected CSV with header x,y".into(),
    })?;
    parse_csv(path, &text)
}

/// Parses path-file text read from `path` (used in messages).
///
/// # Errors
/// As [`read_csv`].
pub fn parse_csv(path: &Path, text: &str) -> Result<Vec<Point>> {
    let err = |line: usize, message: String| Error::PathFile {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let Some((n, header)) = lines.next() else {
        return Err(err(1, "empty file, expected CSV with header x,y".into()));
    };
    let header = header.trim_start_matches('\u{feff}');
    let cols: Vec<&str> = header.split(',').map(str::trim).collect();
    let cols_ok = cols.len() >= 2 && cols[0] == "x" && cols[1] == "y";
    if !cols_ok {
        return Err(err(
            n + 1,
            format!(
                "header is `{}`, expected it to start with x,y",
                header.trim()
            ),
        ));
    }
    let mut points = Vec::new();
    for (n, line) in lines {
        let mut fields = line.split(',').map(str::trim);
        let mut value = |name: &str| -> Result<f64> {
            let f = fields
                .next()
                .ok_or_else(|| err(n + 1, format!("missing {name} value")))?;
            let v: f64 = f.parse().map_err(|_| {
                err(
                    n + 1,
                    format!("{name} is `{f}`, expected a number in metres"),
                )
            })?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(err(
                    n + 1,
                    format!("{name} is `{f}`, expected a finite number"),
                ))
            }
        };
        let x = value("x")?;
        let y = value("y")?;
        points.push(Point::new(x, y));
    }
    if points.is_empty() {
        return Err(err(n + 1, "no waypoint after the header".into()));
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn collinear_runs_are_merged() {
        let f = MapFrame::unit(5, 5);
        let cells: Vec<Cell> = [(0, 0), (0, 1), (0, 2), (1, 2), (2, 2), (2, 1), (2, 1)]
            .into_iter()
            .map(Cell::from)
            .collect();
        let p = cells_to_points(&f, &cells);
        let want: Vec<Point> = [(0, 0), (0, 2), (2, 2), (2, 1)]
            .into_iter()
            .map(|c| f.cell_center(Cell::from(c)))
            .collect();
        assert_eq!(p, want);
        // A U-turn is not collinear.
        let back = [Cell::new(0, 0), Cell::new(0, 1), Cell::new(0, 0)];
        assert_eq!(cells_to_points(&f, &back).len(), 3);
    }

    #[test]
    fn csv_round_trip_and_errors() {
        let pts = vec![Point::new(0.1, -2.0), Point::new(1.0 / 3.0, 1e-7)];
        let text = to_csv(&pts);
        assert_eq!(parse_csv(Path::new("p.csv"), &text).unwrap(), pts);
        let extra = "x,y,theta\n1,2,0.5\n";
        assert_eq!(
            parse_csv(Path::new("p.csv"), extra).unwrap(),
            vec![Point::new(1.0, 2.0)]
        );
        for (t, want) in [
            ("", "empty file"),
            ("a,b\n1,2\n", "header"),
            ("x,y\n", "no waypoint"),
            ("x,y\n1\n", "line 2: missing y"),
            ("x,y\n1,abc\n", "y is `abc`"),
            ("x,y\n1,NaN\n", "finite"),
        ] {
            let e = parse_csv(Path::new("p.csv"), t).unwrap_err().to_string();
            assert!(e.contains(want), "{e:?} should contain {want:?}");
        }
    }
}
