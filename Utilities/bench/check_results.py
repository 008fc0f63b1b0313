#!/usr/bin/python3
"""Checks a bench results.json: every required key is present and its value a finite number
(meta.commit and meta.machine: non-empty strings). Exit 0 when all are, 1 otherwise.

    /usr/bin/python3 Utilities/bench/check_results.py build/bench/results.json
"""
import json
import math
import sys

INPUTS = ("helix384", "tree384", "aorta")
MEASURES = ("seconds", "peak_mb", "mean_dist_vox", "p95_dist_vox", "coverage")
REQUIRED = (
    ["centerline.%s.%s" % (i, m) for i in INPUTS for m in MEASURES]
    + ["centerline.%s.skimage_%s" % (i, m) for i in INPUTS for m in MEASURES]
    + ["centerline.scaling.%s.%s_%s_slope" % (s, w, q) for s in ("helix", "tree")
       for w in ("vc", "skimage") for q in ("time", "memory")]
    + ["centerline.vesselness.%s_noisy.%s.%s" % (s, o, m) for s in ("helix", "tree")
       for o in ("off", "on") for m in MEASURES]
    + ["haptic.loop_1000hz.p99_period_error_us", "haptic.loop_10000hz.achieved_hz",
       "haptic.tick_median_ns", "haptic.loop_1000hz_render.p99_period_error_us",
       "haptic.loop_10000hz_render.achieved_hz"]
    + ["force.ldgf.helix.max_rel_error", "force.ldgf.spiral.max_rel_error"]
    + ["force.%s.%s.%s" % (law, scene, what)
       for law in ("ldgf", "change_of_height", "lateral_gradient", "constraint_proxy")
       for scene in ("helix", "spiral")
       for what in ("1000hz.rel_rms_error", "tick_median_ns")]
    + ["tracer.%s.%s.%s" % (rule, scene, what) for rule in ("offset", "movement")
       for scene in ("helix", "spiral")
       for what in ("mean_error_px", "max_error_px", "max_force_step_n", "reached_fraction")]
    + ["tracer.%s.branch.correct_fraction" % rule for rule in ("offset", "movement")]
    + ["tracer.%s.%s.angle%d.%s" % (rule, variant, angle, what)
       for rule in ("offset", "movement") for variant in ("branch", "branch_at_junction")
       for angle in (10, 20, 30, 45, 60, 90) for what in ("taken", "kept")]
    + ["surface.%s.%s" % (law, what) for law in ("change_of_height", "lateral_gradient")
       for what in ("patch0.mean_fx_n", "patch1.mean_fx_n", "patch2.mean_fx_n", "rms_fy_n")]
    + ["stability.%s.1000hz.max_stable" % m
       for m in ("coupler_kc_n_per_m", "ldgf_lambda_mm", "interpolation_n_per_s")]
    + ["render.agent_fps_cached", "render.agent_fps_full", "meta.quick"]
)
# Raw angiograms from one seed (issue 16): VesselCenterline and scikit-image, worst phantom case.
RAW_MEASURES = ("precision", "recall_r0.5_0.6", "recall_r0.6_0.75", "recall_r0.75_1",
                "recall_r1_2", "recall_r2_up", "recall_r0.5_up", "recall_r1_up", "mean_dist_vox",
                "false_vessel_points", "time_s", "cta_aorta.coverage_1mm")
REQUIRED += (["centerline.raw.%s" % m for m in RAW_MEASURES]
             + ["centerline.raw.skimage.%s" % m for m in RAW_MEASURES]
             + ["centerline.raw.vesselness_whole_volume_s", "centerline.raw.cta_aorta.time_s",
                "centerline.raw.automatic_range", "centerline.raw.stage_shading_s"])
# The phantom under a strong bias field, which the shading correction divides out (session 21).
REQUIRED += ["centerline.raw.%sshaded.%s" % (who, m) for who in ("", "skimage.")
             for m in ("precision", "recall_r0.5_up", "recall_r1_up", "mean_dist_vox",
                       "false_vessel_points")]
# The haptic loop while the camera is dragged in the real GUI (issue 20 item 6).
REQUIRED += ["gui.%s.%s" % (phase, what) for phase in ("idle", "drag")
             for what in ("max_period_error_us", "p99_period_error_us", "overruns", "ticks")]
# Client/server scaling (issue 19 item 4): the largest size on one rank and distributed over 2
# (full runs add 2 and 4 ranks with the whole volume on the first, and 4 distributed).
REQUIRED += ["scaling.largest.%s.%s" % (run, what) for run in ("r1", "r2d")
             for what in ("read_s", "centerline_s", "deliver_s", "bytes_to_client",
                          "peak_rss_mib_max", "haptic.idle.period_error_p99_us",
                          "haptic.render.period_error_p99_us")] + ["scaling.largest.memory_ratio_r2d"]
STRINGS = ("meta.commit", "meta.machine")


def problems(results):
    found = []
    for key in REQUIRED:
        value = results.get(key)
        if value is None:
            found.append("missing: " + key)
        elif isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value):
            found.append("not a finite number: %s = %r" % (key, value))
    for key in STRINGS:
        if not isinstance(results.get(key), str) or not results[key]:
            found.append("missing or empty string: " + key)
    return found


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        with open(sys.argv[1]) as f:
            results = json.load(f)
    except (OSError, ValueError) as e:
        print("check_results: cannot read %s: %s" % (sys.argv[1], e), file=sys.stderr)
        return 1
    found = problems(results)
    for line in found:
        print("check_results:", line, file=sys.stderr)
    print("check_results: %d required keys, %d problem(s), %d keys in all (quick=%s)"
          % (len(REQUIRED) + len(STRINGS), len(found), len(results), results.get("meta.quick")))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
