//! Reading maps out of bags of every storage and layout: the message asked
//! for (first, last, N; across split files), only its chunk read from an
//! indexed MCAP, the same answer from an unindexed one and from sqlite3,
//! and one clear error for every kind of bad bag.

use std::path::{Path, PathBuf};

use oxcover_grid::io::{Thresholds, parse_ascii};
use oxcover_grid::{Occupancy, OccupancyGrid};
use oxcover_rosbag::msgs::{Time, types};
use oxcover_rosbag::{Bag, MessageChoice, cdr, grid, read_map};

mod support;

use support::{Msg, write_db3, write_mcap};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("oxcover-rosbag-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// A 3x2 map whose top-left cell is `first` (so maps can be told apart).
fn map(first: char) -> OccupancyGrid {
    let text = format!("{first}..\n.##\n");
    let cells = parse_ascii(&text).expect("ascii").0.cells().clone();
    OccupancyGrid::new(cells, 0.05, oxcover_grid::Point::new(-1.0, 2.0))
}

fn map_data(first: char) -> Vec<u8> {
    cdr::encode(&grid::to_msg(&map(first), Time::default())).expect("encode")
}

/// The messages of a bag: `chatter` small messages on `/chatter`, and maps
/// on `/map` at 1 s (`#` first), 2 s (`.` first) and 3 s (`?` first), the
/// last written first (log-time order is not file order).
fn messages(chatter: u64) -> Vec<Msg> {
    let mut out: Vec<Msg> = Vec::new();
    out.push(("/map", types::OCCUPANCY_GRID, 3_000_000_000, map_data('?')));
    for i in 0..chatter {
        out.push((
            "/chatter",
            "std_msgs/msg/String",
            i * 100_000,
            vec![0, 1, 0, 0, 6, 0, 0, 0, b'h', b'e', b'l', b'l', b'o', 0],
        ));
        if i == chatter / 2 {
            out.push(("/map", types::OCCUPANCY_GRID, 1_000_000_000, map_data('#')));
        }
    }
    out.push(("/map", types::OCCUPANCY_GRID, 2_000_000_000, map_data('.')));
    out
}

/// The error of reading the map of the bag at `path`, which must fail.
fn map_error(path: &Path) -> String {
    read_map(
        path,
        None,
        MessageChoice::Last,
        &Thresholds::default(),
        1 << 20,
    )
    .expect_err("a bad bag")
    .to_string()
}

/// A bag holding one message, `data`, on `/map`.
fn one_map_bag(path: &Path, data: Vec<u8>) {
    write_mcap(
        path,
        &[("/map", types::OCCUPANCY_GRID, 0, data)],
        mcap::WriteOptions::new(),
    );
}

fn first_cell(path: &Path, choice: MessageChoice) -> Occupancy {
    let m = read_map(path, None, choice, &Thresholds::default(), 1 << 20).expect("map");
    m.cells()[oxcover_grid::Cell::new(0, 0)]
}

fn check_choices(path: &Path) {
    assert_eq!(
        first_cell(path, MessageChoice::First),
        Occupancy::Occupied,
        "{}",
        path.display()
    );
    assert_eq!(
        first_cell(path, MessageChoice::Index(1)),
        Occupancy::Free,
        "{}",
        path.display()
    );
    assert_eq!(first_cell(path, MessageChoice::Last), Occupancy::Unknown);
    let e = read_map(
        path,
        None,
        MessageChoice::Index(3),
        &Thresholds::default(),
        1 << 20,
    )
    .expect_err("no fourth map")
    .to_string();
    assert!(
        e.contains("topic /map has 3 messages, so no message 3"),
        "{e}"
    );
}

#[test]
fn every_storage_gives_the_map_asked_for() {
    let dir = scratch("choices");
    let msgs = messages(2_000);
    let indexed = dir.join("indexed.mcap");
    write_mcap(
        &indexed,
        &msgs,
        mcap::WriteOptions::new().chunk_size(Some(4096)),
    );
    check_choices(&indexed);
    // Without summary or chunks: streamed.
    let plain = dir.join("plain.mcap");
    write_mcap(
        &plain,
        &msgs,
        mcap::WriteOptions::new()
            .use_chunks(false)
            .emit_summary_records(false),
    );
    check_choices(&plain);
    let lz4 = dir.join("lz4.mcap");
    write_mcap(
        &lz4,
        &msgs,
        mcap::WriteOptions::new().compression(Some(mcap::Compression::Lz4)),
    );
    check_choices(&lz4);
    let db3 = dir.join("bag.db3");
    write_db3(&db3, &msgs);
    check_choices(&db3);
    // A folder split in two files, as rosbag2 splits by time: the chatter
    // and the 1 s map in the first, the 2 s and 3 s maps in the second.
    let folder = dir.join("split");
    std::fs::create_dir_all(&folder).expect("folder");
    let (later, earlier): (Vec<Msg>, Vec<Msg>) = msgs
        .iter()
        .cloned()
        .partition(|m| m.0 == "/map" && m.2 >= 2_000_000_000);
    write_mcap(
        &folder.join("split_0.mcap"),
        &earlier,
        mcap::WriteOptions::new(),
    );
    write_mcap(
        &folder.join("split_1.mcap"),
        &later,
        mcap::WriteOptions::new(),
    );
    std::fs::write(
        folder.join("metadata.yaml"),
        "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n  relative_file_paths:\n    - split_0.mcap\n    - split_1.mcap\n",
    )
    .expect("metadata");
    check_choices(&folder);
    let topics = Bag::open(&folder).expect("open").topics().expect("topics");
    assert_eq!(
        topics
            .iter()
            .map(|t| (t.name.as_str(), t.count))
            .collect::<Vec<_>>(),
        [("/chatter", 2_000), ("/map", 3)]
    );
}

#[test]
fn a_bag_of_a_million_messages_is_read_by_its_index_not_whole() {
    let dir = scratch("index");
    let path = dir.join("big.mcap");
    // rosbag2's chunks: libmcap's default of 768 KiB.
    write_mcap(
        &path,
        &messages(1_000_000),
        mcap::WriteOptions::new().chunk_size(Some(768 << 10)),
    );
    let size = std::fs::metadata(&path).expect("size").len();
    let mut bag = Bag::open(&path).expect("open");
    let topic = bag.map_topic(None).expect("topic");
    for (choice, first) in [(MessageChoice::Last, '?'), (MessageChoice::First, '#')] {
        let data = bag.message(&topic, choice).expect("message");
        assert_eq!(data, map_data(first));
    }
    // Summary, message indexes and two chunks: well under a tenth of the file.
    let read = bag.mcap_bytes_read();
    assert!(read * 10 < size, "read {read} of {size} bytes");
}

#[test]
fn bad_bags_are_one_clear_line() {
    let dir = scratch("bad");
    let good = dir.join("good.mcap");
    write_mcap(
        &good,
        &messages(50),
        mcap::WriteOptions::new().compression(Some(mcap::Compression::Lz4)),
    );
    let bytes = std::fs::read(&good).expect("read");
    let read = |name: &str, contents: &[u8], topic: Option<&str>| -> String {
        let p = dir.join(name);
        std::fs::write(&p, contents).expect("write");
        let e = read_map(
            &p,
            topic,
            MessageChoice::Last,
            &Thresholds::default(),
            1 << 20,
        )
        .expect_err(name)
        .to_string();
        assert!(!e.contains('\n') && e.contains(name), "{name}: {e}");
        e
    };
    let mut magic = bytes.clone();
    magic[1] = b'X';
    assert!(read("magic.mcap", &magic, None).contains("not an MCAP file"));
    assert!(read("empty.mcap", b"", None).contains("not an MCAP file"));
    assert!(
        read("truncated.mcap", &bytes[..bytes.len() / 2], None)
            .contains("not a readable MCAP file")
    );
    // A byte of the chunk's compressed data flipped: lz4 still decodes, the CRC does not match.
    let chunk = bytes
        .windows(7)
        .position(|w| w == b"\x03\x00\x00\x00lz4")
        .expect("chunk")
        + 40;
    let mut crc = bytes.clone();
    crc[chunk] ^= 0x55;
    let e = read("crc.mcap", &crc, None);
    assert!(
        e.contains("CRC") || e.contains("decompress") || e.contains("readable"),
        "{e}"
    );
    let unsupported: Vec<u8> = {
        let mut b = bytes.clone();
        let mut i = 0;
        while let Some(p) = b[i..].windows(7).position(|w| w == b"\x03\x00\x00\x00lz4") {
            b[i + p + 4] = b'x';
            i += p + 7;
        }
        b
    };
    assert!(read("xz4.mcap", &unsupported, None).contains("xz4"));
    // Uncompressed, a flipped byte of the map is caught by the chunk's CRC alone.
    let plain = dir.join("plain.mcap");
    write_mcap(
        &plain,
        &messages(50),
        mcap::WriteOptions::new().compression(None),
    );
    let mut flipped = std::fs::read(&plain).expect("plain");
    // The last map's cells: 0 100 100 -1 0 0 (its unknown cell flipped to -2).
    let at = flipped
        .windows(4)
        .position(|w| w == [0, 100, 100, 0xff])
        .expect("the last map")
        + 3;
    flipped[at] ^= 0x01;
    assert!(read("flipped.mcap", &flipped, None).contains("Chunk CRC failed"));
    assert!(
        read("topic.mcap", &bytes, Some("/nothing"))
            .contains("no topic /nothing; the bag has /chatter")
    );
    assert!(
        read("type.mcap", &bytes, Some("/chatter"))
            .contains("is std_msgs/msg/String, expected a nav_msgs/msg/OccupancyGrid")
    );
    assert!(read("db.db3", b"SQLite format 3\0 and then nonsense", None).contains("db.db3"));
    assert!(read("text.db3", b"hello", None).contains("not an SQLite 3 database"));
    // No map topic; two map topics.
    let chatter: Vec<Msg> = messages(5)
        .into_iter()
        .filter(|m| m.0 == "/chatter")
        .collect();
    let p = dir.join("nomap.mcap");
    write_mcap(&p, &chatter, mcap::WriteOptions::new());
    let e = map_error(&p);
    assert!(e.contains("no nav_msgs/msg/OccupancyGrid topic; the bag has /chatter (std_msgs/msg/String, 5 messages)"), "{e}");
    let mut two = messages(5);
    two.push(("/map2", types::OCCUPANCY_GRID, 5, map_data('.')));
    let p = dir.join("two.mcap");
    write_mcap(&p, &two, mcap::WriteOptions::new());
    let e = map_error(&p);
    assert!(
        e.contains("2 nav_msgs/msg/OccupancyGrid topics (/map, /map2); pick one with --topic"),
        "{e}"
    );
    // A grid whose data does not fill width x height; a NaN resolution.
    let mut msg = grid::to_msg(&map('.'), Time::default());
    msg.data.pop();
    let p = dir.join("short.mcap");
    one_map_bag(&p, cdr::encode(&msg).expect("e"));
    let e = map_error(&p);
    assert!(e.contains("header says 3x2, which needs 6 values"), "{e}");
    let mut msg = grid::to_msg(&map('.'), Time::default());
    msg.info.resolution = f32::NAN;
    let p = dir.join("nan.mcap");
    one_map_bag(&p, cdr::encode(&msg).expect("e"));
    let e = map_error(&p);
    assert!(e.contains("info.resolution") && e.contains("NaN"), "{e}");
    // A message that is not an OccupancyGrid at all.
    let p = dir.join("garbage.mcap");
    one_map_bag(&p, vec![0, 1, 0, 0, 1, 2]);
    let e = map_error(&p);
    assert!(e.contains("/map: not a nav_msgs/msg/OccupancyGrid"), "{e}");
    // A folder without metadata, and metadata naming a file outside it.
    let folder = dir.join("folder");
    std::fs::create_dir_all(&folder).expect("folder");
    assert!(!oxcover_rosbag::is_bag(&folder));
    std::fs::write(folder.join("metadata.yaml"), "rosbag2_bagfile_information:\n  storage_identifier: mcap\n  relative_file_paths: [../good.mcap]\n").expect("yaml");
    let e = read_map(
        &folder,
        None,
        MessageChoice::Last,
        &Thresholds::default(),
        1 << 20,
    )
    .expect_err("outside")
    .to_string();
    assert!(e.contains("is not inside the bag folder"), "{e}");
}
