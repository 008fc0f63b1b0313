"""Benchmark (not a test): time and peak memory of the VesselTouch readers on a 512 x 512 x 400
16-bit volume (200 MiB of voxels), against the raw data size.

    /usr/bin/python3 Testing/Benchmarks/reader_memory.py \\
        --plugin <build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
        [--writer <build>/Testing/Logic/IO/vtouchWriteTestVolume] [--size 512 512 400] \\
        [--pieces 1 4]

Writes the volume with ITK (vtouchWriteTestVolume) as .nrrd, .mha, .nii and as a DICOM series (one
file per slice) in a temporary folder, then for each one starts a fresh pvpython that loads the
plugin, notes its peak resident memory so far (baseline), creates the reader and reads the volume
(RequestInformation + UpdatePipeline: the image stays in the reader's output, nothing is copied to
a client), and reports that wall time and the peak resident memory (ru_maxrss) above the baseline.
"copies" = (peak - baseline - raw) / raw: 0 means the voxels were read straight into the output
array. ParaView's own NRRD and MetaImage readers are measured the same way for comparison.
With --pieces N the VesselTouch readers also read piece 0 of N alone (one rank's share in a
parallel pvserver): its peak should be about 1/N of the whole volume's.
"""

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

CHILD = r"""
import json, os, resource, sys, time
from paraview.simple import LoadPlugin, OpenDataFile
from paraview import simple
LoadPlugin(sys.argv[1], ns=globals())
path, proxy, pieces = sys.argv[2], sys.argv[3], int(sys.argv[4])
def rss_kib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
baseline = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB, before the reader exists
start = time.perf_counter()
if proxy == "auto":
    reader = OpenDataFile(path)
else:
    reader = (globals().get(proxy) or getattr(simple, proxy))()
    name = "FileName" if reader.GetProperty("FileName") is not None else "FileNames"
    setattr(reader, name, path if name == "FileName" else [path])
if pieces > 1:
    # What one rank of an N-rank pvserver does: read piece 0 of N (the reader streams sub-extents).
    reader.UpdatePipelineInformation()
    reader.GetClientSideObject().UpdatePiece(0, pieces, 0)
    image = reader.GetClientSideObject().GetOutputDataObject(0)
    points = image.GetNumberOfPoints()
else:
    reader.UpdatePipeline()
    points = reader.GetDataInformation().GetNumberOfPoints()
seconds = time.perf_counter() - start
print(json.dumps({"reader": reader.GetXMLName(), "seconds": seconds, "baseline_kib": baseline,
                  "peak_kib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss,
                  "rss_after_kib": rss_kib(), "points": points}))
"""


def default_writer(plugin):
    build = os.path.abspath(os.path.join(os.path.dirname(plugin), *[os.pardir] * 4))
    return os.path.join(build, "Testing", "Logic", "IO", "vtouchWriteTestVolume")


def measure(plugin, path, proxy, pieces=1):
    out = subprocess.run(["pvpython", "-c", CHILD, plugin, path, proxy, str(pieces)], check=True,
                         capture_output=True, text=True).stdout
    return json.loads([line for line in out.splitlines() if line.startswith("{")][-1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--writer")
    parser.add_argument("--size", type=int, nargs=3, default=[512, 512, 400])
    parser.add_argument("--keep", help="folder to write into and keep (default: a temp folder)")
    parser.add_argument("--pieces", type=int, nargs="+", default=[1],
                        help="also read piece 0 of N for each N given (one rank's share)")
    args = parser.parse_args()
    writer = args.writer or default_writer(args.plugin)
    folder = args.keep or tempfile.mkdtemp(prefix="vtouch-reader-bench-")
    os.makedirs(folder, exist_ok=True)
    raw = 2 * args.size[0] * args.size[1] * args.size[2]
    size = [str(n) for n in args.size]
    try:
        cases = []
        for ext in ["nrrd", "mha", "nii"]:
            path = os.path.join(folder, "volume." + ext)
            if not os.path.exists(path):
                subprocess.run([writer, "volume", path, "axial", "int16"] + size, check=True,
                               capture_output=True)
            cases.append((path, "auto"))
        dicom = os.path.join(folder, "dicom")
        if not os.path.isdir(dicom):
            subprocess.run([writer, "dicom", dicom, "1.2.826.0.1.3680043.2.1125.99", "axial",
                            "-1", "IM"] + size, check=True, capture_output=True)
        cases.append((dicom, "VesselTouchDICOMSeriesReader"))
        vesseltouch_cases = list(cases)
        cases = [(path, proxy, 1) for path, proxy in cases]
        cases.append((os.path.join(folder, "volume.nrrd"), "NrrdReader", 1))
        cases.append((os.path.join(folder, "volume.mha"), "MetaFileSeriesReader", 1))
        for n in args.pieces:
            if n > 1:
                cases += [(path, proxy, n) for path, proxy in vesseltouch_cases]

        print("volume %s int16, raw voxels %.1f MiB" % ("x".join(size), raw / 2.0 ** 20))
        print("%-30s %-30s %6s %8s %10s %10s %8s" % ("input", "reader", "piece", "time s",
                                                      "base MiB", "peak MiB", "copies"))
        for path, proxy, pieces in cases:
            try:
                r = measure(args.plugin, path, proxy, pieces)
            except subprocess.CalledProcessError as e:
                print("%-30s %-30s failed: %s" % (os.path.basename(path), proxy,
                                                  e.stderr.strip().splitlines()[-1:]))
                continue
            # "copies" against the bytes this read should hold: the whole volume or the piece.
            held = 2.0 * r["points"]
            extra = (r["peak_kib"] - r["baseline_kib"]) * 1024.0 - held
            print("%-30s %-30s %6s %8.2f %10.1f %10.1f %8.2f" % (
                os.path.basename(path), r["reader"], "1/%d" % pieces, r["seconds"],
                r["baseline_kib"] / 1024.0, r["peak_kib"] / 1024.0, extra / held))
            sys.stdout.flush()
    finally:
        if not args.keep:
            shutil.rmtree(folder, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
