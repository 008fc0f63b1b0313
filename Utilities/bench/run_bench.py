#!/usr/bin/python3
"""Runs every VesselTouch benchmark and writes <out>/results.json (flat keys, units in the names)
plus the raw data of each section (<out>/raw/*.json) for the charts. Called by Utilities/bench.sh.

    /usr/bin/python3 Utilities/bench/run_bench.py --build BUILD --out OUT [--quick]
        [--only centerline rawcenterline haptic force stability render gui scaling]

Sections (each in its own processes; a failed section is reported and its keys stay missing, so
check_results.py fails):
  centerline  voxel coding (vesseltouch-centerline-sweep) and scikit-image skeletonize_3d (through
              Utilities/skeleton_benchmark.py's --skimage-child) on the helix and tree phantoms and
              the VMTK aorta; size scaling; sweeps of smoothing window, spur pruning, downsampling
              (when the filter has DownsampleFactor), vesselness on noisy raw intensities.
  rawcenterline  VesselCenterline from one seed on raw angiograms (the RawAngiogram phantom family,
              the raw VMTK CTA, a CTA-sized volume) beside scikit-image on an Otsu mask, and
              whole-volume vesselness time (Utilities/bench/raw_centerline_bench.py)
  haptic      vesseltouch-loop-timing --json at 1, 2, 5, 10 kHz with and without a render load;
              vtouchHapticsBenchmark's tick benchmarks (1 M-point scene).
  force       vesseltouch-force-sweep (force error against loop rate, tick cost).
  stability   vesseltouch-stability-map (coupler k_c, LDGF lambda, force interpolation).
  render      Testing/Benchmarks/agent_framerate.py under pvpython and Xvfb.
  gui         Testing/ParaView/gui/bench_camera_drag.py: the haptic loop's period error while the
              camera is dragged in the real ParaView GUI under Xvfb, against an idle phase.
  scaling     the volume on a 1-, 2- and 4-rank pvserver, the session in the client
              (Utilities/bench/scaling_bench.py): time per stage, peak memory per rank, bytes to
              the client, the client's haptic p99 while the server renders.
--quick: smaller volumes, fewer points and shorter runs; every key is still written (the
centerline.helix384/tree384 keys then come from the largest quick size) and meta.quick is 1.
"""
import argparse
import json
import math
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.dont_write_bytecode = True  # no __pycache__ beside the sources
sys.path.insert(0, os.path.join(ROOT, "Utilities"))
sys.path.insert(0, HERE)
import skeleton_benchmark as sb  # noqa: E402  (accuracy, VTP reader, aorta frame, skimage child)

SECTIONS = ("centerline", "rawcenterline", "haptic", "force", "stability", "render", "gui",
            "scaling")


def log(*words):
    print("[bench %6.1f s]" % (time.time() - START), *words, flush=True)


def exe(build, *parts):
    path = os.path.join(build, *parts)
    if not os.path.exists(path):
        raise RuntimeError("missing %s (build with -DVESSELTOUCH_BUILD_BENCHMARKS=ON)" % path)
    return path


def run_json_line(cmd):
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


# ------------------------------------------------------------------------------------------------
# Centerlines
# ------------------------------------------------------------------------------------------------
def centerline_case(build, source, workdir, options=(), skimage=True):
    """source: ("phantom", shape, n) or ("aorta",). Returns a flat dict of this run."""
    os.makedirs(workdir, exist_ok=True)
    tool = exe(build, "Testing", "Benchmarks", "vesseltouch-centerline-sweep")
    if source[0] == "phantom":
        n = str(source[2])
        args = ["phantom", source[1], n, n, n]
        to_reference, cover_mm, reference = None, 1.5, None
    else:
        args = ["image", os.path.join(sb.DATA, "aorta-final-levelset.mha"), "-1e30", "-1e-9"]
        reference = sb.read_vtp_points(os.path.join(sb.DATA, "aorta-centerline.vtp"))
        to_reference, cover_mm = sb.aorta_frame, 1.0
    opts = list(options) + ([] if skimage else ["--no-mask"])
    vc = run_json_line([tool] + opts + args + [workdir])
    if reference is None:
        reference = np.loadtxt(os.path.join(workdir, "analytic.csv"), delimiter=",")[:, :3]
    pts = np.loadtxt(os.path.join(workdir, "voxelcoding.csv"), delimiter=",", ndmin=2)
    pts = pts[:, :3] if pts.size else np.zeros((0, 3))
    mapped = to_reference(pts, world=True) if to_reference else pts
    mean, p95, cover = sb.accuracy(mapped, reference, cover_mm)
    row = {"seconds": vc["seconds"], "peak_mb": vc["extra_rss_bytes"] / 2**20,
           "mean_dist_vox": mean, "p95_dist_vox": p95, "coverage": cover,
           "vessel_voxels": vc["vessel_voxels"], "volume_voxels": vc["nx"] * vc["ny"] * vc["nz"],
           "paths": vc["paths"], "factor": vc.get("downsample", 1),
           "coded_voxels": vc.get("coded_voxels", vc["vessel_voxels"])}
    if skimage:
        out = os.path.join(workdir, "skimage.npy")
        child = subprocess.run([sys.executable, sb.__file__, "--skimage-child",
                                os.path.join(workdir, "mask.raw"), str(vc["nx"]), str(vc["ny"]),
                                str(vc["nz"]), out], check=True, capture_output=True, text=True)
        sk = json.loads(child.stdout.strip().splitlines()[-1])
        ijk = np.load(out).astype(float)
        sk_pts = to_reference(ijk, world=False) if to_reference else ijk
        smean, sp95, scover = sb.accuracy(sk_pts, reference, cover_mm)
        row.update(skimage_seconds=sk["seconds"], skimage_peak_mb=sk["extra_rss_bytes"] / 2**20,
                   skimage_mean_dist_vox=smean, skimage_p95_dist_vox=sp95,
                   skimage_coverage=scover)
    for name in ("mask.raw", "skimage.npy"):
        if os.path.exists(os.path.join(workdir, name)):
            os.remove(os.path.join(workdir, name))
    return row


def value_tag(v):
    return ("m" if v < 0 else "") + ("%g" % abs(v)).replace(".", "p")


def section_centerline(build, quick, tmp):
    results, raw = {}, {"scaling": {}, "sweeps": {}}
    sizes = [32, 48, 64] if quick else [64, 96, 128, 192, 256, 384]
    for shape in ("Helix", "Tree"):
        rows = []
        for n in sizes:
            row = centerline_case(build, ("phantom", shape, n), os.path.join(tmp, "%s%d" % (shape, n)))
            row["size_vox"] = n
            # Full resolution beside the default (which picks a coarse scale for large masks of
            # thick vessels): the chart shows both.
            full = row if row["factor"] == 1 else centerline_case(
                build, ("phantom", shape, n), os.path.join(tmp, "%s%d-full" % (shape, n)),
                ["--downsample", "1"], skimage=False)
            row["full_resolution_seconds"] = full["seconds"]
            row["full_resolution_peak_mb"] = full["peak_mb"]
            rows.append(row)
            log("centerline %s %d: VC %.3f s, skimage %.3f s" % (shape, n, row["seconds"],
                                                                    row["skimage_seconds"]))
            for k, v in row.items():
                results["centerline.scaling.%s%d.%s" % (shape.lower(), n, k)] = v
        raw["scaling"][shape.lower()] = rows
        top = rows[-1]
        for k, v in top.items():
            results["centerline.%s384.%s" % (shape.lower(), k)] = v
        # The same volume coded at full resolution (DownsampleFactor 1), beside the default's
        # automatic scale: what the coarse-to-fine refinement buys and costs.
        full = top if top["factor"] == 1 else centerline_case(
            build, ("phantom", shape, sizes[-1]), os.path.join(tmp, "%s-full" % shape),
            ["--downsample", "1"], skimage=False)
        log("centerline %s %d full resolution: VC %.3f s (default: factor %d, %.3f s)" % (
            shape, sizes[-1], full["seconds"], top["factor"], top["seconds"]))
        for k in ("seconds", "peak_mb", "mean_dist_vox", "p95_dist_vox", "coverage"):
            results["centerline.%s384.full_resolution_%s" % (shape.lower(), k)] = full[k]
        for who, tkey, mkey in (("vc", "seconds", "peak_mb"),
                                ("skimage", "skimage_seconds", "skimage_peak_mb")):
            vox = np.array([r["volume_voxels"] for r in rows], float)
            t = np.array([r[tkey] for r in rows], float)
            m = np.array([max(r[mkey], 1e-3) for r in rows], float)
            big = vox >= vox[len(vox) // 2]  # fit the larger half (small runs are overhead-bound)
            results["centerline.scaling.%s.%s_time_slope" % (shape.lower(), who)] = float(
                np.polyfit(np.log(vox[big]), np.log(np.maximum(t[big], 1e-6)), 1)[0])
            results["centerline.scaling.%s.%s_memory_slope" % (shape.lower(), who)] = float(
                np.polyfit(np.log(vox[big]), np.log(m[big]), 1)[0])
    aorta = centerline_case(build, ("aorta",), os.path.join(tmp, "aorta"))
    log("centerline aorta: VC %.3f s, skimage %.3f s" % (aorta["seconds"], aorta["skimage_seconds"]))
    for k, v in aorta.items():
        results["centerline.aorta.%s" % k] = v
    raw["aorta"] = aorta

    # Parameter sweeps: the filter's parameters that exist now (no downsampling parameter yet).
    n = 48 if quick else 192
    smoothing = [-1, 0, 2] if quick else [-1, 0, 0.5, 1, 2, 4]
    branch = [0, 2.5, 10] if quick else [0, 1, 2.5, 5, 10]
    downsample = [1, 2] if quick else [1, 2, 3, 4]
    inputs = [("helix", ("phantom", "Helix", n)), ("tree", ("phantom", "Tree", n)),
              ("aorta", ("aorta",))]
    params = [("smoothing_mm", "--smoothing-mm", smoothing), ("min_branch", "--min-branch", branch)]
    try:  # DownsampleFactor exists only in newer filters: sweep it when the tool accepts it
        centerline_case(build, ("phantom", "Helix", 32), os.path.join(tmp, "probe"),
                        ["--downsample", "2"], skimage=False)
        params.append(("downsample", "--downsample", downsample))
    except subprocess.CalledProcessError:
        log("centerline: the filter has no DownsampleFactor; not swept")
    results["centerline.sweep.downsample_swept"] = int(params[-1][0] == "downsample")
    for name, source in inputs:
        sweeps = {}
        for param, flag, values in params:
            rows = []
            for v in values:
                try:
                    row = centerline_case(build, source, os.path.join(tmp, "sw-%s" % name),
                                          [flag, str(v)], skimage=False)
                except subprocess.CalledProcessError as e:
                    # e.g. a coarse DownsampleFactor leaves no component big enough: no centerline
                    log("centerline %s %s=%g: no result (%s)" % (
                        name, param, v, (e.stderr or "").strip().splitlines()[-1:]))
                    row = {k: math.nan for k in ("seconds", "peak_mb", "mean_dist_vox",
                                                 "p95_dist_vox", "coverage")}
                row["value"] = v
                rows.append(row)
                for k in ("seconds", "peak_mb", "mean_dist_vox", "p95_dist_vox", "coverage"):
                    results["centerline.sweep.%s.%s_%s.%s" % (name, param, value_tag(v), k)] = row[k]
            sweeps[param] = rows
        raw["sweeps"][name] = sweeps
        log("centerline sweeps %s done" % name)
    # Vesselness on raw intensities: noisy phantoms thresholded at the wall, without and with the
    # Hessian test (noise standard deviation 150 on a 100..1000 scale: the wall is 3 sigma above
    # the background).
    nv = 40 if quick else 128
    raw["vesselness"] = {}
    for shape in ("Helix", "Tree"):
        rows = []
        for on in (False, True):
            opts = ["--noise", "150"] + (["--vesselness"] if on else [])
            row = centerline_case(build, ("phantom", shape, nv),
                                  os.path.join(tmp, "ves-%s" % shape), opts, skimage=False)
            row["vesselness"] = int(on)
            rows.append(row)
            for k in ("seconds", "peak_mb", "mean_dist_vox", "p95_dist_vox", "coverage"):
                results["centerline.vesselness.%s_noisy.%s.%s" % (
                    shape.lower(), "on" if on else "off", k)] = row[k]
        raw["vesselness"][shape.lower()] = rows
        log("centerline vesselness %s: off %.3f s, on %.3f s" % (shape, rows[0]["seconds"],
                                                                 rows[1]["seconds"]))
    return results, raw


def section_rawcenterline(build, quick, tmp):
    import raw_centerline_bench  # noqa: E402  (beside this file)

    return raw_centerline_bench.run(build, quick, tmp, log)


# ------------------------------------------------------------------------------------------------
# Haptics
# ------------------------------------------------------------------------------------------------
def section_haptic(build, quick, tmp):
    results, raw = {}, {}
    tool = exe(build, "Testing", "Logic", "Haptics", "vesseltouch-loop-timing")
    seconds = "0.5" if quick else "3"
    for render in (False, True):
        out = os.path.join(tmp, "loop%s.json" % ("_render" if render else ""))
        cmd = [tool, "--seconds", seconds, "--rates", "1000,2000,5000,10000", "--json", out]
        text = subprocess.run(cmd + (["--render"] if render else []), check=True,
                              capture_output=True, text=True).stdout
        log("loop timing%s:\n%s" % (" +render" if render else "", text.rstrip()))
        data = json.load(open(out))
        raw.update(data)
        results.update({k: v for k, v in data.items() if not isinstance(v, list)})
    # haptic.tick_median_ns is the measure: one session tick on the 1 M-point skeleton
    # (Google Benchmark, warm caches). The real-time loop's own tick cost, which adds the device
    # write and cold caches after each sleep, stays under haptic.loop_<rate>hz.tick_median_ns.
    results["haptic.tick_median_ns"] = results["haptic.loop_1000hz.tick_median_ns"]
    bench = os.path.join(build, "Testing", "Logic", "Haptics", "vtouchHapticsBenchmark")
    if os.path.exists(bench):
        out = os.path.join(tmp, "gbench.json")
        subprocess.run([bench, "--benchmark_filter=Tick", "--benchmark_out=" + out,
                        "--benchmark_out_format=json",
                        "--benchmark_min_time=%s" % ("0.05" if quick else "0.5"),
                        "--benchmark_repetitions=%d" % (3 if quick else 5),
                        "--benchmark_report_aggregates_only=true"],
                       check=True, capture_output=True, text=True)
        laws = {"0": "ldgf", "1": "change_of_height", "2": "lateral_gradient",
                "3": "constraint_proxy"}
        for b in json.load(open(out))["benchmarks"]:
            if b.get("aggregate_name", "median") != "median":
                continue  # keep the median over the repetitions
            name = b.get("run_name", b["name"])
            ns = b["real_time"] * {"ns": 1, "us": 1e3, "ms": 1e6}[b["time_unit"]]
            if name.startswith("BM_PipelineTick_1M/"):
                results["haptic.pipeline_tick_1m.%s_ns" % laws[name.split("/")[1]]] = ns
            elif name.startswith("BM_SessionTick_1M"):
                results["haptic.session_tick_1m_ns"] = ns
                results["haptic.tick_median_ns"] = ns
    return results, raw


def section_force(build, quick, tmp):
    tool = exe(build, "Testing", "Benchmarks", "vesseltouch-force-sweep")
    cmd = [tool, "--seconds", "1.2" if quick else "3"]
    if quick:
        cmd += ["--rates", "250,1000,4000,10000", "--reference-rate", "20000"]
    data = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
    # The surface stimulus traces (lists) are chart data, not results.
    return {k: v for k, v in data.items() if not isinstance(v, list)}, data


def section_stability(build, quick, tmp):
    tool = exe(build, "Testing", "Benchmarks", "vesseltouch-stability-map")
    cmd = [tool] + (["--points", "5", "--rates", "250,1000,4000", "--seconds", "1.0"] if quick
                    else ["--points", "13", "--seconds", "1.5"])
    data = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
    results = {}
    for name in ("coupler_kc_n_per_m", "ldgf_lambda_mm", "interpolation_n_per_s"):
        values = data["stability.%s.values" % name]
        rates = data["stability.%s.rates_hz" % name]
        stable = np.array(data["stability.%s.stable" % name]).reshape(len(rates), len(values))
        default = data["stability.%s.default" % name]
        results["stability.%s.default" % name] = default
        results["stability.%s.stable_fraction" % name] = float(stable.mean())
        for i, rate in enumerate(rates):
            ok = [v for v, s in zip(values, stable[i]) if s]
            # coupler: the stiffest stable k_c; cusp maps: the whole stable range
            results["stability.%s.%.0fhz.min_stable" % (name, rate)] = min(ok) if ok else math.nan
            results["stability.%s.%.0fhz.max_stable" % (name, rate)] = max(ok) if ok else math.nan
    return results, data


def section_render(build, quick, tmp):
    plugin = exe(build, "lib", "paraview-5.11", "plugins", "VesselTouch", "VesselTouch.so")
    out = os.path.join(tmp, "render.json")
    sizes = ["64x64x64", "128x128x128"] if quick else ["128x128x128", "192x192x192",
                                                       "256x256x256", "360x330x420"]
    cmd = [os.path.join(ROOT, "Testing", "Utilities", "vtouch-xvfb-run"), "pvpython",
           os.path.join(ROOT, "Testing", "Benchmarks", "agent_framerate.py"), "--plugin", plugin,
           "--json", out, "--sizes"] + sizes
    if quick:
        cmd += ["--rounds", "1", "--cached-frames", "20", "--full-frames", "2"]
    text = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    log("render:\n" + text.rstrip())
    data = json.load(open(out))
    data["render.sizes"] = sizes
    return {k: v for k, v in data.items() if isinstance(v, (int, float))}, data


def section_gui(build, quick, tmp):
    """The haptic loop while the user drags the camera in the real ParaView GUI (issue 20)."""
    out = os.path.join(tmp, "gui_drag.json")
    env = dict(os.environ)
    env.update({"VESSELTOUCH_PARAVIEW": shutil.which("paraview") or "paraview",
                "VESSELTOUCH_PLUGIN_DIR": exe(build, "lib", "paraview-5.11", "plugins",
                                              "VesselTouch"),
                # The tests' command driver (not in the product plugin: Testing/ParaView/driver).
                "VESSELTOUCH_TEST_DRIVER_DIR": exe(build, "lib", "paraview-5.11", "plugins",
                                                   "VesselTouchTestDriver"),
                "VESSELTOUCH_BINARY_DIR": os.path.join(tmp, "gui")})
    cmd = [os.path.join(ROOT, "Testing", "Utilities", "vtouch-xvfb-run"), "/usr/bin/python3",
           os.path.join(ROOT, "Testing", "ParaView", "gui", "bench_camera_drag.py"),
           "--json", out, "--seconds", "2" if quick else "6"]
    text = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env).stdout
    log("gui camera drag:\n" + text.rstrip())
    data = json.load(open(out))
    return {k: v for k, v in data.items() if isinstance(v, (int, float))}, data


def section_scaling(build, quick, tmp):
    """Client/server: the volume on 1, 2, 4 pvserver ranks, the session in the client (issue 19)."""
    import scaling_bench  # noqa: E402  (beside this file)

    return scaling_bench.run(build, quick, tmp, log)


# ------------------------------------------------------------------------------------------------
def meta(quick):
    def git(*args):
        try:
            return subprocess.run(["git", "-C", ROOT] + list(args), capture_output=True,
                                  text=True, check=True).stdout.strip()
        except (OSError, subprocess.CalledProcessError):
            return "unknown"
    cpu = "unknown cpu"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    dirty = git("status", "--porcelain", "--untracked-files=no")
    return {"meta.commit": git("rev-parse", "--short", "HEAD") + ("+dirty" if dirty else ""),
            "meta.machine": "%s, %s, %d cpu(s), %.1f GB, %s" % (
                platform.node(), cpu, os.cpu_count() or 0,
                os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30,
                platform.platform()),
            "meta.date": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
            "meta.quick": 1 if quick else 0,
            "meta.load_average_1min": os.getloadavg()[0]}


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--only", nargs="+", choices=SECTIONS, default=list(SECTIONS))
    args = parser.parse_args()
    os.makedirs(os.path.join(args.out, "raw"), exist_ok=True)
    results = meta(args.quick)
    failed = []
    with tempfile.TemporaryDirectory(prefix="vtouch-bench-") as tmp:
        for name in args.only:
            t0 = time.time()
            log("section", name)
            try:
                flat, raw = globals()["section_" + name](args.build, args.quick, tmp)
            except Exception as e:  # noqa: BLE001  (report and go on with the other sections)
                detail = getattr(e, "stderr", "") or ""
                log("section %s FAILED: %s %s" % (name, e, detail[-2000:]))
                failed.append(name)
                continue
            results.update(flat)
            results["meta.%s_seconds" % name] = time.time() - t0
            with open(os.path.join(args.out, "raw", name + ".json"), "w") as f:
                json.dump(raw, f, indent=1, sort_keys=True, default=float)
    results["meta.total_seconds"] = time.time() - START
    path = os.path.join(args.out, "results.json")
    previous = {}
    if set(args.only) != set(SECTIONS) and os.path.exists(path):
        previous = json.load(open(path))  # --only: update the sections that ran
    previous.update(results)
    with open(path, "w") as f:
        json.dump(previous, f, indent=1, sort_keys=True)
    log("wrote %s (%d keys)%s" % (path, len(previous),
                                   ", FAILED sections: " + " ".join(failed) if failed else ""))
    return 1 if failed else 0


START = time.time()
if __name__ == "__main__":
    sys.exit(main())
