"""How much memory this process may still take: what the system has available, within the
process's own limits (its address-space rlimit and its cgroup's memory limit), so that a
declared size is refused before the allocation that would end in a MemoryError."""

from __future__ import annotations

import os
from pathlib import Path

UNKNOWN_MEMORY = 1 << 34  # assumed when the system does not say (16 GiB)
_CGROUP = Path("/sys/fs/cgroup")


def _meminfo_available() -> int | None:
    """Linux MemAvailable in bytes, else sysconf's available pages, else None."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def _address_space_left() -> int | None:
    """Bytes left under the soft RLIMIT_AS (None when unlimited or unknown)."""
    try:
        import resource

        soft = resource.getrlimit(resource.RLIMIT_AS)[0]
        if soft == resource.RLIM_INFINITY:
            return None
        with open("/proc/self/status", encoding="ascii") as fh:
            size = next((int(line.split()[1]) * 1024 for line in fh
                         if line.startswith("VmSize:")), 0)
        return max(soft - size, 0)
    except (ImportError, OSError, ValueError, IndexError):
        return None


def _cgroup_left() -> int | None:
    """Bytes left under this process's cgroup v2 memory.max (None when unlimited)."""
    try:
        line = Path("/proc/self/cgroup").read_text().splitlines()[0]
        group = _CGROUP / line.split("::", 1)[1].lstrip("/")
        limit = (group / "memory.max").read_text().strip()
        if limit == "max":
            return None
        return max(int(limit) - int((group / "memory.current").read_text()), 0)
    except (OSError, ValueError, IndexError):
        return None


def available_memory() -> int:
    """Bytes of memory this process may still allocate: the least of what the system has
    available and what its rlimit and cgroup leave (UNKNOWN_MEMORY when nothing says)."""
    known = [v for v in (_meminfo_available(), _address_space_left(), _cgroup_left())
             if v is not None]
    return min(known) if known else UNKNOWN_MEMORY
