//! `oxcover segment`: the rooms of a map and the doors between them, as JSON
//! and as a picture with one colour per room.

use std::io::Write as _;
use std::path::PathBuf;

use clap::ValueEnum;
use oxcover::render::render_to_file;
use oxcover::report::table;
use oxcover::rooms::{door_overlay, report, scene, segment};
use oxcover::{Error, Result};

use super::args::load;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum MethodArg {
    /// Erode until the free space splits into room-sized pieces, grow them back.
    Morphological,
}

#[derive(Debug, clap::Args)]
pub(crate) struct SegmentArgs {
    /// Map file (.yaml, .pgm, .png, .bmp or .map).
    pub(crate) map: PathBuf,
    /// Segmentation method.
    #[arg(long, value_enum, default_value_t = MethodArg::Morphological)]
    pub(crate) method: MethodArg,
    /// Resolution in m/cell for images read without a yaml [default: 1.0].
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub(crate) resolution: Option<f64>,
    /// Smallest room seed in m² (what erosion leaves of a room).
    #[arg(
        long,
        value_name = "M2",
        default_value_t = 1.0,
        allow_negative_numbers = true
    )]
    pub(crate) min_area: f64,
    /// Largest room seed in m²; larger pieces are eroded further.
    #[arg(
        long,
        value_name = "M2",
        default_value_t = 47.0,
        allow_negative_numbers = true
    )]
    pub(crate) max_area: f64,
    /// Rooms and doors to write (JSON).
    #[arg(long, value_name = "ROOMS.json")]
    pub(crate) out: Option<PathBuf>,
    /// SVG picture to write.
    #[arg(long, value_name = "F.svg")]
    pub(crate) svg: Option<PathBuf>,
    /// PNG picture to write.
    #[arg(long, value_name = "F.png")]
    pub(crate) png: Option<PathBuf>,
}

pub(crate) fn cmd_segment(a: &SegmentArgs) -> Result<()> {
    if let Some(f) = &a.out {
        if f.extension().and_then(|e| e.to_str()) != Some("json") {
            return Err(Error::BadParameter {
                name: "--out",
                value: f.display().to_string(),
                expected: "a file name ending in .json".into(),
            });
        }
    }
    let map = load(&a.map, a.resolution)?;
    let rooms = segment(&map, a.min_area, a.max_area)?;
    let rep = report(&map, &rooms, a.min_area, a.max_area);
    let mut written = Vec::new();
    if let Some(f) = &a.out {
        let json = serde_json::to_string_pretty(&rep)
            .map_err(|e| Error::Internal(format!("rooms serialisation failed: {e}")))?;
        std::fs::write(f, json + "\n").map_err(|e| Error::write(f, e))?;
        written.push(f.clone());
    }
    let overlay = door_overlay(&map, &rooms);
    let title = format!(
        "{} - rooms",
        oxcover::pipeline::short_name(&a.map.display().to_string())
    );
    let picture = scene(&map, &rooms, &overlay, title);
    for f in [a.svg.as_ref(), a.png.as_ref()].into_iter().flatten() {
        render_to_file(&picture, f)?;
        written.push(f.clone());
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "{}: {} rooms, {} other free regions, {} doors",
        a.map.display(),
        rooms.seeded,
        rooms.count() - rooms.seeded,
        rooms.doors.len()
    );
    let rows: Vec<(String, String)> = rep
        .rooms
        .iter()
        .filter(|r| r.seeded)
        .map(|r| {
            (
                format!("room {}", r.label),
                format!(
                    "{:.1} m² at ({:.2}, {:.2})",
                    r.area_m2, r.centroid[0], r.centroid[1]
                ),
            )
        })
        .collect();
    let _ = write!(out, "{}", table(&rows));
    for w in written {
        let _ = writeln!(out, "wrote {}", w.display());
    }
    Ok(())
}
