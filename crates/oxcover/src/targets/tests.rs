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
