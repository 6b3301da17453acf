"""Atomic writes: everything goes to a temporary file beside the target, then os.replace.

The one atomic-write helper, shared by core.storage.tables (saved and cached tables), core.export
(every exported file) and the app's screenshots. Temporary files are named
`.NAME.alphascoop-tmp-<host>-<pid>-<random>EXT` (EXT kept: some writers choose the format by
it), so they are plainly ours, and one left by a killed writer is removed by the next write
to its folder once that writer is gone (see remove_stale_temporaries).
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import re
import secrets
import socket
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import BinaryIO

from core.errors import FileFormatError

TEMP_MARK = "alphascoop-tmp"
STALE_UNKNOWN_S = 3600.0  # a temporary whose writer cannot be checked (other host, old name)
STALE_ANYWAY_S = 86400.0  # no write takes a day: the pid was reused by another process
HOST = hashlib.blake2s(socket.gethostname().encode(), digest_size=3).hexdigest()
_TEMPORARY = re.compile(rf"^\..+\.{TEMP_MARK}-(?P<host>[0-9a-f]{{6}})-(?P<pid>\d+)-"
                        r"[0-9a-f]{8}(\.[^.]*)?$")
_LEGACY = re.compile(r"^\..+\.[0-9a-f]{12}\.tmp(\.[^.]*)?$")  # earlier builds' naming


def temporary_name(path: str | os.PathLike, *, pid: int | None = None,
                   host: str | None = None) -> str:
    """The name of a new temporary file for `path` (this host and process by default)."""
    path = Path(path)
    pid = os.getpid() if pid is None else pid
    return f".{path.name}.{TEMP_MARK}-{host or HOST}-{pid}-{secrets.token_hex(4)}{path.suffix}"


def is_temporary(name: str) -> bool:
    """True for a file name that one of our atomic writes makes (this or an older version)."""
    return bool(_TEMPORARY.match(name) or _LEGACY.match(name))


def _writer_alive(pid: int) -> bool | None:
    """Whether process `pid` of this host runs; None where that cannot be asked safely."""
    if sys.platform == "win32":  # os.kill would terminate it there
        return None
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True  # it exists but is someone else's, or an absurd pid: leave the file
    return True


def _is_stale(name: str, age: float) -> bool:
    """True for our temporary `name`, last written `age` seconds ago, whose writer is gone."""
    match = _TEMPORARY.match(name)
    if match is None:
        return bool(_LEGACY.match(name)) and age > STALE_UNKNOWN_S
    if age > STALE_ANYWAY_S:
        return True
    alive = _writer_alive(int(match["pid"])) if match["host"] == HOST else None
    return age > STALE_UNKNOWN_S if alive is None else not alive


def remove_stale_temporaries(folder: str | os.PathLike) -> int:
    """Delete the temporary files our killed writers left in `folder`; returns how many.

    Only regular files named by our pattern are touched, and only when their writer process
    is gone (checked on this host) or they are old enough that no write can still own them.
    """
    removed, now = 0, time.time()
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return 0
    for entry in entries:
        if not entry.name.startswith(".") or not is_temporary(entry.name):
            continue
        try:
            if entry.is_file(follow_symlinks=False) and _is_stale(
                    entry.name, now - entry.stat(follow_symlinks=False).st_mtime):
                os.unlink(entry.path)
                removed += 1
        except OSError:  # vanished meanwhile, or not ours to delete
            continue
    return removed


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path (same folder and extension) that replaces `path` on success.

    On any exception, including Cancelled or KeyboardInterrupt, the temporary file is
    removed and an existing file at `path` is left untouched. Stale temporaries of earlier,
    killed writes in the folder are removed first.
    """
    path = Path(path)
    if not path.parent.is_dir():
        raise FileFormatError(f"{path}: folder {path.parent} does not exist")
    remove_stale_temporaries(path.parent)
    tmp = path.parent / temporary_name(path)
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


def _fsync(name: str | os.PathLike) -> None:
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
