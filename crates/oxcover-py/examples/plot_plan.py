"""Plan a bundled map with oxcover and plot the path with matplotlib.

    pip install ./crates/oxcover-py matplotlib
    python crates/oxcover-py/examples/plot_plan.py [OUT.png]

Run from the repository root; writes docs/python_example.png by default.
"""

import pathlib
import sys

import numpy as np

import oxcover

ROOT = pathlib.Path(__file__).resolve().parents[3]


def main(out: pathlib.Path) -> None:
    m = oxcover.load_map(ROOT / "fixtures/maps/turtlebot_simulator/simple_rooms.yaml")
    plan = oxcover.plan(m, "lanes", robot_radius=0.15, tool_radius=0.15)
    metrics = plan.metrics
    print(plan)
    print(
        f"coverage {metrics['coverage']:.4f}, collisions {metrics['collisions']}, "
        f"{metrics['turns']} turns, est. time {metrics['est_time_s']:.0f} s "
        f"(time efficiency {metrics['time_efficiency']:.3f}), planned in {plan.plan_ms:.0f} ms"
    )

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        sys.exit("matplotlib is not installed: pip install matplotlib")

    # The map in metres: to_array() has row 0 at the origin, so imshow with
    # origin="lower" and the map's extent puts cells where the path is.
    # (This map has no yaw; a rotated map would need a transform.)
    x0, y0, _yaw = m.origin
    extent = [x0, x0 + m.width * m.resolution, y0, y0 + m.height * m.resolution]
    occupancy = m.to_array().astype(float)
    occupancy[occupancy < 0] = 50.0  # unknown as grey
    fig, ax = plt.subplots(figsize=(8, 8 * m.height / m.width + 0.6))
    ax.imshow(100 - occupancy, cmap="gray", origin="lower", extent=extent, vmin=0, vmax=100)
    path = plan.path
    ax.plot(path[:, 0], path[:, 1], lw=0.8, color="tab:blue")
    ax.plot(*path[0], "o", color="tab:green", label="start")
    ax.plot(*path[-1], "s", color="tab:red", label="end")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(
        f"{plan.planner} on simple_rooms: coverage {metrics['coverage']:.3f}, "
        f"{metrics['length_m']:.0f} m, est. {metrics['est_time_s'] / 60:.1f} min"
    )
    ax.legend(loc="upper right")
    ax.set_aspect("equal")
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print(f"wrote {out}")
    assert np.isfinite(path).all()


if __name__ == "__main__":
    main(pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "python_example.png")
