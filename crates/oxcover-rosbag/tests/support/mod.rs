//! Bags for the tests and benches: MCAP files written with the `mcap`
//! crate and sqlite3 files with rosbag2's tables, from a list of messages.

use std::collections::BTreeMap;
use std::io::Cursor;
use std::path::Path;

use mcap::records::MessageHeader;
use oxcover_rosbag::msgs::schema_text;

/// One message: topic, type, log time (ns), data.
pub(crate) type Msg = (&'static str, &'static str, u64, Vec<u8>);

/// An MCAP file of `msgs` written with `options` (each type's schema
/// where this crate defines it, else a placeholder: those messages are
/// never decoded).
pub(crate) fn write_mcap(path: &Path, msgs: &[Msg], options: mcap::WriteOptions) {
    let mut w = options.create(Cursor::new(Vec::new())).expect("writer");
    let mut channels: BTreeMap<&str, u16> = BTreeMap::new();
    for (topic, ty, t, data) in msgs {
        let id = match channels.get(topic) {
            Some(&id) => id,
            None => {
                let schema = schema_text(ty).unwrap_or_else(|| "string data\n".into());
                let s = w
                    .add_schema(ty, "ros2msg", schema.as_bytes())
                    .expect("schema");
                let id = w
                    .add_channel(s, topic, "cdr", &BTreeMap::new())
                    .expect("channel");
                channels.insert(topic, id);
                id
            }
        };
        let header = MessageHeader {
            channel_id: id,
            sequence: 0,
            log_time: *t,
            publish_time: *t,
        };
        w.write_to_known_channel(&header, data).expect("message");
    }
    w.finish().expect("finish");
    std::fs::write(path, w.into_inner().into_inner()).expect("write");
}

/// An sqlite3 storage file of `msgs` with rosbag2's tables and index.
pub(crate) fn write_db3(path: &Path, msgs: &[Msg]) {
    let _ = std::fs::remove_file(path);
    let mut conn = rusqlite::Connection::open(path).expect("db");
    let db = conn.transaction().expect("transaction");
    db.execute_batch(
        "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, \
         serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL); \
         CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, \
         timestamp INTEGER NOT NULL, data BLOB NOT NULL); \
         CREATE INDEX timestamp_idx ON messages (timestamp ASC);",
    )
    .expect("schema");
    let mut ids: BTreeMap<&str, i64> = BTreeMap::new();
    for (topic, ty, t, data) in msgs {
        let n = ids.len() as i64 + 1;
        let id = *ids.entry(topic).or_insert_with(|| {
            db.execute(
                "INSERT INTO topics VALUES (?1, ?2, ?3, 'cdr', '')",
                rusqlite::params![n, topic, ty],
            )
            .expect("topic");
            n
        });
        db.execute(
            "INSERT INTO messages (topic_id, timestamp, data) VALUES (?1, ?2, ?3)",
            rusqlite::params![id, *t as i64, data],
        )
        .expect("message");
    }
    db.commit().expect("commit");
}
