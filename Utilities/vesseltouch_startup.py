"""Start-up script of the main job: the built-in phantom as a MIP, its centerline, the session.

Opens the phantom (a vessel tree) as a MIP, extracts its centerline with VesselCenterline and binds
``vesseltouch.logic()`` (the proxy registered as "VesselTouchSession", which the VesselTouch panel
shows) to it with the pointer device and the view's camera: ready to Start.

Runs inside the ParaView GUI (``paraview --script=...``, plugin loaded with ``--plugins``) and in
pvpython/pvbatch (headless). Environment:
  VESSELTOUCH_PLUGIN       plugin library to load when it is not loaded yet (headless runs)
  VESSELTOUCH_OUTPUT_DIR   if set: write screenshot.png (the render view) and report.txt there
  VESSELTOUCH_DONE_FLAG    if set: a file written last, when the scene is ready
  VESSELTOUCH_VIEW_SIZE    view size in pixels for the screenshot, "800x600" by default
  VESSELTOUCH_TRACE        if "1" (run.sh --headless): also run a scripted, deterministic trace
                           with the simulated device and a ~1 s real-time run, and write into
                           VESSELTOUCH_OUTPUT_DIR the screenshot with the agent cone, trace.npz,
                           force.png (Utilities/plot_force.py via VESSELTOUCH_SYSTEM_PYTHON,
                           /usr/bin/python3 by default) and loop_statistics.json
"""

import os
import sys
import time
import traceback


def _ensure_plugin(simple):
    try:
        simple.VesselPhantom  # noqa: B018 (present once the plugin is loaded)
        return "already loaded"
    except AttributeError:
        pass
    path = os.environ.get("VESSELTOUCH_PLUGIN")
    if not path:
        raise RuntimeError("the VesselTouch plugin is not loaded and VESSELTOUCH_PLUGIN is not set")
    simple.LoadPlugin(path, ns=vars(simple))
    return path


def _report_lines(vesseltouch, phantom, rep, view, seconds):
    info = phantom.GetDataInformation(0)
    line_info = phantom.GetDataInformation(1)
    extent = info.GetExtent()
    scalars = info.GetPointDataInformation().GetAttributeInformation(0)
    lines = ["VesselTouch main job report", ""]
    lines += ["%-12s %s" % (k + ":", v) for k, v in sorted(vesseltouch.build_info().items())]
    lines += [
        "",
        "dataset:     %s (%s)" % ("VesselPhantom1", phantom.Shape),
        "volume:      %d x %d x %d voxels, %s in [%g, %g]" % (
            extent[1] - extent[0] + 1, extent[3] - extent[2] + 1, extent[5] - extent[4] + 1,
            scalars.GetName(), *scalars.GetComponentRange(0)),
        "centerline:  %d polylines, %d points" % (
            line_info.GetNumberOfCells(), line_info.GetNumberOfPoints()),
        "display:     %s, blend mode %d (1 = maximum intensity)" % (
            rep.Representation, vesseltouch.mip.BlendMode(rep)),
        "view:        %d x %d pixels" % tuple(view.ViewSize),
        "set-up time: %.2f s" % seconds,
    ]
    return lines


def _bind_session(vesseltouch, phantom, view):
    """VesselCenterline on the phantom's volume, and the panel's session bound to it with the
    pointer device and the view's camera. Returns (centerline, session)."""
    centerline = vesseltouch.ExtractCenterlines(phantom, registrationName="VesselCenterline1")
    session = vesseltouch.logic()
    session.Bind(centerline, view)
    session.SetDevice("pointer")
    session.SetForceLaw("LDGF")
    return centerline, session


def _session_lines(vesseltouch, session, centerline, seconds):
    status = session.GetStatus()
    info = centerline.GetDataInformation()
    return [
        "extracted:   VesselCenterline, %d polylines, %d points (%.2f s)" % (
            info.GetNumberOfCells(), info.GetNumberOfPoints(), seconds),
        "session:     %s: %d paths, %d points, device %s, force law %s" % (
            vesseltouch.SESSION_NAME, status["paths"],
            status["points"], session.proxy.DeviceType, session.proxy.ForceLaw),
    ]


def _trace_path(centerline, forward):
    """(index, length in mm, depth range in mm along ``forward``) of the centerline's longest
    polyline (the session's path order): the sweep starts where the hand meets no other vessel
    first, and runs through the most changes of depth."""
    from paraview import servermanager
    import numpy
    poly = servermanager.Fetch(centerline)
    best = (0, 0.0, 0.0)
    for cell in range(poly.GetNumberOfCells()):
        ids = poly.GetCell(cell).GetPointIds()
        points = numpy.array([poly.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())])
        length = float(numpy.linalg.norm(numpy.diff(points, axis=0), axis=1).sum())
        depth = points @ numpy.asarray(forward)
        if length > best[1]:
            best = (cell, length, float(depth.max() - depth.min()))
    return best


def _screenshot_tick(log, measures):
    """The tick whose agent the screenshot shows: the last tracing tick in which the agent heads
    away from the viewer (so the cone shows its blue base beside its red sides), else the last
    tracing tick."""
    import numpy
    tracing = numpy.flatnonzero(measures["tracing"])
    if len(tracing) == 0:
        return len(log["time"]) - 1, "the last tick (the agent never traced)"
    depth = measures["depth_mm"]
    position = numpy.asarray(log["position"], dtype=float)
    away = [i for i in tracing[::-1] if i >= 20 and depth[i] - depth[i - 20]
            > 0.3 * numpy.linalg.norm(position[i] - position[i - 20]) > 0.0]
    if away:
        return int(away[0]), "the last tick in which the agent heads away from the viewer"
    return int(tracing[-1]), "the last tracing tick"


def _run_trace(vesseltouch, session, centerline, view, output_dir):
    """The headless job: a deterministic scripted trace with the simulated device, the agent
    cone over the MIP, the force plot, and ~1 s of the real-time loop. Returns report lines."""
    import json
    import subprocess
    import numpy
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.util.numpy_support import numpy_to_vtk

    lines = [""]
    # 1. Offline: the hand sweeps along the longest path on simulated time (deterministic).
    _, _, _, forward = session.GetCameraFrame()
    path, length, rise = _trace_path(centerline, forward)
    speed = 60.0  # device mm/s; zoom 1 and the view's scale map them to pixels
    session.SetDevice("simulated")
    session.SetForceLaw("LDGF", k=0.3, lambda_mm=0.005)
    session.SetForceZones(gain_N=0.3, zero_below=0.05, saturate_above=0.5)
    session.SetZoom(1.0)
    session.SetHandSweep(path=path, speed_mm_per_s=speed)
    t0 = time.time()
    # The sweep: the hand approaches the path's first point and follows it until the agent
    # stops at its end (the vessel falls away from the viewer: the force pulls on). Then the
    # same hand is played back in reverse as a scripted trajectory (the vessel rises toward the
    # viewer: the force pushes back).
    probe = session.RunOffline(6.0, rate_Hz=1000.0)
    moved = numpy.flatnonzero(numpy.linalg.norm(numpy.diff(probe["position"], axis=0), axis=1)
                              > 1e-6)
    tracing = numpy.flatnonzero(probe["state"] == 1)
    if len(moved) == 0 or len(tracing) == 0:
        raise RuntimeError("the scripted hand did not trace path %d" % path)
    arrived = int(moved[-1]) + 1
    forward_ticks = numpy.arange(0, arrived + 1, 5)
    back_ticks = numpy.arange(arrived, int(tracing[0]), -5)
    t_forward = probe["time"][forward_ticks] - probe["time"][0]
    t_back = t_forward[-1] + 0.15 + (probe["time"][arrived] - probe["time"][back_ticks])
    times = numpy.concatenate([t_forward, t_back[1:]])
    hand = numpy.concatenate([probe["hand"][forward_ticks], probe["hand"][back_ticks[1:]]])
    log = session.PlayTrajectory(times, hand[:, 0], hand[:, 1], rate_Hz=1000.0,
                                 cursor_start=probe["cursor"][0])
    duration = float(times[-1])
    offline_seconds = time.time() - t0
    agent = session.GetAgentState()
    offline_stats = session.GetStatistics()
    trace_npz = session.SaveLog(os.path.join(output_dir, "trace.npz"), log)
    measures = session.GetTraceMeasures(log)
    tick, why = _screenshot_tick(log, measures)
    position = [float(v) for v in log["position"][tick]]
    step = max(tick - 20, 0)
    direction = numpy.asarray(log["position"][tick]) - numpy.asarray(log["position"][step])
    if not numpy.isfinite(direction).all() or numpy.linalg.norm(direction) < 1e-9:
        direction = numpy.asarray(agent["tangent"]) * (agent["direction"] or 1)
    tracing = measures["tracing"]
    lines += [
        "trace:       simulated device, LDGF: a hand sweep along path %d (%.1f mm, depth range "
        "%.1f mm) at %.0f mm/s, then that hand played back in reverse" % (path, length, rise,
                                                                         speed),
        "             %.3f s at 1 kHz on simulated time (%d ticks, computed in %.2f s)"
        % (duration, len(log["time"]), offline_seconds),
        "             tracing %.0f %% of ticks on paths %s, max |force| %.3f N, depth %.1f..%.1f mm"
        % (100.0 * tracing.mean(), sorted({int(v) for v in log["path"][tracing]}),
           float(measures["force_magnitude"].max()),
           float(measures["depth_mm"][tracing].min()) if tracing.any() else 0.0,
           float(measures["depth_mm"][tracing].max()) if tracing.any() else 0.0),
        "             final agent: state %d, position (%.1f, %.1f, %.1f) mm"
        % (agent["state"], *agent["position"]),
        "log:         %s" % trace_npz,
    ]

    # 2. The agent cone over the cached MIP, where and how the log places it.
    overlay = vesseltouch.AgentOverlay(view, size_mm=10.0)
    overlay.MoveAgent(position, direction.tolist(), 0.0, state="tracing")
    overlay.Render()
    pixels = overlay.CaptureWindow()[::-1]  # rows bottom-up for VTK
    image = vtkImageData()
    image.SetDimensions(pixels.shape[1], pixels.shape[0], 1)
    image.GetPointData().SetScalars(numpy_to_vtk(pixels.reshape(-1, 3).copy()))
    screenshot = os.path.join(output_dir, "screenshot.png")
    writer = vtkPNGWriter()
    writer.SetFileName(screenshot)
    writer.SetInputData(image)
    writer.Write()
    x, y = overlay.ProjectToDisplay(position)
    overlay.Remove()
    agent_json = {"tick": tick, "time_s": float(log["time"][tick]), "why": why,
                  "position_mm": position, "direction": direction.tolist(),
                  "pixel": [x, pixels.shape[0] - 1 - y], "image_size": list(pixels.shape[1::-1])}
    lines += ["screenshot:  %s (agent at t = %.3f s: %s; pixel %.0f, %.0f from the top left)"
              % (screenshot, agent_json["time_s"], why, agent_json["pixel"][0],
                 agent_json["pixel"][1])]

    # 3. The force plot, with Debian's Python (matplotlib).
    plot = os.path.join(os.environ.get("VESSELTOUCH_SOURCE_DIR", _source_dir()), "Utilities",
                        "plot_force.py")
    force_png = os.path.join(output_dir, "force.png")
    python = os.environ.get("VESSELTOUCH_SYSTEM_PYTHON", "/usr/bin/python3")
    result = subprocess.run([python, plot, trace_npz, force_png], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, universal_newlines=True, timeout=120)
    if result.returncode != 0:
        raise RuntimeError("plot_force.py failed:\n" + result.stdout)
    lines += ["force plot:  %s" % force_png]

    # 4. About one second of the real-time loop (its own thread, the same tick code).
    session.SetHandSweep(path=path, speed_mm_per_s=speed)
    session.Start(rate_Hz=1000.0)
    time.sleep(1.0)
    live = session.GetAgentState()
    session.Stop()
    realtime = session.GetStatistics()
    status = session.GetStatus()
    statistics = {
        "realtime": dict(realtime, seconds=1.0, scheduler=status["scheduler"],
                         fault=status["fault_text"], agent_state=live["state"],
                         note="~1 s of the real-time loop (wall clock, its own thread) with the "
                              "simulated device and the same hand sweep"),
        "offline": dict(offline_stats, seconds=duration, ticks_logged=len(log["time"]),
                        note="the scripted trace on simulated time: deterministic, not real time;"
                             " these loop statistics are those the session held after it"),
        "agent_in_screenshot": agent_json,
    }
    statistics_json = os.path.join(output_dir, "loop_statistics.json")
    with open(statistics_json, "w") as out:
        json.dump(statistics, out, indent=2, sort_keys=True)
    lines += [
        "real time:   1.0 s at 1 kHz: %.0f Hz achieved, %d ticks, %d overruns, %d skipped "
        "deadlines" % (realtime["achieved_rate_Hz"], realtime["ticks"], realtime["overruns"],
                       realtime["skipped_deadlines"]),
        "             period error p50 %.1f us, p99 %.1f us, p99.9 %.1f us, max %.1f us; "
        "tick cost p50 %.1f us, p99 %.1f us" % (
            realtime["period_error_p50_us"], realtime["period_error_p99_us"],
            realtime["period_error_p999_us"], realtime["period_error_max_us"],
            realtime["tick_cost_p50_us"], realtime["tick_cost_p99_us"]),
        "             scheduler: %s" % status["scheduler"],
        "statistics:  %s" % statistics_json,
    ]
    session.SetDevice("pointer")
    return lines


def _source_dir():
    try:
        return os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    except NameError:  # run by the GUI's --script without __file__
        return os.getcwd()


def _frame_vessels(view):
    """Closer than the whole volume: the phantom's tree fills about half the view."""
    view.GetActiveCamera().Dolly(1.5)


def main():
    from paraview import simple

    start = time.time()
    plugin = _ensure_plugin(simple)
    import vesseltouch

    view = simple.GetActiveViewOrCreate("RenderView")
    size = os.environ.get("VESSELTOUCH_VIEW_SIZE", "800x600").lower().split("x")
    output_dir = os.environ.get("VESSELTOUCH_OUTPUT_DIR")
    trace = os.environ.get("VESSELTOUCH_TRACE") == "1"
    if output_dir:
        view.ViewSize = [int(size[0]), int(size[1])]
    phantom, rep = vesseltouch.OpenDefaultScene(view)
    _frame_vessels(view)
    seconds = time.time() - start
    extraction_start = time.time()
    centerline, session = _bind_session(vesseltouch, phantom, view)
    extraction = time.time() - extraction_start
    simple.SetActiveSource(phantom)  # the panel and the MIP button act on the volume

    if output_dir:
        os.makedirs(output_dir, exist_ok=True)
        lines = _report_lines(vesseltouch, phantom, rep, view, seconds)
        lines += _session_lines(vesseltouch, session, centerline, extraction)
        lines += ["plugin:      %s" % plugin]
        if trace:
            lines += _run_trace(vesseltouch, session, centerline, view, output_dir)
        else:
            screenshot = os.path.join(output_dir, "screenshot.png")
            simple.SaveScreenshot(screenshot, view, ImageResolution=[int(size[0]), int(size[1])])
            lines += ["screenshot:  %s" % screenshot]
        lines += ["total time:  %.2f s" % (time.time() - start)]
        with open(os.path.join(output_dir, "report.txt"), "w") as report:
            report.write("\n".join(lines) + "\n")
        print("\n".join(lines))
        if trace or os.path.basename(sys.executable).startswith(("pvpython", "pvbatch")):
            simple.Delete(view)  # pvpython under Xvfb crashes at exit with a live render view
    flag = os.environ.get("VESSELTOUCH_DONE_FLAG")
    if flag:
        with open(flag, "w") as done:
            done.write("ok\n")


try:
    main()
except Exception:  # report clearly, and make headless runs fail
    traceback.print_exc()
    flag = os.environ.get("VESSELTOUCH_DONE_FLAG")
    if flag:
        with open(flag, "w") as done:
            done.write("error\n" + traceback.format_exc())
    if not hasattr(sys, "ps1") and os.environ.get("VESSELTOUCH_OUTPUT_DIR"):
        sys.exit(1)
