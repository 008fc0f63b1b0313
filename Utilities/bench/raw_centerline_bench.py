"""Section "rawcenterline" of Utilities/bench/run_bench.py (issue 16, item 5): VesselCenterline
on raw angiograms from one seed, no intensity range typed, against scikit-image's skeletonize_3d on
an Otsu mask of the same volume, in the same run.

Inputs:
  * the RawAngiogram VesselPhantom family: seeds x Gaussian noise levels x sizes (full: 128^3,
    256^3 and 384^3, seeds 1-3 below 384^3 and seed 1 at 384^3, noise 20 and 50 on a tissue of 400
    and vessels of 1000; in full mode also two TOF-MRA-like cases, 128^3 and 256^3 with tissue
    150 under Rician noise 40; --quick: 96^3, seed 1, both noise levels); the seed is the root's
    first point (port 1);
  * the shared raw CTA (vmtk-aorta/aorta.mha) seeded on the first point of VMTK's reference
    centerline, judged by the fraction of that reference within 1 mm of the extraction;
  * a CTA-sized raw angiogram (full: 512 x 512 x 400, --quick: 96 x 96 x 80) for the time a
    user waits, beside the time of whole-volume multi-scale vesselness on the same volume
    (vesseltouch-whole-volume-vesselness).
Measures: Utilities/bench/centerline_metrics.py. Keys (flat, units in the names):
  centerline.raw.<measure>            worst case over the phantom family (precision and recalls:
                                      the minimum; mean_dist_vox: the maximum; false_vessel_points:
                                      the sum), measure in precision, recall_r0.5_0.6,
                                      recall_r0.6_0.75, recall_r0.75_1, recall_r1_2, recall_r2_up,
                                      recall_r0.5_up, recall_r1_up, mean_dist_vox, p95_dist_vox,
                                      false_vessel_points
  centerline.raw.skimage.<measure>    the same for scikit-image (its mask: Otsu's threshold, or
                                      where that keeps more than 5 % of the volume, i.e. split
                                      the tissue, Otsu again above it: otsu_upper_cases counts them)
  centerline.raw.case.<tag>.<m>, centerline.raw.skimage.case.<tag>.<m>   every case
  centerline.raw.shaded.<measure>, .shaded.case.<tag>.<m> (and .skimage.shaded.*)   the phantom
                                      under a bias field of +/- 30 % and 50 % (quick: 50 % at
                                      96^3), apart from the family; .case.<tag>.corrected: the
                                      filter's ShadingCorrected
  centerline.raw.time_s               VesselCenterline's UpdatePipeline on the CTA-sized volume;
                                      centerline.raw.tubularity_s and .stage_<stage>_s its
                                      stages (the filter's Candidate<Stage>Seconds field data;
                                      NaN when the filter does not report them)
  centerline.raw.skimage.time_s       Otsu + skeletonize_3d on it
  centerline.raw.vesselness_whole_volume_s  whole-volume multi-scale vesselness on it
  centerline.raw.automatic_range      1 when the filter chose the range itself, 0 when the Otsu
                                      range was typed for it (a filter without
                                      AutomaticIntensityRange)
  centerline.raw.cta_aorta.coverage_1mm, .time_s, .paths and centerline.raw.skimage.cta_aorta.*
"""
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "Utilities"))
import centerline_metrics as cm  # noqa: E402
import skeleton_benchmark as sb  # noqa: E402

AGGREGATE = {"precision": min, "recall_r0.5_0.6": min, "recall_r0.6_0.75": min,
             "recall_r0.75_1": min, "recall_r1_2": min, "recall_r2_up": min,
             "recall_r0.5_up": min, "recall_r1_up": min, "mean_dist_vox": max,
             "p95_dist_vox": max, "false_vessel_points": sum}
NOISE = (20, 50)


def phantom_cases(quick):
    if quick:
        grid = [(96, 1)]
    else:
        grid = [(n, seed) for n in (128, 256) for seed in (1, 2, 3)] + [(384, 1)]
    cases = []
    for n, seed in grid:
        for noise in NOISE:
            cases.append({"tag": "n%d_s%d_g%d" % (n, seed, noise),
                          "phantom": {"Dimensions": [n, n, n], "Seed": seed,
                                      "NoiseStandardDeviation": noise,
                                      "AngiogramSegments": 100 if n < 128 else 200 if n < 256
                                      else 400}})
    if not quick:
        # TOF-MRA-like: dim tissue under Rician noise (magnitude images: the background's noise
        # is biased upward and never negative).
        for n in (128, 256):
            cases.append({"tag": "n%d_s1_mra" % n,
                          "phantom": {"Dimensions": [n, n, n], "Seed": 1, "NoiseModel": "Rician",
                                      "TissueIntensity": 150, "NoiseStandardDeviation": 40,
                                      "AngiogramSegments": 200}})
    return cases


def shaded_cases(quick):
    """The phantom under a strong bias field (a coil's or a body-long shading; the family has
    +/- 10 %), which the filter's shading correction (Docs/CENTERLINES.md, "Raw angiograms",
    step 0) divides out: measured apart from the family, scikit-image beside it."""
    n, biases = (96, (0.5,)) if quick else (128, (0.3, 0.5))
    return [{"tag": "shaded_n%d_s1_g20_b%g" % (n, b),
             "phantom": {"Dimensions": [n, n, n], "Seed": 1, "NoiseStandardDeviation": 20,
                         "AngiogramSegments": 100 if n < 128 else 200, "BiasAmplitude": b}}
            for b in biases]


def timing_case(quick):
    dims = [96, 96, 80] if quick else [512, 512, 400]
    return {"tag": "large", "phantom": {"Dimensions": dims, "Seed": 1, "NoiseStandardDeviation": 20,
                                        "AngiogramSegments": 400}}


def cta_case():
    reference = sb.read_vtp_points(os.path.join(sb.DATA, "aorta-centerline.vtp"))
    seed = reference[0] * np.array([-1.0, -1.0, 1.0])  # reference frame -> image world
    return {"tag": "cta_aorta", "file": os.path.join(sb.DATA, "aorta.mha"),
            "seed_mm": [float(v) for v in seed]}, reference


def lines_of(conn, offsets):
    return [conn[offsets[i]:offsets[i + 1]] for i in range(len(offsets) - 1)]


def skimage_run(volume, workdir):
    """Otsu mask of the whole volume (centerline_metrics.vessel_threshold: Otsu again above it
    where Otsu split the tissue), skeletonize_3d in a child process:
    (ijk points, skeletonize seconds, child seconds, threshold, threshold method)."""
    nz, ny, nx = volume.shape
    threshold, method = cm.vessel_threshold(volume)
    mask_path = os.path.join(workdir, "mask.raw")
    (volume > threshold).astype(np.uint8).tofile(mask_path)
    out = os.path.join(workdir, "skimage.npy")
    t0 = time.perf_counter()
    child = subprocess.run([sys.executable, sb.__file__, "--skimage-child", mask_path, str(nx),
                            str(ny), str(nz), out], check=True, capture_output=True, text=True)
    total = time.perf_counter() - t0
    info = json.loads(child.stdout.strip().splitlines()[-1])
    ijk = np.load(out).astype(float)
    os.remove(mask_path)
    os.remove(out)
    return ijk, info["seconds"], total, threshold, method


def run(build, quick, tmp, log):
    plugin = os.path.join(build, "lib", "paraview-5.11", "plugins", "VesselTouch", "VesselTouch.so")
    if not os.path.exists(plugin):
        raise RuntimeError("missing %s (build the plugin)" % plugin)
    workdir = os.path.join(tmp, "rawcenterline")
    os.makedirs(workdir, exist_ok=True)
    cta, reference = cta_case()
    cases = phantom_cases(quick) + shaded_cases(quick) + [timing_case(quick), cta]
    with open(os.path.join(workdir, "cases.json"), "w") as f:
        json.dump(cases, f)
    cmd = [os.path.join(ROOT, "Testing", "Utilities", "vtouch-xvfb-run"), "pvpython",
           os.path.join(ROOT, "Testing", "Benchmarks", "raw_angiogram_extract.py"),
           "--plugin", plugin, "--cases", os.path.join(workdir, "cases.json"), "--out", workdir,
           "--keep-volume"]
    text = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    log("raw centerline extraction:\n" + text.rstrip())

    results, raw = {}, {"cases": {}}
    per_case = {"vc": [], "skimage": [], "shaded_vc": [], "shaded_skimage": []}
    for case in cases:
        tag = case["tag"]
        data = np.load(os.path.join(workdir, tag + ".npz"))
        record = json.load(open(os.path.join(workdir, tag + ".json")))
        volume = data["volume"]
        spacing = data["spacing"]
        voxel = float(spacing.min())
        points = data["points"]
        lines = lines_of(data["conn"], data["offsets"])
        ijk, sk_seconds, sk_total, otsu, otsu_method = skimage_run(volume, workdir)
        row = {"time_s": record["time_s"], "input_s": record["phantom_s"],
               "paths": record["paths"], "range_mode": record["range_mode"],
               "skimage_time_s": sk_seconds, "otsu_threshold": otsu,
               "otsu_method": otsu_method,
               "dimensions": record["dimensions"]}
        row.update({k: v for k, v in record.items() if k.startswith("field.")})
        if tag == "cta_aorta":
            mapped = points * np.array([-1.0, -1.0, 1.0])
            row["coverage_1mm"] = cm.coverage(mapped, lines, reference, 1.0, 0.25)
            row["skimage_coverage_1mm"] = cm.coverage(sb.aorta_frame(ijk, world=False), None,
                                                      reference, 1.0, 0.25)
            for k in ("coverage_1mm", "time_s", "paths"):
                results["centerline.raw.cta_aorta.%s" % k] = row[k]
            results["centerline.raw.skimage.cta_aorta.coverage_1mm"] = row["skimage_coverage_1mm"]
            results["centerline.raw.skimage.cta_aorta.time_s"] = sk_seconds
            log("raw CTA: VC %.3f s, reference within 1 mm %.3f; skimage %.3f s, %.3f" % (
                row["time_s"], row["coverage_1mm"], sk_seconds, row["skimage_coverage_1mm"]))
        else:
            truth = data["truth_points"]
            radius = data["truth_radius"]
            truth_lines = lines_of(data["truth_conn"], data["truth_offsets"])
            vc = cm.measure(points, lines, truth, radius, truth_lines, voxel)
            sk = cm.measure(data["origin"] + ijk * spacing, None, truth, radius, truth_lines,
                            voxel)
            row["vc"], row["skimage"] = vc, sk
            if tag == "large":
                results["centerline.raw.time_s"] = row["time_s"]
                # The filter's stage times (field data Candidate<Stage>Seconds), when it has them.
                for k, v in record.items():
                    if k.startswith("field.Candidate") and k.endswith("Seconds") and v:
                        stage = k[len("field.Candidate"):-len("Seconds")].lower()
                        results["centerline.raw.stage_%s_s" % stage] = v[0]
                results["centerline.raw.tubularity_s"] = record.get(
                    "field.CandidateTubularitySeconds", [math.nan])[0]
                results["centerline.raw.skimage.time_s"] = sk_seconds
                results["centerline.raw.large.voxels"] = float(np.prod(record["dimensions"]))
                for k in ("precision", "recall_r0.5_up", "recall_r1_up", "mean_dist_vox",
                          "false_vessel_points"):
                    results["centerline.raw.large.%s" % k] = vc[k]
            elif tag.startswith("shaded_"):
                per_case["shaded_vc"].append(vc)
                per_case["shaded_skimage"].append(sk)
                for k in AGGREGATE:
                    results["centerline.raw.shaded.case.%s.%s" % (tag, k)] = vc[k]
                    results["centerline.raw.skimage.shaded.case.%s.%s" % (tag, k)] = sk[k]
                results["centerline.raw.shaded.case.%s.corrected" % tag] = record.get(
                    "field.ShadingCorrected", [math.nan])[0]
            else:
                per_case["vc"].append(vc)
                per_case["skimage"].append(sk)
                for k in AGGREGATE:
                    results["centerline.raw.case.%s.%s" % (tag, k)] = vc[k]
                    results["centerline.raw.skimage.case.%s.%s" % (tag, k)] = sk[k]
                results["centerline.raw.case.%s.time_s" % tag] = row["time_s"]
                results["centerline.raw.skimage.case.%s.time_s" % tag] = sk_seconds
            log("raw %s: VC %.3f s precision %.3f recall r>=0.5 %.3f r>=1 %.3f mean %.3f vox, "
                "false %d | skimage %.3f s precision %.3f recall %.3f %.3f mean %.3f false %d" % (
                    tag, row["time_s"], vc["precision"], vc["recall_r0.5_up"], vc["recall_r1_up"],
                    vc["mean_dist_vox"], vc["false_vessel_points"], sk_seconds, sk["precision"],
                    sk["recall_r0.5_up"], sk["recall_r1_up"], sk["mean_dist_vox"],
                    sk["false_vessel_points"]))
        raw["cases"][tag] = row
        os.remove(os.path.join(workdir, tag + ".npz"))
    for who, prefix in (("vc", "centerline.raw."), ("skimage", "centerline.raw.skimage."),
                        ("shaded_vc", "centerline.raw.shaded."),
                        ("shaded_skimage", "centerline.raw.skimage.shaded.")):
        for k, fold in AGGREGATE.items():
            values = [c[k] for c in per_case[who] if not math.isnan(c[k])]
            results[prefix + k] = float(fold(values)) if values else math.nan
    results["centerline.raw.phantom_cases"] = len(per_case["vc"])
    results["centerline.raw.skimage.otsu_upper_cases"] = sum(
        1 for c in raw["cases"].values() if c["otsu_method"] == "otsu_upper")
    results["centerline.raw.automatic_range"] = int(
        all(raw["cases"][c["tag"]]["range_mode"] == "automatic" for c in cases))
    # Whole-volume vesselness on the CTA-sized phantom (the same spec as the timing case).
    tool = os.path.join(build, "Testing", "Benchmarks", "vesseltouch-whole-volume-vesselness")
    if not os.path.exists(tool):
        raise RuntimeError("missing %s (build with -DVESSELTOUCH_BUILD_BENCHMARKS=ON)" % tool)
    dims = timing_case(quick)["phantom"]["Dimensions"]
    out = subprocess.run([tool] + [str(d) for d in dims] + ["--seed", "1", "--noise", "20",
                                                            "--segments", "400"],
                         check=True, capture_output=True, text=True).stdout
    ves = json.loads(out.strip().splitlines()[-1])
    results["centerline.raw.vesselness_whole_volume_s"] = ves["seconds"]
    raw["vesselness_whole_volume"] = ves
    log("raw: whole-volume vesselness on %s: %.2f s (VesselCenterline %.2f s)" % (
        "x".join(map(str, dims)), ves["seconds"], results["centerline.raw.time_s"]))
    raw["aggregate"] = {k: v for k, v in results.items() if ".case." not in k}
    return results, raw
