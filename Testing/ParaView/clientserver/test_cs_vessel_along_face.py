"""Client/server integration test (issue 19, item 2): vessels lying along the piece face.

Run as ``pvpython test_cs_vessel_along_face.py`` with VESSELTOUCH_PLUGIN set, on a display
(vtouch-xvfb-run). A 128^3 phantom built here (tubes of radius 3 voxels, binary, written as raw
NRRD): the executive splits it on 2 ranks at z = 63 (the layer z = 63 is the upper piece's), and
- five vessels run along that face for 84 voxels at z = 63 - 0.7, -0.3, 0, +0.3 and +0.7,
  then turn into one piece or the other and run on beyond the other rank's ghost margin, so
  each rank codes the stretch along the face from a component it sees differently (its own
  root): the two ranks' copies differ by fractions of a voxel, on either side of the face;
- a branch leaves the +0.7 vessel on the face into the upper piece (a junction on the face,
  hanging on a duplicated vessel);
- a vessel crosses the face at about 17 degrees, both ends far in either piece.
Ownership by point position lost such stretches (neither rank kept them: Docs/CLIENT-SERVER.md).
With the overlap band the stitched skeleton must have the built-in run's vessel ends,
bifurcations and loops, no cut end unmatched, no point dropped (StitchPointsDropped 0), no
bifurcation without its branch, and every point within 0.1 voxel of the built-in run plus the
built-in run's own root dependence there (per point: how far the same built-in run moves when
rooted elsewhere, the largest over each connected part, as the distributed test's envelope
does per phantom). Exits non-zero on any failure.
"""

import os
import shutil
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]
from vtouch_pvserver import run_connected, write_float_nrrd  # noqa: E402
from vtouch_skeleton_graph import graph  # noqa: E402
from vtouch_testing import Check, plugin_path  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402

PLUGIN = plugin_path()
CHECK = Check("client/server vessel along a piece face")
check = CHECK.true
N = 128
FACE_Z = 63.0
RADIUS = 3.0
# The ghost margin for LargestVesselRadius 3 (GhostMarginRule: ceil(7 R + 1) + 2); the test
# checks the filter reports it.
GHOST_VOXELS = 24
FILTER = dict(AutomaticIntensityRange=0, LowerThreshold=550.0, DistributedExtraction=1,
              LargestVesselRadius=RADIUS)


def polylines():
    """The phantom's vessels as polylines (x, y, z) in voxels."""
    lines = []
    for k, (offset, turn_z) in enumerate([(-0.7, 8.0), (-0.3, 118.0), (0.0, 8.0), (0.3, 118.0),
                                          (0.7, 8.0)]):
        y = 14.0 + 19.0 * k
        z = FACE_Z + offset
        lines.append([(14.0, y, z), (96.0, y, z), (112.0, y, turn_z)])
    lines.append([(56.0, 90.0, FACE_Z + 0.7), (44.0, 90.0, 92.0)])  # the branch, upward
    lines.append([(10.0, 116.0, 8.0), (22.0, 116.0, 45.0), (104.0, 116.0, 70.0),
                  (116.0, 116.0, 118.0)])  # a shallow crossing (~17 degrees)
    return lines


def phantom_image():
    """1000 within RADIUS of a polyline, 0 elsewhere, as vtkImageData (1 mm voxels at 0)."""
    z, y, x = np.meshgrid(np.arange(N), np.arange(N), np.arange(N), indexing="ij")
    grid = np.stack([x, y, z], axis=-1).reshape(-1, 3).astype(np.float64)
    inside = np.zeros(len(grid), dtype=bool)
    for line in polylines():
        for a, b in zip(line[:-1], line[1:]):
            a, b = np.array(a), np.array(b)
            ab = b - a
            t = np.clip(((grid - a) @ ab) / (ab @ ab), 0.0, 1.0)
            inside |= np.linalg.norm(grid - (a + t[:, None] * ab), axis=1) <= RADIUS
    values = np.where(inside, 1000.0, 0.0).astype(np.float32)
    image = vtkImageData()
    image.SetDimensions(N, N, N)
    array = numpy_to_vtk(values, deep=True)
    array.SetName("ImageScalars")
    image.GetPointData().SetScalars(array)
    return image


def nearest_distances(a, b):
    """For each point of `a`, the distance to the nearest point of `b` (voxels)."""
    out = np.empty(len(a))
    for start in range(0, len(a), 512):
        block = a[start:start + 512]
        out[start:start + 512] = np.sqrt(((block[:, None, :] - b[None, :, :]) ** 2)
                                         .sum(axis=2)).min(axis=1)
    return out


def topology(g):
    return {"ends": g["ends"], "bifurcations": len(g["bifurcations"]), "cycles": g["cycles"]}


def components(points, link=4.0):
    """Labels of the connected parts of a skeleton's points (linked within `link` voxels: the
    coder's points may lie a few voxels apart; the phantom's vessels lie 19 apart)."""
    label = list(range(len(points)))

    def find(a):
        while label[a] != a:
            label[a] = label[label[a]]
            a = label[a]
        return a
    for i in range(len(points)):
        near = np.nonzero(np.linalg.norm(points[i + 1:] - points[i], axis=1) <= link)[0]
        for j in near:
            label[find(int(i + 1 + j))] = find(i)
    return np.array([find(i) for i in range(len(points))])


def builtin_reference(path):
    """The built-in graph and, per reference point, how far it moves when the run is rooted at
    another point (seeded at each part's two far ends, its lowest x and its farthest from the
    face, and where each rank's grown piece cuts it): the coder's own root dependence there. A
    seeded run codes the seed's part only, so each rerooted run is compared on its own part."""
    simple.LoadPlugin(PLUGIN, remote=False, ns=globals())
    volume = simple.OpenDataFile(path)
    centerline = VesselCenterline(Input=volume, **FILTER)  # noqa: F821
    centerline.UpdatePipeline()
    reference = graph(sm.Fetch(centerline), 1.0)
    points = reference["points"]
    parts = components(points)
    envelope = np.zeros(len(points))
    for part in sorted(set(parts)):
        members = np.nonzero(parts == part)[0]
        seeds = {members[np.argmin(points[members, 0])],
                 members[np.argmax(np.abs(points[members, 2] - FACE_Z))]}
        # Where a rank's grown piece cuts the part: a rank codes what it sees of the part from
        # a root of its own, often that cut.
        for z in (FACE_Z - GHOST_VOXELS, FACE_Z + GHOST_VOXELS):
            k = members[np.argmin(np.abs(points[members, 2] - z))]
            if abs(points[k, 2] - z) < 2.0:
                seeds.add(k)
        for k in sorted(seeds):
            rerooted = VesselCenterline(Input=volume, UseSeedPoint=1,  # noqa: F821
                                        SeedPoint=[float(x) for x in points[k]], **FILTER)
            rerooted.UpdatePipeline()
            other = graph(sm.Fetch(rerooted), 1.0)["points"]
            simple.Delete(rerooted)
            envelope[members] = np.maximum(envelope[members],
                                           nearest_distances(points[members], other))
    print("built in: %d paths, %s, %d parts; root envelope up to %.3f voxel (median %.3f)"
          % (reference["paths"], topology(reference), len(set(parts)), envelope.max(),
             np.median(envelope)))
    # The largest move over each part: a root changes the coder's slabs along the whole part
    # (Docs/CLIENT-SERVER.md), so a rank that roots the part elsewhere may move any point of it
    # that far, not only where these few roots did.
    for part in set(parts):
        members = parts == part
        envelope[members] = envelope[members].max()
    simple.Delete(centerline)
    simple.Delete(volume)
    return reference, envelope


def field(data, name):
    a = data.GetFieldData().GetArray(name)
    return None if a is None else a.GetTuple(0)[0]


def distributed(path, reference, envelope):
    volume = simple.OpenDataFile(path)
    centerline = simple.VesselCenterline(Input=volume, **FILTER)
    centerline.UpdatePipeline()
    data = sm.Fetch(centerline)
    got = graph(data, 1.0)
    names = ("StitchCutEndsJoined", "StitchCutEndsUnmatched", "StitchAttachmentsUnresolved",
             "StitchBifurcationsWithoutBranch", "StitchDuplicatesRemoved", "StitchPointsDropped")
    stitch = {n: field(data, n) for n in names}
    print("on 2 ranks: %d paths, %d points, %s; %s"
          % (got["paths"], len(got["points"]), topology(got), stitch))
    check(field(data, "DistributedPieces") == 2, "the extraction ran on both ranks")
    check(field(data, "GhostMarginVoxels") == GHOST_VOXELS, "the ghost margin is %d voxels (%s)"
          % (GHOST_VOXELS, field(data, "GhostMarginVoxels")))
    check((stitch["StitchDuplicatesRemoved"] or 0) > 0, "the ranks' copies overlapped (%s removed)"
          % stitch["StitchDuplicatesRemoved"])
    for n in names[1:4] + names[5:]:
        check(stitch[n] == 0, "%s is 0 (%s)" % (n, stitch[n]))
    check(topology(got) == topology(reference), "the built-in topology (%s vs %s)"
          % (topology(got), topology(reference)))
    # Both ways: every stitched point near the reference, every reference point near the
    # stitched skeleton (a lost stretch shows here), each within 0.1 voxel + the root envelope
    # at the reference point concerned.
    to_reference = nearest_distances(got["points"], reference["points"])
    nearest = np.array([int(np.argmin(np.linalg.norm(reference["points"] - p, axis=1)))
                        for p in got["points"]])
    excess_got = to_reference - (envelope[nearest] + 0.1)
    excess_ref = nearest_distances(reference["points"], got["points"]) - (envelope + 0.1)
    worst = max(excess_got.max(), excess_ref.max())
    for k in np.argsort(-excess_got)[:3]:
        if excess_got[k] > 0.0:
            print("  stitched point %s is %.3f voxel from the built-in run (envelope there %.3f)"
                  % (np.round(got["points"][k], 2), to_reference[k], envelope[nearest[k]]))
    print("  largest distance beyond 0.1 voxel + the root envelope: %.3f voxel; largest "
          "distance %.3f voxel" % (worst, max(to_reference.max(), (excess_ref + envelope
                                                                    + 0.1).max())))
    check(worst <= 0.0, "every point within 0.1 voxel + the root envelope (worst excess %.3f)"
          % worst)
    simple.Delete(centerline)
    simple.Delete(volume)


def main():
    folder = tempfile.mkdtemp(prefix="vtouch-cs-along-face-")
    try:
        path = os.path.join(folder, "along_face.nrrd")
        write_float_nrrd(path, phantom_image())
        reference, envelope = builtin_reference(path)
        check(reference["paths"] > 0, "the built-in reference has paths")
        simple.Disconnect()
        run_connected(PLUGIN, check, lambda: distributed(path, reference, envelope))
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    CHECK.finish()


if __name__ == "__main__":
    main()
