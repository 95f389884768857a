//! MovingAI grid benchmark maps (Sturtevant 2012): `type`, `height`, `width`,
//! `map`, then `height` rows of `width` characters.
//!
//! `.`, `G` and `S` are free; every other character is blocked (contract).
//! Resolution 1.0 m, origin (0, 0).

use std::path::Path;

use super::{ReadOptions, check_size, read_bytes};
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::occupancy::{Occupancy, OccupancyGrid};

/// Reads a MovingAI `.map` file.
///
/// # Errors
/// [`Error`] naming the file and the header line or row at fault.
pub fn read_movingai(path: &Path, options: &ReadOptions) -> Result<OccupancyGrid> {
    let bytes = read_bytes(path)?;
    parse_movingai(path, &bytes, options)
}

/// Parses the bytes of a MovingAI map read from `path` (used in messages).
///
/// # Errors
/// As [`read_movingai`].
pub fn parse_movingai(path: &Path, bytes: &[u8], options: &ReadOptions) -> Result<OccupancyGrid> {
    let format = |message: String| Error::Format {
        path: path.to_path_buf(),
        message,
    };
    let text = std::str::from_utf8(bytes)
        .map_err(|_| format("not text, expected a MovingAI map (type/height/width/map)".into()))?;
    let mut lines = text.lines().enumerate();
    let (mut height, mut width) = (None, None);
    let mut saw_type = false;
    loop {
        let Some((n, line)) = lines.next() else {
            let what = if text.trim().is_empty() {
                "empty file, expected a MovingAI header (type/height/width/map)"
            } else {
                "header ends before the `map` line"
            };
            return Err(format(what.into()));
        };
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        if line == "map" {
            break;
        }
        let (key, value) = line.split_once(char::is_whitespace).unwrap_or((line, ""));
        let value = value.trim();
        let parse = |v: &str| {
            v.parse::<u64>().map_err(|_| {
                format(format!(
                    "line {}: {key} is `{v}`, expected a whole number",
                    n + 1
                ))
            })
        };
        match key {
            "type" => saw_type = true,
            "height" => height = Some(parse(value)?),
            "width" => width = Some(parse(value)?),
            _ => {
                return Err(format(format!(
                    "line {}: unexpected header line `{line}`, expected type, height, width or map",
                    n + 1
                )));
            }
        }
    }
    if !saw_type {
        return Err(format("missing `type` header line".into()));
    }
    let height = height.ok_or_else(|| format("missing `height` header line".into()))?;
    let width = width.ok_or_else(|| format("missing `width` header line".into()))?;
    check_size(path, width, height, options.max_cells)?;
    let (width, height) = (width as usize, height as usize);
    let mut cells = Vec::with_capacity(width * height);
    let mut rows = 0;
    for (n, line) in lines {
        if rows == height {
            break;
        }
        let line = line.trim_end_matches(['\r', ' ', '\t']);
        if line.chars().count() != width {
            return Err(format(format!(
                "line {}: map row {} has {} cells, expected width {width}",
                n + 1,
                rows,
                line.chars().count()
            )));
        }
        cells.extend(line.chars().map(|ch| match ch {
            '.' | 'G' | 'S' => Occupancy::Free,
            _ => Occupancy::Occupied,
        }));
        rows += 1;
    }
    if rows < height {
        return Err(Error::Truncated {
            path: path.to_path_buf(),
            width,
            height,
            expected: height,
            found: rows,
            unit: "map rows",
        });
    }
    let grid =
        Grid::from_vec(width, height, cells).ok_or_else(|| format("size mismatch".into()))?;
    Ok(OccupancyGrid::unit(grid))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<OccupancyGrid> {
        parse_movingai(Path::new("t.map"), s.as_bytes(), &ReadOptions::default())
    }

    #[test]
    fn reads_the_benchmark_format() {
        let m = parse("type octile\nheight 2\nwidth 3\nmap\n.@T\nGS.\n").unwrap();
        assert_eq!((m.width(), m.height()), (3, 2));
        assert_eq!(m.counts().free, 4);
        assert_eq!(m.resolution(), 1.0);
    }

    #[test]
    fn malformed_maps_are_errors() {
        for (s, want) in [
            ("", "empty file"),
            ("type octile\nheight 2\nwidth 2\nmap\n..\n", "truncated"),
            (
                "type octile\nheight 2\nwidth 2\nmap\n...\n..\n",
                "expected width 2",
            ),
            ("type octile\nheight x\nwidth 2\nmap\n", "height is `x`"),
            ("type octile\nwidth 2\nmap\n", "missing `height`"),
            (
                "type octile\nheight 100000\nwidth 100000\nmap\n",
                "exceeds the limit",
            ),
        ] {
            let e = parse(s).unwrap_err().to_string();
            assert!(e.contains(want), "{e:?} should contain {want:?}");
        }
    }
}
