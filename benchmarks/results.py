"""One JSON result per benchmark run, the only source of the figures in the READMEs.

A result holds where and when it was measured (commit, date, machine, CPU count) and its
figures: each a measured value beside the anchor measured in the same run, like for like (end to
end against end to end, wall against wall, CPU against CPU), the ratio between them and the goal
it is held to. `benchmarks/report.py` turns the latest results into the READMEs' tables.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import platform
import subprocess
import tempfile
from dataclasses import asdict, dataclass, field
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"
FOLDER_ENV = "ALPHASCOOP_BENCH_RESULTS"  # another folder for the results (the harness's tests)
SCHEMA = "alphascoop-benchmark-result/1"


@dataclass(frozen=True)
class Figure:
    """One measured figure: `value` (in `unit`) against `anchor_value` of the same run.

    `ratio` is value / anchor_value; `goal` is a comparison and a bound such as "<= 0.8" on the
    ratio (or on the value when there is no anchor), `met` whether it holds (None: no goal).
    """

    name: str
    label: str
    value: float
    unit: str
    anchor: str | None = None
    anchor_value: float | None = None
    goal: str | None = None
    ratio: float | None = field(default=None)
    met: bool | None = field(default=None)

    def __post_init__(self) -> None:
        if self.anchor_value is not None and self.ratio is None and self.anchor_value != 0:
            object.__setattr__(self, "ratio", self.value / self.anchor_value)
        if self.goal is not None and self.met is None:
            object.__setattr__(self, "met", goal_met(self.goal, self.checked()))

    def checked(self) -> float:
        """The number the goal is held to: the ratio when there is an anchor, else the value."""
        return self.ratio if self.ratio is not None else self.value


def goal_met(goal: str, number: float) -> bool:
    """Whether `number` satisfies a goal written "<= 0.8", ">= 1.7", "< 2" or "> 20"."""
    op, bound = goal.split()
    limit = float(bound)
    return {"<=": number <= limit, ">=": number >= limit, "<": number < limit,
            ">": number > limit}[op]


def slug(text: str) -> str:
    """A figure name made of a label: lower case, runs of other characters as one "_"."""
    return "_".join("".join(c if c.isalnum() else " " for c in text.lower()).split())


def clock_pair(name: str, label: str, mine: dict, anchor: str, theirs: dict,
               goal: str | None = None, cpu_goal: str | None = None) -> list[Figure]:
    """Two figures of one comparison, on the wall clock ("seconds") and on the CPU clock
    ("cpu_seconds"), from two measurements of the same run; none when either failed."""
    if "seconds" not in mine or not theirs.get("seconds"):
        return []
    return [Figure(name=f"{name}_{clock}", label=f"{label}, {word}", value=mine[key], unit="s",
                   anchor=anchor, anchor_value=theirs[key], goal=held)
            for clock, word, key, held in (("wall", "wall", "seconds", goal),
                                           ("cpu", "CPU", "cpu_seconds", cpu_goal))
            if theirs.get(key)]


CODE = ("*.py", "*.toml", "*.txt")  # what can change a figure; the READMEs and results cannot


def _git(*args: str) -> str:
    """The output of one git command in the repository (raises when git fails)."""
    return subprocess.run(["git", *args], cwd=Path(__file__).resolve().parent.parent,
                          capture_output=True, text=True, check=True).stdout.strip()


def _commit() -> tuple[str, bool]:
    """The checked-out commit and whether its code in the work tree differs from it."""
    try:
        sha = _git("rev-parse", "HEAD")
        dirty = bool(_git("status", "--porcelain", "--untracked-files=no", "--", *CODE))
    except (OSError, subprocess.CalledProcessError):
        return "unknown", True
    return sha, dirty


_STARTED = _commit()  # the code a run starts with (this module is imported at its start)


def _run_commit() -> tuple[str, bool]:
    """The commit the run started on, dirty when its code differed from that commit then or
    differs now (a commit of code during the run; commits of the READMEs do not count)."""
    sha, dirty = _STARTED
    if sha == "unknown":
        return sha, True
    try:
        changed = bool(_git("diff", "--name-only", sha, "--", *CODE))
    except (OSError, subprocess.CalledProcessError):
        changed = True
    return sha, dirty or changed


def machine() -> dict:
    """Where the run happened: processor, CPU count, memory, Python."""
    with open("/proc/meminfo") as handle:
        total_kib = int(handle.readline().split()[1])
    return {"processor": platform.processor() or platform.machine(), "cpu_count": os.cpu_count(),
            "memory_gib": round(total_kib / 1024**2, 1), "python": platform.python_version(),
            "system": platform.platform()}


def results_folder() -> Path:
    """Where results are written and read: $ALPHASCOOP_BENCH_RESULTS, else benchmarks/results."""
    return Path(os.environ.get(FOLDER_ENV) or RESULTS)


def save(benchmark: str, figures: list[Figure], *, tables: list[dict] | None = None,
         notes: list[str] | None = None, folder: Path | None = None) -> Path:
    """Write `folder/<benchmark>.json` atomically and return its path.

    `tables` are extra detail tables ({"title", "columns", "rows"}); `notes` are sentences the
    report prints under the benchmark's table (what was measured, on which input).
    """
    folder = folder or results_folder()
    sha, dirty = _run_commit()
    result = {"schema": SCHEMA, "benchmark": benchmark, "commit": sha, "dirty": dirty,
              "date": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
              "machine": machine(), "figures": [asdict(f) for f in figures],
              "tables": tables or [], "notes": notes or []}
    folder.mkdir(parents=True, exist_ok=True)
    target = folder / f"{benchmark}.json"
    fd, tmp = tempfile.mkstemp(dir=folder, suffix=".json.tmp")
    try:
        with os.fdopen(fd, "w") as stream:
            json.dump(result, stream, indent=2, allow_nan=False)
            stream.write("\n")
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return target


def load(benchmark: str, folder: Path | None = None) -> dict:
    """The saved result of one benchmark (raises FileNotFoundError when it never ran)."""
    folder = folder or results_folder()
    with open(folder / f"{benchmark}.json") as handle:
        result = json.load(handle)
    if result.get("schema") != SCHEMA:
        raise ValueError(f"{benchmark}.json is not a {SCHEMA} result")
    return result
