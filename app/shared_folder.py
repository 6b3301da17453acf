"""A table handed over in shared memory, and how long its files live.

The window's build runner (app.build_process) makes a SharedFolder on /dev/shm; the build
process writes the table into it (core.storage.tables.save_mapped) and hands it over before it
writes the cache entry; the window and the topology process map it (core.storage.mapped: no copy, no
read). Each holder lets go once it has mapped the table (or given up: cancelled, superseded,
failed), and the folder is removed when the last one has, so the pages live on only in those
mappings and are returned when the last array over them is gone. A window killed before that
leaves a folder named after its pid, which the next window removes
(app.child_process.remove_orphans).
"""

from __future__ import annotations

import shutil
import threading
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from app import child_process

PREFIX = "alphascoop-shared-"


class SharedFolder:
    """A scratch folder in shared memory, removed once every holder let go; its maker holds
    it from the start (`release`), others through `hold`."""

    def __init__(self, root: str | Path | None = None) -> None:
        """Make the folder in root (default child_process.SHARED_ROOT; OSError when it
        cannot be made)."""
        self.path, self._owner_lock = child_process.make_scratch(
            PREFIX, child_process.SHARED_ROOT if root is None else root)
        self._lock = threading.Lock()
        self._holders = 1
        self._release_own = self._releaser()

    @classmethod
    def make(cls, root: str | Path | None = None) -> SharedFolder | None:
        """A new folder in root (default child_process.SHARED_ROOT), None when there is no
        shared memory to put one in (then the table is handed over as a file)."""
        root = child_process.SHARED_ROOT if root is None else root
        if not Path(root).is_dir():
            return None
        try:
            return cls(root)
        except OSError:
            return None

    @property
    def removed(self) -> bool:
        """True once the last holder let go and the folder is gone."""
        with self._lock:
            return self._holders == 0

    def hold(self) -> Callable[[], None]:
        """One more holder; returns its release (calling it again does nothing)."""
        with self._lock:
            if self._holders == 0:
                raise ValueError("the shared folder is already removed")
            self._holders += 1
        return self._releaser()

    def release(self) -> None:
        """The maker lets go (again: nothing)."""
        self._release_own()

    def _releaser(self) -> Callable[[], None]:
        """A release that counts once."""
        done = threading.Event()

        def release() -> None:
            with self._lock:
                if done.is_set():
                    return
                done.set()
                self._holders -= 1
                if self._holders:
                    return
                self._owner_lock.close()
                shutil.rmtree(self.path, ignore_errors=True)

        return release


@dataclass(frozen=True, eq=False)
class SharedTable:
    """A table the build process handed over in `folder`; it holds a lock on the file
    `saving` until it has written the table's cache entry (the topology process waits for
    it before rewriting that entry with the signatures)."""

    folder: SharedFolder
    saving: Path
