"""The READMEs' figures, made from the benchmark results (benchmarks/results/*.json).

    python benchmarks/report.py --write    # rewrite the generated blocks of both READMEs
    python benchmarks/report.py --check    # exit 1 when a generated block differs from its file

benchmarks/README.md holds one block per benchmark between `<!-- report:begin NAME -->` and
`<!-- report:end NAME -->`: where and when it ran, then every figure of its latest result beside
the anchor measured in the same run. README.md holds the handful of figures a user cares about
between `<!-- figures:begin -->` and `<!-- figures:end -->`. Only the text between markers is
generated; the guide around it is written by hand.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import os
import re
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from results import RESULTS, load

ROOT = Path(__file__).resolve().parent.parent
BENCH_README = ROOT / "benchmarks" / "README.md"
USER_README = ROOT / "README.md"
BLOCK = re.compile(r"(<!-- report:begin (\S+) -->\n)(.*?)(<!-- report:end \2 -->)", re.S)
FIGURES = re.compile(r"(<!-- figures:begin -->\n)(.*?)(<!-- figures:end -->)", re.S)

# The README's figures: (benchmark, figure name), in this order; a name also matches the same
# name with a suffix (bench_core's "_200000"); a figure whose result does not exist is left out.
FEATURED = (
    ("bench_first_open", "slider_live_vs_gudhi_wall"),
    ("bench_core", "build_gudhi_fast_wall"),
    ("bench_core", "build_load_wall"),
    ("bench_slider", "drag_step_max_wall"),
    ("bench_modes", "density_wall"),
    ("bench_modes", "anisotropic_wall"),
    ("bench_weighted", "weighted_vs_gudhi_weighted_fast_wall"),
    ("molecule", "end_to_end_10008"),
    ("bench_cache", "entry_size_1000000"),
    ("bench_cache", "reopen_1000000_wall"),
    ("bench_tiled", "tiled_vs_memory"),
    ("bench_tiled", "one_to_two_workers"),
)


def results(folder: Path = RESULTS) -> dict[str, dict]:
    """Every saved result in the folder, by benchmark name."""
    return {path.stem: load(path.stem, folder) for path in sorted(folder.glob("*.json"))}


def number(value: float, unit: str = "") -> str:
    """A figure as the READMEs print it: three significant digits and its unit."""
    text = f"{value:.3g}" if abs(value) < 1000 else f"{value:,.0f}"
    return f"{text} {unit}".strip()


def ratio(figure: dict) -> str:
    """The figure's ratio to its anchor as "0.58x", or "-" when it has no anchor."""
    return "-" if figure.get("ratio") is None else f"{figure['ratio']:.3g}x"


def verdict(figure: dict) -> str:
    """The goal and whether the figure met it, e.g. "<= 0.8: met"."""
    if figure.get("goal") is None:
        return "-"
    return f"{figure['goal']}: {'met' if figure['met'] else 'NOT met'}"


def provenance(result: dict) -> str:
    """One line saying where and when a result was measured."""
    when = _dt.datetime.fromisoformat(result["date"]).strftime("%Y-%m-%d %H:%M UTC")
    box = result["machine"]
    dirty = ", with uncommitted changes" if result.get("dirty") else ""
    return (f"Commit `{result['commit'][:10]}`{dirty}, {when}; {box['processor']}, "
            f"{box['cpu_count']} CPUs, {box['memory_gib']} GiB, Python {box['python']}.")


def benchmark_block(result: dict) -> str:
    """The generated text of one benchmark: provenance, its figures' table, its notes."""
    lines = [provenance(result), "",
             "| figure | value | anchor, same run | ratio | goal |", "|---|---|---|---|---|"]
    for fig in result["figures"]:
        anchor = "-" if fig.get("anchor") is None else (
            f"{fig['anchor']}: {number(fig['anchor_value'], fig['unit'])}")
        lines.append(f"| {fig['label']} | {number(fig['value'], fig['unit'])} | {anchor} | "
                     f"{ratio(fig)} | {verdict(fig)} |")
    for table in result.get("tables", []):
        lines += ["", f"{table['title']}:", "", "| " + " | ".join(table["columns"]) + " |",
                  "|" + "---|" * len(table["columns"])]
        lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in table["rows"]]
    if result.get("notes"):
        lines += ["", *result["notes"]]
    return "\n".join(lines) + "\n"


def missing_block(name: str) -> str:
    """What a benchmark's block says before it has a result."""
    return f"No result yet: run `python benchmarks/{name}.py` (it writes results/{name}.json).\n"


def find(figures: list[dict], name: str) -> dict | None:
    """The figure called `name`, or `name` with a suffix such as bench_core's "_200000"."""
    return next((f for f in figures if f["name"] == name or f["name"].startswith(f"{name}_")),
                None)


def figures_block(found: dict[str, dict]) -> str:
    """README.md's short figures table: the featured figures that have a result, each on the
    wall clock with its CPU-clock twin's ratio beside it."""
    lines = ["| figure | ours (wall) | anchor, same run | wall ratio | CPU ratio | benchmark |",
             "|---|---|---|---|---|---|"]
    for name, figure in FEATURED:
        figures = found.get(name, {}).get("figures", [])
        fig = find(figures, figure)
        if fig is None:
            continue
        twin = find(figures, figure.replace("_wall", "_cpu")) if "_wall" in figure else None
        label = fig["label"].replace(", wall", "") if twin else fig["label"]
        anchor = f"{fig['anchor']}: {number(fig['anchor_value'], fig['unit'])}"
        lines.append(f"| {label} | {number(fig['value'], fig['unit'])} | {anchor} | "
                     f"{ratio(fig)} | {ratio(twin) if twin else '-'} | `{name}`, "
                     f"{found[name]['machine']['cpu_count']} CPUs |")
    return "\n".join(lines) + "\n"


def render_benchmarks(text: str, found: dict[str, dict]) -> str:
    """benchmarks/README.md with every block regenerated, and a section added for a result
    that has no block yet."""
    def fill(match: re.Match) -> str:
        name = match.group(2)
        body = benchmark_block(found[name]) if name in found else missing_block(name)
        return match.group(1) + body + match.group(4)

    text = BLOCK.sub(fill, text)
    present = {match.group(2) for match in BLOCK.finditer(text)}
    for name in sorted(set(found) - present):
        text = (text.rstrip("\n") + f"\n\n## {name}\n\n<!-- report:begin {name} -->\n"
                f"{benchmark_block(found[name])}<!-- report:end {name} -->\n")
    return text


def render_readme(text: str, found: dict[str, dict]) -> str:
    """README.md with its figures block regenerated."""
    if not FIGURES.search(text):
        raise ValueError("README.md has no <!-- figures:begin --> ... <!-- figures:end --> block")
    return FIGURES.sub(lambda m: m.group(1) + figures_block(found) + m.group(3), text)


def rendered(folder: Path = RESULTS, bench_readme: Path = BENCH_README,
             readme: Path = USER_README) -> dict[Path, tuple[str, str]]:
    """{file: (its text now, the text the results make)} for both READMEs."""
    found = results(folder)
    bench_now, readme_now = bench_readme.read_text(), readme.read_text()
    return {bench_readme: (bench_now, render_benchmarks(bench_now, found)),
            readme: (readme_now, render_readme(readme_now, found))}


def stale(folder: Path = RESULTS, bench_readme: Path = BENCH_README,
          readme: Path = USER_README) -> list[Path]:
    """The READMEs whose generated text is not what the results make."""
    return [path for path, (now, made) in rendered(folder, bench_readme, readme).items()
            if now != made]


def write_atomic(path: Path, text: str) -> None:
    """Replace path's text through a temporary file in its folder."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".md.tmp")
    try:
        with os.fdopen(fd, "w") as stream:
            stream.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def main(argv: list[str] | None = None) -> int:
    """--write rewrites the READMEs' generated blocks; --check exits 1 when they are stale."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    action = parser.add_mutually_exclusive_group(required=True)
    action.add_argument("--write", action="store_true", help="rewrite the generated blocks")
    action.add_argument("--check", action="store_true", help="exit 1 when a block is stale")
    args = parser.parse_args(argv)
    if args.check:
        old = stale()
        for path in old:
            print(f"{path.relative_to(ROOT)}: its figures are not the report's output "
                  "(run python benchmarks/report.py --write)", file=sys.stderr)
        return 1 if old else 0
    for path, (now, made) in rendered().items():
        if now != made:
            write_atomic(path, made)
            print(f"rewrote {path.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
