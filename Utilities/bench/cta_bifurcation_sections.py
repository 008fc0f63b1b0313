#!/usr/bin/python3
"""The raw CTA's iliac bifurcation seen in cross-section (issue 16): where does the lumen split
into two lobes, and where do VMTK's two reference centerlines and VesselCenterline run there?

    /usr/bin/python3 Utilities/bench/cta_bifurcation_sections.py --build BUILD
        [--out Docs/centerlines/raw_cta_bifurcation_sections.png]

Runs VesselCenterline on vmtk-aorta/aorta.mha from VMTK's reference's first point with no range
typed (the benchmark's CTA case), then for every coronal row j of the volume around the
bifurcation (the aorta runs along j there, within about 10 degrees) takes the lumen's section: the
voxels in the range the filter chose, in the components of the (i, k) plane that hold a reference
point. Prints, per row: the section's area and extents (mm), its number of lobes (regional maxima
of the in-plane distance map, spacing honoured, with a prominence of at least 0.5 mm: an
in-plane voxel is 0.88 mm, so a dent of the digital contour does not make a lobe; project rule),
the largest inscribed disc's radius, the distance of each VMTK line and of the extraction from
the section's centroid, and the two VMTK lines' distance apart. Then the upper bound the two-lobe
rule sets on "reference within 1 mm": where the section is one lobe, a network with one line
there is within 1 mm of both reference lines only where they are less than 2 mm apart (the
branch entries of Docs/CENTERLINES.md, Method step 9, carry the branch's axis on into the lobe,
as VMTK's lines run, and pass that bound).
The picture: the sections (intensity, the range's contour) with the reference lines and the
extraction, over a strip of the coronal MIP.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import textwrap

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "Utilities"))
import centerline_metrics as cm  # noqa: E402
import raw_centerline_bench as rb  # noqa: E402

LOBE_PROMINENCE_MM = 0.5
ROWS = range(110, 142)  # coronal rows j around the bifurcation (the carina is near j 121)
SHOWN = (114, 118, 120, 122, 124, 126, 128, 130, 132, 134)


def reference_lines(reference):
    """VMTK's polylines: consecutive points closer than 3 mm belong to one line (as the C++ test)."""
    lines, start = [], 0
    for i in range(1, len(reference) + 1):
        if i == len(reference) or np.linalg.norm(reference[i] - reference[i - 1]) > 3.0:
            lines.append(np.arange(start, i))
            start = i
    return lines


def extract(build, tmp):
    case, reference = rb.cta_case()
    with open(os.path.join(tmp, "cases.json"), "w") as f:
        json.dump([case], f)
    plugin = os.path.join(build, "lib", "paraview-5.11", "plugins", "VesselTouch", "VesselTouch.so")
    subprocess.run([os.path.join(ROOT, "Testing", "Utilities", "vtouch-xvfb-run"), "pvpython",
                    os.path.join(ROOT, "Testing", "Benchmarks", "raw_angiogram_extract.py"),
                    "--plugin", plugin, "--cases", os.path.join(tmp, "cases.json"), "--out", tmp,
                    "--keep-volume"], check=True, capture_output=True)
    data = np.load(os.path.join(tmp, case["tag"] + ".npz"))
    record = json.load(open(os.path.join(tmp, case["tag"] + ".json")))
    return data, record, reference


def sections(data, record, reference):
    from scipy import ndimage as ndi
    from skimage.morphology import h_maxima

    spacing, origin = data["spacing"], data["origin"]
    direction = np.array([-1.0, -1.0, 1.0])
    lower, upper = record["field.IntensityRangeUsed"][:2]
    volume = data["volume"]  # (k, j, i)
    to_ijk = lambda world: (world - origin) * direction / spacing  # noqa: E731
    ref_ijk = to_ijk(reference * direction)
    lines = reference_lines(reference)
    points = data["points"]
    dense, _ = cm.resample(points, rb.lines_of(data["conn"], data["offsets"]), 0.25)
    ours_ijk = to_ijk(dense)
    rows = []
    for j in ROWS:
        inside = (volume[:, j, :] >= lower) & (volume[:, j, :] <= upper)
        labels, _ = ndi.label(inside)
        near = [ref_ijk[line][np.argmin(abs(ref_ijk[line, 1] - j))] for line in lines]
        keep = {labels[int(round(q[2])), int(round(q[0]))] for q in near} - {0}
        section = np.isin(labels, list(keep))
        dist = ndi.distance_transform_edt(section, sampling=(spacing[2], spacing[0]))
        lobes = ndi.label(h_maxima(dist, LOBE_PROMINENCE_MM))[1]
        ks, is_ = np.nonzero(section)
        centre = np.array([is_.mean(), ks.mean()])
        off = lambda q: float(np.hypot((q[0] - centre[0]) * spacing[0],  # noqa: E731
                                       (q[2] - centre[1]) * spacing[2]))
        here = ours_ijk[abs(ours_ijk[:, 1] - j) <= 0.5]
        rows.append(dict(j=j, area_mm2=section.sum() * spacing[0] * spacing[2],
                         width_i_mm=(np.ptp(is_) + 1) * spacing[0],
                         width_k_mm=(np.ptp(ks) + 1) * spacing[2], lobes=lobes,
                         disc_mm=float(dist.max()), centre=centre,
                         vmtk_off_mm=[off(q) for q in near],
                         vmtk_apart_mm=float(np.linalg.norm((near[0] - near[1]) * spacing)),
                         ours_off_mm=[off(q) for q in here], ours=here, near=near,
                         section=section, image=volume[:, j, :]))
    return rows, ref_ijk, lines


def draw(rows, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    shown = [r for r in rows if r["j"] in SHOWN]
    fig, axes = plt.subplots(2, 5, figsize=(15, 6.4))
    for ax, r in zip(axes.ravel(), shown):
        img = r["image"]
        ax.imshow(img, origin="lower", cmap="gray", aspect=1.50009 / 0.878906,
                  vmin=0, vmax=float(img.max()))
        ax.contour(r["section"].astype(float), levels=[0.5], colors="orange", linewidths=0.8)
        for q, colour, label in ((r["near"][0], "lime", "VMTK line 1 (right iliac)"),
                                 (r["near"][1], "cyan", "VMTK line 2 (left iliac)")):
            ax.plot(q[0], q[2], "o", color=colour, ms=6, mfc="none", mew=1.5, label=label)
        if len(r["ours"]):
            ax.plot(r["ours"][:, 0], r["ours"][:, 2], "r.", ms=3, label="VesselCenterline")
        ax.plot(*r["centre"], "y+", ms=8, label="section centroid")
        ax.set_xlim(55, 95)
        ax.set_ylim(8, 25)
        ax.set_title("j %d: %d lobe%s, apart %.1f mm" % (r["j"], r["lobes"],
                                                         "" if r["lobes"] == 1 else "s",
                                                         r["vmtk_apart_mm"]), fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
    axes[0, 0].legend(loc="lower left", fontsize=6, framealpha=0.6)
    fig.suptitle("\n".join(textwrap.wrap(title, 190)), fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.88), h_pad=1.5)
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", required=True)
    parser.add_argument("--out", default=os.path.join(ROOT, "Docs", "centerlines",
                                                      "raw_cta_bifurcation_sections.png"))
    args = parser.parse_args()
    from scipy.spatial import cKDTree

    with tempfile.TemporaryDirectory() as tmp:
        data, record, reference = extract(args.build, tmp)
    rows, ref_ijk, lines = sections(data, record, reference)
    print(" j  area_mm2 width_i_mm width_k_mm lobes disc_mm  VMTK1/VMTK2 from centroid (mm)  "
          "apart_mm  VesselCenterline from centroid (mm)")
    for r in rows:
        ours = ("%.1f-%.1f" % (min(r["ours_off_mm"]), max(r["ours_off_mm"]))
                if r["ours_off_mm"] else "-")
        print("%3d %8.0f %9.1f %9.1f %5d %7.1f %12.1f / %.1f %14.1f   %s" % (
            r["j"], r["area_mm2"], r["width_i_mm"], r["width_k_mm"], r["lobes"], r["disc_mm"],
            r["vmtk_off_mm"][0], r["vmtk_off_mm"][1], r["vmtk_apart_mm"], ours))
    top_split = max(r["j"] for r in rows if r["lobes"] >= 2)
    # Points of the second line above the last two-lobe row, more than 2 mm from the first line:
    # one network line covers at most one of each such pair within 1 mm.
    d, _ = cKDTree(reference[lines[0]]).query(reference[lines[1]])
    pairs = int(((ref_ijk[lines[1], 1] > top_split) & (d > 2.0)).sum())
    cover = cm.coverage(data["points"] * np.array([-1.0, -1.0, 1.0]),
                        rb.lines_of(data["conn"], data["offsets"]), reference, 1.0, 0.25)
    print("last two-lobe row j %d; reference points the one-lobe stretch leaves to one line: %d "
          "of %d; upper bound on the reference within 1 mm for a network that branches where "
          "the lumen splits: %.3f; VesselCenterline: %.3f" % (
              top_split, pairs, len(reference), 1.0 - pairs / len(reference), cover))
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    draw(rows, args.out, "Raw CTA, the aorta's lowest centimetre in coronal sections j (voxel "
         "rows, 0.88 mm; i across, k up): the lumen (orange: the range [%.0f, %.0f]) is two lobes "
         "up to j %d, one flattened lobe above; VMTK's two lines run apart in it, and so does "
         "VesselCenterline (red: the left iliac's axis carried on to the aorta's, Method step 9): "
         "reference within 1 mm %.3f (at most %.3f branching where the lumen splits)"
         % (record["field.IntensityRangeUsed"][0], record["field.IntensityRangeUsed"][1],
            top_split, cover, 1.0 - pairs / len(reference)))
    print("wrote", args.out)


if __name__ == "__main__":
    main()
