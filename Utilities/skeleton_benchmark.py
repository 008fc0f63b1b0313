#!/usr/bin/python3
"""Side-by-side benchmark: VesselTouch voxel coding (C++) vs scikit-image skeletonize_3d.

Runs both on the same volumes (the C++ side writes the vessel mask it used; scikit-image reads it),
measures wall time and peak extra resident memory of each in its own process, and the accuracy of
both against the analytic centerline (phantoms) or VMTK's reference centerline (aorta).

    /usr/bin/python3 Utilities/skeleton_benchmark.py --build /work/build-skeleton \
        [--sizes 64 128 256 384] [--markdown table.md] [--json results.json]

--json writes one flat record per input: case, dims, vessel_voxels, seconds, peak_mb,
mean_dist_vox, p95_dist_vox, coverage and the skimage_ equivalents (skimage_seconds,
skimage_peak_mb, skimage_mean_dist_vox, skimage_coverage), plus budget_mb and speedup
(aorta distances in mm), downsample (the factor asked for, "auto" = the filter's default) and
factor (the one used). --downsample F sets the filter's DownsampleFactor (1 = full resolution).

Memory: peak RSS during the skeletonization minus the RSS just before it (the input volume is
not counted), read from /proc (VmHWM after resetting it through /proc/self/clear_refs).
"""
import argparse
import base64
import json
import os
import resource  # noqa: F401  (kept for platforms without clear_refs)
import subprocess
import sys
import tempfile
import time
import zlib

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "shared", "data", "vmtk-aorta")


def status_kb(key):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(key):
                return int(line.split()[1])
    return -1


def skimage_child(mask_path, nx, ny, nz, out_path):
    """Runs in its own process: load the mask, skeletonize, report time and memory."""
    from skimage.morphology import skeletonize_3d

    mask = np.fromfile(mask_path, dtype=np.uint8).reshape(nz, ny, nx)
    base = status_kb("VmRSS:")
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")
    t0 = time.perf_counter()
    skel = skeletonize_3d(mask)
    seconds = time.perf_counter() - t0
    peak = status_kb("VmHWM:")
    kji = np.argwhere(skel > 0)
    np.save(out_path, kji[:, ::-1].astype(np.int32))  # (i, j, k)
    print(json.dumps({"seconds": seconds, "extra_rss_bytes": (peak - base) * 1024,
                      "points": int(len(kji))}))


def read_vtp_points(path):
    """Points of a VTK XML PolyData written with zlib-compressed inline binary arrays."""
    text = open(path).read()
    start = text.index('Name="Points"')
    body = text[text.index(">", start) + 1:text.index("</DataArray>", start)].strip()
    header = base64.b64decode(body[:24])
    blocks, _, _ = np.frombuffer(header[:12], dtype=np.uint32)
    hlen = 4 * (3 + blocks)
    hchars = ((hlen + 2) // 3) * 4
    header = np.frombuffer(base64.b64decode(body[:hchars]), dtype=np.uint32)
    data = base64.b64decode(body[hchars:])
    out, off = b"", 0
    for size in header[3:3 + blocks]:
        out += zlib.decompress(data[off:off + int(size)])
        off += int(size)
    return np.frombuffer(out, dtype=np.float32).reshape(-1, 3).astype(float)


def accuracy(points_mm, reference_mm, cover_mm):
    from scipy.spatial import cKDTree

    if len(points_mm) == 0:
        return float("nan"), float("nan"), 0.0
    d_out, _ = cKDTree(reference_mm).query(points_mm)
    d_ref, _ = cKDTree(points_mm).query(reference_mm)
    return float(np.mean(d_out)), float(np.percentile(d_out, 95)), float(np.mean(d_ref <= cover_mm))


def run_case(build, name, args, workdir, reference=None, to_reference=None, cover_mm=1.5,
             voxel_mm=1.0, skip_skimage=False, downsample=None):
    exe = os.path.join(build, "Testing", "Logic", "Skeleton", "vtouchSkeletonBenchmark")
    os.makedirs(workdir, exist_ok=True)
    extra = [str(downsample)] if downsample is not None else []
    vc = json.loads(subprocess.run([exe] + args + [workdir] + extra, check=True,
                                   capture_output=True, text=True).stdout.strip().splitlines()[-1])
    nx, ny, nz = vc["nx"], vc["ny"], vc["nz"]
    # x, y, z (mm), then radius (mm) and path id
    vc_pts = np.loadtxt(os.path.join(workdir, "voxelcoding.csv"), delimiter=",", ndmin=2)[:, :3]
    if reference is None:
        reference = np.loadtxt(os.path.join(workdir, "analytic.csv"), delimiter=",")[:, :3]
    row = {"case": name, "dims": f"{nx}x{ny}x{nz}", "vessel_voxels": vc["vessel_voxels"],
           "downsample": "auto" if downsample is None else downsample,
           "factor": vc.get("factor", 1),
           "vc_s": vc["seconds"], "vc_mb": vc["extra_rss_bytes"] / 2**20,
           "budget_mb": (nx * ny * nz * 2 / 8 + 24 * vc["vessel_voxels"]) / 2**20}
    mapped = to_reference(vc_pts, world=True) if to_reference else vc_pts
    row["vc_mean_vox"], row["vc_p95_vox"], row["vc_cover"] = accuracy(mapped, reference, cover_mm)
    row["vc_mean_vox"] /= voxel_mm
    row["vc_p95_vox"] /= voxel_mm
    if skip_skimage:
        row.update(sk_s=float("nan"), sk_mb=float("nan"), sk_mean_vox=float("nan"),
                   sk_cover=float("nan"))
        return row
    sk_out = os.path.join(workdir, "skimage.npy")
    child = subprocess.run([sys.executable, os.path.abspath(__file__), "--skimage-child",
                            os.path.join(workdir, "mask.raw"), str(nx), str(ny), str(nz), sk_out],
                           check=True, capture_output=True, text=True)
    sk = json.loads(child.stdout.strip().splitlines()[-1])
    ijk = np.load(sk_out).astype(float)
    sk_pts = to_reference(ijk, world=False) if to_reference else ijk
    row.update(sk_s=sk["seconds"], sk_mb=sk["extra_rss_bytes"] / 2**20)
    row["sk_mean_vox"], _, row["sk_cover"] = accuracy(sk_pts, reference, cover_mm)
    row["sk_mean_vox"] /= voxel_mm
    return row


def aorta_frame(points, world):
    """To VMTK's frame (see ../shared/data/README.md): from world (direction -1,-1,1) or index."""
    if world:
        return points * np.array([-1.0, -1.0, 1.0])
    return np.array([156.445, 24.6094, 0.0]) + points * np.array([0.878906, 0.878906, 1.50009])


def table(rows):
    head = ("| case | volume | vessel voxels | factor | voxel coding s | skimage s | speed-up | "
            "VC extra MB | skimage extra MB | budget MB | VC mean dist | VC p95 dist | VC coverage | "
            "skimage mean dist | skimage coverage |")
    lines = [head, "|" + "---|" * 15]
    for r in rows:
        speed = r["sk_s"] / r["vc_s"] if r["vc_s"] > 0 else float("nan")
        lines.append(
            f"| {r['case']} | {r['dims']} | {r['vessel_voxels']} | {r.get('factor', 1)} | "
            f"{r['vc_s']:.3f} | "
            f"{r['sk_s']:.2f} | {speed:.1f}x | {r['vc_mb']:.1f} | {r['sk_mb']:.1f} | "
            f"{r['budget_mb']:.1f} | {r['vc_mean_vox']:.2f} | {r['vc_p95_vox']:.2f} | "
            f"{r['vc_cover']:.3f} | "
            f"{r['sk_mean_vox']:.2f} | {r['sk_cover']:.3f} |")
    return "\n".join(lines)


def flat_record(r):
    """The --json record of one table row (stable key names for other tools)."""
    speed = r["sk_s"] / r["vc_s"] if r["vc_s"] > 0 else float("nan")

    def num(x):
        return None if x != x else x  # NaN -> null (strict JSON)

    return {"case": r["case"], "dims": r["dims"], "vessel_voxels": int(r["vessel_voxels"]),
            "seconds": num(r["vc_s"]), "peak_mb": num(r["vc_mb"]),
            "mean_dist_vox": num(r["vc_mean_vox"]), "p95_dist_vox": num(r["vc_p95_vox"]),
            "coverage": num(r["vc_cover"]), "skimage_seconds": num(r["sk_s"]),
            "skimage_peak_mb": num(r["sk_mb"]), "skimage_mean_dist_vox": num(r["sk_mean_vox"]),
            "skimage_coverage": num(r["sk_cover"]), "budget_mb": num(r["budget_mb"]),
            "speedup": num(speed), "downsample": r.get("downsample", "auto"),
            "factor": r.get("factor", 1)}


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--skimage-child":
        skimage_child(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5]),
                      sys.argv[6])
        return
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", required=True, help="build folder with vtouchSkeletonBenchmark")
    parser.add_argument("--sizes", type=int, nargs="+", default=[64, 128, 256, 384])
    parser.add_argument("--no-angiogram", action="store_true", help="skip the 360x330x420 case")
    parser.add_argument("--markdown", help="also write the table to this file")
    parser.add_argument("--json", help="also write per-input flat results (a JSON list) here")
    parser.add_argument("--downsample", type=int, default=None,
                        help="the filter's DownsampleFactor for the voxel coding (default: the "
                        "filter's, 0 = automatic; 1 = full resolution). scikit-image always runs "
                        "at full resolution; vessel voxels are the full-resolution count")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory(prefix="vtouch-bench-") as tmp:
        for shape in ("Helix", "Tree"):
            for n in args.sizes:
                rows.append(run_case(args.build, f"{shape} {n}", ["phantom", shape, str(n), str(n),
                                     str(n)], os.path.join(tmp, f"{shape}{n}"),
                                     downsample=args.downsample))
                print(table(rows[-1:]).splitlines()[-1], flush=True)
        ref = read_vtp_points(os.path.join(DATA, "aorta-centerline.vtp"))
        rows.append(run_case(args.build, "aorta level set",
                             ["image", os.path.join(DATA, "aorta-final-levelset.mha"), "-1e30",
                              "-1e-9"], os.path.join(tmp, "aorta"), reference=ref,
                             to_reference=aorta_frame, cover_mm=1.0, voxel_mm=1.0,
                             downsample=args.downsample))
        print(table(rows[-1:]).splitlines()[-1], flush=True)
        if not args.no_angiogram:
            rows.append(run_case(args.build, "Tree (paper size)", ["phantom", "Tree", "360", "330",
                                 "420"], os.path.join(tmp, "angio"), downsample=args.downsample))
            print(table(rows[-1:]).splitlines()[-1], flush=True)
    text = table(rows)
    print()
    print(text)
    print("\nDistances in voxels (aorta: mm); coverage = fraction of reference points within 1.5 "
          "voxels (aorta: 1 mm) of the skeleton. Budget = 2 bits per volume voxel + 24 bytes per "
          "vessel voxel.")
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text + "\n")
    if args.json:
        with open(args.json, "w") as f:
            json.dump([flat_record(r) for r in rows], f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
