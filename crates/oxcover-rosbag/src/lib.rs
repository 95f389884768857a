//! ROS 2 bags for coverage planning.
//!
//! - **Reading maps** ([`read_map`], [`Bag`]): a rosbag2 bag is a folder with
//!   `metadata.yaml`, or one `.mcap` (storage `mcap`, chunks plain, zstd or
//!   lz4) or `.db3` (storage `sqlite3`) file. The map is one
//!   `nav_msgs/msg/OccupancyGrid` message, picked by topic (default: the
//!   bag's only OccupancyGrid topic) and position ([`MessageChoice`],
//!   default the last), and read by the contract's rules ([`grid`]). Only
//!   that message is read: an indexed MCAP by its index (one chunk), an
//!   sqlite3 file by one query. Every file is recognised by its first
//!   bytes before anything else is read.
//! - **Writing plans** ([`write_mcap`]): one MCAP file with `/map`,
//!   `/coverage_path` (`nav_msgs/msg/Path`, stamped by the time model),
//!   `/rooms` and `/coverage_targets` (`visualization_msgs/msg/MarkerArray`)
//!   and `/odom` (`nav_msgs/msg/Odometry`) for executed trajectories; CDR
//!   with `ros2msg` schemas and rosbag2's metadata, as `ros2 bag play` and
//!   Foxglove open it.
//!
//! The containers and encodings are well-kept crates' (`mcap`,
//! `cdr-encoding`, `rusqlite`); this crate holds the message types
//! ([`msgs`]), the choice of what to read, and the conversions.

pub mod bag;
pub mod cdr;
pub mod grid;
pub mod markers;
mod mcap_read;
pub mod msgs;
mod sqlite_read;
mod storage;
pub mod write;

pub use bag::{Bag, MessageChoice, TopicInfo, is_bag, read_map};
pub use write::{OdomSample, PlanBag, StampedPose, write_mcap};
