//! Readers round-trip: what the writer writes (and what other tools write in
//! every image variant the contract lists) reads back to the same cells.

use std::path::PathBuf;

use oxcover_grid::io::{ReadOptions, read_map, write_ros_map};
use oxcover_grid::{Grid, Occupancy, OccupancyGrid, Point};
use proptest::prelude::*;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("oxcover-io-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create scratch dir");
    dir
}

fn occupancy(v: u8) -> Occupancy {
    match v % 3 {
        0 => Occupancy::Free,
        1 => Occupancy::Occupied,
        _ => Occupancy::Unknown,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn pgm_yaml_writer_round_trips(w in 1usize..60, h in 1usize..60, cells in proptest::collection::vec(any::<u8>(), 3600), res in 0.01f64..2.0, ox in -50.0f64..50.0, oy in -50.0f64..50.0) {
        let grid = Grid::from_fn(w, h, |c| occupancy(cells[c.row * 60 + c.col]));
        let map = OccupancyGrid::new(grid, res, Point::new(ox, oy));
        let dir = scratch("pgm");
        let yaml = dir.join(format!("m{w}x{h}.yaml"));
        write_ros_map(&map, &yaml).unwrap();
        let back = read_map(&yaml, &ReadOptions::default()).unwrap();
        prop_assert_eq!(back.cells(), map.cells());
        prop_assert_eq!(back.frame(), map.frame());
    }

    #[test]
    fn png_variants_read_like_the_grey_value(w in 1u32..40, h in 1u32..40, values in proptest::collection::vec(any::<u8>(), 1600), variant in 0usize..6) {
        let grey: Vec<u8> = (0..(w * h) as usize).map(|i| values[i]).collect();
        let dir = scratch("png");
        let path = dir.join(format!("v{variant}-{w}x{h}.png"));
        let file = std::fs::File::create(&path).unwrap();
        let mut enc = png::Encoder::new(std::io::BufWriter::new(file), w, h);
        let data: Vec<u8> = match variant {
            0 => { enc.set_color(png::ColorType::Grayscale); grey.clone() }
            1 => { enc.set_color(png::ColorType::GrayscaleAlpha); grey.iter().flat_map(|&g| [g, 17]).collect() }
            2 => { enc.set_color(png::ColorType::Rgb); grey.iter().flat_map(|&g| [g, g, g]).collect() }
            3 => { enc.set_color(png::ColorType::Rgba); grey.iter().flat_map(|&g| [g, g, g, 0]).collect() }
            4 => {
                enc.set_color(png::ColorType::Grayscale);
                enc.set_depth(png::BitDepth::Sixteen);
                grey.iter().flat_map(|&g| (u16::from(g) * 257).to_be_bytes()).collect()
            }
            _ => {
                enc.set_color(png::ColorType::Indexed);
                enc.set_palette((0..=255u8).flat_map(|g| [g, g, g]).collect::<Vec<u8>>());
                grey.clone()
            }
        };
        let mut writer = enc.write_header().unwrap();
        writer.write_image_data(&data).unwrap();
        writer.finish().unwrap();
        let map = read_map(&path, &ReadOptions::default()).unwrap();
        let want = oxcover_grid::io::Thresholds::default();
        for (i, &g) in grey.iter().enumerate() {
            prop_assert_eq!(map.cells().as_slice()[i], want.classify(f64::from(g)));
        }
    }
}

/// A floor plan drawn to its own rule (only near-white free, as the ipa
/// benchmark reads its plans) is read by setting the thresholds; the
/// default stays the contract's ROS defaults, which call light grey free.
#[test]
fn plain_images_take_the_thresholds_they_are_given() {
    let dir = scratch("thresholds");
    let path = dir.join("plan.pgm");
    // Black wall, light grey outside (230), white floor, mid grey.
    let values = [0u8, 230, 255, 128];
    let mut bytes = b"P5\n4 1\n255\n".to_vec();
    bytes.extend_from_slice(&values);
    std::fs::write(&path, bytes).unwrap();
    let cells = |opts: &ReadOptions| read_map(&path, opts).unwrap().cells().as_slice().to_vec();
    use Occupancy::{Free, Occupied, Unknown};
    assert_eq!(
        cells(&ReadOptions::default()),
        [Occupied, Free, Free, Unknown]
    );
    let white_only = oxcover_grid::io::Thresholds {
        occupied_thresh: 4.5 / 255.0,
        free_thresh: 4.5 / 255.0,
        ..oxcover_grid::io::Thresholds::default()
    };
    assert_eq!(
        cells(&ReadOptions::default().thresholds(white_only)),
        [Occupied, Occupied, Free, Occupied]
    );
}

#[test]
fn every_bundled_map_reads() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/maps");
    let files = [
        ("turtlebot_simulator/simple_rooms.yaml", (400, 300)),
        ("turtlebot_simulator/hospital_section.yaml", (1086, 443)),
        ("nav2/turtlebot3_world.yaml", (384, 384)),
        ("nobleo/basement.yaml", (600, 600)),
        ("navigation_tutorials/lse_arena.yaml", (80, 60)),
        ("movingai/room-32-32-4.map", (32, 32)),
        ("movingai/maze-32-32-2.map", (32, 32)),
        ("pythonrobotics/test.png", (44, 44)),
    ];
    for (f, (w, h)) in files {
        let m = read_map(&root.join(f), &ReadOptions::default()).unwrap();
        assert_eq!((m.width(), m.height()), (w, h), "{f}");
        assert!(m.counts().free > 0, "{f}");
    }
    // The basement's grey outside is unknown, never free (contract, shared/maps README).
    let b = read_map(&root.join("nobleo/basement.yaml"), &ReadOptions::default()).unwrap();
    assert!(b.counts().unknown > b.counts().free);
}

/// `map_format` names the reader `read_map` picks: by extension, else by
/// the first bytes (a MovingAI map under any name), and an image otherwise.
#[test]
fn map_format_names_the_reader_read_map_picks() {
    use oxcover_grid::io::{MapFormat, map_format};
    let dir = scratch("format");
    let file = |name: &str, bytes: &[u8]| {
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    };
    let movingai = b"type octile\nheight 1\nwidth 2\nmap\n..\n";
    let cases = [
        (file("a.yaml", b"not read"), MapFormat::RosYaml),
        (file("a.YML", b"not read"), MapFormat::RosYaml),
        (file("a.map", b"not read"), MapFormat::MovingAi),
        (file("grid.txt", movingai), MapFormat::MovingAi),
        (
            file("plan.pgm", b"P5\n2 1\n255\n\xff\xff"),
            MapFormat::Image,
        ),
        (file("empty.png", b""), MapFormat::Image),
    ];
    for (path, want) in &cases {
        assert_eq!(map_format(path).unwrap(), *want, "{}", path.display());
    }
    // The content sniff agrees with what `read_map` then does with it.
    let grid = read_map(&cases[3].0, &ReadOptions::default().resolution(0.5)).unwrap();
    assert_eq!(
        (grid.width(), grid.height(), grid.resolution()),
        (2, 1, 1.0)
    );
    let missing = dir.join("missing.png");
    let err = map_format(&missing).unwrap_err().to_string();
    assert!(err.contains("missing.png"), "{err}");
}
