"""VesselPhantom: both output ports, every shape, determinism, and clear errors on bad input."""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, plugin_path, run_pvpython  # noqa: E402

from paraview import servermanager, simple  # noqa: E402
from paraview.vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

check = Check("VesselPhantom")
simple.LoadPlugin(plugin_path(), ns=globals())


def fetch(source, port):
    return servermanager.Fetch(source, idx=port)


# Defaults: a 128^3 unsigned short tree and its seven analytic centerlines.
default = VesselPhantom()  # noqa: F821
default.UpdatePipeline()
image = fetch(default, 0)
lines = fetch(default, 1)
check.equal(image.GetDimensions(), (128, 128, 128), "default dimensions")
check.equal(image.GetPointData().GetScalars().GetDataTypeAsString(), "unsigned short",
            "default scalar type")
check.equal(image.GetPointData().GetScalars().GetName(), "Intensity", "scalar name")
check.equal(lines.GetNumberOfLines(), 7, "tree of depth 3 has seven vessels")
check.true(lines.GetPointData().GetArray("Radius") is not None, "centerline carries Radius")

# Every shape gives the expected number of polylines; the voxel at the centerline is bright.
expected_lines = {"Circle": 1, "Winding line": 1, "Helix": 1, "Straight tube": 1,
                  "Y bifurcation": 3, "Tree": 7, "Loop network": 5, "Column (4x4 voxels)": 1}
for shape, count in expected_lines.items():
    phantom = VesselPhantom(Shape=shape, Dimensions=[48, 40, 44], Spacing=[1.0, 1.2, 1.1],  # noqa: F821
                            Origin=[-5, 3, 7], NoiseStandardDeviation=0.0)
    phantom.UpdatePipeline()
    volume = fetch(phantom, 0)
    centerline = fetch(phantom, 1)
    check.equal(centerline.GetNumberOfLines(), count, "%s polylines" % shape)
    check.equal(volume.GetOrigin(), (-5.0, 3.0, 7.0), "%s origin" % shape)
    values = vtk_to_numpy(volume.GetPointData().GetScalars())
    radius = vtk_to_numpy(centerline.GetPointData().GetArray("Radius"))
    bright = 0
    samples = range(0, centerline.GetNumberOfPoints(), max(1, centerline.GetNumberOfPoints() // 15))
    for i in samples:
        p = centerline.GetPoint(i)
        voxel = volume.FindPoint(p)
        if voxel >= 0 and values[voxel] > 100 + 0.4 * 900:
            bright += 1
    check.true(bright >= 0.9 * len(samples), "%s: voxels on the centerline are bright (%d of %d)"
               % (shape, bright, len(samples)))
    check.true(radius.min() > 0, "%s radii are positive" % shape)

# Determinism: the same seed gives the same volume; another seed other noise.
a = vtk_to_numpy(fetch(VesselPhantom(Dimensions=[24, 24, 24], Seed=7), 0).GetPointData().GetScalars())  # noqa: F821
b = vtk_to_numpy(fetch(VesselPhantom(Dimensions=[24, 24, 24], Seed=7), 0).GetPointData().GetScalars())  # noqa: F821
c = vtk_to_numpy(fetch(VesselPhantom(Dimensions=[24, 24, 24], Seed=8), 0).GetPointData().GetScalars())  # noqa: F821
check.true((a == b).all(), "same seed, same volume")
check.true((a != c).any(), "another seed, other noise")

# Float output.
f = fetch(VesselPhantom(Dimensions=[16, 16, 16], OutputScalarType="Float"), 0)  # noqa: F821
check.equal(f.GetPointData().GetScalars().GetDataTypeAsString(), "float", "float output")

# The helix's analytic centerline length matches its formula.
helix = VesselPhantom(Shape="Helix", Dimensions=[64, 64, 64])  # noqa: F821
h = fetch(helix, 1)
length = sum(math.dist(h.GetPoint(i), h.GetPoint(i + 1)) for i in range(h.GetNumberOfPoints() - 1))
n = 63.0
expected = 3 * math.hypot(2 * math.pi * 0.3 * n, 0.25 * n)
check.near(length, expected, 1e-3 * expected, "helix length")

# Raw angiogram: a random tree in port 1 (Radius from the root's 4 voxels down to 0.5, Tangent),
# vessels at the peak intensity over tissue, the root's first point on a bright voxel; the same
# seed gives the same volume; Rician noise is a magnitude (never negative).
def raw_angiogram(**kwargs):
    p = VesselPhantom(Shape="Raw angiogram", Dimensions=[80, 80, 80], AngiogramSegments=60,  # noqa: F821
                      OutputScalarType="Float", **kwargs)
    p.UpdatePipeline()
    return fetch(p, 0), fetch(p, 1)


volume, tree = raw_angiogram(Seed=3)
values = vtk_to_numpy(volume.GetPointData().GetScalars())
radius = vtk_to_numpy(tree.GetPointData().GetArray("Radius"))
check.true(tree.GetNumberOfLines() >= 30, "raw angiogram tree has %d vessels" % tree.GetNumberOfLines())
check.near(float(radius.max()), 4.0, 1e-9, "raw angiogram root radius")
check.true(radius.min() >= 0.5 - 1e-9, "raw angiogram radii >= 0.5 voxel (%g)" % radius.min())
check.true(tree.GetPointData().GetArray("Tangent") is not None, "raw angiogram tangents")
median = float(sorted(values[::97])[len(values[::97]) // 2])
check.true(300 < median < 500, "raw angiogram background is tissue (median %g)" % median)
root = volume.FindPoint(tree.GetPoint(0))
check.true(values[root] > 800, "the root's first point is on the vessel (%g)" % values[root])
again = vtk_to_numpy(raw_angiogram(Seed=3)[0].GetPointData().GetScalars())
check.true((again == values).all(), "raw angiogram: same seed, same volume")
rician = vtk_to_numpy(raw_angiogram(Seed=3, NoiseModel="Rician", TissueIntensity=0,
                                    NoiseStandardDeviation=30)[0].GetPointData().GetScalars())
check.true(rician.min() >= 0.0, "Rician noise gives magnitudes")

# Bad input: a clear message in the output, an empty output, and no crash.
bad_cases = {
    "zero size": "Dimensions=[0, 10, 10]",
    "flat": "Dimensions=[64, 64, 1]",
    "negative spacing": "Spacing=[1, -1, 1]",
    "NaN spacing": "Spacing=[1, float('nan'), 1]",
    "radius larger than the volume": "RadiusFraction=0.9",
    "absurd tree depth": "Shape='Tree', TreeDepth=40",
    "raw angiogram without segments": "Shape='Raw angiogram', AngiogramSegments=0",
    "raw angiogram too small for its root": "Shape='Raw angiogram', Dimensions=[30, 64, 64]",
}
for label, arguments in bad_cases.items():
    code = ("from paraview.simple import *\n"
            "LoadPlugin(%r, ns=globals())\n"
            "p = VesselPhantom(%s)\n"
            "p.UpdatePipeline()\n"
            "print('POINTS', p.GetDataInformation(0).GetNumberOfPoints(),"
            " p.GetDataInformation(1).GetNumberOfPoints())\n" % (plugin_path(), arguments))
    rc, out = run_pvpython(code)
    check.equal(rc, 0, "%s: pvpython exits cleanly" % label)
    check.true("POINTS 0 0" in out, "%s: empty outputs\n%s" % (label, out))
    check.true("VesselPhantom:" in out, "%s: a clear error message\n%s" % (label, out))

check.finish()
