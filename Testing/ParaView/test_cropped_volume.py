"""A volume whose extent does not start at 0 (ParaView's Extract Subset, a reader's VOI):
VesselCenterline and VesselCandidateRegion place their output where the voxels are.

A user crops a large angiogram to the region of interest before extracting; the crop keeps the
voxels' extent (Extract Subset's VOI [10, 127, ...] is the extent [10, 127, ...]), and the
filters must read it. Before, both indexed the voxels from the origin as if the extent started
at 0: the centerlines came out shifted by the crop's start (12.8 mm on the tree below), and a seed
given in world coordinates fell on another voxel. Each case compares the cropped run with the
whole volume's run, away from the crop's faces (a crop cuts vessels, so their ends move).
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, plugin_path  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402
from vtkmodules.numpy_interface import dataset_adapter as dsa  # noqa: E402
import numpy as np  # noqa: E402

simple.LoadPlugin(plugin_path(), ns=globals())
CHECK = Check("cropped_volume")

# The crop's first voxel, per axis; the phantoms have 1 mm voxels from the origin.
CROP_START = (10, 12, 8)
# Away from the crop's faces by more than a vessel's end cap (project rule for this test: the
# phantoms' largest radius is 4 voxels, an end moves by at most about one radius plus a voxel).
FACE_CLEARANCE_MM = 6.0


def points_of(source):
    data = sm.Fetch(source)
    return np.asarray(dsa.WrapDataObject(data).Points if data.GetNumberOfPoints() else
                      np.zeros((0, 3)), dtype=float)


def nearest_mm(a, b):
    """For each point of `a`, the distance to the nearest point of `b`."""
    return np.array([np.min(np.linalg.norm(b - p, axis=1)) for p in a]) if len(b) else \
        np.full(len(a), np.inf)


def inside(points, bounds, margin):
    lo = np.array(bounds[0::2]) + margin
    hi = np.array(bounds[1::2]) - margin
    return np.all((points >= lo) & (points <= hi), axis=1)


def crop(volume):
    """Extract Subset from CROP_START to the extent's end, as a user crops to a region."""
    subset = crop_by(volume, CROP_START, 0)
    got = subset.GetDataInformation().DataInformation.GetExtent()
    CHECK.equal(tuple(got[0::2]), CROP_START, "Extract Subset keeps the VOI as the extent")
    return subset


def compare(name, whole_run, cropped_run, cropped_bounds, p95_mm):
    whole = points_of(whole_run)
    cropped = points_of(cropped_run)
    if not CHECK.true(len(whole) > 20 and len(cropped) > 20,
                      "%s: both runs give centerlines (%d, %d points)"
                      % (name, len(whole), len(cropped))):
        return
    CHECK.true(bool(np.all(inside(cropped, cropped_bounds, -0.5))),
               "%s: every point of the cropped run lies in the cropped volume (%s to %s)"
               % (name, cropped.min(axis=0), cropped.max(axis=0)))
    inner = cropped[inside(cropped, cropped_bounds, FACE_CLEARANCE_MM)]
    CHECK.true(len(inner) > 10, "%s: points away from the crop's faces (%d)" % (name, len(inner)))
    d = nearest_mm(inner, whole)
    # A crop that cuts vessels moves the coder's root and ends (Docs/CENTERLINES.md: the root
    # envelope, up to about 2 voxels), and a raw volume's automatic range follows the crop's
    # statistics: the same vessels, not the same points.
    CHECK.true(float(np.percentile(d, 95)) <= p95_mm,
               "%s: away from the faces 95 %% of the cropped run within %.1f mm of the whole "
               "run (%.3f mm)" % (name, p95_mm, float(np.percentile(d, 95))))


def crop_by(volume, start, end_margin):
    """Extract Subset from `start` to the extent's end less `end_margin` voxels."""
    volume.UpdatePipeline()
    extent = volume.GetDataInformation().DataInformation.GetExtent()
    subset = simple.ExtractSubset(Input=volume)
    subset.VOI = [start[0], extent[1] - end_margin, start[1], extent[3] - end_margin,
                  start[2], extent[5] - end_margin]
    subset.UpdatePipeline()
    return subset


# A binary-like tree, no seed (the mask's default range). Two voxels off every face cut no
# vessel: the cropped run is the whole run, point for point.
tree = VesselPhantom(Shape="Tree", Dimensions=[128, 128, 128])  # noqa: F821
whole_tree = points_of(VesselCenterline(Input=tree))  # noqa: F821
trimmed = points_of(VesselCenterline(Input=crop_by(tree, (2, 2, 2), 2)))  # noqa: F821
if CHECK.true(len(trimmed) == len(whole_tree) > 20,
              "tree, 2 voxels off every face: the whole run's point count (%d, %d)"
              % (len(trimmed), len(whole_tree))):
    CHECK.true(float(np.max(np.abs(trimmed - whole_tree))) == 0.0,
               "tree, 2 voxels off every face: the whole run's points exactly (%.3g mm)"
               % float(np.max(np.abs(trimmed - whole_tree))))
tree_cropped = crop(tree)
compare("tree", VesselCenterline(Input=tree),  # noqa: F821
        VesselCenterline(Input=tree_cropped),  # noqa: F821
        tree_cropped.GetDataInformation().DataInformation.GetBounds(), p95_mm=2.5)

# A raw angiogram (ClientServer.DistributedRawSeeded's), one click: the automatic range at a seed
# given in world coordinates, inside the crop.
raw = VesselPhantom(Shape=8, Dimensions=[112, 112, 112],  # noqa: F821
                           AngiogramSegments=60, ClutterCount=4, Seed=3, OutputScalarType=10)
raw_cropped = crop(raw)
SEED_MM = [44.88289970840682, 60.87682959102523, 8.0]


def seeded_centerline(volume):
    return VesselCenterline(Input=volume, AutomaticIntensityRange=1,  # noqa: F821
                                   UseSeedPoint=1, SeedPoint=SEED_MM)


whole_raw = seeded_centerline(raw)
cropped_raw = seeded_centerline(raw_cropped)
compare("raw seeded", whole_raw, cropped_raw,
        raw_cropped.GetDataInformation().DataInformation.GetBounds(), p95_mm=1.5)


def range_used(run):
    used = sm.Fetch(run).GetFieldData().GetArray("IntensityRangeUsed")
    return [used.GetValue(0), used.GetValue(1)] if used else None


whole_range, cropped_range = range_used(whole_raw), range_used(cropped_raw)
if CHECK.true(whole_range is not None and cropped_range is not None, "both runs report a range"):
    # The crop's own statistics move the estimate a little (3 % of the width here).
    width = whole_range[1] - whole_range[0]
    CHECK.true(max(abs(a - b) for a, b in zip(whole_range, cropped_range)) <= 0.05 * width,
               "raw seeded: the range estimated at the seed within 5 %% of the whole run's "
               "width (%s, %s)" % (cropped_range, whole_range))

# The candidate region (the panel's Preview) at the same seed: the cropped mask is the whole
# mask's crop, voxel for voxel, away from the crop's faces.
def candidate(volume):
    region = VesselCandidateRegion(Input=volume, AutomaticIntensityRange=1,  # noqa: F821
                                          UseSeedPoint=1, SeedPoint=SEED_MM)
    image = sm.Fetch(region)
    mask = dsa.WrapDataObject(image).PointData["CandidateVessel"]
    dims = image.GetDimensions()
    return np.asarray(mask).reshape(dims[2], dims[1], dims[0]), image.GetExtent()


whole_mask, _ = candidate(raw)
cropped_mask, cropped_extent = candidate(raw_cropped)
CHECK.equal(tuple(cropped_extent[0::2]), CROP_START, "the candidate region keeps the crop's extent")
i, j, k = CROP_START
clear = int(FACE_CLEARANCE_MM)
whole_part = whole_mask[k:, j:, i:][clear:-clear, clear:-clear, clear:-clear]
cropped_part = cropped_mask[clear:-clear, clear:-clear, clear:-clear]
if CHECK.true(int(whole_part.sum()) > 100,
              "the whole run's candidate region has vessel voxels in the crop (%d)"
              % int(whole_part.sum())):
    agree = float(np.sum((whole_part > 0) & (cropped_part > 0))) / float(np.sum(whole_part > 0))
    CHECK.true(agree >= 0.95,
               "the cropped candidate region holds the whole run's voxels there (%.3f)" % agree)

CHECK.finish()
