"""Benchmark (not a test): the real aorta at finer sampling, full resolution against the automatic
scale, both against VMTK's reference centerline.

    pvpython Testing/Benchmarks/aorta_upsampled.py \\
        --plugin <build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
        [--factors 1 3 4] [--json out.json]

The VMTK level set (../shared/data/vmtk-aorta/aorta-final-levelset.mha, vessel where < 0) is
resampled by each magnification factor (linear interpolation, vtkImageResample): x3 gives a
469 x 1177 x 100 volume whose aorta is 8 to 26 voxels in radius, the thick-vessel case the automatic
scale (DownsampleFactor 0) is for. Each volume runs through VesselCenterline with DownsampleFactor 1
(full resolution) and 0 (automatic, the default). Prints time, the factor used, the number of
paths and the distances to the reference (mm): mean and p95 from the output to the reference, and
the fraction of reference points within 1 mm of the output.
"""

import argparse
import json
import os
import sys
import time

import numpy as np
from paraview import servermanager, simple
from scipy.spatial import cKDTree
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkImagingCore import vtkImageResample
from vtkmodules.vtkIOImage import vtkMetaImageReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "..", "shared", "data", "vmtk-aorta")
# A voxel (i, j, k) of the level set lies at this point of the reference's frame (see the data
# folder's README): both in-plane axes are flipped relative to the MetaImage offset.
VMTK_ORIGIN = np.array([156.445, 24.6094, 0.0])


def reference_points():
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(os.path.join(DATA, "aorta-centerline.vtp"))
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPoints().GetData())


def run(image, magnification, reference, origin):
    resample = vtkImageResample()
    resample.SetInputData(image)
    resample.SetInterpolationModeToLinear()
    for axis in range(3):
        resample.SetAxisMagnificationFactor(axis, magnification)
    resample.Update()
    volume = resample.GetOutput()
    source = simple.TrivialProducer()
    source.GetClientSideObject().SetOutput(volume)
    rows = []
    for factor in (1, 0):
        centerline = simple.VesselCenterline(Input=source, AutomaticIntensityRange=0,
                                             LowerThreshold=-1e30,
                                             UpperThreshold=-1e-9, DownsampleFactor=factor)
        t0 = time.perf_counter()
        centerline.UpdatePipeline()
        seconds = time.perf_counter() - t0
        poly = servermanager.Fetch(centerline)
        points = vtk_to_numpy(poly.GetPoints().GetData()).copy()
        # ParaView's MetaImage reader ignores the direction matrix: world = origin + index * spacing.
        in_reference = VMTK_ORIGIN + (points - origin)
        to_reference, _ = cKDTree(reference).query(in_reference)
        covered, _ = cKDTree(in_reference).query(reference)
        used = poly.GetFieldData().GetArray("DownsampleFactorUsed")
        rows.append({
            "magnification": magnification,
            "dims": "x".join(str(d) for d in volume.GetDimensions()),
            "downsample": factor,
            "factor_used": int(used.GetValue(0)) if used else None,
            "seconds": seconds,
            "paths": poly.GetNumberOfLines(),
            "mean_mm": float(to_reference.mean()),
            "p95_mm": float(np.percentile(to_reference, 95)),
            "within_1mm": float((covered <= 1.0).mean()),
        })
        simple.Delete(centerline)
    simple.Delete(source)
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--plugin", required=True, help="VesselTouch.so")
    parser.add_argument("--factors", type=float, nargs="+", default=[1, 3, 4],
                        help="magnification factors of the level set")
    parser.add_argument("--json", help="also write the rows here")
    args = parser.parse_args()
    simple.LoadPlugin(args.plugin)  # adds VesselCenterline to paraview.simple
    reader = vtkMetaImageReader()
    reader.SetFileName(os.path.join(DATA, "aorta-final-levelset.mha"))
    reader.Update()
    image = reader.GetOutput()
    origin = np.array(image.GetOrigin())
    reference = reference_points()
    rows = []
    print("| magnification | volume | DownsampleFactor | factor used | s | paths | mean mm | "
          "p95 mm | reference within 1 mm |")
    print("|---|---|---|---|---|---|---|---|---|")
    for m in args.factors:
        for r in run(image, m, reference, origin):
            rows.append(r)
            print("| x%g | %s | %s | %s | %.3f | %d | %.2f | %.2f | %.3f |" % (
                r["magnification"], r["dims"], "auto (0)" if r["downsample"] == 0 else "1",
                r["factor_used"], r["seconds"], r["paths"], r["mean_mm"], r["p95_mm"],
                r["within_1mm"]), flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
