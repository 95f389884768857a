//! Reading a map out of a bag against reading it from its PGM, in the same
//! run: the bundled `turtlebot3_world` map (384×384) as the one
//! OccupancyGrid of a bag that also holds 10,000 messages of two other
//! topics, in MCAP storage (zstd chunks of 768 KiB, as rosbag2 records them) and
//! in sqlite3 storage (rosbag2's tables). The bags are written to a scratch
//! folder first.
//!
//! Run: `cargo bench -p oxcover-rosbag --bench read`; `cargo xtask bench
//! --only bag_read` runs it and writes the figures into `docs/benchmarks.md`.

#![expect(
    missing_docs,
    reason = "criterion_group! generates an undocumented pub fn"
)]

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use oxcover_grid::io::{ReadOptions, Thresholds, read_map};
use oxcover_rosbag::msgs::{Time, types};
use oxcover_rosbag::{MessageChoice, cdr, grid};

#[path = "../tests/support/mod.rs"]
mod support;

use support::{Msg, write_db3, write_mcap};

const OTHER: usize = 10_000;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The messages: 10,000 on /scan and /odom (alternately, 256 bytes each,
/// every 10 ms) with the map at the middle.
fn messages(map: &[u8]) -> Vec<Msg> {
    let mut out = Vec::with_capacity(OTHER + 1);
    for i in 0..OTHER {
        let (topic, ty) = if i % 2 == 0 {
            ("/scan", "sensor_msgs/msg/LaserScan")
        } else {
            ("/odom", "nav_msgs/msg/Odometry")
        };
        let mut data = vec![0, 1, 0, 0];
        data.extend((0..252).map(|k| ((i + k) % 251) as u8));
        out.push((topic, ty, i as u64 * 10_000_000, data));
        if i == OTHER / 2 {
            out.push((
                "/map",
                types::OCCUPANCY_GRID,
                i as u64 * 10_000_000 + 1,
                map.to_vec(),
            ));
        }
    }
    out
}

fn bench(c: &mut Criterion) {
    let pgm = root().join("fixtures/maps/nav2/turtlebot3_world.pgm");
    let yaml = root().join("fixtures/maps/nav2/turtlebot3_world.yaml");
    let map = read_map(&yaml, &ReadOptions::default()).expect("map");
    let data = cdr::encode(&grid::to_msg(&map, Time::default())).expect("encode");
    let msgs = messages(&data);
    let dir = std::env::temp_dir().join(format!("oxcover-bench-bags-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let (mcap, db3) = (dir.join("bag.mcap"), dir.join("bag.db3"));
    // rosbag2's MCAP storage writes with libmcap's defaults: zstd chunks of
    // 768 KiB.
    let options = mcap::WriteOptions::new()
        .profile("ros2")
        .chunk_size(Some(768 * 1024));
    write_mcap(&mcap, &msgs, options);
    write_db3(&db3, &msgs);
    let mut g = c.benchmark_group("bag_read");
    g.sample_size(30).measurement_time(Duration::from_secs(4));
    g.bench_function("pgm", |b| {
        b.iter(|| read_map(black_box(&pgm), &ReadOptions::default()).expect("pgm"));
    });
    for (name, path) in [("mcap", &mcap), ("db3", &db3)] {
        g.bench_function(name, |b| {
            b.iter(|| {
                oxcover_rosbag::read_map(
                    black_box(path),
                    None,
                    MessageChoice::Last,
                    &Thresholds::default(),
                    1 << 28,
                )
                .expect("bag")
            });
        });
    }
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, bench);
criterion_main!(benches);
