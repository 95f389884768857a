//! Room segmentation on real maps (the bundled fixtures): plausible room
//! counts, every free cell in exactly one room, every door cell touching the
//! other room of its door.

use std::path::{Path, PathBuf};

use oxcover_decomp::{RoomParams, Rooms, morphological};
use oxcover_grid::io::{ReadOptions, read_map};
use oxcover_grid::{Dir4, Grid};

fn fixture(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/maps")
        .join(rel)
}

fn check(free: &Grid<bool>, r: &Rooms) {
    for c in free.cells() {
        assert_eq!(free[c], r.labels[c] != 0, "{c:?}");
    }
    for d in &r.doors {
        let (a, b) = d.rooms;
        assert!(a < b);
        for &c in &d.cells {
            let me = r.labels[c];
            let other = if me == a { b } else { a };
            assert!(me == a || me == b, "{d:?}");
            assert!(
                Dir4::ALL
                    .iter()
                    .any(|&dir| r.labels.step(c, dir).is_some_and(|n| r.labels[n] == other)),
                "{c:?} of {d:?} does not touch room {other}"
            );
        }
        assert!(d.cells.contains(&d.centre));
    }
}

#[test]
fn bundled_maps_have_plausible_rooms() {
    // (map, seeded rooms expected): a flat of seven rooms, a hospital wing of
    // wards along a corridor, the two halves of the lee2011 office, and the
    // TurtleBot3 arena (one room round its pillars).
    for (map, rooms) in [
        ("turtlebot_simulator/simple_rooms.yaml", 5..=9),
        ("turtlebot_simulator/hospital_section.yaml", 30..=50),
        ("lee2011/office.yaml", 2..=3),
        ("nav2/turtlebot3_world.yaml", 1..=2),
    ] {
        let m = read_map(&fixture(map), &ReadOptions::default()).expect("bundled map");
        let free = m.free_mask();
        let r = morphological(&free, &RoomParams::indoor(m.resolution()));
        check(&free, &r);
        assert!(
            rooms.contains(&r.seeded),
            "{map}: {} seeded rooms",
            r.seeded
        );
        // Every seeded room is at least the smallest room size.
        let cell = m.resolution() * m.resolution();
        for &a in &r.areas[..r.seeded] {
            assert!(a as f64 * cell >= 1.0, "{map}: a room of {a} cells");
        }
    }
}

#[test]
fn the_medial_axis_method_finds_the_doors_of_the_bundled_maps() {
    // (map, rooms expected). The flat: six rooms behind its 1.5 m openings
    // (a door by the default width) and the hall. The hospital wing: the
    // wards behind doorways part from the corridor, the wards open to it
    // along their whole width stay with it. The office's halves join
    // through an opening wider than a door; the arena has none.
    for (map, rooms) in [
        ("turtlebot_simulator/simple_rooms.yaml", 7..=7),
        ("turtlebot_simulator/hospital_section.yaml", 15..=25),
        ("lee2011/office.yaml", 1..=2),
        ("nav2/turtlebot3_world.yaml", 1..=1),
    ] {
        let m = read_map(&fixture(map), &ReadOptions::default()).expect("bundled map");
        let free = m.free_mask();
        let r = oxcover_decomp::voronoi(&free, &RoomParams::indoor(m.resolution()));
        check(&free, &r);
        assert!(rooms.contains(&r.seeded), "{map}: {} rooms", r.seeded);
        assert!(
            r.doors.len() + 1 >= r.seeded,
            "{map}: rooms not joined by doors"
        );
    }
}
