"""Shared fixtures: the repository root, the bundled maps and the `oxcover`
command line the Python package is compared against."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]

# Every map bundled in the repository, in every format the readers take.
BUNDLED_MAPS = sorted(
    [str(p.relative_to(ROOT)) for p in (ROOT / "fixtures" / "maps").glob("*/*.yaml")]
    + [str(p.relative_to(ROOT)) for p in (ROOT / "fixtures" / "maps").glob("*/*.map")]
    + ["crates/oxcover/assets/simple_rooms.yaml"]
)


def _cli_binary() -> pathlib.Path:
    given = os.environ.get("OXCOVER_BIN")
    if given:
        return pathlib.Path(given)
    built = ROOT / "target" / "release" / "oxcover"
    if not built.exists():
        subprocess.run(
            ["cargo", "build", "--release", "--locked", "-p", "oxcover", "--bin", "oxcover"],
            cwd=ROOT,
            check=True,
        )
    return built


@pytest.fixture(scope="session")
def cli():
    """Runs `oxcover ARGS` from the repository root; returns the completed
    process (stdout and stderr as text)."""
    binary = _cli_binary()

    def run(*args):
        return subprocess.run(
            [str(binary), *map(str, args)],
            cwd=ROOT,
            capture_output=True,
            text=True,
        )

    return run


@pytest.fixture(autouse=True)
def _at_root(monkeypatch):
    """Relative map paths resolve as the command line's do."""
    monkeypatch.chdir(ROOT)


def cli_error(process) -> str:
    """The one-line message of a failed command, without its prefix."""
    assert process.returncode == 2, (process.returncode, process.stderr)
    lines = process.stderr.strip().splitlines()
    assert len(lines) == 1, process.stderr
    prefix = "oxcover: error: "
    assert lines[0].startswith(prefix), lines[0]
    return lines[0][len(prefix):]
