"""Declared sizes are checked before anything is allocated for them: a header claiming
gigabytes, or compressed data expanding past the memory available, is a FileFormatError and
allocates nothing big (measured with tracemalloc, which sees numpy's and Python's buffers)."""

from __future__ import annotations

import struct
import tracemalloc
import zipfile

import numpy as np
import pytest

from core.errors import FileFormatError
from core.io import read_points, sizes

SMALL_PEAK = 16 << 20  # bytes: reading a refused file must stay far below what it declares


def _peak(path) -> tuple[int, FileFormatError | None]:
    """(tracemalloc peak in bytes, the FileFormatError raised or None) of read_points(path)."""
    tracemalloc.start()
    try:
        read_points(path)
        error = None
    except FileFormatError as exc:
        error = exc
    finally:
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    return peak, error


def _npy_header(shape, dtype="<f8") -> bytes:
    """A version 1.0 .npy header declaring `shape`."""
    text = f"{{'descr': '{dtype}', 'fortran_order': False, 'shape': {shape}, }}"
    text += " " * (63 - (len(text) + 10) % 64) + "\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(text)) + text.encode()


def _deflated_zeros(path, shape, key="points") -> None:
    """An .npz whose array of zeros is written in chunks (never held in memory whole)."""
    nbytes = int(np.prod(shape)) * 8
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as zf, \
            zf.open(f"{key}.npy", "w", force_zip64=True) as member:
        member.write(_npy_header(shape))
        chunk = bytes(1 << 20)
        for start in range(0, nbytes, len(chunk)):
            member.write(chunk[: min(len(chunk), nbytes - start)])


def test_deflate_bomb_beyond_memory_is_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(sizes, "available_memory", lambda: 64 << 20)  # as if 64 MB were free
    path = tmp_path / "bomb.npz"
    _deflated_zeros(path, (2_000_000, 3))  # 48 MB of zeros, deflated to about 50 KB
    assert path.stat().st_size < 200_000
    peak, error = _peak(path)
    assert error is not None and "bomb.npz" in str(error) and "memory" in str(error)
    assert peak < SMALL_PEAK


def test_deflated_array_within_memory_reads(tmp_path):
    path = tmp_path / "zeros.npz"
    _deflated_zeros(path, (1000, 3))
    report = read_points(path).report
    assert (report.n_read, report.n_duplicates) == (1000, 999)


def test_npz_header_claiming_more_than_its_entry_holds(tmp_path):
    path = tmp_path / "liar.npz"
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as zf:
        zf.writestr("points.npy", _npy_header((100_000_000, 3)) + bytes(240))
    peak, error = _peak(path)
    assert error is not None and "declares 2,400,000,000 bytes" in str(error)
    assert peak < SMALL_PEAK


def test_npy_header_claiming_more_than_the_file_holds(tmp_path):
    path = tmp_path / "liar.npy"
    path.write_bytes(_npy_header((100_000_000, 3)) + bytes(240))
    peak, error = _peak(path)
    assert error is not None and "truncated NumPy file" in str(error)
    assert peak < SMALL_PEAK


def test_available_memory_is_positive():
    assert sizes.available_memory() > 1 << 20


PCD_HEAD = ("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
            "WIDTH {n}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {n}\nDATA {kind}\n")
PCD_CASES = {
    # compressed block: 90 bytes claiming 3.3 GB
    "bomb": (1000, "binary_compressed", struct.pack("<II", 90, 3_300_000_000) + bytes(90),
             "claims 3,300,000,000 bytes"),
    "huge_points": (10**12, "binary_compressed", struct.pack("<II", 90, 12 * 10**6) + bytes(90),
                    "claims 12,000,000 bytes for 1,000,000,000,000 points"),
    "ascii_short": (10**7, "ascii", b"1 2 3\n" * 1000, "header declares 10,000,000 points"),
    "ascii_rows": (1000, "ascii", b"1.00000 2.00000 3.00000\n" * 600, "1,000 points, 600 read"),
}


@pytest.mark.parametrize("case", sorted(PCD_CASES))
def test_pcd_declared_sizes(tmp_path, case):
    n, kind, body, message = PCD_CASES[case]
    path = tmp_path / f"{case}.pcd"
    path.write_bytes(PCD_HEAD.format(n=n, kind=kind).encode() + body)
    peak, error = _peak(path)
    assert error is not None and message in str(error) and path.name in str(error)
    assert peak < SMALL_PEAK


def test_pcd_compressed_beyond_memory(tmp_path, monkeypatch):
    monkeypatch.setattr(sizes, "available_memory", lambda: 1 << 20)
    path = tmp_path / "big.pcd"
    path.write_bytes(PCD_HEAD.format(n=100_000, kind="binary_compressed").encode()
                     + struct.pack("<II", 20_000, 1_200_000) + bytes(20_000))
    peak, error = _peak(path)
    assert error is not None and "memory" in str(error) and peak < SMALL_PEAK


@pytest.mark.parametrize("ext", [".pcd", ".ply"])
def test_header_without_end_gives_up_early(tmp_path, ext):
    first = b"# .PCD v0.7\nFIELDS x y z\n" if ext == ".pcd" else b"ply\nformat ascii 1.0\n"
    path = tmp_path / f"endless{ext}"
    path.write_bytes(first + b"comment " + b"x" * (8 << 20))  # 8 MB header line, no newline
    peak, error = _peak(path)
    assert error is not None and path.name in str(error) and peak < SMALL_PEAK
