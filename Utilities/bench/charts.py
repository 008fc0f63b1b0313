#!/usr/bin/python3
"""Draws the benchmark charts from <out>/results.json and <out>/raw/*.json into <out>/*.png.

    /usr/bin/python3 Utilities/bench/charts.py OUT

Charts (each captioned with the machine, the commit and quick/full mode):
  centerline_accuracy_vs_time.png  mean / p95 distance and coverage against extraction time, voxel
                                   coding over its parameters and scikit-image, per input
  centerline_scaling.png           time and peak memory against volume size, log-log, fitted slopes
  force_error_vs_rate.png          force error against loop rate per force law, helix and spiral
  force_error_vs_tick_cost.png     force error at 1 kHz against the tick's median cost
  tracer_rules.png                 the two tracing rules: tracking error, force steps at the
                                   spiral's cusps, branch choices against the branch angle
  surface_stimulus.png             Hayward & Yi's surface (eqs. 4-7): change of height against
                                   the lateral gradient along the traced line
  loop_period_error.png            period-error histograms at 1, 2, 5, 10 kHz, with and without
                                   a render load
  stability_maps.png               stable/unstable over coupler k_c, LDGF lambda, force
                                   interpolation bound against loop rate, defaults marked
  render_fps.png                   agent frames/s cached vs full re-render over volume sizes
  client_server_scaling.png        peak memory per rank, centerline time, bytes to the client and
                                   the client's haptic p99 against the pvserver rank count; the
                                   largest volume's time per stage per run
  raw_centerline.png               raw angiograms from one seed: recall per radius class and
                                   precision (worst phantom case), VesselCenterline vs
                                   scikit-image, every case as dots; times beside
A chart whose data is missing is skipped with a notice (exit status stays 0: check_results.py is
the judge of completeness).
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

LAWS = (("ldgf", "LDGF"), ("change_of_height", "change of height"),
        ("lateral_gradient", "lateral gradient"), ("constraint_proxy", "constraint proxy"))


def load(out, name):
    path = os.path.join(out, "raw", name + ".json")
    return json.load(open(path)) if os.path.exists(path) else None


def caption(fig, results):
    mode = "QUICK (small inputs)" if results.get("meta.quick") else "full"
    fig.text(0.01, 0.005, "%s | commit %s | %s | %s | load avg %.1f" % (
        results.get("meta.machine", "?"), results.get("meta.commit", "?"), mode,
        results.get("meta.date", "?"), results.get("meta.load_average_1min", float("nan"))),
        fontsize=6.5, color="0.35", ha="left", va="bottom")


def save(fig, out, name, results):
    caption(fig, results)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(os.path.join(out, name), dpi=110)
    plt.close(fig)
    print("charts: wrote", name)


def chart_centerline_accuracy(out, results):
    raw = load(out, "centerline")
    if not raw:
        return
    inputs = [("helix", "helix phantom"), ("tree", "tree phantom"), ("aorta", "VMTK aorta (mm)")]
    measures = [("mean_dist_vox", "mean distance to reference (voxels)"),
                ("p95_dist_vox", "p95 distance to reference (voxels)"),
                ("coverage", "coverage (fraction of reference covered)")]
    fig, axes = plt.subplots(len(measures), len(inputs), figsize=(14, 10.5))
    for col, (name, title) in enumerate(inputs):
        sweeps = raw["sweeps"].get(name, {})
        if name == "aorta":
            base = raw["aorta"]
        else:
            base = raw["scaling"][name][-1]
        for row, (key, label) in enumerate(measures):
            ax = axes[row][col]
            for param, marker, what in (("smoothing_mm", "o-", "VC smoothing window W (mm)"),
                                        ("min_branch", "s--", "VC MinimumBranchLength (radii)"),
                                        ("downsample", "^:", "VC DownsampleFactor")):
                rows = sweeps.get(param, [])
                if not rows:
                    continue
                xs = [r["seconds"] for r in rows]
                ys = [r[key] for r in rows]
                ax.plot(xs, ys, marker, label=what, alpha=0.85)
                for r in rows:
                    ax.annotate("%g" % r["value"], (r["seconds"], r[key]), fontsize=7,
                                xytext=(3, 3), textcoords="offset points")
            if name in raw.get("vesselness", {}):
                for r in raw["vesselness"][name]:
                    ax.plot(r["seconds"], r[key], "D", color="tab:green" if r["vesselness"]
                            else "tab:olive", label="VC noisy input, vesselness %s" % (
                                "on" if r["vesselness"] else "off"))
            ax.plot(base["seconds"], base[key], "*", ms=14, color="tab:red",
                    label="VC defaults, largest size")
            ax.plot(base["skimage_seconds"], base["skimage_" + key], "X", ms=11,
                    color="black", label="scikit-image skeletonize_3d, largest size")
            ax.set_xscale("log")
            ax.set_xlabel("extraction time (s, log)")
            ax.set_ylabel(label.replace("voxels", "mm") if name == "aorta" else label)
            if row == 0:
                size = "%d^3" % base["size_vox"] if "size_vox" in base else "157x393x34"
                ax.set_title("%s (sweeps at a smaller size; stars: %s)" % (title, size),
                             fontsize=9)
            ax.grid(alpha=0.3, which="both")
    handles, labels = axes[0][1].get_legend_handles_labels()
    uniq = dict(zip(labels, handles))
    fig.legend(uniq.values(), uniq.keys(), loc="upper center", ncol=3, fontsize=8,
               bbox_to_anchor=(0.5, 1.0))
    fig.subplots_adjust(top=0.9)
    caption(fig, results)
    fig.tight_layout(rect=(0, 0.03, 1, 0.93))
    fig.savefig(os.path.join(out, "centerline_accuracy_vs_time.png"), dpi=110)
    plt.close(fig)
    print("charts: wrote centerline_accuracy_vs_time.png")


def chart_centerline_scaling(out, results):
    raw = load(out, "centerline")
    if not raw:
        return
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    for shape, color in (("helix", "tab:blue"), ("tree", "tab:orange")):
        rows = raw["scaling"].get(shape, [])
        if not rows:
            continue
        vox = np.array([r["volume_voxels"] for r in rows], float)
        for ax, key, skey, unit in ((axes[0], "seconds", "skimage_seconds", "time"),
                                    (axes[1], "peak_mb", "skimage_peak_mb", "memory")):
            for who, k, style in (("vc", key, "o-"), ("skimage", skey, "x--")):
                ys = np.maximum(np.array([r[k] for r in rows], float), 1e-3)
                slope = results.get("centerline.scaling.%s.%s_%s_slope" % (shape, who, unit),
                                    float("nan"))
                ax.loglog(vox, ys, style, color=color,
                          label="%s %s (slope %.2f)" % (
                              shape, "voxel coding, default scale" if who == "vc"
                              else "scikit-image", slope))
            fkey = "full_resolution_" + key
            if all(fkey in r for r in rows):
                ys = np.maximum(np.array([r[fkey] for r in rows], float), 1e-3)
                ax.loglog(vox, ys, "s:", color=color, alpha=0.6,
                          label="%s voxel coding, full resolution" % shape)
    axes[0].set_ylabel("extraction time (s)")
    axes[1].set_ylabel("peak extra resident memory (MB)")
    for ax in axes:
        ax.set_xlabel("volume size (voxels)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    axes[0].set_title("time vs volume size (slope fitted on the larger half)", fontsize=10)
    axes[1].set_title("peak memory vs volume size", fontsize=10)
    save(fig, out, "centerline_scaling.png", results)


def chart_force(out, results):
    raw = load(out, "force")
    if not raw:
        return
    fig, axes = plt.subplots(1, 2, figsize=(13, 5), sharey=True)
    for ax, scene in zip(axes, ("helix", "spiral")):
        for law, label in LAWS:
            pre = "force.%s.%s." % (law, scene)
            pts = sorted((float(k[len(pre):-len("hz.rel_rms_error")]), v) for k, v in raw.items()
                         if k.startswith(pre) and k.endswith("hz.rel_rms_error"))
            if pts:
                ax.loglog([p[0] for p in pts], [max(p[1], 1e-6) for p in pts], "o-", label=label)
        ax.axvline(1000, color="0.5", ls=":", lw=1, label="default 1 kHz")
        ax.set_xlabel("haptic loop rate (Hz)")
        ax.set_title("%s: error vs a %.0f Hz reference run (hand %.0f mm/s)" % (
            scene, raw.get("force.reference_rate_hz", 0), raw.get("force.hand_speed_mm_per_s", 0)),
            fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    axes[0].set_ylabel("relative RMS force error (1 = 100 %)")
    save(fig, out, "force_error_vs_rate.png", results)

    fig, ax = plt.subplots(figsize=(7.5, 5))
    for law, label in LAWS:
        for scene, marker in (("helix", "o"), ("spiral", "s")):
            cost = raw.get("force.%s.%s.tick_median_ns" % (law, scene))
            err = raw.get("force.%s.%s.1000hz.rel_rms_error" % (law, scene))
            if cost is not None and err is not None:
                ax.loglog(cost, max(err, 1e-6), marker, ms=9, label="%s, %s" % (label, scene))
    ax.set_xlabel("median session tick cost (ns, offline, 1 kHz)")
    ax.set_ylabel("relative RMS force error at 1 kHz")
    ax.set_title("force error vs tick cost", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, ncol=2)
    save(fig, out, "force_error_vs_tick_cost.png", results)


def chart_tracer(out, results):
    """The two tracing rules (Yi & Hayward 3.2.1): tracking error, force steps, and the branch
    choice against the branch's angle, with the junction re-decision (default) and without it."""
    raw = load(out, "force")
    if not raw or "tracer.offset.helix.mean_error_px" not in raw:
        return
    rules = (("offset", "offset (default)"), ("movement", "movement (paper)"))
    scenes = ("helix", "spiral")
    fig, axes = plt.subplots(1, 4, figsize=(18, 4.5))
    width = 0.38
    x = np.arange(len(scenes))
    for i, (rule, label) in enumerate(rules):
        mean = [raw.get("tracer.%s.%s.mean_error_px" % (rule, s), np.nan) for s in scenes]
        peak = [raw.get("tracer.%s.%s.max_error_px" % (rule, s), np.nan) for s in scenes]
        step = [raw.get("tracer.%s.%s.max_force_step_n" % (rule, s), np.nan) for s in scenes]
        axes[0].bar(x + (i - 0.5) * width, mean, width, label=label + " mean")
        axes[0].plot(x + (i - 0.5) * width, peak, "k^", ms=7)
        axes[1].bar(x + (i - 0.5) * width, step, width, label=label)
        angles = raw.get("tracer.%s.branch.angles_deg" % rule) or []
        for variant, style, suffix in (("branch", "-o", ""),
                                       ("branch_at_junction", ":x", ", choice at junction final")):
            for ax, what in ((axes[2], "taken"), (axes[3], "kept")):
                ys = [raw.get("tracer.%s.%s.angle%d.%s" % (rule, variant, a, what), np.nan)
                      for a in angles]
                ax.plot(angles, ys, style, color="C%d" % i, label=label + suffix)
    axes[0].set_yscale("log")
    axes[0].set_title("tracking error (bars mean, triangles max), px", fontsize=10)
    axes[1].set_title("largest per-tick LDGF target step, N", fontsize=10)
    axes[2].set_title("hand follows the branch: fraction ending on it", fontsize=10)
    axes[3].set_title("hand follows the parent: fraction ending on it", fontsize=10)
    for ax in axes[:2]:
        ax.set_xticks(x)
        ax.set_xticklabels(["helix (side)", "spiral 3 deg off edge-on"])
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3, axis="y")
    for ax in axes[2:]:
        ax.set_xlabel("branch angle to the parent, degrees (5 dither seeds)")
        ax.set_ylim(-0.05, 1.05)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    save(fig, out, "tracer_rules.png", results)


def chart_surface(out, results):
    """Hayward & Yi's surface stimulus (eqs. 4-7): change of height against the lateral gradient."""
    raw = load(out, "force")
    if not raw or "surface.trace.x_mm" not in raw:
        return
    x = np.array(raw["surface.trace.x_mm"])
    fig, axes = plt.subplots(2, 1, figsize=(12, 6.5), sharex=True)
    for law, label, style in (("lateral_gradient", "lateral gradient (eq. 5)", "-"),
                              ("change_of_height", "change of height (eq. 7)", "-")):
        axes[0].plot(x, raw["surface.trace.%s_fx_n" % law], style, lw=1.2, label=label)
        axes[1].plot(x, raw["surface.trace.%s_fy_n" % law], style, lw=0.8, label=label)
    expected = np.where(x < -10, np.tan(0.4), np.where(x > 10, -np.tan(0.7), 0.0))
    axes[0].plot(x, expected, "k:", lw=1, label="-k dz/dx (k = 1 N)")
    axes[0].set_ylabel("force along the motion (N)")
    axes[1].set_ylabel("force across the motion (N)")
    axes[1].set_xlabel("x along the trace y = 0 (mm); patches: slope -tan 0.4 | 0 | +tan 0.7")
    axes[0].set_title("Hayward & Yi's surface z = tan(a) x + A sin(wx) y, traced at 20 mm/s: both "
                      "render the slope; only the lateral gradient adds the cross texture",
                      fontsize=10)
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    save(fig, out, "surface_stimulus.png", results)


def chart_loop(out, results):
    raw = load(out, "haptic")
    if not raw:
        return
    rates = (1000, 2000, 5000, 10000)
    fig, axes = plt.subplots(1, len(rates), figsize=(16, 4.5), sharey=True)
    lowest = [1.0]
    for ax, rate in zip(axes, rates):
        for suffix, color, label in (("", "tab:blue", "idle"), ("_render", "tab:red",
                                                                "with render load")):
            pre = "haptic.loop_%dhz%s." % (rate, suffix)
            edges = raw.get(pre + "hist_edges_us")
            counts = raw.get(pre + "hist_counts")
            if not edges:
                continue
            edges = np.array(edges + [edges[-1] * 1.1])
            counts = np.array(counts, float)
            frac = counts / max(counts.sum(), 1)
            floor = 0.3 / max(counts.sum(), 1)
            lowest[0] = min(lowest[0], floor)
            ax.stairs(np.where(frac > 0, frac, floor * 1e-3), np.maximum(edges, 0.1), color=color,
                      label="%s: p99 %.1f us, %.0f Hz" % (
                          label, raw.get(pre + "p99_period_error_us", float("nan")),
                          raw.get(pre + "achieved_hz", float("nan"))))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("period error: wake-up after deadline (us, log)")
        ax.set_title("%d Hz" % rate, fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    axes[0].set_ylabel("fraction of ticks (0.5 us bins to 50 us, then 10 % wide)")
    axes[0].set_ylim(lowest[0], 1.5)
    save(fig, out, "loop_period_error.png", results)


def chart_stability(out, results):
    raw = load(out, "stability")
    if not raw:
        return
    maps = (("coupler_kc_n_per_m", "constraint proxy coupler stiffness k_c (N/m)"),
            ("ldgf_lambda_mm", "LDGF lambda at a projection cusp (mm)"),
            ("interpolation_n_per_s", "force interpolation bound at a cusp (N/s)"))
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
    for ax, (name, label) in zip(axes, maps):
        values = np.array(raw["stability.%s.values" % name])
        rates = np.array(raw["stability.%s.rates_hz" % name])
        stable = np.array(raw["stability.%s.stable" % name]).reshape(len(rates), len(values))
        vv, rr = np.meshgrid(values, rates)
        ax.scatter(vv[stable > 0], rr[stable > 0], marker="o", color="tab:green", s=40,
                   label="stable")
        ax.scatter(vv[stable == 0], rr[stable == 0], marker="x", color="tab:red", s=40,
                   label="unstable (energy growth)")
        ax.plot([raw["stability.%s.default" % name]], [1000], "*", color="black", ms=16,
                label="default (%g at 1 kHz)" % raw["stability.%s.default" % name])
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_yticks(rates)
        ax.set_yticklabels(["%g" % r for r in rates])
        ax.minorticks_off()
        ax.set_xlabel(label)
        ax.set_ylabel("haptic loop rate (Hz)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7, loc="best")
    save(fig, out, "stability_maps.png", results)


def chart_render(out, results):
    raw = load(out, "render")
    if not raw:
        return
    sizes = raw.get("render.sizes", [])
    vox, cached, full = [], [], []
    for s in sizes:
        n = [int(p) for p in s.split("x")]
        vox.append(n[0] * n[1] * n[2])
        cached.append(raw["render.%s.agent_fps_cached" % s])
        full.append(raw["render.%s.agent_fps_full" % s])
    fig, ax = plt.subplots(figsize=(7.5, 5))
    ax.loglog(vox, cached, "o-", label="cached MIP (agent-only frames)")
    ax.loglog(vox, full, "s--", label="full re-render every frame")
    for x, s in zip(vox, sizes):
        ax.annotate(s, (x, cached[vox.index(x)]), fontsize=7, xytext=(3, 3),
                    textcoords="offset points")
    ax.axhline(60, color="0.5", ls=":", lw=1, label="60 fps GUI timer")
    ax.set_xlabel("volume size (voxels)")
    ax.set_ylabel("agent frame rate (frames/s) at %dx%d px" % (
        raw.get("render.width_px", 0), raw.get("render.height_px", 0)))
    ax.set_title("agent frame rate over a MIP (Xvfb, Mesa llvmpipe)", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    save(fig, out, "render_fps.png", results)


def chart_client_server_scaling(out, results):
    """Issue 19 item 4: per volume size, against the rank count, the whole volume on the first
    rank (solid) and distributed extraction (dashed): the largest rank's peak memory, the
    centerline's time in the pipeline, the bytes sent to the client, the client's haptic p99."""
    raw = load(out, "scaling")
    if not raw:
        return
    runs = raw["runs"]
    panels = (("peak_rss_mib_max", "largest rank's peak memory (MiB)"),
              ("centerline_s", "VesselCenterline in the pipeline (s)"),
              ("bytes_to_client", "skeleton sent to the client (bytes)"),
              ("haptic.render.period_error_p99_us", "client haptic p99 period error\n"
               "while the server renders (us)"))
    fig, axes = plt.subplots(1, 5, figsize=(19, 4.2))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, (key, label) in zip(axes[:4], panels):
        for i, size in enumerate(raw["sizes"]):
            for distributed, style in ((False, "o-"), (True, "s--")):
                chosen = [r for r in runs if r == "r1" or r.endswith("d") == distributed]
                ranks = [int(r[1:].rstrip("d")) for r in chosen]
                values = [raw.get("%s.%s" % (size, r), {}).get(key, float("nan")) for r in chosen]
                ax.plot(ranks, values, style, color=colours[i % len(colours)],
                        label="%s %s" % (size, "distributed" if distributed else "whole on rank 0"))
        ax.set_xticks(sorted({int(r[1:].rstrip("d")) for r in runs}))
        ax.set_xlabel("pvserver ranks (2 cores: 4 oversubscribe)")
        ax.set_ylabel(label, fontsize=8)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=6)
    chart_scaling_stages(axes[4], raw, colours)
    fig.suptitle("client/server: the volume on N ranks, the haptic session in the client",
                 fontsize=10)
    save(fig, out, "client_server_scaling.png", results)


def chart_scaling_stages(ax, raw, colours):
    """Where VesselCenterline's time in the pipeline goes on the largest volume, per run: stacked,
    each stage the slowest rank's (distributed runs: stage_piece*; the first rank's coder
    otherwise), the rest of the pipeline's wall time on top. A stage's slowest rank need not be
    the same rank for every stage, so the stack may exceed the wall time (then no rest is drawn)."""
    size = raw["sizes"][-1]
    stages = (("reader re-run (grown piece)", ("stage_pieceUpstream_s",)),
              ("mask", ("stage_pieceMask_s", "stage_coderMask_s")),
              ("global SS field (rounds)", ("stage_coderGlobalSeedCode_s",)),
              ("coding", ("stage_pieceCode_s", "stage_coderCoderAll_s")),
              ("gather wait + stitch", ("stage_pieceGatherWait_s", "stage_distributedStitch_s")))
    runs = raw["runs"]
    bottoms = [0.0] * len(runs)
    for j, (label, keys) in enumerate(stages):
        values = []
        for r in runs:
            data = raw.get("%s.%s" % (size, r), {})
            if label == "gather wait + stitch":
                values.append(sum(data.get(k, 0.0) for k in keys))
            else:
                values.append(next((data[k] for k in keys if k in data), 0.0))
        ax.bar(range(len(runs)), values, bottom=bottoms, color=colours[j % len(colours)],
               label=label)
        bottoms = [b + v for b, v in zip(bottoms, values)]
    rest = [max(0.0, raw.get("%s.%s" % (size, r), {}).get("centerline_s", 0.0) - b)
            for r, b in zip(runs, bottoms)]
    ax.bar(range(len(runs)), rest, bottom=bottoms, color="lightgrey", label="rest of the wall time")
    ax.set_xticks(range(len(runs)))
    ax.set_xticklabels(runs)
    ax.set_xlabel("run (d: distributed)")
    ax.set_ylabel("%s: time per stage (s)" % size, fontsize=8)
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=6)


def chart_raw_centerline(out, results):
    raw = load(out, "rawcenterline")
    if not raw:
        return
    classes = [("recall_r0.5_0.6", "recall\nr 0.5-0.6"), ("recall_r0.6_0.75", "recall\n0.6-0.75"),
               ("recall_r0.75_1", "recall\n0.75-1"), ("recall_r1_2", "recall\n1-2"),
               ("recall_r2_up", "recall\n>= 2"), ("precision", "precision")]
    cases = {t: c for t, c in raw["cases"].items() if "vc" in c and t != "large"}
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5), gridspec_kw={"width_ratios": [3, 1.2]})
    x = np.arange(len(classes))
    for offset, who, label, colour in ((-0.2, "vc", "VesselCenterline (seed, %s range)" % (
            "automatic" if results.get("centerline.raw.automatic_range") else "Otsu"), "C0"),
                                       (0.2, "skimage", "skimage skeletonize_3d (Otsu mask)",
                                        "C1")):
        prefix = "centerline.raw." if who == "vc" else "centerline.raw.skimage."
        worst = [results.get(prefix + k, float("nan")) for k, _ in classes]
        ax.bar(x + offset, worst, 0.38, color=colour, alpha=0.55, label=label + ": worst case")
        for i, (k, _) in enumerate(classes):
            values = [c[who][k] for c in cases.values()]
            ax.plot(np.full(len(values), x[i] + offset), values, ".", color=colour, ms=4)
    ax.axhline(0.95, color="0.4", ls=":", lw=1)
    ax.axhline(0.99, color="0.4", ls="--", lw=1)
    ax.set_xticks(x)
    ax.set_xticklabels([l for _, l in classes], fontsize=8)
    ax.set_ylim(max(0.0, min(0.8, np.nanmin([results.get("centerline.raw.precision", 1),
                                             results.get("centerline.raw.skimage.precision", 1)])
                             - 0.05)), 1.005)
    ax.set_ylabel("fraction (radius r in voxels)")
    ax.set_title("RawAngiogram phantoms (%d cases; dots: each case), targets 0.95 and 0.99" %
                 len(cases), fontsize=10)
    ax.legend(fontsize=8, loc="lower left")
    labels = ["VesselCenterline", "skimage", "whole-volume\nvesselness"]
    times = [results.get("centerline.raw.time_s", float("nan")),
             results.get("centerline.raw.skimage.time_s", float("nan")),
             results.get("centerline.raw.vesselness_whole_volume_s", float("nan"))]
    bx.bar(range(3), times, color=["C0", "C1", "C2"])
    bx.set_xticks(range(3))
    bx.set_xticklabels(labels, fontsize=8)
    bx.set_ylabel("seconds")
    bx.set_title("CTA-sized volume (%.0f Mvoxels)" % (
        results.get("centerline.raw.large.voxels", float("nan")) / 1e6), fontsize=10)
    save(fig, out, "raw_centerline.png", results)


def summary(out, results):
    """OUT/summary.md: the headline numbers as Markdown tables (copied by bench.sh --publish)."""
    r = results.get
    lines = ["Benchmarks: commit %s, %s, %s mode, %s." % (
        r("meta.commit"), r("meta.machine"), "quick" if r("meta.quick") else "full", r("meta.date")),
        "", "| input | VC s | VC peak MB | VC mean / p95 dist | VC coverage | skimage s | "
        "skimage peak MB | skimage mean / p95 dist | skimage coverage |", "|" + "---|" * 9]
    for name in ("helix384", "tree384", "aorta"):
        p = "centerline.%s." % name
        if r(p + "seconds") is None:
            continue
        lines.append("| %s | %.3f | %.1f | %.2f / %.2f | %.3f | %.3f | %.1f | %.2f / %.2f | %.3f |" % (
            name, r(p + "seconds"), r(p + "peak_mb"), r(p + "mean_dist_vox"),
            r(p + "p95_dist_vox"), r(p + "coverage"), r(p + "skimage_seconds"),
            r(p + "skimage_peak_mb"), r(p + "skimage_mean_dist_vox"),
            r(p + "skimage_p95_dist_vox"), r(p + "skimage_coverage")))
    if r("centerline.raw.precision") is not None:
        lines += ["", "| raw angiograms (worst phantom case) | precision | recall r>=0.5 | "
                  "recall r>=1 | recall 0.5-0.6 | mean dist vox | false points | CTA within 1 mm "
                  "| s (CTA-sized) |", "|" + "---|" * 9]
        for who, p in (("VesselCenterline", "centerline.raw."),
                       ("skimage (Otsu)", "centerline.raw.skimage.")):
            lines.append("| %s | %.3f | %.3f | %.3f | %.3f | %.2f | %d | %.3f | %.2f |" % (
                who, r(p + "precision"), r(p + "recall_r0.5_up"), r(p + "recall_r1_up"),
                r(p + "recall_r0.5_0.6"), r(p + "mean_dist_vox"), r(p + "false_vessel_points"),
                r(p + "cta_aorta.coverage_1mm"), r(p + "time_s")))
        lines.append("| whole-volume vesselness | | | | | | | | %.2f |" % r(
            "centerline.raw.vesselness_whole_volume_s"))
    lines += ["", "| loop | achieved Hz | p50 / p99 / p99.9 period error us | max us | "
              "+render achieved Hz | +render p99 / p99.9 us | +render max us |", "|" + "---|" * 7]
    for rate in (1000, 2000, 5000, 10000):
        p, q = "haptic.loop_%dhz." % rate, "haptic.loop_%dhz_render." % rate
        if r(p + "achieved_hz") is None:
            continue
        lines.append("| %d Hz | %.1f | %.1f / %.1f / %.1f | %.0f | %.1f | %.1f / %.1f | %.0f |" % (
            rate, r(p + "achieved_hz"), r(p + "p50_period_error_us"), r(p + "p99_period_error_us"),
            r(p + "p999_period_error_us"), r(p + "max_period_error_us"), r(q + "achieved_hz", 0),
            r(q + "p99_period_error_us", 0), r(q + "p999_period_error_us", 0),
            r(q + "max_period_error_us", 0)))
    lines += ["", "| force law | helix err 250 Hz / 1 kHz / 10 kHz | spiral err 250 Hz / 1 kHz / "
              "10 kHz | tick ns (helix, spiral) |", "|" + "---|" * 4]
    for law, label in LAWS:
        cells = []
        for scene in ("helix", "spiral"):
            cells.append(" / ".join(
                "%.2g" % r("force.%s.%s.%dhz.rel_rms_error" % (law, scene, rate), float("nan"))
                for rate in (250, 1000, 10000)))
        lines.append("| %s | %s | %s | %.0f, %.0f |" % (
            label, cells[0], cells[1], r("force.%s.helix.tick_median_ns" % law, float("nan")),
            r("force.%s.spiral.tick_median_ns" % law, float("nan"))))
    lines += ["", "LDGF against the analytic k tan(beta): worst relative error %.4f (helix), "
              "%.4f (spiral)." % (r("force.ldgf.helix.max_rel_error", float("nan")),
                                  r("force.ldgf.spiral.max_rel_error", float("nan"))),
              "", "Agent frame rate at the largest size: cached %.1f fps, full %.2f fps." % (
                  r("render.agent_fps_cached", float("nan")), r("render.agent_fps_full",
                                                                float("nan")))]
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("charts: wrote summary.md")


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    out = sys.argv[1]
    try:
        results = json.load(open(os.path.join(out, "results.json")))
    except (OSError, ValueError) as e:
        print("charts: no results: %s" % e, file=sys.stderr)
        return 1
    for chart in (chart_centerline_accuracy, chart_centerline_scaling, chart_force, chart_tracer,
                  chart_surface, chart_loop, chart_stability, chart_render, chart_raw_centerline,
                  chart_client_server_scaling, summary):
        try:
            chart(out, results)
        except Exception as e:  # noqa: BLE001  (one broken chart must not hide the others)
            print("charts: %s skipped: %r" % (chart.__name__, e), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
