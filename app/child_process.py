"""Run a long pass in a spawned child process that Cancel kills at once and that never holds
the window's GIL (the build: app.build_process; the topology: app.topology_process).

The child runs `work(*args, progress)` (or `work(*args, progress, hand_over)`, see
run_in_child) and answers through a pipe with the messages of app.messages: Reported for
each progress report, each message it hands over, then Finished (its result) or Failed (its
error). Those messages, and the job in `args`, cross the process boundary as plain data
(app.messages.to_plain), here only. Its files
live in a temporary folder named after the window's pid (`scratch`, `make_scratch`; a table
handed over in shared memory lives in one on /dev/shm: app.shared_folder), so a window that
was killed leaves folders the next window can recognise and remove (`remove_orphans`, in the
temp dir and in /dev/shm); the child also exits by itself when its window is gone.
"""

from __future__ import annotations

import contextlib
import fcntl
import multiprocessing
import os
import shutil
import signal
import tempfile
import threading
import time
from collections.abc import Callable, Iterator
from multiprocessing.connection import Connection
from pathlib import Path
from typing import BinaryIO, Protocol

from app.messages import Failed, Finished, Reported, from_plain, to_plain
from core import errors
from core.progress import Progress

POLL_SECONDS = 0.1
PARENT_POLL_SECONDS = 1.0
PREFIXES = ("alphascoop-build-", "alphascoop-topology-", "alphascoop-shared-")
SHARED_ROOT = Path("/dev/shm")  # shared memory as files (Linux); absent elsewhere


LOCK_NAME = ".owner.lock"


class CancelFlag(Protocol):
    """What run_in_child watches: a threading.Event, or anything else that says is_set()."""

    def is_set(self) -> bool: ...


@contextlib.contextmanager
def scratch(prefix: str) -> Iterator[str]:
    """A temporary folder of this process (make_scratch in the temp dir), removed on exit."""
    folder, lock = make_scratch(prefix)
    try:
        yield str(folder)
    finally:
        lock.close()
        shutil.rmtree(folder, ignore_errors=True)


def make_scratch(prefix: str, root: str | os.PathLike | None = None) -> tuple[Path, BinaryIO]:
    """A new folder '<prefix><pid>-<random>' of this process in root (default: the temp dir;
    prefix from PREFIXES) and the open lock file in it: the process holds an advisory lock on
    it for as long as the folder exists (close it before removing the folder), so
    `remove_orphans` can tell a living owner even where its pid is not visible (another pid
    namespace sharing the folder); the kernel drops the lock when the process dies."""
    folder = Path(tempfile.mkdtemp(prefix=f"{prefix}{os.getpid()}-", dir=root))
    try:
        lock = open(folder / LOCK_NAME, "wb")  # the caller closes it
        fcntl.flock(lock, fcntl.LOCK_EX)
    except BaseException:
        shutil.rmtree(folder, ignore_errors=True)
        raise
    return folder, lock


def remove_orphans(folder: str | os.PathLike | None = None) -> list[Path]:
    """Remove the scratch folders in `folder` (default: the temp dir and SHARED_ROOT) whose
    owner process is dead (a window killed mid-build); folders of living processes, and names
    without a pid, stay. Returns what was removed."""
    roots = [Path(folder)] if folder is not None else [Path(tempfile.gettempdir()), SHARED_ROOT]
    removed = []
    for path in (path for root in roots if root.is_dir()
                 for path in root.glob("alphascoop-*-*-*")):
        pid = _owner(path.name)
        if pid is not None and path.is_dir() and not _alive(pid) and not _locked(path):
            shutil.rmtree(path, ignore_errors=True)
            removed.append(path)
    return removed


def _locked(folder: Path) -> bool:
    """True when some living process holds the folder's owner lock (see `scratch`)."""
    try:
        with open(folder / LOCK_NAME, "rb") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except FileNotFoundError:
        return False
    except OSError:  # held (BlockingIOError), or unreadable: leave the folder alone
        return True
    return False


def _owner(name: str) -> int | None:
    """The pid in a scratch folder's name, None for other names."""
    for prefix in PREFIXES:
        head, _, rest = name.partition(prefix)
        pid = rest.split("-", 1)[0]
        if not head and rest and pid.isdigit():
            return int(pid)
    return None


def _alive(pid: int) -> bool:
    """True when a process with this pid runs (ours or another user's; a zombie is dead)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        pass
    try:  # Linux: the state letter follows the parenthesised command name
        state = Path(f"/proc/{pid}/stat").read_text().rpartition(")")[2].split()[0]
    except (OSError, IndexError):
        return True
    return state not in ("Z", "X")


class LeaveRunning(Exception):
    """Raised by a `handed` callback of run_in_child: the caller has what it needs, the child
    finishes its work on its own (run_in_child's `finish`)."""


def run_in_child(work: Callable[..., object], args: tuple, progress: Progress,
                 cancel: CancelFlag, name: str,
                 handed: Callable[[object], None] | None = None,
                 finish: Callable[[], None] | None = None) -> object:
    """Run work(*args, progress) in a spawned process; what it returned (an app.messages
    message or plain text; args too are messages or plain values). Its errors are raised
    here as the same core.errors class (MemoryError as MemoryError); Cancelled as soon as
    `cancel` is set (the child is killed).

    With `handed`, work gets a third callable, hand_over(message), to pass a result before
    it is done (a file it has finished writing, say): handed(message) runs here as soon as
    it comes, while the child goes on; its errors stop the child too. When it raises
    LeaveRunning, None is returned at once and the child is left to end on its own,
    followed by a thread (killed as soon as `cancel` is set); `finish()` runs once it has
    ended (else right here, when this returns or raises)."""
    context = multiprocessing.get_context("spawn")  # forking a process with Qt threads is unsafe
    receiver, sender = context.Pipe(duplex=False)
    plain_args = tuple(to_plain(arg) for arg in args)
    child = context.Process(target=child_main,
                            args=(work, plain_args, sender, os.getpid(), handed is not None),
                            name=name, daemon=True)
    child.start()
    sender.close()
    left = False
    try:
        return _follow(child, receiver, progress, cancel, handed)
    except LeaveRunning:
        left = True
        threading.Thread(target=_end, args=(child, receiver, cancel, finish),
                         name=f"{name}-follower", daemon=True).start()
        return None
    finally:
        if not left:
            _end(child, receiver, _ENDED, finish)


class _Ended:
    """A cancel flag that is always set: end the child now."""

    def is_set(self) -> bool:
        return True


_ENDED = _Ended()


def _end(child, receiver: Connection, cancel: CancelFlag,
         finish: Callable[[], None] | None) -> None:
    """Wait until the child has ended (killed once cancel is set), then close and finish."""
    try:
        while child.is_alive() and not cancel.is_set():
            child.join(POLL_SECONDS)
        if child.is_alive():
            child.kill()
        child.join()
        receiver.close()
    finally:
        if finish is not None:
            finish()


def _follow(child, receiver: Connection, progress: Progress, cancel: CancelFlag,
            handed: Callable[[object], None] | None = None) -> object:
    """Relay the child's messages until it is done; Cancelled as soon as cancel is set."""
    while True:
        if cancel.is_set():
            raise errors.Cancelled("cancelled by the user")
        try:
            message = from_plain(receiver.recv()) if receiver.poll(POLL_SECONDS) else None
        except EOFError:
            message = _DIED
        if message is None:
            continue
        if isinstance(message, Reported):
            progress(message.fraction, message.stage)
        elif isinstance(message, Finished):
            return message.result
        elif isinstance(message, Failed):
            raise _error(message.error, message.text)
        elif handed is not None and message is not _DIED:
            handed(message)
        else:
            child.join(1.0)
            raise errors.AlphaScoopError(
                f"the background process stopped without a result (exit code "
                f"{child.exitcode}; out of memory?)")


_DIED = object()  # the pipe closed before Finished or Failed came


def _error(name: str, text: str) -> Exception:
    """The exception a child reported by class name."""
    if name == "MemoryError":
        return MemoryError(text)
    error_class = getattr(errors, name, None)
    if isinstance(error_class, type) and issubclass(error_class, errors.AlphaScoopError):
        return error_class(text)
    return errors.AlphaScoopError(text)


def child_main(work: Callable[..., object], args: tuple, sender: Connection, parent: int,
               hands_over: bool = False) -> None:
    """Body of a child process: run work on the messages in args (given hand_over too when
    `hands_over`), send its result (Finished) or its error (Failed), as plain data."""
    _show_name(multiprocessing.current_process().name)
    threading.Thread(target=_exit_with_parent, args=(parent,), daemon=True).start()

    def send(message: object) -> None:
        sender.send(to_plain(message))

    callbacks: list[Callable] = [lambda f, s: send(Reported(f, s))]
    if hands_over:
        callbacks.append(send)
    try:
        send(Finished(work(*(from_plain(arg) for arg in args), *callbacks)))
    except errors.AlphaScoopError as error:
        send(Failed(type(error).__name__, str(error)))
    except MemoryError:
        send(Failed("MemoryError", "not enough memory for this point set"))
    except Exception as error:  # reported to the user as one line, never a traceback
        send(Failed("AlphaScoopError", f"unexpected error in the background process "
                                       f"({type(error).__name__}: {error})"))
    finally:
        sender.close()


def _show_name(name: str) -> None:
    """Name this process as ps and top show it (Linux keeps its first 15 characters; a no-op
    elsewhere): a user, or a benchmark sampling its peak memory, can tell which pass it is."""
    with contextlib.suppress(OSError):
        Path("/proc/self/comm").write_text(name[:15], encoding="utf-8")


def _exit_with_parent(parent: int) -> None:
    """Child thread: end the process once the window that started it is gone (killed
    windows leave no build running; its scratch folder is removed by the next window)."""
    while os.getppid() == parent:
        time.sleep(PARENT_POLL_SECONDS)
    os.kill(os.getpid(), signal.SIGKILL)  # at once: nothing of the pass is worth keeping
