"""Coverage targets from Python: each keyword gives the path file, the
picture and the metrics `oxcover plan` and `oxcover eval` give with the
same option, byte for byte, and a bad target raises with the command
line's message."""

import json

import pytest

import oxcover
from conftest import cli_error

MAP = "fixtures/maps/turtlebot_simulator/simple_rooms.yaml"
ZONE = "fixtures/targets/simple_rooms_zone.geojson"
KEEP_OUT = "fixtures/targets/simple_rooms_keep_out.geojson"
ROBOT = {"robot_radius": 0.15, "tool_radius": 0.15}
ROBOT_FLAGS = ["--robot-radius", "0.15", "--tool-radius", "0.15"]

# (keywords, the same as flags) for each target keyword.
CASES = {
    "zones": ({"zones": ZONE}, ["--zones", ZONE]),
    "keep_out": ({"keep_out": KEEP_OUT}, ["--keep-out", KEEP_OUT]),
    "rooms_only": ({"rooms_only": [5, 2], "room_order": "given"},
                   ["--rooms-only", "5,2", "--room-order", "given"]),
    "spot": ({"spot": (16.0, 3.3, 1.0)}, ["--spot", "16,3.3,1.0"]),
    "clearance": ({"clearance": 0.1}, ["--clearance", "0.1"]),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_each_target_keyword_plans_and_scores_as_the_command_line(cli, tmp_path, case):
    kwargs, options = CASES[case]
    out, png = tmp_path / "cli.csv", tmp_path / "cli.png"
    done = cli("plan", MAP, "--planner", "lanes", "--out", out, "--png", png,
               *ROBOT_FLAGS, *options)
    assert done.returncode == 0, done.stderr
    m = oxcover.load_map(MAP)
    p = oxcover.plan(m, "lanes", **ROBOT, **kwargs)
    assert p.to_csv() == out.read_text()
    # The picture too, targets drawn (chosen rooms labelled).
    assert p.to_png() == png.read_bytes()
    assert p.metrics["coverage"] == 1.0
    scored = cli("eval", MAP, out, *ROBOT_FLAGS, *[o for o in options if o != "--room-order" and o != "given"])
    assert scored.returncode == 0, scored.stderr
    eval_kwargs = {k: v for k, v in kwargs.items() if k != "room_order"}
    assert oxcover.evaluate(m, out, **ROBOT, **eval_kwargs) == json.loads(scored.stdout)


def test_done_resumes_as_the_command_line(cli, tmp_path):
    m = oxcover.load_map(MAP)
    whole = oxcover.plan(m, "lanes", **ROBOT)
    lines = whole.to_csv().splitlines()
    done_file = tmp_path / "done.csv"
    done_file.write_text("\n".join(lines[: len(lines) // 2]) + "\n")
    out = tmp_path / "rest.csv"
    done = cli("plan", MAP, "--planner", "lanes", "--done", done_file, "--out", out, *ROBOT_FLAGS)
    assert done.returncode == 0, done.stderr
    rest = oxcover.plan(m, "lanes", **ROBOT, done=done_file)
    assert rest.to_csv() == out.read_text()
    # An array of the done points plans the same.
    half = whole.path[: len(lines) // 2 - 1]
    assert oxcover.plan(m, "lanes", **ROBOT, done=half).to_csv() == out.read_text()


@pytest.mark.parametrize(
    "kwargs, options",
    [
        ({"rooms_only": [99]}, ["--rooms-only", "99"]),
        ({"spot": (50.0, 50.0, 1.0)}, ["--spot", "50,50,1"]),
        ({"zones": "fixtures/targets/README.md"}, ["--zones", "fixtures/targets/README.md"]),
    ],
)
def test_bad_targets_raise_with_the_command_lines_message(cli, kwargs, options):
    done = cli("plan", MAP, "--planner", "lanes", *ROBOT_FLAGS, *options)
    with pytest.raises(ValueError) as e:
        oxcover.plan(oxcover.load_map(MAP), "lanes", **ROBOT, **kwargs)
    assert str(e.value) == cli_error(done)
