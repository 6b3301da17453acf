"""Re-open instantly: interval tables cached by the content hash of the points.

Entries live in platformdirs' user cache dir ("alphascoop/tables", or $ALPHASCOOP_CACHE_DIR)
as the .npz files `AlphaComplex.save` writes. A corrupt or unreadable entry is deleted and
rebuilt, never an error; a cache that cannot be written is simply skipped. Temporary files of
stores that were killed (a cancelled build process) are removed on every lookup and prune;
only finished entries (named by their key) ever count as results.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import zipfile
from collections.abc import Callable
from pathlib import Path

import numpy as np

from core.atomic import remove_stale_temporaries
from core.complex import AlphaComplex
from core.errors import AlphaScoopError

CACHE_VERSION = 1  # bump when the saved table layout or the build rules change
MAX_CACHE_BYTES = 2 * 1024**3  # oldest entries are pruned beyond this
Progress = Callable[[float, str], None]


def cache_dir() -> Path:
    """The folder holding cached tables ($ALPHASCOOP_CACHE_DIR overrides the platform one)."""
    override = os.environ.get("ALPHASCOOP_CACHE_DIR")
    if override:
        return Path(override)
    from platformdirs import user_cache_dir

    return Path(user_cache_dir("alphascoop")) / "tables"


def points_key(points: np.ndarray) -> str:
    """Hex digest of the points' shape and float64 bytes, plus the cache version."""
    arr = np.ascontiguousarray(points, dtype=np.float64)
    digest = hashlib.blake2b(digest_size=20)
    digest.update(f"alphascoop-table-v{CACHE_VERSION}:{arr.shape}".encode())
    digest.update(memoryview(arr).cast("B"))
    return digest.hexdigest()


def entry_path(points: np.ndarray) -> Path:
    """Where the table of these (n, d) points is (or would be) cached."""
    return cache_dir() / f"{points_key(points)}.npz"


def is_cached(pointset) -> bool:
    """True when a cache entry exists for these points (it may still prove unreadable)."""
    try:
        return entry_path(np.asarray(getattr(pointset, "points", pointset))).is_file()
    except OSError:  # a cache folder we may not read is no cache
        return False


def _load(path: Path, n_points: int) -> AlphaComplex | None:
    """The cached complex, or None (and the entry removed) if it is missing or unusable."""
    try:
        if not path.is_file():
            return None
        if not zipfile.is_zipfile(path):
            raise ValueError("not an .npz archive")
        ac = AlphaComplex.load(path)
        if len(ac.input_index) != n_points:
            raise ValueError("cached table was built from other points")
        return ac
    except (AlphaScoopError, OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
        with contextlib.suppress(OSError):
            path.unlink()
        return None


def store(ac: AlphaComplex, points: np.ndarray) -> Path | None:
    """Save ac as the entry of these points (with its signatures, if computed); None when
    the cache folder cannot be written."""
    path = entry_path(np.asarray(points, dtype=np.float64))
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        ac.save(path)
        prune(path.parent, keep=path)
    except (OSError, AlphaScoopError):
        return None
    return path


def load_cached(points: np.ndarray) -> AlphaComplex | None:
    """The cached complex of these (n, d) points, or None (a bad entry is removed).

    Stale temporaries of killed stores are cleaned from the cache folder first.
    """
    points = np.asarray(points, dtype=np.float64)
    path = entry_path(points)
    remove_stale_temporaries(path.parent)
    ac = _load(path, len(points))
    if ac is not None:
        with contextlib.suppress(OSError):
            os.utime(path)  # mark as recently used
    return ac


def prune(folder: Path, max_bytes: int | None = None, *, keep: Path | None = None) -> None:
    """Delete the least recently used entries until the folder holds at most max_bytes.

    The newest entry (or `keep`, the one just written) always stays, even when it alone is
    larger than max_bytes (default MAX_CACHE_BYTES). Temporary files of running stores are
    left alone and not counted; those of killed stores are deleted.
    """
    limit = MAX_CACHE_BYTES if max_bytes is None else max_bytes
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


def _stat(path: Path) -> os.stat_result | None:
    """The file's stat, or None if it vanished meanwhile (another process pruning)."""
    try:
        return path.stat()
    except OSError:
        return None


def build_cached(pointset, *, use_cache: bool = True, progress: Progress | None = None,
                 signatures: bool = False) -> AlphaComplex:
    """AlphaComplex of pointset.points (or an (n, d) array), from the cache when possible.

    With `signatures`, they are computed too and cached with the table, so that re-opening
    needs no topology pass either.
    """
    points = np.asarray(getattr(pointset, "points", pointset), dtype=np.float64)
    if not use_cache:
        ac = AlphaComplex.from_points(points, progress=progress)
        if signatures:
            ac.signatures()
        return ac
    ac = load_cached(points)
    if ac is not None:
        if progress is not None:
            progress(1.0, "loaded from cache")
        if signatures and "_signatures" not in ac.__dict__:
            ac.signatures()
            store(ac, points)
        return ac
    ac = AlphaComplex.from_points(points, progress=progress)
    if signatures:
        if progress is not None:
            progress(1.0, "topology")
        ac.signatures()
    store(ac, points)
    return ac
