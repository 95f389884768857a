//! Tests of the doorways segmentation.

use super::*;

/// Two rooms 60 × 40 cells, one above the other, a wall 4 cells thick
/// between them with an 18-cell gap.
fn two_rooms() -> Grid<bool> {
    Grid::from_fn(64, 90, |c: Cell| {
        let inside = (2..62).contains(&c.col) && (2..88).contains(&c.row);
        let wall = (43..47).contains(&c.row) && !(23..41).contains(&c.col);
        inside && !wall
    })
}

#[test]
fn a_gap_in_a_thin_wall_is_a_door() {
    let free = two_rooms();
    let r = doorways(&free, &RoomParams::indoor(0.05));
    assert_eq!(r.count(), 2, "{:?}", r.areas);
}
