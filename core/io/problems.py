"""A third-party parser's failure, told in words: which file, and what is wrong with it.

Readers hand their libraries' exceptions here instead of quoting them; a codec, parser or
numpy message means nothing to the user. The original stays as the exception's __cause__.
"""

from __future__ import annotations

import json
import struct
import zipfile
import zlib
from pathlib import Path
from xml.etree.ElementTree import ParseError

from core.errors import FileFormatError

MAX_MESSAGE = 300  # characters of a message, values quoted from the file included

# (words found in a library's message, what they mean), checked in order
_MEANINGS = (
    (("decompress", "compressed", "lzf", "inflate", "invalid distance", "invalid code"),
     "its compressed data is corrupt"),
    (("codec", "decode", "utf-8", "ascii"), "it holds bytes that are not text"),
    (("json",), "its JSON header is malformed"),
    (("xml", "not well-formed", "mismatched tag"), "its XML is malformed"),
    (("base64",), "its encoded data is corrupt"),
    (("field larger than field limit",), "a line is far too long"),
    (("could not convert", "not a number", "to float", "invalid literal"),
     "a value is not a number"),
    (("columns", "inhomogeneous", "cannot reshape", "row", "unmatched data"),
     "its rows do not have the values the header declares"),
    (("end of file", "eof", "truncated", "expected length", "unpack requires",
      "not enough", "too short", "out of range", "index"),
     "it ends early or its sizes disagree"),
    (("magic", "header", "not a zip", "section", "signature"),
     "its header is not what this format has"),
)


def describe(exc: BaseException) -> str:
    """What an exception from a parser says about the file, in plain words."""
    if isinstance(exc, UnicodeDecodeError):
        return "it holds bytes that are not text"
    if isinstance(exc, json.JSONDecodeError):
        return "its JSON header is malformed"
    if isinstance(exc, ParseError):
        return "its XML is malformed"
    if isinstance(exc, zlib.error):
        return "its compressed data is corrupt"
    if isinstance(exc, (EOFError, struct.error)):
        return "it ends early or its sizes disagree"
    if isinstance(exc, zipfile.BadZipFile):
        return "it is not a valid zip archive"
    text = f"{type(exc).__name__} {exc}".lower()
    for words, meaning in _MEANINGS:
        if any(w in text for w in words):
            return meaning
    return "its content is corrupt or not in this format"


def unreadable(path: Path, what: str, exc: BaseException) -> FileFormatError:
    """FileFormatError 'PATH: not a readable WHAT file: <what is wrong>' (cause attached)."""
    error = FileFormatError(f"{path}: not a readable {what} file: {describe(exc)}")
    error.__cause__ = exc
    return error


def plain_line(message: str) -> str:
    """One printable line: control and undecodable characters shown as '?', length capped."""
    text = " ".join(message.split())
    text = "".join(c if c.isprintable() and c != "\ufffd" else "?" for c in text)
    return text if len(text) <= MAX_MESSAGE else text[: MAX_MESSAGE - 3] + "..."
