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

#[test]
fn no_free_cell_gives_no_room() {
    for free in [Grid::new(40, 30, false), Grid::new(0, 0, false)] {
        let r = doorways(&free, &RoomParams::indoor(0.05));
        assert_eq!((r.count(), r.seeded, r.doors.len()), (0, 0, 0));
    }
}

#[test]
fn one_open_hall_is_one_room() {
    // 30 m x 20 m, no wall inside.
    let free = Grid::from_fn(600, 400, |c: Cell| {
        (1..599).contains(&c.col) && (1..399).contains(&c.row)
    });
    let r = doorways(&free, &RoomParams::indoor(0.05));
    assert_eq!((r.count(), r.seeded), (1, 1));
}

#[test]
fn one_cell_corridors_give_labels_not_a_panic() {
    // A comb of corridors one cell wide, every other column.
    let free = Grid::from_fn(41, 41, |c: Cell| c.row == 20 || c.col % 2 == 1);
    let r = doorways(&free, &RoomParams::indoor(0.05));
    for c in free.cells() {
        assert_eq!(free[c], r.labels[c] != 0, "{c:?}");
    }
    // And at a bad resolution: every free cell one room of one cell or more.
    let r = doorways(&free, &RoomParams::indoor(f64::NAN));
    assert!(r.count() >= 1);
}

#[test]
fn labels_do_not_depend_on_the_thread_count() {
    let free = two_rooms();
    let params = RoomParams::indoor(0.05);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool")
            .install(|| doorways(&free, &params))
    };
    let one = run(1);
    assert_eq!(one, run(2));
    assert_eq!(one, run(5));
}

#[test]
fn labels_are_numbered_top_left_first() {
    let r = doorways(&two_rooms(), &RoomParams::indoor(0.05));
    // The upper room holds the first free cell in row-major order.
    assert_eq!(r.labels[Cell::new(2, 2)], 1);
    assert_eq!(r.labels[Cell::new(87, 61)], 2);
    assert_eq!(r.doors.len(), 1);
    assert_eq!(r.doors[0].rooms, (1, 2));
}

#[test]
fn blocks_are_a_tenth_of_a_metre_or_so() {
    use super::blocks::block_side;
    assert_eq!(block_side(0.05), 2);
    assert_eq!(block_side(0.025), 4);
    assert_eq!(block_side(0.03), 3);
    assert_eq!(block_side(0.07), 1);
    assert_eq!(block_side(0.1), 1);
    assert_eq!(block_side(f64::NAN), 1);
    assert_eq!(block_side(0.0), 1);
    // A map finer than is useful: blocks of at most 64 cells a side.
    assert_eq!(block_side(1e-9), 64);
}

#[test]
fn a_wall_one_cell_thick_is_kept_on_blocks() {
    // Two rooms 3 m x 2 m at 5 cm, a wall one cell thick between them with
    // a 0.9 m door; the wall in the middle of a block and on its edge.
    for wall_row in [43, 44] {
        let free = Grid::from_fn(64, 90, |c: Cell| {
            let inside = (2..62).contains(&c.col) && (2..88).contains(&c.row);
            let door = (23..41).contains(&c.col);
            inside && (c.row != wall_row || door)
        });
        let r = doorways(&free, &RoomParams::indoor(0.05));
        assert_eq!(r.count(), 2, "wall row {wall_row}: {:?}", r.areas);
        for c in free.cells() {
            assert_eq!(free[c], r.labels[c] != 0, "{c:?}");
        }
        assert_ne!(r.labels[Cell::new(10, 10)], r.labels[Cell::new(80, 10)]);
    }
}

#[test]
fn edge_cells_are_the_obstacle_cells_beside_a_free_one() {
    // A 3 × 3 room in a 5 × 5 grid: its ring of walls, less the corners,
    // which touch it diagonally only; and one wall cell inside.
    let mut free = Grid::from_fn(5, 5, |c: Cell| {
        (1..4).contains(&c.row) && (1..4).contains(&c.col)
    });
    free[Cell::new(2, 2)] = false;
    let edges = edge_cells(&free);
    let expect: Vec<Vec<u32>> = vec![
        vec![1, 2, 3],
        vec![0, 4],
        vec![0, 2, 4],
        vec![0, 4],
        vec![1, 2, 3],
    ];
    assert_eq!(edges, expect);
    // And by brute force on a random grid.
    let free = oxcover_grid::random::random_density(37, 23, 0.4, 3).free_mask();
    let brute: Vec<Vec<u32>> = (0..free.height())
        .map(|r| {
            (0..free.width())
                .filter(|&c| {
                    let here = Cell::new(r, c);
                    !free[here]
                        && Dir4::ALL
                            .iter()
                            .any(|&d| free.step(here, d).is_some_and(|n| free[n]))
                })
                .map(|c| c as u32)
                .collect()
        })
        .collect();
    assert_eq!(edge_cells(&free), brute);
}
