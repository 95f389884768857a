//! The coverage-target options shared by `plan`, `eval`, `simulate` and
//! `render` (the contract's "Coverage targets").

use std::path::PathBuf;

use clap::ValueEnum;
use oxcover::Result;
use oxcover::grid::Point;
use oxcover::path::read_csv;
use oxcover::targets::{Kinds, RoomOrder, Spot, Targets, read_areas};

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum RoomOrderArg {
    Given,
    Fastest,
}

#[derive(Debug, clap::Args)]
pub(crate) struct TargetArgs {
    /// Cover only coverable cells whose centre lies inside these zones
    /// (GeoJSON Polygons/MultiPolygons, holes allowed, map-frame metres);
    /// the robot may drive outside them to get there.
    #[arg(long, value_name = "F.geojson")]
    pub(crate) zones: Option<PathBuf>,
    /// Never enter these areas (GeoJSON Polygons: every cell they meet is
    /// blocked) or cross these virtual walls (LineStrings: every cell they
    /// touch is blocked).
    #[arg(long, value_name = "F.geojson")]
    pub(crate) keep_out: Option<PathBuf>,
    /// Cover only the rooms with these labels (as `oxcover segment` numbers
    /// them, e.g. 3,5).
    #[arg(long, value_name = "A,B,...", value_delimiter = ',')]
    pub(crate) rooms_only: Option<Vec<u32>>,
    /// The order of the chosen rooms: as given, or the fastest.
    #[arg(long, value_enum, value_name = "given|fastest", default_value_t = RoomOrderArg::Fastest)]
    pub(crate) room_order: RoomOrderArg,
    /// Resume: the cells this path (CSV, x,y) covered are not required; the
    /// start defaults to its last point.
    #[arg(long, value_name = "PATH.csv")]
    pub(crate) done: Option<PathBuf>,
    /// Spot cleaning: cover the disc of radius R metres round X,Y.
    #[arg(long, value_name = "X,Y,R", value_parser = parse_spot, allow_hyphen_values = true)]
    pub(crate) spot: Option<Spot>,
}

impl TargetArgs {
    /// The files this option set reads (to check outputs against).
    pub(crate) fn inputs(&self) -> Vec<&std::path::Path> {
        [&self.zones, &self.keep_out, &self.done]
            .into_iter()
            .filter_map(|p| p.as_deref())
            .collect()
    }

    /// The targets the options describe, their files read.
    pub(crate) fn targets(&self) -> Result<Targets> {
        if self.room_order == RoomOrderArg::Given && self.rooms_only.is_none() {
            return Err(oxcover::Error::BadParameter {
                name: "--room-order",
                value: "given".into(),
                expected: "--rooms-only with the rooms in the order to cover them".into(),
            });
        }
        Ok(Targets {
            zones: self
                .zones
                .as_deref()
                .map(|p| read_areas(p, "--zones", Kinds::Polygons))
                .transpose()?,
            spot: self.spot,
            keep_out: self
                .keep_out
                .as_deref()
                .map(|p| read_areas(p, "--keep-out", Kinds::PolygonsAndLines))
                .transpose()?,
            rooms_only: self.rooms_only.clone(),
            room_order: match self.room_order {
                RoomOrderArg::Given => RoomOrder::Given,
                RoomOrderArg::Fastest => RoomOrder::Fastest,
            },
            done: self.done.as_deref().map(read_csv).transpose()?,
        })
    }
}

fn parse_spot(s: &str) -> std::result::Result<Spot, String> {
    let err = || format!("expected X,Y,R in metres (e.g. 1.5,-2,0.5), got `{s}`");
    let v: Vec<f64> = s
        .split(',')
        .map(|t| t.trim().parse::<f64>().map_err(|_| err()))
        .collect::<std::result::Result<_, _>>()?;
    let [x, y, r] = v[..] else {
        return Err(err());
    };
    if !(x.is_finite() && y.is_finite()) {
        return Err(format!("expected a finite centre X,Y, got `{s}`"));
    }
    if !(r.is_finite() && r > 0.0) {
        return Err(format!("expected a finite radius R above 0, got `{s}`"));
    }
    Ok(Spot {
        centre: Point::new(x, y),
        radius: r,
    })
}
