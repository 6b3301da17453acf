"""Atomic writes: everything goes to a temporary file beside the target, then os.replace.

Shared by core.storage (saved tables) and core.export (every exported file).
"""

from __future__ import annotations

import contextlib
import os
import secrets
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import BinaryIO

from core.errors import FileFormatError


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path (same folder and extension) that replaces `path` on success.

    On any exception, including Cancelled or KeyboardInterrupt, the temporary file is
    removed and an existing file at `path` is left untouched.
    """
    path = Path(path)
    if not path.parent.is_dir():
        raise FileFormatError(f"{path}: folder {path.parent} does not exist")
    tmp = path.parent / f".{path.stem}.{secrets.token_hex(6)}.tmp{path.suffix}"
    try:  # mode 0o666 minus the umask, like any new file (mkstemp would give 0o600)
        os.close(os.open(tmp, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o666))
    except OSError as exc:
        raise FileFormatError(f"{path}: cannot write here ({exc.strerror})") from None
    try:
        yield Path(tmp)
        _fsync(tmp)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _fsync(name: str) -> None:
    """Flush the written file to disk before it replaces the old one."""
    with open(name, "rb+") as fh:
        os.fsync(fh.fileno())


def atomic_write(path: str | os.PathLike, write: Callable[[BinaryIO], object]) -> None:
    """Call write(binary_file) on a temporary file, then move it over `path`."""
    with atomic_path(path) as tmp, open(tmp, "wb") as fh:
        write(fh)


def atomic_write_text(path: str | os.PathLike, text: str) -> None:
    """Write `text` as UTF-8 atomically."""
    atomic_write(path, lambda fh: fh.write(text.encode("utf-8")))
