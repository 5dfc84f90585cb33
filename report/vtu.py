"""Reading the project's .vtu files (runtime/output/vtk.c): XML UnstructuredGrid with
the arrays appended raw (UInt64 byte counts, little endian) or inline ASCII.

read(path) -> {"points", "displacement", "mode_shape" (modes), cell and cell data
arrays by name, "fields": {name: value}}; cells(data) -> [(vtk type, point ids)].
"""
import xml.etree.ElementTree as ET

import numpy as np

_DTYPES = {"Float64": "<f8", "Float32": "<f4", "Int64": "<i8", "Int32": "<i4", "UInt8": "u1", "UInt64": "<u8"}


def read(path):
    raw = open(path, "rb").read()
    marker = raw.find(b"<AppendedData")
    if marker >= 0:
        start = raw.index(b"_", marker) + 1
        head = raw[:marker] + b"</VTKFile>"
        blob = raw[start:]
    else:
        head, blob = raw, b""
    root = ET.fromstring(head)
    grid = root.find("UnstructuredGrid")
    piece = grid.find("Piece")

    def array(node):
        dt = np.dtype(_DTYPES[node.get("type")])
        if node.get("format") == "appended":
            off = int(node.get("offset"))
            n = int(np.frombuffer(blob, dtype="<u8", count=1, offset=off)[0])
            a = np.frombuffer(blob, dtype=dt, count=n // dt.itemsize, offset=off + 8)
        else:
            a = np.array(node.text.split(), dtype=dt)
        ncomp = int(node.get("NumberOfComponents", "1"))
        return a.reshape(-1, ncomp) if ncomp > 1 else a

    out = {"points": array(piece.find("Points/DataArray"))}
    for sec in ("PointData", "CellData", "Cells"):
        node = piece.find(sec)
        if node is not None:
            for a in node.findall("DataArray"):
                out[a.get("Name")] = array(a)
    out["fields"] = {a.get("Name"): float(a.text) for a in grid.findall("FieldData/DataArray")}
    return out


def cells(data):
    out, start = [], 0
    for o, ty in zip(data["offsets"], data["types"]):
        out.append((int(ty), data["connectivity"][start:o]))
        start = o
    return out
