//! PNG (grey, grey+alpha, RGB, RGBA, palette; 8 or 16 bit) and BMP through the
//! `image` crate. Colour channels are averaged; alpha is ignored (contract).
//!
//! BMP is read because map_server reads it (SDL_image) and real maps use it
//! (`turtlebot_stage/maps/robopark2.bmp`); the contract lists PGM and PNG, BMP
//! is an addition that changes nothing for them.

use std::io::Cursor;
use std::path::Path;

use image::{DynamicImage, ImageFormat, ImageReader, Limits};

use super::check_size;
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::occupancy::Occupancy;

/// Decodes PNG/BMP bytes, classifying each averaged 0..=255 value with `classify`.
pub(super) fn decode(
    path: &Path,
    bytes: &[u8],
    max_cells: usize,
    classify: impl Fn(f64) -> Occupancy,
) -> Result<Grid<Occupancy>> {
    let format = match image::guess_format(bytes) {
        Ok(f @ (ImageFormat::Png | ImageFormat::Bmp)) => f,
        _ => {
            return Err(Error::UnsupportedFormat {
                path: path.to_path_buf(),
                message: "not a PGM, PNG or BMP image".into(),
            });
        }
    };
    let name = if format == ImageFormat::Png {
        "PNG"
    } else {
        "BMP"
    };
    let corrupt = |e: image::ImageError| Error::Format {
        path: path.to_path_buf(),
        message: format!("corrupt or truncated {name}: {e}"),
    };
    // PNG keeps its size in the first chunk: check it before the decoder, which
    // may want more of a file whose header already says it is too large.
    if format == ImageFormat::Png && bytes.len() >= 24 && &bytes[12..16] == b"IHDR" {
        let be =
            |i: usize| u32::from_be_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
        check_size(path, u64::from(be(16)), u64::from(be(20)), max_cells)?;
    }
    let (w, h) = ImageReader::with_format(Cursor::new(bytes), format)
        .into_dimensions()
        .map_err(corrupt)?;
    check_size(path, u64::from(w), u64::from(h), max_cells)?;
    let mut reader = ImageReader::with_format(Cursor::new(bytes), format);
    let mut limits = Limits::default();
    // The size check above is the real guard; allow what a max-size RGBA16 image needs.
    limits.max_alloc = Some((max_cells as u64).saturating_mul(8).max(1 << 20));
    reader.limits(limits);
    let img = reader.decode().map_err(corrupt)?;
    let (width, height) = (img.width() as usize, img.height() as usize);
    let cells: Vec<Occupancy> = match &img {
        DynamicImage::ImageLuma8(b) => b.pixels().map(|p| classify(f64::from(p.0[0]))).collect(),
        DynamicImage::ImageLumaA8(b) => b.pixels().map(|p| classify(f64::from(p.0[0]))).collect(),
        DynamicImage::ImageRgb8(b) => b.pixels().map(|p| classify(avg8(&p.0))).collect(),
        DynamicImage::ImageRgba8(b) => b.pixels().map(|p| classify(avg8(&p.0[..3]))).collect(),
        DynamicImage::ImageLuma16(b) => b.pixels().map(|p| classify(scale16(p.0[0]))).collect(),
        DynamicImage::ImageLumaA16(b) => b.pixels().map(|p| classify(scale16(p.0[0]))).collect(),
        DynamicImage::ImageRgb16(b) => b.pixels().map(|p| classify(avg16(&p.0))).collect(),
        DynamicImage::ImageRgba16(b) => b.pixels().map(|p| classify(avg16(&p.0[..3]))).collect(),
        other => other
            .to_rgb32f()
            .pixels()
            .map(|p| classify(f64::from(p.0[0] + p.0[1] + p.0[2]) / 3.0 * 255.0))
            .collect(),
    };
    Grid::from_vec(width, height, cells).ok_or_else(|| Error::Format {
        path: path.to_path_buf(),
        message: "decoder returned a buffer of the wrong size".into(),
    })
}

fn avg8(c: &[u8]) -> f64 {
    c.iter().map(|&v| f64::from(v)).sum::<f64>() / c.len() as f64
}

fn scale16(v: u16) -> f64 {
    f64::from(v) * 255.0 / 65535.0
}

fn avg16(c: &[u16]) -> f64 {
    c.iter().map(|&v| scale16(v)).sum::<f64>() / c.len() as f64
}
