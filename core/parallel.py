"""Memory-bound numpy passes split between two threads (the explorer's slider steps).

numpy releases the GIL in take/compress/comparisons on plain dtypes, and on this kind of
machine such passes are bound by memory latency, not by one core: two halves at once take
little more than half the time. Short passes stay in the calling thread.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor, wait
from typing import TypeVar

import numpy as np

from core.arrays import ascends

PARALLEL_ABOVE = 1 << 19  # elements: longer passes are split between two threads
HELPER = "alphascoop-helper"
PASSES = "passes"  # the helper role of the build's and the topology's passes
_lock = threading.Lock()
_pools: dict[str, ThreadPoolExecutor] = {}
_unsplit = threading.local()  # .on: this thread runs an `unsplit` job
T = TypeVar("T")
U = TypeVar("U")


def _pool(role: str) -> ThreadPoolExecutor:
    """The one-thread helper for `role`: the slider's split passes ("halves"), the build's
    and topology's ("passes") and background jobs get separate ones, so a slider step never
    queues behind a cursor being set up or a table being built in the same process."""
    with _lock:
        if role not in _pools:
            _pools[role] = ThreadPoolExecutor(1, thread_name_prefix=f"{HELPER}-{role}")
        return _pools[role]


def together(job: Callable[[], T]) -> Callable[[], T]:
    """Start job in a helper thread; returns a function that waits for its result (for
    the caller to do other work meanwhile). In that helper itself the job runs at once
    (waiting on itself would deadlock)."""
    if _inside("jobs"):
        value = job()
        return lambda: value
    return _pool("jobs").submit(job).result


def both(first: Callable[[], T], second: Callable[[], U]) -> tuple[T, U]:
    """(first(), second()) run at once, second in the passes' helper thread (both in this
    thread when it is that helper: waiting on itself would deadlock)."""
    if _inside(PASSES):
        return first(), second()
    other = _pool(PASSES).submit(second)
    try:
        mine = first()
    except BaseException:
        wait([other])  # the helper is done with the caller's arrays; first's error is raised
        raise
    return mine, other.result()


def unsplit(job: Callable[[], T]) -> T:
    """job() with every pass in it run in this thread, none handed to a helper: for a job
    run beside another that splits its own passes (the second core is taken; sharing the
    passes' one helper would queue each job's halves behind the other's)."""
    before = getattr(_unsplit, "on", False)  # an unsplit job inside another stays unsplit
    _unsplit.on = True
    try:
        return job()
    finally:
        _unsplit.on = before


def in_unsplit() -> bool:
    """Whether this thread runs an `unsplit` job: its work should take no second core (a
    triangulation in two halves included, core.backends.split)."""
    return bool(getattr(_unsplit, "on", False))


def _inside(role: str) -> bool:
    """Whether this thread is `role`'s helper (waiting on itself would deadlock), or runs
    an `unsplit` job."""
    if in_unsplit():
        return True
    return threading.current_thread().name.startswith(f"{HELPER}-{role}")


def halves(part: Callable[[int, int], object], n: int, role: str = "halves") -> None:
    """part(start, stop) over [0, n): long ranges in two halves at once, one of them in
    `role`'s helper thread. These numpy passes release the GIL and are bound by memory
    latency, so the second core nearly halves them."""
    if n < PARALLEL_ABOVE or _inside(role):
        part(0, n)  # short, or already in that helper
        return
    other = _pool(role).submit(part, n // 2, n)
    part(0, n // 2)
    other.result()


def in_chunks(part: Callable[[int, int], object], n: int, size: int) -> None:
    """part(start, stop) over [0, n) in chunks of `size` (the same boundaries as a plain
    loop, so every row sees the same arithmetic), alternate chunks in a helper thread."""
    starts = range(0, n, size)
    if len(starts) < 2 or _inside(PASSES):
        for lo in starts:
            part(lo, min(lo + size, n))
        return

    def run(mine: range) -> None:
        for lo in mine:
            part(lo, min(lo + size, n))

    other = _pool(PASSES).submit(run, starts[1::2])
    try:
        run(starts[0::2])
    finally:
        other.result()


def take(source: np.ndarray, ids: np.ndarray, dtype: type | None = None) -> np.ndarray:
    """source[ids] along the first axis (ids in [-len, len), negatives from the end as in
    Python), gathered in halves: random gathers are bound by memory latency. `dtype`: the
    result's, cast while gathering (default source's)."""
    out = np.empty((len(ids), *source.shape[1:]), dtype=dtype or source.dtype)

    def part(start: int, stop: int) -> None:
        if out.dtype == source.dtype:
            np.take(source, ids[start:stop], axis=0, out=out[start:stop], mode="wrap")
        else:
            out[start:stop] = np.take(source, ids[start:stop], axis=0, mode="wrap")

    halves(part, len(ids), PASSES)
    return out


def inverse_permutation(order: np.ndarray) -> np.ndarray:
    """(n,) int32 inverse of the permutation `order`: the new row of each old row of an
    array reordered by it; its two halves scattered at once."""
    inverse = np.empty(len(order), dtype=np.int32)

    def part(lo: int, hi: int) -> None:
        inverse[order[lo:hi]] = np.arange(lo, hi, dtype=np.int32)

    halves(part, len(order), PASSES)
    return inverse


def renumber(ids: np.ndarray, inverse: np.ndarray) -> np.ndarray:
    """int32 `ids` (-1 = none) renumbered by an int32 `inverse` (inverse_permutation; -1
    for rows not kept): one gather in halves from the inverse with -1 appended, which index
    -1 reads."""
    return take(np.append(inverse, np.int32(-1)), ids.ravel()).reshape(ids.shape)


def nonzero(test: Callable[[int, int], np.ndarray], n: int) -> np.ndarray:
    """(k,) int64 flat indices, ascending, of the True items of the (n, ...) boolean array
    whose rows [lo, hi) test(lo, hi) gives (as np.flatnonzero of the whole): each half's
    rows tested and listed at once, then the two lists joined in place."""
    found: dict[int, tuple[int, np.ndarray]] = {}  # first row -> (first flat index, list)

    def find(start: int, stop: int) -> None:
        mask = test(start, stop)
        found[start] = (start * (mask.size // max(stop - start, 1)), np.flatnonzero(mask))

    halves(find, n, PASSES)
    parts = [found[lo] for lo in sorted(found)]
    if len(parts) == 1:
        return parts[0][1].astype(np.int64, copy=False)
    ends = np.cumsum([0] + [len(hits) for _, hits in parts])
    out = np.empty(int(ends[-1]), dtype=np.int64)

    def join(k: int) -> None:
        offset, hits = parts[k]
        np.add(hits, offset, out=out[ends[k]:ends[k + 1]])

    both(lambda: join(0), lambda: join(1))
    return out


def cast(source: np.ndarray, dtype: type) -> np.ndarray:
    """source.astype(dtype) (a new array), the rows in halves."""
    out = np.empty(source.shape, dtype=dtype)

    def part(start: int, stop: int) -> None:
        out[start:stop] = source[start:stop]

    halves(part, len(source), PASSES)
    return out


def rows_cols(slots: np.ndarray, width: int) -> tuple[np.ndarray, np.ndarray]:
    """np.divmod(slots, width) of (n,) int64 flat slots: (rows, columns), in halves (as a
    floor division and a product: numpy divides by a constant several times faster than
    it takes remainders)."""
    rows, cols = np.empty(len(slots), dtype=np.int64), np.empty(len(slots), dtype=np.int64)

    def part(start: int, stop: int) -> None:
        np.floor_divide(slots[start:stop], width, out=rows[start:stop])
        np.multiply(rows[start:stop], width, out=cols[start:stop])
        np.subtract(slots[start:stop], cols[start:stop], out=cols[start:stop])

    halves(part, len(slots), PASSES)
    return rows, cols


def searchsorted(ascending: np.ndarray, values: np.ndarray, side: str = "left") -> np.ndarray:
    """np.searchsorted(ascending, values, side) as (n,) intp, the values in halves."""
    out = np.empty(len(values), dtype=np.intp)

    def part(start: int, stop: int) -> None:
        out[start:stop] = np.searchsorted(ascending, values[start:stop], side=side)

    halves(part, len(values), PASSES)
    return out


def searchsorted_ascending(ascending: np.ndarray, values: np.ndarray, side: str = "left",
                           chunk: int = 1 << 12) -> np.ndarray:
    """np.searchsorted(ascending, values, side) as (n,) intp for ascending `values` too:
    chunk by chunk, each searched only in the stretch of `ascending` its two ends bound (a
    binary search that stays in cache), alternate chunks in a helper thread; values that
    do not ascend are searched whole (`searchsorted`)."""
    if not ascends(values):
        return searchsorted(ascending, values, side)
    out = np.empty(len(values), dtype=np.intp)

    def part(start: int, stop: int) -> None:
        piece = values[start:stop]
        first = int(np.searchsorted(ascending, piece[0], side))
        last = int(np.searchsorted(ascending, piece[-1], side))
        np.add(np.searchsorted(ascending[first:last], piece, side), first, out=out[start:stop])

    in_chunks(part, len(values), chunk)
    return out


def argsort_stable(values: np.ndarray) -> np.ndarray:
    """np.argsort(values, kind="stable") as (n,) intp: long arrays as two halves sorted at
    once, then merged (ties keep the first half first, so the order is the same)."""
    n = len(values)
    if n < PARALLEL_ABOVE or _inside(PASSES):
        return np.argsort(values, kind="stable")
    half = n // 2
    first, second = both(lambda: np.argsort(values[:half], kind="stable"),
                         lambda: np.argsort(values[half:], kind="stable"))
    second += half
    at = np.searchsorted(np.take(values, first), np.take(values, second), side="right")
    at += np.arange(len(second))  # where each of the second half lands in the merged order
    out = np.empty(n, dtype=np.intp)
    from_second = np.zeros(n, dtype=bool)
    from_second[at] = True
    out[at] = second
    out[~from_second] = first
    return out


def reduce_segments(ufunc: np.ufunc, values: Callable[[int, int], np.ndarray],
                    starts: np.ndarray, n: int, dtype: type) -> np.ndarray:
    """ufunc.reduceat over the segments [starts[i], starts[i+1]) of an n-long sequence
    whose items [lo, hi) `values(lo, hi)` gives; the segments in halves (each half gathers
    only its own items)."""
    out = np.empty(len(starts), dtype=dtype)

    def part(first: int, last: int) -> None:
        lo = int(starts[first])
        hi = int(starts[last]) if last < len(starts) else n
        out[first:last] = ufunc.reduceat(values(lo, hi), starts[first:last] - lo)

    halves(part, len(starts), PASSES)
    return out


def select(keep: np.ndarray, pairs: list[tuple[np.ndarray, np.ndarray]],
           ranks: np.ndarray | None = None) -> None:
    """out[:] = source[keep] for each (source, out) pair, and ranks[:] = flatnonzero(keep),
    in halves; the outputs are preallocated with exactly count_nonzero(keep) items."""
    half = len(keep) // 2
    before = {0: 0, half: int(np.count_nonzero(keep[:half]))}

    def part(start: int, stop: int) -> None:
        mask = keep[start:stop]
        offset = before[start]
        taken = int(np.count_nonzero(mask))
        for source, out in pairs:
            np.compress(mask, source[start:stop], out=out[offset:offset + taken])
        if ranks is not None:
            np.add(np.flatnonzero(mask), start, out=ranks[offset:offset + taken],
                   casting="unsafe")

    halves(part, len(keep))


def place(first: np.ndarray, ones: np.ndarray, others: np.ndarray, out: np.ndarray) -> None:
    """out[first] = ones and out[~first] = others (each in order), in halves."""
    half = len(first) // 2
    before = int(np.count_nonzero(first[:half]))

    def part(start: int, stop: int) -> None:
        mask = first[start:stop]
        taken = int(np.count_nonzero(mask))
        done = before if start else 0
        out[start:stop][mask] = ones[done:done + taken]
        rest = start - done
        out[start:stop][~mask] = others[rest:rest + (stop - start - taken)]

    halves(part, len(first))


def slot_of(neighbors: np.ndarray, cells: np.ndarray, target: np.ndarray) -> np.ndarray:
    """(n,) int64 first column of neighbors[cells] holding target (0 if none), as argmax
    would give, by one compare per column instead of a (n, w) boolean argmax."""
    rows = take(neighbors, cells)
    slot = np.zeros(len(cells), dtype=np.int64)
    for c in range(neighbors.shape[1] - 1, -1, -1):
        slot[rows[:, c] == target] = c
    return slot
