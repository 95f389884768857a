//! Targets' own tests: GeoJSON read and refused, areas onto cells (each
//! against cells worked out by hand or by brute force), required cells.

use geo::{LineString, Polygon, polygon};
use oxcover_grid::io::parse_ascii;
use oxcover_grid::{Cell, DiscRobot, Grid, MapFrame, Point};
use oxcover_planners::{CoverageProblem, Start};

use super::*;

fn err(text: &str, kinds: Kinds) -> String {
    parse_areas(text, kinds).unwrap_err()
}

const SQUARE: &str = r#"{"type":"Polygon","coordinates":[[[0,0],[2,0],[2,2],[0,2],[0,0]]]}"#;

#[test]
fn a_feature_collection_a_feature_and_a_bare_geometry_are_read() {
    let one = parse_areas(SQUARE, Kinds::Polygons).unwrap();
    assert_eq!(one.polygons.len(), 1);
    let feature = format!(r#"{{"type":"Feature","properties":null,"geometry":{SQUARE}}}"#);
    assert_eq!(parse_areas(&feature, Kinds::Polygons).unwrap(), one);
    let fc = format!(
        r#"{{"type":"FeatureCollection","features":[{feature},
        {{"type":"Feature","properties":{{}},"geometry":{{"type":"LineString","coordinates":[[0,0],[1,1,7]]}}}}]}}"#
    );
    let both = parse_areas(&fc, Kinds::PolygonsAndLines).unwrap();
    assert_eq!((both.polygons.len(), both.lines.len()), (1, 1));
    // An altitude is ignored.
    assert_eq!(
        both.lines[0],
        LineString::from(vec![(0.0, 0.0), (1.0, 1.0)])
    );
}

#[test]
fn bad_files_name_the_feature_and_what_is_wrong() {
    let p = Kinds::Polygons;
    assert!(err("x,y\n1,2", p).contains("not GeoJSON"));
    assert!(err(r#"{"type":"Nope"}"#, p).contains("not valid GeoJSON"));
    let line = r#"{"type":"FeatureCollection","features":[
        {"type":"Feature","properties":null,"geometry":{"type":"LineString","coordinates":[[0,0],[1,1]]}}]}"#;
    assert_eq!(
        err(line, p),
        "feature 0 is a LineString, expected Polygon or MultiPolygon"
    );
    let short = r#"{"type":"Polygon","coordinates":[[[0,0],[1,0],[0,0]]]}"#;
    assert!(err(short, p).contains("exterior ring has 3 position(s), a ring needs at least 4"));
    let open = r#"{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,1]]]}"#;
    assert!(err(open, p).contains("is not closed"));
    let bow = r#"{"type":"Polygon","coordinates":[[[0,0],[2,2],[2,0],[0,2],[0,0]]]}"#;
    let e = err(bow, p);
    assert!(
        e.contains("self-intersection") && e.contains("at (1.000, 1.000)"),
        "{e}"
    );
    assert!(
        err(
            r#"{"type":"Polygon","coordinates":[[[0,0],[1e999,0],[1,1],[0,0]]]}"#,
            p
        )
        .contains("not valid GeoJSON")
    );
    let none = r#"{"type":"Feature","properties":null,"geometry":null}"#;
    assert!(err(none, p).contains("no geometry"));
    let empty = r#"{"type":"FeatureCollection","features":[]}"#;
    assert!(err(empty, p).contains("holds no geometry"));
    let point = r#"{"type":"Point","coordinates":[0,0]}"#;
    assert!(err(point, Kinds::PolygonsAndLines).contains("is a Point"));
}

/// A 10 x 10 unit map, origin (0, 0): cell (r, c) is the square
/// x in [c, c+1], y in [9 - r, 10 - r].
fn frame() -> MapFrame {
    MapFrame::new(10, 10, 1.0, Point::origin())
}

fn marked(f: impl FnOnce(&mut Grid<bool>) -> Placement) -> (Vec<Cell>, Placement) {
    let mut g = Grid::new(10, 10, false);
    let p = f(&mut g);
    (g.true_cells().collect(), p)
}

#[test]
fn squares_meeting_a_polygon_include_those_it_only_touches() {
    // x in [2.5, 4], y in [5, 6.5]: columns 2-4 (x = 4 touches column 4),
    // rows 3-4 (y from 5 to 6.5 is rows 4 and 3) and row 5 (y = 5 touches it).
    let poly = polygon![(x: 2.5, y: 5.0), (x: 4.0, y: 5.0), (x: 4.0, y: 6.5), (x: 2.5, y: 6.5)];
    let (cells, p) = marked(|g| polygon_squares(&frame(), &poly, g));
    let mut want = Vec::new();
    for r in 3..=5 {
        for c in 2..=4 {
            want.push(Cell::new(r, c));
        }
    }
    assert_eq!(cells, want);
    assert!(!p.clipped);
}

#[test]
fn centres_inside_a_polygon_leave_its_hole_out() {
    let outer =
        polygon![(x: 0.0, y: 0.0), (x: 10.0, y: 0.0), (x: 10.0, y: 10.0), (x: 0.0, y: 10.0)];
    let hole = polygon![(x: 3.0, y: 3.0), (x: 7.0, y: 3.0), (x: 7.0, y: 7.0), (x: 3.0, y: 7.0)];
    let ring = Polygon::new(outer.exterior().clone(), vec![hole.exterior().clone()]);
    let (cells, _) = marked(|g| polygon_centres(&frame(), &ring, g));
    assert_eq!(cells.len(), 100 - 16);
    assert!(!cells.contains(&Cell::new(4, 4)));
}

#[test]
fn a_line_marks_every_square_it_touches() {
    // Along y = 5 (the border of rows 4 and 5) from x = 1.5 to 3.5.
    let l = LineString::from(vec![(1.5, 5.0), (3.5, 5.0)]);
    let (cells, _) = marked(|g| line_squares(&frame(), &l, g));
    let want: Vec<Cell> = [4, 5]
        .into_iter()
        .flat_map(|r| (1..=3).map(move |c| Cell::new(r, c)))
        .collect();
    assert_eq!(cells, want);
    // A diagonal through cell corners: each corner touches four squares.
    let d = LineString::from(vec![(1.0, 1.0), (3.0, 3.0)]);
    let (cells, _) = marked(|g| line_squares(&frame(), &d, g));
    // Squares whose closed square meets the segment, found by brute force.
    let f = frame();
    let want: Vec<Cell> = Grid::new(10, 10, false)
        .cells()
        .filter(|&c| {
            let (x0, y0) = (c.col as f64, (9 - c.row) as f64);
            (0..=2000).any(|k| {
                let t = 1.0 + 2.0 * f64::from(k) / 2000.0;
                (x0..=x0 + 1.0).contains(&t) && (y0..=y0 + 1.0).contains(&t)
            })
        })
        .collect();
    assert_eq!(cells, want);
    assert_eq!(f.resolution(), 1.0);
}

#[test]
fn a_line_on_a_rotated_map_blocks_the_cells_under_it() {
    let f = MapFrame::new(10, 10, 1.0, Point::new(1.0, 2.0)).with_yaw(0.7);
    let (a, b) = (
        f.cell_center(Cell::new(2, 1)),
        f.cell_center(Cell::new(7, 8)),
    );
    let l = LineString::from(vec![(a.x, a.y), (b.x, b.y)]);
    let mut g = Grid::new(10, 10, false);
    line_squares(&f, &l, &mut g);
    for k in 0..=100 {
        let p = a + (b - a) * (f64::from(k) / 100.0);
        let c = f.cell_at(&p).unwrap();
        assert!(g[c], "{c:?}");
    }
}

#[test]
fn a_disc_and_the_clipping_note() {
    let (cells, p) = marked(|g| disc_centres(&frame(), Point::new(0.5, 9.5), 1.0, g));
    assert_eq!(
        cells,
        vec![Cell::new(0, 0), Cell::new(0, 1), Cell::new(1, 0)]
    );
    assert!(p.clipped);
}

fn room() -> oxcover_grid::OccupancyGrid {
    parse_ascii("##########\n#........#\n#........#\n#........#\n##########")
        .unwrap()
        .0
}

#[test]
fn keep_out_covering_the_map_nowhere_and_zones_outside_are_refused() {
    let map = room();
    let far = Areas {
        polygons: vec![polygon![(x: 50.0, y: 50.0), (x: 60.0, y: 50.0), (x: 60.0, y: 60.0)]],
        lines: Vec::new(),
    };
    let t = Targets {
        keep_out: Some(far.clone()),
        ..Targets::default()
    };
    assert!(
        t.blocked_map(&map)
            .unwrap_err()
            .to_string()
            .starts_with("--keep-out: no keep-out area")
    );
    let problem = CoverageProblem::new(&map, DiscRobot::cell_sized(1.0), Start::First).unwrap();
    let cells = problem.cells();
    let t = Targets {
        zones: Some(far),
        ..Targets::default()
    };
    assert!(
        t.required(&map, cells)
            .unwrap_err()
            .to_string()
            .starts_with("--zones: no zone")
    );
    let t = Targets {
        rooms_only: Some(vec![7]),
        ..Targets::default()
    };
    let e = t.required(&map, cells).unwrap_err().to_string();
    assert_eq!(
        e,
        "--rooms-only: no room 7 on this map: the rooms are 1 to 1 (`oxcover segment` lists them)"
    );
}

#[test]
fn a_spot_and_a_done_path_narrow_the_required_cells() {
    let map = room();
    let problem = CoverageProblem::new(&map, DiscRobot::cell_sized(1.0), Start::First).unwrap();
    let cells = problem.cells();
    // Cell (2, 4) has its centre at (4.5, 2.5).
    let spot = Targets {
        spot: Some(Spot {
            centre: Point::new(4.5, 2.5),
            radius: 1.0,
        }),
        ..Targets::default()
    };
    let t = spot.required(&map, cells).unwrap().unwrap();
    assert_eq!(t.required.count_true(), 5);
    let done = Targets {
        done: Some(vec![Point::new(1.5, 3.5), Point::new(8.5, 3.5)]),
        ..spot
    };
    let t = done.required(&map, cells).unwrap().unwrap();
    // The top row's cell of the spot is done.
    assert_eq!((t.required.count_true(), t.done_cells), (4, 1));
    let (start, note) = resume_start(&map, 0.0, &[Point::new(8.5, 3.5)]).unwrap();
    assert_eq!((start, note), (Point::new(8.5, 3.5), None));
    // Standing in the wall: moved to the nearest cell centre, with a note.
    let (start, note) = resume_start(&map, 0.0, &[Point::new(9.5, 3.5)]).unwrap();
    assert_eq!(start, Point::new(8.5, 3.5));
    assert!(note.unwrap().contains("1.000 m away"));
}

/// A star-shaped polygon with a hole, `n` points, round (cx, cy).
fn star(n: usize, cx: f64, cy: f64, seed: u64) -> Polygon<f64> {
    let mut x = seed;
    let mut rnd = || {
        x = x
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let ring = |r0: f64, r1: f64, rnd: &mut dyn FnMut() -> f64| {
        let mut pts: Vec<(f64, f64)> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                let r = r0 + (r1 - r0) * rnd();
                (cx + r * a.cos(), cy + r * a.sin())
            })
            .collect();
        pts.push(pts[0]);
        LineString::from(pts)
    };
    let outer = ring(3.0, 4.5, &mut rnd);
    let hole = ring(0.8, 1.5, &mut rnd);
    Polygon::new(outer, vec![hole])
}

/// The scanlines against `geo`'s own predicates, cell by cell, on rotated
/// and plain frames.
#[test]
fn scanlines_agree_with_geo_cell_by_cell() {
    use geo::{Intersects, MapCoords, Rect};
    for (seed, yaw) in [(1, 0.0), (2, 0.3), (3, -1.1), (4, 0.0)] {
        let f = MapFrame::new(24, 20, 0.5, Point::new(-1.0, -0.5)).with_yaw(yaw);
        let p = star(9 + seed as usize, 5.0, 4.0, seed);
        let (centres, _) = {
            let mut g = Grid::new(24, 20, false);
            let pl = polygon_centres(&f, &p, &mut g);
            (g, pl)
        };
        let mut squares = Grid::new(24, 20, false);
        polygon_squares(&f, &p, &mut squares);
        // The polygon in grid coordinates, as the rasteriser sees it.
        let g = p.map_coords(|c| {
            let (row, col) = f.fractional_cell(&Point::new(c.x, c.y));
            geo::Coord {
                x: col + 0.5,
                y: row + 0.5,
            }
        });
        for c in centres.cells() {
            let (x, y) = (c.col as f64, c.row as f64);
            let centre = geo::Point::new(x + 0.5, y + 0.5);
            assert_eq!(
                centres[c],
                g.intersects(&centre),
                "seed {seed}: centre of {c:?}"
            );
            let square = Rect::new(
                geo::Coord { x, y },
                geo::Coord {
                    x: x + 1.0,
                    y: y + 1.0,
                },
            );
            assert_eq!(
                squares[c],
                g.intersects(&square),
                "seed {seed}: square of {c:?}"
            );
        }
    }
}

/// A polygon of 200,000 points over a 2000 x 2000 map: linear work, not
/// a test per cell against every edge.
#[test]
fn a_huge_polygon_is_rasterised_in_linear_time() {
    let f = MapFrame::new(2000, 2000, 0.01, Point::origin());
    let p = star(100_000, 10.0, 10.0, 7);
    let t = std::time::Instant::now();
    let mut g = Grid::new(2000, 2000, false);
    let placed = polygon_squares(&f, &p, &mut g);
    assert!(placed.cells > 300_000, "{}", placed.cells);
    assert!(t.elapsed().as_secs_f64() < 20.0, "{:?}", t.elapsed());
}

/// Large files are read and checked in bounded time, valid or not.
#[test]
fn large_polygons_are_checked_quickly() {
    let ring = |n: usize, bow: bool| {
        let mut pts: Vec<String> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                let r = if bow && i == n / 2 {
                    50.0
                } else {
                    10.0 + (i % 7) as f64 * 0.01
                };
                format!("[{},{}]", r * a.cos(), r * a.sin())
            })
            .collect();
        if bow {
            // The far point's return crosses the ring.
            pts.insert(n / 2 + 1, "[-60,0.5]".into());
        }
        pts.push(pts[0].clone());
        format!(
            r#"{{"type":"Polygon","coordinates":[[{}]]}}"#,
            pts.join(",")
        )
    };
    for bow in [false, true] {
        let text = ring(MAX_POLYGON_POSITIONS - 2, bow);
        let t = std::time::Instant::now();
        let r = parse_areas(&text, Kinds::Polygons);
        assert_eq!(r.is_err(), bow, "{:?}", r.err());
        assert!(t.elapsed().as_secs_f64() < 10.0, "{:?}", t.elapsed());
    }
    let e = parse_areas(&ring(MAX_POLYGON_POSITIONS + 1, false), Kinds::Polygons).unwrap_err();
    assert!(e.contains("at most 10000 per polygon"), "{e}");
}

/// A target's window holds every cell centre its zones and its spot take
/// in, on a turned map too; with both, the cells both take in; none
/// without either.
#[test]
fn the_extent_holds_every_cell_the_zones_and_spot_take_in() {
    for yaw in [0.0, 0.7] {
        let cells = Grid::new(40, 30, oxcover_grid::Occupancy::Free);
        let map = oxcover_grid::OccupancyGrid::new(cells, 0.5, Point::new(-3.0, 2.0)).with_yaw(yaw);
        let f = map.frame();
        let (a, b) = (
            f.cell_center(Cell::new(5, 7)),
            f.cell_center(Cell::new(12, 20)),
        );
        let zone = polygon![(x: a.x, y: a.y), (x: b.x, y: a.y), (x: b.x, y: b.y), (x: a.x, y: b.y)];
        let spot = Spot::new(f.cell_center(Cell::new(14, 18)), 2.2).unwrap();
        let zones = Some(Areas {
            polygons: vec![zone.clone()],
            lines: Vec::new(),
        });
        let cases = [
            (zones.clone(), None),
            (None, Some(spot)),
            (zones.clone(), Some(spot)),
        ];
        for (zones, spot) in cases {
            let t = Targets {
                zones: zones.clone(),
                spot,
                ..Targets::default()
            };
            let (r0, r1, c0, c1) = t.extent(&map).expect("a window");
            let mut inside = Grid::new(40, 30, true);
            if zones.is_some() {
                inside.fill(false);
                polygon_centres(f, &zone, &mut inside);
            }
            if let Some(s) = spot {
                let mut disc = Grid::new(40, 30, false);
                disc_centres(f, s.centre, s.radius, &mut disc);
                inside = inside.zip_map(&disc, |&a, &b| a && b);
            }
            assert!(
                inside.count_true() > 0,
                "yaw {yaw} zones {} spot {}",
                zones.is_some(),
                spot.is_some()
            );
            for c in inside.true_cells() {
                assert!(
                    (r0..r1).contains(&c.row) && (c0..c1).contains(&c.col),
                    "{c:?} outside {:?} (yaw {yaw})",
                    (r0, r1, c0, c1)
                );
            }
            // No more than a cell or two beyond the cells taken in.
            assert!(
                (r1 - r0) * (c1 - c0) < 40 * 30 / 2,
                "{:?}",
                (r0, r1, c0, c1)
            );
        }
    }
    assert_eq!(Targets::default().extent(&room()), None);
}
