//! A small ASCII map format for tests and examples.
//!
//! `#` blocked, `.` free, `S` the start (free), `?` unknown. Leading and trailing
//! blank lines and the indentation common to all lines are ignored, so maps can
//! be written inline in Rust string literals. Unit frame (1 m cells).

use crate::error::{Error, Result};
use crate::grid::{Cell, Grid};
use crate::occupancy::{Occupancy, OccupancyGrid};

/// Parses an ASCII map; returns the map and the `S` cell if there is one.
///
/// # Errors
/// [`Error::Format`] for ragged rows, unknown characters, several `S`, or no row.
pub fn parse_ascii(text: &str) -> Result<(OccupancyGrid, Option<Cell>)> {
    let format = |message: String| Error::Format {
        path: "<ascii map>".into(),
        message,
    };
    let rows: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    let height = rows.len();
    let width = rows.first().map_or(0, |r| r.chars().count());
    if height == 0 || width == 0 {
        return Err(format("no map rows".into()));
    }
    let mut cells = Vec::with_capacity(width * height);
    let mut start = None;
    for (r, line) in rows.iter().enumerate() {
        if line.chars().count() != width {
            return Err(format(format!(
                "row {r} has {} cells, expected {width}",
                line.chars().count()
            )));
        }
        for (c, ch) in line.chars().enumerate() {
            cells.push(match ch {
                '#' => Occupancy::Occupied,
                '.' => Occupancy::Free,
                '?' => Occupancy::Unknown,
                'S' => {
                    if start.replace(Cell::new(r, c)).is_some() {
                        return Err(format("more than one S".into()));
                    }
                    Occupancy::Free
                }
                other => {
                    return Err(format(format!(
                        "row {r} col {c}: `{other}`, expected #, ., S or ?"
                    )));
                }
            });
        }
    }
    let grid = Grid::from_vec(width, height, cells).ok_or_else(|| format("size".into()))?;
    Ok((OccupancyGrid::unit(grid), start))
}

/// The free cells of the ASCII map whose rows are `rows` (the
/// [`parse_ascii`] format, one string per row): a compact way to write small
/// masks in tests and examples.
///
/// # Errors
/// As [`parse_ascii`].
pub fn ascii_mask(rows: &[&str]) -> Result<Grid<bool>> {
    Ok(parse_ascii(&rows.join("\n"))?.0.free_mask())
}

/// Draws a map as ASCII (`#` occupied, `.` free, `?` unknown), overlaying
/// `marks` (cell, character) in order, so later marks win.
#[must_use]
pub fn to_ascii(map: &Grid<Occupancy>, marks: &[(Cell, char)]) -> String {
    let mut chars: Grid<char> = map.map(|o| match o {
        Occupancy::Free => '.',
        Occupancy::Occupied => '#',
        Occupancy::Unknown => '?',
    });
    for &(cell, ch) in marks {
        if let Some(c) = chars.get_mut(cell) {
            *c = ch;
        }
    }
    let mut s = String::with_capacity((map.width() + 1) * map.height());
    for r in 0..map.height() {
        s.extend(chars.row(r));
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_through_to_ascii() {
        let text = "
            #..#
            .S?.
        ";
        let (m, s) = parse_ascii(text).unwrap();
        assert_eq!(s, Some(Cell::new(1, 1)));
        assert_eq!(
            to_ascii(m.cells(), &[(Cell::new(1, 1), 'S')]),
            "#..#\n.S?.\n"
        );
        assert!(parse_ascii("..\n.").is_err());
        assert!(parse_ascii("S.S").is_err());
        assert!(parse_ascii("a").is_err());
        assert!(parse_ascii("\n\n").is_err());
    }
}
