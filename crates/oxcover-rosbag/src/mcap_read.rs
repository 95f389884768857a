//! Reading one message out of an MCAP file without reading the rest.
//!
//! An indexed file (a summary with chunk indexes, as rosbag2 and the MCAP
//! libraries write by default) is read by its index: the footer and summary,
//! then the message indexes of the chunks that hold the topic, then the one
//! chunk that holds the message asked for (its CRC checked). A file without
//! an index is streamed record by record, keeping only the message asked for.
//! The container code is the `mcap` crate's; this module picks what to read.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};

use mcap::records::{self, Record, op};
use mcap::sans_io::linear_reader::{LinearReadEvent, LinearReaderOptions};
use mcap::sans_io::summary_reader::{SummaryReadEvent, SummaryReader, SummaryReaderOptions};

use crate::storage::{TopicInfo, bad};
use oxcover_grid::Error;

/// How an MCAP file begins (and ends).
pub(crate) const MAGIC: &[u8] = b"\x89MCAP0\r\n";
/// Largest record or chunk read (compressed or not): a map of the cell cap
/// (2^28 cells) with room to spare.
const RECORD_LIMIT: usize = 1 << 30;

/// An open MCAP file and, where it has one, its summary.
pub(crate) struct McapFile {
    path: PathBuf,
    file: File,
    summary: Option<mcap::Summary>,
    /// Bytes read from the file so far.
    pub(crate) bytes_read: u64,
}

/// Where one message of a topic is: its log time, its chunk (index into the
/// summary's chunk indexes) and its rank among the topic's messages in that
/// chunk, in file order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Entry {
    log_time: u64,
    chunk: usize,
    rank: usize,
}

impl McapFile {
    /// Opens `path`, checking its magic before anything else, and reads
    /// its summary where it has one.
    pub(crate) fn open(path: &Path) -> Result<Self, Error> {
        let io = |source| Error::Io {
            path: path.to_path_buf(),
            source,
        };
        let mut file = File::open(path).map_err(io)?;
        let len = file.metadata().map_err(io)?.len();
        let mut head = [0u8; 8];
        let n = read_up_to(&mut file, &mut head).map_err(io)?;
        if head[..n] != MAGIC[..n.min(MAGIC.len())] || n < MAGIC.len() {
            return Err(bad(
                path,
                "not an MCAP file (it does not begin with the MCAP magic bytes)",
            ));
        }
        let mut me = Self {
            path: path.to_path_buf(),
            file,
            summary: None,
            bytes_read: n as u64,
        };
        me.summary = me.read_summary(len).ok().flatten();
        Ok(me)
    }

    fn mcap_error(&self, e: &mcap::McapError) -> Error {
        bad(&self.path, &format!("not a readable MCAP file: {e}"))
    }

    fn read_summary(&mut self, len: u64) -> Result<Option<mcap::Summary>, Error> {
        let mut reader = SummaryReader::new_with_options(
            SummaryReaderOptions::default()
                .with_file_size(len)
                .with_record_length_limit(RECORD_LIMIT),
        );
        while let Some(event) = reader.next_event() {
            match event.map_err(|e| self.mcap_error(&e))? {
                SummaryReadEvent::ReadRequest(need) => {
                    let buf = reader.insert(need);
                    let n = self.file.read(buf).map_err(|e| self.io(e))?;
                    self.bytes_read += n as u64;
                    reader.notify_read(n);
                }
                SummaryReadEvent::SeekRequest(to) => {
                    let pos = self.file.seek(to).map_err(|e| self.io(e))?;
                    reader.notify_seeked(pos);
                }
            }
        }
        Ok(reader.finish())
    }

    fn io(&self, source: std::io::Error) -> Error {
        Error::Io {
            path: self.path.clone(),
            source,
        }
    }

    /// Whether the summary can find every message of every channel: chunk
    /// indexes with message indexes, and statistics to count with.
    fn indexed(&self) -> Option<&mcap::Summary> {
        let s = self.summary.as_ref()?;
        let stats = s.stats.as_ref()?;
        let indexed_messages: bool = !s.chunk_indexes.is_empty()
            && s.chunk_indexes
                .iter()
                .all(|c| !c.message_index_offsets.is_empty() || c.chunk_length == 0);
        (indexed_messages || stats.message_count == 0).then_some(s)
    }

    /// Every topic with its type and message count.
    pub(crate) fn topics(&mut self) -> Result<Vec<TopicInfo>, Error> {
        if let Some(summary) = self.indexed() {
            let counts = &summary
                .stats
                .as_ref()
                .map(|s| s.channel_message_counts.clone())
                .unwrap_or_default();
            let mut topics: BTreeMap<String, TopicInfo> = BTreeMap::new();
            let mut channels: Vec<_> = summary.channels.values().collect();
            channels.sort_by_key(|c| c.id);
            for c in channels {
                let t = topics.entry(c.topic.clone()).or_insert_with(|| TopicInfo {
                    name: c.topic.clone(),
                    type_name: c
                        .schema
                        .as_ref()
                        .map(|s| s.name.clone())
                        .unwrap_or_default(),
                    count: 0,
                });
                t.count += counts.get(&c.id).copied().unwrap_or(0);
            }
            return Ok(topics.into_values().collect());
        }
        let mut topics: BTreeMap<String, TopicInfo> = BTreeMap::new();
        self.stream(|channel, _, _| {
            let t = topics
                .entry(channel.topic.clone())
                .or_insert_with(|| TopicInfo {
                    name: channel.topic.clone(),
                    type_name: channel
                        .schema
                        .as_ref()
                        .map(|s| s.name.clone())
                        .unwrap_or_default(),
                    count: 0,
                });
            t.count += 1;
            false
        })?;
        Ok(topics.into_values().collect())
    }

    /// Messages on `topic`.
    pub(crate) fn count(&mut self, topic: &str) -> Result<u64, Error> {
        Ok(self
            .topics()?
            .into_iter()
            .find(|t| t.name == topic)
            .map_or(0, |t| t.count))
    }

    /// The first or last message of `topic`; `None` where it has none.
    pub(crate) fn end(&mut self, topic: &str, last: bool) -> Result<Option<Vec<u8>>, Error> {
        match self.count(topic)? {
            0 => Ok(None),
            n => self.nth(topic, if last { n - 1 } else { 0 }).map(Some),
        }
    }

    /// The data of message `k` (from 0, in log-time order; file order
    /// among equal times) of `topic`.
    pub(crate) fn nth(&mut self, topic: &str, k: u64) -> Result<Vec<u8>, Error> {
        if self.indexed().is_some() {
            return self.nth_indexed(topic, k);
        }
        // Unindexed: a first pass for the order, a second for the message.
        let mut times: Vec<(u64, u64)> = Vec::new();
        let mut seq = 0u64;
        self.stream(|channel, log_time, _| {
            if channel.topic == topic {
                times.push((log_time, seq));
                seq += 1;
            }
            false
        })?;
        times.sort_unstable();
        let Some(&(_, want)) = usize::try_from(k).ok().and_then(|k| times.get(k)) else {
            return Err(bad(
                &self.path,
                &format!("topic {topic} has no message {k}"),
            ));
        };
        let mut seq = 0u64;
        let mut found = None;
        self.stream(|channel, _, data| {
            if channel.topic == topic {
                // Read on to the end: each chunk's CRC is checked at its end.
                if seq == want {
                    found = Some(data.to_vec());
                }
                seq += 1;
            }
            false
        })?;
        found.ok_or_else(|| bad(&self.path, &format!("topic {topic} has no message {k}")))
    }

    /// The data of every message of `topic`, in log-time order (file
    /// order among equal times): the file streamed once.
    pub(crate) fn all(&mut self, topic: &str) -> Result<Vec<Vec<u8>>, Error> {
        let mut found: Vec<(u64, usize, Vec<u8>)> = Vec::new();
        self.stream(|channel, log_time, data| {
            if channel.topic == topic {
                found.push((log_time, found.len(), data.to_vec()));
            }
            false
        })?;
        found.sort_by_key(|m| (m.0, m.1));
        Ok(found.into_iter().map(|m| m.2).collect())
    }

    fn nth_indexed(&mut self, topic: &str, k: u64) -> Result<Vec<u8>, Error> {
        let summary = self
            .summary
            .take()
            .ok_or_else(|| bad(&self.path, "no summary"))?;
        let result = self.nth_in(&summary, topic, k);
        self.summary = Some(summary);
        result
    }

    fn nth_in(&mut self, summary: &mcap::Summary, topic: &str, k: u64) -> Result<Vec<u8>, Error> {
        let ids: Vec<u16> = summary
            .channels
            .values()
            .filter(|c| c.topic == topic)
            .map(|c| c.id)
            .collect();
        let mut entries: Vec<Entry> = Vec::new();
        for (chunk, index) in summary.chunk_indexes.iter().enumerate() {
            let mut in_chunk: Vec<(u64, u64)> = Vec::new();
            for id in &ids {
                if let Some(&offset) = index.message_index_offsets.get(id) {
                    let mi = self.message_index(offset)?;
                    in_chunk.extend(mi.records.iter().map(|r| (r.offset, r.log_time)));
                }
            }
            in_chunk.sort_unstable();
            entries.extend(
                in_chunk
                    .iter()
                    .enumerate()
                    .map(|(rank, &(_, log_time))| Entry {
                        log_time,
                        chunk,
                        rank,
                    }),
            );
        }
        entries.sort_unstable();
        let Some(entry) = usize::try_from(k)
            .ok()
            .and_then(|k| entries.get(k))
            .copied()
        else {
            return Err(bad(
                &self.path,
                &format!("topic {topic} has no message {k}"),
            ));
        };
        let index = &summary.chunk_indexes[entry.chunk];
        let bytes = self.read_at(index.chunk_start_offset, index.chunk_length)?;
        // The chunk record is read whole by the crate's linear reader, which
        // checks the CRC at its end and holds each record inside to the
        // chunk's own size (a corrupt length cannot ask for more).
        let limit = usize::try_from(index.uncompressed_size.max(index.chunk_length))
            .unwrap_or(usize::MAX)
            .min(RECORD_LIMIT);
        let mut reader = mcap::sans_io::LinearReader::new_with_options(
            LinearReaderOptions::default()
                .with_skip_start_magic(true)
                .with_skip_end_magic(true)
                .with_validate_chunk_crcs(true)
                .with_record_length_limit(limit),
        );
        let mut rest: &[u8] = &bytes;
        let (mut rank, mut found) = (0, None);
        while let Some(event) = reader.next_event() {
            match event.map_err(|e| self.mcap_error(&e))? {
                LinearReadEvent::ReadRequest(need) => {
                    let n = need.min(rest.len());
                    reader.insert(n).copy_from_slice(&rest[..n]);
                    reader.notify_read(n);
                    rest = &rest[n..];
                }
                LinearReadEvent::Record { data, opcode } => {
                    if let Ok(Record::Message { header, data }) = mcap::parse_record(opcode, data)
                        && ids.contains(&header.channel_id)
                    {
                        if rank == entry.rank {
                            found = Some(data.into_owned());
                        }
                        rank += 1;
                    }
                }
            }
        }
        if bytes.first() != Some(&op::CHUNK) {
            return Err(bad(&self.path, "a chunk index does not point to a chunk"));
        }
        found.ok_or_else(|| {
            bad(
                &self.path,
                &format!("message {k} of {topic} is missing from the chunk its index names"),
            )
        })
    }

    /// The message index record at `offset`.
    fn message_index(&mut self, offset: u64) -> Result<records::MessageIndex, Error> {
        let head = self.read_at(offset, 9)?;
        let len = u64::from_le_bytes(
            head[1..9]
                .try_into()
                .map_err(|_| bad(&self.path, "short record"))?,
        );
        if head[0] != op::MESSAGE_INDEX || len > RECORD_LIMIT as u64 {
            return Err(bad(
                &self.path,
                "a chunk index does not point to a message index",
            ));
        }
        let body = self.read_at(offset.saturating_add(9), len)?;
        match mcap::parse_record(op::MESSAGE_INDEX, &body) {
            Ok(Record::MessageIndex(mi)) => Ok(mi),
            Ok(_) => Err(bad(
                &self.path,
                "a chunk index does not point to a message index",
            )),
            Err(e) => Err(self.mcap_error(&e)),
        }
    }

    /// `len` bytes at `offset`, refused past the record limit or the end of the file.
    fn read_at(&mut self, offset: u64, len: u64) -> Result<Vec<u8>, Error> {
        if len > RECORD_LIMIT as u64 {
            return Err(self.mcap_error(&mcap::McapError::ChunkTooLarge(len)));
        }
        self.file
            .seek(SeekFrom::Start(offset))
            .map_err(|e| self.io(e))?;
        let mut buf = vec![0u8; len as usize];
        let n = read_up_to(&mut self.file, &mut buf).map_err(|e| self.io(e))?;
        self.bytes_read += n as u64;
        if n < buf.len() {
            return Err(bad(
                &self.path,
                "truncated: an index points past the end of the file",
            ));
        }
        Ok(buf)
    }

    /// Streams every message in file order to `visit` (channel, log time,
    /// data) until it returns true; chunk CRCs are checked.
    fn stream(
        &mut self,
        mut visit: impl FnMut(&mcap::Channel<'_>, u64, &[u8]) -> bool,
    ) -> Result<(), Error> {
        self.file.seek(SeekFrom::Start(0)).map_err(|e| self.io(e))?;
        let file = self.file.try_clone().map_err(|e| self.io(e))?;
        let options = LinearReaderOptions::default()
            .with_validate_chunk_crcs(true)
            .with_record_length_limit(RECORD_LIMIT);
        let reader = mcap::io::MessageReader::new_with_options(
            BufReader::new(Counted(file, &mut self.bytes_read)),
            options,
        );
        for message in reader {
            let message =
                message.map_err(|e| bad(&self.path, &format!("not a readable MCAP file: {e}")))?;
            if visit(&message.channel, message.log_time, &message.data) {
                break;
            }
        }
        Ok(())
    }
}

/// A reader that counts the bytes it reads.
struct Counted<'a>(File, &'a mut u64);

impl Read for Counted<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.0.read(buf)?;
        *self.1 += n as u64;
        Ok(n)
    }
}

/// Reads until `buf` is full or the file ends; the number of bytes read.
fn read_up_to(file: &mut File, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut n = 0;
    while n < buf.len() {
        match file.read(&mut buf[n..]) {
            Ok(0) => break,
            Ok(m) => n += m,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(n)
}
