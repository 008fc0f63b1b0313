"""The built-in (one process) VesselCenterline outputs' hashes, to show that a change to the
distributed path leaves one process unaffected (issue 19, item 2).

    VESSELTOUCH_PLUGIN=<build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
        pvpython Testing/ParaView/clientserver/hash_builtin_centerlines.py

Run it with two plugins (main's and a branch's) and compare the lines. Hashed: the points, the
lines and every point and field array but the stage times (*Seconds), of the 96^3 tree, ring, Y,
loop network and raw angiogram phantoms (default parameters) and the raw angiogram seeded at its
skeleton's middle point. A measurement, not a test: nothing is asserted.
"""

import hashlib
import os

from paraview import servermanager as sm
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy


def digest(d):
    h = hashlib.sha256()
    h.update(vtk_to_numpy(d.GetPoints().GetData()).tobytes())
    h.update(vtk_to_numpy(d.GetLines().GetConnectivityArray()).tobytes())
    for attributes in (d.GetPointData(), d.GetFieldData()):
        for i in range(attributes.GetNumberOfArrays()):
            a = attributes.GetAbstractArray(i)
            if "Seconds" in a.GetName():
                continue
            h.update(a.GetName().encode())
            if a.IsNumeric():
                h.update(vtk_to_numpy(a).tobytes())
            else:
                h.update("|".join(a.GetValue(k) for k in range(a.GetNumberOfValues())).encode())
    return h.hexdigest()[:16]


def main():
    simple.LoadPlugin(os.environ["VESSELTOUCH_PLUGIN"], remote=False, ns=globals())
    for name, shape in (("tree", 5), ("ring", 0), ("Y", 4), ("loop network", 6), ("raw", 8)):
        phantom = VesselPhantom(Dimensions=[96, 96, 96], Shape=shape)  # noqa: F821
        centerline = VesselCenterline(Input=phantom)  # noqa: F821
        centerline.UpdatePipeline()
        d = sm.Fetch(centerline)
        print(name, d.GetNumberOfPoints(), digest(d))
        if shape == 8:
            seed = list(d.GetPoint(d.GetNumberOfPoints() // 2))
            seeded = VesselCenterline(Input=phantom, UseSeedPoint=1, SeedPoint=seed)  # noqa: F821
            seeded.UpdatePipeline()
            e = sm.Fetch(seeded)
            print("raw seeded", e.GetNumberOfPoints(), digest(e))


main()
