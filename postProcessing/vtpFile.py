"""The ParaView files the simulator writes (demModels/core/io/VtkWriter), read with numpy alone:
.vtp PolyData in either vtkFormat, ascii (numbers in the XML) or binary (raw data appended after
the XML, each array in zlib-compressed blocks after a UInt64 header, as vtkZLibDataCompressor
writes them), and .pvd time series.

    piece = read_vtp("VTK/particles_00003.vtp")
    piece.points                # n x 3
    piece.point_data["radius"]  # n
    piece.cell_data, piece.verts, piece.lines   # cells: (connectivity, offsets)
    for time, file in read_pvd("VTK/particles.pvd"): ..."""
import os
import xml.etree.ElementTree as ET
import zlib

import numpy as np

TYPES = {"Float64": "<f8", "Float32": "<f4", "Int64": "<i8", "Int32": "<i4", "UInt8": "u1"}


class Piece:
    def __init__(self, attributes):
        self.attributes = attributes
        self.points = np.zeros((0, 3))
        self.point_data = {}
        self.cell_data = {}
        self.verts = (np.zeros(0, np.int64), np.zeros(0, np.int64))
        self.lines = (np.zeros(0, np.int64), np.zeros(0, np.int64))


def _compressed_array(appended, offset):
    """The bytes of one appended array: header [blocks, block size, last size, compressed sizes]."""
    blocks, block_size, last_size = np.frombuffer(appended, "<u8", 3, offset)
    sizes = np.frombuffer(appended, "<u8", int(blocks), offset + 24)
    at = offset + 24 + 8 * int(blocks)
    out = []
    for k, size in enumerate(sizes):
        block = zlib.decompress(appended[at:at + int(size)])
        expected = last_size if k + 1 == blocks and last_size else block_size
        if len(block) != expected:
            raise ValueError("block %d of the array at offset %d has %d bytes, expected %d"
                             % (k, offset, len(block), expected))
        out.append(block)
        at += int(size)
    return b"".join(out)


def _values(element, appended, compressed):
    dtype = TYPES[element.get("type")]
    components = int(element.get("NumberOfComponents", "1"))
    form = element.get("format")
    if form == "ascii":
        values = np.array((element.text or "").split(), dtype=dtype)
    elif form == "appended":
        if not compressed:
            raise ValueError("appended data without a compressor is not written by this project")
        values = np.frombuffer(_compressed_array(appended, int(element.get("offset"))), dtype)
    else:
        raise ValueError("DataArray format '%s' is not written by this project" % form)
    return values.reshape(-1, components) if components > 1 else values


def read_vtp(path):
    """The first piece of a .vtp, its arrays as numpy arrays."""
    with open(path, "rb") as f:
        data = f.read()
    appended = b""
    start = data.find(b"<AppendedData")
    if start >= 0:
        underscore = data.index(b"_", start)
        appended = data[underscore + 1:]
        data = data[:start] + b"</VTKFile>\n"
    root = ET.fromstring(data)
    compressed = root.get("compressor") == "vtkZLibDataCompressor"
    if compressed and root.get("header_type") != "UInt64":
        raise ValueError("%s: header_type %s, expected UInt64" % (path, root.get("header_type")))
    element = root.find("PolyData/Piece")
    piece = Piece(dict(element.attrib))

    def arrays(section):
        found = element.find(section)
        return {} if found is None else {
            a.get("Name"): _values(a, appended, compressed) for a in found.iter("DataArray")}

    piece.point_data = arrays("PointData")
    piece.cell_data = arrays("CellData")
    points = arrays("Points")
    if points:
        piece.points = next(iter(points.values())).reshape(-1, 3)
    for name in ("Verts", "Lines"):
        cells = arrays(name)
        if cells:
            setattr(piece, name.lower(), (cells["connectivity"], cells["offsets"]))
    return piece


def read_pvd(path):
    """[(time, file path)] of a .pvd series, files relative to the .pvd's folder resolved."""
    root = ET.parse(path).getroot()
    folder = os.path.dirname(path)
    return [(float(d.get("timestep")), os.path.join(folder, d.get("file"))) for d in root.iter("DataSet")]
