"""Never write over the file being read: an export whose target is its source is refused.

"The same file" means the same file on disk (device and inode), not the same string: a path
through `..`, a symbolic link or a hard link to the source is refused too.
"""

from __future__ import annotations

import os

from core.errors import InputError


def same_file(a: str | os.PathLike, b: str | os.PathLike) -> bool:
    """True when both paths exist and name one file on disk (os.path.samefile)."""
    try:
        return os.path.samefile(a, b)
    except (OSError, ValueError):  # one of them does not exist, or cannot be looked at
        return False


def refuse_source(target: str | os.PathLike, source: str | os.PathLike | None) -> None:
    """InputError when writing `target` would replace `source`, the file the data came from."""
    if source is not None and same_file(target, source):
        raise InputError(f"{target}: this is the input file {source}; refusing to overwrite "
                         "it (choose another output name)")
