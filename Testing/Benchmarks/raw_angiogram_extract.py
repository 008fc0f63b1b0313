"""Benchmark runner (not a test): VesselCenterline on raw angiograms, in the ParaView pipeline, as
a user runs it: one seed, no intensity range typed. Called by Utilities/bench/run_bench.py (section
rawcenterline) and by raw_angiogram_accuracy_test.py; the measures are computed from its output
by Utilities/bench/centerline_metrics.py.

    Testing/Utilities/vtouch-xvfb-run pvpython Testing/Benchmarks/raw_angiogram_extract.py \\
        --plugin <build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
        --cases cases.json --out DIR [--keep-volume]

cases.json is a list of cases:
  {"tag": "n128_s1_g20", "phantom": {"Dimensions": [128, 128, 128], "Seed": 1,
                                     "NoiseStandardDeviation": 20, ...VesselPhantom properties}}
  {"tag": "cta_aorta", "file": ".../aorta.mha", "seed_mm": [x, y, z]}
  {"tag": "tof", "file": ".../chris_MRA.nii.gz", "seed_voxel": [i, j, k]}   (world from the image)
A phantom is a VesselPhantom with Shape "Raw angiogram" (the other properties as given); its seed
is the first point of the true tree (port 1), on the root. For each case DIR/<tag>.npz holds the
extraction (points, line offsets), the truth (phantom: points, radius, line offsets), spacing,
origin, the MIP along z, and the volume when --keep-volume (for scikit-image); DIR/<tag>.json the
times: phantom_s (generation), time_s (VesselCenterline's UpdatePipeline, the input already
updated: what the user waits for), every field-data array of the output whose name ends in
"Seconds" (the filter's stage times) or holds "Range", and how the intensity range was chosen:
"automatic" (the filter's AutomaticIntensityRange) or, while the filter has no such property,
"otsu" / "otsu_upper" (centerline_metrics.vessel_threshold on the whole volume, up to its
maximum, typed for the user).
"""

import argparse
import json
import os
import sys
import time

import numpy as np
from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ beside the sources
sys.path.insert(0, os.path.join(HERE, "..", "..", "Utilities", "bench"))
import centerline_metrics as cm  # noqa: E402


def lines_to_offsets(lines):
    offsets = np.cumsum([0] + [len(l) for l in lines]).astype(np.int64)
    conn = np.concatenate(lines).astype(np.int64) if lines else np.zeros(0, np.int64)
    return conn, offsets


def volume_array(image):
    dims = image.GetDimensions()
    values = vtk_to_numpy(image.GetPointData().GetScalars())
    return values.reshape(dims[2], dims[1], dims[0])  # (k, j, i)


def run_case(case, out_dir, keep_volume):
    tag = case["tag"]
    record = {"tag": tag}
    t0 = time.perf_counter()
    truth_points = truth_radius = None
    truth_lines = []
    if "phantom" in case:
        props = dict(case["phantom"])
        source = VesselPhantom(Shape="Raw angiogram", **props)  # noqa: F821
        source.UpdatePipeline()
        truth = servermanager.Fetch(source, idx=1)
        truth_points, truth_lines = cm.vtk_lines(truth)
        truth_radius = vtk_to_numpy(truth.GetPointData().GetArray("Radius")).astype(float)
        seed = list(truth_points[0])
    else:
        source = simple.OpenDataFile(case["file"])
        source.UpdatePipeline()
        if "seed_voxel" in case:
            image = servermanager.Fetch(source)
            m = image.GetDirectionMatrix()
            direction = np.array([[m.GetElement(r, c) for c in range(3)] for r in range(3)])
            seed = list(np.array(image.GetOrigin()) + direction @ (
                np.array(case["seed_voxel"], float) * np.array(image.GetSpacing())))
        else:
            seed = list(case["seed_mm"])
    record["phantom_s"] = time.perf_counter() - t0
    image = servermanager.Fetch(source)
    volume = volume_array(image)
    record["dimensions"] = list(image.GetDimensions())
    record["spacing_mm"] = list(image.GetSpacing())
    record["seed_mm"] = seed

    filt = VesselCenterline(Input=source, UseSeedPoint=1, SeedPoint=seed)  # noqa: F821
    if "AutomaticIntensityRange" in filt.ListProperties():
        filt.AutomaticIntensityRange = 1
        record["range_mode"] = "automatic"
    else:
        lower, method = cm.vessel_threshold(volume)
        filt.LowerThreshold = lower
        filt.UpperThreshold = float(volume.max())
        record["range_mode"] = method
        record["otsu_lower"] = lower
    t0 = time.perf_counter()
    filt.UpdatePipeline()
    record["time_s"] = time.perf_counter() - t0
    poly = servermanager.Fetch(filt)
    points, lines = cm.vtk_lines(poly)
    fd = poly.GetFieldData()
    for i in range(fd.GetNumberOfArrays()):
        array = fd.GetArray(i)
        name = fd.GetArrayName(i) or ""
        if array is not None and array.GetNumberOfTuples() >= 1 and (
                name.endswith("Seconds") or "Range" in name or name.startswith("Shading")):
            values = vtk_to_numpy(array).ravel().astype(float).tolist()
            record["field." + name] = values
    record["paths"] = len(lines)
    conn, offsets = lines_to_offsets(lines)
    m = image.GetDirectionMatrix()
    arrays = dict(points=points, conn=conn, offsets=offsets,
                  direction=np.array([[m.GetElement(r, c) for c in range(3)] for r in range(3)]),
                  spacing=np.array(image.GetSpacing(), float),
                  origin=np.array(image.GetOrigin(), float), mip_z=volume.max(axis=0),
                  seed=np.array(seed, float))
    if truth_points is not None:
        tconn, toffsets = lines_to_offsets(truth_lines)
        arrays.update(truth_points=truth_points, truth_radius=truth_radius, truth_conn=tconn,
                      truth_offsets=toffsets)
    if keep_volume:
        arrays["volume"] = volume
    np.savez(os.path.join(out_dir, tag + ".npz"), **arrays)
    with open(os.path.join(out_dir, tag + ".json"), "w") as f:
        json.dump(record, f, indent=1)
    simple.Delete(filt)
    simple.Delete(source)
    print("%s: %s range, %d paths, VesselCenterline %.3f s (input %.3f s)" % (
        tag, record["range_mode"], len(lines), record["time_s"], record["phantom_s"]), flush=True)
    return record


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--cases", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--keep-volume", action="store_true")
    args = parser.parse_args()
    simple.LoadPlugin(args.plugin, ns=globals())
    os.makedirs(args.out, exist_ok=True)
    with open(args.cases) as f:
        cases = json.load(f)
    for case in cases:
        run_case(case, args.out, args.keep_volume)


if __name__ == "__main__":
    main()
