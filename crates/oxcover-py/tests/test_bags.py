"""ROS 2 bags checked with readers we did not write: a plan's MCAP read by
`rosbags` and by `mcap` with `mcap-ros2-support` gives the CSV path point
for point, stamps that never decrease and end `est_time_s` after the first,
and the map cell for cell; bags written by `rosbags` (mcap and sqlite3
storage) holding turtlebot3_world plan to the yaml map's path byte for
byte, for every complete planner; Python reads and writes the same bags
as the command line."""

import csv
import json

import numpy as np
import pytest

import oxcover
from conftest import ROOT

rosbags_highlevel = pytest.importorskip("rosbags.highlevel")
rosbags_rosbag2 = pytest.importorskip("rosbags.rosbag2")
rosbags_typesys = pytest.importorskip("rosbags.typesys")
mcap_reader = pytest.importorskip("mcap.reader")
mcap_ros2_decoder = pytest.importorskip("mcap_ros2.decoder")

MAP = "fixtures/maps/nav2/turtlebot3_world.yaml"
TYPESTORE = rosbags_typesys.get_typestore(rosbags_typesys.Stores.ROS2_HUMBLE)


def stamp_s(stamp):
    return stamp.sec + stamp.nanosec * 1e-9


def read_with_rosbags(path):
    """{topic: [decoded message, ...]} by rosbags' AnyReader."""
    out = {}
    with rosbags_highlevel.AnyReader([path], default_typestore=TYPESTORE) as reader:
        for conn, _, raw in reader.messages():
            out.setdefault(conn.topic, []).append(reader.deserialize(raw, conn.msgtype))
    return out


def read_with_mcap(path):
    """{topic: [decoded message, ...]} by mcap + mcap-ros2-support, which
    decode with the schemas the file carries."""
    out = {}
    with open(path, "rb") as f:
        reader = mcap_reader.make_reader(f, decoder_factories=[mcap_ros2_decoder.DecoderFactory()])
        for _, channel, _, decoded in reader.iter_decoded_messages():
            out.setdefault(channel.topic, []).append(decoded)
    return out


@pytest.fixture(scope="module")
def plan_bag(tmp_path_factory, cli):
    d = tmp_path_factory.mktemp("bag")
    paths = {k: d / f"plan.{k}" for k in ("csv", "json", "mcap")}
    done = cli("plan", MAP, "--planner", "lanes", "--out", paths["csv"], "--report",
               paths["json"], "--bag", paths["mcap"])
    assert done.returncode == 0, done.stderr
    return paths


@pytest.mark.parametrize("reader", [read_with_rosbags, read_with_mcap])
def test_independent_readers_agree_with_the_csv_report_and_map(plan_bag, reader):
    topics = reader(plan_bag["mcap"])
    assert sorted(topics) == ["/coverage_path", "/map", "/rooms"]
    path = topics["/coverage_path"][0]
    assert path.header.frame_id == "map"
    with open(plan_bag["csv"]) as f:
        rows = [(float(r["x"]), float(r["y"])) for r in csv.DictReader(f)]
    got = [(p.pose.position.x, p.pose.position.y) for p in path.poses]
    assert got == rows, "the path, point for point"
    stamps = [stamp_s(p.header.stamp) for p in path.poses]
    assert all(b >= a for a, b in zip(stamps, stamps[1:]))
    est = json.loads(plan_bag["json"].read_text())["est_time_s"]
    assert abs((stamps[-1] - stamps[0]) - est) <= 1e-3 * est
    # Each pose faces along the path: its heading is that of its next move.
    p0, p1 = path.poses[0].pose, path.poses[1].pose
    yaw = 2 * np.arctan2(p0.orientation.z, p0.orientation.w)
    move = np.arctan2(p1.position.y - p0.position.y, p1.position.x - p0.position.x)
    assert abs(np.angle(np.exp(1j * (yaw - move)))) < 1e-9
    grid = topics["/map"][0]
    want = oxcover.load_map(MAP)
    assert (grid.info.width, grid.info.height) == (want.width, want.height)
    cells = np.asarray(grid.data, dtype=np.int8).reshape(grid.info.height, grid.info.width)
    assert np.array_equal(cells, want.to_array(rows="up")), "the map, cell for cell"
    assert abs(grid.info.resolution - 0.05) < 1e-7
    rooms = topics["/rooms"][0]
    assert any(m.text == "1" for m in rooms.markers)


def test_simulate_odometry_reads_in_rosbags(cli, tmp_path):
    bag = tmp_path / "sim.mcap"
    done = cli("simulate", "fixtures/maps/lee2011/living.yaml", "--planner", "lanes", "--bag", bag)
    assert done.returncode == 0, done.stderr
    odom = read_with_rosbags(bag)["/odom"]
    stamps = [stamp_s(o.header.stamp) for o in odom]
    assert len(odom) > 100 and all(b > a for a, b in zip(stamps, stamps[1:]))
    assert odom[0].child_frame_id == "base_link"


def write_rosbags_bag(path, storage):
    """The bundled turtlebot3_world map as one OccupancyGrid message, written
    by rosbags with `storage` (mcap or sqlite3)."""
    m = oxcover.load_map(MAP)
    t = TYPESTORE.types
    header = t["std_msgs/msg/Header"](stamp=t["builtin_interfaces/msg/Time"](sec=5, nanosec=0), frame_id="map")
    origin = t["geometry_msgs/msg/Pose"](
        position=t["geometry_msgs/msg/Point"](x=-10.0, y=-10.0, z=0.0),
        orientation=t["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
    )
    info = t["nav_msgs/msg/MapMetaData"](
        map_load_time=header.stamp, resolution=0.05, width=m.width, height=m.height, origin=origin)
    msg = t["nav_msgs/msg/OccupancyGrid"](header=header, info=info, data=m.to_array(rows="up").ravel())
    plugin = {"mcap": rosbags_rosbag2.StoragePlugin.MCAP, "sqlite3": rosbags_rosbag2.StoragePlugin.SQLITE3}
    with rosbags_rosbag2.Writer(path, version=9, storage_plugin=plugin[storage]) as w:
        chatter = w.add_connection("/chatter", "std_msgs/msg/String", typestore=TYPESTORE)
        for i in range(20):
            data = TYPESTORE.serialize_cdr(t["std_msgs/msg/String"](data=f"hello {i}"), "std_msgs/msg/String")
            w.write(chatter, i * 1_000_000, data)
        conn = w.add_connection("/map", "nav_msgs/msg/OccupancyGrid", typestore=TYPESTORE)
        w.write(conn, 5_000_000_000, TYPESTORE.serialize_cdr(msg, "nav_msgs/msg/OccupancyGrid"))


COMPLETE = sorted(p["name"] for p in oxcover.planners() if p["complete"])


@pytest.fixture(scope="module")
def rosbags_bags(tmp_path_factory):
    d = tmp_path_factory.mktemp("rosbags")
    bags = {}
    for storage in ("mcap", "sqlite3"):
        folder = d / storage
        write_rosbags_bag(folder, storage)
        bags[storage] = folder
    return bags


@pytest.mark.parametrize("planner", COMPLETE)
def test_rosbags_bags_plan_to_the_yaml_maps_path(cli, tmp_path, rosbags_bags, planner):
    outs = {}
    for name, source in [("yaml", MAP), *sorted(rosbags_bags.items())]:
        out = tmp_path / f"{name}.csv"
        done = cli("plan", source, "--planner", planner, "--out", out)
        # A planner that refuses the map refuses it from every source alike.
        outs[name] = (done.returncode, out.read_bytes() if out.exists() else done.stderr.split(": ")[-1])
    assert outs["mcap"] == outs["yaml"] and outs["sqlite3"] == outs["yaml"], planner


def test_python_reads_and_writes_bags_as_the_command_line(cli, tmp_path, rosbags_bags, plan_bag):
    m = oxcover.load_map(str(rosbags_bags["mcap"]), topic="/map", message="last")
    assert np.array_equal(m.to_array(), oxcover.load_map(MAP).to_array())
    assert oxcover.load_map(str(rosbags_bags["sqlite3"]), message=0).to_array().shape == (384, 384)
    p = oxcover.plan(oxcover.load_map(MAP), "lanes")
    (tmp_path / "py").mkdir()
    written = p.write(bag=tmp_path / "py" / "plan.mcap", out=tmp_path / "py.csv")
    assert len(written) == 2
    assert (tmp_path / "py" / "plan.mcap").read_bytes() == plan_bag["mcap"].read_bytes(), "byte for byte"
    with pytest.raises(ValueError, match="no topic /scan"):
        oxcover.load_map(str(rosbags_bags["mcap"]), topic="/scan")
    with pytest.raises(ValueError, match="has 1 messages, so no message 4"):
        oxcover.load_map(str(rosbags_bags["sqlite3"]), message=4)
    with pytest.raises(ValueError, match="expected first, last or a message number"):
        oxcover.load_map(str(rosbags_bags["sqlite3"]), message="newest")


def test_the_python_readme_bag_example_runs(tmp_path, monkeypatch):
    text = (ROOT / "crates" / "oxcover-py" / "README.md").read_text()
    blocks = [b.split("```", 1)[0] for b in text.split("```python\n")[1:]]
    (code,) = [b for b in blocks if "bag=" in b]
    monkeypatch.chdir(tmp_path)
    exec(code.replace('"fixtures/', f'"{ROOT}/fixtures/'), {"oxcover": oxcover})
    topics = read_with_rosbags(tmp_path / "plan.mcap")
    assert sorted(topics) == ["/coverage_path", "/map", "/rooms"]
