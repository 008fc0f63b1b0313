"""VesselCenterline: phantoms to polylines with geometry arrays and topology, and clear errors."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, plugin_path  # noqa: E402

from paraview import servermanager, simple  # noqa: E402
from paraview.vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

check = Check("VesselCenterline")
simple.LoadPlugin(plugin_path(), ns=globals())

ARRAYS = ("Radius", "Tangent", "Curvature", "Torsion", "BifurcationLabel", "PathId", "PointIndex")
TOPOLOGY = ("PathHeadJunction", "PathTailJunction", "JunctionChildPath", "JunctionChildEnd",
            "JunctionParentPath", "JunctionParentPoint")


def centerline(shape, **kwargs):
    phantom = VesselPhantom(Shape=shape, Dimensions=[64, 64, 64], NoiseStandardDeviation=0.0,  # noqa: F821
                            OutputScalarType="Float")
    filt = VesselCenterline(Input=phantom, AutomaticIntensityRange=0,  # noqa: F821
                            LowerThreshold=550.0, **kwargs)
    filt.UpdatePipeline()
    return servermanager.Fetch(filt), servermanager.Fetch(phantom, idx=1)


def free_ends(poly):
    fd = poly.GetFieldData()
    head = vtk_to_numpy(fd.GetArray("PathHeadJunction"))
    tail = vtk_to_numpy(fd.GetArray("PathTailJunction"))
    labels = vtk_to_numpy(poly.GetPointData().GetArray("BifurcationLabel"))
    return int((head < 0).sum() + (tail < 0).sum()), int((labels == 2).sum())


# A Y: two polylines, three free ends, one junction; every array present and sane.
poly, analytic = centerline("Y bifurcation")
check.equal(poly.GetNumberOfLines(), 2, "Y gives two paths")
for name in ARRAYS:
    check.true(poly.GetPointData().GetArray(name) is not None, "point array %s" % name)
for name in TOPOLOGY:
    check.true(poly.GetFieldData().GetArray(name) is not None, "field array %s" % name)
check.equal(poly.GetFieldData().GetArray("JunctionChildPath").GetNumberOfTuples(), 1,
            "Y has one junction")
used = poly.GetFieldData().GetArray("DownsampleFactorUsed")
check.true(used is not None and used.GetValue(0) == 1,
           "the automatic scale keeps a small mask at full resolution (DownsampleFactorUsed 1)")
ends, labelled = free_ends(poly)
check.equal(ends, 3, "Y has three free ends")
check.equal(labelled, 3, "three points labelled as end points")
tangent = vtk_to_numpy(poly.GetPointData().GetArray("Tangent"))
norms = (tangent ** 2).sum(axis=1) ** 0.5
check.true(abs(norms - 1.0).max() < 1e-3, "tangents are unit vectors")
radius = vtk_to_numpy(poly.GetPointData().GetArray("Radius"))
check.true(radius.min() > 0 and radius.max() < 10, "radii are plausible (%g..%g)"
           % (radius.min(), radius.max()))
# Points lie on the analytic centerline (world frame).
from vtkmodules.vtkCommonDataModel import vtkPointLocator  # noqa: E402
locator = vtkPointLocator()
locator.SetDataSet(analytic)
locator.BuildLocator()
worst = 0.0
for i in range(0, poly.GetNumberOfPoints()):
    p = poly.GetPoint(i)
    q = analytic.GetPoint(locator.FindClosestPoint(p))
    worst = max(worst, sum((a - b) ** 2 for a, b in zip(p, q)) ** 0.5)
check.true(worst < 2.5, "every point within 2.5 mm of the analytic centerline (worst %.2f)" % worst)

# DownsampleFactor 2: about 8x fewer voxels coded, same topology, refined on the full-resolution
# mask: in world mm near the analytic centerline (within 1 original voxel on average).
coarse, _ = centerline("Y bifurcation", DownsampleFactor=2)
check.equal(coarse.GetNumberOfLines(), 2, "Y downsampled by 2 gives two paths")
check.equal(coarse.GetFieldData().GetArray("DownsampleFactorUsed").GetValue(0), 2,
            "DownsampleFactorUsed reports the factor asked for")
total = 0.0
for i in range(0, coarse.GetNumberOfPoints()):
    p = coarse.GetPoint(i)
    q = analytic.GetPoint(locator.FindClosestPoint(p))
    total += sum((a - b) ** 2 for a, b in zip(p, q)) ** 0.5
mean = total / max(1, coarse.GetNumberOfPoints())
check.true(mean < 1.0, "downsampled centerline within 1 voxel on average (%.2f mm)" % mean)

# A loop network comes out with a loop: junctions = paths - components + loops.
poly, _ = centerline("Loop network")
junctions = poly.GetFieldData().GetArray("JunctionChildPath").GetNumberOfTuples()
check.equal(junctions - poly.GetNumberOfLines() + 1, 1, "loop network has one loop")

# Bad input: thresholds that select nothing give an empty output and an error, not a crash.
phantom = VesselPhantom(Dimensions=[32, 32, 32])  # noqa: F821
bad = VesselCenterline(Input=phantom, AutomaticIntensityRange=0, LowerThreshold=1e9)  # noqa: F821
bad.UpdatePipeline()
check.equal(servermanager.Fetch(bad).GetNumberOfPoints(), 0, "empty mask gives empty output")

check.finish()
