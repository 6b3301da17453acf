"""VTK XML writers (VTU and VTP), zlib-compressed base64, with cell data and field data.

meshio writes no VTP and drops field data from VTU, so this small writer covers both; the
files are read back by VTK itself (pyvista) and by meshio in the tests. meshio cannot read
VTK's String arrays, so a VTU's text field data is written as UInt8 arrays of its UTF-8 bytes
(`text_of` reads one back); a VTP, which meshio does not read, keeps String arrays.
"""

from __future__ import annotations

import base64
import zlib
from xml.sax.saxutils import quoteattr

import numpy as np

VTK_TYPES = {
    np.dtype(np.float64): "Float64", np.dtype(np.float32): "Float32",
    np.dtype(np.int64): "Int64", np.dtype(np.int32): "Int32",
    np.dtype(np.int8): "Int8", np.dtype(np.uint8): "UInt8",
}
VTK_VERTEX, VTK_LINE, VTK_TRIANGLE, VTK_TETRA = 1, 3, 5, 10
CELL_TYPES = {1: VTK_VERTEX, 2: VTK_LINE, 3: VTK_TRIANGLE, 4: VTK_TETRA}


def _encode(raw: bytes) -> str:
    """Inline zlib-compressed payload: the block header (UInt64s) and the data, each base64."""
    packed = zlib.compress(raw, 6)
    header = np.array([1, len(raw), len(raw), len(packed)], dtype="<u8").tobytes()
    return (base64.b64encode(header) + base64.b64encode(packed)).decode("ascii")


def data_array(name: str, values: np.ndarray) -> str:
    """One <DataArray> for a (n,) or (n, c) numeric array."""
    values = np.ascontiguousarray(values)
    if values.dtype == np.bool_:
        values = values.astype(np.uint8)
    values = values.astype(values.dtype.newbyteorder("<"), copy=False)
    comps = 1 if values.ndim == 1 else values.shape[1]
    kind = VTK_TYPES[values.dtype.newbyteorder("=")]
    return (f'<DataArray type="{kind}" Name={quoteattr(name)} NumberOfComponents="{comps}" '
            f'NumberOfTuples="{len(values)}" format="binary">{_encode(values.tobytes())}'
            "</DataArray>")


def string_array(name: str, text: str) -> str:
    """A one-tuple String <DataArray> (null-terminated UTF-8)."""
    raw = text.encode("utf-8") + b"\0"
    return (f'<DataArray type="String" Name={quoteattr(name)} NumberOfTuples="1" '
            f'format="binary">{_encode(raw)}</DataArray>')


def bytes_array(name: str, text: str) -> str:
    """Text as a UInt8 <DataArray> of its UTF-8 bytes (a type every VTK reader knows)."""
    return data_array(name, np.frombuffer(text.encode("utf-8"), dtype=np.uint8))


def text_of(values: np.ndarray) -> str:
    """The text a bytes_array holds, from the (n,) uint8 array a reader returns."""
    return np.asarray(values, dtype=np.uint8).tobytes().decode("utf-8")


def field_data(meta: dict, text=string_array) -> str:
    """<FieldData>: numbers (and lists of numbers) as Float64, everything else as `text`
    makes it (String arrays; bytes_array for readers without strings)."""
    parts = []
    for key, value in meta.items():
        if isinstance(value, bool) or value is None:
            parts.append(text(key, str(value)))
        elif isinstance(value, (int, float)):
            parts.append(data_array(key, np.array([value], dtype=np.float64)))
        elif isinstance(value, (list, tuple)) and all(isinstance(v, (int, float)) for v in value):
            parts.append(data_array(key, np.asarray(value, dtype=np.float64)))
        else:
            parts.append(text(key, str(value)))
    return f"<FieldData>{''.join(parts)}</FieldData>"


def _cell_data(cell_data: dict[str, np.ndarray]) -> str:
    """<CellData> with one array per entry."""
    return "<CellData>" + "".join(data_array(k, v) for k, v in cell_data.items()) + "</CellData>"


def _document(kind: str, body: str, meta: dict, text=string_array) -> bytes:
    """Wrap a dataset body into a VTKFile element (text field data made by `text`)."""
    return (f'<?xml version="1.0"?>\n<VTKFile type="{kind}" version="1.0" '
            f'byte_order="LittleEndian" header_type="UInt64" '
            f'compressor="vtkZLibDataCompressor">\n<{kind}>{field_data(meta, text)}\n'
            f"{body}\n</{kind}>\n</VTKFile>\n").encode()


def _points(points: np.ndarray) -> str:
    """<Points> of (n, 3) float64 coordinates."""
    return f"<Points>{data_array('Points', np.asarray(points, dtype=np.float64))}</Points>"


def vtu_bytes(points: np.ndarray, blocks: list[np.ndarray], cell_data: dict, meta: dict,
              point_data: dict | None = None) -> bytes:
    """Unstructured grid of (n, 3) points and cell blocks ((c_i, k_i) int with k_i in 1..4),
    with optional point data ((n,) arrays by name)."""
    conn = np.concatenate([b.ravel() for b in blocks]).astype(np.int64)
    sizes = np.concatenate([np.full(len(b), b.shape[1]) for b in blocks]).astype(np.int64)
    types = np.concatenate([np.full(len(b), CELL_TYPES[b.shape[1]]) for b in blocks])
    cells = (data_array("connectivity", conn) + data_array("offsets", np.cumsum(sizes))
             + data_array("types", types.astype(np.uint8)))
    body = (f'<Piece NumberOfPoints="{len(points)}" NumberOfCells="{len(sizes)}">'
            f"{_points(points)}<Cells>{cells}</Cells>{_cell_data(cell_data)}"
            f"{_point_data(point_data or {})}</Piece>")
    return _document("UnstructuredGrid", body, meta, text=bytes_array)  # meshio reads it too


def _point_data(point_data: dict[str, np.ndarray]) -> str:
    """<PointData> with one array per entry (nothing when there is none)."""
    if not point_data:
        return ""
    return ("<PointData>" + "".join(data_array(k, np.asarray(v)) for k, v in point_data.items())
            + "</PointData>")


def vtp_bytes(points: np.ndarray, faces: np.ndarray, meta: dict) -> bytes:
    """Polydata of (n, 3) points and (f, 3) triangles."""
    faces = np.asarray(faces, dtype=np.int64)
    polys = (data_array("connectivity", faces.ravel())
             + data_array("offsets", 3 * np.arange(1, len(faces) + 1, dtype=np.int64)))
    body = (f'<Piece NumberOfPoints="{len(points)}" NumberOfVerts="0" NumberOfLines="0" '
            f'NumberOfStrips="0" NumberOfPolys="{len(faces)}">{_points(points)}'
            f"<Polys>{polys}</Polys></Piece>")
    return _document("PolyData", body, meta)
