"""The Python package against the command line: same paths, same metrics,
same messages; numpy round trips; threads; determinism."""

import json
import pathlib
import threading
import time

import numpy as np
import pytest

import oxcover
from conftest import BUNDLED_MAPS, ROOT, cli_error

PLANNERS = [p["name"] for p in oxcover.planners()]
# A robot of 0.15 m on the metre-scale maps; unit-cell MovingAI maps get a
# tool of one cell.
ROBOT = {"robot_radius": 0.15, "tool_radius": 0.15}


def robot_for(map_path):
    return {} if map_path.endswith(".map") else ROBOT


def flags(kwargs):
    out = []
    for k, v in kwargs.items():
        out += ["--" + k.replace("_", "-"), str(v)]
    return out


def test_planners_match_the_command_line(cli):
    listed = [line.split()[0] for line in cli("planners").stdout.splitlines()[1:] if line.strip()]
    assert PLANNERS == [name for name in listed if name != "sensor-bcd"]
    assert "lanes" in PLANNERS and len(PLANNERS) >= 12


@pytest.mark.parametrize("planner", PLANNERS)
@pytest.mark.parametrize("map_path", BUNDLED_MAPS)
def test_same_path_as_the_command_line(cli, tmp_path, map_path, planner):
    """Byte-identical path file, or the same one-line refusal."""
    kwargs = robot_for(map_path)
    out = tmp_path / "cli.csv"
    done = cli("plan", map_path, "--planner", planner, "--out", out, *flags(kwargs))
    m = oxcover.load_map(map_path)
    if done.returncode != 0:
        with pytest.raises(ValueError) as e:
            oxcover.plan(m, planner, **kwargs)
        assert str(e.value) == cli_error(done)
        return
    p = oxcover.plan(m, planner, **kwargs)
    assert p.to_csv() == out.read_text()
    # The array holds the same waypoints as the file.
    rows = np.loadtxt(out, delimiter=",", skiprows=1, ndmin=2)
    assert p.path.shape == rows.shape and p.path.dtype == np.float64
    assert np.array_equal(p.path, rows)
    assert len(p) == rows.shape[0]


@pytest.mark.parametrize(
    "image, resolution",
    [
        ("fixtures/maps/pythonrobotics/test.png", 0.1),
        ("fixtures/maps/lee2011/living.pgm", 0.05),
        ("fixtures/fuzz/seeds/bmp/wall.bmp", 0.5),
    ],
)
def test_plain_images_load_as_on_the_command_line(cli, tmp_path, image, resolution):
    """PNG, PGM and BMP read without a yaml, placed by `resolution`."""
    out = tmp_path / "cli.csv"
    done = cli("plan", image, "--planner", "boustrophedon", "--resolution", resolution, "--out", out)
    m = oxcover.load_map(image, resolution=resolution)
    assert m.resolution == resolution and m.origin == (0.0, 0.0, 0.0)
    if done.returncode != 0:
        with pytest.raises(ValueError) as e:
            oxcover.plan(m, "boustrophedon")
        assert str(e.value) == cli_error(done)
        return
    assert oxcover.plan(m, "boustrophedon").to_csv() == out.read_text()


def test_images_are_classified_as_on_the_command_line(cli, tmp_path):
    """`free_thresh`, `occupied_thresh` and `negate` read an image as the
    command line's flags do; given for a yaml they are refused alike, and
    a resolution a yaml does not use is a warning where the command line
    prints a note."""
    image = tmp_path / "plan.pgm"
    image.write_bytes(b"P5\n6 1\n255\n" + bytes([0, 230, 251, 255, 128, 250]))
    for kwargs in [{}, {"free_thresh": 0.018, "occupied_thresh": 0.018}, {"negate": True}]:
        args = ["--negate"] if kwargs.get("negate") else flags(kwargs)
        out = tmp_path / "cli.csv"
        done = cli("plan", image, "--planner", "dtc", "--out", out, *args)
        assert done.returncode == 0, done.stderr
        m = oxcover.load_map(image, **kwargs)
        assert oxcover.plan(m, "dtc").to_csv() == out.read_text()
    free = oxcover.load_map(image, free_thresh=0.018, occupied_thresh=0.018).free_mask()
    assert free.tolist() == [[False, False, True, True, False, False]]
    yaml = "fixtures/maps/turtlebot_simulator/simple_rooms.yaml"
    done = cli("info", yaml, "--free-thresh", "0.01")
    with pytest.raises(ValueError) as e:
        oxcover.load_map(yaml, free_thresh=0.01)
    assert str(e.value) == cli_error(done)
    with pytest.warns(UserWarning, match="is for images read without a yaml"):
        m = oxcover.load_map(yaml, resolution=2.0)
    assert m.resolution == 0.05


def test_an_exact_search_runs_the_same_from_python(cli, tmp_path):
    """`optimal` refuses the maps above at their sizes; here it plans."""
    args = {"tool_radius": 2.0}
    out = tmp_path / "cli.csv"
    done = cli("plan", "fixtures/maps/movingai/room-32-32-4.map", "--planner", "optimal",
               "--out", out, *flags(args))
    assert done.returncode == 0, done.stderr
    p = oxcover.plan(oxcover.load_map("fixtures/maps/movingai/room-32-32-4.map"), "optimal", **args)
    assert p.to_csv() == out.read_text()


def test_options_reach_the_pipeline_as_on_the_command_line(cli, tmp_path):
    args = {
        "robot_radius": 0.1, "tool_radius": 0.2, "start": "1.0,1.0", "seed": 7,
        "boundary_pass": "off", "rooms": "off", "speed": 0.5, "turn_rate": 1.0,
        "sweep_angle": 30,
    }
    out, report = tmp_path / "cli.csv", tmp_path / "cli.json"
    done = cli("plan", "crates/oxcover/assets/simple_rooms.yaml", "--planner", "boustrophedon",
               "--out", out, "--report", report, *flags(args))
    assert done.returncode == 0, done.stderr
    m = oxcover.load_map("crates/oxcover/assets/simple_rooms.yaml")
    p = oxcover.plan(m, "boustrophedon", robot_radius=0.1, tool_radius=0.2, start=(1.0, 1.0),
                     seed=7, boundary_pass=False, rooms=False, speed=0.5, turn_rate=1.0,
                     sweep_angle=30)
    assert p.to_csv() == out.read_text()
    theirs, ours = json.loads(report.read_text()), p.report()
    assert theirs.pop("plan_ms") > 0 and ours.pop("plan_ms") == p.plan_ms
    assert ours == theirs
    # The report carries the metrics at its top level.
    assert p.metrics == {k: theirs[k] for k in p.metrics}


def test_write_makes_the_command_lines_files(cli, tmp_path):
    m = oxcover.load_map("fixtures/maps/lee2011/living.yaml")
    p = oxcover.plan(m, "lanes", **ROBOT)
    written = p.write(out=tmp_path / "a.csv", png=tmp_path / "a.png", svg=tmp_path / "a.svg")
    assert sorted(pathlib.Path(w).name for w in written) == ["a.csv", "a.png", "a.svg"]
    done = cli("plan", "fixtures/maps/lee2011/living.yaml", "--planner", "lanes",
               "--out", tmp_path / "b.csv", "--png", tmp_path / "b.png",
               "--svg", tmp_path / "b.svg", *flags(ROBOT))
    assert done.returncode == 0, done.stderr
    for ext in ["csv", "png", "svg"]:
        assert (tmp_path / f"a.{ext}").read_bytes() == (tmp_path / f"b.{ext}").read_bytes(), ext
    assert p.to_png() == (tmp_path / "b.png").read_bytes()
    assert p.to_svg() == (tmp_path / "b.svg").read_text()
    assert p.to_png()[:8] == b"\x89PNG\r\n\x1a\n"


def test_evaluate_matches_eval(cli, tmp_path):
    m = oxcover.load_map("fixtures/maps/nav2/turtlebot3_world.yaml")
    p = oxcover.plan(m, "boustrophedon", **ROBOT)
    (tmp_path / "p.csv").write_text(p.to_csv())
    done = cli("eval", "fixtures/maps/nav2/turtlebot3_world.yaml", tmp_path / "p.csv",
               *flags(ROBOT))
    assert done.returncode == 0, done.stderr
    theirs = json.loads(done.stdout)
    assert oxcover.evaluate(m, tmp_path / "p.csv", **ROBOT) == theirs
    assert oxcover.evaluate(m, p.path, **ROBOT) == theirs
    assert oxcover.evaluate(m, p.path.tolist(), **ROBOT) == theirs
    assert p.metrics == theirs
    assert {"coverage", "collisions", "est_time_s", "bound_time_s", "time_efficiency"} <= set(theirs)


def test_segment_matches_the_command_line(cli, tmp_path):
    done = cli("segment", "fixtures/maps/turtlebot_simulator/simple_rooms.yaml",
               "--out", tmp_path / "rooms.json")
    assert done.returncode == 0, done.stderr
    theirs = json.loads((tmp_path / "rooms.json").read_text())
    m = oxcover.load_map("fixtures/maps/turtlebot_simulator/simple_rooms.yaml")
    ours = oxcover.segment(m)
    labels = ours.pop("labels")
    assert ours == theirs
    assert labels.shape == m.shape and labels.dtype == np.uint32
    assert theirs["seeded"] >= 2
    assert theirs["method"] == "doorways"
    # Every free cell has a room; the labels are the report's rooms.
    free = m.free_mask()
    assert ((labels > 0) == free).all()
    assert sorted(set(np.unique(labels)) - {0}) == sorted(r["label"] for r in theirs["rooms"])
    area = m.resolution ** 2
    for r in theirs["rooms"]:
        assert (labels == r["label"]).sum() * area == pytest.approx(r["area_m2"])


def test_simulate_matches_the_command_line(cli, tmp_path):
    out = tmp_path / "run.csv"
    done = cli("simulate", "fixtures/maps/lee2011/living.yaml", "--planner", "boustrophedon",
               "--odometry-noise", "0.01", "--seed", "3", "--out", out, *flags(ROBOT))
    assert done.returncode == 0, done.stderr
    m = oxcover.load_map("fixtures/maps/lee2011/living.yaml")
    # `oxcover simulate` plans with the robot's tracking margin (0.02 m)
    # plus half a cell as clearance.
    p = oxcover.plan(m, "boustrophedon", seed=3, clearance=0.02 + 0.05 / 2.0, **ROBOT)
    run = oxcover.simulate(p, odometry_noise=0.01)
    rows = np.loadtxt(out, delimiter=",", skiprows=1)
    assert out.read_text().splitlines()[0].split(",") == run["columns"]
    assert np.array_equal(run["samples"], rows)
    # The same warning as the command line's, if any.
    warned = [l.removeprefix("warning: ") for l in done.stderr.splitlines() if l.startswith("warning: ")]
    assert run["warning"] == (warned[0] if warned else None)
    assert run["metrics"]["coverage"] > 0.9
    assert not run["samples"].flags.writeable
    # The plan's seed drives the noise, as --seed does on the command line.
    other = oxcover.simulate(
        oxcover.plan(m, "boustrophedon", seed=4, clearance=0.02 + 0.05 / 2.0, **ROBOT),
        odometry_noise=0.01,
    )
    assert not np.array_equal(other["samples"], run["samples"])
    assert run["report"]["planner"] == "boustrophedon"


def test_explore_matches_the_command_line(cli, tmp_path):
    world = "fixtures/worlds/demir2018/fig11_octagon.ron"
    out = tmp_path / "trace.csv"
    done = cli("explore", world, "--out", out)
    assert done.returncode == 0, done.stderr
    res = oxcover.explore(world)
    rows = np.loadtxt(out, delimiter=",", skiprows=1)
    assert np.array_equal(res["path"], rows[:, :2])
    assert np.array_equal(res["states"], rows[:, 2].astype(np.uint8))
    assert res["report"]["complete"] and res["metrics"]["coverage"] > 0.99
    assert isinstance(res["map"], oxcover.Map) and res["graph"]["nodes"]
    # The seed's own algorithm, as `--algorithm paper`.
    done = cli("explore", world, "--algorithm", "paper", "--out", out)
    assert done.returncode == 0, done.stderr
    seed = oxcover.explore(world, algorithm="paper")
    rows = np.loadtxt(out, delimiter=",", skiprows=1)
    assert np.array_equal(seed["path"], rows[:, :2])
    assert seed["report"]["cycles"] == 0


# ---- numpy round trips ---------------------------------------------------


def test_occupancy_grid_round_trip_plans_the_same_path():
    """A map sent as a nav_msgs/OccupancyGrid (int8, row 0 at the origin)
    plans exactly as the map file."""
    m = oxcover.load_map("fixtures/maps/nav2/turtlebot3_world.yaml")
    data = m.to_array()
    assert data.dtype == np.int8 and data.shape == m.shape
    assert set(np.unique(data)) <= {-1, 0, 100}
    # As a ROS 2 node receives it: a flat int8 sequence, reshaped.
    msg_data = data.ravel().tolist()
    received = np.asarray(msg_data, dtype=np.int8).reshape(m.height, m.width)
    again = oxcover.Map.from_array(received, m.resolution, m.origin)
    assert np.array_equal(again.to_array(), data)
    assert oxcover.plan(again, "lanes", **ROBOT).to_csv() == oxcover.plan(m, "lanes", **ROBOT).to_csv()
    # Other integer widths and uint8 (255 = unknown) give the same map.
    for arr in [received.astype(np.int64), received.astype(np.int16),
                received.astype(np.uint8)]:
        assert np.array_equal(oxcover.Map.from_array(arr, m.resolution, m.origin).to_array(), data)


def occupancy_grid_msg(m, yaw):
    """A nav_msgs/msg/OccupancyGrid as rclpy delivers it (duck-typed: no ROS
    here): int8 data as a flat array, the origin's yaw as a quaternion."""
    from types import SimpleNamespace as NS

    x, y, _ = m.origin
    return NS(
        header=NS(frame_id="map"),
        info=NS(
            resolution=m.resolution,
            width=m.width,
            height=m.height,
            origin=NS(position=NS(x=x, y=y, z=0.0),
                      orientation=NS(x=0.0, y=0.0, z=np.sin(yaw / 2), w=np.cos(yaw / 2))),
        ),
        data=m.to_array().ravel().tolist(),
    )


def test_a_ros_occupancy_grid_message_plans_as_the_map_file(tmp_path):
    m = oxcover.load_map("fixtures/maps/nav2/turtlebot3_world.yaml")
    received = oxcover.Map.from_ros(occupancy_grid_msg(m, 0.0))
    assert received.origin == m.origin and received.shape == m.shape
    assert oxcover.plan(received, "lanes", **ROBOT).to_csv() == oxcover.plan(m, "lanes", **ROBOT).to_csv()
    turned = oxcover.Map.from_ros(occupancy_grid_msg(m, 0.6))
    assert turned.origin[2] == pytest.approx(0.6, abs=1e-12)
    msg = occupancy_grid_msg(m, 0.0)
    msg.data = msg.data[:-1]
    with pytest.raises(ValueError, match="info.width × info.height"):
        oxcover.Map.from_ros(msg)
    del msg.info.resolution
    with pytest.raises(ValueError, match="without `info.resolution`"):
        oxcover.Map.from_ros(msg)


def test_rows_up_is_the_ros_order_and_down_the_image_order():
    # 3 rows, 4 columns: only the bottom-left cell (row 0 up) is free.
    grid = np.full((3, 4), 100, dtype=np.int8)
    grid[0, 0] = 0
    up = oxcover.Map.from_array(grid, 0.5, (1.0, 2.0, 0.0))
    assert up.cell_center(0, 0) == (1.25, 2.25)
    assert up.counts() == {"free": 1, "occupied": 11, "unknown": 0}
    down = oxcover.Map.from_array(np.flipud(grid), 0.5, (1.0, 2.0, 0.0), rows="down")
    assert np.array_equal(down.to_array(), up.to_array())
    assert np.array_equal(up.to_array(rows="down"), np.flipud(grid))
    assert up.cell_center(2, 0, rows="down") == (1.25, 2.25)


def test_bool_mask_and_thresholds():
    mask = np.zeros((5, 6), dtype=bool)
    mask[1:4, 1:5] = True
    m = oxcover.Map.from_array(mask, 1.0)
    assert np.array_equal(m.free_mask(), mask)
    assert m.counts() == {"free": 12, "occupied": 18, "unknown": 0}
    # map_server's thresholds: below 19.6 % free, above 65 % occupied.
    values = np.array([[0, 19, 20, 50, 65, 66, 100, -1]], dtype=np.int8)
    t = oxcover.Map.from_array(values, 1.0).to_array()
    assert t.tolist() == [[0, 0, -1, -1, -1, 100, 100, -1]]
    t = oxcover.Map.from_array(values, 1.0, free_thresh=0.5, occupied_thresh=0.5).to_array()
    assert t.tolist() == [[0, 0, 0, -1, 100, 100, 100, -1]]


def test_yaw_matches_a_yaml_with_the_same_origin(tmp_path):
    image = (ROOT / "fixtures/maps/lee2011/living.pgm").resolve()
    yaml = tmp_path / "rotated.yaml"
    yaml.write_text(
        f"image: {image}\nresolution: 0.05\norigin: [1.5, -2.0, 0.6]\n"
        "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    from_file = oxcover.load_map(yaml)
    assert from_file.origin == (1.5, -2.0, 0.6)
    from_array = oxcover.Map.from_array(from_file.to_array(), 0.05, (1.5, -2.0, 0.6))
    assert from_array.origin == (1.5, -2.0, 0.6)
    assert from_array.cell_center(0, 0) == from_file.cell_center(0, 0)
    a = oxcover.plan(from_file, "boustrophedon", **ROBOT)
    b = oxcover.plan(from_array, "boustrophedon", **ROBOT)
    assert a.to_csv() == b.to_csv()
    # The path really is in the rotated frame: its bounding box is not the
    # unrotated one's.
    flat = oxcover.plan(oxcover.Map.from_array(from_file.to_array(), 0.05, (1.5, -2.0, 0.0)),
                        "boustrophedon", **ROBOT)

    def box(p):
        return np.concatenate([p.min(axis=0), p.max(axis=0)])

    assert not np.allclose(box(a.path), box(flat.path))


def test_path_array_is_read_only_and_owned():
    p = oxcover.plan(oxcover.load_map("fixtures/maps/lee2011/living.yaml"), "dtc", **ROBOT)
    assert not p.path.flags.writeable and p.path.flags.c_contiguous
    with pytest.raises(ValueError):
        p.path[0, 0] = 1.0
    q = p.path.copy()
    q[0, 0] = 1.0
    assert p.path[0, 0] != 1.0 or q[0, 0] == p.path[0, 0]


# ---- bad input: the command line's message, as an exception ------------


@pytest.mark.parametrize(
    "cli_args, call, exc",
    [
        (["plan", "nope.yaml", "--planner", "dtc"],
         lambda: oxcover.load_map("nope.yaml"), OSError),
        (["plan", "fixtures/maps/lee2011/living.yaml", "--planner", "nope"],
         lambda: oxcover.plan(oxcover.load_map("fixtures/maps/lee2011/living.yaml"), "nope"),
         ValueError),
        (["plan", "fixtures/maps/lee2011/living.yaml", "--planner", "sensor-bcd"],
         lambda: oxcover.plan(oxcover.load_map("fixtures/maps/lee2011/living.yaml"), "sensor-bcd"),
         ValueError),
        (["plan", "fixtures/maps/lee2011/living.yaml", "--planner", "dtc", "--robot-radius", "-1"],
         lambda: oxcover.plan(oxcover.load_map("fixtures/maps/lee2011/living.yaml"), "dtc",
                              robot_radius=-1), ValueError),
        (["plan", "fixtures/maps/lee2011/living.yaml", "--planner", "dtc", "--tool-radius", "nan"],
         lambda: oxcover.plan(oxcover.load_map("fixtures/maps/lee2011/living.yaml"), "dtc",
                              tool_radius=float("nan")), ValueError),
        (["plan", "fixtures/maps/lee2011/living.yaml", "--planner", "dtc", "--start", "-50,-50"],
         lambda: oxcover.plan(oxcover.load_map("fixtures/maps/lee2011/living.yaml"), "dtc",
                              start=(-50, -50)), ValueError),
        (["plan", "fixtures/maps/lee2011/living.yaml", "--planner", "dtc", "--speed", "0"],
         lambda: oxcover.plan(oxcover.load_map("fixtures/maps/lee2011/living.yaml"), "dtc",
                              speed=0), ValueError),
        (["plan", "fixtures/maps/lee2011/living.yaml", "--planner", "dtc", "--memory-limit", "1K"],
         lambda: oxcover.plan(oxcover.load_map("fixtures/maps/lee2011/living.yaml"), "dtc",
                              memory_limit="1K"), ValueError),
        (["plan", "fixtures/maps/lee2011/living.yaml", "--planner", "dtc", "--memory-limit", "lots"],
         lambda: oxcover.plan(oxcover.load_map("fixtures/maps/lee2011/living.yaml"), "dtc",
                              memory_limit="lots"), ValueError),
        (["plan", "fixtures/maps/pythonrobotics/test.png", "--planner", "dtc", "--resolution", "0"],
         lambda: oxcover.load_map("fixtures/maps/pythonrobotics/test.png", resolution=0), ValueError),
        (["segment", "fixtures/maps/lee2011/living.yaml", "--door-width", "-1"],
         lambda: oxcover.segment(oxcover.load_map("fixtures/maps/lee2011/living.yaml"),
                                 door_width=-1), ValueError),
        (["simulate", "fixtures/maps/lee2011/living.yaml", "--planner", "dtc", "--dt", "5"],
         lambda: oxcover.simulate(oxcover.plan(oxcover.load_map("fixtures/maps/lee2011/living.yaml"),
                                               "dtc"), dt=5), ValueError),
        (["simulate", "fixtures/maps/lee2011/living.yaml", "--planner", "dtc", "--robot-spec",
          "nope.ron"],
         lambda: oxcover.simulate(oxcover.plan(oxcover.load_map("fixtures/maps/lee2011/living.yaml"),
                                               "dtc"), robot_spec="nope.ron"), OSError),
        (["explore", "nope.ron"], lambda: oxcover.explore("nope.ron"), OSError),
    ],
)
def test_bad_input_raises_with_the_command_lines_message(cli, cli_args, call, exc):
    expected = cli_error(cli(*cli_args))
    with pytest.raises(exc) as e:
        call()
    assert str(e.value) == expected


def test_bad_files_raise_with_the_command_lines_message(cli, tmp_path):
    bad_yaml = tmp_path / "bad.yaml"
    bad_yaml.write_text("image: missing.pgm\nresolution: -3\norigin: [0, 0, 0]\n")
    with pytest.raises(ValueError) as e:
        oxcover.load_map(bad_yaml)
    assert str(e.value) == cli_error(cli("info", bad_yaml))
    bad_csv = tmp_path / "bad.csv"
    bad_csv.write_text("x,y\n1,2\nthree,4\n")
    m = oxcover.load_map("fixtures/maps/lee2011/living.yaml")
    with pytest.raises(ValueError) as e:
        oxcover.evaluate(m, bad_csv)
    assert str(e.value) == cli_error(cli("eval", "fixtures/maps/lee2011/living.yaml", bad_csv))
    p = oxcover.plan(m, "dtc", **ROBOT)
    missing = tmp_path / "no" / "such" / "folder.csv"
    with pytest.raises(ValueError) as e:
        p.write(out=missing)
    assert str(e.value) == cli_error(
        cli("plan", "fixtures/maps/lee2011/living.yaml", "--planner", "dtc", "--out", missing))
    with pytest.raises(ValueError) as e:
        p.write(png=tmp_path / "picture.svg")
    assert "--png" in str(e.value) and ".png" in str(e.value)
    assert not (tmp_path / "picture.svg").exists()


@pytest.mark.parametrize(
    "array, kwargs, words",
    [
        (np.zeros((2, 2, 2), dtype=bool), {}, "2-D"),
        (np.zeros((0, 3), dtype=bool), {}, "at least one cell"),
        (np.zeros((2, 2), dtype=np.float32), {}, "dtype"),
        (np.array([[0, 101]], dtype=np.int16), {}, "101 at row 0, column 1"),
        (np.array([[0, 200]], dtype=np.uint8), {}, "200 at row 0, column 1"),
        (np.zeros((2, 2), dtype=bool), {"resolution": 0.0}, "resolution"),
        (np.zeros((2, 2), dtype=bool), {"origin": (0, float("inf"), 0)}, "origin"),
        (np.zeros((2, 2), dtype=bool), {"rows": "sideways"}, "rows"),
        (np.zeros((2, 2), dtype=np.int8), {"free_thresh": 0.9}, "free_thresh"),
        ([[True, False]], {}, "numpy array"),
    ],
)
def test_bad_arrays_raise_value_errors_naming_what_is_wrong(array, kwargs, words):
    args = {"resolution": 0.05, **kwargs}
    resolution = args.pop("resolution")
    with pytest.raises(ValueError) as e:
        oxcover.Map.from_array(array, resolution, **args)
    assert words in str(e.value)
    assert "\n" not in str(e.value)


def test_bad_paths_for_evaluate():
    m = oxcover.load_map("fixtures/maps/lee2011/living.yaml")
    for path, words in [(np.zeros((3, 3)), "3×3"), ([[0.0, float("nan")]], "finite"),
                        ("nope.csv", "nope.csv")]:
        with pytest.raises((ValueError, OSError)) as e:
            oxcover.evaluate(m, path)
        assert words in str(e.value)


def test_bad_keyword_is_a_type_error():
    m = oxcover.load_map("fixtures/maps/lee2011/living.yaml")
    with pytest.raises(TypeError):
        oxcover.plan(m, "dtc", tool_radiu=0.2)


# ---- threads and determinism -------------------------------------------


def test_two_threads_plan_at_once_and_get_the_sequential_results():
    m = oxcover.load_map("crates/oxcover/assets/simple_rooms.yaml")
    jobs = [("smooth", 0.15), ("trapezoidal", 0.15)]
    sequential = [oxcover.plan(m, name, tool_radius=t).to_csv() for name, t in jobs]
    results = [None, None]
    ticks = []

    def work(i):
        name, t = jobs[i]
        results[i] = oxcover.plan(m, name, tool_radius=t).to_csv()

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for th in threads:
        th.start()
    # Python keeps running while both plan: the GIL is released.
    while any(th.is_alive() for th in threads):
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    for th in threads:
        th.join()
    assert results == sequential
    assert len(ticks) > 50, f"the main thread ran only {len(ticks)} times while planning"


def test_same_seed_same_output():
    m = oxcover.load_map("fixtures/maps/lee2011/office.yaml")
    a = oxcover.plan(m, "smooth", seed=5, **ROBOT)
    b = oxcover.plan(m, "smooth", seed=5, **ROBOT)
    assert a.to_csv() == b.to_csv() and a.metrics == b.metrics


def test_help_is_useful():
    assert "planner" in oxcover.plan.__doc__ and "GIL" in oxcover.plan.__doc__
    assert oxcover.plan.__text_signature__.startswith("(map, planner, *, robot_radius=0.0")
    assert "nav_msgs/OccupancyGrid" in oxcover.Map.from_array.__doc__
    assert oxcover.__version__
