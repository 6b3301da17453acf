"""Atomic writes for the exporters: re-exports core.atomic (shared with core.storage)."""

from core.atomic import atomic_path, atomic_write, atomic_write_text

__all__ = ["atomic_path", "atomic_write", "atomic_write_text"]
