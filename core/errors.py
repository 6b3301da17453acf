"""Exception types shared by the core: one base, so the app and CLI can show any of them plainly."""

from __future__ import annotations


class AlphaScoopError(Exception):
    """Base of every error the core raises on purpose; its message is meant for the user."""


class InputError(AlphaScoopError, ValueError):
    """The points cannot make an alpha complex (empty, non-finite, too few, collinear...)."""


class FileFormatError(AlphaScoopError, ValueError):
    """A file could not be read or written; the message names the file and the problem."""


class Cancelled(AlphaScoopError):
    """Raised from a progress callback to stop a long computation early."""
