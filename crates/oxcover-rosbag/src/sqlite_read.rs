//! Reading one message out of a rosbag2 `sqlite3` storage file (`.db3`):
//! its `topics` table (id, name, type) and `messages` table (topic_id,
//! timestamp, data), queried for the one row asked for, so a bag of a
//! million messages is not loaded to read one. SQLite is `rusqlite`'s, with
//! the library built in (nothing to install).

use std::path::{Path, PathBuf};

use rusqlite::{Connection, OpenFlags, OptionalExtension as _};

use crate::storage::{TopicInfo, bad};
use oxcover_grid::Error;

/// How an SQLite 3 database begins.
pub(crate) const MAGIC: &[u8] = b"SQLite format 3\0";

/// An open rosbag2 sqlite3 file.
pub(crate) struct SqliteFile {
    path: PathBuf,
    db: Connection,
}

impl SqliteFile {
    /// Opens `path` read-only, after checking its first bytes are SQLite's.
    pub(crate) fn open(path: &Path) -> Result<Self, Error> {
        let head = crate::storage::head(path, MAGIC.len())?;
        if head != MAGIC {
            return Err(bad(
                path,
                "not an SQLite 3 database (a rosbag2 .db3 file begins with `SQLite format 3`)",
            ));
        }
        let db = Connection::open_with_flags(
            path,
            OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX,
        )
        .map_err(|e| bad(path, &format!("cannot open the SQLite database: {e}")))?;
        // Pages mapped rather than read one call at a time: finding one
        // topic's message walks many rows (rosbag2 indexes time, not topic).
        let _ = db.pragma_update(None, "mmap_size", 1i64 << 30);
        let me = Self {
            path: path.to_path_buf(),
            db,
        };
        // A database that is not a rosbag2 one says so here, not at a query.
        for table in ["topics", "messages"] {
            let found: Option<String> = me
                .db
                .query_row(
                    "SELECT name FROM sqlite_master WHERE type = 'table' AND name = ?1",
                    [table],
                    |row| row.get(0),
                )
                .optional()
                .map_err(|e| me.sql(&e))?;
            if found.is_none() {
                return Err(bad(
                    path,
                    &format!("an SQLite database without the rosbag2 table `{table}`"),
                ));
            }
        }
        Ok(me)
    }

    fn sql(&self, e: &rusqlite::Error) -> Error {
        bad(
            &self.path,
            &format!("not a readable rosbag2 sqlite3 file: {e}"),
        )
    }

    /// Every topic with its type and message count.
    pub(crate) fn topics(&self) -> Result<Vec<TopicInfo>, Error> {
        let mut stmt = self
            .db
            .prepare(
                "SELECT t.name, t.type, (SELECT COUNT(*) FROM messages m WHERE m.topic_id = t.id) \
                 FROM topics t ORDER BY t.name",
            )
            .map_err(|e| self.sql(&e))?;
        let rows = stmt
            .query_map([], |row| {
                Ok(TopicInfo {
                    name: row.get(0)?,
                    type_name: row.get(1)?,
                    count: row.get::<_, i64>(2)?.max(0) as u64,
                })
            })
            .map_err(|e| self.sql(&e))?;
        rows.collect::<Result<Vec<_>, _>>()
            .map_err(|e| self.sql(&e))
    }

    /// The data of every message of `topic`, by timestamp, then row id.
    pub(crate) fn all(&self, topic: &str) -> Result<Vec<Vec<u8>>, Error> {
        let mut stmt = self
            .db
            .prepare(
                "SELECT m.data FROM messages m JOIN topics t ON m.topic_id = t.id \
                 WHERE t.name = ?1 ORDER BY m.timestamp, m.id",
            )
            .map_err(|e| self.sql(&e))?;
        let rows = stmt
            .query_map([topic], |row| row.get(0))
            .map_err(|e| self.sql(&e))?;
        rows.collect::<Result<Vec<Vec<u8>>, _>>()
            .map_err(|e| self.sql(&e))
    }

    /// Topic names and types (no counts: counting scans every message).
    pub(crate) fn kinds(&self) -> Result<Vec<(String, String)>, Error> {
        let mut stmt = self
            .db
            .prepare("SELECT name, type FROM topics ORDER BY name")
            .map_err(|e| self.sql(&e))?;
        let rows = stmt
            .query_map([], |row| Ok((row.get(0)?, row.get(1)?)))
            .map_err(|e| self.sql(&e))?;
        rows.collect::<Result<Vec<(String, String)>, _>>()
            .map_err(|e| self.sql(&e))
    }

    /// Messages on `topic`.
    pub(crate) fn count(&self, topic: &str) -> Result<u64, Error> {
        self.db
            .query_row(
                "SELECT COUNT(*) FROM messages WHERE topic_id IN (SELECT id FROM topics WHERE name = ?1)",
                [topic],
                |row| row.get::<_, i64>(0),
            )
            .map(|n| n.max(0) as u64)
            .map_err(|e| self.sql(&e))
    }

    /// The first or last message of `topic` by timestamp (then row id),
    /// found through rosbag2's timestamp index; `None` where it has none.
    pub(crate) fn end(&self, topic: &str, last: bool) -> Result<Option<Vec<u8>>, Error> {
        let order = if last { "DESC" } else { "ASC" };
        self.db
            .query_row(
                &format!(
                    "SELECT data FROM messages NOT INDEXED WHERE topic_id IN (SELECT id FROM topics WHERE name = ?1) \
                     ORDER BY timestamp {order}, id {order} LIMIT 1"
                ),
                [topic],
                |row| row.get(0),
            )
            .optional()
            .map_err(|e| self.sql(&e))
    }

    /// The data of message `k` (from 0, by timestamp, then row id) of `topic`.
    pub(crate) fn nth(&self, topic: &str, k: u64) -> Result<Vec<u8>, Error> {
        let offset = i64::try_from(k).unwrap_or(i64::MAX);
        let data: Option<Vec<u8>> = self
            .db
            .query_row(
                "SELECT m.data FROM messages m JOIN topics t ON m.topic_id = t.id \
                 WHERE t.name = ?1 ORDER BY m.timestamp, m.id LIMIT 1 OFFSET ?2",
                rusqlite::params![topic, offset],
                |row| row.get(0),
            )
            .optional()
            .map_err(|e| self.sql(&e))?;
        data.ok_or_else(|| bad(&self.path, &format!("topic {topic} has no message {k}")))
    }
}
