"""Where a distributed VesselCenterline departs from the single run, point by point (issue 19,
item 2: the stitched skeleton within 0.1 voxel of a single-process run).

    VESSELTOUCH_PLUGIN=<build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
      Testing/Utilities/vtouch-xvfb-run pvpython \\
      Testing/ParaView/clientserver/compare_to_single_run.py --phantom Y --ranks 4 \\
      [--volume tree.nrrd] [--seed X Y Z] [--lower 550] [--radius 3.2] [--near-root 4]

The single run is the built-in VesselCenterline (this process); the distributed run is the same
filter on an N-rank pvserver (DistributedExtraction on). Both outputs are fetched and compared as
ClientServer.DistributedExtraction compares them (vtouch_skeleton_graph: point to nearest point,
in voxels of the largest spacing, both ways). `--phantom NAME` writes the 128^3 VesselPhantom of
that test (tree, ring, Y, loop network; radius 0.025 N, threshold 550, LargestVesselRadius 3.2)
or `along-face` ClientServer.VesselAlongPieceFace's tubes (LargestVesselRadius 3) instead of
reading `--volume`. Printed: the topologies, the share of points within 0.1 voxel,
and for every point beyond it (either way): the distance, the piece owning it (the executive's
split, the shared face owned by the upper piece: vtouch::PieceOwnership), its distance to the
nearest shared face and to the nearest junction, vessel end and root of the single run, and a
class:
- `root`: within --near-root voxels of the distributed run's root (its own known cause, left
  to the trace stage);
- `interior`: farther than the overlap band (4 voxels) + copy reach (1.5 voxels) from every
  shared face: the stitch takes the owner's points as they are there, so the owner coded them
  differently (a coding cause);
- `band`: within that distance of a shared face: the stitch picks copies there, so either.
A measurement, not a test: nothing is asserted.
"""

import argparse
import os
import shutil
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]
from vtouch_pvserver import ParallelServer, write_float_nrrd  # noqa: E402
from vtouch_skeleton_graph import graph  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402
from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator  # noqa: E402

PHANTOMS = {"tree": 5, "loop network": 6, "ring": 0, "Y": 4}
ALONG_FACE = "along-face"  # ClientServer.VesselAlongPieceFace's phantom
PHANTOM_N = 128
PHANTOM_RADIUS_FRACTION = 0.025
BAND_VOXELS = 4.0        # kOverlapBandVoxels (vtouchSkeletonOverlapResolver.h)
COPY_REACH_VOXELS = 1.5  # kCopyReachVoxels
TOLERANCE_VOXELS = 0.1   # the 0.1 voxel


def field(data, name):
    a = data.GetFieldData().GetArray(name)
    return None if a is None else [a.GetTuple(i) for i in range(a.GetNumberOfTuples())]


def pieces(whole, ranks):
    """The executive's split (block mode, by cells), as the filter asks for it."""
    translator = vtkExtentTranslator()
    out = []
    for r in range(ranks):
        e = [0] * 6
        translator.PieceToExtentThreadSafe(r, ranks, 0, whole, e, translator.BLOCK_MODE, 0)
        out.append(e)
    return out


def owner(index, split, whole):
    """vtouch::PieceOwnership::owner: half-open boxes, the shared face the upper piece's, open
    to infinity on the volume's own faces; outside every box, the nearest."""
    best, nearest = None, -1
    for r, e in enumerate(split):
        d = 0.0
        for a in range(3):
            lo = -np.inf if e[2 * a] <= whole[2 * a] else e[2 * a]
            hi = np.inf if e[2 * a + 1] >= whole[2 * a + 1] else e[2 * a + 1]
            x = index[a]
            d = max(d, lo - x if x < lo else (x - hi if x >= hi else 0.0))
        if d == 0.0:
            return r
        if best is None or d < best:
            best, nearest = d, r
    return nearest


def shared_faces(split, whole):
    """(axis, coordinate) of every face a piece shares with another."""
    faces = set()
    for e in split:
        for a in range(3):
            if e[2 * a] > whole[2 * a]:
                faces.add((a, float(e[2 * a])))
    return sorted(faces)


def to_face(index, faces):
    return min((abs(index[a] - c) for a, c in faces), default=float("inf"))


def nearest(points, x):
    if len(points) == 0:
        return float("inf"), -1
    d = np.linalg.norm(np.asarray(points) - x, axis=1)
    i = int(np.argmin(d))
    return float(d[i]), i


def run_filter(volume, args, distributed, ranks):
    options = dict(AutomaticIntensityRange=1 if args.automatic else 0, LowerThreshold=args.lower,
                   UpperThreshold=args.upper, DistributedExtraction=1 if distributed else 0)
    if args.radius > 0:
        options["LargestVesselRadius"] = args.radius
    if args.seed:
        options.update(UseSeedPoint=1, SeedPoint=args.seed)
    make = getattr(simple, "VesselCenterline", None) or globals()["VesselCenterline"]
    centerline = make(Input=volume, **options)
    centerline.UpdatePipeline()
    data = sm.Fetch(centerline)
    simple.Delete(centerline)
    return data


def write_phantom(name, folder):
    if name == ALONG_FACE:
        # ClientServer.VesselAlongPieceFace's tubes (radius 3, binary; LargestVesselRadius 3).
        from test_cs_vessel_along_face import phantom_image
        path = os.path.join(folder, "along_face.nrrd")
        write_float_nrrd(path, phantom_image())
        return path
    simple.LoadPlugin(os.environ["VESSELTOUCH_PLUGIN"], remote=False, ns=globals())
    phantom = VesselPhantom(Dimensions=[PHANTOM_N] * 3,  # noqa: F821
                            RadiusFraction=PHANTOM_RADIUS_FRACTION, Shape=PHANTOMS[name])
    path = os.path.join(folder, "%s.nrrd" % name.replace(" ", "_"))
    write_float_nrrd(path, sm.Fetch(phantom))
    simple.Delete(phantom)
    return path


def single_run(path, args):
    simple.LoadPlugin(os.environ["VESSELTOUCH_PLUGIN"], remote=False, ns=globals())
    volume = simple.OpenDataFile(path)
    volume.UpdatePipeline()
    info = volume.GetDataInformation().DataInformation
    whole = list(info.GetExtent())
    spacing = list(sm.Fetch(volume).GetSpacing())
    origin = list(sm.Fetch(volume).GetOrigin())
    data = run_filter(volume, args, False, 1)
    simple.Delete(volume)
    return data, whole, spacing, origin


def distributed_run(path, args):
    server = ParallelServer(ranks=args.ranks)
    server.start()
    try:
        server.connect(os.environ["VESSELTOUCH_PLUGIN"])
        volume = simple.OpenDataFile(path)
        data = run_filter(volume, args, True, args.ranks)
        simple.Delete(volume)
        simple.Disconnect()
    finally:
        server.stop()
    return data


def report(single, got, whole, spacing, origin, args):
    voxel = max(spacing)
    ref, dist = graph(single, voxel), graph(got, voxel)
    split = pieces(whole, args.ranks)
    faces = shared_faces(split, whole)
    roots = field(got, "RootChoiceRoots") or []
    root_points = [np.array(origin) + np.array(r) * np.array(spacing) for r in roots]
    if args.seed:
        root_points.append(np.array(args.seed))
    junctions = [ref["chains"][p][i] for p, i in ref["parents"]]

    def topology(g):
        return "%d paths, %d points, %d ends, %d bifurcations, %d loops" % (
            g["paths"], len(g["points"]), g["ends"], len(g["bifurcations"]), g["cycles"])
    print("single run:  %s" % topology(ref))
    print("%d ranks:     %s; split %s; stitch %s" % (
        args.ranks, topology(dist), split,
        {n: field(got, n)[0][0] for n in ("StitchCutEndsJoined", "StitchCutEndsUnmatched",
                                           "StitchDuplicatesRemoved", "StitchPointsDropped")
         if field(got, n)}))
    rows = []
    for label, a, b in (("distributed", dist["points"], ref["points"]),
                        ("single", ref["points"], dist["points"])):
        within = 0
        for x in a:
            d, _ = nearest(b, x)
            d /= voxel
            if d <= TOLERANCE_VOXELS:
                within += 1
                continue
            index = (x - np.array(origin)) / np.array(spacing)
            near_root = min((np.linalg.norm(x - r) / voxel for r in root_points),
                            default=float("inf"))
            face = to_face(index, faces)
            kind = ("root" if near_root <= args.near_root else
                    "interior" if face > BAND_VOXELS + COPY_REACH_VOXELS else "band")
            rows.append((label, d, x, owner(index, split, whole), face,
                         nearest(junctions, x)[0] / voxel, nearest(ref["end_points"], x)[0] / voxel,
                         near_root, kind))
        print("%s points within %.1f voxel of the other run: %d of %d (%.1f %%)"
              % (label, TOLERANCE_VOXELS, within, len(a), 100.0 * within / max(1, len(a))))
    print("%-11s %8s  %-26s %5s %8s %9s %7s %7s  %s" % (
        "point of", "voxels", "position (mm)", "owner", "to face", "junction", "end", "root",
        "class"))
    for label, d, x, r, face, junction, end, root, kind in sorted(rows, key=lambda t: -t[1]):
        print("%-11s %8.3f  (%7.2f, %7.2f, %7.2f) %5d %8.2f %9.2f %7.2f %7.2f  %s"
              % (label, d, x[0], x[1], x[2], r, face, junction, end, root, kind))
    counted = [t for t in rows if t[8] != "root"]
    print("beyond %.1f voxel, not near a root: %d points (%d interior, %d band), farthest %.3f"
          % (TOLERANCE_VOXELS, len(counted), sum(t[8] == "interior" for t in counted),
             sum(t[8] == "band" for t in counted), max((t[1] for t in counted), default=0.0)))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--volume", help="a volume VesselTouch's readers read (NRRD, ...)")
    parser.add_argument("--phantom", choices=sorted(PHANTOMS) + [ALONG_FACE],
                        help="ClientServer.DistributedExtraction's 128^3 phantom instead")
    parser.add_argument("--ranks", type=int, default=4)
    parser.add_argument("--seed", type=float, nargs=3, default=None, help="world mm: seeded")
    parser.add_argument("--lower", type=float, default=None,
                        help="LowerThreshold (default 550 for a phantom, 500 for a volume)")
    parser.add_argument("--upper", type=float, default=65535.0)
    parser.add_argument("--automatic", action="store_true",
                        help="AutomaticIntensityRange (the raw modes; --lower, --upper unused)")
    parser.add_argument("--radius", type=float, default=None,
                        help="LargestVesselRadius, mm (default 3.2 for a phantom, 0 = automatic)")
    parser.add_argument("--near-root", type=float, default=4.0,
                        help="points this close to the root (voxels) are classed `root`")
    args = parser.parse_args()
    if "VESSELTOUCH_PLUGIN" not in os.environ:
        sys.exit("set VESSELTOUCH_PLUGIN to the plugin's VesselTouch.so")
    if bool(args.volume) == bool(args.phantom):
        sys.exit("give either --volume or --phantom")
    if args.volume and not os.path.exists(args.volume):
        sys.exit("no volume at %s" % args.volume)
    if args.ranks < 2:
        sys.exit("--ranks must be 2 or more (one rank is the single run)")
    if args.lower is None:
        args.lower = 550.0 if args.phantom else 500.0
    if args.radius is None:
        args.radius = (3.0 if args.phantom == ALONG_FACE else
                       PHANTOM_RADIUS_FRACTION * PHANTOM_N if args.phantom else 0.0)
    folder = tempfile.mkdtemp(prefix="vtouch-compare-")
    try:
        path = write_phantom(args.phantom, folder) if args.phantom else args.volume
        single, whole, spacing, origin = single_run(path, args)
        simple.Disconnect()
        got = distributed_run(path, args)
        report(single, got, whole, spacing, origin, args)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main()
