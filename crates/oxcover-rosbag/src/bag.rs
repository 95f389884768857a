//! rosbag2 bags as the contract names them: a folder with `metadata.yaml`
//! (its `storage_identifier` and `relative_file_paths`), or one `.mcap`
//! (storage `mcap`) or `.db3` (storage `sqlite3`) file; topics listed with
//! their types and counts; one message picked by topic and position; the
//! map read from its `nav_msgs/msg/OccupancyGrid` message.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use oxcover_grid::Error;
use oxcover_grid::io::Thresholds;

use crate::mcap_read::{self, McapFile};
use crate::msgs::types;
use crate::sqlite_read::{self, SqliteFile};
pub use crate::storage::TopicInfo;
use crate::storage::{bad, head};

/// Which message of a topic to read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MessageChoice {
    /// The earliest (by log time).
    First,
    /// The latest: the map as the mapping run left it (the default).
    #[default]
    Last,
    /// The message at this position, from 0, in log-time order.
    Index(u64),
}

impl FromStr for MessageChoice {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "first" => Ok(Self::First),
            "last" => Ok(Self::Last),
            n => n
                .parse()
                .map(Self::Index)
                .map_err(|_| format!("`{s}`, expected first, last or a message number from 0")),
        }
    }
}

impl std::fmt::Display for MessageChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::First => f.write_str("first"),
            Self::Last => f.write_str("last"),
            Self::Index(k) => write!(f, "{k}"),
        }
    }
}

/// How a file of a bag is stored.
enum Storage {
    Mcap(McapFile),
    Sqlite(SqliteFile),
}

/// An open bag: its storage files in order.
pub struct Bag {
    path: PathBuf,
    files: Vec<Storage>,
}

/// Whether `path` is a bag: a folder holding `metadata.yaml`, a file named
/// `.mcap` or `.db3`, or a file beginning with MCAP's or SQLite's magic
/// (only those bytes are read).
#[must_use]
pub fn is_bag(path: &Path) -> bool {
    if path.is_dir() {
        return path.join("metadata.yaml").is_file();
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    if matches!(ext.as_str(), "mcap" | "db3") {
        return true;
    }
    head(path, 16)
        .is_ok_and(|h| h.starts_with(mcap_read::MAGIC) || h.starts_with(sqlite_read::MAGIC))
}

impl Bag {
    /// Opens the bag at `path`, checking each file's first bytes before
    /// reading on.
    ///
    /// # Errors
    /// One line naming the file: a folder without `metadata.yaml` or with
    /// an unknown storage, a file that is neither MCAP nor SQLite, a
    /// corrupted summary or database.
    pub fn open(path: &Path) -> Result<Self, Error> {
        let files = if path.is_dir() {
            let (storage, names) = read_metadata(path)?;
            names
                .iter()
                .map(|n| open_file(&path.join(n), Some(&storage)))
                .collect::<Result<Vec<_>, _>>()?
        } else {
            vec![open_file(path, None)?]
        };
        Ok(Self {
            path: path.to_path_buf(),
            files,
        })
    }

    /// Every topic, with its type and message count over all files, by name.
    ///
    /// # Errors
    /// A storage file that cannot be read.
    pub fn topics(&mut self) -> Result<Vec<TopicInfo>, Error> {
        let mut all: Vec<TopicInfo> = Vec::new();
        for file in &mut self.files {
            let topics = match file {
                Storage::Mcap(f) => f.topics()?,
                Storage::Sqlite(f) => f.topics()?,
            };
            for t in topics {
                match all.iter_mut().find(|a| a.name == t.name) {
                    Some(a) => a.count += t.count,
                    None => all.push(t),
                }
            }
        }
        all.sort_by(|a, b| a.name.cmp(&b.name));
        Ok(all)
    }

    /// The serialized (CDR) data of the message `choice` picks on `topic`.
    /// Files are taken in the metadata's order, as rosbag2 splits them.
    ///
    /// # Errors
    /// An unknown topic (listing the bag's), a position past the topic's
    /// last message, a storage file that cannot be read.
    pub fn message(&mut self, topic: &str, choice: MessageChoice) -> Result<Vec<u8>, Error> {
        if !self.kinds()?.iter().any(|(n, _)| n == topic) {
            let topics = self.topics()?;
            return Err(bad(
                &self.path,
                &format!("no topic {topic}; the bag has {}", list(&topics)),
            ));
        }
        let found = match choice {
            MessageChoice::First | MessageChoice::Last => {
                let last = choice == MessageChoice::Last;
                let mut found = None;
                let n = self.files.len();
                for i in 0..n {
                    let file = &mut self.files[if last { n - 1 - i } else { i }];
                    found = match file {
                        Storage::Mcap(f) => f.end(topic, last)?,
                        Storage::Sqlite(f) => f.end(topic, last)?,
                    };
                    if found.is_some() {
                        break;
                    }
                }
                found
            }
            MessageChoice::Index(k) => {
                let mut k = k;
                let mut found = None;
                for file in &mut self.files {
                    let count = match file {
                        Storage::Mcap(f) => f.count(topic)?,
                        Storage::Sqlite(f) => f.count(topic)?,
                    };
                    if k < count {
                        found = Some(match file {
                            Storage::Mcap(f) => f.nth(topic, k)?,
                            Storage::Sqlite(f) => f.nth(topic, k)?,
                        });
                        break;
                    }
                    k -= count;
                }
                found
            }
        };
        found.ok_or_else(|| {
            let count = self
                .topics()
                .ok()
                .and_then(|t| t.into_iter().find(|t| t.name == topic))
                .map_or(0, |t| t.count);
            let k = match choice {
                MessageChoice::Index(k) => k,
                MessageChoice::First | MessageChoice::Last => 0,
            };
            bad(
                &self.path,
                &format!("topic {topic} has {count} messages, so no message {k} (numbered from 0)"),
            )
        })
    }

    /// The serialized data of every message on `topic`, file by file, each
    /// file's in log-time order (for a trajectory; a map is read with
    /// [`Bag::message`], which reads one).
    ///
    /// # Errors
    /// A storage file that cannot be read.
    pub fn messages(&mut self, topic: &str) -> Result<Vec<Vec<u8>>, Error> {
        let mut out = Vec::new();
        for file in &mut self.files {
            out.extend(match file {
                Storage::Mcap(f) => f.all(topic)?,
                Storage::Sqlite(f) => f.all(topic)?,
            });
        }
        Ok(out)
    }

    /// Bytes read from the bag's MCAP files so far (what an indexed read
    /// spares shows here).
    #[must_use]
    pub fn mcap_bytes_read(&self) -> u64 {
        self.files
            .iter()
            .map(|f| match f {
                Storage::Mcap(m) => m.bytes_read,
                Storage::Sqlite(_) => 0,
            })
            .sum()
    }

    /// Every topic's name and type, without counting messages (counting
    /// an sqlite3 bag's messages scans it).
    fn kinds(&mut self) -> Result<Vec<(String, String)>, Error> {
        let mut all: Vec<(String, String)> = Vec::new();
        for file in &mut self.files {
            let kinds = match file {
                Storage::Mcap(f) => f
                    .topics()?
                    .into_iter()
                    .map(|t| (t.name, t.type_name))
                    .collect(),
                Storage::Sqlite(f) => f.kinds()?,
            };
            for k in kinds {
                if !all.iter().any(|a| a.0 == k.0) {
                    all.push(k);
                }
            }
        }
        all.sort();
        Ok(all)
    }

    /// The occupancy grid topic to read: `topic` where given (it must be
    /// an OccupancyGrid), else the bag's only OccupancyGrid topic.
    ///
    /// # Errors
    /// An unknown topic or one of another type, no OccupancyGrid topic, or
    /// several and none chosen (each listing the bag's topics).
    pub fn map_topic(&mut self, topic: Option<&str>) -> Result<String, Error> {
        let kinds = self.kinds()?;
        let is_grid = |ty: &str| ty == types::OCCUPANCY_GRID || ty == "nav_msgs/OccupancyGrid";
        if let Some(name) = topic {
            return match kinds.iter().find(|t| t.0 == name) {
                Some(t) if is_grid(&t.1) => Ok(t.0.clone()),
                Some(t) => Err(bad(
                    &self.path,
                    &format!(
                        "topic {name} is {}, expected a {}",
                        t.1,
                        types::OCCUPANCY_GRID
                    ),
                )),
                None => {
                    let topics = self.topics()?;
                    Err(bad(
                        &self.path,
                        &format!("no topic {name}; the bag has {}", list(&topics)),
                    ))
                }
            };
        }
        let grids: Vec<&str> = kinds
            .iter()
            .filter(|t| is_grid(&t.1))
            .map(|t| t.0.as_str())
            .collect();
        match grids.as_slice() {
            [one] => Ok((*one).to_string()),
            [] => {
                let topics = self.topics()?;
                Err(bad(
                    &self.path,
                    &format!(
                        "no {} topic; the bag has {}",
                        types::OCCUPANCY_GRID,
                        list(&topics)
                    ),
                ))
            }
            many => Err(bad(
                &self.path,
                &format!(
                    "{} {} topics ({}); pick one with --topic",
                    many.len(),
                    types::OCCUPANCY_GRID,
                    many.join(", ")
                ),
            )),
        }
    }
}

/// The bag's topics for a message: "/a (type, n messages), ...".
fn list(topics: &[TopicInfo]) -> String {
    if topics.is_empty() {
        return "no topics".into();
    }
    topics
        .iter()
        .map(|t| format!("{} ({}, {} messages)", t.name, t.type_name, t.count))
        .collect::<Vec<_>>()
        .join(", ")
}

fn open_file(path: &Path, storage: Option<&str>) -> Result<Storage, Error> {
    let h = head(path, 16)?;
    let storage = storage.map(str::to_string).unwrap_or_else(|| {
        if h.starts_with(sqlite_read::MAGIC)
            || path
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("db3"))
                && !h.starts_with(mcap_read::MAGIC)
        {
            "sqlite3".into()
        } else {
            "mcap".into()
        }
    });
    match storage.as_str() {
        "mcap" => McapFile::open(path).map(Storage::Mcap),
        "sqlite3" => SqliteFile::open(path).map(Storage::Sqlite),
        other => Err(bad(
            path,
            &format!("storage `{other}`, expected mcap or sqlite3"),
        )),
    }
}

/// A bag folder's storage identifier and file names, from `metadata.yaml`.
fn read_metadata(dir: &Path) -> Result<(String, Vec<String>), Error> {
    let path = dir.join("metadata.yaml");
    if !path.is_file() {
        return Err(bad(
            dir,
            "a folder without metadata.yaml, expected a rosbag2 bag folder",
        ));
    }
    let text = oxcover_grid::io::limited::read_limited_string(
        &path,
        oxcover_grid::io::limited::MAX_YAML_BYTES,
    )
    .map_err(|source| Error::Io {
        path: path.clone(),
        source,
    })?;
    let docs = yaml_rust2::YamlLoader::load_from_str(&text)
        .map_err(|e| bad(&path, &format!("not YAML: {e}")))?;
    let info = docs
        .first()
        .map(|d| &d["rosbag2_bagfile_information"])
        .filter(|i| !i.is_badvalue())
        .ok_or_else(|| {
            bad(
                &path,
                "no `rosbag2_bagfile_information`, expected rosbag2 metadata",
            )
        })?;
    let storage = info["storage_identifier"]
        .as_str()
        .ok_or_else(|| bad(&path, "no `storage_identifier` (mcap or sqlite3)"))?
        .to_string();
    let names: Vec<String> = info["relative_file_paths"]
        .as_vec()
        .map(|v| {
            v.iter()
                .filter_map(|n| n.as_str().map(str::to_string))
                .collect()
        })
        .unwrap_or_default();
    if names.is_empty() {
        return Err(bad(
            &path,
            "no `relative_file_paths`, expected the bag's storage files",
        ));
    }
    if let Some(n) = names
        .iter()
        .find(|n| Path::new(n).is_absolute() || n.contains(".."))
    {
        return Err(bad(
            &path,
            &format!("file `{n}` is not inside the bag folder"),
        ));
    }
    Ok((storage, names))
}

/// Reads the map of a bag: the OccupancyGrid message `choice` picks on
/// `topic` (default: the bag's only OccupancyGrid topic), classified with
/// `thresholds`' occupancy thresholds, at most `max_cells` cells.
///
/// # Errors
/// As [`Bag::open`], [`Bag::map_topic`] and [`Bag::message`]; a message
/// that does not decode as an OccupancyGrid; the grid checks of
/// [`crate::grid::from_msg`].
pub fn read_map(
    path: &Path,
    topic: Option<&str>,
    choice: MessageChoice,
    thresholds: &Thresholds,
    max_cells: usize,
) -> Result<oxcover_grid::OccupancyGrid, Error> {
    let mut bag = Bag::open(path)?;
    let topic = bag.map_topic(topic)?;
    let data = bag.message(&topic, choice)?;
    let msg: crate::msgs::OccupancyGrid = crate::cdr::decode(&data).map_err(|e| {
        bad(
            path,
            &format!("{topic}: not a nav_msgs/msg/OccupancyGrid: {e}"),
        )
    })?;
    crate::grid::from_msg(path, &msg, thresholds, max_cells)
}
