"""What calling oxcover from Python costs over the command line.

    python crates/oxcover-py/benchmarks/overhead.py [MAP.yaml] [--runs N]

For one request (default: nav2's warehouse map, 1006 × 1674 cells, planner
lanes, robot = tool radius 0.15 m), runs `oxcover plan --report` and
`oxcover.plan(...)` alternately, N times each, and compares the command
line's own `plan_ms` (planning alone, as its report states it) with the
wall time of the whole Python call (request, planning with the GIL released,
the N×2 path array, the Plan object). The map is read once in Python (its
reading is not planning, and the CLI's plan_ms does not include it either).
Prints a markdown table for docs/benchmarks.md.
"""

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import oxcover

ROOT = pathlib.Path(__file__).resolve().parents[3]
DEFAULT_MAP = ROOT.parent / "shared/maps/ros/nav2/nav2_bringup_maps/warehouse.yaml"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("map", nargs="?", default=str(DEFAULT_MAP))
    ap.add_argument("--planner", default="lanes")
    ap.add_argument("--radius", type=float, default=0.15)
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--bin", default=os.environ.get("OXCOVER_BIN", str(ROOT / "target/release/oxcover")))
    a = ap.parse_args()
    if not pathlib.Path(a.map).exists():
        sys.exit(f"{a.map}: not found (the shared maps are not part of the repository)")
    m = oxcover.load_map(a.map)
    kwargs = {"robot_radius": a.radius, "tool_radius": a.radius}
    cli_ms, cli_wall_ms, py_call_ms, py_plan_ms = [], [], [], []
    same = True
    with tempfile.TemporaryDirectory() as tmp:
        report, csv = pathlib.Path(tmp) / "r.json", pathlib.Path(tmp) / "p.csv"
        for _ in range(a.runs):
            t0 = time.perf_counter()
            subprocess.run(
                [a.bin, "plan", a.map, "--planner", a.planner, "--robot-radius", str(a.radius),
                 "--tool-radius", str(a.radius), "--report", str(report), "--out", str(csv)],
                check=True, capture_output=True,
            )
            cli_wall_ms.append((time.perf_counter() - t0) * 1e3)
            cli_ms.append(json.loads(report.read_text())["plan_ms"])
            t0 = time.perf_counter()
            p = oxcover.plan(m, a.planner, **kwargs)
            py_call_ms.append((time.perf_counter() - t0) * 1e3)
            py_plan_ms.append(p.plan_ms)
            same = same and p.to_csv() == csv.read_text()
    med = statistics.median
    ratio = med(py_call_ms) / med(cli_ms)
    print(f"map {pathlib.Path(a.map).name} ({m.width} x {m.height} cells), planner {a.planner}, "
          f"r = t = {a.radius} m, {a.runs} runs each, alternating; same path as the CLI: {same}")
    print()
    print("| measure | median ms | min ms | max ms |")
    print("|---|---:|---:|---:|")
    for name, xs in [("CLI `plan_ms` (report)", cli_ms),
                     ("Python `oxcover.plan(...)` wall time", py_call_ms),
                     ("Python `Plan.plan_ms`", py_plan_ms),
                     ("CLI process wall time (read map, plan, score, write)", cli_wall_ms)]:
        print(f"| {name} | {med(xs):.1f} | {min(xs):.1f} | {max(xs):.1f} |")
    print()
    print(f"Python call / CLI plan_ms (medians): {ratio:.3f} "
          f"({'within' if ratio <= 1.10 else 'ABOVE'} the 10 % allowed)")
    if not same:
        sys.exit("the Python path differs from the CLI's")


if __name__ == "__main__":
    main()
