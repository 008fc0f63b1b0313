"""Benchmark (not a test): agent frame rate over a MIP with the cached MIP image against the whole
volume re-rendered every frame, side by side in one run, over several volume sizes.

    Testing/Utilities/vtouch-xvfb-run pvpython Testing/Benchmarks/agent_framerate.py \\
        --plugin <build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
        [--json <out.json>] [--sizes 128x128x128 256x256x256 360x330x420] [--rounds 3]

For each size: a VesselPhantom (Tree) of that size shown as a MIP (vesseltouch.ShowAsMIP) in an
800 x 600 render view, and a vesseltouch.AgentOverlay. The agent then moves along a circle through
the vessels (position, direction and roll change every frame). The two modes are interleaved in
``--rounds`` rounds so that a load change on the shared machine hits both alike:

* cached: AgentOverlay.MoveAgent with the cache on (the volume is not re-rendered),
* full:   the same MoveAgent with ``use_cache = False``: a normal ParaView render per frame, which
          ray-casts the whole volume again (what the agent would cost without the cache).

Prints both rates and their ratio per size, and writes flat JSON (units in the key names):
``render.agent_fps_cached`` and ``render.agent_fps_full`` (the largest size, the issue's
360x330x420 by default), and ``render.<size>.agent_fps_cached``, ``.agent_fps_full``,
``.cached_frame_ms``, ``.full_frame_ms``, ``.speedup_ratio``, ``.cache_reuse_fraction``.
"""

import argparse
import json
import math
import os
import platform
import sys
import time

from paraview import simple


def parse_size(text):
    parts = [int(p) for p in text.lower().split("x")]
    if len(parts) != 3 or min(parts) < 8:
        raise argparse.ArgumentTypeError("a size is NXxNYxNZ, e.g. 360x330x420")
    return parts


def arguments():
    default_plugin = os.environ.get("VESSELTOUCH_PLUGIN", "")
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--plugin", default=default_plugin, help="VesselTouch.so")
    parser.add_argument("--json", help="write the results here")
    parser.add_argument("--sizes", nargs="+", type=parse_size,
                        default=[[128, 128, 128], [256, 256, 256], [360, 330, 420]])
    parser.add_argument("--resolution", nargs=2, type=int, default=[800, 600])
    parser.add_argument("--rounds", type=int, default=3, help="interleaved rounds per size")
    parser.add_argument("--cached-frames", type=int, default=60, help="cached frames per round")
    parser.add_argument("--full-frames", type=int, default=3, help="full frames per round")
    args = parser.parse_args()
    if not args.plugin or not os.path.exists(args.plugin):
        parser.error("--plugin (or VESSELTOUCH_PLUGIN) must name the built VesselTouch.so")
    return args


def agent_path(bounds, frame):
    """A circle in the volume's middle slab: position, direction of travel and a turning roll."""
    centre = [(bounds[2 * i] + bounds[2 * i + 1]) / 2.0 for i in range(3)]
    radius = 0.25 * min(bounds[1] - bounds[0], bounds[3] - bounds[2])
    angle = 0.05 * frame
    position = [centre[0] + radius * math.cos(angle), centre[1] + radius * math.sin(angle),
                centre[2] + 0.2 * (bounds[5] - bounds[4]) * math.sin(3 * angle)]
    direction = [-math.sin(angle), math.cos(angle), 0.6 * math.cos(3 * angle)]
    return position, direction, 10.0 * frame


def run_mode(overlay, bounds, frames, use_cache, start_frame):
    overlay.use_cache = use_cache
    reused = 0
    start = time.perf_counter()
    for k in range(frames):
        position, direction, roll = agent_path(bounds, start_frame + k)
        reused += overlay.MoveAgent(position, direction, roll, "tracing")
    return time.perf_counter() - start, reused


def measure(view, size, args):
    import vesseltouch
    phantom = simple.VesselPhantom(Shape="Tree", Dimensions=size)
    built = time.perf_counter()
    rep = vesseltouch.ShowAsMIP(phantom, view)
    built = time.perf_counter() - built
    bounds = phantom.GetDataInformation().GetBounds()
    overlay = vesseltouch.AgentOverlay(view, rep, size_mm=0.06 * (bounds[1] - bounds[0]))
    overlay.MoveAgent(*agent_path(bounds, 0))  # the first full render fills the cache
    overlay.MoveAgent(*agent_path(bounds, 1))  # warm the cached path
    totals = {True: [0.0, 0, 0], False: [0.0, 0, 0]}  # seconds, frames, reused
    frame = 2
    for _ in range(args.rounds):
        for use_cache, frames in ((True, args.cached_frames), (False, args.full_frames)):
            if use_cache:
                overlay.use_cache = True
                overlay.Render()  # re-fill the cache after the full frames (not timed)
            seconds, reused = run_mode(overlay, bounds, frames, use_cache, frame)
            frame += frames
            totals[use_cache][0] += seconds
            totals[use_cache][1] += frames
            totals[use_cache][2] += reused
    overlay.Remove()
    simple.Delete(rep)
    simple.Delete(phantom)
    cached_s, cached_n, cached_reused = totals[True]
    full_s, full_n, _ = totals[False]
    fps_cached, fps_full = cached_n / cached_s, full_n / full_s
    return {"agent_fps_cached": fps_cached, "agent_fps_full": fps_full,
            "cached_frame_ms": 1000.0 * cached_s / cached_n,
            "full_frame_ms": 1000.0 * full_s / full_n,
            "speedup_ratio": fps_cached / fps_full,
            "cache_reuse_fraction": cached_reused / cached_n,
            "frames_cached": cached_n, "frames_full": full_n, "mip_setup_seconds": built}


def main():
    args = arguments()
    simple.LoadPlugin(args.plugin, ns=globals())
    simple._add_functions(vars(simple))  # VesselPhantom in paraview.simple too
    view = simple.CreateView("RenderView")
    view.ViewSize = args.resolution
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    view.OrientationAxesVisibility = 0
    results = {"render.width_px": args.resolution[0], "render.height_px": args.resolution[1],
               "render.machine": "%s, %d cpu(s)" % (platform.node(), os.cpu_count() or 0)}
    print("%-14s %12s %12s %8s %10s" % ("volume", "cached fps", "full fps", "ratio", "reused"))
    for size in args.sizes:
        name = "x".join(str(n) for n in size)
        row = measure(view, size, args)
        for key, value in row.items():
            results["render.%s.%s" % (name, key)] = value
        print("%-14s %12.1f %12.2f %8.1f %9.0f%%" % (name, row["agent_fps_cached"],
                                                      row["agent_fps_full"], row["speedup_ratio"],
                                                      100.0 * row["cache_reuse_fraction"]),
              flush=True)
    largest = "x".join(str(n) for n in max(args.sizes, key=lambda s: s[0] * s[1] * s[2]))
    results["render.agent_fps_cached"] = results["render.%s.agent_fps_cached" % largest]
    results["render.agent_fps_full"] = results["render.%s.agent_fps_full" % largest]
    results["render.speedup_ratio"] = results["render.%s.speedup_ratio" % largest]
    print("%s at %dx%d: cached %.1f fps, full %.2f fps, ratio %.1f"
          % (largest, args.resolution[0], args.resolution[1], results["render.agent_fps_cached"],
             results["render.agent_fps_full"], results["render.speedup_ratio"]))
    if args.json:
        with open(args.json, "w") as out:
            json.dump(results, out, indent=1, sort_keys=True)
        print("wrote", args.json)
    # Delete the view before the interpreter exits: a render view still alive at pvpython's exit
    # is destroyed after its X connection and crashes in teardown (seen with ParaView 5.11).
    simple.Delete(view)
    return 0


if __name__ == "__main__":
    sys.exit(main())
