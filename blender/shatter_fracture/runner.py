"""Finding and running the `shatter` binary: plain Python, no Blender.

Everything here is testable outside Blender (`blender/tests/test_runner.py` runs it with
`python3`). The add-on builds a `Request` from its redo panel, `command_line` turns it
into `shatter fracture ...` arguments, and `run` executes them, turning every failure
(a missing binary, a refused mesh, a crash, output that is not the report) into a
`ShatterError` whose message is meant for the user, never a traceback.

>>> req = Request(method="slice", pieces=3, seed=7)
>>> command_line("/bin/shatter", "in.glb", "out.glb", req)[1:6]
['fracture', 'in.glb', '--method', 'slice', '--pieces']
"""

import json
import os
import shutil
import subprocess
import time
from dataclasses import dataclass, field
from typing import Callable, List, Optional, Sequence, Tuple

Vec3 = Tuple[float, float, float]

METHODS = ("voronoi", "tetra", "slice")
PATTERNS = ("uniform", "clustered", "radial", "splinter")
PLACEMENTS = ("interior", "thesis")

HOW_TO_INSTALL = (
    "build it with `cargo build --release -p shatter-cli` and put it on PATH, "
    "or set its path in Edit > Preferences > Add-ons > Shatter Fracture"
)


class ShatterError(Exception):
    """A failure to show the user as it is (the operator reports it, no traceback)."""


@dataclass
class Request:
    """What to ask `shatter fracture` for (the redo panel's values, lower-case)."""

    method: str = "voronoi"
    # voronoi (generated seeds) and slice: number of seeds or planes.
    pieces: int = 20
    # voronoi: seed pattern, used when no seed points are given.
    pattern: str = "uniform"
    # voronoi radial: the impact point in the mesh file's frame, or None (shatter picks).
    impact: Optional[Vec3] = None
    # voronoi: explicit seed points in the mesh file's frame (child vertices, particles).
    seeds: Optional[List[Vec3]] = None
    # tetra.
    random_vertices: int = 50
    skip: int = 0
    center: bool = False
    placement: str = "interior"
    seed: int = 0
    # Ask for the bond list (--json-bonds).
    bonds: bool = False

    def check(self):
        """Raises ShatterError when a value is out of range (before anything runs)."""
        if self.method not in METHODS:
            raise ShatterError("unknown method %r (one of %s)" % (self.method, ", ".join(METHODS)))
        if self.pattern not in PATTERNS:
            raise ShatterError("unknown pattern %r (one of %s)" % (self.pattern, ", ".join(PATTERNS)))
        if self.placement not in PLACEMENTS:
            raise ShatterError("unknown placement %r" % self.placement)
        if self.method in ("voronoi", "slice") and self.seeds is None and self.pieces < 1:
            raise ShatterError("Pieces must be at least 1 (got %d)" % self.pieces)
        if self.method == "tetra" and (self.random_vertices < 0 or self.skip < 0):
            raise ShatterError("Random Vertices and Skip cannot be negative")
        if self.seeds is not None:
            if self.method != "voronoi":
                raise ShatterError("seed points apply to the voronoi method only")
            if not self.seeds:
                raise ShatterError("no seed points: the chosen source has no vertices or particles")
        if self.seed < 0:
            raise ShatterError("Seed cannot be negative (got %d)" % self.seed)


def find_binary(preferred: str = "") -> str:
    """The shatter executable: `preferred` (a file, or a folder holding `shatter`) when
    set, else `shatter` on PATH. Raises ShatterError saying what is missing."""
    preferred = (preferred or "").strip()
    if preferred:
        path = os.path.abspath(os.path.expanduser(preferred))
        if os.path.isdir(path):
            path = os.path.join(path, "shatter")
        if not os.path.isfile(path):
            raise ShatterError(
                "The shatter binary set in the add-on's preferences does not exist: %s" % path)
        if not os.access(path, os.X_OK):
            raise ShatterError(
                "The shatter binary set in the add-on's preferences is not executable: %s" % path)
        return path
    found = shutil.which("shatter")
    if found is None:
        raise ShatterError("The shatter binary was not found on PATH: " + HOW_TO_INSTALL)
    return found


def write_points(path: str, points: Sequence[Vec3]):
    """Writes points in shatter's POINTS.xyz format (one `x y z` per line)."""
    with open(path, "w") as f:
        f.write("# %d seed points written by the Blender add-on shatter_fracture\n" % len(points))
        for p in points:
            f.write("%.17g %.17g %.17g\n" % tuple(p))


def _vec(v: Vec3) -> str:
    return "%.17g,%.17g,%.17g" % tuple(v)


def command_line(binary: str, mesh: str, out: str, req: Request,
                 seeds_file: Optional[str] = None) -> List[str]:
    """The argument list of `shatter fracture` for a request. `seeds_file` must hold
    `req.seeds` (see `write_points`) when they are given."""
    req.check()
    args = [binary, "fracture", mesh, "--method", req.method]
    if req.method == "voronoi":
        if req.seeds is not None:
            if seeds_file is None:
                raise ShatterError("internal: seed points given without a seeds file")
            args += ["--seeds-file", seeds_file]
        else:
            args += ["--pieces", str(req.pieces), "--pattern", req.pattern]
            if req.pattern == "radial" and req.impact is not None:
                args += ["--impact", _vec(req.impact)]
    elif req.method == "slice":
        args += ["--pieces", str(req.pieces)]
    else:
        args += ["--random-vertices", str(req.random_vertices), "--skip", str(req.skip),
                 "--placement", req.placement]
        if req.center:
            args.append("--center")
    args += ["--seed", str(req.seed), "--out", out, "--json"]
    if req.bonds:
        args.append("--json-bonds")
    return args


@dataclass
class Result:
    """A successful run: the JSON report, the warnings and the wall time."""

    report: dict
    warnings: List[str] = field(default_factory=list)
    seconds: float = 0.0


def _error_lines(stderr: str) -> List[str]:
    return [line[len("error:"):].strip() if line.startswith("error:") else line.strip()
            for line in stderr.splitlines() if line.strip() and not line.startswith("warning:")]


def run(args: List[str], progress: Optional[Callable[[float], None]] = None,
        poll_seconds: float = 0.05) -> Result:
    """Runs shatter; `progress(elapsed_seconds)` is called while it runs. Raises
    ShatterError with shatter's own message when it fails."""
    start = time.perf_counter()
    try:
        proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                stdin=subprocess.DEVNULL, text=True)
    except OSError as e:
        raise ShatterError("Cannot start shatter (%s): %s" % (args[0], e.strerror or e))
    if progress is None:
        stdout, stderr = proc.communicate()
    else:
        while True:
            try:
                stdout, stderr = proc.communicate(timeout=poll_seconds)
                break
            except subprocess.TimeoutExpired:
                progress(time.perf_counter() - start)
    seconds = time.perf_counter() - start
    warnings = [line[len("warning:"):].strip() for line in stderr.splitlines()
                if line.startswith("warning:")]
    if proc.returncode != 0:
        lines = _error_lines(stderr)
        detail = "; ".join(lines) if lines else "no message"
        if proc.returncode == 2:
            raise ShatterError("shatter refused the input: " + detail)
        if proc.returncode < 0:
            raise ShatterError("shatter was killed by signal %d: %s" % (-proc.returncode, detail))
        raise ShatterError("shatter failed (exit code %d): %s" % (proc.returncode, detail))
    try:
        report = json.loads(stdout)
    except ValueError:
        raise ShatterError("shatter's output is not its JSON report (is %s the shatter "
                           "binary?): %r" % (args[0], stdout[:200]))
    if not isinstance(report, dict) or "fragments" not in report:
        raise ShatterError("shatter's JSON report has no fragment count: %r" % stdout[:200])
    if "--json-bonds" in args and not isinstance(report.get("bond_list"), list):
        raise ShatterError("shatter's report has no bond list (a shatter older than "
                           "--json-bonds?)")
    return Result(report=report, warnings=warnings, seconds=seconds)
