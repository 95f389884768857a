//! # oxcover-decomp
//!
//! Decompositions of grid maps used by the coverage planners:
//!
//! - [`quadtree`]: quadtree decomposition (QTD) of a binary matrix into uniform
//!   blocks, padded to a power of two, with O(log n) incremental updates that
//!   report which blocks changed (Siamantas 2010's per-step decomposition).
//! - [`rectangular`]: the rectangular decomposition of Zhang & Yan 2008:
//!   real and virtual square nodes, the interleaving network of connectible
//!   nodes, and rectangles grown next to blocked neighbours.
//! - [`slices`]: a grid cut by parallel lanes at any angle into free
//!   intervals, and cellular decompositions built from them with their
//!   adjacency graphs: [`boustrophedon`](mod@boustrophedon) (Choset & Pignon: cut at critical
//!   events) and [`trapezoidal`](mod@trapezoidal) (also cut where a side bends).
//! - [`border_expansion`](mod@border_expansion): Pavlíček 2002's roads, the boundaries of successive
//!   offsets of the obstacles, with safety levels and the road graph.
//! - [`rooms`]: room segmentation of indoor maps by morphology (erode until
//!   the free space splits into room-sized seeds, grow them back), with the
//!   doors between rooms; [`voronoi_rooms`]: the same output from the
//!   distance transform's medial axis, split at its narrow points (doors).
//!
//! ```
//! use oxcover_decomp::QuadTree;
//! use oxcover_grid::{Cell, Grid};
//!
//! // A 4x4 free matrix is one block; blocking a cell splits it into 7.
//! let mut q = QuadTree::new(&Grid::new(4, 4, false));
//! assert_eq!(q.blocks().len(), 1);
//! let changes = q.set(Cell::new(0, 0), true);
//! assert_eq!((changes.removed.len(), changes.added.len()), (1, 7));
//! assert_eq!(q.free_blocks().iter().map(|b| b.area()).sum::<usize>(), 15);
//! ```

pub mod border_expansion;
pub mod boustrophedon;
pub mod doorways;
pub mod quadtree;
pub mod rectangular;
pub mod rooms;
pub mod slices;
pub mod trapezoidal;
pub mod voronoi_rooms;

pub use border_expansion::{BorderExpansion, Road, border_expansion};
pub use boustrophedon::boustrophedon;
pub use doorways::doorways;
pub use quadtree::{Block, BlockChanges, QuadTree};
pub use rectangular::{Rectangle, RectangularDecomposition, dir8_bit};
pub use rooms::{Door, RoomParams, Rooms, merge_small_regions, morphological};
pub use slices::{Interval, Lane, SliceDecomposition, Slices};
pub use trapezoidal::trapezoidal;
pub use voronoi_rooms::voronoi;
