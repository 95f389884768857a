//! The `lee2011` reproduction's shapes and its claim on one room: `smooth`
//! executed in closed loop covers at least 95 % with no collision of the
//! robot disc. (That the committed maps are the rasterised worlds, byte for
//! byte, and the page what the command writes, is tested in the module.)

use oxcover_grid::{Point, Vector};
use xtask::reproduce::lee2011::{self, Shape};

#[test]
fn shapes_contain_what_they_should() {
    // A U (concave): its bay is outside, its arms inside.
    let u = Shape::Polygon(vec![
        Point::new(0.0, 0.0),
        Point::new(3.0, 0.0),
        Point::new(3.0, 3.0),
        Point::new(2.0, 3.0),
        Point::new(2.0, 1.0),
        Point::new(1.0, 1.0),
        Point::new(1.0, 3.0),
        Point::new(0.0, 3.0),
    ]);
    assert!(
        u.contains(Point::new(0.5, 2.5))
            && u.contains(Point::new(2.5, 2.5))
            && u.contains(Point::new(1.5, 0.5))
    );
    assert!(!u.contains(Point::new(1.5, 2.0)) && !u.contains(Point::new(4.0, 1.0)));
    let r = Shape::Rect {
        centre: Point::new(0.0, 0.0),
        size: Vector::new(2.0, 1.0),
        angle_deg: 90.0,
    };
    assert!(r.contains(Point::new(0.0, 0.9)) && !r.contains(Point::new(0.9, 0.0)));
    let c = Shape::Circle {
        centre: Point::new(1.0, 1.0),
        radius: 0.5,
    };
    assert!(c.contains(Point::new(1.3, 1.3)) && !c.contains(Point::new(1.4, 1.4)));
}

/// The target on the most cluttered room, first seeded start.
#[test]
fn smooth_covers_the_workshop_in_closed_loop_without_collision() {
    let worlds = lee2011::worlds().unwrap();
    let (e, w) = worlds
        .iter()
        .enumerate()
        .find(|(_, w)| w.name == "workshop")
        .unwrap();
    let map = w.rasterise();
    let start = lee2011::starts(&map, e).unwrap()[0];
    let cfg = lee2011::closed_loop().unwrap();
    let (m, _, run) = lee2011::run_one(&map, e, 0, start, "smooth", &cfg).unwrap();
    assert!(m.coverage >= 95.0, "{m:?}");
    assert_eq!(m.collisions, 0, "{m:?}");
    assert!(run.tracking_max < 0.0225, "tracking {:?}", m.tracking);
}
