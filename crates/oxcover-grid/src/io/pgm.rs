//! Netpbm greymaps: PGM P2 (ASCII) and P5 (binary), 8 or 16 bit.
//!
//! Written by hand rather than through an image crate so that a lying header is
//! reported precisely ("header says 1000x1000, which needs 1000000 bytes, but
//! the file holds 812") and the size is checked before anything is allocated.
//! Samples are scaled to 0..=255 by `v·255/maxval` before classification.

use std::path::Path;

use super::check_size;
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::occupancy::Occupancy;

/// Decodes PGM bytes, classifying each scaled sample with `classify`.
pub(super) fn decode(
    path: &Path,
    bytes: &[u8],
    max_cells: usize,
    classify: impl Fn(f64) -> Occupancy,
) -> Result<Grid<Occupancy>> {
    let format = |message: String| Error::Format {
        path: path.to_path_buf(),
        message,
    };
    let binary = match bytes.get(..2) {
        Some(b"P5") => true,
        Some(b"P2") => false,
        Some([b'P', k]) if k.is_ascii_digit() => {
            return Err(Error::UnsupportedFormat {
                path: path.to_path_buf(),
                message: format!(
                    "Netpbm type P{} is not supported, expected a P2 or P5 greymap",
                    *k as char
                ),
            });
        }
        _ => return Err(format("not a PGM file (expected magic P2 or P5)".into())),
    };
    let mut cursor = Header { bytes, pos: 2 };
    let width = cursor.number(path, "width")?;
    let height = cursor.number(path, "height")?;
    check_size(path, width, height, max_cells)?;
    let maxval = cursor.number(path, "maxval")?;
    if !(1..=65535).contains(&maxval) {
        return Err(format(format!("maxval is {maxval}, expected 1..=65535")));
    }
    let (width, height) = (width as usize, height as usize);
    let n = width * height;
    let scale = 255.0 / maxval as f64;
    let mut cells = Vec::with_capacity(n);
    if binary {
        // Exactly one whitespace byte separates maxval from the raster.
        match bytes.get(cursor.pos) {
            Some(b) if b.is_ascii_whitespace() => cursor.pos += 1,
            _ => return Err(format("expected one whitespace byte after maxval".into())),
        }
        let raster = &bytes[cursor.pos..];
        let bpp = if maxval < 256 { 1 } else { 2 };
        if raster.len() < n * bpp {
            return Err(Error::Truncated {
                path: path.to_path_buf(),
                width,
                height,
                expected: n * bpp,
                found: raster.len(),
                unit: "bytes of pixel data",
            });
        }
        for i in 0..n {
            let v = if bpp == 1 {
                u32::from(raster[i])
            } else {
                u32::from(u16::from_be_bytes([raster[2 * i], raster[2 * i + 1]]))
            };
            if v > maxval as u32 {
                return Err(sample_error(path, i, width, v, maxval));
            }
            cells.push(classify(v as f64 * scale));
        }
    } else {
        for i in 0..n {
            let v = match cursor.token() {
                Some(tok) => parse_u32(tok).ok_or_else(|| {
                    format(format!(
                        "pixel {} (row {}, col {}) is `{}`, expected a number",
                        i,
                        i / width,
                        i % width,
                        String::from_utf8_lossy(tok)
                    ))
                })?,
                None => {
                    return Err(Error::Truncated {
                        path: path.to_path_buf(),
                        width,
                        height,
                        expected: n,
                        found: i,
                        unit: "pixel values",
                    });
                }
            };
            if u64::from(v) > maxval {
                return Err(sample_error(path, i, width, v, maxval));
            }
            cells.push(classify(v as f64 * scale));
        }
    }
    Grid::from_vec(width, height, cells).ok_or_else(|| format("internal size mismatch".into()))
}

fn sample_error(path: &Path, i: usize, width: usize, v: u32, maxval: u64) -> Error {
    Error::Format {
        path: path.to_path_buf(),
        message: format!(
            "pixel {} (row {}, col {}) is {v}, above maxval {maxval}",
            i,
            i / width,
            i % width
        ),
    }
}

fn parse_u32(tok: &[u8]) -> Option<u32> {
    std::str::from_utf8(tok).ok()?.parse().ok()
}

struct Header<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Header<'a> {
    /// Next whitespace-separated token, skipping `#` comments.
    fn token(&mut self) -> Option<&'a [u8]> {
        loop {
            while self.pos < self.bytes.len() && self.bytes[self.pos].is_ascii_whitespace() {
                self.pos += 1;
            }
            if self.bytes.get(self.pos) == Some(&b'#') {
                while self.pos < self.bytes.len() && self.bytes[self.pos] != b'\n' {
                    self.pos += 1;
                }
                continue;
            }
            break;
        }
        let start = self.pos;
        while self.pos < self.bytes.len()
            && !self.bytes[self.pos].is_ascii_whitespace()
            && self.bytes[self.pos] != b'#'
        {
            self.pos += 1;
        }
        (self.pos > start).then(|| &self.bytes[start..self.pos])
    }

    fn number(&mut self, path: &Path, what: &str) -> Result<u64> {
        let tok = self.token().ok_or_else(|| Error::Format {
            path: path.to_path_buf(),
            message: format!("header ends before {what}"),
        })?;
        std::str::from_utf8(tok)
            .ok()
            .and_then(|s| s.parse::<u64>().ok())
            .ok_or_else(|| Error::Format {
                path: path.to_path_buf(),
                message: format!(
                    "header {what} is `{}`, expected a whole number",
                    String::from_utf8_lossy(tok)
                ),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grey(v: f64) -> Occupancy {
        if v > 127.0 {
            Occupancy::Free
        } else {
            Occupancy::Occupied
        }
    }

    #[test]
    fn reads_p2_with_comments_and_p5_16_bit() {
        let p2 = b"P2\n# a comment\n3 2 # trailing\n255\n0 255 0\n255 0 255\n";
        let g = decode(Path::new("a.pgm"), p2, 100, grey).unwrap();
        assert_eq!((g.width(), g.height()), (3, 2));
        assert_eq!(g.as_slice()[1], Occupancy::Free);
        assert_eq!(g.as_slice()[3], Occupancy::Free);
        let mut p5 = b"P5 2 1 65535\n".to_vec();
        p5.extend([0xff, 0xff, 0x00, 0x10]);
        let g = decode(Path::new("b.pgm"), &p5, 100, grey).unwrap();
        assert_eq!(g.as_slice(), &[Occupancy::Free, Occupancy::Occupied]);
    }

    #[test]
    fn lying_headers_are_errors() {
        let cases: [(&[u8], &str); 7] = [
            (b"P5\n4 4\n255\n\x00\x00", "truncated"),
            (b"P2\n2 2\n255\n0 0 0", "truncated"),
            (b"P5\n100000 100000\n255\n", "exceeds the limit"),
            (b"P5\n0 5\n255\n", "empty"),
            (b"P5\n2 x\n255\n", "header height is `x`"),
            (b"P2\n1 1\n10\n11\n", "above maxval"),
            (b"P6\n1 1\n255\n\x00\x00\x00", "P6 is not supported"),
        ];
        for (bytes, want) in cases {
            let e = decode(Path::new("x.pgm"), bytes, 1 << 20, grey)
                .unwrap_err()
                .to_string();
            assert!(e.contains(want), "{e:?} should contain {want:?}");
        }
    }
}
