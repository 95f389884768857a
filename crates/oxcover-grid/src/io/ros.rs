//! ROS map_server maps: the yaml metadata, the pixel rules, and a writer.
//!
//! Pixel value `v` (colour channels averaged, alpha ignored, scaled to 0..=255)
//! gives `p = (255 − v)/255`, or `v/255` when `negate` is set. Trinary: free if
//! `p < free_thresh`, occupied if `p > occupied_thresh`, unknown otherwise.
//! Deviations from map_server, all on purpose (see the contract): alpha is not
//! averaged in; in `scale` mode the in-between probabilities are *unknown*
//! (this crate keeps three states and never treats a doubtful cell as free);
//! in `raw` mode the value is the occupancy itself (0 free, 1..=100 occupied,
//! anything else unknown).

use std::path::{Path, PathBuf};

use yaml_rust2::{Yaml, YamlLoader};

use super::{ReadOptions, decode_image};
use crate::error::{Error, Result};
use crate::math::Point;
use crate::occupancy::{Occupancy, OccupancyGrid};

/// How pixel values map to occupancy (`mode` in the yaml).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Mode {
    /// Free / occupied / unknown by the two thresholds (map_server default).
    #[default]
    Trinary,
    /// Like trinary; values between the thresholds are unknown here.
    Scale,
    /// The pixel value is the occupancy value.
    Raw,
}

/// The pixel-classification part of a map yaml.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Thresholds {
    /// `negate`: dark means free instead of occupied.
    pub negate: bool,
    /// `occupied_thresh`; default 0.65 (map_server).
    pub occupied_thresh: f64,
    /// `free_thresh`; default 0.196 (map_server).
    pub free_thresh: f64,
    /// `mode`; default trinary.
    pub mode: Mode,
}

impl Default for Thresholds {
    /// The ROS defaults used for images without a yaml: negate 0, 0.65, 0.196, trinary.
    fn default() -> Self {
        Self {
            negate: false,
            occupied_thresh: 0.65,
            free_thresh: 0.196,
            mode: Mode::Trinary,
        }
    }
}

impl Thresholds {
    /// Classifies an averaged pixel value on the 0..=255 scale.
    #[must_use]
    pub fn classify(&self, v: f64) -> Occupancy {
        match self.mode {
            Mode::Raw => {
                let value = if self.negate { 255.0 - v } else { v };
                let value = value.floor();
                if value == 0.0 {
                    Occupancy::Free
                } else if (1.0..=100.0).contains(&value) {
                    Occupancy::Occupied
                } else {
                    Occupancy::Unknown
                }
            }
            Mode::Trinary | Mode::Scale => {
                let p = if self.negate {
                    v / 255.0
                } else {
                    (255.0 - v) / 255.0
                };
                if p > self.occupied_thresh {
                    Occupancy::Occupied
                } else if p < self.free_thresh {
                    Occupancy::Free
                } else {
                    Occupancy::Unknown
                }
            }
        }
    }
}

/// The content of a ROS map yaml.
#[derive(Clone, Debug, PartialEq)]
pub struct MapYaml {
    /// Image path, resolved against the yaml's directory.
    pub image: PathBuf,
    /// Metres per pixel.
    pub resolution: f64,
    /// Lower-left corner of the bottom-left pixel.
    pub origin: Point,
    /// Rotation of the image about `origin` (radians, the third `origin`
    /// value): map_server's pose of the lower-left pixel.
    pub yaw: f64,
    /// Pixel rules.
    pub thresholds: Thresholds,
}

/// Counts the aliases of a YAML event stream.
struct AliasCount(usize);

impl yaml_rust2::parser::EventReceiver for AliasCount {
    fn on_event(&mut self, ev: yaml_rust2::parser::Event) {
        if matches!(ev, yaml_rust2::parser::Event::Alias(_)) {
            self.0 += 1;
        }
    }
}

/// Largest resolution a map may have (m per pixel): beyond it metre
/// coordinates of cells lose their precision or overflow.
pub const MAX_RESOLUTION: f64 = 1000.0;
/// Largest origin coordinate (m): 10,000 km, beyond any floor.
pub const MAX_ORIGIN: f64 = 1e7;

/// Parses the text of a map yaml read from `path` (used for messages and to
/// resolve the image path).
///
/// Required fields, as in map_server: `image`, `resolution`, `origin`, `negate`,
/// `occupied_thresh`, `free_thresh`; `mode` is optional.
///
/// # Errors
/// [`Error::MissingField`] / [`Error::InvalidField`] naming the field, or
/// [`Error::Format`] for text that is not a YAML mapping.
pub fn parse_map_yaml(path: &Path, text: &str) -> Result<MapYaml> {
    let format = |message: String| Error::Format {
        path: path.to_path_buf(),
        message,
    };
    // A byte-order mark (editors on Windows write one) is not part of the YAML.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    // Aliases first, on the event stream (nothing is expanded there): a few
    // hundred bytes of nested aliases expand to gigabytes when loaded, and
    // the map_server format needs none.
    let mut aliases = AliasCount(0);
    yaml_rust2::parser::Parser::new_from_str(text)
        .load(&mut aliases, true)
        .map_err(|e| format(format!("invalid YAML: {e}")))?;
    if aliases.0 > 0 {
        return Err(format(format!(
            "YAML aliases (`*name`, {} of them) are not accepted in a map yaml: write the values out",
            aliases.0
        )));
    }
    let docs = YamlLoader::load_from_str(text).map_err(|e| format(format!("invalid YAML: {e}")))?;
    let doc = docs.first().ok_or_else(|| {
        format("empty file, expected a YAML mapping with image, resolution, origin, ...".into())
    })?;
    if doc.as_hash().is_none() {
        return Err(format(
            "expected a YAML mapping with image, resolution, origin, ...".into(),
        ));
    }
    let missing = |field: &'static str| Error::MissingField {
        path: path.to_path_buf(),
        field,
    };
    let invalid = |field: &'static str, value: &Yaml, expected: &'static str| Error::InvalidField {
        path: path.to_path_buf(),
        field,
        value: show(value),
        expected,
    };
    let field = |name: &'static str| -> Result<&Yaml> {
        match &doc[name] {
            Yaml::BadValue | Yaml::Null => Err(missing(name)),
            v => Ok(v),
        }
    };

    let image = field("image")?;
    let image = match image {
        Yaml::String(s) if !s.trim().is_empty() => s.trim().to_string(),
        v => return Err(invalid("image", v, "a file name")),
    };
    let resolution_v = field("resolution")?;
    let resolution = number(resolution_v)
        .filter(|r| r.is_finite() && *r > 0.0 && *r <= MAX_RESOLUTION)
        .ok_or_else(|| {
            invalid(
                "resolution",
                resolution_v,
                "a number > 0 and at most 1000 (metres per pixel)",
            )
        })?;
    let origin_v = field("origin")?;
    let origin = match origin_v.as_vec() {
        Some(v) if v.len() == 3 => {
            let nums: Option<Vec<f64>> = v.iter().map(number).collect();
            match nums {
                Some(n) if n.iter().all(|x| x.is_finite() && x.abs() <= MAX_ORIGIN) => n,
                _ => {
                    return Err(invalid(
                        "origin",
                        origin_v,
                        "[x, y, yaw] with three numbers of at most 10^7 (metres)",
                    ));
                }
            }
        }
        _ => {
            return Err(invalid(
                "origin",
                origin_v,
                "[x, y, yaw] with three finite numbers",
            ));
        }
    };
    let negate_v = field("negate")?;
    let negate = match negate_v {
        Yaml::Integer(0) | Yaml::Boolean(false) => false,
        Yaml::Integer(1) | Yaml::Boolean(true) => true,
        v => return Err(invalid("negate", v, "0 or 1")),
    };
    let thresh = |name: &'static str| -> Result<f64> {
        let v = field(name)?;
        number(v)
            .filter(|t| (0.0..=1.0).contains(t))
            .ok_or_else(|| invalid(name, v, "a number in [0, 1]"))
    };
    let occupied_thresh = thresh("occupied_thresh")?;
    let free_thresh = thresh("free_thresh")?;
    if free_thresh > occupied_thresh {
        return Err(invalid(
            "free_thresh",
            &doc["free_thresh"],
            "a value <= occupied_thresh",
        ));
    }
    let mode = match &doc["mode"] {
        Yaml::BadValue | Yaml::Null => Mode::Trinary,
        Yaml::String(s) => match s.trim() {
            "trinary" => Mode::Trinary,
            "scale" => Mode::Scale,
            "raw" => Mode::Raw,
            _ => return Err(invalid("mode", &doc["mode"], "trinary, scale or raw")),
        },
        v => return Err(invalid("mode", v, "trinary, scale or raw")),
    };

    let image_path = Path::new(&image);
    let image = if image_path.is_absolute() {
        image_path.to_path_buf()
    } else {
        path.parent().unwrap_or(Path::new("")).join(image_path)
    };
    Ok(MapYaml {
        image,
        resolution,
        origin: Point::new(origin[0], origin[1]),
        yaw: origin[2],
        thresholds: Thresholds {
            negate,
            occupied_thresh,
            free_thresh,
            mode,
        },
    })
}

/// Reads a ROS map yaml and its image.
///
/// # Errors
/// As [`parse_map_yaml`], plus the image's own errors; a missing image is
/// reported against the yaml's `image` field.
pub fn read_ros_yaml(path: &Path, options: &ReadOptions) -> Result<OccupancyGrid> {
    let bytes = super::limited::read_limited_after(
        path,
        super::limited::MAX_YAML_BYTES,
        super::limited::text_head,
    )
    .map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let text = String::from_utf8(bytes).map_err(|_| Error::Format {
        path: path.to_path_buf(),
        message: "not UTF-8 text, expected a ROS map yaml".into(),
    })?;
    let meta = parse_map_yaml(path, &text)?;
    let image_bytes = super::limited::read_limited_after(
        &meta.image,
        super::limited::MAX_MAP_BYTES,
        super::map_head,
    )
    .map_err(|e| Error::Format {
        path: path.to_path_buf(),
        message: format!(
            "field `image` names {}, which cannot be read: {e}",
            meta.image.display()
        ),
    })?;
    let cells = decode_image(
        &meta.image,
        &image_bytes,
        options.max_cells,
        &meta.thresholds,
    )?;
    Ok(OccupancyGrid::new(cells, meta.resolution, meta.origin).with_yaw(meta.yaw))
}

/// Builds a map from a yaml's text and its image's bytes already in memory
/// (e.g. embedded with `include_bytes!`); `yaml_path` is used in messages and
/// to name the image.
///
/// # Errors
/// As [`read_ros_yaml`].
pub fn read_ros_yaml_from_bytes(
    yaml_path: &Path,
    yaml_text: &str,
    image_bytes: &[u8],
    options: &ReadOptions,
) -> Result<OccupancyGrid> {
    let meta = parse_map_yaml(yaml_path, yaml_text)?;
    let cells = decode_image(
        &meta.image,
        image_bytes,
        options.max_cells,
        &meta.thresholds,
    )?;
    Ok(OccupancyGrid::new(cells, meta.resolution, meta.origin).with_yaw(meta.yaw))
}

/// The two files of `map` as a ROS map, as (path, contents), image first:
/// `<stem>.pgm` (P5, 8 bit) next to `yaml_path`, then the yaml, in the form
/// `map_saver` writes (free 254, occupied 0, unknown 205, trinary thresholds
/// 0.65 / 0.196). ROS tools and [`read_ros_yaml`] read it back to the same
/// cells.
///
/// # Errors
/// [`Error::Format`] when `yaml_path` has no file name.
pub fn ros_map_files(map: &OccupancyGrid, yaml_path: &Path) -> Result<[(PathBuf, Vec<u8>); 2]> {
    let stem = yaml_path
        .file_stem()
        .and_then(|s| s.to_str())
        .ok_or_else(|| Error::Format {
            path: yaml_path.to_path_buf(),
            message: "expected a yaml path with a file name".into(),
        })?;
    let pgm_name = format!("{stem}.pgm");
    let pgm_path = yaml_path.with_file_name(&pgm_name);
    let mut pgm = format!("P5\n# oxcover\n{} {}\n255\n", map.width(), map.height()).into_bytes();
    pgm.extend(map.cells().as_slice().iter().map(|o| match o {
        Occupancy::Free => 254u8,
        Occupancy::Occupied => 0,
        Occupancy::Unknown => 205,
    }));
    let o = map.frame().origin();
    let yaml = format!(
        "image: {pgm_name}\nmode: trinary\nresolution: {}\norigin: [{}, {}, {:?}]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
        map.resolution(),
        o.x,
        o.y,
        map.frame().yaw()
    );
    Ok([
        (pgm_path, pgm),
        (yaml_path.to_path_buf(), yaml.into_bytes()),
    ])
}

/// Writes `map` as a ROS map: the files of [`ros_map_files`], image first.
///
/// # Errors
/// As [`ros_map_files`]; [`Error::Write`] naming a file that could not be written.
pub fn write_ros_map(map: &OccupancyGrid, yaml_path: &Path) -> Result<()> {
    for (path, data) in ros_map_files(map, yaml_path)? {
        std::fs::write(&path, data).map_err(|source| Error::Write { path, source })?;
    }
    Ok(())
}

fn number(v: &Yaml) -> Option<f64> {
    match v {
        Yaml::Integer(i) => Some(*i as f64),
        Yaml::Real(_) => v.as_f64(),
        _ => None,
    }
}

fn show(v: &Yaml) -> String {
    match v {
        Yaml::Real(s) => s.clone(),
        Yaml::Integer(i) => i.to_string(),
        Yaml::String(s) => format!("`{s}`"),
        Yaml::Boolean(b) => b.to_string(),
        Yaml::Array(a) => format!("[{}]", a.iter().map(show).collect::<Vec<_>>().join(", ")),
        Yaml::Hash(_) => "a mapping".into(),
        Yaml::Null | Yaml::BadValue => "empty".into(),
        Yaml::Alias(_) => "an alias".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "image: m.pgm\nresolution: 0.05\norigin: [-1.0, 2, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";

    #[test]
    fn parses_a_map_server_yaml() {
        let m = parse_map_yaml(Path::new("dir/m.yaml"), GOOD).unwrap();
        assert_eq!(m.image, Path::new("dir/m.pgm"));
        assert_eq!(m.resolution, 0.05);
        assert_eq!((m.origin, m.yaw), (Point::new(-1.0, 2.0), 0.0));
        let turned = parse_map_yaml(Path::new("m.yaml"), &GOOD.replace("0.0]", "2.5]")).unwrap();
        assert_eq!(turned.yaw, 2.5);
        assert_eq!(m.thresholds, Thresholds::default());
        // Resolutions and origins that would overflow metre coordinates.
        let huge = GOOD.replace("resolution: 0.05", "resolution: 1e308");
        assert!(parse_map_yaml(Path::new("m.yaml"), &huge).is_err());
        let far = GOOD.replace("[-1.0, 2, 0.0]", "[-1e300, 2, 0.0]");
        assert!(parse_map_yaml(Path::new("m.yaml"), &far).is_err());
        // An alias bomb: refused before anything is expanded.
        let mut bomb = String::from("a: &a [x, x, x, x, x, x, x, x, x]\n");
        for k in 1..9 {
            bomb += &format!(
                "b{k}: &b{k} [{}]\n",
                vec![
                    if k == 1 {
                        "*a".to_string()
                    } else {
                        format!("*b{}", k - 1)
                    };
                    9
                ]
                .join(", ")
            );
        }
        bomb += GOOD;
        let e = parse_map_yaml(Path::new("m.yaml"), &bomb)
            .unwrap_err()
            .to_string();
        assert!(e.contains("aliases"), "{e}");
        // The same file saved with a byte-order mark.
        let bom = format!("\u{feff}{GOOD}");
        let b = parse_map_yaml(Path::new("dir/m.yaml"), &bom).unwrap();
        assert_eq!((b.image, b.resolution), (m.image, m.resolution));
    }

    #[test]
    fn classification_matches_map_server() {
        let t = Thresholds::default();
        assert_eq!(t.classify(254.0), Occupancy::Free);
        assert_eq!(t.classify(0.0), Occupancy::Occupied);
        assert_eq!(t.classify(205.0), Occupancy::Unknown);
        let n = Thresholds { negate: true, ..t };
        assert_eq!(n.classify(0.0), Occupancy::Free);
        assert_eq!(n.classify(255.0), Occupancy::Occupied);
        let raw = Thresholds {
            mode: Mode::Raw,
            ..t
        };
        assert_eq!(raw.classify(0.0), Occupancy::Free);
        assert_eq!(raw.classify(100.0), Occupancy::Occupied);
        assert_eq!(raw.classify(255.0), Occupancy::Unknown);
    }

    #[test]
    fn field_errors_name_the_field() {
        let cases = [
            (
                GOOD.replace("resolution: 0.05\n", ""),
                "missing field `resolution`",
            ),
            (GOOD.replace("0.0]", ".nan]"), "field `origin`"),
            (GOOD.replace("negate: 0", "negate: 2"), "field `negate`"),
            (GOOD.replace("0.196", "1.5"), "field `free_thresh`"),
            (GOOD.replace("0.05", "-0.05"), "field `resolution`"),
            (GOOD.replace("0.05", ".nan"), "field `resolution`"),
            (format!("{GOOD}mode: fancy\n"), "field `mode`"),
            ("[1, 2]".to_string(), "expected a YAML mapping"),
            ("image: [unclosed".to_string(), "invalid YAML"),
        ];
        for (text, want) in cases {
            let e = parse_map_yaml(Path::new("m.yaml"), &text)
                .unwrap_err()
                .to_string();
            assert!(e.contains(want), "{e:?} should contain {want:?}");
        }
    }
}
