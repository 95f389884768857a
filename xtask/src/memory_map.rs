//! `cargo xtask memory-map`: the large map of the memory measurements in
//! `docs/benchmarks.md` ("Memory of `plan`"), written as a grey PNG row by
//! row (a 16384² map is a 300 KB file and never held whole in memory here).
//!
//! The map: a walled square, three walls across it every quarter with a
//! 200-pixel door near the left, and a 400-pixel block in the middle.

use std::io::Write as _;
use std::path::Path;

use anyhow::{Context, bail};

/// Writes the `size` × `size` map to `out`.
///
/// # Errors
/// A size below 64 or above 16384, or a file that cannot be written.
pub fn run(size: u32, out: &Path) -> anyhow::Result<()> {
    if !(64..=16384).contains(&size) {
        bail!("--size must be within 64..=16384");
    }
    let file = std::fs::File::create(out).with_context(|| format!("creating {}", out.display()))?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), size, size);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header()?.into_stream_writer()?;
    let n = size as usize;
    let (free, wall) = (254u8, 0u8);
    let door = (n / 160)..(n / 160 + n / 80);
    let block = (n * 5 / 16)..(n * 5 / 16 + n / 40);
    let mut row = vec![free; n];
    for y in 0..n {
        let border = y == 0 || y == n - 1;
        let across = y % (n / 4) == 0 && y > 0;
        for (x, v) in row.iter_mut().enumerate() {
            let walled = border || x == 0 || x == n - 1 || (across && !door.contains(&x));
            let blocked = block.contains(&x) && block.contains(&y);
            *v = if walled || blocked { wall } else { free };
        }
        writer.write_all(&row)?;
    }
    writer.finish()?;
    println!("wrote {} ({size}x{size})", out.display());
    Ok(())
}
