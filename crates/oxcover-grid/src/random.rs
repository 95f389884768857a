//! Seeded random maps (`ChaCha8Rng::seed_from_u64`): the same seed gives the same
//! map on every machine.
//!
//! - [`uniform_obstacles`]: exactly `k` blocked cells, uniformly placed.
//! - [`uniform_connected`]: the seed-000 experiment: `k` blocked cells, uniform
//!   among placements whose free space is 4-connected (rejection sampling).
//! - [`incremental_connected`]: for larger grids where rejection would never
//!   succeed: obstacles added one at a time, each uniform among the free cells
//!   whose blocking keeps the free space 4-connected. Not the same distribution
//!   as rejection; say which one an experiment used.
//! - [`random_density`]: each cell blocked with probability `p` (benchmarks).
//! - [`rectangles`] and [`blobs`]: axis-aligned boxes and discs for sweeps.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::components::{components4, reachable};
use crate::error::{Error, Result};
use crate::grid::{Cell, Grid};
use crate::occupancy::OccupancyGrid;

/// Attempts [`uniform_connected`] makes before giving up.
pub const MAX_REJECTION_ATTEMPTS: usize = 100_000;

/// `width × height` free cells with exactly `min(count, cells)` blocked ones,
/// uniformly placed (partial Fisher–Yates).
#[must_use]
pub fn uniform_obstacles(width: usize, height: usize, count: usize, seed: u64) -> OccupancyGrid {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    OccupancyGrid::from_free_mask(&sample_free(width, height, count, &mut rng))
}

fn sample_free(width: usize, height: usize, count: usize, rng: &mut ChaCha8Rng) -> Grid<bool> {
    let n = width * height;
    let count = count.min(n);
    let mut idx: Vec<u32> = (0..n as u32).collect();
    let mut free = Grid::new(width, height, true);
    for i in 0..count {
        let j = rng.random_range(i..n);
        idx.swap(i, j);
        free.as_mut_slice()[idx[i] as usize] = false;
    }
    free
}

/// Exactly `count` blocked cells, uniform among placements whose free cells are
/// one non-empty 4-connected component (rejection sampling).
///
/// # Errors
/// [`Error::Generator`] when no placement is found in [`MAX_REJECTION_ATTEMPTS`].
pub fn uniform_connected(
    width: usize,
    height: usize,
    count: usize,
    seed: u64,
) -> Result<OccupancyGrid> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    if count >= width * height {
        return Err(too_many(width, height, count));
    }
    for _ in 0..MAX_REJECTION_ATTEMPTS {
        let free = sample_free(width, height, count, &mut rng);
        if components4(&free).count() == 1 {
            return Ok(OccupancyGrid::from_free_mask(&free));
        }
    }
    Err(Error::Generator {
        message: format!(
            "no placement of {count} obstacles on {width}x{height} with connected free space in {MAX_REJECTION_ATTEMPTS} attempts; use incremental_connected"
        ),
    })
}

/// Exactly `count` blocked cells placed one at a time, each uniform among the free
/// cells whose blocking keeps the free space 4-connected.
///
/// # Errors
/// [`Error::Generator`] when no such cell is left before `count` are placed.
pub fn incremental_connected(
    width: usize,
    height: usize,
    count: usize,
    seed: u64,
) -> Result<OccupancyGrid> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    if count >= width * height {
        return Err(too_many(width, height, count));
    }
    let mut free = Grid::new(width, height, true);
    let mut candidates: Vec<Cell> = free.cells().collect();
    // Cells whose blocking would cut the free space now; they may become
    // acceptable after the next placement, so they go back into the pool then.
    let mut rejected: Vec<Cell> = Vec::new();
    let mut placed = 0;
    while placed < count {
        if candidates.is_empty() {
            return Err(Error::Generator {
                message: format!(
                    "only {placed} of {count} obstacles fit on {width}x{height} without cutting the free space"
                ),
            });
        }
        let i = rng.random_range(0..candidates.len());
        let c = candidates.swap_remove(i);
        free[c] = false;
        if keeps_connected(&free, c) {
            placed += 1;
            candidates.append(&mut rejected);
        } else {
            free[c] = true;
            rejected.push(c);
        }
    }
    Ok(OccupancyGrid::from_free_mask(&free))
}

fn keeps_connected(free: &Grid<bool>, removed: Cell) -> bool {
    let mut nbrs = free
        .neighbours4(removed)
        .filter(|(_, n)| free[*n])
        .map(|(_, n)| n);
    let Some(first) = nbrs.next() else {
        return free.count_true() == 0;
    };
    let r = reachable(free, first);
    r.count_true() == free.count_true()
}

fn too_many(width: usize, height: usize, count: usize) -> Error {
    Error::Generator {
        message: format!("{count} obstacles leave no free cell on {width}x{height}"),
    }
}

/// Each cell blocked independently with probability `density` (clamped to 0..=1).
#[must_use]
pub fn random_density(width: usize, height: usize, density: f64, seed: u64) -> OccupancyGrid {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let p = if density.is_finite() {
        density.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let free = Grid::from_fn(width, height, |_| rng.random::<f64>() >= p);
    OccupancyGrid::from_free_mask(&free)
}

/// `count` axis-aligned boxes with sides in `1..=max_side`, uniformly placed,
/// inside a one-cell wall around the map.
#[must_use]
pub fn rectangles(
    width: usize,
    height: usize,
    count: usize,
    max_side: usize,
    seed: u64,
) -> OccupancyGrid {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut free = walled(width, height);
    let max_side = max_side.max(1);
    for _ in 0..count {
        let h = rng.random_range(1..=max_side).min(height);
        let w = rng.random_range(1..=max_side).min(width);
        let r0 = rng.random_range(0..=height - h);
        let c0 = rng.random_range(0..=width - w);
        for r in r0..r0 + h {
            for c in c0..c0 + w {
                free[Cell::new(r, c)] = false;
            }
        }
    }
    OccupancyGrid::from_free_mask(&free)
}

/// `count` discs with radii in `1..=max_radius` cells, inside a one-cell wall.
#[must_use]
pub fn blobs(
    width: usize,
    height: usize,
    count: usize,
    max_radius: usize,
    seed: u64,
) -> OccupancyGrid {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut free = walled(width, height);
    let max_radius = max_radius.max(1);
    for _ in 0..count {
        let rad = rng.random_range(1..=max_radius) as isize;
        let cr = rng.random_range(0..height) as isize;
        let cc = rng.random_range(0..width) as isize;
        for dr in -rad..=rad {
            for dc in -rad..=rad {
                if dr * dr + dc * dc > rad * rad {
                    continue;
                }
                let (r, c) = (cr + dr, cc + dc);
                if r >= 0 && c >= 0 && (r as usize) < height && (c as usize) < width {
                    free[Cell::new(r as usize, c as usize)] = false;
                }
            }
        }
    }
    OccupancyGrid::from_free_mask(&free)
}

fn walled(width: usize, height: usize) -> Grid<bool> {
    Grid::from_fn(width, height, |c| {
        c.row > 0 && c.col > 0 && c.row + 1 < height && c.col + 1 < width
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_map() {
        assert_eq!(
            uniform_obstacles(20, 10, 37, 7),
            uniform_obstacles(20, 10, 37, 7)
        );
        assert_ne!(
            uniform_obstacles(20, 10, 37, 7),
            uniform_obstacles(20, 10, 37, 8)
        );
        assert_eq!(uniform_obstacles(20, 10, 37, 7).counts().occupied, 37);
        assert_eq!(
            random_density(30, 30, 0.2, 1),
            random_density(30, 30, 0.2, 1)
        );
        assert_eq!(rectangles(30, 20, 5, 6, 3), rectangles(30, 20, 5, 6, 3));
        assert_eq!(blobs(30, 20, 5, 3, 3), blobs(30, 20, 5, 3, 3));
    }

    #[test]
    fn connected_generators_keep_free_space_connected() {
        for seed in 0..20 {
            let m = uniform_connected(8, 8, 15, seed).unwrap();
            assert_eq!(m.counts().occupied, 15);
            assert_eq!(components4(&m.free_mask()).count(), 1);
            let m = incremental_connected(32, 32, 240, seed).unwrap();
            assert_eq!(m.counts().occupied, 240);
            assert_eq!(components4(&m.free_mask()).count(), 1);
        }
        assert!(uniform_connected(2, 2, 4, 0).is_err());
    }
}
