//! A plan's segments beside its ground-truth rooms, one PNG: each segment
//! or room one colour ([`oxcover::render::region_rgb`]), obstacles dark,
//! free cells outside every room (truth) light grey.

use std::path::Path;

use oxcover::render::region_rgb;
use oxcover_grid::Grid;

/// Pixels between the two halves.
const GAP: usize = 12;

/// Writes `segments` (over the free cells `free`) and `truth` side by side
/// to `out`, scaled down to at most 700 pixels wide per half.
///
/// # Errors
/// When the file cannot be written.
pub(super) fn write(
    free: &Grid<bool>,
    segments: &Grid<u32>,
    truth: &Grid<u32>,
    out: &Path,
) -> anyhow::Result<()> {
    let (w, h) = (free.width(), free.height());
    let step = w.div_ceil(700).max(1);
    let (sw, sh) = (w.div_ceil(step), h.div_ceil(step));
    let width = 2 * sw + GAP;
    let mut rgb = vec![255u8; width * sh * 3];
    let colour = |free: bool, label: u32| -> [u8; 3] {
        match (free, label) {
            (false, _) => [70, 70, 70],
            (true, 0) => [215, 215, 215],
            (true, l) => region_rgb(l),
        }
    };
    for y in 0..sh {
        for x in 0..sw {
            let c = oxcover_grid::Cell::new(y * step, x * step);
            let left = colour(free[c], segments[c]);
            let right = colour(truth[c] > 0 || free[c], truth[c]);
            let right = if truth[c] == 0 && !free[c] {
                [70, 70, 70]
            } else {
                right
            };
            for (x0, px) in [(x, left), (sw + GAP + x, right)] {
                let i = (y * width + x0) * 3;
                rgb[i..i + 3].copy_from_slice(&px);
            }
        }
    }
    let file = std::fs::File::create(out)?;
    let mut enc = png::Encoder::new(
        std::io::BufWriter::new(file),
        u32::try_from(width)?,
        u32::try_from(sh)?,
    );
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header()?.write_image_data(&rgb)?;
    Ok(())
}
