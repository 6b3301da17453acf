"""The messages between the window and its build and topology processes, as frozen
dataclasses.

A child process (app.child_process) gets its job as one message and answers through a pipe:
Reported progress, hand-overs while it works (TableHandedOver, OpeningFound, TableRead,
TopologyWritten), then Finished with its result or Failed. Only app.child_process turns them
into plain data (`to_plain`: dicts of str, int, float, bool and None, tagged with the class
name) and back (`from_plain`), at the pipe and the process's arguments; everywhere else they
are these classes.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from core.modes.alpha_modes import Mode, make_mode

Plain = dict | str | int | float | bool | None


@dataclass(frozen=True)
class Reported:
    """The child's progress: fraction 0..1 of its work, and the stage it is at."""

    fraction: float
    stage: str


@dataclass(frozen=True)
class Finished:
    """The child's work is done: its result (a message, or plain text)."""

    result: object


@dataclass(frozen=True)
class Failed:
    """The child's work raised: the core.errors class name (or "MemoryError") and its text."""

    error: str
    text: str


@dataclass(frozen=True)
class BuildJob:
    """What a build process builds, beside the points (and weights, normals) in its folder:
    the alpha `mode`, whether the `signatures` too, the cache entry to `save_to` (None: no
    cache), the triangulation `backend` (None: automatic) and the `shared` memory folder to
    hand the table over in (None: through files)."""

    mode: Mode
    signatures: bool
    save_to: str | None
    backend: str | None
    shared: str | None


@dataclass(frozen=True)
class TableHandedOver:
    """The build process's table: in the shared folder `table` (`mapped`) or in that file,
    the cursor's orders (a folder, a file, or None when not found), and the lock file the
    process holds until it has written the cache entry (`saving`)."""

    table: str
    mapped: bool
    orders: str | None
    saving: str


@dataclass(frozen=True)
class OpeningFound:
    """The table's quick opening alpha (None when the signatures hold it or none was
    found): a build process's second hand-over, and its result."""

    opening_alpha: float | None


@dataclass(frozen=True)
class TopologyJob:
    """What a topology process reads: the `table` (a file, or a shared folder it maps), the
    cache `entry` to rewrite with the signatures (or None), the hand-over file `target` to
    write, and the lock file the build process holds while it writes the entry (`saving`)."""

    table: str
    entry: str | None
    target: str
    saving: str | None


@dataclass(frozen=True)
class TableRead:
    """The topology process has read (or mapped) its table: a shared folder may go."""


@dataclass(frozen=True)
class TopologyWritten:
    """The topology process has written its hand-over file `target` (the cache entry's
    rewrite may follow)."""

    target: str


MESSAGES = {cls.__name__: cls for cls in (
    Reported, Finished, Failed, BuildJob, TableHandedOver, OpeningFound, TopologyJob,
    TableRead, TopologyWritten)}


def to_plain(value: object) -> Plain:
    """A message (or plain value) as plain data: {"kind": class name, field: value, ...}."""
    if type(value) not in MESSAGES.values():
        return value  # plain already: a str result, None
    plain: dict = {"kind": type(value).__name__}
    for field in fields(value):
        item = getattr(value, field.name)
        plain[field.name] = item.to_dict() if isinstance(item, Mode) else to_plain(item)
    return plain


def from_plain(plain: Plain) -> object:
    """The message `to_plain` made (plain values are returned as they are); ValueError for
    a dict of an unknown kind or with other fields."""
    if not isinstance(plain, dict):
        return plain
    kind = MESSAGES.get(plain.get("kind"))
    names = None if kind is None else {field.name for field in fields(kind)}
    if kind is None or set(plain) - {"kind"} != names:
        raise ValueError(f"not a message of the window's processes: {sorted(plain)}")
    return kind(**{name: _mode_of_dict(plain[name]) if kind is BuildJob and name == "mode"
                   else from_plain(plain[name]) for name in names})


def _mode_of_dict(saved: dict) -> Mode:
    """The Mode of Mode.to_dict()."""
    return make_mode(saved["density"], saved["combine"], saved["anisotropy"],
                     saved["normals"] == "given")
