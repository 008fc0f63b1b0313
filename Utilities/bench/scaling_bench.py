"""Section "scaling" of Utilities/bench/run_bench.py (issue 19, item 4): the volume on a 1-, 2- and
4-rank pvserver, the haptic session in the client.

For each volume size a vessel tree is written as a raw NRRD (uint16, so that VesselTouch's reader
reads each rank's piece alone: Docs/READERS.md), then Testing/Benchmarks/scaling_client.py runs
once per rank count under vtouch-xvfb-run and measures, from the client: the read, VesselCenterline
in the pipeline (reader already updated) and the filter's own stage times, the delivery of the
skeleton to the client and its bytes, each rank's peak resident memory (VmHWM), and the client's
haptic loop (p99 period error) idle and while the server renders the MIP.

Configurations ("runs"): r1 (one rank), r<N> (N ranks, VesselCenterline's default: the first rank
codes the whole volume) and r<N>d (N ranks, DistributedExtraction on: each rank codes its piece),
side by side. Full: 256^3, 512 x 512 x 256 and 1024 x 1024 x 512, runs r1 r2 r2d r4 r4d; --quick:
96 x 96 x 64, runs r1 r2d. On 2 cores 4 ranks oversubscribe: their times show contention, their
memory is the measure (Docs/SCALING.md).

Keys (flat): scaling.<X>x<Y>x<Z>.<run>.<measure> with every measure scaling_client.py writes
(read_s, centerline_s, stage_<stage>_s, deliver_s, bytes_to_client, peak_rss_mib_max,
peak_rss_mib.rank<r>, haptic.{idle,render}.period_error_p99_us, and for the distributed runs
where centerline_s goes: centerline_before_request_s, centerline_request_to_exit_s,
centerline_after_request_data_s, stage_pieceUpstream_s, stage_pieceReader_s,
stage_pieceGatherWait_s, ... per rank as .rank<r>; Docs/SCALING.md), plus
scaling.<size>.memory_ratio_<run> = peak_rss_mib_max of the run / of r1, and scaling.largest.*
copies of the largest size's keys (the quick and full runs then share names).
"""
import json
import math
import os
import subprocess
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))

BACKGROUND = 100
VESSEL = 1000


def tree_segments(dims, seed=7):
    """A bifurcating tree filling the box, in voxel coordinates: (points (n x 3), radius) per
    segment. The trunk runs corner to corner, so every piece boundary of a block split is crossed;
    branches leave in all directions; radii follow Murray's law (r_child = r / 2^(1/3)) from a
    trunk of 1/40 of the smallest side down to 1.5 voxels (the thresholded path's vessels)."""
    rng = np.random.default_rng(seed)
    d = np.array(dims, dtype=float)
    r0 = max(2.5, min(dims) / 40.0)
    segments = []

    def curve(a, b, bend):
        t = np.linspace(0.0, 1.0, max(2, int(np.linalg.norm(b - a) * 2)))[:, None]
        mid = (a + b) / 2 + bend
        return (1 - t) ** 2 * a + 2 * (1 - t) * t * mid + t ** 2 * b

    def grow(a, direction, length, radius, depth):
        b = np.clip(a + direction * length, 2 + radius, d - 3 - radius)
        if np.linalg.norm(b - a) < 4 * radius:
            return
        bend = rng.normal(0.0, 0.15 * length, 3)
        points = curve(a, b, bend)
        segments.append((points, radius))
        if depth == 0 or radius / 2 ** (1 / 3) < 1.5:
            return
        for _ in range(2):
            axis = rng.normal(size=3)
            axis /= np.linalg.norm(axis)
            grow(points[-1], axis, length * 0.7, radius / 2 ** (1 / 3), depth - 1)

    start = d * 0.12
    direction = (d * 0.88 - start)
    length = np.linalg.norm(direction) * 0.55
    grow(start, direction / np.linalg.norm(direction), length, r0, 5)
    return segments


def write_tree_nrrd(path, dims):
    """Writes the tree as uint16 raw NRRD (x fastest): background 100, vessels 1000 with a linear
    partial-volume ramp over the last voxel of the wall. Returns the number of vessel voxels."""
    X, Y, Z = dims
    volume = np.full((Z, Y, X), BACKGROUND, dtype=np.uint16)
    for points, radius in tree_segments(dims):
        reach = int(math.ceil(radius + 1))
        for p in points[::1]:
            lo = np.maximum(np.floor(p).astype(int) - reach, 0)
            hi = np.minimum(np.floor(p).astype(int) + reach + 2, [X, Y, Z])
            if np.any(hi <= lo):
                continue
            z, y, x = np.ogrid[lo[2]:hi[2], lo[1]:hi[1], lo[0]:hi[0]]
            dist = np.sqrt((x - p[0]) ** 2 + (y - p[1]) ** 2 + (z - p[2]) ** 2)
            value = (BACKGROUND + (VESSEL - BACKGROUND) * np.clip(radius + 0.5 - dist, 0, 1))
            box = volume[lo[2]:hi[2], lo[1]:hi[1], lo[0]:hi[0]]
            np.maximum(box, value.astype(np.uint16), out=box)
    with open(path, "wb") as f:
        f.write(("NRRD0004\ntype: uint16\ndimension: 3\nsizes: %d %d %d\nspacings: 1 1 1\n"
                 "encoding: raw\nendian: little\n\n" % (X, Y, Z)).encode())
        volume.tofile(f)
    return int((volume >= (BACKGROUND + VESSEL) // 2).sum())


def run(build, quick, tmp, log):
    plugin = os.path.join(build, "lib", "paraview-5.11", "plugins", "VesselTouch", "VesselTouch.so")
    if not os.path.exists(plugin):
        raise RuntimeError("missing " + plugin)
    sizes = [(96, 96, 64)] if quick else [(256, 256, 256), (512, 512, 256), (1024, 1024, 512)]
    runs = [(1, False), (2, True)] if quick else [(1, False), (2, False), (2, True), (4, False),
                                                   (4, True)]
    results, raw = {}, {"sizes": [], "runs": ["r%d%s" % (n, "d" if d else "") for n, d in runs]}
    for dims in sizes:
        tag = "%dx%dx%d" % dims
        path = os.path.join(tmp, "scaling_%s.nrrd" % tag)
        t = time.time()
        vessel_voxels = write_tree_nrrd(path, dims)
        log("scaling: wrote %s (%d vessel voxels) in %.1f s" % (tag, vessel_voxels, time.time() - t))
        results["scaling.%s.vessel_voxels" % tag] = vessel_voxels
        raw["sizes"].append(tag)
        for n, distributed in runs:
            run_name = "r%d%s" % (n, "d" if distributed else "")
            out = os.path.join(tmp, "scaling_%s_%s.json" % (tag, run_name))
            cmd = [os.path.join(ROOT, "Testing", "Utilities", "vtouch-xvfb-run"), "pvpython",
                   os.path.join(ROOT, "Testing", "Benchmarks", "scaling_client.py"),
                   "--plugin", plugin, "--volume", path, "--ranks", str(n), "--json", out,
                   "--seconds", "1.5" if quick else "4"] + (["--distributed"] if distributed
                                                             else [])
            t = time.time()
            done = subprocess.run(cmd, capture_output=True, text=True, timeout=1800)
            data = json.load(open(out)) if os.path.exists(out) else {}
            if done.returncode != 0 or "error" in data:
                raise RuntimeError("scaling %s %s failed: %s\n%s" % (
                    tag, run_name, data.get("error"), (done.stdout + done.stderr)[-3000:]))
            log("scaling: %s %s: centerline %.2f s, peak rank %.0f MiB, %d bytes to the "
                "client, haptic p99 idle %.0f us / render %.0f us (%.0f s)"
                % (tag, run_name, data["centerline_s"], data["peak_rss_mib_max"],
                   data["bytes_to_client"],
                   data["haptic.idle.period_error_p99_us"],
                   data["haptic.render.period_error_p99_us"], time.time() - t))
            if distributed:
                log("scaling: %s %s: centerline %.2f s = before the request %.2f + request to "
                    "rank 0's exit %.2f + after %.2f; slowest rank: upstream (reader %.2f) %.2f, "
                    "extraction %.2f, gather wait %.2f"
                    % (tag, run_name, data["centerline_s"],
                       data.get("centerline_before_request_s", math.nan),
                       data.get("centerline_request_to_exit_s", math.nan),
                       data.get("centerline_after_request_data_s", math.nan),
                       data.get("stage_pieceReader_s", math.nan),
                       data.get("stage_pieceUpstream_s", math.nan),
                       data.get("stage_pieceExtract_s", math.nan),
                       data.get("stage_pieceGatherWait_s", math.nan)))
            raw["%s.%s" % (tag, run_name)] = data
            for key, value in data.items():
                if isinstance(value, (int, float)) and not isinstance(value, bool):
                    results["scaling.%s.%s.%s" % (tag, run_name, key)] = value
        base = results["scaling.%s.r1.peak_rss_mib_max" % tag]
        for run_name in raw["runs"][1:]:
            results["scaling.%s.memory_ratio_%s" % (tag, run_name)] = (
                results["scaling.%s.%s.peak_rss_mib_max" % (tag, run_name)] / base)
    largest = "%dx%dx%d" % sizes[-1]
    for key, value in list(results.items()):
        if key.startswith("scaling.%s." % largest):
            results["scaling.largest." + key[len("scaling.%s." % largest):]] = value
    return results, raw
