"""`alphascoop info` and `alphascoop export`: the core on the command line (no Qt).

Errors are one line on stderr with a non-zero exit status; progress bars appear on stderr
only when it is a terminal.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import shutil
import sys
import time
import warnings
from collections.abc import Iterator, Sequence
from pathlib import Path

import numpy as np

from app.args import (
    add_mode_options,
    count,
    mode_of,
    negative_values_joined,
    probe_radius,
    radius,
    squared_radius,
)
from app.tiled_cli import add_tiled_options, check_tiled
from core.errors import AlphaScoopError, InputError
from core.query.classes import CLASSES

SIMPLEX_NAMES = ("vertices", "edges", "triangles", "tetrahedra")
SOURCE_TEXT = {"built": " (built in {seconds:.2f} s)", "cache": " (from cache)",
               "rebuilt": " (rebuilt in {seconds:.2f} s: the cached table was damaged: {damage})"}


class UsageError(Exception):
    """A bad command line (reported in one line, exit status 2)."""


class Parser(argparse.ArgumentParser):
    """argparse that raises instead of printing usage and exiting."""

    def error(self, message: str):
        raise UsageError(message)


def index(text: str) -> int:
    """A whole number from 0."""
    if not text.isdigit():
        raise argparse.ArgumentTypeError(f"expected a whole number from 0, not {text!r}")
    return int(text)


def _common(sub: argparse.ArgumentParser) -> None:
    """Options shared by info and export."""
    sub.add_argument("file", help="point file (see README: Formats)")
    sub.add_argument("--columns", metavar="A,B[,C]", help="coordinate columns (names or 0-based)")
    sub.add_argument("--subsample", type=count, metavar="N", help="thin to at most N points")
    sub.add_argument("--scan", type=index, metavar="N",
                     help="E57: read only scan N (0-based; default all scans, poses applied)")
    sub.add_argument("--no-cache", action="store_true", help="rebuild, ignore the table cache")
    sub.add_argument("--backend", choices=("qhull", "gmsh"),
                     help="triangulation backend (default: gmsh where installed and exact, "
                          "else qhull; weighted points: geogram where built, which "
                          "qhull overrides)")
    sizes = sub.add_mutually_exclusive_group()
    sizes.add_argument("--weights", metavar="COLUMN",
                       help="weighted points: squared radii from this column")
    sizes.add_argument("--radius", metavar="COLUMN",
                       help="weighted points: radii from this column (squared)")
    sub.add_argument("--radius-add", type=probe_radius, metavar="R",
                     help="add R to every point's radius before squaring (a probe radius)")
    sub.add_argument("--probe", type=probe_radius, metavar="R",
                     help="molecules: solvent probe radius in Å added to every atom "
                     "(default 1.4; 0 = van der Waals surface)")
    sub.add_argument("--keep-water", action="store_true", help="molecules: keep water atoms")
    add_mode_options(sub)
    add_tiled_options(sub, count)


def build_parser() -> Parser:
    """The subcommand parser."""
    parser = Parser(prog="alphascoop", description="Alpha shapes from the command line.")
    subs = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    info = subs.add_parser("info", help="load report, spectrum, optimal alpha, shape summary")
    _common(info)
    at = info.add_mutually_exclusive_group()
    at.add_argument("--alpha", type=radius, metavar="R", help="alpha radius (default: opening)")
    at.add_argument("--alpha2", type=squared_radius, metavar="A2",
                    help="squared alpha (may be negative for weighted points)")
    info.add_argument("--json", action="store_true", help="print JSON instead of text")
    export = subs.add_parser("export", help="write the shape at one alpha (format from -o)")
    _common(export)
    export.add_argument("-o", "--output", required=True, metavar="OUT", help="output file")
    choice = export.add_mutually_exclusive_group()
    choice.add_argument("--alpha", type=radius, metavar="R", help="alpha radius")
    choice.add_argument("--alpha2", type=squared_radius, metavar="A2",
                        help="squared alpha (may be negative for weighted points)")
    choice.add_argument("--optimal", type=count, nargs="?", const=1, metavar="K",
                        help="optimal alpha for at most K solid components (default: the "
                        "opening alpha, as info and the window; alpha² 0 for a molecule)")
    split = export.add_mutually_exclusive_group()
    split.add_argument("--no-manifold", dest="manifold", action="store_false",
                       help="keep the raw boundary (3D surfaces are split where the shape "
                       "touches itself by default, to a closed 2-manifold)")
    split.add_argument("--manifold", dest="manifold", action="store_true",
                       help="the default; accepted for compatibility")
    export.add_argument("--sidecar", action="store_true", help="also write OUT.json metadata")
    export.add_argument("--table", action="store_true", help="write the interval table "
                        "(.npz or .csv) instead of the shape")
    export.add_argument("--pockets", action="store_true", help="molecules: write the pockets "
                        "instead of the shape (.vtu: their tetrahedra and mouths with cell data "
                        "`pocket`; .csv: the residues lining each)")
    return parser


def _progress():
    """A (callback, close) pair drawing a tqdm bar on stderr, or doing nothing off a terminal."""
    if not sys.stderr.isatty():
        return None, lambda: None
    from tqdm import tqdm

    size = shutil.get_terminal_size()  # 80x24 where a terminal reports 0 (tqdm then hides)
    bar = tqdm(total=100, file=sys.stderr, leave=False, ncols=min(size.columns, 100),
               nrows=size.lines,
               bar_format="{desc} {percentage:3.0f}%|{bar}| {elapsed}")

    def update(fraction: float, stage: str) -> None:
        bar.set_description(stage)
        bar.update(max(0, round(100 * fraction) - bar.n))

    return update, bar.close


def load(args) -> tuple:
    """(PointSet, Obtained (the complex and its source), seconds) for the file and options."""
    from core.modes.alpha_modes import file_normals
    from core.obtain import obtain

    mode = _mode(args)
    ps = _read(args)
    normals = file_normals(mode, ps.attributes, args.file)
    update, close = _progress()
    start = time.perf_counter()
    try:
        # Where the optimal or opening alpha is needed, the topology is cached with the
        # table too.
        needs_topology = args.command == "info" or chosen_alpha(args) is None
        obtained = obtain(ps.points, weights=ps.weights, mode=mode, normals=normals,
                          signatures=needs_topology and not getattr(args, "table", False),
                          use_cache=not args.no_cache, backend=args.backend,
                          progress=update)
    finally:
        close()
    asked, used = obtained.complex.mode.density, obtained.complex.build_info.density_neighbours
    if used:
        print(f"alphascoop: note: --density {asked} asks for more neighbours than the "
              f"{len(obtained.complex.points):,} points have; each point's spacing is "
              f"measured to its {used:,}th nearest neighbour instead", file=sys.stderr)
    estimated = obtained.complex.build_info.estimated_normals
    if estimated:
        print(f"alphascoop: note: {estimated:,} of {len(obtained.complex.points):,} points had "
              "a zero normal in the file; their normals were estimated from their neighbours",
              file=sys.stderr)
    if obtained.damage is not None:  # export prints no source: say it here, for both commands
        print(f"alphascoop: note: the cached table was damaged ({obtained.damage}); "
              "it was rebuilt", file=sys.stderr)
    return ps, obtained, time.perf_counter() - start


def _mode(args):
    """The alpha mode of the options (a UsageError for options that need another)."""
    try:
        return mode_of(args)
    except ValueError as exc:
        raise UsageError(str(exc)) from None


def is_molecule(args) -> bool:
    """The file is a PDB/mmCIF molecule (read as balls: atoms with radii plus the probe)."""
    from core.io.molecule import molecule_extension

    return molecule_extension(Path(args.file)) is not None


def _read(args):
    """The PointSet of the file; a molecule's atoms weighted by (radius + probe)²."""
    from core.io import read_points

    if not is_molecule(args):
        if args.probe is not None:
            raise UsageError("--probe applies to molecule files (PDB, mmCIF) only; for "
                             "points with a radius column use --radius-add")
        return read_points(args.file, columns=args.columns, subsample=args.subsample,
                           weights=args.weights, radius=args.radius,
                           radius_add=args.radius_add, scan=args.scan)
    from core.io.molecule import read_molecule_pointset

    for option in ("columns", "subsample", "weights", "radius", "radius_add", "scan"):
        if getattr(args, option) is not None:
            raise UsageError(f"--{option.replace('_', '-')} does not apply to molecule files "
                             "(use --probe)")
    return read_molecule_pointset(args.file, probe=probe(args), keep_water=args.keep_water)[0]


def probe(args) -> float:
    """The probe radius of a molecule (Å): --probe, else the water molecule's."""
    from core.io.molecule import DEFAULT_PROBE

    return DEFAULT_PROBE if args.probe is None else args.probe


def _molecule_point_data(args, ac) -> dict | None:
    """A molecule's per-atom exposed area as export point data ("atom_area"), else None."""
    if not is_molecule(args) or not args.output.lower().endswith(".vtu"):
        return None
    from core.molecule.analysis import measure_molecule

    return {"atom_area": measure_molecule(ac, probe(args)).point_area}


def molecule_summary(ac, probe: float, mol=None) -> dict:
    """The `molecule` object of `info`: exact area and volume, per-atom area, cavities and
    pockets (their lining atoms named from `mol`, the Molecule read, when given)."""
    from core.io.molecule import atom_labels
    from core.molecule.analysis import measure_molecule

    labels = None if mol is None else atom_labels(mol, ac.points)
    return measure_molecule(ac, probe).to_dict(labels)


POCKETS_SHOWN = 5  # pockets named in `info`'s text (all of them in --json)


def _molecule_text(mol: dict) -> list[str]:
    """Text lines of the `molecule` object."""
    kind = "solvent-accessible" if mol["probe"] > 0 else "van der Waals"
    cavities = ", ".join(f"{v:.4g} Å³ ({a:.4g} Å²)" for v, a in
                         zip(mol["cavities"], mol["cavity_areas"], strict=True))
    pockets = mol["pockets"]
    shown = "; ".join(
        f"{p['volume']:.4g} Å³ ({p['area']:.4g} Å², {len(p['mouths'])} mouth"
        f"{'s' if len(p['mouths']) != 1 else ''}, {len(p['atoms'])} atoms)"
        for p in pockets[:POCKETS_SHOWN])
    return [
        f"atoms       {mol['atoms']:,} balls, probe {mol['probe']:g} Å ({kind} surface)",
        f"surface     {mol['surface_area']:,.2f} Å² (exact)",
        f"volume      {mol['volume']:,.2f} Å³ (exact, union of balls)",
        f"cavities    {len(mol['cavities'])}" + (f" (exact): {cavities}" if cavities else ""),
        f"pockets     {len(pockets)}" + (f", largest: {shown}" if shown else "")
        + (" ..." if len(pockets) > POCKETS_SHOWN else ""),
    ]


def chosen_alpha(args) -> dict | None:
    """The alpha the command line asks for, as keyword arguments of the core's queries
    ({"alpha": R} or {"alpha2": A2}), or None (the default)."""
    if getattr(args, "alpha2", None) is not None:
        return {"alpha2": args.alpha2}
    if getattr(args, "alpha", None) is not None:
        return {"alpha": args.alpha}
    return None


def opening_alpha(ac, molecule: bool) -> float:
    """Where the window opens and what `export` writes by default: alpha² = 0 for a molecule
    (the union of its balls: the solvent-accessible surface, what its measures are of), else
    the opening alpha (ac.default_alpha())."""
    return 0.0 if molecule else float(ac.default_alpha())


def summary(ps, obtained, seconds: float, at: dict | None, molecule: bool = False) -> dict:
    """Everything `info` reports, as a JSON-ready dict (`obtained`: core.obtain's result;
    `at`: chosen_alpha's result, None: the opening alpha; `molecule`: opens at alpha² = 0)."""
    from core.complex import at_value
    from core.topology.pieces import pieces_at

    ac = obtained.complex
    optimal, opening = float(ac.optimal_alpha()), opening_alpha(ac, molecule)
    pieces = pieces_at(ac.index, ac.points, opening)
    shape = ac.shape(**(at or at_value(opening)))
    alpha = shape.alpha
    spectrum = np.asarray(ac.spectrum())
    weighted = ac.weights is not None
    classes = {SIMPLEX_NAMES[k]: dict(zip(CLASSES, np.bincount(
        ac.classify(alpha2=shape.alpha2, k=k), minlength=4).tolist(), strict=True))
        for k in range(ac.dim + 1)}
    first = 0 if weighted or len(spectrum) < 2 else 1  # classic: 0 (bare points) left out
    return {
        "load": ps.report.to_dict(),
        "source": obtained.source,
        "damage": obtained.damage,
        "mode": ac.mode.to_dict(),
        "build": ac.build_info.to_dict(),
        "complex": {"dim": ac.dim, "ambient_dim": ac.ambient_dim, "seconds": round(seconds, 3),
                    "from_cache": obtained.from_cache,
                    **{SIMPLEX_NAMES[k]: len(ac.simplices(k)) for k in range(ac.dim + 1)}},
        "spectrum": {"count": len(spectrum), "min": float(spectrum[first]),
                     "max": float(spectrum[-1]), "min2": _sq(spectrum[first]),
                     "max2": _sq(spectrum[-1])},
        "backend": ac.build_info.backend,
        "backend_note": ac.build_info.backend_note,
        "weighted": weighted,
        "hidden_points": int((np.asarray(ac.input_index) < 0).sum()),
        "optimal_alpha": optimal,
        "optimal_alpha2": _sq(optimal),
        "default_alpha": opening,
        "default_alpha2": _sq(opening),
        "opening_spacings": pieces.spacings,
        "opening_pieces": pieces.to_dict(),
        "opening_pieces_text": pieces.line(),
        "alpha": alpha,
        "alpha2": shape.alpha2 if np.isfinite(shape.alpha2) else None,
        "betti": [int(b) for b in ac.betti(alpha2=shape.alpha2)],
        "volume" if ac.dim == 3 else "area": shape.measure,
        "classes": classes,
        **_geographic(ps, ac, shape),
    }


def _sq(value: float) -> float | None:
    """A table value (radius; signed for weighted sets) squared with its sign, None beyond
    float64 (JSON has no infinity)."""
    square = float(value) * abs(float(value))
    return square if np.isfinite(square) else None


def _alpha_text(alpha: float, alpha2: float | None) -> str:
    """'alpha² A2 (alpha R)' for weighted sets (no radius below zero)."""
    return f"alpha² {alpha2:.6g}" + (f" (alpha {alpha:.6g})" if alpha >= 0 else "")


def _pieces_line(info: dict) -> str:
    """'pieces      5 pieces of 41+ points hold 99 % of the points; ...' at the opening."""
    return f"pieces      {info['opening_pieces_text']} at the opening alpha"


def _spacings(info: dict) -> str:
    """', 1.81 spacings' (the opening alpha in median nearest-neighbour spacings), or ''."""
    value = info.get("opening_spacings")
    return f", {value:.3g} spacings" if value is not None else ""


def _geographic(ps, ac, shape) -> dict:
    """For points read from longitude/latitude: units, projection, ellipsoidal measures."""
    georef = ps.report.georef
    if georef is None:
        return {}
    from core.export.polygons import geographic_metadata

    meta = geographic_metadata(ac, shape, georef)
    return {k: meta[k] for k in ("units", "area_m2", "perimeter_m") if k in meta}


def _text(info: dict, lines: list[str]) -> str:
    """The human-readable form of `summary`."""
    cx, sp = info["complex"], info["spectrum"]
    measure = "volume" if "volume" in info else "area"
    lines = [*lines,
        f"mode        {info['mode_text']}",
        f"complex     {cx['dim']}D, " + ", ".join(
            f"{cx[n]:,} {n}" for n in SIMPLEX_NAMES if n in cx)
        + SOURCE_TEXT[info["source"]].format(seconds=cx["seconds"], damage=info["damage"]),
        f"build       {info['build_text']}",
        f"spectrum    {sp['count']:,} critical alphas, {sp['min']:.6g} .. {sp['max']:.6g}"
        + (f" (squared {sp['min2']:.6g} .. {sp['max2']:.6g})" if info["weighted"] else ""),
    ]
    if info["weighted"]:
        lines += [
            f"hidden      {info['hidden_points']:,} points (their ball adds nothing)",
            f"optimal     {_alpha_text(info['optimal_alpha'], info['optimal_alpha2'])}"
            " (every point in one solid)",
            f"opening     {_alpha_text(info['default_alpha'], info['default_alpha2'])}"
            + (" (the union of the balls: what the measures below are of)" if "molecule"
               in info else " (the shape looks like the object)"),
            _pieces_line(info),
            f"at          {_alpha_text(info['alpha'], info['alpha2'])}"]
    else:
        lines += [
            f"optimal     alpha {info['optimal_alpha']:.6g} (every point in one solid)",
            f"opening     alpha {info['default_alpha']:.6g}{_spacings(info)} (the shape looks "
            "like the object)",
            _pieces_line(info),
            f"at alpha    {info['alpha']:.6g}"]
    lines.append("betti       " + " ".join(f"b{i} {b}" for i, b in enumerate(info["betti"])))
    if info.get("units") == "m":
        unit = "m²" if measure == "area" else "m³"
        lines.append(f"{f'{measure} ({unit})':<12}{info[measure]:.6g} in the projection"
                     + (f", {info['area_m2']:.6g} on the WGS 84 ellipsoid (perimeter "
                        f"{info['perimeter_m']:.6g} m)" if "area_m2" in info else ""))
    elif "molecule" in info:
        unit = "Å²" if measure == "area" else "Å³"
        lines.append(f"{f'{measure} ({unit})':<12}{info[measure]:.6g} of the cells (the "
                     "balls' exact figures: below)")
    else:
        lines.append(f"{measure:<12}{info[measure]:.6g}")
    lines.append(f"{'classes':<12}" + "".join(f"{c:>10}" for c in CLASSES))
    for name, counts in info["classes"].items():
        lines.append(f"  {name:<10}" + "".join(f"{counts[c]:>10,}" for c in CLASSES))
    return "\n".join(lines)


def cmd_info(args) -> int:
    """Print the load report and the shape summary (and a molecule's measures)."""
    check_tiled(args, UsageError)
    if args.tiled:
        return _tiled_info(args)
    ps, obtained, seconds = load(args)
    ac = obtained.complex
    info = summary(ps, obtained, seconds, chosen_alpha(args), molecule=is_molecule(args))
    if is_molecule(args):
        from core.io.molecule import read_molecule

        info["molecule"] = molecule_summary(ac, probe(args),
                                            read_molecule(args.file, keep_water=args.keep_water))
    text = None if args.json else _text({**info, "mode_text": ac.mode.describe(),
                                         "build_text": ac.build_info.describe()},
                                        ps.report.lines())
    if text is not None and "molecule" in info:
        text += "\n" + "\n".join(_molecule_text(info["molecule"]))
    print(json.dumps(info, indent=2) if args.json else text)
    return 0


def cmd_export(args) -> int:
    """Write the shape (or the table) and print one line about it."""
    from core.export import SHAPE_FORMATS, TABLE_FORMATS, write_shape, write_table
    from core.export.targets import refuse_source

    if args.pockets:
        return _export_pockets(args)
    formats = TABLE_FORMATS if args.table else SHAPE_FORMATS
    ext = os.path.splitext(args.output)[1].lower()
    if ext not in formats:  # before the build, which may take a while
        raise AlphaScoopError(f"{args.output}: cannot export to {ext or 'no extension'!r}; "
                              f"choose one of {' '.join(formats)}")
    try:  # never write over the input (same file on disk); a bad command line
        refuse_source(args.output, args.file)
        if args.sidecar and not args.table:
            refuse_source(f"{args.output}.json", args.file)
    except InputError as exc:
        raise UsageError(str(exc)) from None
    check_tiled(args, UsageError)
    if args.tiled:
        return _tiled_export(args)
    ps, obtained, _ = load(args)
    ac = obtained.complex
    if args.table:
        print(write_table(ac, args.output, source=args.file).line())
        return 0
    from core.complex import at_value

    at = chosen_alpha(args) or at_value(ac.optimal_alpha(args.optimal) if args.optimal
                                        else opening_alpha(ac, is_molecule(args)))
    report = write_shape(ac, at.get("alpha"), args.output, alpha2=at.get("alpha2"),
                         manifold=args.manifold, sidecar=args.sidecar, source=args.file,
                         georef=ps.report.georef, point_data=_molecule_point_data(args, ac))
    print(report.line())
    return 0


def _export_pockets(args) -> int:
    """`export --pockets`: a molecule's pockets at alpha² = 0 as VTU or CSV."""
    from app.pocket_export import write_pockets_csv, write_pockets_vtu
    from core.export.targets import refuse_source
    from core.io.molecule import atom_labels, molecule_extension, read_molecule
    from core.molecule.analysis import measure_molecule

    ext = os.path.splitext(args.output)[1].lower()
    if not is_molecule(args):
        raise UsageError(f"--pockets needs a molecule file (.pdb, .cif, .pqr, .xyzr...), "
                         f"not {os.path.basename(args.file)}")
    if ext not in (".vtu", ".csv") or args.table:
        raise UsageError("--pockets writes a molecule's pockets to .vtu or .csv")
    try:
        refuse_source(args.output, args.file)
    except InputError as exc:
        raise UsageError(str(exc)) from None
    _, obtained, _ = load(args)
    ac = obtained.complex
    pockets = measure_molecule(ac, probe(args)).pockets
    if ext == ".vtu":
        count = write_pockets_vtu(args.output, ac, pockets, {"probe": probe(args)})
        print(f"{args.output}: {len(pockets)} pockets, {count:,} cells (cell data pocket, mouth)")
    else:
        labels = atom_labels(read_molecule(args.file, keep_water=args.keep_water), ac.points)
        count = write_pockets_csv(args.output, pockets, labels)
        lining = "atoms" if molecule_extension(Path(args.file)) == ".xyzr" else "residues"
        print(f"{args.output}: {len(pockets)} pockets, {count:,} lining {lining}")
    return 0


def _tiled(args, summary: bool = False):
    """The tiled run of the options (app.tiled_cli), with a progress bar on a terminal;
    `summary`: only the shape's numbers (app.tiled_cli.run_tiled)."""
    from app import tiled_cli

    if is_molecule(args):
        raise UsageError("--tiled does not apply to molecule files")
    update, close = _progress()
    try:
        return tiled_cli.run_tiled(args, update, summary)
    finally:
        close()


def _tiled_info(args) -> int:
    """`info --tiled`: the tiled shape's summary."""
    from app import tiled_cli

    info = tiled_cli.tiled_summary(*_tiled(args, summary=True))
    print(json.dumps(info, indent=2) if args.json else tiled_cli.tiled_text(info))
    return 0


def _tiled_export(args) -> int:
    """`export --tiled`: the tiled shape written by the exporters."""
    from app import tiled_cli

    merged, _, georef, _ = _tiled(args)
    print(tiled_cli.write_tiled(args, merged, georef))
    return 0


@contextlib.contextmanager
def quiet_numerics() -> Iterator[None]:
    """No numpy floating-point warnings (overflow, invalid value...) and no RuntimeWarnings
    printed: odd values in a user's file are the file's, and the load report or the one
    error line says what matters. Warnings asked for with `python -W` are still shown."""
    with np.errstate(all="ignore"), warnings.catch_warnings():
        if not sys.warnoptions:
            warnings.simplefilter("ignore", RuntimeWarning)
        yield


def main(argv: Sequence[str] | None = None) -> int:
    """Run `alphascoop info|export ...`; return the exit status (0 = success).

    Whatever happens, an error is one line on stderr: never a traceback, never a warning.
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    with quiet_numerics():
        return _run(argv)


def _run(argv: list[str]) -> int:
    """main's body: the command, and every failure turned into one line and a status."""
    try:
        args = build_parser().parse_args(negative_values_joined(argv))
        return cmd_info(args) if args.command == "info" else cmd_export(args)
    except UsageError as exc:
        print(f"alphascoop: error: {exc} (see alphascoop {' '.join(argv[:1])} --help)",
              file=sys.stderr)
        return 2
    except AlphaScoopError as exc:
        print(f"alphascoop: error: {exc}", file=sys.stderr)
        return 1
    except MemoryError:
        print("alphascoop: error: not enough memory for this point set (try --subsample N)",
              file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("alphascoop: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # e.g. `alphascoop info F | head`: stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    except OSError as exc:  # a folder or file the system refuses, outside the readers
        print(f"alphascoop: error: {exc.strerror or exc}"
              f"{f': {exc.filename}' if exc.filename else ''}", file=sys.stderr)
        return 1
    except SystemExit as exc:  # --help
        return int(exc.code or 0)
    except Exception as exc:  # a bug of ours: still one line, with what to report
        problem = next(iter(str(exc).strip().splitlines()), "")
        print(f"alphascoop: error: unexpected {type(exc).__name__}"
              f"{f': {problem}' if problem else ''} (please report this)", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
