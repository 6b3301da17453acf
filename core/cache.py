"""Re-open instantly: interval tables cached by the content hash of the points.

Entries live in platformdirs' user cache dir ("alphascoop/tables", or $ALPHASCOOP_CACHE_DIR)
as the .npz files `AlphaComplex.save` writes, at most MAX_CACHE_BYTES of them (or
$ALPHASCOOP_CACHE_LIMIT, e.g. "8G": a 1M-point table with its topology is about 1 GB in the
compact layout of core/storage/compact.py; entries of the layout before still load).
core.obtain is the one path that reads and fills it; this module names, reads, writes and
prunes entries. A corrupt or unreadable entry is deleted (and rebuilt by core.obtain), never
an error; a cache that cannot be written is simply skipped. Temporary files of stores that
were killed (a cancelled build process) are removed on every lookup and prune; only finished
entries (named by their key) ever count as results. An entry whose members match the
checksums written last is taken as this program wrote it, without the array-by-array checks
a table file from elsewhere gets (core.storage.tables.load's trust_checksums): the checksums
catch damage, not an entry crafted on purpose in the user's own cache folder.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import re
import warnings
import zipfile
from pathlib import Path

import numpy as np

from core.complex import AlphaComplex
from core.errors import AlphaScoopError
from core.modes.alpha_modes import Mode
from core.storage.atomic import remove_stale_temporaries

CACHE_VERSION = 2  # bump when the build rules change, or older layouts no longer load
MAX_CACHE_BYTES = 2 * 1024**3  # oldest entries are pruned beyond this ($ALPHASCOOP_CACHE_LIMIT)
_UNITS = {"": 1, "K": 1024, "M": 1024**2, "G": 1024**3, "T": 1024**4}
_SIZE = re.compile(r"\s*(\d+(?:\.\d*)?)\s*([KMGT]?)(?:I?B)?\s*", re.IGNORECASE)


def cache_limit() -> int:
    """Bytes the cache may hold: $ALPHASCOOP_CACHE_LIMIT ("8G", "500M", "3.5GiB", bytes) or
    MAX_CACHE_BYTES. A value that is no size is a warning, and the default applies."""
    value = os.environ.get("ALPHASCOOP_CACHE_LIMIT", "").strip()
    if not value:
        return MAX_CACHE_BYTES
    match = _SIZE.fullmatch(value)
    if match is None:
        warnings.warn(f"ALPHASCOOP_CACHE_LIMIT={value!r} is not a size such as 8G or 500M; "
                      f"the table cache keeps its default of {MAX_CACHE_BYTES // 1024**3} GiB",
                      stacklevel=2)
        return MAX_CACHE_BYTES
    return int(float(match[1]) * _UNITS[match[2].upper()])


def cache_dir() -> Path:
    """The folder holding cached tables ($ALPHASCOOP_CACHE_DIR overrides the platform one)."""
    override = os.environ.get("ALPHASCOOP_CACHE_DIR")
    if override:
        return Path(override)
    from platformdirs import user_cache_dir

    return Path(user_cache_dir("alphascoop")) / "tables"


def points_key(points: np.ndarray, mode: Mode | None = None,
               normals: np.ndarray | None = None, weights: np.ndarray | None = None) -> str:
    """Hex digest of the points' shape and float64 bytes, the cache version, for a mode
    (core/modes/alpha_modes.py) its parameters and any given normals, and the weights of a weighted
    set."""
    arr = np.ascontiguousarray(points, dtype=np.float64)
    digest = hashlib.blake2b(digest_size=20)
    digest.update(f"alphascoop-table-v{CACHE_VERSION}:{arr.shape}".encode())
    digest.update(memoryview(arr).cast("B"))
    if mode is not None and mode.active:
        digest.update(f"mode:{mode.key()}".encode())
        if mode.normals == "given" and normals is not None:
            digest.update(memoryview(np.ascontiguousarray(normals, dtype=np.float64)).cast("B"))
            digest.update(b":zero-normals-estimated")  # earlier builds left zero ones classic
    if weights is not None:
        w = np.ascontiguousarray(weights, dtype=np.float64)
        digest.update(f":weights{w.shape}".encode())
        digest.update(memoryview(w).cast("B"))
        # earlier builds took Qhull's lifted hull, whose flat cells on degenerate weighted sets
        # gave voids that are not there (core.backends.geogram now triangulates them)
        digest.update(b":regular-by-geogram")
    return digest.hexdigest()


def entry_path(points: np.ndarray, mode: Mode | None = None,
               normals: np.ndarray | None = None, weights: np.ndarray | None = None, *,
               folder: str | os.PathLike | None = None) -> Path:
    """Where the table of these (n, d) points (in `mode`, with `weights`) is (or would be)
    cached, in `folder` (default cache_dir())."""
    return (Path(folder) if folder is not None else cache_dir()) / (
        f"{points_key(points, mode, normals, weights)}.npz")


def pointset_weights(pointset) -> np.ndarray | None:
    """The (n,) weights a point set carries (its `weights` attribute), None for arrays."""
    weights = getattr(pointset, "weights", None)
    return None if weights is None else np.asarray(weights, dtype=np.float64)


def is_cached(pointset, mode: Mode | None = None, normals: np.ndarray | None = None) -> bool:
    """True when a cache entry exists for these points (it may still prove unreadable)."""
    return entry_exists(entry_path(np.asarray(getattr(pointset, "points", pointset)), mode,
                               normals, pointset_weights(pointset)))


def read_entry(path: Path, n_points: int, mode: Mode) -> tuple[AlphaComplex | None, str | None]:
    """(the cached complex, None), (None, None) when there is no entry, or (None, why) when
    it is unusable (damaged, or built from other points or in another mode: the entry is
    then removed). Stale temporaries of killed stores are cleaned from its folder first; a
    good entry is marked as recently used."""
    with contextlib.suppress(OSError):
        remove_stale_temporaries(path.parent)
    if not entry_exists(path):
        return None, None
    try:
        if not zipfile.is_zipfile(path):
            raise ValueError("not an .npz archive")
        ac = AlphaComplex.load(path, trust_checksums=True)  # written here, checksummed
        if len(ac.input_index) != n_points:
            raise ValueError("it was built from other points")
        if ac.mode != mode:
            raise ValueError("it was built in another mode")
    except (AlphaScoopError, OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile) as exc:
        with contextlib.suppress(OSError):
            path.unlink()
        return None, _reason(exc, path)
    with contextlib.suppress(OSError):
        os.utime(path)  # mark as recently used
    return ac, None


def _reason(exc: BaseException, path: Path) -> str:
    """Why an entry was refused, in a few words without its (long, hashed) file name."""
    text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    text = text.removeprefix(f"{path}: ").removeprefix(f"{path.name}: ")
    return text.removeprefix("not a valid Alpha Scoop table ").strip("()") or "unreadable"


def save_entry(ac: AlphaComplex, path: Path) -> Path | None:
    """Save ac (with its signatures, if computed) as the cache entry `path` and prune the
    folder; None when the cache folder cannot be written."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        ac.save(path)
        prune(path.parent, keep=path)
    except (OSError, AlphaScoopError):
        return None
    return path


def store(ac: AlphaComplex, points: np.ndarray, normals: np.ndarray | None = None,
          weights: np.ndarray | None = None) -> Path | None:
    """Save ac as the entry of these points (and input weights) in ac's mode (with its
    signatures, if computed); None when the cache folder cannot be written."""
    return save_entry(ac, entry_path(np.asarray(points, dtype=np.float64), ac.mode, normals,
                                     weights))


def load_cached(points: np.ndarray, mode: Mode | None = None,
                normals: np.ndarray | None = None,
                weights: np.ndarray | None = None) -> AlphaComplex | None:
    """The cached complex of these (n, d) points in `mode` (with input `weights`), or None (a
    bad entry is removed)."""
    points = np.asarray(points, dtype=np.float64)
    return read_entry(entry_path(points, mode, normals, weights), len(points), mode or Mode())[0]


def prune(folder: Path, max_bytes: int | None = None, *, keep: Path | None = None) -> None:
    """Delete the least recently used entries until the folder holds at most max_bytes.

    The newest entry (or `keep`, the one just written) always stays, even when it alone is
    larger than max_bytes (default cache_limit()). Temporary files of running stores are
    left alone and not counted; those of killed stores are deleted.
    """
    limit = cache_limit() if max_bytes is None else max_bytes
    remove_stale_temporaries(folder)
    entries = [(st.st_mtime, st.st_size, p) for p in folder.glob("*.npz")
               if not p.name.startswith(".") and (st := _stat(p)) is not None]
    entries.sort(key=lambda e: (e[2] == keep, e[0]), reverse=True)
    total = 0
    for i, (_, size, entry) in enumerate(entries):
        total += size
        if total > limit and i > 0:
            with contextlib.suppress(OSError):
                entry.unlink()


def entry_exists(path: Path) -> bool:
    """The entry `path` is a file; False when its folder may not be read (no cache)."""
    try:
        return path.is_file()
    except OSError:
        return False


def _stat(path: Path) -> os.stat_result | None:
    """The file's stat, or None if it vanished meanwhile (another process pruning)."""
    try:
        return path.stat()
    except OSError:
        return None
