//! # oxcover-distance
//!
//! Grid distance transforms for coverage planning, on 4-connected moves:
//!
//! - [`astar`]: A* between two cells (Manhattan heuristic, bucket queue), the
//!   same route lengths as a wavefront at a fraction of the cells touched.
//! - [`lee`]: the Lee wavefront as a reusable workspace ([`Wavefront`]):
//!   multi-source, optional per-cell move masks, retrace that keeps direction.
//! - [`zelinsky`]: Zelinsky's distance transform and path transform
//!   (obstacle-proximity weighted, Dijkstra).
//! - [`brushfire`](mod@brushfire): distance to the nearest obstacle (4- or 8-connected).
//! - [`cidt`](mod@cidt): constrained inverse distance transform: nearest target, stopping
//!   the wave as soon as nothing nearer can appear.
//! - [`cfcidt`]: coarse-to-fine CIDT over an incrementally maintained block map,
//!   exact (same distance as a full BFS) thanks to a block-level lower bound.
//! - [`reference`](mod@reference): a plain `VecDeque` BFS that tests and benchmarks compare against.
//!
//! ```
//! use oxcover_distance::{cidt, Wavefront};
//! use oxcover_grid::{io::parse_ascii, Cell};
//!
//! let (map, start) = parse_ascii("
//!     S.#..
//!     ..#..
//!     .....
//! ").unwrap();
//! let mut wave = Wavefront::new(&map.free_mask());
//! // Nearest cell in the right-hand room, and the path there.
//! let near = cidt(&mut wave, &[start.unwrap()], |c| c.col >= 3).unwrap();
//! assert_eq!((near.distance, near.first()), (5, Cell::new(2, 3)));
//! assert_eq!(wave.retrace(near.first()).unwrap().len(), 6);
//! ```

pub mod astar;
pub mod brushfire;
pub mod cfcidt;
pub mod cidt;
pub mod lee;
pub mod reference;
pub mod zelinsky;

pub use astar::AStar;
pub use brushfire::{Connectivity, brushfire};
pub use cfcidt::{BlockMap, CoarseToFine, CoarseToFineFound};
pub use cidt::{Nearest, cidt};
pub use lee::Wavefront;
pub use zelinsky::{PathTransformParams, distance_transform, path_transform};
