"""Turn bench_core measurements into figures, goal ratios, a printed table and a JSON file."""

from __future__ import annotations

import json
import math
import operator
import os
import tempfile

# label, numerator figure, denominator figure, comparison, goal
GOALS = (
    ("build / scipy Delaunay (time)", "build.seconds", "scipy.seconds", "<=", 1.5),
    ("build / gudhi fast (time)", "build.seconds", "gudhi.seconds", "<=", 0.8),
    ("build / scipy (peak extra memory)", "build.extra_mib", "scipy.extra_mib", "<=", 2.0),
    ("worst shape(alpha) / build", "shape.worst_seconds", "build.seconds", "<=", 1e-3),
    ("build / load", "build.seconds", "query.load_seconds", ">=", 20.0),
    ("signatures() / build", "query.signatures_seconds", "build.seconds", "<=", 0.5),
    ("shape / Open3D, same alpha (worst)", "pair.shape_seconds", "pair.open3d_seconds",
     "<=", 0.1),
)
COMPARE = {"<=": operator.le, ">=": operator.ge}
ROWS = {"scipy": "scipy Delaunay", "gudhi": "gudhi AlphaComplex fast", "build":
        "AlphaComplex.from_points", "open3d": "Open3D TetraMesh (once)"}
BUSY = 0.8  # cpu/wall below this for a one-thread step: the shared machine was busy


def figures(results: dict) -> dict:
    """Flat {'name.key': number} of every scalar measurement, plus the derived worst/fastest."""
    flat = {}
    for name, result in results.items():
        for key, value in result.items():
            if isinstance(value, int | float) and not isinstance(value, bool):
                flat[f"{name}.{key}"] = float(value)
    shapes = results.get("query", {}).get("shapes", [])
    per_alpha = results.get("open3d", {}).get("per_alpha", [])
    for clock in ("seconds", "cpu_seconds"):
        if shapes:
            flat[f"shape.worst_{clock}"] = max(s[clock] for s in shapes)
        flat.update(_worst_pair(shapes, per_alpha, clock))
    return flat


def _worst_pair(shapes: list[dict], per_alpha: list[dict], clock: str) -> dict:
    """Our shape time and Open3D's at the alpha where ours is slowest relative to theirs."""
    ours = {s["alpha"]: s[clock] for s in shapes}
    pairs = [(ours[p["alpha"]], p[clock]) for p in per_alpha if p["alpha"] in ours]
    if not pairs:
        return {}
    shape, o3d = max(pairs, key=lambda pair: pair[0] / max(pair[1], 1e-12))
    return {f"pair.shape_{clock}": shape, f"pair.open3d_{clock}": o3d}


def _cpu_key(key: str) -> str | None:
    """The CPU-time figure matching a wall-time figure, None for non-time figures."""
    return key.replace("seconds", "cpu_seconds") if key.endswith("seconds") else None


def ratios(flat: dict) -> list[dict]:
    """One dict per goal: value, reference, ratios and passed / cpu_passed (None: not measured)."""
    rows = []
    for label, num, den, op, goal in GOALS:
        value, ref = flat.get(num), flat.get(den)
        ratio = _ratio(value, ref)
        cpu_value, cpu_ref = flat.get(_cpu_key(num)), flat.get(_cpu_key(den))
        cpu_ratio = _ratio(cpu_value, cpu_ref)
        passed, cpu_passed = (None if r is None else bool(COMPARE[op](r, goal))
                              for r in (ratio, cpu_ratio))
        rows.append({"figure": label, "value": value, "reference": ref, "ratio": ratio,
                     "cpu_ratio": cpu_ratio, "goal": f"{op} {goal:g}", "passed": passed,
                     "cpu_passed": cpu_passed, "num": num, "den": den,
                     "cpu_value": cpu_value, "cpu_reference": cpu_ref})
    return rows


def _ratio(value: float | None, ref: float | None) -> float | None:
    """value / ref, or None when either is missing or ref is zero."""
    return value / ref if value is not None and ref else None


def _verdict(passed: bool | None, cpu_passed: bool | None) -> str:
    """PASS / FAIL / n/a on wall time, with the CPU-time verdict added when it differs."""
    word = {True: "PASS", False: "FAIL", None: "n/a"}
    if cpu_passed is None or cpu_passed == passed:
        return word[passed]
    return f"{word[passed]} (cpu: {word[cpu_passed]})"


def _num(value: float | None, digits: int = 3) -> str:
    """Short human number; '-' when absent."""
    return "-" if value is None else f"{value:.{digits}g}"


def format_tables(n: int, results: dict, rows: list[dict]) -> str:
    """The measurements and the goal ratios as two plain-text (markdown) tables."""
    lines = [f"### n = {n}", "",
             "| measurement | wall s | cpu s | peak MiB | extra MiB | note |",
             "|---|---|---|---|---|---|"]
    for name, label in ROWS.items():
        res = results.get(name)
        if res is None:
            continue
        lines.append(f"| {label} | {_num(res.get('seconds'))} | {_num(res.get('cpu_seconds'))} "
                     f"| {_num(res.get('peak_mib'), 4)} | {_num(res.get('extra_mib'), 4)} "
                     f"| {_note(res)} |")
        lines += [_timed(f"build: {stage['stage']}", stage, "") for stage in res.get("stages", [])]
    lines += _query_lines(results.get("query", {}), results.get("open3d", {}))
    lines += ["", "| figure | value s/MiB | reference | ratio | cpu ratio | goal | pass |",
              "|---|---|---|---|---|---|---|"]
    for row in rows:
        verdict = _verdict(row["passed"], row["cpu_passed"])
        lines.append(f"| {row['figure']} | {_num(row['value'])} | {_num(row['reference'])} | "
                     f"{_num(row['ratio'])} | {_num(row['cpu_ratio'])} | {row['goal']} | "
                     f"{verdict} |")
    return "\n".join(lines)


def _note(res: dict) -> str:
    """The error of a measurement, or a warning when its wall time far exceeds its CPU time."""
    if "error" in res:
        return res["error"]
    if res["cpu_seconds"] < BUSY * res["seconds"]:
        return f"cpu only {res['cpu_seconds'] / res['seconds']:.0%} of wall: machine busy?"
    return ""


def _query_lines(query: dict, o3d: dict) -> list[str]:
    """Table rows for load, save, signatures and each timed alpha."""
    if not query or "error" in query:
        return [f"| query | | | | | {query.get('error', 'not run')} |"]
    lines = [_timed("load (best)", query, "load_"),
             _timed("signatures() (fresh table)", query, "signatures_"),
             _timed("spectrum(), first call", query, "spectrum_first_call_"),
             _timed("shape, first call", query, "shape_first_call_", "lazy set-up included"),
             _timed("optimal_alpha()", query, "optimal_alpha_")]
    for shape in query["shapes"]:
        where = "optimal" if shape["quantile"] is None else f"q{shape['quantile']:g}"
        lines.append(_timed(f"shape {where} alpha={shape['alpha']:.4g}", shape, "",
                            f"{shape['simplices']} simplices"))
    for part in query.get("shape_parts", []):
        lines.append(_timed(f"shape part at alpha={part['alpha']:.4g}: {part['part']}", part, ""))
    for item in o3d.get("per_alpha", []):
        lines.append(_timed(f"Open3D alpha={item['alpha']:.4g}", item, "",
                            f"{item['triangles']} triangles"))
    return lines


def _timed(label: str, res: dict, prefix: str, note: str = "") -> str:
    """A table row with the wall and CPU seconds stored under prefix in res."""
    wall, cpu = res.get(f"{prefix}seconds"), res.get(f"{prefix}cpu_seconds")
    return f"| {label} | {_num(wall)} | {_num(cpu)} | | | {note} |"


def _finite(value: object) -> object:
    """value with every non-finite float replaced by None, so the JSON stays standard."""
    if isinstance(value, dict):
        return {key: _finite(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(item) for item in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def write_json(path: str, payload: dict) -> None:
    """Write payload as indented JSON atomically (temp file + os.replace)."""
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(suffix=".json", dir=folder)
    try:
        with os.fdopen(fd, "w") as handle:
            json.dump(_finite(payload), handle, indent=2, allow_nan=False, default=str)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


ANCHORS = {"scipy.seconds": "scipy Delaunay", "gudhi.seconds": "gudhi AlphaComplex fast",
           "scipy.extra_mib": "scipy Delaunay", "build.seconds": "our build",
           "query.load_seconds": "AlphaComplex.load", "pair.open3d_seconds": "Open3D alpha shape"}


def result_figures(n: int, rows: list[dict]) -> list:
    """The goal rows of one size as benchmarks.results Figures: one on the wall clock and, for
    times, one on the CPU clock, each with its anchor from the same run."""
    from results import Figure, slug

    out = []
    for row in rows:
        if row["ratio"] is None:
            continue
        unit = "MiB" if row["num"].endswith("mib") else "s"
        base = slug(row["figure"].replace(" (time)", ""))
        clocks = [("wall", row["value"], row["reference"])]
        if row["cpu_ratio"] is not None:
            clocks.append(("CPU", row["cpu_value"], row["cpu_reference"]))
        for clock, value, anchor in clocks:
            suffix = "" if unit == "MiB" else f", {clock}"
            out.append(Figure(name=f"{base}_{clock.lower()}_{n}",
                              label=f"{row['figure']}{suffix}, {n:,} torus points", value=value,
                              unit=unit, anchor=ANCHORS.get(row["den"], row["den"]),
                              anchor_value=anchor, goal=row["goal"]))
    return out
