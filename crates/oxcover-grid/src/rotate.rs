//! Rotating a map about its centre (nearest-neighbour resampling), for
//! rotation studies such as Pavlíček 2002's claim that boustrophedon depends on the
//! map's orientation and border expansion does not.

use crate::grid::Grid;
use crate::math::Point;
use crate::occupancy::{Occupancy, OccupancyGrid};

/// `map` rotated by `degrees` counter-clockwise about its centre, on a canvas
/// just large enough; cells from outside the original map are unknown. Same
/// resolution, origin (0, 0).
#[must_use]
pub fn rotate(map: &OccupancyGrid, degrees: f64) -> OccupancyGrid {
    let (w, h) = (map.width() as f64, map.height() as f64);
    let snap = |v: f64| {
        if (v - v.round()).abs() < 1e-12 {
            v.round()
        } else {
            v
        }
    };
    let (s, c) = degrees.to_radians().sin_cos();
    let (s, c) = (snap(s), snap(c));
    let nw = (w * c.abs() + h * s.abs()).ceil().max(1.0) as usize;
    let nh = (w * s.abs() + h * c.abs()).ceil().max(1.0) as usize;
    let (cx, cy) = (w / 2.0, h / 2.0);
    let (ncx, ncy) = (nw as f64 / 2.0, nh as f64 / 2.0);
    let cells = Grid::from_fn(nw, nh, |cell| {
        // Grid coordinates with y up for a counter-clockwise map rotation.
        let x = cell.col as f64 + 0.5 - ncx;
        let y = ncy - (cell.row as f64 + 0.5);
        let (ox, oy) = (c * x + s * y, -s * x + c * y);
        let (col, row) = (ox + cx, cy - oy);
        if col < 0.0 || row < 0.0 || col >= w || row >= h {
            return Occupancy::Unknown;
        }
        map.cells()[crate::grid::Cell::new(row as usize, col as usize)]
    });
    OccupancyGrid::new(cells, map.resolution(), Point::new(0.0, 0.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::parse_ascii;

    #[test]
    fn quarter_turns_are_exact() {
        let (m, _) = parse_ascii("..#\n...").unwrap();
        let r = rotate(&m, 90.0);
        assert_eq!((r.width(), r.height()), (2, 3));
        // The blocked top-right cell moves to the top-left.
        assert_eq!(r.cells()[crate::grid::Cell::new(0, 0)], Occupancy::Occupied);
        assert_eq!(r.counts().free, 5);
        let back = rotate(&rotate(&r, 90.0), 180.0);
        assert_eq!(back.cells(), m.cells());
    }

    #[test]
    fn oblique_rotation_keeps_the_free_area_roughly() {
        let (m, _) = parse_ascii(&vec!["..........".to_string(); 10].join("\n")).unwrap();
        let r = rotate(&m, 30.0);
        let free = r.counts().free as f64;
        assert!((free - 100.0).abs() < 12.0, "{free}");
    }
}
