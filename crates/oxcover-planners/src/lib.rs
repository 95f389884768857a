//! # oxcover-planners
//!
//! Coverage planners on grid maps, behind one [`Planner`] trait and one
//! [`registry()`] ([`build`] sets a planner's options, e.g. a sweep angle), and
//! the coverage problem they all work on ([`CoverageProblem`]: made once from
//! a map, a robot and a [`Start`]; it hands planners their [`PlannerInput`]
//! and expands, leads in and boundary-passes their plans):
//!
//! | name | module | source | complete |
//! |---|---|---|---|
//! | `dtc` | [`dtc`] | Zelinsky et al. 1993 | yes |
//! | `full-dtc` | [`full_dtc`] | Siamantas 2010's baseline: DTC for every goal | yes |
//! | `grid-cover` | [`grid_cover`] | Siamantas, Gatsis & Tzes 2010 | yes |
//! | `rect-priority` | [`rect_priority`] | Zhang & Yan 2008 | no (paper: > 90 %) |
//! | `optimal` | [`optimal`] | exact minimum moves (frontier DP), coverage grid ≤ 16 wide | yes |
//! | `stc` | [`stc`] | Gabriely & Rimon 2001, full mega-cells only | no |
//! | `spiral-stc` | [`stc`] | Gabriely & Rimon 2002, with partly blocked mega-cells | yes |
//! | `bsa` | [`bsa`] | Gonzalez et al. 2005 | yes |
//! | `boustrophedon` | [`sweep`] | Choset & Pignon 1997 (Pavlíček 2002) | yes |
//! | `trapezoidal` | [`sweep`] | slab decomposition (Pavlíček 2002, Fig. 8) | yes |
//! | `border-expansion` | [`border_expansion`] | Pavlicek et al. 2002 | yes |
//! | `lanes` | [`lanes`] | edge loops + straight lanes at each region's fastest angle, ordered by estimated time (issue 15) | yes |
//! | `smooth` | [`smooth`] | after Lee et al. 2011, for time: wall following, nested virtual-wall rings, slivers, PSO-tuned Bézier fillets | yes |
//!
//! The online sensor-based planner of Demir 2018 (`sensor-bcd`) needs a
//! world to sense, not a grid; it lives in `oxcover-world`.
//!
//! Planners work on the coverage grid ([`oxcover_grid::CoarseGrid`]; one tool
//! diameter per cell, the fine grid itself with the default radii) and return
//! coverage or fine cell paths; [`CoverageProblem::expand`] makes every plan a 4-connected path
//! of plannable fine cells. The sweep and border-expansion planners return
//! metre paths whose every segment is checked cell by cell against the
//! plannable mask (exact traversal), so they too never cross a wall. [`boundary_pass()`] covers what a plan left uncovered
//! along walls (Pavlíček 2002's extra run along obstacle boundaries).
//!
//! ```
//! use oxcover_grid::{io::parse_ascii, DiscRobot};
//! use oxcover_planners::{find, CoverageProblem, Start};
//!
//! let (map, start) = parse_ascii("S..\n...").unwrap();
//! let robot = DiscRobot::cell_sized(map.resolution());
//! let problem = CoverageProblem::new(&map, robot, Start::Cell(start.unwrap())).unwrap();
//! let plan = find("grid-cover").unwrap().plan(&problem.input(0)).unwrap();
//! let fine = problem.expand(&plan).unwrap();
//! assert_eq!(fine.len(), 6); // a Hamiltonian path: 5 moves
//! ```

pub mod border_expansion;
pub mod boundary_pass;
pub mod bsa;
mod buckets;
mod detours;
pub mod dtc;
pub mod error;
pub mod full_dtc;
pub mod grid_cover;
pub mod lanes;
mod metre_path;
pub mod optimal;
pub mod planner;
pub mod problem;
pub mod pso;
pub mod rect_priority;
pub mod registry;
pub mod room_tour;
mod route;
pub mod smooth;
pub mod stc;
pub mod sweep;
#[cfg(test)]
mod testing;
pub mod time;
pub mod tour;

pub use boundary_pass::{
    BoundaryRoute, boundary_pass, boundary_pass_covered, boundary_tour, boundary_tour_to,
    boundary_tour_to_covered, covered_by,
};
pub use error::{Error, Result};
pub use planner::{Planner, PlannerOptions, steps};
pub use problem::{
    CoverageProblem, PlanOutput, PlannerInput, Start, Transit, coarse_block, largest_region_cell,
    largest_region_start,
};
pub use registry::{build, find, registry};
pub use room_tour::{ANY_UNIT, RoomUnits, room_order, unit_claims, unit_exits, unit_exits_with};
pub use time::TimeModel;
