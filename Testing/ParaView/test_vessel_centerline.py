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

# --- Raw angiograms: one click, no range typed (AutomaticIntensityRange, the default). ---
import numpy  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader  # noqa: E402

# A binary mask gives the same centerline with the automatic range as with the 0.5 threshold.
binary = simple.PythonCalculator(Input=VesselPhantom(Shape="Y bifurcation",  # noqa: F821
                                                     Dimensions=[48, 48, 48],
                                                     NoiseStandardDeviation=0.0),
                                 Expression="(inputs[0].PointData['Intensity'] > 550) * 1.0",
                                 ArrayName="Mask")
automatic = VesselCenterline(Input=binary, Scalars=["POINTS", "Mask"])  # noqa: F821
override = VesselCenterline(Input=binary, Scalars=["POINTS", "Mask"],  # noqa: F821
                            AutomaticIntensityRange=0, LowerThreshold=0.5)
a_poly, o_poly = servermanager.Fetch(automatic), servermanager.Fetch(override)
check.true(a_poly.GetNumberOfPoints() > 0 and numpy.allclose(
    vtk_to_numpy(a_poly.GetPoints().GetData()), vtk_to_numpy(o_poly.GetPoints().GetData())),
    "a binary mask: automatic range = the 0.5 threshold (%d points)" % a_poly.GetNumberOfPoints())
used = a_poly.GetFieldData().GetArray("IntensityRangeUsed")
check.true(used is not None and used.GetValue(0) == 0.5,
           "the binary mask's range is its midpoint (%s)" % (used and used.GetValue(0)))
check.true(a_poly.GetFieldData().GetArray("NonTubularPathsRemoved") is None,
           "a binary mask is not pruned for tube-likeness (raw-intensity path only)")

DATA = os.environ.get("VTOUCH_SHARED_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                                   "shared", "data"))
CTA = os.path.join(DATA, "vmtk-aorta", "aorta.mha")
if os.path.exists(CTA):
    ref_reader = vtkXMLPolyDataReader()
    ref_reader.SetFileName(os.path.join(DATA, "vmtk-aorta", "aorta-centerline.vtp"))
    ref_reader.Update()
    # The reference's frame flips both in-plane axes of the reader's world frame (data README).
    reference = vtk_to_numpy(ref_reader.GetOutput().GetPoints().GetData()) * [-1.0, -1.0, 1.0]
    cta = simple.OpenDataFile(CTA)
    cta.UpdatePipeline()
    raw = VesselCenterline(Input=cta, UseSeedPoint=1, SeedPoint=[float(v) for v in reference[0]])  # noqa: F821
    raw.UpdatePipeline()
    poly = servermanager.Fetch(raw)
    fd = poly.GetFieldData()
    check.equal(fd.GetAbstractArray("ExtractionMessage").GetValue(0), "",
                "raw CTA from a seed only: no message")
    check.equal(fd.GetArray("IntensityRangeAutomatic").GetValue(0), 1, "the range was estimated")
    pruned = fd.GetArray("NonTubularPathsRemoved")
    check.true(pruned is not None and pruned.GetValue(0) >= 0,
               "the raw path judged the sections' tube-likeness (%s paths removed)"
               % (pruned and pruned.GetValue(0)))
    lower = fd.GetArray("IntensityRangeUsed").GetValue(0)
    points = vtk_to_numpy(poly.GetPoints().GetData())
    dist = numpy.sqrt(((reference[:, None, :] - points[None, :, :]) ** 2).sum(-1)).min(1)
    within1, within2 = (dist <= 1.0).mean(), (dist <= 2.0).mean()
    print("raw CTA: range [%g, %g], %d paths; reference within 1 mm %.3f, 2 mm %.3f, mean %.2f mm"
          % (lower, fd.GetArray("IntensityRangeUsed").GetValue(1), poly.GetNumberOfLines(),
             within1, within2, dist.mean()))
    # Issue 16 asks >= 0.95 within 1 mm: 0.978 by this measure (nearest output point; 0.954
    # before the shading correction), 0.985 along the polylines of the core's run without it
    # (RawAortaCtaFromASeedAloneCoversTheVmtkReference); 0.878 and 0.917
    # before each branch's entry was carried on its own axis to its parent's (the left iliac's
    # path crossed the flattened lumen above the carina sideways, VMTK's line runs on along the
    # iliac's axis: Docs/CENTERLINES.md, "Raw angiograms", step 7).
    check.true(within1 >= 0.95, "reference within 1 mm of the extraction: %.3f >= 0.95" % within1)
    check.true(within2 >= 0.99, "reference within 2 mm of the extraction: %.3f >= 0.99" % within2)
    # Topology on the part the reference covers: its three ends are reached, and exactly one
    # bifurcation there has both branches running on along the reference (the iliac one); other
    # junctions there are side branches leaving it, or the seed's own split.
    ends = [reference[0], reference[-1]]
    lines = poly.GetLines()
    check.true(all(numpy.sqrt(((points - e) ** 2).sum(1)).min() <= 2.0 for e in ends),
               "the reference's ends are reached")
    path_id = vtk_to_numpy(poly.GetPointData().GetArray("PathId"))
    index = vtk_to_numpy(poly.GetPointData().GetArray("PointIndex"))
    near = numpy.sqrt(((points[:, None, :] - reference[None, :, :]) ** 2).sum(-1)).min(1) <= 2.0
    parent = vtk_to_numpy(fd.GetArray("JunctionParentPath"))
    parent_point = vtk_to_numpy(fd.GetArray("JunctionParentPoint"))
    child = vtk_to_numpy(fd.GetArray("JunctionChildPath"))
    on_reference = 0
    for p, q, c in zip(parent, parent_point, child):
        at = numpy.nonzero((path_id == p) & (index == q))[0][0]
        length = int((path_id == p).sum())
        if near[at] and 0 < q < length - 1 and near[path_id == c].sum() >= 10 \
                and near[(path_id == p) & (index > q)].sum() >= 10:
            on_reference += 1
    check.equal(on_reference, 1, "one bifurcation on the reference's part (the iliac one)")
    # The volume darkens toward its top (the aorta's brightest voxel per coronal row j 2300 at
    # the iliacs, 440 at j 390; the background with it): the shading correction (session 21)
    # carries the seed's range up the abdominal aorta, which stopped at j 285 before. The network
    # reaches the top tenth of the volume there, and every point in its top fifth lies on a voxel
    # at least twice its row's median: on the vessel, not on the noise.
    check.equal(fd.GetArray("ShadingCorrected").GetValue(0), 1, "the CTA's shading was corrected")
    span = fd.GetArray("ShadingGainSpan")
    check.true(span.GetValue(0) < 0.5 <= 1.0 <= span.GetValue(1),
               "the gain spans the volume's darkening (%.2f-%.2f of the seed's)"
               % (span.GetValue(0), span.GetValue(1)))
    volume_image = servermanager.Fetch(cta)
    ni, nj, nk = volume_image.GetDimensions()
    voxels = vtk_to_numpy(volume_image.GetPointData().GetScalars()).reshape(nk, nj, ni)
    row_median = numpy.median(voxels, axis=(0, 2))
    ids = numpy.array([volume_image.FindPoint(p) for p in points])
    j_of = (ids // ni) % nj
    check.true(j_of.max() >= 0.9 * (nj - 1),
               "the network runs up the aorta to the top tenth of the volume (row %d of %d)"
               % (j_of.max(), nj - 1))
    top = j_of >= 0.8 * (nj - 1)
    values = vtk_to_numpy(volume_image.GetPointData().GetScalars())[ids[top]]
    ratio = (values / row_median[j_of[top]]).min() if top.any() else 0.0
    check.true(top.sum() >= 20 and ratio >= 2.0,
               "%d points in the top fifth, each on a voxel >= 2 x its row's median (lowest %.1f)"
               % (top.sum(), ratio))

    # The candidate region previews what was coded, with the same range.
    region = VesselCandidateRegion(Input=cta, UseSeedPoint=1,  # noqa: F821
                                   SeedPoint=[float(v) for v in reference[0]])
    region.UpdatePipeline()
    image = servermanager.Fetch(region)
    candidate = vtk_to_numpy(image.GetPointData().GetArray("CandidateVessel"))
    check.true(image.GetPointData().GetArray("CandidateVessel").GetDataType() == 3
               and 5000 < int(candidate.sum()) < candidate.size // 20,
               "the candidate region is an unsigned char mask of the vessels (%d voxels)"
               % int(candidate.sum()))
    check.equal(image.GetFieldData().GetArray("IntensityRangeUsed").GetValue(0), lower,
                "the preview used the extraction's range")

    # Bad seeds: a clear message that says what to do, an empty output, no crash.
    corner = [reference[0][0] + 60.0, reference[0][1] - 60.0, reference[0][2]]
    for name, point, text in (("background", corner, "background"),
                              ("outside", [1e4, 0.0, 0.0], "outside the volume")):
        bad_seed = VesselCenterline(Input=cta, UseSeedPoint=1, SeedPoint=point)  # noqa: F821
        bad_seed.UpdatePipeline()
        out = servermanager.Fetch(bad_seed)
        message = out.GetFieldData().GetAbstractArray("ExtractionMessage").GetValue(0)
        check.true(out.GetNumberOfPoints() == 0 and text in message
                   and "pick a point on a vessel" in message,
                   "seed on %s: empty output and %r" % (name, message))
else:
    print("no shared raw CTA at %s: raw-angiogram checks skipped" % CTA)

# A volume with no vessel-like structure says so.
flat = VesselPhantom(Shape="Y bifurcation", Dimensions=[24, 24, 24],  # noqa: F821
                     NoiseStandardDeviation=0.0, PeakIntensity=100.0)
nothing = VesselCenterline(Input=flat)  # noqa: F821
nothing.UpdatePipeline()
message = servermanager.Fetch(nothing).GetFieldData().GetAbstractArray(
    "ExtractionMessage").GetValue(0)
check.true("no vessel-like structure" in message, "a flat volume says so (%r)" % message)

check.finish()
