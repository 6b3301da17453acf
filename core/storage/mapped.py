"""Arrays as a folder of raw .npy files that other processes map instead of reading: how the
window's build process hands a table to the window and to the topology process through
shared memory (a folder on /dev/shm) without a copy or a read.

`write_arrays` writes one .npy per array on two threads (a copy into tmpfs is memory-bound
and leaves the GIL) after checking the folder's free space; `map_arrays` maps them
read-only (np.load's mmap_mode="r"): every process mapping the same files shares their
pages, and a write through them is a ValueError, never a silent change of a table another
process also uses. Unlinking the files once all readers mapped them keeps the pages until
the last mapping goes (the kernel's rule), so nothing is left in /dev/shm when the readers
end; a mapping goes when the last array over it is garbage.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Mapping
from pathlib import Path

import numpy as np

SUFFIX = ".npy"
HEADER_BYTES = 4096  # per file: the .npy header and the page it rounds up to
ROOM_MARGIN = 256 * 2**20  # free space left in the folder's file system after a write


def bytes_needed(arrays: Mapping[str, np.ndarray]) -> int:
    """What write_arrays takes of the folder's file system, rounded up per file."""
    return sum(np.asarray(a).nbytes + HEADER_BYTES for a in arrays.values())


def has_room(folder: str | os.PathLike, needed: int) -> bool:
    """True when the file system of folder has `needed` bytes free and ROOM_MARGIN over."""
    try:
        stat = os.statvfs(folder)
    except OSError:
        return False
    return stat.f_bavail * stat.f_frsize >= needed + ROOM_MARGIN


def write_arrays(folder: str | os.PathLike, arrays: Mapping[str, np.ndarray]) -> bool:
    """Write each array as folder/<name>.npy (names are plain file names); False, with
    nothing written, when the folder's file system lacks the room (then the caller hands
    the arrays over another way). OSError (the space ran out meanwhile) leaves the files
    that were written: the caller removes its folder."""
    if not has_room(folder, bytes_needed(arrays)):
        return False
    shares: list[list[str]] = [[], []]
    loads = [0, 0]
    for name in sorted(arrays, key=lambda n: -np.asarray(arrays[n]).nbytes):
        lighter = loads.index(min(loads))  # biggest first onto the lighter thread
        shares[lighter].append(name)
        loads[lighter] += np.asarray(arrays[name]).nbytes
    errors: list[BaseException] = []

    def write(names: list[str]) -> None:
        try:
            for name in names:
                np.save(Path(folder) / f"{name}{SUFFIX}", arrays[name], allow_pickle=False)
        except BaseException as error:  # raised in the caller: never a file silently missing
            errors.append(error)

    helper = threading.Thread(target=write, args=(shares[1],), name="alphascoop-map-write")
    helper.start()
    write(shares[0])
    helper.join()
    if errors:
        raise errors[0]
    return True


def map_arrays(folder: str | os.PathLike) -> dict[str, np.ndarray]:
    """Every array write_arrays wrote in folder by name, mapped read-only: no copy, and no
    read until a page is touched."""
    out = {}
    for path in sorted(Path(folder).glob(f"*{SUFFIX}")):
        array = np.asarray(np.load(path, mmap_mode="r", allow_pickle=False))
        array.flags.writeable = False  # already so (mode "r"); said for the reader
        out[path.name.removesuffix(SUFFIX)] = array
    return out
