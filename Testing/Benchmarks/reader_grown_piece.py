"""The reader's re-execution for a grown piece, alone (issue 19, item 4): what a distributed
VesselCenterline's request costs each rank before its RequestData (Docs/SCALING.md, "Where the
distributed filter's time goes"). In one process, built in:

    VESSELTOUCH_READER_HUGE_PAGES=0|1 pvpython Testing/Benchmarks/reader_grown_piece.py \\
        --plugin build/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
        --volume tree.nrrd [--piece 0 --pieces 2 --margin 73]

Reads piece `--piece` of `--pieces` (the executive's block split), keeps it held elsewhere (as a
view or the data information keeps a rank's piece), then asks for the same piece grown by
`--margin` voxels on its shared faces, as the filter does. Prints one JSON line per read: wall s,
the reader's own ReaderSeconds and ReaderValueRangeSeconds, bytes read and reused, and the
process's minor page faults during the read (getrusage: the first touch of the new piece's
memory, independent of the machine's load, unlike the times).
"""

import argparse
import json
import resource
import time

from paraview import simple
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator, vtkStreamingDemandDrivenPipeline


def timed_read(algorithm, extent, label):
    faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    t = time.perf_counter()
    algorithm.UpdateExtent(extent)
    out = {"read": label, "extent": list(extent), "wall_s": time.perf_counter() - t,
           "minor_page_faults": resource.getrusage(resource.RUSAGE_SELF).ru_minflt - faults}
    fd = algorithm.GetOutput().GetFieldData()
    for name in ("ReaderSeconds", "ReaderValueRangeSeconds", "ReaderVoxelBytesRead",
                 "ReaderVoxelBytesReused"):
        a = fd.GetArray(name)
        out[name] = a.GetValue(0) if a is not None else None
    print(json.dumps(out), flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--volume", required=True)
    parser.add_argument("--piece", type=int, default=0)
    parser.add_argument("--pieces", type=int, default=2)
    parser.add_argument("--margin", type=int, default=73, help="voxels (the scaling run's G)")
    args = parser.parse_args()
    simple.LoadPlugin(args.plugin, remote=False)
    algorithm = simple.OpenDataFile(args.volume).GetClientSideObject()
    algorithm.UpdateInformation()
    whole = algorithm.GetOutputInformation(0).Get(vtkStreamingDemandDrivenPipeline.WHOLE_EXTENT())
    piece = [0] * 6
    vtkExtentTranslator().PieceToExtentThreadSafe(args.piece, args.pieces, 0, list(whole), piece,
                                                  vtkExtentTranslator.BLOCK_MODE, 0)
    grown = [max(whole[a], piece[a] - args.margin) if a % 2 == 0 else
             min(whole[a], piece[a] + args.margin) for a in range(6)]
    timed_read(algorithm, piece, "piece")
    held = vtkImageData()  # the piece held elsewhere: the reader copies from it
    held.ShallowCopy(algorithm.GetOutput())
    timed_read(algorithm, grown, "grown")


main()
