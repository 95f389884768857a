//! `oxcover segment`: the rooms of a map and the doors between them, as JSON
//! and as a picture with one colour per room.

use std::io::Write as _;
use std::path::PathBuf;

use clap::ValueEnum;
use oxcover::render::render_bytes;
use oxcover::report::table;
use oxcover::rooms::{Method, SegmentOptions, report, rooms_overlay, scene, segment};
use oxcover::{Error, Result};

use super::args::{MCAP, MapArgs, PNG, SVG, asked, check_outputs, load};

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum MethodArg {
    /// Split where a wall has a gap: doors between wall ends, walls
    /// continued across a room's open side (the rooms people name).
    Doorways,
    /// Erode until the free space splits into room-sized pieces, grow them back.
    Morphological,
    /// Split at the narrow points of the distance transform's medial axis.
    Voronoi,
}

#[derive(Debug, clap::Args)]
pub(crate) struct SegmentArgs {
    /// Map: .yaml, .pgm, .png, .bmp, .map, or a rosbag2 bag (folder, .mcap, .db3).
    pub(crate) map: PathBuf,
    /// Segmentation method.
    #[arg(long, value_enum, default_value_t = MethodArg::Doorways)]
    pub(crate) method: MethodArg,
    #[command(flatten)]
    pub(crate) reading: MapArgs,
    /// Smallest room in m² (morphological: what erosion leaves of a room;
    /// doorways, voronoi: smaller regions join a neighbour).
    #[arg(
        long,
        value_name = "M2",
        default_value_t = 1.0,
        allow_negative_numbers = true
    )]
    pub(crate) min_area: f64,
    /// Largest room seed in m²; larger pieces are eroded further (morphological).
    #[arg(
        long,
        value_name = "M2",
        default_value_t = 47.0,
        allow_negative_numbers = true
    )]
    pub(crate) max_area: f64,
    /// Widest opening taken for a door, in metres (doorways, voronoi).
    #[arg(
        long,
        value_name = "M",
        default_value_t = 1.6,
        allow_negative_numbers = true
    )]
    pub(crate) door_width: f64,
    /// Rooms and doors to write: JSON, or a picture (.png or .svg).
    #[arg(long, value_name = "ROOMS.json|F.png")]
    pub(crate) out: Option<PathBuf>,
    /// SVG picture to write.
    #[arg(long, value_name = "F.svg")]
    pub(crate) svg: Option<PathBuf>,
    /// PNG picture to write.
    #[arg(long, value_name = "F.png")]
    pub(crate) png: Option<PathBuf>,
    /// ROS 2 bag to write (MCAP: /map and /rooms, outlines and labels).
    #[arg(long, value_name = "F.mcap")]
    pub(crate) bag: Option<PathBuf>,
}

pub(crate) fn cmd_segment(a: &SegmentArgs) -> Result<()> {
    let outs = asked([
        ("--out", a.out.as_deref(), &["json", "png", "svg"]),
        ("--svg", a.svg.as_deref(), SVG),
        ("--png", a.png.as_deref(), PNG),
        ("--bag", a.bag.as_deref(), MCAP),
    ]);
    check_outputs(&[&a.map], &outs)?;
    let out_ext = a.out.as_ref().map(|f| {
        f.extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .unwrap_or_default()
    });
    let map = load(&a.map, &a.reading)?;
    let options = SegmentOptions {
        method: match a.method {
            MethodArg::Doorways => Method::Doorways,
            MethodArg::Morphological => Method::Morphological,
            MethodArg::Voronoi => Method::Voronoi,
        },
        min_area_m2: a.min_area,
        max_area_m2: a.max_area,
        door_width_m: a.door_width,
    };
    let rooms = segment(&map, &options)?;
    let rep = report(&map, &rooms, &options);
    let mut files: Vec<(std::path::PathBuf, Vec<u8>)> = Vec::new();
    let json_out = a
        .out
        .as_ref()
        .filter(|_| out_ext.as_deref() == Some("json"));
    let picture_out = a
        .out
        .as_ref()
        .filter(|_| out_ext.as_deref() != Some("json"));
    if let Some(f) = json_out {
        let json = serde_json::to_string_pretty(&rep)
            .map_err(|e| Error::Internal(format!("rooms serialisation failed: {e}")))?;
        files.push((f.clone(), (json + "\n").into_bytes()));
    }
    let overlay = rooms_overlay(&map, &rooms);
    let title = format!(
        "{} - rooms",
        oxcover::pipeline::short_name(&a.map.display().to_string())
    );
    let picture = scene(&map, &rooms, &overlay, title);
    for f in [picture_out, a.svg.as_ref(), a.png.as_ref()]
        .into_iter()
        .flatten()
    {
        files.push((f.clone(), render_bytes(&picture, f)?));
    }
    if let Some(f) = &a.bag {
        let extras = oxcover::bag::BagExtras {
            rooms: Some(oxcover::bag::label_markers(&map, &rooms)),
            ..oxcover::bag::BagExtras::default()
        };
        let time = oxcover::planners::TimeModel::default();
        files.push((
            f.clone(),
            oxcover::bag::bag_bytes(&map, &[], &time, extras, f)?,
        ));
    }
    // All of them or none.
    let written = oxcover::output::write_files(files)?;
    let mut out = super::out::stdout();
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
                    "{:>7.1} m² at ({:>7.2}, {:>7.2})",
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
