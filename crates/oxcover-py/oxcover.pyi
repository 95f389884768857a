"""Complete coverage path planning for robots (type stubs of the native module).

Maps in (files or numpy arrays), coverage paths, metrics and pictures out.
Units are metres in the ROS map frame. Errors raise ValueError (bad input),
OSError (a file that cannot be read or written) or RuntimeError (an internal
fault), with the message the `oxcover` command line prints.
"""

import os
import pathlib
from typing import Any, Literal, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

PathLike = Union[str, "os.PathLike[str]"]
Rows = Literal["up", "down"]

class PlannerInfo(TypedDict):
    name: str
    complete: bool
    summary: str

class Map:
    """An occupancy grid placed in the map frame (unknown is never free)."""

    @staticmethod
    def from_array(
        array: npt.NDArray[Any],
        resolution: float,
        origin: Tuple[float, float, float] = (0.0, 0.0, 0.0),
        *,
        rows: Rows = "up",
        free_thresh: float = 0.196,
        occupied_thresh: float = 0.65,
    ) -> "Map":
        """A map from a 2-D array: a bool free mask, or integer occupancy in
        the nav_msgs/OccupancyGrid convention (-1 unknown, 255 in uint8;
        0..100 percent). Row 0 at the origin (rows="up") or at the top
        (rows="down")."""
    @staticmethod
    def from_ros(
        msg: Any, *, free_thresh: float = 0.196, occupied_thresh: float = 0.65
    ) -> "Map":
        """A map from a nav_msgs/msg/OccupancyGrid message (duck-typed)."""
    def to_array(self, *, rows: Rows = "up") -> npt.NDArray[np.int8]:
        """0 free, 100 occupied, -1 unknown (nav_msgs/OccupancyGrid)."""
    def free_mask(self, *, rows: Rows = "up") -> npt.NDArray[np.bool_]: ...
    def counts(self) -> dict[str, int]: ...
    def cell_center(
        self, row: int, column: int, *, rows: Rows = "up"
    ) -> Tuple[float, float]: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def shape(self) -> Tuple[int, int]: ...
    @property
    def resolution(self) -> float: ...
    @property
    def origin(self) -> Tuple[float, float, float]:
        """(x, y, yaw) of the lower-left corner of the bottom-left cell."""
    @property
    def name(self) -> str: ...

class Plan:
    """A coverage plan: the path, its metrics, and what made it."""

    @property
    def path(self) -> npt.NDArray[np.float64]:
        """N×2 waypoints (x, y in metres), read-only."""
    @property
    def metrics(self) -> dict[str, Any]:
        """The contract's metrics (coverage, collisions, length_m, turns,
        est_time_s, bound_time_s, time_efficiency, ...)."""
    @property
    def plan_ms(self) -> float: ...
    @property
    def planner(self) -> str: ...
    @property
    def coverage_without_boundary_pass(self) -> float: ...
    @property
    def room_units(self) -> Optional[int]: ...
    def report(self) -> dict[str, Any]:
        """The JSON report `oxcover plan --report` writes."""
    def to_csv(self) -> str:
        """The path file `oxcover plan --out` writes, byte for byte."""
    def to_png(self) -> bytes: ...
    def to_svg(self) -> str: ...
    def write(
        self,
        *,
        out: Optional[PathLike] = None,
        svg: Optional[PathLike] = None,
        png: Optional[PathLike] = None,
        report: Optional[PathLike] = None,
        bag: Optional[PathLike] = None,
    ) -> list[pathlib.Path]:
        """Writes the files all or none; returns the paths written. `bag` is
        a ROS 2 bag (MCAP): /map, /coverage_path, /rooms, /coverage_targets."""
    def __len__(self) -> int: ...

def load_map(
    path: PathLike,
    *,
    resolution: Optional[float] = None,
    free_thresh: Optional[float] = None,
    occupied_thresh: Optional[float] = None,
    negate: bool = False,
    topic: Optional[str] = None,
    message: Union[int, str, None] = None,
) -> Map:
    """Reads a ROS yaml (+ PGM/PNG/BMP), a PGM/PNG/BMP image, a MovingAI
    .map, or a rosbag2 bag (folder, .mcap or .db3: the OccupancyGrid message
    `topic` and `message` ("last", "first" or a number from 0) pick);
    `resolution` places an image read without a yaml, and `free_thresh`,
    `occupied_thresh` and `negate` (map_server's fields) classify its
    pixels."""

def planners() -> list[PlannerInfo]: ...
def plan(
    map: Map,
    planner: str,
    *,
    robot_radius: float = 0.0,
    tool_radius: Optional[float] = None,
    start: Optional[Tuple[float, float]] = None,
    seed: int = 0,
    boundary_pass: bool = True,
    rooms: bool = True,
    speed: float = 0.3,
    turn_rate: float = 0.52,
    sweep_angle: Optional[float] = None,
    memory_limit: Union[str, int, None] = "auto",
    zones: Optional[PathLike] = None,
    keep_out: Optional[PathLike] = None,
    rooms_only: Optional[Sequence[int]] = None,
    room_order: Literal["fastest", "given"] = "fastest",
    done: Union[PathLike, npt.ArrayLike, None] = None,
    spot: Optional[Tuple[float, float, float]] = None,
    clearance: float = 0.0,
) -> Plan:
    """Plans a coverage path, as `oxcover plan MAP --planner NAME`; the
    target keywords are the command line's `--zones`, `--keep-out`,
    `--rooms-only`, `--room-order`, `--done`, `--spot`, `--clearance`."""

def evaluate(
    map: Map,
    path: Union[PathLike, npt.ArrayLike],
    *,
    robot_radius: float = 0.0,
    tool_radius: Optional[float] = None,
    speed: float = 0.3,
    turn_rate: float = 0.52,
    zones: Optional[PathLike] = None,
    keep_out: Optional[PathLike] = None,
    rooms_only: Optional[Sequence[int]] = None,
    done: Union[PathLike, npt.ArrayLike, None] = None,
    spot: Optional[Tuple[float, float, float]] = None,
    clearance: float = 0.0,
) -> dict[str, Any]:
    """The contract's metrics of a path (CSV file or N×2 array), against
    the same targets as `oxcover eval` with the same options."""

def segment(
    map: Map,
    *,
    method: Literal["doorways", "voronoi", "morphological"] = "doorways",
    min_area: float = 1.0,
    max_area: float = 47.0,
    door_width: float = 1.6,
    rows: Rows = "up",
) -> dict[str, Any]:
    """Rooms: `labels` (uint32 array) and `oxcover segment`'s JSON keys."""

def simulate(
    plan: Plan,
    *,
    robot_spec: Optional[PathLike] = None,
    controller: Literal["klancar", "kanayama"] = "klancar",
    dt: float = 0.02,
    odometry_noise: float = 0.0,
) -> dict[str, Any]:
    """A plan executed in closed loop: `samples` (N×7, read-only),
    `columns`, `metrics`, `report`, `warning`."""

def explore(
    world: PathLike,
    *,
    robot_radius: float = 0.2,
    tool_radius: float = 0.25,
    margin: float = 0.04,
    rays: int = 180,
    max_range: float = 3.0,
    noise: float = 0.0,
    seed: int = 0,
    start: Optional[Tuple[float, float]] = None,
    algorithm: Literal["cycles", "paper"] = "cycles",
) -> dict[str, Any]:
    """Sensor-based coverage of a polygonal world: `path`, `states`,
    `graph`, `metrics`, `report`, `map`."""
