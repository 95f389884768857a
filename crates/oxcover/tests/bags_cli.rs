//! ROS 2 bags through the command line: a plan written with `--bag` holds
//! the map, the path stamped by the time model and the rooms, and reads
//! back; planning from that bag gives the yaml map's path byte for byte;
//! `info` lists a bag's topics; `simulate` and `segment` write theirs; and
//! every bad bag exits 2 with one line, writing nothing.

use std::collections::BTreeMap;
use std::io::Cursor;
use std::path::Path;
use std::process::Command;

use oxcover::rosbag::msgs::{self, Time, types};
use oxcover::rosbag::{Bag, MessageChoice, cdr, grid};

mod common;

use common::{bin, root, run, scratch};

fn turtlebot() -> String {
    root("fixtures/maps/nav2/turtlebot3_world.yaml")
}

/// A bag of one topic's messages (log time, data).
fn write_bag(path: &Path, topic: &str, ty: &str, messages: &[(u64, Vec<u8>)]) {
    let mut w = mcap::WriteOptions::new()
        .create(Cursor::new(Vec::new()))
        .expect("writer");
    let schema = msgs::schema_text(ty).unwrap_or_default();
    let s = w
        .add_schema(ty, "ros2msg", schema.as_bytes())
        .expect("schema");
    let c = w
        .add_channel(s, topic, "cdr", &BTreeMap::new())
        .expect("channel");
    for (t, data) in messages {
        let header = mcap::records::MessageHeader {
            channel_id: c,
            sequence: 0,
            log_time: *t,
            publish_time: *t,
        };
        w.write_to_known_channel(&header, data).expect("message");
    }
    w.finish().expect("finish");
    std::fs::write(path, w.into_inner().into_inner()).expect("write bag");
}

#[test]
fn a_plan_bag_reads_back_and_plans_to_the_same_path() {
    let d = scratch("bag-plan");
    let (csv, bag) = (d.join("p.csv"), d.join("plan.mcap"));
    let (stdout, _) = run(&[
        "plan",
        &turtlebot(),
        "--planner",
        "lanes",
        "--out",
        &csv.display().to_string(),
        "--bag",
        &bag.display().to_string(),
    ]);
    assert!(
        stdout.contains("wrote ") && stdout.contains("plan.mcap"),
        "{stdout}"
    );
    let mut b = Bag::open(&bag).expect("open");
    let topics: Vec<(String, String, u64)> = b
        .topics()
        .expect("topics")
        .into_iter()
        .map(|t| (t.name, t.type_name, t.count))
        .collect();
    assert_eq!(
        topics,
        [
            ("/coverage_path".into(), types::PATH.into(), 1),
            ("/map".into(), types::OCCUPANCY_GRID.into(), 1),
            ("/rooms".into(), types::MARKER_ARRAY.into(), 1),
        ]
    );
    // The path: the CSV's points, stamps from 0 never decreasing.
    let path: msgs::Path = cdr::decode(
        &b.message("/coverage_path", MessageChoice::Last)
            .expect("path"),
    )
    .expect("decode");
    let points = oxcover::read_csv(&csv).expect("csv");
    assert_eq!(path.poses.len(), points.len());
    for (pose, p) in path.poses.iter().zip(&points) {
        assert_eq!((pose.pose.position.x, pose.pose.position.y), (p.x, p.y));
    }
    let stamps: Vec<u64> = path.poses.iter().map(|p| p.header.stamp.nanos()).collect();
    assert_eq!(stamps[0], 0);
    assert!(stamps.windows(2).all(|w| w[1] >= w[0]));
    // The map: the yaml's cells.
    let grid_msg: msgs::OccupancyGrid =
        cdr::decode(&b.message("/map", MessageChoice::Last).expect("map")).expect("decode");
    let yaml = oxcover::pipeline::load_map(Path::new(&turtlebot()), None).expect("yaml");
    assert_eq!(grid_msg, grid::to_msg(&yaml, Time::default()));
    // Planning from the bag: the same path, byte for byte.
    let again = d.join("again.csv");
    run(&[
        "plan",
        &bag.display().to_string(),
        "--planner",
        "lanes",
        "--out",
        &again.display().to_string(),
    ]);
    assert_eq!(
        std::fs::read(&csv).expect("csv"),
        std::fs::read(&again).expect("again")
    );
    let (info, _) = run(&["info", &bag.display().to_string()]);
    assert!(
        info.contains("3 topics") && info.contains("/coverage_path  nav_msgs/msg/Path"),
        "{info}"
    );
    assert!(info.contains("384x384"), "{info}");
}

#[test]
fn simulate_and_segment_write_their_bags() {
    let d = scratch("bag-sim");
    let (sim, seg) = (d.join("sim.mcap"), d.join("seg.mcap"));
    let map = root("fixtures/maps/lee2011/living.yaml");
    run(&[
        "simulate",
        &map,
        "--planner",
        "lanes",
        "--bag",
        &sim.display().to_string(),
    ]);
    let mut b = Bag::open(&sim).expect("open");
    let odom = b
        .topics()
        .expect("topics")
        .into_iter()
        .find(|t| t.name == "/odom")
        .expect("odom");
    assert_eq!(odom.type_name, types::ODOMETRY);
    assert!(odom.count > 100, "{odom:?}");
    let last: msgs::Odometry =
        cdr::decode(&b.message("/odom", MessageChoice::Last).expect("odom")).expect("decode");
    let first: msgs::Odometry =
        cdr::decode(&b.message("/odom", MessageChoice::First).expect("odom")).expect("decode");
    assert!(last.header.stamp.nanos() > first.header.stamp.nanos());
    run(&["segment", &map, "--bag", &seg.display().to_string()]);
    let mut b = Bag::open(&seg).expect("open");
    let rooms: msgs::MarkerArray =
        cdr::decode(&b.message("/rooms", MessageChoice::Last).expect("rooms")).expect("decode");
    assert!(
        rooms
            .markers
            .iter()
            .any(|m| m.kind == msgs::Marker::LINE_LIST)
    );
    assert!(rooms.markers.iter().any(|m| m.text == "1"));
}

#[test]
fn bad_bags_exit_2_with_one_line_and_write_nothing() {
    let d = scratch("bag-bad");
    let good = d.join("good.mcap");
    run(&[
        "plan",
        &turtlebot(),
        "--planner",
        "lanes",
        "--bag",
        &good.display().to_string(),
    ]);
    let bytes = std::fs::read(&good).expect("good");
    let file = |name: &str, contents: &[u8]| -> String {
        let p = d.join(name);
        std::fs::write(&p, contents).expect("write");
        p.display().to_string()
    };
    let magic = file(
        "magic.mcap",
        &[b"\x89MCAQ".as_slice(), &bytes[5..]].concat(),
    );
    let truncated = file("truncated.mcap", &bytes[..bytes.len() * 2 / 3]);
    let mut flipped = bytes.clone();
    let zstd = bytes
        .windows(8)
        .position(|w| w == b"\x04\x00\x00\x00zstd")
        .expect("a zstd chunk");
    flipped[zstd + 40] ^= 0xFF;
    let flipped = file("flipped.mcap", &flipped);
    let mut unsupported = bytes.clone();
    let mut at = 0;
    while let Some(p) = unsupported[at..]
        .windows(8)
        .position(|w| w == b"\x04\x00\x00\x00zstd")
    {
        unsupported[at + p + 4] = b'q';
        at += p + 8;
    }
    let unsupported = file("qstd.mcap", &unsupported);
    let chatter = d.join("chatter.mcap");
    write_bag(
        &chatter,
        "/chatter",
        "std_msgs/msg/String",
        &[(0, vec![0, 1, 0, 0, 1, 0, 0, 0, 0])],
    );
    let map = oxcover::pipeline::load_map(Path::new(&turtlebot()), None).expect("map");
    let grid_bag = |name: &str, edit: &dyn Fn(&mut msgs::OccupancyGrid)| -> String {
        let mut m = grid::to_msg(&map, Time::default());
        edit(&mut m);
        let p = d.join(name);
        write_bag(
            &p,
            "/map",
            types::OCCUPANCY_GRID,
            &[(0, cdr::encode(&m).expect("encode"))],
        );
        p.display().to_string()
    };
    let short = grid_bag("short.mcap", &|m| {
        m.data.pop();
    });
    let zero = grid_bag("zero.mcap", &|m| m.info.resolution = 0.0);
    let nan = grid_bag("nan.mcap", &|m| m.info.resolution = f32::NAN);
    let good_s = good.display().to_string();
    let chatter_s = chatter.display().to_string();
    let yaml = turtlebot();
    let out = d.join("out.csv");
    let out_s = out.display().to_string();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec![&magic], "not an MCAP file"),
        (vec![&truncated], "not a readable MCAP file"),
        (vec![&flipped], "flipped.mcap"),
        (vec![&unsupported], "Unsupported compression format `qstd`"),
        (
            vec![&chatter_s],
            "no nav_msgs/msg/OccupancyGrid topic; the bag has /chatter",
        ),
        (
            vec![&good_s, "--topic", "/scan"],
            "no topic /scan; the bag has /coverage_path",
        ),
        (
            vec![&good_s, "--topic", "/coverage_path"],
            "is nav_msgs/msg/Path, expected a nav_msgs/msg/OccupancyGrid",
        ),
        (
            vec![&good_s, "--message", "1"],
            "topic /map has 1 messages, so no message 1",
        ),
        (
            vec![&good_s, "--message", "latest"],
            "expected first, last or a message number from 0",
        ),
        (vec![&good_s, "--negate"], "is a rosbag2 bag"),
        (vec![&short, "--message", "first"], "needs 147456 values"),
        (vec![&zero], "info.resolution"),
        (vec![&nan], "info.resolution"),
        (vec![&yaml, "--topic", "/map"], "--topic"),
    ];
    for (args, want) in cases {
        let _ = std::fs::remove_file(&out);
        let mut all = vec!["plan"];
        all.extend(&args[..1]);
        all.extend(["--planner", "lanes", "--out", &out_s]);
        all.extend(&args[1..]);
        let o = Command::new(bin()).args(&all).output().expect("run");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {err}");
        assert!(
            err.contains(want) && err.trim_end().lines().count() == 1,
            "{all:?}: {err}"
        );
        assert!(!out.exists(), "{all:?} wrote its output");
    }
    // --bag: named .mcap, and never the input bag itself.
    for (bag, want) in [("plan.bag", "--bag"), (good_s.as_str(), "good.mcap")] {
        let o = Command::new(bin())
            .args(["plan", &good_s, "--planner", "lanes", "--bag", bag])
            .output()
            .expect("run");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{bag}: {err}");
        assert!(err.contains(want), "{bag}: {err}");
    }
    assert_eq!(
        std::fs::read(&good).expect("good"),
        bytes,
        "the input bag is untouched"
    );
}
