#!/usr/bin/python3
"""Pictures of raw-angiogram centerlines over the MIP (issue 16): VesselCenterline from one seed
(no range typed) beside scikit-image's skeletonize_3d on an Otsu mask, for Docs/centerlines/.

    /usr/bin/python3 Utilities/bench/render_centerline_mip.py --build BUILD [--out Docs/centerlines]
        [--cases phantom cta tof]

phantom: the RawAngiogram VesselPhantom, 256^3, seed 1, Gaussian noise 20
         (-> bench_raw_phantom_vs_skimage.png);
cta:     the shared raw CTA vmtk-aorta/aorta.mha seeded on VMTK's reference's first point
         (-> bench_raw_cta_aorta_vs_skimage.png);
tof:     the shared TOF-MRA tof-mra-willis/chris_MRA.nii.gz seeded on the basilar artery (voxel
         95, 123, 15), VesselCenterline alone (-> raw_tof_willis.png).
Each picture: the MIP along z, and over it the extraction (red; on the phantom, yellow where a
point is more than 1.5 voxels outside every true vessel, and blue where the true axis is not
covered: the misses; on the CTA, VMTK's reference in green).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ beside the sources
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import centerline_metrics as cm  # noqa: E402
import raw_centerline_bench as rb  # noqa: E402

CASES = {
    "phantom": ({"tag": "phantom", "phantom": {"Dimensions": [256, 256, 256], "Seed": 1,
                                               "NoiseStandardDeviation": 20,
                                               "AngiogramSegments": 200}},
                "bench_raw_phantom_vs_skimage.png"),
    "cta": (None, "bench_raw_cta_aorta_vs_skimage.png"),
    "tof": ({"tag": "tof", "file": os.path.join(ROOT, "..", "shared", "data", "tof-mra-willis",
                                                "chris_MRA.nii.gz"),
             "seed_voxel": [95, 123, 15]}, "raw_tof_willis.png"),
}


def render_tof(data, record, path):
    """The TOF-MRA's axial MIP with VesselCenterline's points and the seed (no reference)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    mip = data["mip_z"]
    inverse = np.linalg.inv(data["direction"])
    ijk = (inverse @ (data["points"] - data["origin"]).T).T / data["spacing"]
    fig, ax = plt.subplots(figsize=(4.2, 5.6))
    ax.imshow(mip, cmap="gray", origin="lower", vmin=0, vmax=np.percentile(mip, 99.5),
              interpolation="nearest")
    ax.scatter(ijk[:, 0], ijk[:, 1], s=3.0, c="red", linewidths=0,
               label="VesselCenterline (seed only)")
    seed = CASES["tof"][0]["seed_voxel"]
    ax.plot([seed[0]], [seed[1]], "c+", ms=10, mew=1.5, label="seed (basilar)")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_xlim(0, mip.shape[1] - 1)
    ax.set_ylim(0, mip.shape[0] - 1)
    ax.set_title("TOF-MRA (MRIcroGL chris_MRA, CC BY-NC 4.0), axial MIP:\ncenterlines from one "
                 "seed on the basilar artery, range estimated (%d paths)" % record["paths"],
                 fontsize=7)
    ax.legend(loc="lower right", fontsize=6, markerscale=1.5, framealpha=0.8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def to_pixels(points_mm, origin, spacing, direction):
    """World mm -> (i, j) pixel coordinates of the z MIP."""
    ijk = (points_mm - origin) * direction / spacing
    return ijk[:, 0], ijk[:, 1]


def draw(path, mip, panels, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import textwrap

    ny, nx = mip.shape
    width = max(4.5, 6.0 * nx / max(nx, ny) + 0.5)
    fig, axes = plt.subplots(1, len(panels), figsize=(width * len(panels), 7.2))
    lo, hi = np.percentile(mip, [1, 99.7])
    for ax, (name, layers) in zip(np.atleast_1d(axes), panels):
        ax.imshow(mip, cmap="gray", vmin=lo, vmax=hi, origin="lower", interpolation="nearest")
        for (u, v), colour, size, label in layers:
            if len(u):
                ax.scatter(u, v, s=size, c=colour, linewidths=0, label=label)
        ax.set_title("\n".join(textwrap.wrap(name, 52)), fontsize=9)
        ax.set_xlim(-0.5, nx - 0.5)
        ax.set_ylim(-0.5, ny - 0.5)
        ax.set_xticks([])
        ax.set_yticks([])
        ax.legend(loc="upper right", fontsize=7, markerscale=4, framealpha=0.6)
    fig.suptitle("\n".join(textwrap.wrap(title, 48 * len(panels))), fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.92))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def render(build, which, out_dir, tmp):
    case, name = CASES[which]
    reference = None
    if which == "cta":
        case, reference = rb.cta_case()
    with open(os.path.join(tmp, "cases.json"), "w") as f:
        json.dump([case], f)
    plugin = os.path.join(build, "lib", "paraview-5.11", "plugins", "VesselTouch", "VesselTouch.so")
    subprocess.run([os.path.join(ROOT, "Testing", "Utilities", "vtouch-xvfb-run"), "pvpython",
                    os.path.join(ROOT, "Testing", "Benchmarks", "raw_angiogram_extract.py"),
                    "--plugin", plugin, "--cases", os.path.join(tmp, "cases.json"), "--out", tmp,
                    "--keep-volume"], check=True)
    data = np.load(os.path.join(tmp, case["tag"] + ".npz"))
    record = json.load(open(os.path.join(tmp, case["tag"] + ".json")))
    if which == "tof":
        os.makedirs(out_dir, exist_ok=True)
        path = os.path.join(out_dir, name)
        render_tof(data, record, path)
        print("wrote", path)
        return
    spacing, origin = data["spacing"], data["origin"]
    direction = np.array([-1.0, -1.0, 1.0]) if which == "cta" else np.ones(3)
    points = data["points"]
    lines = rb.lines_of(data["conn"], data["offsets"])
    dense, _ = cm.resample(points, lines, 0.25 * spacing.min())
    ijk, sk_seconds, _, otsu, _ = rb.skimage_run(data["volume"], tmp)
    sk_world = origin + ijk * spacing * direction
    voxel = float(spacing.min())
    panels = []
    if which == "phantom":
        truth = data["truth_points"]
        radius = data["truth_radius"]
        truth_lines = rb.lines_of(data["truth_conn"], data["truth_offsets"])
        truth_dense, truth_r = cm.resample(truth, truth_lines, 0.25 * voxel, radius)
        for label, pts, pts_lines in (("VesselCenterline", dense, lines), ("skimage", sk_world,
                                                                           None)):
            from scipy.spatial import cKDTree
            m = cm.measure(points if pts_lines is not None else pts, pts_lines, truth, radius,
                           truth_lines, voxel)
            false = cm.outside_distance(pts, truth_dense, truth_r, voxel) > 1.5 * voxel
            d, _ = cKDTree(pts).query(truth_dense)
            missed = d > np.maximum(1.5 * voxel, truth_r)
            panels.append(("%s: precision %.3f, recall r>=0.5 %.3f, r>=1 %.3f, mean %.2f vox, "
                           "false points %d" % (label, m["precision"], m["recall_r0.5_up"],
                                                m["recall_r1_up"], m["mean_dist_vox"],
                                                m["false_vessel_points"]),
                           [(to_pixels(pts[~false], origin, spacing, direction), "red", 1.0,
                             "centerline"),
                            (to_pixels(pts[false], origin, spacing, direction), "yellow", 2.0,
                             "outside every vessel"),
                            (to_pixels(truth_dense[missed], origin, spacing, direction), "deepskyblue",
                             2.0, "true axis missed")]))
        title = ("RawAngiogram phantom %s, seed 1, noise 20 (tissue 400, vessels 1000): "
                 "VesselCenterline from the root (%s range) and skimage on an Otsu mask (%.0f)"
                 % ("x".join(map(str, record["dimensions"])), record["range_mode"], otsu))
    else:
        ref_world = reference * direction
        cover = cm.coverage(points * direction, lines, reference, 1.0, 0.25)
        sk_cover = cm.coverage(sk_world * direction, None, reference, 1.0, 0.25)
        for label, pts, c in (("VesselCenterline", dense, cover), ("skimage", sk_world, sk_cover)):
            panels.append(("%s: VMTK reference within 1 mm %.3f" % (label, c),
                           [(to_pixels(ref_world, origin, spacing, direction), "lime", 3.0,
                             "VMTK reference"),
                            (to_pixels(pts, origin, spacing, direction), "red", 1.0,
                             "centerline")]))
        title = ("Raw CTA (vmtk-aorta/aorta.mha), one seed (VMTK's reference's first point, in "
                 "the right iliac): VesselCenterline (%s range) and skimage on an Otsu mask (%.0f)"
                 % (record["range_mode"], otsu))
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, name)
    draw(path, data["mip_z"], panels, title)
    print("wrote", path)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", required=True)
    parser.add_argument("--out", default=os.path.join(ROOT, "Docs", "centerlines"))
    parser.add_argument("--cases", nargs="+", choices=sorted(CASES), default=sorted(CASES))
    args = parser.parse_args()
    for which in args.cases:
        with tempfile.TemporaryDirectory(prefix="vtouch-render-") as tmp:
            render(args.build, which, args.out, tmp)


if __name__ == "__main__":
    main()
