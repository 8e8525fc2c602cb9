"""Run by ParaView's pvpython: opens every .pvd series of a case's VTK/ folder as ParaView
does (PVDReader), steps through its times and saves what it read, for paraviewFrames.py to
check: one .npz a series (times, then per time the counts, the points, the line
connectivity and every point and cell array) and report.json (the series and their number of
times). The readers' errors and warnings go to the output, which paraviewFrames.py reads.

usage: pvpython paraviewReadSeries.py CASE OUT_DIR"""
import glob
import json
import os
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import Delete, PVDReader
from vtkmodules.util.numpy_support import vtk_to_numpy

case, out = sys.argv[1:]
os.makedirs(out, exist_ok=True)

report = {}
for pvd in sorted(glob.glob(os.path.join(case, "VTK", "*.pvd"))):
    series = os.path.splitext(os.path.basename(pvd))[0]
    reader = PVDReader(FileName=pvd)
    times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]
    arrays = {"times": np.array(times)}
    for k, t in enumerate(times):
        reader.UpdatePipeline(t)
        data = servermanager.Fetch(reader)
        prefix = "%d/" % k
        arrays[prefix + "class"] = np.array(data.GetClassName())
        arrays[prefix + "points"] = (vtk_to_numpy(data.GetPoints().GetData())
                                     if data.GetPoints() else np.zeros((0, 3)))
        arrays[prefix + "verts"] = np.array(data.GetNumberOfVerts())
        arrays[prefix + "lines"] = np.array(data.GetNumberOfLines())
        if data.GetNumberOfLines():
            arrays[prefix + "lineConnectivity"] = vtk_to_numpy(data.GetLines().GetConnectivityArray())
        for kind, fields in (("point", data.GetPointData()), ("cell", data.GetCellData())):
            for i in range(fields.GetNumberOfArrays()):
                array = fields.GetArray(i)
                arrays["%s%s/%s" % (prefix, kind, array.GetName())] = vtk_to_numpy(array)
    np.savez(os.path.join(out, series + ".npz"), **arrays)
    report[series] = len(times)
    Delete(reader)

with open(os.path.join(out, "report.json"), "w") as f:
    json.dump({"series": report}, f)
